"""``microslip modes``: the frf configuration with a [modes] table to a nonlinear mode, plots and a report."""

import numpy as np
import pytest

from microslip.cli import main
from microslip.common._table import read_table
from microslip.config import ConfigError, load_config
from test_hbm_cli import _edit, config_dir  # noqa: F401  (the example block's configuration, as frf's tests)


def test_modes_writes_the_mode_its_synthesis_and_a_report(config_dir, capsys):
    out = config_dir / "out"
    assert main(["modes", str(config_dir / "block.toml"), "--out", str(out)]) == 0
    for name in ("modes.csv", "modes.png", "synthesis.csv", "synthesis.png", "report.html", "report.md"):
        assert (out / name).stat().st_size > 0
    printed = capsys.readouterr()
    assert "[10/10] modal amplitude 1e-05 kg^1/2 m" in printed.err  # progress along the mode
    columns, units = read_table(out / "modes.csv")
    assert units["modal amplitude"] == "kg^0.5 m" and units["damping ratio"] == "-" and units["x a1"] == "m"
    assert columns["modal amplitude"][0] == pytest.approx(1e-9) and columns["modal amplitude"][-1] == pytest.approx(1e-5)
    # x moves cos(30 deg) / sqrt(0.1 kg) = 2.739 times the modal amplitude along the stuck mode
    assert columns["x a1"][0] / columns["modal amplitude"][0] == pytest.approx(np.cos(np.radians(30)) / np.sqrt(0.1))
    report = (out / "report.md").read_text()
    assert "Mode 1: 2603.06 Hz with the contacts stuck" in report  # sqrt((1e7 + 3/4 of the contact's kt) / 0.1)
    assert "static state: normal force N0 = 21.36" in report and "3 of 4 elements closed" in report
    assert "| modal amplitude (kg^1/2 m) | x harmonic 1 (µm) | frequency (Hz) |" in report
    assert "synthesised from the mode alone" in report and "its peak near the mode" in report
    assert "Mode 1: 2603.06 Hz" in printed.out
    # the synthesis against harmonic balance: the peak of x within a few percent (the block's second mode, which the
    # force along x also excites, adds to harmonic balance's x only)
    difference = float(report.split("the synthesis differs by ")[1].split(" %")[0])
    assert abs(difference) < 5


def test_modes_needs_neither_excitation_nor_sweep(config_dir):
    cfg = config_dir / "block.toml"
    text = cfg.read_text()
    start, end = text.index("[excitation]"), text.index("[output]")
    cfg.write_text(text[:start] + "[sweep]\nharmonics = 3\n\n" + text[end:])
    out = config_dir / "out"
    assert main(["modes", str(cfg), "--out", str(out), "--quiet"]) == 0
    assert (out / "modes.csv").is_file() and not (out / "synthesis.csv").exists()
    assert "H = 3 harmonics" in (out / "report.md").read_text()


def test_modes_stopped_early_writes_what_it_has_and_fails(config_dir, capsys):
    cfg = config_dir / "block.toml"
    _edit(cfg, "[output]", "[continuation]\nmax_points = 5\n\n[output]")
    assert main(["modes", str(cfg), "--out", str(config_dir / "out"), "--quiet"]) == 1
    assert "stopped at max_points = 5 points" in capsys.readouterr().err
    assert "**Incomplete mode**" in (config_dir / "out" / "report.md").read_text()


@pytest.mark.parametrize("old, new, words", [
    ("dof = \"x\"", "dof = \"z\"", "[modes] dof: 'z' is not a DOF"),
    ("dof = \"x\"", "dof = 5", "[modes] dof names DOF 5; the structure has 2"),
    ("dof = \"x\"", "dfo = \"x\"", "[modes] has an unknown key 'dfo'; did you mean 'dof'?"),
    ("amplitude = [1e-9, 1e-5]", "amplitude = [1e-5, 1e-9]", "[modes] amplitude must rise from start to end"),
    ("amplitude = [1e-9, 1e-5]", "amplitude = 1e-5", "[modes] amplitude must be a list [start, end]"),
    ("amplitude = [1e-9, 1e-5]", "amplitude = [-1e-9, 1e-5]", "[modes] amplitude[0] must be"),
    ("dof = \"x\"", "mode = 3", "[modes] mode must be at most the number of DOFs (2), got 3"),
    ("dof = \"x\"", "mode = 0", "[modes] mode must be an integer >= 1, got 0"),
    ("dof = \"x\"", "compare = \"yes\"", "[modes] compare must be True or False"),
    ("dof = \"x\"", "folds = \"skip\"", "[modes] folds must be one of 'stop', 'follow', got 'skip'"),
])
def test_modes_configuration_errors_name_the_key(config_dir, old, new, words):
    cfg = config_dir / "block.toml"
    _edit(cfg, old, new)
    with pytest.raises(ConfigError) as info:
        load_config(cfg, nonlinear=True)
    assert words in str(info.value)
    assert main(["modes", str(cfg), "--out", str(config_dir / "out")]) == 2


def test_modes_folds_key_reaches_the_solver(config_dir, monkeypatch):
    """``[modes] folds`` is what ``nonlinear_modes`` is called with (default "stop")."""
    import microslip.frequency

    class Called(Exception):
        pass

    cfg = config_dir / "block.toml"
    assert load_config(cfg, nonlinear=True).nonlinear_mode.folds == "stop"
    _edit(cfg, "dof = \"x\"", "dof = \"x\"\nfolds = \"follow\"")
    seen = {}

    def spy(*args, **kwargs):
        seen.update(kwargs)
        raise Called  # enough: the call's arguments are what is checked

    monkeypatch.setattr(microslip.frequency, "nonlinear_modes", spy)
    with pytest.raises(Called):
        main(["modes", str(cfg), "--out", str(config_dir / "out"), "--quiet"])
    assert seen["folds"] == "follow"


def test_modes_needs_a_modes_table_and_frf_ignores_it(config_dir, capsys):
    cfg = config_dir / "block.toml"
    text = cfg.read_text()
    (config_dir / "plain.toml").write_text(text[:text.index("\n[modes]")])
    assert main(["modes", str(config_dir / "plain.toml"), "--out", str(config_dir / "out")]) == 2
    assert "needs the key 'modes'" in capsys.readouterr().err
    assert load_config(cfg).nonlinear_mode is None  # microslip frf reads the same file without it


def test_modes_help_explains_every_option(capsys):
    with pytest.raises(SystemExit):
        main(["modes", "--help"])
    text = " ".join(capsys.readouterr().out.split())  # the description wrapped to the terminal: words rejoined
    for words in ("config", "--out", "--quiet", "[modes]", "modes.csv", "synthesis.csv", "Exit status"):
        assert words in text


DISK = """title = "Six-sector disk"

[structure]
M = [[0.1, 0.0, 0.0], [0.0, 0.2, 0.0], [0.0, 0.0, 0.1]]
K = [[3e7, -1e7, -0.5e7], [-1e7, 2e7, -1e7], [-0.5e7, -1e7, 3e7]]
rayleigh = [2.0, 0.0]

[cyclic]
sectors = 6
left = [0]
right = [2]
engine_order = 1

[[contact]]
model = "sphere_4_elements.json"
tangential = {"1" = 1.0, "next:1" = -1.0}
approach = "1.5um"

[excitation]
h1 = [0, "1N", 0]

[sweep]
omega = [9000, 16000]
harmonics = 3

[modes]
amplitude = [1e-8, 1e-4]
dof = 1
"""


def test_modes_of_a_sector_take_the_engine_order_as_nodal_diameter(config_dir):
    (config_dir / "disk.toml").write_text(DISK)
    out = config_dir / "out"
    assert main(["modes", str(config_dir / "disk.toml"), "--out", str(out), "--quiet"]) == 0
    report = (out / "report.md").read_text()
    assert "| nodal diameter | 1 |" in report
    difference = float(report.split("the synthesis differs by ")[1].split(" %")[0])
    assert abs(difference) < 2  # measured -0.12 %: a sector's blade on its neighbours, one mode near
    (config_dir / "plain.toml").write_text(DISK.replace("[cyclic]\nsectors = 6\nleft = [0]\nright = [2]\n"
                                                        "engine_order = 1\n", "")
                                           .replace('{"1" = 1.0, "next:1" = -1.0}', "1")
                                           .replace("dof = 1", "dof = 1\nnodal_diameter = 2"))
    with pytest.raises(ConfigError, match=r"\[modes\] nodal_diameter needs a \[cyclic\] table"):
        load_config(config_dir / "plain.toml", nonlinear=True)
