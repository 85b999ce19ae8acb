"""``tune(..., load_range=...)``: the points, or J and the points, chosen by measurement (issue 3, item 4)."""

import json
import math
import re

import numpy as np
import pytest

import microslip.tuning.target.search as target_search
from microslip import Sphere, TargetNotMet, TargetProblem, tune, tune_to_target
from microslip.tuning.target import load_optimal_points, stored_fractions, stored_mismatch

SPHERE = Sphere.paper()
STORED = load_optimal_points()


@pytest.fixture(scope="module")
def paper_problem():
    return TargetProblem(SPHERE, (7.5, 37.5))


def test_given_elements_reuses_the_stored_optimised_points():
    model = tune(SPHERE, 37.5, elements=6, load_range=(7.5, 37.5))
    t = STORED["fractions"][6] * SPHERE.gross_slip_displacement(37.5)
    expected = tune(SPHERE, 37.5, displacements=t)
    np.testing.assert_array_equal(model.kt, expected.kt)
    np.testing.assert_array_equal(model.gaps, expected.gaps)
    # not the paper's force-spaced array of the same J
    assert not np.allclose(model.kt, tune(SPHERE, 37.5, elements=6).kt)


def test_targets_give_the_smallest_j_that_meets_them(paper_problem):
    model = tune(SPHERE, 37.5, load_range=(7.5, 37.5), energy_target=0.02, force_target=0.02)
    e, f = paper_problem.worst(model)
    assert e <= 0.02 and f <= 0.02
    # the stored points of one element fewer do not meet them: it is the smallest
    smaller, _ = paper_problem.tune_fractions(STORED["fractions"][model.elements - 1])
    assert paper_problem.score(smaller) > 1
    assert model.elements == 11  # README, "Accuracy" section


def test_one_target_alone_defaults_the_other_to_2_percent(paper_problem):
    model = tune(SPHERE, 37.5, load_range=(7.5, 37.5), energy_target=0.02)
    assert model.elements == 11


def test_other_problems_are_searched_afresh():
    # N_lo = 10 N is not the stored problem: the search of tune_to_target, deterministic
    model = tune(SPHERE, 37.5, elements=2, load_range=(10.0, 37.5))
    np.testing.assert_allclose(model.kt, tune_to_target(SPHERE, (10.0, 37.5), elements=2).model.kt, rtol=1e-12)


def test_unreachable_targets_raise_with_the_best_found(monkeypatch):
    # every J up to 32 "stored" (resampled) so the test re-measures rather than searches
    known = {J: target_search._resample(STORED["fractions"][16], J) for J in range(2, 33)}
    monkeypatch.setattr(target_search, "stored_fractions", lambda *a, **k: known)
    with pytest.raises(TargetNotMet, match=r"no J up to max_elements = 32 meets the target .* best found is J = \d+"):
        tune(SPHERE, 37.5, load_range=(7.5, 37.5), energy_target=1e-4, force_target=1e-4)


@pytest.mark.parametrize("kwargs, exc, message", [
    ({"energy_target": 0.02}, ValueError, r"energy_target= and force_target= need load_range=\(N_lo, N_hi\)"),
    ({"load_range": (7.5, 37.5), "forces": [15.0]}, ValueError, "load_range= chooses the tuning points itself"),
    ({"load_range": (7.5, 30.0), "elements": 4}, ValueError,
     r"normal_load must be the top of load_range .* normal_load = 37.5 N with load_range \(7.5, 30\) N"),
    ({"load_range": (7.5, 37.5)}, ValueError, "load_range= needs elements= .* or energy_target="),
    ({"load_range": (7.5, 37.5), "elements": "4"}, TypeError, "elements must be an integer, got '4'"),
    ({"load_range": (7.5, 37.5), "energy_target": -1.0}, ValueError, "energy_target must be positive, got -1.0"),
    ({"load_range": 37.5, "elements": 4}, TypeError, "load_range must be a pair"),
])
def test_bad_arguments(kwargs, exc, message):
    with pytest.raises(exc, match=message):
        tune(SPHERE, 37.5, **kwargs)


@pytest.mark.parametrize("kwargs, message", [
    ({"energy_target": 2, "force_target": 2}, "energy_target must be a fraction in (0, 1] (fractions: 0.02 means 2 %), "
                                              "got 2; for 2 % pass 0.02"),
    ({"force_target": 5.0}, "force_target must be a fraction in (0, 1] (fractions: 0.02 means 2 %), got 5"),
])
def test_targets_are_fractions_and_percent_numbers_are_refused(kwargs, message):
    """Before, energy_target=2 meant 200 % and returned J = 2; the command line's 2 meant 2 %."""
    with pytest.raises(ValueError, match=re.escape(message)):
        tune(SPHERE, 37.5, load_range=(7.5, 37.5), **kwargs)
    with pytest.raises(ValueError, match=re.escape(message)):
        TargetProblem(SPHERE, (7.5, 37.5), **kwargs)  # refused before the family or the reference is built


def test_an_infinite_target_leaves_that_error_out():
    small = {"ratios": (0.0,), "phases_deg": (90.0,), "amplitudes": (1.0,), "levels": (1.0,)}
    problem = TargetProblem(SPHERE, (7.5, 37.5), force_target=math.inf, steps_per_cycle=32, reference_elements=100,
                            family_options=small)
    model, _ = problem.tune_fractions(np.arange(1, 5) / 4)
    energy, force = problem.worst(model)
    assert force > 0 and problem.score(model) == energy / 0.02  # the force difference counts for nothing
    assert model.provenance.notes["force_target"] == "no limit"  # the file stays plain JSON (no Infinity)
    assert "Infinity" not in json.dumps(model.to_dict())


def test_stored_points_match_only_their_problem():
    assert stored_mismatch(SPHERE, (7.5, 37.5)) is None
    assert stored_fractions(SPHERE, (7.5, 37.5), energy_target=0.05, force_target=0.05) is not None  # same ratio
    assert stored_mismatch(Sphere(radius=5e-3, E=200e9, nu=0.3, mu=0.3), (7.5, 37.5)) == \
        "they are for mu = 0.4, not 0.3"
    assert stored_mismatch(SPHERE, (15.0, 37.5)) == "they are for the load range 7.5-37.5 N, not 15-37.5 N"
    assert "min_amplitude 0.5, not 0.25" in stored_mismatch(SPHERE, (7.5, 37.5), min_amplitude=0.25)
    assert "energy_target / force_target = 1, not 0.5" in stored_mismatch(SPHERE, (7.5, 37.5), energy_target=0.01)
    assert stored_fractions(SPHERE, (15.0, 37.5)) is None


def test_cli_tune_load_range(tmp_path, capsys):
    from microslip import MicroslipModel
    from microslip.cli import main

    out = tmp_path / "m.json"
    assert main(["tune", "--elements", "6", "--load-range", "7.5N,37.5N", "-o", str(out), "--quiet"]) == 0
    model = MicroslipModel.load(out)
    np.testing.assert_allclose(model.kt, tune(SPHERE, 37.5, elements=6, load_range=(7.5, 37.5)).kt, rtol=1e-12)


@pytest.mark.parametrize("args, message", [
    (["--load-range", "7.5N,37.5N", "--load", "30N"], "normal_load must be the top of load_range"),
    (["--load-range", "7.5N,37.5N", "--forces", "15N"], "--load-range chooses the tuning points itself"),
])
def test_cli_tune_load_range_errors(args, message, tmp_path):
    from microslip.cli import build_parser

    parsed = build_parser().parse_args(["tune", *args, "-o", str(tmp_path / "m.json")])
    with pytest.raises(ValueError, match=message):
        parsed.func(parsed)
    assert not (tmp_path / "m.json").exists()


def test_tune_to_target_checks_elements_before_building_the_reference(monkeypatch):
    def fail(*args, **kwargs):
        raise AssertionError("the problem was built before the arguments were checked")

    monkeypatch.setattr(target_search, "TargetProblem", fail)
    with pytest.raises(TypeError, match="elements must be an integer, got '4'"):
        tune_to_target(SPHERE, (7.5, 37.5), elements="4")
    with pytest.raises(ValueError, match="elements must be an integer >= 1, got 0"):
        tune_to_target(SPHERE, (7.5, 37.5), elements=0)
