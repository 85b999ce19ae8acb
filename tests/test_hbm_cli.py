"""``microslip frf``: a TOML configuration to a curve, plots and a report; configuration errors."""

import shutil
from pathlib import Path

import numpy as np
import pytest

from microslip._table import read_table
from microslip.cli import main
from microslip.frequency.config import ConfigError, load_config

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


@pytest.fixture
def config_dir(tmp_path):
    shutil.copy(EXAMPLES / "inclined_block.toml", tmp_path / "block.toml")
    shutil.copy(EXAMPLES / "sphere_4_elements.json", tmp_path / "sphere_4_elements.json")
    return tmp_path


def _edit(path, old, new):
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new))


def test_frf_writes_curve_plots_and_report(config_dir, capsys):
    cfg = config_dir / "block.toml"
    _edit(cfg, "omega = [12000, 18000]", "omega = [13000, 16000]")
    out = config_dir / "out"
    assert main(["frf", str(cfg), "-o", str(out)]) == 0
    for name in ("frf.csv", "frf.png", "contacts.png", "report.html", "report.md"):
        assert (out / name).stat().st_size > 0
    err = capsys.readouterr().err
    assert "[10/10] omega =" in err  # progress along the curve
    columns, units = read_table(out / "frf.csv")
    assert units["omega"] == "rad/s" and units["q0 max"] == "m"
    assert columns["omega"][0] == 13000 and columns["omega"][-1] == 16000
    report = (out / "report.md").read_text()
    assert "| x |" in report and "static normal load" in report


def test_config_matrices_from_npz_and_frequency_in_hz(config_dir):
    cfg = config_dir / "block.toml"
    np.savez(config_dir / "m.npz", M=0.1 * np.eye(2), K=1e7 * np.eye(2))
    _edit(cfg, "M = [[0.1, 0.0], [0.0, 0.1]]          # kg", 'matrices = "m.npz"\nrayleigh = [173.2, 0.0]')
    _edit(cfg, "K = [[1e7, 0.0], [0.0, 1e7]]          # N/m\n", "")
    _edit(cfg, "C = [[17.32, 0.0], [0.0, 17.32]]      # N s/m\n", "")
    _edit(cfg, "omega = [12000, 18000]                # rad/s", 'frequency = ["2kHz", "2.5kHz"]')
    c = load_config(cfg)
    assert np.allclose(c.structure.C, 17.32 * np.eye(2))
    assert np.allclose(c.omega, (2 * np.pi * 2000, 2 * np.pi * 2500))
    assert c.dof_names == ["x", "y"] and c.harmonics == 7 and c.harmonic == 1


@pytest.mark.parametrize("old, new, message", [
    ("[sweep]", "[swep]", "unknown top-level key\\(s\\) \\['swep'\\]"),
    ('h1 = ["0.6N", "0N"]', 'h1 = ["0.6m", "0N"]', "unknown force unit 'm'"),
    ('h1 = ["0.6N", "0N"]', 'first = [0.6, 0.0]', "key 'first' is neither 'static' nor 'h<harmonic>'"),
    ('model = "sphere_4_elements.json"', 'model = "nope.json"', "model file .*nope.json.* does not exist"),
    ('preload = "37.5N"', 'preload = "37.5N"\napproach = "1um"\nbogus = 1', None),
    ("omega = [12000, 18000]", "omega = [12000]", "the range must have 2 values"),
    ("tangential = [0.8660254, 0.5]", "tangential = [1.0]", "tangential must have one coefficient per DOF"),
    ('dofs = ["x", "y"]', 'dofs = ["x"]', "dofs names 1 DOFs, the matrices have 2"),
    ("plot = [0, 1]", "plot = [4]", "plot names DOF 4; the structure has 2"),
    ("harmonics = 7", "harmonics = 7\n[continuation]\nstep = 1", "\\[continuation\\] unknown key"),
    ("M = [[0.1, 0.0], [0.0, 0.1]]", 'M = "heavy"', "\\[structure\\] M must be a matrix|M must be"),
])
def test_config_errors_name_the_key(config_dir, old, new, message):
    cfg = config_dir / "block.toml"
    _edit(cfg, old, new)
    if message is None:  # extra keys in a contact table are tolerated; a preload and an approach together too
        load_config(cfg)
        return
    with pytest.raises((ConfigError, FileNotFoundError, ValueError), match=message):
        load_config(cfg)


def test_frf_reports_errors_without_traceback(config_dir, capsys):
    cfg = config_dir / "block.toml"
    _edit(cfg, "[sweep]", "[sweeep]")
    assert main(["frf", str(cfg)]) == 2
    assert "microslip frf: error:" in capsys.readouterr().err
    assert main(["frf", str(config_dir / "missing.toml")]) == 2


def test_frf_help_documents_every_option(capsys):
    with pytest.raises(SystemExit):
        main(["frf", "--help"])
    text = capsys.readouterr().out
    for option in ("config", "--output", "--quiet", "microslip.frequency.config"):
        assert option in text
