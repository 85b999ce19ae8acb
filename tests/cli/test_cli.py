"""The ``microslip`` command line, run in-process (and once through the console script)."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from microslip import MicroslipModel, Sphere, tune
from microslip.cli import COMMANDS, main


def read_csv(path):
    lines = Path(path).read_text().splitlines()
    header = lines[0].split(",")
    data = np.array([[float(c) for c in ln.split(",")] for ln in lines[1:]])
    return header, data


@pytest.fixture
def model_file(tmp_path):
    path = tmp_path / "model.json"
    assert main(["tune", "-o", str(path)]) == 0
    return path


def test_tune_writes_a_model_that_load_reads(tmp_path, capsys):
    path = tmp_path / "model.json"
    assert main(["tune", "-o", str(path)]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out == {"written": str(path), "elements": 4, "mu": 0.4}
    # the defaults are the paper's benchmark, tuned at 37.5 N with four elements
    assert MicroslipModel.load(path) == tune(Sphere.paper(), 37.5, elements=4)


def test_tune_options_with_units(tmp_path):
    path = tmp_path / "m.json"
    assert main(["tune", "--radius", "10mm", "--E", "210GPa", "--nu", "0.29", "--mu", "0.5",
                 "--load", "0.05kN", "--forces", "5N,15N,25N", "-o", str(path)]) == 0
    sphere = Sphere(radius=10e-3, E=210e9, nu=0.29, mu=0.5)
    assert MicroslipModel.load(path) == tune(sphere, 50.0, forces=[5.0, 15.0, 25.0])
    t_gs = float(sphere.gross_slip_displacement(50.0))
    disp = f"{0.3 * t_gs * 1e6!r}um,{t_gs!r}"
    path2 = tmp_path / "m2.json"
    assert main(["tune", "--radius", "10mm", "--E", "210GPa", "--nu", "0.29", "--mu", "0.5",
                 "--load", "50N", "--displacements", disp, "--output", str(path2)]) == 0
    assert MicroslipModel.load(path2).elements == 2
    assert main(["tune", "--elements", "7", "-o", str(path)]) == 0
    assert MicroslipModel.load(path).elements == 7


def test_simulate_a_table_with_units(model_file, tmp_path, capsys):
    history = tmp_path / "history.csv"
    t_um = np.array([0.0, 0.4, 0.9, 1.3, 0.2, -0.8, -1.3, 0.0])
    n_um = np.array([2.0, 2.0, 2.1, 2.2, 2.0, 1.9, 2.0, 2.0])
    history.write_text("# a load path\nt [um], n [um]\n"
                       + "".join(f"{a}, {b}\n" for a, b in zip(t_um, n_um)))
    out = tmp_path / "forces.csv"
    capsys.readouterr()
    assert main(["simulate", str(model_file), str(history), "-o", str(out)]) == 0
    assert f"wrote {out} (8 steps" in capsys.readouterr().out
    header, data = read_csv(out)
    assert header == ["t [m]", "n [m]", "T [N]", "N [N]"]
    r = MicroslipModel.load(model_file).simulate(t_um * 1e-6, n_um * 1e-6)
    np.testing.assert_allclose(data[:, 0], t_um * 1e-6, rtol=1e-15)
    np.testing.assert_allclose(data[:, 2], r.T, rtol=1e-15)  # CSV keeps repr(float): exact
    np.testing.assert_allclose(data[:, 3], r.N, rtol=1e-15)


def test_simulate_constant_normal_approach_or_load_and_plot(model_file, tmp_path):
    history = tmp_path / "h.txt"
    history.write_text("t\n0\n5e-7\n1e-6\n")  # no unit: SI
    model = MicroslipModel.load(model_file)
    out = tmp_path / "a.csv"
    assert main(["simulate", str(model_file), str(history), "--n", "2um", "-o", str(out)]) == 0
    _, data = read_csv(out)
    np.testing.assert_allclose(data[:, 2], model.simulate([0, 5e-7, 1e-6], 2e-6).T, rtol=1e-15)
    out2, png = tmp_path / "b.csv", tmp_path / "loop.png"
    assert main(["simulate", str(model_file), str(history), "--load", "30N", "-o", str(out2),
                 "--plot", str(png)]) == 0
    _, data = read_csv(out2)
    np.testing.assert_allclose(data[:, 3], 30.0, rtol=1e-12)  # the model's own normal curve
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # --unit gives the unit of columns whose header has none
    history.write_text("t\n0\n0.5\n1\n")
    out3 = tmp_path / "c.csv"
    assert main(["simulate", str(model_file), str(history), "--n", "2um", "--unit", "um", "-o", str(out3)]) == 0
    np.testing.assert_allclose(read_csv(out3)[1], data_at(out), rtol=1e-15)


def data_at(path):
    return read_csv(path)[1]


@pytest.mark.parametrize("command", [None] + COMMANDS)
def test_help_of_every_sub_command(command, capsys):
    argv = ["--help"] if command is None else [command, "--help"]
    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 0
    text = capsys.readouterr().out
    assert "usage: microslip" in text
    if command is not None:
        assert command in text


def test_every_option_is_explained(capsys):
    """No option of any sub-command without a help text."""
    from microslip.cli import build_parser

    parser = build_parser()
    sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
    for name, p in sub.choices.items():
        for action in p._actions:
            assert action.help, f"microslip {name}: option {action.option_strings or action.dest} has no help"


@pytest.mark.parametrize("argv, message", [
    (["tune", "--load", "10parsec"], "argument --load: value: unknown force unit 'parsec'"),
    (["tune", "--E", "200GN"], "argument --E: value: unknown pressure unit 'GN'"),
    (["tune", "--forces", "5N,ten"], "argument --forces: value: cannot read 'ten' as a number"),
    (["simulate", "m.json", "h.csv", "--n", "2 furlongs"], "argument --n: value: unknown length unit 'furlongs'"),
    (["tune", "--elements", "4", "--forces", "15N"], "not allowed with argument"),
    (["bogus"], "invalid choice: 'bogus'"),
])
def test_argument_errors_exit_with_code_2(argv, message, capsys):
    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 2
    assert message in capsys.readouterr().err


def test_errors_from_the_work_exit_with_code_2(model_file, tmp_path, capsys):
    def run(argv):
        capsys.readouterr()
        code = main(argv)
        return code, capsys.readouterr().err

    missing = tmp_path / "missing.json"
    code, err = run(["simulate", str(missing), str(tmp_path / "h.csv")])
    assert code == 2 and f"microslip simulate: error: model file {str(missing)!r} does not exist" in err
    code, err = run(["simulate", str(model_file), str(tmp_path / "h.csv")])
    assert code == 2 and "table file" in err and "does not exist" in err
    history = tmp_path / "h.csv"
    history.write_text("t [parsec]\n1\n")
    code, err = run(["simulate", str(model_file), str(history), "--n", "2um"])
    assert code == 2 and "column 't': unknown length unit 'parsec'" in err
    history.write_text("x [um]\n1\n")
    code, err = run(["simulate", str(model_file), str(history), "--n", "2um"])
    assert code == 2 and "no column 't'; the columns are ['x']" in err
    code, err = run(["tune", "--forces", "1N,2N", "-o", str(tmp_path / "x.json")])
    assert code == 2 and "microslip tune: error: forces: the last point must be at gross slip" in err
    code, err = run(["tune", "--elements", "0", "-o", str(tmp_path / "x.json")])
    assert code == 2 and "elements must be an integer >= 1, got 0" in err
    code, err = run(["tune", "--nu", "0.7", "-o", str(tmp_path / "x.json")])
    assert code == 2 and "nu must lie in (-1.0, 0.5], got 0.7" in err
    assert not (tmp_path / "x.json").exists()


def test_console_script(tmp_path):
    script = shutil.which("microslip") or str(Path(sys.executable).with_name("microslip"))
    assert Path(script).exists(), "the console script 'microslip' is not installed"
    out = tmp_path / "model.json"
    done = subprocess.run([script, "tune", "--elements", "3", "-o", str(out)], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    assert MicroslipModel.load(out).elements == 3
    bad = subprocess.run([script, "tune", "--load", "10parsec"], capture_output=True, text=True, timeout=120)
    assert bad.returncode == 2 and "unknown force unit 'parsec'" in bad.stderr


def test_a_negative_value_with_a_unit_reaches_its_option(tmp_path, capsys):
    # argparse used to take "-30N" for an option and stop with "expected one argument"
    from microslip import Sphere, tune

    tune(Sphere.paper(), 37.5, elements=4).save(tmp_path / "m.json")
    # refused by the option's own check (argparse's exit status 2), naming the option and the value
    with pytest.raises(SystemExit) as stop:
        main(["accuracy", str(tmp_path / "m.json"), "--load", "-30N", "--out", str(tmp_path / "out"), "--quiet"])
    err = capsys.readouterr().err
    assert stop.value.code == 2 and "expected one argument" not in err and "--load" in err and "-30" in err
