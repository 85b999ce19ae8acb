"""``microslip tune --reference sphere|cylinder|punch``, ``--E2``/``--nu2``: the command line tunes what the API tunes.

Each reference tuned from the command line equals the Python ``tune`` (or ``tune_on_loops``) of the same reference
bit for bit (the same code path); a missing option is named, an option the reference does not use is refused naming
the reference, before any work; ``--help`` explains the new options.
"""

from __future__ import annotations

import numpy as np
import pytest

from microslip import Cylinder, MicroslipModel, Sphere, loops, mdr, tune, tune_on_loops
from microslip.cli import main
from microslip.loops.synthetic import dataset_files
from microslip.reference import RoundedPunch


def tuned(argv, path):
    assert main(["tune", *argv, "-o", str(path)]) == 0
    return MicroslipModel.load(path)


def same(cli: MicroslipModel, api: MicroslipModel) -> None:
    """Equal bit for bit: every parameter array and mu (the provenance aside)."""
    for name in ("kt", "kn", "gaps"):
        assert np.array_equal(getattr(cli, name), getattr(api, name)), name
    assert cli.mu == api.mu and cli == api


@pytest.mark.parametrize("argv, second", [([], {}), (["--E2", "210GPa", "--nu2", "0.29"], {"E2": 210e9, "nu2": 0.29})])
def test_tune_sphere_equals_the_python_tune(tmp_path, argv, second):
    cli = tuned(["--reference", "sphere", "--radius", "4mm", "--E", "190GPa", "--nu", "0.28", "--mu", "0.5",
                 "--load", "30N", "--elements", "5", *argv], tmp_path / "s.json")
    api = tune(Sphere(radius=4e-3, E=190e9, nu=0.28, mu=0.5, **second), 30.0, elements=5)
    same(cli, api)
    assert cli.provenance.reference == api.provenance.reference
    assert cli.provenance.reference["kind"] == "Sphere" and cli.provenance.reference.get("E2") == second.get("E2")


def test_tune_default_is_still_the_paper_sphere(tmp_path):
    same(tuned([], tmp_path / "d.json"), tune(Sphere.paper(), 37.5, elements=4))


@pytest.mark.parametrize("argv, second", [([], {}), (["--E2", "120GPa", "--nu2", "0.33"], {"E2": 120e9, "nu2": 0.33})])
def test_tune_punch_equals_the_python_tune_on_its_mdr_array(tmp_path, argv, second):
    cli = tuned(["--reference", "punch", "--flat-radius", "1mm", "--edge-radius", "5mm", "--mdr-elements", "1000",
                 "--E", "210GPa", "--nu", "0.3", "--mu", "0.35", "--load", "40N", "--elements", "6", *argv],
                tmp_path / "p.json")
    material = Sphere(radius=5e-3, E=210e9, nu=0.3, mu=0.35, **second)
    reference = mdr(material, max_load=40.0, elements=1000, profile=RoundedPunch(1e-3, 5e-3)).as_reference()
    api = tune(reference, 40.0, elements=6)
    same(cli, api)
    p = cli.provenance
    assert p.reference == api.provenance.reference and p.normal_load == 40.0
    assert p.reference["model"]["profile"] == {"kind": "RoundedPunch", "flat_radius": 1e-3, "edge_radius": 5e-3}
    assert p.notes == {"reference": "punch", "E": 210e9, "nu": 0.3, "mdr_elements": 1000, **second}


def test_tune_punch_with_forces_and_the_default_mdr_array(tmp_path):
    cli = tuned(["--reference", "punch", "--flat-radius", "0.5mm", "--edge-radius", "2mm", "--load", "20N",
                 "--forces", "2N,4N,8N"], tmp_path / "f.json")
    reference = mdr(Sphere(radius=2e-3, E=200e9, nu=0.3, mu=0.4), max_load=20.0, elements=2000,
                    profile=RoundedPunch(0.5e-3, 2e-3)).as_reference()
    same(cli, tune(reference, 20.0, forces=[2.0, 4.0, 8.0]))
    assert cli.provenance.notes["mdr_elements"] == 2000


@pytest.mark.parametrize("argv, second", [(["--reference", "cylinder", "--length", "12mm"], {}),
                                          (["--E2", "210GPa", "--nu2", "0.29"], {"E2": 210e9, "nu2": 0.29})])
def test_tune_cylinder_on_loops_equals_tune_on_loops(tmp_path, argv, second):
    files = list(map(str, dataset_files()))
    cli = tuned([*files, "--elements", "6", "--quiet", "--out", str(tmp_path), *argv], tmp_path / "c.json")
    length = 12e-3 if "--length" in argv else 10e-3
    records = [loops.analyse(loops.read(p)) for p in files]
    api = tune_on_loops(records, Cylinder(length, 5e-3, 200e9, 0.3, law="palmgren", **second), elements=6).model
    same(cli, api)
    normal = cli.provenance.reference["normal"]
    assert normal["kind"] == "Cylinder" and normal["length"] == length and normal.get("E2") == second.get("E2")


@pytest.mark.parametrize("argv, message", [
    (["--reference", "punch", "--edge-radius", "5mm"], "--reference punch needs --flat-radius (e.g. --flat-radius 1mm)"),
    (["--reference", "punch", "--flat-radius", "1mm"], "--reference punch needs --edge-radius (e.g. --edge-radius 5mm)"),
    (["--reference", "punch", "--flat-radius", "1mm", "--edge-radius", "5mm", "--radius", "5mm"],
     "--radius does not apply to the flat punch with rounded edges (--reference punch)"),
    (["--reference", "punch", "--flat-radius", "1mm", "--edge-radius", "5mm", "--length", "10mm"],
     "--length does not apply to the flat punch with rounded edges (--reference punch)"),
    (["--reference", "punch", "--flat-radius", "1mm", "--edge-radius", "5mm", "--normal-law", "lundberg"],
     "--normal-law does not apply to the flat punch with rounded edges (--reference punch)"),
    (["--flat-radius", "1mm"], "--flat-radius does not apply to the sphere on a plane (--reference sphere)"),
    (["--reference", "sphere", "--edge-radius", "1mm"],
     "--edge-radius does not apply to the sphere on a plane (--reference sphere)"),
    (["--mdr-elements", "400"], "--mdr-elements does not apply to the sphere on a plane (--reference sphere)"),
    (["--length", "10mm"], "--length does not apply to the sphere on a plane (--reference sphere)"),
    (["--E2", "210GPa"], "--E2 needs --nu2"),
    (["--reference", "punch", "--flat-radius", "1mm", "--edge-radius", "5mm", "--nu2", "0.3"], "--nu2 needs --E2"),
    (["--reference", "cylinder", "--length", "10mm"], "--reference cylinder needs measured LOOPS"),
])
def test_tune_refuses_options_by_name_before_any_work(tmp_path, capsys, argv, message):
    out = tmp_path / "m.json"
    capsys.readouterr()
    assert main(["tune", *argv, "-o", str(out)]) == 2
    assert message in capsys.readouterr().err
    assert not out.exists()


def test_tune_refuses_loops_with_another_reference(tmp_path, capsys):
    out = tmp_path / "m.json"
    code = main(["tune", str(dataset_files()[0]), "--reference", "punch", "--flat-radius", "1mm",
                 "--edge-radius", "5mm", "-o", str(out), "--quiet"])
    err = capsys.readouterr().err
    assert code == 2 and "measured LOOPS are tuned on a cylinder on a flat (--reference cylinder)" in err
    assert not out.exists()


@pytest.mark.parametrize("argv, message", [
    (["--reference", "cone"], "argument --reference: invalid choice: 'cone'"),
    (["--flat-radius", "-1mm"], "argument --flat-radius: must be a positive length, got '-1mm'"),
    (["--edge-radius", "5 parsecs"], "argument --edge-radius: value: unknown length unit"),
    (["--E2", "200GN"], "argument --E2: value: unknown pressure unit 'GN'"),
    (["--E2", "0GPa"], "argument --E2: must be a positive pressure, got '0GPa'"),
    (["--nu2", "0.7"], "argument --nu2: must be a Poisson's ratio in (-1, 0.5] such as 0.3, got '0.7'"),
    (["--nu2", "x"], "argument --nu2: expected a Poisson's ratio such as 0.3, got 'x'"),
    (["--mdr-elements", "0"], "argument --mdr-elements: must be a positive integer, got '0'"),
    (["--fla", "1mm"], "unrecognized arguments"),  # no abbreviations
])
def test_tune_checks_the_new_values_when_read(capsys, argv, message):
    with pytest.raises(SystemExit) as exc:
        main(["tune", *argv])
    assert exc.value.code == 2 and message in capsys.readouterr().err


def test_tune_help_lists_the_references_and_their_options(capsys):
    with pytest.raises(SystemExit):
        main(["tune", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "{sphere,cylinder,punch}" in text
    for option in ("--flat-radius", "--edge-radius", "--mdr-elements", "--E2", "--nu2", "--length", "--radius"):
        assert option in text, option
    assert "radius of the flat face" in text and "radius of the rounded edge" in text
    assert "Young's modulus of the second body" in text and "Poisson's ratio of the second body" in text


# -- [[damper.interface]] and [[contact]] may name the reference instead of a model file ----------------------------

PUNCH = 'reference = {kind = "punch", flat_radius = "1mm", edge_radius = "5mm", mdr_elements = 1000}\nload = "40N"'


def test_tune_in_the_configuration_equals_the_python_tune(tmp_path):
    from microslip.config import load_config
    from test_design_cli import write_config

    cfg = load_config(write_config(tmp_path, lambda t: t.replace('model = "flat.json"', PUNCH + "\nelements = 4")))
    reference = mdr(Sphere(radius=5e-3, E=200e9, nu=0.3, mu=0.4), max_load=40.0, elements=1000,
                    profile=RoundedPunch(1e-3, 5e-3)).as_reference()
    api = tune(reference, 40.0, elements=4)
    flat = [c.model for c in cfg.dampers[0].contacts if c.interface == cfg.dampers[0].contacts[0].interface]
    assert len(flat) == 2
    for model in flat:
        same(model, api)


@pytest.mark.parametrize("text, message", [
    ('reference = {kind = "punch", flat_radius = "1mm"}\nload = "40N"',
     "reference: kind = 'punch' needs edge_radius (e.g. edge_radius = \"5mm\")"),
    ('reference = {kind = "sphere", flat_radius = "1mm"}\nload = "40N"',
     "reference: flat_radius does not apply to the sphere on a plane (kind = 'sphere')"),
    ('reference = {kind = "cylinder"}\nload = "40N"', "reference: a cylinder on a flat has no closed-form tangential"),
    ('reference = {kind = "punch", flat_radius = "1mm", edge_radius = "5mm", E2 = "210GPa"}\nload = "40N"',
     "reference: E2 needs nu2"),
    ('reference = {kind = "sphere"}', "needs the key 'load'"),
    ('reference = {kind = "sphere"}\nload = "-4N"', "load must be a positive force"),
    ('model = "flat.json"\nload = "4N"', "load goes with reference = {kind = ...}"),
    ('model = "flat.json"\nreference = {kind = "sphere"}\nload = "4N"', "gives both model and reference"),
    ('reference = {kind = "sphere", radus = "1mm"}\nload = "4N"', "reference has an unknown key 'radus'"),
    ('reference = {kind = "sphere", E = "200GN"}\nload = "4N"', "unknown pressure unit 'GN'"),
])
def test_tune_in_the_configuration_refuses_by_name(tmp_path, text, message):
    import re

    from microslip.config import ConfigError, load_config
    from test_design_cli import write_config

    path = write_config(tmp_path, lambda t: t.replace('model = "flat.json"', text))
    with pytest.raises(ConfigError, match=re.escape(f"{path}: [[damper]] 1 interface 1") + ".*" + re.escape(message)):
        load_config(path)
