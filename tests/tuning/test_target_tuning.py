import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from microslip import Sphere, TargetNotMet, TargetProblem, smallest_elements, tune, tune_to_target
from microslip.tuning.target import ElementSweep, dense_options, element_sweep, load_optimal_points, optimal_points
from microslip.tuning.target.search import _fractions, _log_spacings, _starts

SPHERE = Sphere.paper()
SMALL = {"ratios": (0.0, 0.6), "phases_deg": (90.0,), "amplitudes": (0.5, 1.0, 2.0), "levels": (0.5, 1.0)}


@pytest.fixture(scope="module")
def small():
    """A cheap problem: 9 paths, 60 samples per cycle, a 400-element reference."""
    return TargetProblem(SPHERE, (7.5, 37.5), steps_per_cycle=60, reference_elements=400, family_options=SMALL)


@pytest.fixture(scope="module")
def paper_problem():
    """The problem of the README's sweep: loads 7.5..37.5 N, t_a >= 0.5 t_gs(N_min), 2 % and 2 %."""
    return TargetProblem(SPHERE, (7.5, 37.5))


def test_family_restriction(small, paper_problem):
    for pb in (small, paper_problem):
        for p in pb.family:
            assert p.params["N_m"] - p.params["N_a"] >= 7.5 * (1 - 1e-12)
            assert p.params["amplitude"] >= 0.5
            assert p.N.max() <= 37.5 * (1 + 1e-12)
    assert len(paper_problem.family) == 96


def test_even_spacings_are_the_tune_models(small):
    res = small.tune_spacing("force", 4)
    assert res.model == tune(SPHERE, 37.5, elements=4) and res.spacing == "force"
    res = small.tune_spacing("displacement", 5)
    tgs = float(SPHERE.gross_slip_displacement(37.5))
    # t_j = (j / J) t_gs, in tune_fractions' order of operations: (t_gs j) / J may round the other way
    assert res.model == tune(SPHERE, 37.5, displacements=np.arange(1, 6) / 5 * tgs)
    assert res.meets == (res.energy_error <= 0.02 and res.force_difference <= 0.02)


def test_optimised_points_beat_their_start_and_stay_a_paper_model(small):
    J = 5
    res = optimal_points(small, J, method="local", maxfev=60, restarts=1)
    even = small.tune_spacing("displacement", J)
    score = max(res.energy_error, res.force_difference) / 0.02
    assert score <= max(even.energy_error, even.force_difference) / 0.02 + 1e-12
    # the result is still tuned by the paper's equations on its points
    assert res.model == tune(SPHERE, 37.5, displacements=res.points.t)
    assert np.all(np.diff(res.points.t) > 0) and res.points.t[-1] == pytest.approx(
        float(SPHERE.gross_slip_displacement(37.5)))
    assert "spacing='optimal'" in repr(res)
    ax = res.plot(SPHERE)
    assert "t (µm)" in ax.get_xlabel() and "T (N)" in ax.get_ylabel()
    plt.close("all")


def test_global_search_is_deterministic_and_no_worse_than_its_start(small):
    """Differential evolution (fixed seed) then Nelder-Mead: same points twice, never worse than the local search."""
    J = 4
    local = optimal_points(small, J, method="local", restarts=0)  # the best spacing law alone
    a = optimal_points(small, J, budget=120, restarts=1, maxfev=40)
    b = optimal_points(small, J, budget=120, restarts=1, maxfev=40)
    np.testing.assert_array_equal(a.points.t, b.points.t)
    assert max(a.energy_error, a.force_difference) <= max(local.energy_error, local.force_difference) + 1e-12
    assert a.evaluations > 120  # the starts, the evolution and the polish all ran


def test_dense_options_sample_the_ranges():
    opts = dense_options(0.5)
    amps, levels = np.array(opts["amplitudes"]), np.array(opts["levels"])
    assert amps.size == 40 and amps[0] == pytest.approx(0.5) and amps[-1] == pytest.approx(3.0)
    assert np.allclose(np.diff(np.log(amps)), np.log(6.0) / 39)  # geometric
    assert levels.size == 10 and levels[0] == pytest.approx(0.1) and levels[-1] == pytest.approx(1.0)
    assert dense_options(4.0)["amplitudes"] == (4.0,)


def test_tune_to_target_returns_an_optimised_model(small):
    res = tune_to_target(SPHERE, (7.5, 37.5), elements=3, problem=small, maxfev=30, restarts=1,
                         budget=40)
    assert res.elements == 3 and res.spacing == "optimal" and res.evaluations > 1
    # the search starts from the best of the spacing laws; what it returns must score better than that start
    # (measured: 11.6 against 13.2; the search keeps its start when it finds nothing better, so "not worse"
    # would hold for a search that did nothing)
    start = min(small.score(small.tune_fractions(u)[0]) for u in _starts(3))
    assert small.normalised(res.energy_error, res.force_difference) < 0.95 * start


def test_smallest_elements_finds_the_first_j_that_meets(small):
    loose = TargetProblem(SPHERE, (7.5, 37.5), energy_target=0.3, force_target=0.3, steps_per_cycle=60,
                          reference_elements=400, family_options=SMALL)
    res = smallest_elements(SPHERE, (7.5, 37.5), problem=loose, spacing="displacement", max_elements=12)
    assert res.meets
    if res.elements > 2:
        before = loose.tune_spacing("displacement", res.elements - 1)
        assert not before.meets


def test_unreachable_target_reports_the_best_found():
    tight = TargetProblem(SPHERE, (7.5, 37.5), energy_target=1e-6, force_target=1e-6, steps_per_cycle=60,
                          reference_elements=400, family_options=SMALL)
    with pytest.raises(TargetNotMet, match=r"no J up to max_elements = 4 meets the target .* the best found is J = "
                                           r"\d: energy [\d.e-]+ %, force") as info:
        smallest_elements(SPHERE, (7.5, 37.5), problem=tight, spacing="displacement", max_elements=4)
    assert info.value.best.elements in (2, 3, 4) and not info.value.best.meets


@pytest.mark.parametrize("kwargs, exc, message", [
    ({"load_range": 37.5}, TypeError, "load_range must be a pair"),
    ({"load_range": (37.5, 7.5)}, ValueError, "load_range must satisfy N_lo < N_hi, got \\(37.5, 7.5\\)"),
    ({"load_range": (-1.0, 7.5)}, ValueError, r"load_range\[0\] must be positive"),
    ({"load_range": (7.5, 37.5), "energy_target": 0.0}, ValueError, "energy_target must be positive"),
    ({"load_range": (7.5, 37.5), "min_amplitude": 50.0}, ValueError, "leave no path of the family"),
    ({"load_range": (7.5, 37.5), "reference_elements": 10**12}, ValueError,
     "reference_elements must be at most 10000000"),
    ({"load_range": (7.5, 37.5), "reference_elements": 2.5}, TypeError, "reference_elements must be an integer"),
])
def test_problem_bad_input(kwargs, exc, message):
    with pytest.raises(exc, match=message):
        TargetProblem(SPHERE, **{"reference_elements": 50, "steps_per_cycle": 16, "family_options": SMALL, **kwargs})


def test_bad_arguments(small):
    with pytest.raises(ValueError, match="spacing must be one of force, displacement, optimal"):
        smallest_elements(SPHERE, (7.5, 37.5), problem=small, spacing="random")
    with pytest.raises(ValueError, match="start must have 4 fractions, got 2"):
        optimal_points(small, 4, start=[0.5, 1.0])
    with pytest.raises(ValueError, match="method must be one of global, local, got 'annealing'"):
        optimal_points(small, 4, method="annealing")
    with pytest.raises(ValueError, match="budget must be an integer >= 1, got 0"):
        optimal_points(small, 4, budget=0)
    with pytest.raises(TypeError, match="dense must be True or False, got 'yes'"):
        TargetProblem(SPHERE, (7.5, 37.5), dense="yes", family_options=SMALL, reference_elements=50,
                      steps_per_cycle=16)
    with pytest.raises(ValueError, match="amplitudes must be an integer >= 2, got 1"):
        dense_options(0.5, amplitudes=1)
    with pytest.raises(ValueError, match="spacing must be 'force' or 'displacement' here"):
        small.tune_spacing("optimal", 3)
    with pytest.raises(ValueError, match="spacings must be among"):
        element_sweep(small, [2], spacings=("even",))
    with pytest.raises(TypeError, match="family_options must be a mapping"):
        TargetProblem(SPHERE, (7.5, 37.5), family_options="abc", reference_elements=50, steps_per_cycle=16)
    with pytest.raises(TypeError, match="problem must be a TargetProblem, got str"):
        element_sweep("problem", [2])
    with pytest.raises(TypeError, match=r"elements\[i\] must be an integer, got nan"):
        element_sweep(small, [2, float("nan")])
    with pytest.raises(ValueError, match="spacing must be one of 'force'"):
        element_sweep(small, [2], spacings=("force",)).smallest("forse")
    with pytest.raises(ValueError, match="energy_error must be finite, got nan"):
        small.normalised(float("nan"), 0.01)
    with pytest.raises(ValueError, match="spacing must be one of 'force', 'displacement', 'optimal', got 'even'"):
        small.result(*small.tune_fractions([0.5, 1.0]), "even")
    with pytest.raises(TypeError, match="points must be TuningPoints"):
        small.result(small.tune_fractions([0.5, 1.0])[0], [0.5, 1.0], "optimal")
    with pytest.raises(ValueError, match=r"fractions must increase strictly up to 1 \(gross slip\), got \[0.5 2. \]"):
        small.tune_fractions([0.5, 2.0])
    with pytest.raises(ValueError, match="elements must be at most 10000000"):
        small.tune_spacing("force", 10**12)


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(1e-3, 1.0), min_size=2, max_size=20, unique=True))
def test_log_spacings_round_trip(values):
    u = np.sort(values)
    assume(np.min(np.diff(u)) > 1e-6)  # points closer than that are no distinct tuning points
    u = u / u[-1]
    back = _fractions(_log_spacings(u))
    assert np.allclose(back, u, rtol=1e-9, atol=1e-12) and back[-1] == 1.0 and np.all(np.diff(back) > 0)


def test_sweep_with_known_points(small):
    known = {3: np.array([0.3, 0.7, 1.0]), 4: np.array([0.2, 0.45, 0.75, 1.0])}
    sw = element_sweep(small, [2, 3, 4], spacings=("force", "optimal"), fractions=known, restarts=1, maxfev=20,
                       method="local")
    assert isinstance(sw, ElementSweep) and list(sw.elements) == [2, 3, 4]
    np.testing.assert_allclose(sw.fractions[4], known[4])  # re-measured, not searched again
    res = small.tune_spacing("force", 3)
    assert sw.energy_error["force"][1] == res.energy_error
    assert len(sw.rows()) == 3 and "energy error optimal [%]" in sw.columns()
    assert len(sw.plot().axes) == 2
    plt.close("all")


def test_stored_optimal_points_meet_the_target(paper_problem):
    """The README's claim, re-measured: the stored optimised points of the smallest J meet 2 % / 2 %."""
    data = load_optimal_points()
    assert data["problem"]["load_range"] == [7.5, 37.5]
    fractions = data["fractions"]
    for J, u in fractions.items():
        assert u.size == J and u[-1] == 1.0 and np.all(np.diff(u) > 0)
    scores = {}
    for J in sorted(fractions):
        model, _ = paper_problem.tune_fractions(fractions[J])
        scores[J] = paper_problem.score(model)
        if scores[J] <= 1:
            break
    best = min(J for J, s in scores.items() if s <= 1)
    # and the even-displacement array of the same J does not: the optimisation is what makes it
    assert paper_problem.tune_spacing("displacement", best).meets is False
    assert best == STORED_SMALLEST


#: smallest J meeting 2 % / 2 % with the stored optimised points (README, "Accuracy" section)
STORED_SMALLEST = 11


def test_dense_sampling_measures_between_the_default_samples():
    """README: the default family samples 6 amplitudes >= 0.5; sampled densely, the worst energy error of the
    stored J = 11 points is far above 2 % (26 %, measured), while on the default samples it meets 2 %."""
    dense = TargetProblem(SPHERE, (7.5, 37.5), dense=True)
    assert len(dense.family) == 1560 and dense.dense
    amps = {p.params["amplitude"] for p in dense.family}
    assert len(amps) == 40 and min(amps) == pytest.approx(0.5)
    model, _ = dense.tune_fractions(load_optimal_points()["fractions"][STORED_SMALLEST])
    e, f = dense.worst(model)
    assert e > 0.10  # the energy error between the default samples: 0.262 measured, far from 0.02
    assert f < 0.03  # the force difference hardly moves (2.18 % against 1.28 %): it is not sampling-sensitive


def test_cli_target_elements(tmp_path, capsys):
    import json

    from microslip import MicroslipModel
    from microslip.cli import main

    out = tmp_path / "opt.json"
    assert main(["target", "--elements", "2", "-o", str(out), "--quiet"]) == 0
    summary = json.loads(capsys.readouterr().out)
    model = MicroslipModel.load(out)
    assert model.elements == 2 and summary["elements"] == 2 and len(summary["points_um"]) == 2
    assert summary["meets_target"] is False  # two elements are far from 2 %


def test_cli_target_sweep_reusing_points(tmp_path, capsys):
    from microslip.cli import main

    assert main(["target", "--sweep", "2-3", "--reuse-points", "--out", str(tmp_path), "--quiet"]) == 0
    printed = capsys.readouterr().out
    assert "smallest J meeting the target with optimal points" in printed
    assert (tmp_path / "sweep.csv").exists() and (tmp_path / "sweep.png").exists()


@pytest.mark.parametrize("args", [["--load-range", "37.5N"], ["--sweep", "0-3"], ["--sweep", "a"]])
def test_cli_target_bad_options(args, capsys):
    from microslip.cli import main

    with pytest.raises(SystemExit):
        main(["target"] + args)
    assert "expected" in capsys.readouterr().err


def test_cli_target_sweep_from_stored_points_is_no_worse(tmp_path, capsys, paper_problem):
    import json

    from microslip.cli import main

    saved = tmp_path / "points.json"
    assert main(["target", "--sweep", "3", "--start-from-stored", "--budget", "8", "--seed", "1",
                 "--out", str(tmp_path), "--save-points", str(saved), "--quiet"]) == 0
    capsys.readouterr()
    found = np.array(json.loads(saved.read_text())["fractions"]["3"])
    stored = load_optimal_points()["fractions"][3]
    score = {name: paper_problem.score(paper_problem.tune_fractions(u)[0]) for name, u in
             (("found", found), ("stored", stored))}
    assert score["found"] <= score["stored"] + 1e-12


def test_the_differential_evolution_shows_its_progress(small, capsys, monkeypatch):
    """It ran silently for 35 s on the default problem: now a line per generation, at most one every 5 s."""
    from microslip.common import _progress

    clock = iter(range(0, 10_000, 6))  # each reading of the clock 6 s later: more than 5 s between lines
    monkeypatch.setattr(_progress.time, "perf_counter", lambda: float(next(clock)))
    optimal_points(small, 3, budget=64, restarts=0, progress=True)
    err = capsys.readouterr().err
    lines = [ln for ln in err.splitlines() if "generation" in ln and "best score" in ln]
    assert len(lines) >= 2, err
    assert lines[0].strip().startswith("generation ") and " of 3, best score " in lines[0]
