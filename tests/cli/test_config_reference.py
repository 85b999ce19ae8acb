"""The configuration reference is rendered from the schema the readers check files against: it lists exactly the
keys they accept, files using every documented key are read, and a key it does not document is refused."""

import re
import shutil

import numpy as np
import pytest

from _paths import EXAMPLES
from microslip.cli import main
from microslip.config import ConfigError, config_from_data, load_config, read_toml, reference_markdown
from microslip.config import schema
from microslip.config.frf import KEYS, refuse_unknown
from microslip.study import load_study
from test_design_cli import cartesian, write_config  # the blade pair with an under-platform damper


def _rendered_tables(text: str) -> list[tuple[str, list[str]]]:
    """``(heading, [key, ...])`` of every table section of the rendered reference, in order."""
    out = []
    for block in re.split(r"^### ", text, flags=re.M)[1:]:
        heading = block.splitlines()[0]
        out.append((heading, re.findall(r"^\| `([^`]+)` \|", block, flags=re.M)))
    return out


def test_the_reference_lists_every_table_and_exactly_its_declared_keys():
    rendered = _rendered_tables(reference_markdown())
    tables = schema.FRF_TABLES + schema.STUDY_TABLES
    assert len(rendered) == len(tables)
    for (heading, keys), table in zip(rendered, tables):
        assert keys == [k.name for k in table.keys], heading
        assert table.header in heading if table.header else heading == "The file's top level"


def test_every_key_has_a_type_a_unit_column_a_default_an_example_and_a_description():
    for table in schema.FRF_TABLES + schema.STUDY_TABLES:
        for key in table.keys:
            assert key.description and key.example and key.default_text, (table.name, key.name)
            assert all(t.strip() in schema.TYPES for t in key.type.split("|")), (table.name, key.name)


def test_the_readers_accept_exactly_the_declared_keys():
    # the readers' lists of accepted keys are the schema's, table by table (not a copy that could drift)
    assert KEYS == {t.name: t.names for t in schema.FRF_TABLES if t.name not in ("reference", "[excitation]")}
    for where, accepted in KEYS.items():
        refuse_unknown({key: None for key in accepted}, where, "f.toml")
        with pytest.raises(ConfigError, match=f"f.toml: {re.escape(where)} has an unknown key 'undocumented'"):
            refuse_unknown({"undocumented": 1}, where, "f.toml")
    # [continuation] is StepControl: every setting and no other
    from dataclasses import fields

    from microslip.frequency import StepControl
    assert set(KEYS["[continuation]"]) == {f.name for f in fields(StepControl)}
    assert {k.name: k.default for k in schema.CONTINUATION.keys} == {f.name: f.default for f in fields(StepControl)}


# -- files that use every documented key ---------------------------------------------------------------------

BLOCK_EXTRA = """
[excitation]
static = [0.0, "-1N"]
h1 = ["0.6N", "0N"]
phase_h1 = [0.0, 90.0]
scale = 2.0

[sweep]
omega = [12000, 18000]
samples = 256
harmonics = 7
reduction = "exact"
engine_order = 3

[continuation]
ds_initial = 0.02
chord_error = 1e-4
ds_max = 0.05
ds_min = 1e-7
max_angle = 0.1
max_iterations = 12
max_points = 5000
target_iterations = 3
tolerance = 1e-9

[output]
plot = ["x", "y"]
harmonic = 1
frequency_unit = "rad/s"
"""


def _block(folder, edit=lambda text: text):
    """examples/inclined_block.toml (its contact model beside it), edited, in ``folder``."""
    shutil.copy(EXAMPLES / "sphere_4_elements.json", folder)
    text = (EXAMPLES / "inclined_block.toml").read_text()
    text = text[:text.index("\n[excitation]")] + BLOCK_EXTRA + text[text.index("\n[modes]"):]
    path = folder / "block.toml"
    path.write_text(edit(text))
    return path


def _used(data: dict, tables=schema.FRF_TABLES) -> set:
    """``(table name, key)`` of every key a configuration's tables use (patterned keys by their pattern)."""
    by = {t.name: t for t in tables}
    used = set()

    def visit(table: str, values: dict):
        for key, value in values.items():
            spec = by[table].key(key)
            assert spec is not None, (table, key)
            used.add((table, spec.name))
            child = {"structure": "[structure]", "cyclic": "[cyclic]", "contact": "[[contact]]", "damper": "[[damper]]",
                     "excitation": "[excitation]", "sweep": "[sweep]", "design": "[design]",
                     "continuation": "[continuation]", "output": "[output]", "modes": "[modes]",
                     "prestress": "[prestress]", "speed": "[speed]", "campbell": "[campbell]",
                     "interface": "[[damper.interface]]", "reference": "reference", "vary": "[vary]",
                     "case": "[[case]]", "random": "[random]", "mistuning": "[mistuning]"}.get(key)
            if child in by and isinstance(value, dict):
                visit(child, value)
            elif child in by and isinstance(value, list):
                for item in value:
                    visit(child, item)

    visit(tables[0].name, data)
    return used


def _documents(folder):
    """Configurations that between them use every key of the frf schema, and ``nonlinear`` for each."""
    docs = []
    # 1. the inclined block, inline matrices: the excitation, sweep, continuation, output and modes tables
    block = _block(folder, lambda t: t.replace("engine_order = 3\n", "").replace(
        "dof = \"x\"", "dof = \"x\"\nmode = 1\ncompare = false")
        + '\n[speed]\nat = ["0rpm", "6000rpm"]\nK = [[1.1e7, 0.0], [0.0, 1.1e7]]\n'
          '\n[campbell]\nspeeds = ["0rpm", "8000rpm"]\npoints = 5\nengine_orders = [1, 2]\nmodes = 2\n'
          'contacts = "both"\nnodal_diameters = [0]\n')
    docs.append((block, True))
    # 2. matrices from an .npz, Rayleigh damping, a sphere tuned when the file is read, the range in Hz
    M, K = np.diag([0.1, 0.1]), np.diag([1e7, 1e7])
    np.savez(folder / "block.npz", M=M, K=K)
    text = block.read_text()
    structure = text[text.index("\n[structure]") + 1:text.index("\n[[contact]]") + 1]
    two = block.with_name("block2.toml")
    two.write_text(text.replace(structure, '[structure]\nmatrices = "block.npz"\nrayleigh = [1.0, 2e-6]\n'
                                            'dofs = ["x", "y"]\n\n')
                   .replace('model = "sphere_4_elements.json"',
                            'reference = {kind = "sphere", radius = "5mm", E = "200GPa", nu = 0.3, mu = 0.4, '
                            'E2 = "210GPa", nu2 = 0.3}\nload = "40N"\nelements = 3\napproach = "1um"')
                   .replace("omega = [12000, 18000]", "frequency = [1900, 2900]")
                   .replace('reduction = "exact"', 'reduction = "modal"\nmodes = 1')
                   + '\n[prestress]\nfriction = "stuck"\nmodes = 2\nrayleigh_damping = [0.01, 0.02]\n'
                     'rayleigh_modes = [1, 2]\n')
    docs.append((two, True))
    # 3. one finite-element file with its variables' names and a DOF map; a punch tuned when the file is read
    np.savez(folder / "fe.npz", MGG=M, KGG=K)
    (folder / "dofs.csv").write_text("node,component\n7,x\n7,y\n")
    three = block.with_name("block3.toml")
    three.write_text(text.replace(structure, '[structure]\nfile = "fe.npz"\nformat = "npz"\nnames = {M = "MGG", K = "KGG"}\n'
                                              'dof_map = "dofs.csv"\n\n')
                     .replace('model = "sphere_4_elements.json"',
                              'reference = {kind = "punch", flat_radius = "0.5mm", edge_radius = "5mm", '
                              'mdr_elements = 200}\nload = "40N"')
                     .replace('plot = ["x", "y"]', 'plot = ["7:x", "7:y"]').replace('dof = "x"', 'dof = "7:x"')
                     + '\n[prestress]\nfriction = "released"\nmodal_damping = [0.01, 0.02]\n')
    docs.append((three, True))
    # 4. the blade pair with its damper as one sector of a disk (engine order in [cyclic]), its design table
    pair = write_config(folder, lambda t: t.replace("damping = 200.0", 'damping = 200.0\nretention = "1e3N/m"')
                        .replace("[excitation]", "[cyclic]\nsectors = 12\nleft = [2]\nright = [5]\nengine_order = 2\n"
                                                 "frame = \"cylindrical\"\naxis = [0, 0, 1]\npoint = [0, 0, 0]\n\n"
                                                 "[excitation]")
                        + "\n[modes]\nnodal_diameter = 2\nfolds = \"follow\"\n")
    docs.append((pair, True))
    # 5. the damper's load from its speed and radius, an interface tuned when the file is read, the engine order
    #    in [sweep]
    five = folder / "pair5.toml"
    five.write_text(pair.read_text().replace('centrifugal_load = "50N"', 'speed = "1000rad/s"\nradius = "0.25m"')
                    .replace('model = "curved.json"', 'reference = {kind = "sphere"}\nload = "37.5N"\nelements = 3')
                    .replace("engine_order = 2\n", "").replace("harmonics = 3", "harmonics = 3\nengine_order = 2")
                    .replace("[modes]\nnodal_diameter = 2\nfolds = \"follow\"\n", ""))
    docs.append((five, False))
    # 6. the pair as a sector in the global Cartesian frame: its boundary nodes' coordinates, no other node
    (folder / "six").mkdir()
    six = write_config(folder / "six")
    cartesian(six)
    six.write_text(six.read_text().replace("engine_order = 2\n", "engine_order = 2\nnodes = []\n"))
    docs.append((six, False))
    return docs




@pytest.mark.filterwarnings("ignore::microslip.OneSidedDamperWarning")  # document 4: keys, not physics
def test_files_using_every_documented_key_are_read(tmp_path):
    used = set()
    for path, nonlinear in _documents(tmp_path):
        load_config(path, nonlinear=nonlinear)  # raises if any key or value is refused
        used |= _used(read_toml(path))
    declared = {(t.name, k.name) for t in schema.FRF_TABLES for k in t.keys}
    assert declared == used


@pytest.mark.filterwarnings("ignore::microslip.OneSidedDamperWarning")  # document 4: keys, not physics
def test_the_continuation_table_reaches_the_step_control(tmp_path):
    # every key of [continuation] is StepControl's own: the values are passed on as written (the chord rule too)
    cfg = load_config(_block(tmp_path, lambda t: t.replace("engine_order = 3\n", "")), nonlinear=True)
    assert cfg.control.chord_error == 1e-4 and cfg.control.ds_max == 0.05 and cfg.control.max_points == 5000


def test_a_file_with_an_undocumented_key_in_any_table_is_refused(tmp_path):
    for path, nonlinear in _documents(tmp_path):
        data = read_toml(path)
        tables = [("the file", data)] + [(f"[{k}]", v) for k, v in data.items() if isinstance(v, dict)] + [
            (f"[[{k}]]", v[0]) for k, v in data.items() if isinstance(v, list) and v and isinstance(v[0], dict)]
        for where, table in tables:
            table["undocumented"] = 1
            with pytest.raises(ConfigError, match="has an unknown key 'undocumented'"):
                config_from_data(data, path, nonlinear=nonlinear)
            del table["undocumented"]


def test_a_value_of_the_wrong_type_is_refused_with_the_type_and_an_example(tmp_path):
    path = _block(tmp_path, lambda t: t.replace("reduction = \"exact\"", "reduction = 3"))
    with pytest.raises(ConfigError, match=r"block.toml: \[sweep\] reduction must be a string, got 3 \(e.g. reduction "
                                          r"= \"exact\"\)"):
        load_config(path)
    path = _block(tmp_path, lambda t: t.replace('title = "Block on an inclined plane"', "title = 5"))
    with pytest.raises(ConfigError, match=r"block.toml: title must be a string, got 5"):
        load_config(path)


def test_a_study_using_every_documented_key_is_read_and_an_undocumented_one_refused(tmp_path):
    base = _block(tmp_path, lambda t: t.replace("engine_order = 3\n", ""))
    study = tmp_path / "study.toml"
    text = ('base = "block.toml"\nsolve = "frf"\ntitle = "all keys"\n[vary]\n"sweep.harmonics" = [5, 7]\n'
            '[[case]]\n"contact.sphere.preload" = "30N"\n[random]\nsamples = 2\nseed = 1\n'
            '"excitation.scale" = {uniform = [1.0, 2.0]}\n')
    study.write_text(text)
    load_study(study)
    used = _used(read_toml(study), schema.STUDY_TABLES)
    declared = {(t.name, k.name) for t in schema.STUDY_TABLES for k in t.keys}
    # [mistuning] needs a bladed disk: its keys are read in tests/study/test_mistuning_study.py
    assert declared - used == {("the study file", "mistuning")} | {("[mistuning]", k.name)
                                                                   for k in schema.MISTUNING.keys}
    assert base.is_file()
    for where, edit in [("the study file", "undocumented = 1\n" + text), ("[random]", text + "undocumented = 1\n")]:
        study.write_text(edit)
        with pytest.raises(ConfigError, match=f"{re.escape(where)} has an unknown key 'undocumented'"):
            load_study(study)


def test_the_command_prints_the_reference_and_writes_it(tmp_path, capsys):
    assert main(["config-reference"]) == 0
    assert capsys.readouterr().out == reference_markdown()
    out = tmp_path / "configuration.md"
    assert main(["config-reference", "-o", str(out)]) == 0
    assert out.read_text(encoding="utf-8") == reference_markdown()


def test_the_commands_point_to_the_reference(capsys):
    for command in ("frf", "modes", "design", "sweep"):
        with pytest.raises(SystemExit):
            main([command, "--help"])
        text = " ".join(capsys.readouterr().out.split())
        assert "microslip config-reference" in text and "__doc__" not in text, command
