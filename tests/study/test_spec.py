"""The study file: key paths into the base configuration, the cases, and every mistake refused before any work."""

import re

import numpy as np
import pytest

from microslip.config import ConfigError, read_toml
from microslip.study import load_study
from microslip.study.key_paths import set_key
from microslip.study.spec import Study


def test_the_smallest_study_as_written_gives_its_six_cases(block):
    study = load_study(block)
    cases = study.cases()
    assert study.parameters == ["contact.sphere.preload", "excitation.h1"]
    assert [c.values for c in cases] == [{"contact.sphere.preload": p, "excitation.h1": h}
                                         for p in ["25N", "37.5N", "50N"] for h in [["0.3N", "0N"], ["0.6N", "0N"]]]
    assert len({c.key for c in cases}) == 6
    assert [c.key for c in load_study(block).cases()] == [c.key for c in cases]  # keys are stable across runs
    cfg = study.configuration(cases[3])
    assert cfg.structure.contacts[0].preload == 37.5
    np.testing.assert_array_equal(cfg.force[1], [0.6, 0.0])


def test_a_changed_base_or_model_file_changes_every_key(block):
    keys = {c.key for c in load_study(block).cases()}
    model = block.with_name("sphere_4_elements.json")
    model.write_text(model.read_text().replace("\n", "\n ", 1))  # same model, different bytes
    assert not keys & {c.key for c in load_study(block).cases()}


def test_key_paths_reach_named_numbered_and_only_tables(damper_pair):
    data = read_toml(damper_pair)
    out = set_key(data, "damper.mass", 0.03, where="t")
    assert out["damper"][0]["mass"] == 0.03 and data["damper"][0]["mass"] == 0.02  # a copy: the base is untouched
    assert set_key(data, "damper.1.mass", 0.04, where="t")["damper"][0]["mass"] == 0.04
    assert set_key(data, "damper.interface.curved.angle", 50, where="t")["damper"][0]["interface"][1]["angle"] == 50
    assert set_key(data, "damper.interface.1.angle", 130, where="t")["damper"][0]["interface"][0]["angle"] == 130
    assert set_key(data, "sweep.harmonics", 5, where="t")["sweep"]["harmonics"] == 5
    assert set_key(data, "excitation.scale", 2.0, where="t")["excitation"]["scale"] == 2.0
    cyclic = {"cyclic": {"engine_order": 1}, "sweep": {}}
    moved = set_key(cyclic, "sweep.engine_order", 2, where="t")
    assert moved == {"cyclic": {}, "sweep": {"engine_order": 2}}  # one engine order, where the study put it


@pytest.mark.parametrize("path, message", [
    ("contact.sphere.prelod", "[[contact]] has no key 'prelod'; did you mean 'preload'?"),
    ("contact.sphre.preload", "no [[contact]] table named 'sphre'; did you mean 'sphere'?"),
    ("contact.2.preload", "names [[contact]] 2; the base configuration has 1 (numbered from 1)"),
    ("contacts.sphere.preload", "starts with 'contacts', which is no table of the configuration; did you mean "
                                "'contact'?"),
    ("sweep.omegas", "[sweep] has no key 'omegas'; did you mean 'omega'?"),
    ("excitation.h0", "[excitation] has no key 'h0'"),
    ("damper.mass", "names a [[damper]] table; the base configuration has none"),
    ("harmonics", "is not a key of the configuration's top level"),
    ("sweep..harmonics", "has an empty part"),
    ("contact.sphere", "names a table, not a key"),
])
def test_an_unknown_key_path_is_refused_naming_it(block, path, message):
    block.write_text(f'base = "inclined_block.toml"\n[vary]\n"{path}" = [1.0]\n')
    with pytest.raises(ConfigError, match=re.escape(message)) as err:
        load_study(block)
    assert str(block) in str(err.value) and path in str(err.value)


@pytest.mark.parametrize("value, message", [
    ('["25m"]', "[vary] 'contact.sphere.preload' = \"25m\" is refused by the base configuration"),
    ('["lots"]', "'contact.sphere.preload' = \"lots\" is refused"),
    ("[[1, 2]]", "'contact.sphere.preload' = [1, 2] is refused"),
])
def test_a_value_of_the_wrong_type_or_unit_is_refused_naming_it(block, value, message):
    block.write_text(f'base = "inclined_block.toml"\n[vary]\n"contact.sphere.preload" = {value}\n')
    with pytest.raises(ConfigError, match=re.escape(message)):
        load_study(block)


@pytest.mark.parametrize("text, message", [
    ('base = "inclined_block.toml"\nsweep = 1\n[vary]\n"sweep.harmonics" = [3]', "unknown key 'sweep'"),
    ('[vary]\n"sweep.harmonics" = [3]', "a study needs base ="),
    ('base = "missing.toml"\n[vary]\n"sweep.harmonics" = [3]', "missing.toml' does not exist"),
    ('base = "inclined_block.toml"\nsolve = "time"\n[vary]\n"sweep.harmonics" = [3]', "solve must be one of"),
    ('base = "inclined_block.toml"', "the study varies nothing"),
    ('base = "inclined_block.toml"\n[vary]\n"sweep.harmonics" = 3', "must be a non-empty list of values"),
    ('base = "inclined_block.toml"\n[vary]\n"sweep.harmonics" = []', "must be a non-empty list of values"),
    # issue 24, item 23: two summary rows with the same key
    ('base = "inclined_block.toml"\n[vary]\n"contact.sphere.preload" = ["25N", "50N", "25N"]',
     "[vary] 'contact.sphere.preload' lists the value \"25N\" twice (values 1 and 3): the cases would be one case "
     "solved twice, with the same key; list each value once"),
    ('base = "inclined_block.toml"\n[vary]\n"excitation.h1" = [[0.6, 0.0], [0.6, 0.0]]',
     "[vary] 'excitation.h1' lists the value [0.6, 0.0] twice (values 1 and 2)"),
    ('base = "inclined_block.toml"\n[random]\nseed = 1\n"contact.sphere.mu" = {uniform = [0.4, 0.6]}',
     "[random] needs samples"),
    ('base = "inclined_block.toml"\n[random]\nsamples = 3\n"contact.sphere.preload" = {gauss = [1, 2]}',
     "unknown distribution 'gauss'"),
    ('base = "inclined_block.toml"\n[random]\nsamples = 3\n"contact.sphere.preload" = {uniform = [2, 1]}',
     "uniform needs lo < hi"),
    ('base = "inclined_block.toml"\n[random]\nsamples = 3\n"contact.sphere.preload" = {uniform = ["2N", "3mm"]}',
     "must have the same unit"),
    ('base = "inclined_block.toml"\n[random]\nsamples = 3\n"contact.sphere.preload" = {uniform = ["2m", "3m"]}',
     "[random] 'contact.sphere.preload' = \"2.'"),
    ('base = "inclined_block.toml"\n[random]\nsamples = 0\n"contact.sphere.preload" = {uniform = [2, 3]}',
     "[random] samples must be"),
    ('base = "inclined_block.toml"\n[mistuning]\nstd = 0.02\nsamples = 3', "needs a base configuration with a "
                                                                          "[cyclic] table"),
    ('base = "inclined_block.toml"\n[[case]]\n', "each [[case]] must be a table of key paths and values"),
])
def test_a_bad_study_file_is_refused_naming_the_key(block, text, message):
    block.write_text(text + "\n")
    with pytest.raises((ConfigError, FileNotFoundError), match=re.escape(message).replace("'", "'?")):
        load_study(block)


def test_random_samples_are_reproducible_from_the_seed_and_keep_their_unit(block):
    block.write_text('base = "inclined_block.toml"\n[random]\nsamples = 4\nseed = 7\n'
                     '"contact.sphere.preload" = {uniform = ["30N", "40N"]}\n'
                     '"excitation.scale" = {loguniform = [0.5, 2.0]}\n')
    a, b = load_study(block).cases(), load_study(block).cases()
    assert [c.values for c in a] == [c.values for c in b]
    loads = [float(c.values["contact.sphere.preload"][:-1]) for c in a]
    assert all(c.values["contact.sphere.preload"].endswith("N") for c in a)
    assert all(30 <= x <= 40 for x in loads) and len(set(loads)) == 4
    assert all(0.5 <= c.values["excitation.scale"] <= 2.0 for c in a)
    block.write_text(block.read_text().replace("seed = 7", "seed = 8"))
    assert [c.values for c in load_study(block).cases()] != [c.values for c in a]


def test_blocks_combine_as_a_product(block):
    block.write_text('base = "inclined_block.toml"\n[vary]\n"contact.sphere.preload" = ["25N", "50N"]\n'
                     '[[case]]\n"excitation.scale" = 1.0\n[[case]]\n"excitation.scale" = 2.0\n'
                     '"sweep.harmonics" = 5\n')
    study = load_study(block)
    assert isinstance(study, Study) and len(study.cases()) == 4
    assert study.parameters == ["contact.sphere.preload", "excitation.scale", "sweep.harmonics"]
    assert study.cases()[1].values == {"contact.sphere.preload": "25N", "excitation.scale": 2.0, "sweep.harmonics": 5}
