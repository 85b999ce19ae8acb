"""``microslip simulate`` on the contact plane: orbits built from options, tables with two tangential columns."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from microslip import MicroslipModel, paths
from microslip.cli import main


def read_csv(path):
    lines = Path(path).read_text().splitlines()
    return lines[0].split(","), np.array([[float(c) for c in ln.split(",")] for ln in lines[1:]])


@pytest.fixture
def model_file(tmp_path):
    path = tmp_path / "model.json"
    assert main(["tune", "-o", str(path)]) == 0
    return path


def test_an_elliptic_orbit_with_a_varying_load_is_the_paths_builder_and_the_march(model_file, tmp_path, capsys):
    out, png = tmp_path / "forces.csv", tmp_path / "orbit.png"
    capsys.readouterr()
    assert main(["simulate", str(model_file), "--orbit", "ellipse", "--size", "1.5um", "--minor", "0.7um",
                 "--angle", "-30", "--load", "25N", "--load-amplitude", "10N", "--load-phase", "90", "--cycles", "2",
                 "--steps-per-cycle", "120", "-o", str(out), "--plot", str(png)]) == 0
    printed = capsys.readouterr().out
    model = MicroslipModel.load(model_file)
    path = paths.ellipse(model, 1.5e-6, 0.7e-6, 25.0, 10.0, 90.0, angle_deg=-30.0, cycles=2, steps_per_cycle=120)
    r = path.simulate(model)
    header, data = read_csv(out)
    assert header == ["tx [m]", "ty [m]", "n [m]", "Tx [N]", "Ty [N]", "N [N]"]
    assert data.shape == (3 * 120 + 1, 6)
    np.testing.assert_array_equal(data[:, :2], path.t)  # CSV keeps repr(float): exact
    np.testing.assert_array_equal(data[:, 2], path.n)
    np.testing.assert_array_equal(data[:, 3:5], r.T)
    np.testing.assert_array_equal(data[:, 5], r.N)
    energy = r.friction_work[path.steady.start + 1:path.steady.stop].sum()
    assert f"wrote {out} (361 steps, ellipse 1.5 x 0.7 µm, N = 25 + 10 sin(tau + 90°) N, at -30°" in printed
    assert f"energy per cycle {energy:.4g} J (the last)" in printed
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("shape, extra", [("circle", []), ("figure-eight", ["--minor", "0.4um", "--angle", "45"]),
                                          ("line", ["--angle", "120"])])
def test_every_orbit_runs_with_its_defaults(model_file, tmp_path, shape, extra):
    out = tmp_path / f"{shape}.csv"
    assert main(["simulate", str(model_file), "--orbit", shape, "--size", "1um", "--load", "30N", *extra,
                 "-o", str(out)]) == 0
    header, data = read_csv(out)
    assert header[:2] == ["tx [m]", "ty [m]"] and data.shape[0] == (4 if shape == "circle" else 3) * 360 + 1
    np.testing.assert_allclose(data[:, 5], 30.0, rtol=1e-12)  # the model's own normal curve


def test_a_table_with_two_tangential_columns_runs_on_the_plane(model_file, tmp_path):
    history = tmp_path / "orbit.csv"
    k = np.arange(50)
    tx, ty = 1.2 * np.cos(2 * np.pi * k / 25) - 1.2, 0.8 * np.sin(2 * np.pi * k / 25)
    rows = "".join(f"{float(a)!r}, {float(b)!r}, 2.1\n" for a, b in zip(tx, ty))
    history.write_text("x [um], y [um], n [um]\n" + rows)
    out = tmp_path / "f.csv"
    assert main(["simulate", str(model_file), str(history), "--t-column", "x", "--ty-column", "y",
                 "-o", str(out)]) == 0
    header, data = read_csv(out)
    r = MicroslipModel.load(model_file).simulate(np.column_stack([tx, ty]) * 1e-6, 2.1e-6)
    assert header == ["tx [m]", "ty [m]", "n [m]", "Tx [N]", "Ty [N]", "N [N]"]
    np.testing.assert_allclose(data[:, 3:5], r.T, rtol=1e-15, atol=1e-15 * np.abs(r.T).max())


def test_an_orbit_beyond_the_tuning_load_warns_once(model_file, tmp_path, capsys):
    out = tmp_path / "f.csv"
    assert main(["simulate", str(model_file), "--orbit", "circle", "--size", "1um", "--load", "35N",
                 "--load-amplitude", "10N", "-o", str(out)]) == 0
    err = capsys.readouterr().err
    assert err.count("warning") == 1
    assert "the normal load along the orbit reaches 45 N, beyond the load" in err and "(37.5 N;" in err


@pytest.mark.parametrize("argv, message", [
    ([], "give either a HISTORY table or --orbit (an orbit built from options), not neither"),
    (["h.csv", "--orbit", "circle", "--size", "1um", "--load", "30N"],
     "give either a HISTORY table or --orbit (an orbit built from options), not both"),
    (["--orbit", "circle", "--size", "1um"], "--orbit needs --load, the mean normal load along the orbit (e.g. 30N)"),
    (["--orbit", "line", "--load", "30N"], "--orbit line needs --size (e.g. 1.5um)"),
    (["--orbit", "circle", "--size", "1um", "--n", "2um"],
     "--orbit takes the normal load (--load, --load-amplitude, --load-phase), not --n"),
    (["--orbit", "circle", "--size", "1um", "--load", "30N", "--minor", "1um"],
     "--minor shapes an ellipse or a figure-eight, not a circle"),
    (["--orbit", "circle", "--size", "1um", "--load", "30N", "--angle", "20"],
     "--angle turns an ellipse, a figure-eight or a line; a circle has no direction"),
    (["--orbit", "ellipse", "--size", "1um", "--minor", "2um", "--load", "30N"],
     "--minor 2e-06 m exceeds --size 1e-06 m: the semi-minor axis of an ellipse is at most its semi-major axis"),
    (["--orbit", "line", "--size", "1um", "--load", "30N", "--load-amplitude", "40N"],
     "--load-amplitude 40 N exceeds --load 30 N: the normal load along the orbit would become negative"),
    (["--orbit", "line", "--size", "1um", "--load", "30N", "--steps-per-cycle", "4"],
     "--steps-per-cycle must be at least 8, got 4"),
    (["h.csv", "--size", "1um"], "--size shape(s) an orbit: give --orbit too, or leave them out"),
])
def test_orbit_options_that_do_not_fit_together_are_refused(model_file, argv, message, capsys):
    code = main(["simulate", str(model_file), *argv])
    err = capsys.readouterr().err
    assert code == 2 and f"microslip simulate: error: {message}" in err


@pytest.mark.parametrize("argv, message", [
    (["--orbit", "square"], "argument --orbit: invalid choice: 'square'"),
    (["--angle", "nan"], "argument --angle: must be a finite angle in degrees, got 'nan'"),
    (["--angle", "north"], "argument --angle: expected an angle in degrees such as 30, got 'north'"),
    (["--size", "-1um"], "argument --size: must be a positive length, got '-1um'"),
    (["--load-amplitude", "-1N"], "argument --load-amplitude: must be a non-negative force, got '-1N'"),
    (["--cycles", "0"], "argument --cycles: must be a positive integer, got '0'"),
])
def test_orbit_option_values_are_checked_when_read(argv, message, capsys):
    with pytest.raises(SystemExit) as exc:
        main(["simulate", "m.json", *argv])
    assert exc.value.code == 2 and message in capsys.readouterr().err
