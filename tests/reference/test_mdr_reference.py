"""An MDR array as a reference contact: the paper's tuning for any axisymmetric profile, and its limits."""

import numpy as np
import pytest

from microslip import LoadLimitError, MicroslipModel, Sphere, mdr, paths, tune
from microslip.reference import RoundedPunch

SPHERE = Sphere.paper()


@pytest.fixture(scope="module")
def sphere_mdr():
    return mdr(SPHERE, max_load=40.0, elements=2000)


def test_tuning_on_the_mdr_sphere_equals_tuning_on_the_closed_forms(sphere_mdr):
    on_mdr = tune(sphere_mdr.as_reference(), 37.5, elements=4)
    closed = tune(SPHERE, 37.5, elements=4)
    # the 2000-element array matches Hertz and Cattaneo-Mindlin to ~1e-6 (tests/test_mdr.py);
    # measured here: stiffnesses within 1e-6, gaps within 2e-13 m
    np.testing.assert_allclose(on_mdr.kt, closed.kt, rtol=1e-5)
    np.testing.assert_allclose(on_mdr.kn, closed.kn, rtol=1e-5)
    np.testing.assert_allclose(on_mdr.gaps, closed.gaps, rtol=0, atol=1e-5 * closed.gaps.max())


def test_backbone_inverse_and_gross_slip_of_the_mdr_reference(sphere_mdr):
    ref = sphere_mdr.as_reference()
    T = np.linspace(-15.0, 15.0, 31)
    t = ref.backbone_displacement(T, 37.5)
    np.testing.assert_allclose(ref.backbone(t, 37.5), T, rtol=0, atol=1e-9 * 15)
    assert float(ref.gross_slip_displacement(37.5)) == pytest.approx(
        float(SPHERE.gross_slip_displacement(37.5)), rel=1e-5)
    with pytest.raises(ValueError, match=r"T must satisfy \|T\| <= mu\*N"):
        ref.backbone_displacement(16.0, 37.5)


def test_a_rounded_punch_is_tuned_and_its_family_of_paths_built():
    punch = mdr(SPHERE, max_load=50.0, elements=1500, profile=RoundedPunch(1e-3, 5e-3)).as_reference()
    model = tune(punch, 40.0, elements=6)
    n = float(punch.approach(40.0))
    # the tuned array carries the tuning load and slips at mu N there, as the continuous punch
    assert float(model.normal_force(n)) == pytest.approx(40.0, rel=1e-9)
    assert float(model.slip_force(n)) == pytest.approx(0.4 * 40.0, rel=1e-9)
    assert len(paths.default_family(punch, 40.0)) > 0


def test_loads_beyond_max_load_are_refused_and_an_mdr_model_is_not_saved(sphere_mdr, tmp_path):
    with pytest.raises(LoadLimitError, match=r"N reaches 41 N, beyond max_load = 40 N"):
        sphere_mdr.approach(41.0)
    with pytest.raises(LoadLimitError):
        sphere_mdr.as_reference().backbone(1e-7, 45.0)
    with pytest.raises(TypeError, match=r"an MDRModel is not saved"):
        sphere_mdr.save(tmp_path / "x.json")
    assert not (tmp_path / "x.json").exists()


def test_mdr_simulate_forwards_the_recording_options(sphere_mdr):
    t = np.linspace(0.0, 1e-6, 50)
    r = sphere_mdr.simulate(t, 1e-6, per_element=False, work=False)
    assert r.Ti is None and r.friction_work is None
    assert isinstance(sphere_mdr, MicroslipModel)


def test_accuracy_command_with_a_punch_reference_and_its_input_errors(tmp_path, capsys):
    from microslip.cli import main

    model_file = tmp_path / "punch.json"
    punch = mdr(SPHERE, max_load=37.5, elements=800, profile=RoundedPunch(1e-3, 5e-3)).as_reference()
    tune(punch, 37.5, elements=6).save(model_file)
    out = tmp_path / "acc"
    fast = ["--mdr-elements", "400", "--steps-per-cycle", "60", "--quiet", "--out", str(out)]
    assert main(["accuracy", str(model_file), "--reference", "punch", *fast]) == 0
    assert (out / "accuracy.csv").exists() and (out / "summary.txt").exists()
    capsys.readouterr()
    assert main(["accuracy", str(model_file), "--mu", "0.3", *fast]) == 2
    assert "the model's friction coefficient (0.4" in capsys.readouterr().err
    assert main(["accuracy", str(model_file), "--reference", "punch", "--min-load", "100N", *fast]) == 2
    assert "no path of the family has its lowest load >= --min-load 100 N" in capsys.readouterr().err
    assert main(["accuracy", str(model_file), "--min-amplitude", "-1", *fast]) == 2
    assert "--min-amplitude must be non-negative, got -1.0" in capsys.readouterr().err


def test_accuracy_names_the_path_beyond_the_reference_limit():
    from microslip import accuracy

    small = mdr(SPHERE, max_load=20.0, elements=200)
    family = paths.default_family(SPHERE, 37.5, ratios=(0.0,), amplitudes=(1.0,), levels=(0.5, 1.0))
    with pytest.raises(LoadLimitError, match=r"paths\[1\] \(.*\) reaches the approach .* max_load = 20 N"):
        accuracy(tune(SPHERE, 37.5, elements=4), small, family)
