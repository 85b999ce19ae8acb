"""The command line uses what a model file records of its tuning, and says when it departs from it."""

from __future__ import annotations

import json

import numpy as np
import pytest

from microslip import MicroslipModel
from microslip.cli import main
from microslip.loops.synthetic import dataset_files

CHEAP = ["--mdr-elements", "200", "--steps-per-cycle", "32", "--quiet"]  # a coarse reference: seconds, not minutes


def run(argv, capsys):
    capsys.readouterr()
    code = main(argv)
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture(scope="module")
def sphere_model(tmp_path_factory):
    path = tmp_path_factory.mktemp("sphere") / "m.json"
    assert main(["tune", "--radius", "10mm", "--load", "50N", "-o", str(path)]) == 0
    return path


@pytest.fixture(scope="module")
def cylinder_model(tmp_path_factory):
    path = tmp_path_factory.mktemp("cylinder") / "c.json"
    assert main(["tune", *map(str, dataset_files()), "--elements", "6", "-o", str(path), "--quiet"]) == 0
    return path


def test_tune_records_the_options_in_the_model_file(sphere_model, cylinder_model):
    p = MicroslipModel.load(sphere_model).provenance
    assert p.reference["radius"] == 10e-3 and p.normal_load == 50.0
    assert p.mu_source == "the default --mu 0.4 (the paper's)"
    c = MicroslipModel.load(cylinder_model).provenance
    assert c.kind == "MeasuredContact" and c.loops == tuple(map(str, dataset_files()))
    assert c.mu_source == "fitted from the slip forces"


def test_tune_on_loops_prints_percentages_not_raw_fractions(tmp_path, capsys):
    code, out, _ = run(["tune", *map(str, dataset_files()), "--elements", "6", "-o", str(tmp_path / "c.json"),
                        "--quiet"], capsys)
    summary = json.loads(out)
    assert code == 0 and "fit_relative_residual" not in summary  # printed 0.0011305052964766381 before
    from microslip import Cylinder, loops, tune_on_loops

    result = tune_on_loops([loops.analyse(loops.read(p)) for p in dataset_files()],
                           Cylinder(10e-3, 5e-3, 200e9, 0.3, law="palmgren"), elements=6)
    printed = {"fit": summary["fit_relative_residual_percent"], **summary["worst_validation_difference_percent"]}
    exact = {"fit": result.reference.fit.relative_residual, **result.validation.worst()}
    for key, value in printed.items():
        # a percentage to three significant digits: within half a unit of the third digit of 100 x the fraction
        assert value == pytest.approx(100 * exact[key], rel=5e-3), key
        assert len(f"{value:g}".replace(".", "").replace("-", "").lstrip("0")) <= 3, value


def test_accuracy_compares_with_the_sphere_the_model_was_tuned_on(sphere_model, tmp_path, capsys):
    """Before: the paper's 5 mm sphere at 37.5 N, whatever the model was tuned on."""
    code, out, err = run(["accuracy", str(sphere_model), "--out", str(tmp_path), *CHEAP], capsys)
    assert code == 0 and err == ""
    assert "against the exact contact of a sphere, radius 10 mm, E = 200 GPa" in out and "loads up to 50 N" in out
    assert "tuned on a Sphere (radius = 0.01 m" in (tmp_path / "summary.txt").read_text()


def test_accuracy_says_a_load_other_than_the_tuning_load(sphere_model, tmp_path, capsys):
    code, out, err = run(["accuracy", str(sphere_model), "--load", "20N", "--out", str(tmp_path), *CHEAP], capsys)
    said = (f"--load 20 N differs from the load {sphere_model} was tuned at (50 N): the family's loads go up to "
            "20 N, not to the tuning load (drop --load to use 50 N)")
    assert code == 0 and f"microslip accuracy: warning: {said}" in err
    assert f"note: {said}" in (tmp_path / "summary.txt").read_text()
    code, out, err = run(["accuracy", str(sphere_model), "--load", "60N", "--out", str(tmp_path), *CHEAP], capsys)
    assert "beyond the tuning load, where every element is closed" in err
    assert err.count("warning") == 1  # said once, not once per path by the model


def test_accuracy_refuses_to_compare_a_cylinder_model_with_a_sphere_unless_asked(cylinder_model, tmp_path, capsys):
    code, _, err = run(["accuracy", str(cylinder_model), "--out", str(tmp_path / "a"), *CHEAP], capsys)
    assert code == 2 and f"microslip accuracy: error: {cylinder_model} was tuned on a MeasuredContact" in err
    assert "--reference sphere (with --radius, --E, --nu) or --reference punch" in err
    assert not (tmp_path / "a").exists()
    code, out, err = run(["accuracy", str(cylinder_model), "--reference", "sphere", "--out", str(tmp_path / "b"),
                          *CHEAP], capsys)
    assert code == 0 and "not a sphere: it is compared with a sphere as asked (--reference sphere)" in err


def test_accuracy_of_a_model_that_records_no_tuning_says_what_it_assumes(tmp_path, capsys):
    from microslip import Sphere, tune

    bare = tune(Sphere.paper(), 37.5, elements=4).with_provenance(None)
    path = bare.save(tmp_path / "bare.json")
    code, out, err = run(["accuracy", str(path), "--out", str(tmp_path / "r"), *CHEAP], capsys)
    assert code == 0 and "records no tuning" in err and "radius 5 mm" in out and "loads up to 37.5 N" in out


def test_simulate_beyond_the_tuning_load_warns_with_the_tuned_range(sphere_model, tmp_path, capsys):
    """Before: --load 1e9N wrote an approach of tens of metres without a word."""
    history = tmp_path / "h.csv"
    history.write_text("t [um]\n0\n1\n")
    out = tmp_path / "f.csv"
    code, stdout, err = run(["simulate", str(sphere_model), str(history), "--load", "1e9N", "-o", str(out)], capsys)
    assert code == 0
    assert (f"microslip simulate: warning: --load 1e+09 N is beyond the load {sphere_model} was tuned for (50 N; "
            "tuned range 0-50 N") in err
    assert err.count("warning") == 1
    assert "at 1e+09 N, approach 31.65 m" in stdout  # the approach is shown, in metres
    code, _, err = run(["simulate", str(sphere_model), str(history), "--load", "50N", "-o", str(out)], capsys)
    assert code == 0 and err == ""


@pytest.mark.parametrize("argv, message", [
    (["simulate", "m.json", "h.csv", "--load", "-30N"], "argument --load: must be a non-negative force, got '-30N'"),
    (["tune", "--load", "-30N"], "argument --load: must be a positive force, got '-30N'"),
    (["tune", "--radius", "-5mm"], "argument --radius: must be a positive length, got '-5mm'"),
    (["tune", "--forces", "5N,-15N"], "argument --forces: must be a positive force, got '-15N'"),
    (["tune", "--load-range", "-7.5N,37.5N"], "argument --load-range: must be a positive force, got '-7.5N'"),
    (["accuracy", "m.json", "--min-load", "-7.5N"], "argument --min-load: must be a positive force, got '-7.5N'"),
])
def test_negative_values_with_a_unit_reach_their_option(argv, message, capsys):
    """Before: argparse took '-30N' for an option ('expected one argument')."""
    with pytest.raises(SystemExit) as exc:
        main(argv)
    err = capsys.readouterr().err
    assert exc.value.code == 2 and message in err and "expected one argument" not in err


def test_a_negative_approach_is_a_separated_contact(sphere_model, tmp_path):
    history = tmp_path / "h.csv"
    history.write_text("t [um]\n0\n1\n")
    out = tmp_path / "f.csv"
    assert main(["simulate", str(sphere_model), str(history), "--n", "-1um", "-o", str(out)]) == 0
    data = np.genfromtxt(out, delimiter=",", names=True)
    np.testing.assert_array_equal(data["n_m"], [-1e-6, -1e-6])
    np.testing.assert_array_equal(data["N_N"], [0.0, 0.0])  # every element open
