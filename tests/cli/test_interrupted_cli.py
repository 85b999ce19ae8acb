"""Ctrl-C and peaks on the range's edge in ``microslip frf`` and ``microslip modes``: what was computed is written,
marked, and the command says so in one line (exit status 130 when interrupted)."""

import sys

from microslip.cli import main
from microslip.common._table import read_table
from test_hbm_cli import _edit, config_dir  # noqa: F401  (the example block's configuration)
from _paths import REPO

sys.path.insert(0, str(REPO / "tests" / "frequency"))
from test_design import interrupt_after  # noqa: E402


def test_an_interrupted_frf_writes_the_curve_so_far_and_exits_130(config_dir, capsys, monkeypatch):
    interrupt_after(monkeypatch, 7)
    out = config_dir / "out"
    assert main(["frf", str(config_dir / "block.toml"), "--out", str(out), "--quiet"]) == 130
    columns, _ = read_table(out / "frf.csv")
    assert columns["omega"].size == 7 and columns["omega"][0] == 12000.0
    report = (out / "report.md").read_text()
    assert "**Interrupted** (interrupted at omega = " in report and "after 7 points" in report
    err = capsys.readouterr().err
    assert "Traceback" not in err
    assert err.strip().splitlines()[-1].startswith("microslip frf: interrupted: interrupted at omega = ")


def test_an_interrupted_mode_writes_the_mode_so_far_and_exits_130(config_dir, capsys, monkeypatch):
    interrupt_after(monkeypatch, 12)
    out = config_dir / "out"
    assert main(["modes", str(config_dir / "block.toml"), "--out", str(out), "--quiet"]) == 130
    columns, _ = read_table(out / "modes.csv")
    assert columns["modal amplitude"].size == 12 and not (out / "synthesis.csv").exists()
    assert "**Interrupted** (interrupted at modal amplitude " in (out / "report.md").read_text()
    err = capsys.readouterr().err
    assert "Traceback" not in err
    assert err.strip().splitlines()[-1].startswith("microslip modes: interrupted: interrupted at modal amplitude ")


def test_ctrl_c_before_anything_is_computed_is_one_line(config_dir, capsys, monkeypatch):
    import microslip.config

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(microslip.config, "load_config", interrupted)
    assert main(["frf", str(config_dir / "block.toml"), "--out", str(config_dir / "out"), "--quiet"]) == 130
    assert capsys.readouterr().err == "microslip frf: interrupted\n"


def test_frf_says_when_a_curve_is_highest_on_the_range_edge(config_dir, capsys):
    # the block's first resonance is at 15390 rad/s: up to 15000 the response still rises at the end
    _edit(config_dir / "block.toml", "omega = [12000, 18000]", "omega = [12000, 15000]")
    out = config_dir / "out"
    assert main(["frf", str(config_dir / "block.toml"), "--out", str(out), "--quiet"]) == 0
    err = capsys.readouterr().err
    assert ("microslip frf: warning: x: the highest point of the curve is the end of the frequency range (omega = "
            "15000 rad/s") in err and "widen [sweep] omega past that end" in err
    report = (out / "report.md").read_text()
    assert "**Highest on the range's edge**: x: " in report and "on the range's edge: no peak" in report
