import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from microslip import Sphere, accuracy, mdr, paths, tune
from microslip.accuracy import PathBatch, reference_run

SPHERE = Sphere.paper()
J4 = tune(SPHERE, 37.5, elements=4)


@pytest.fixture(scope="module")
def reference():
    return mdr(SPHERE, max_load=37.5, elements=800)


@pytest.fixture(scope="module")
def small_family():
    return paths.default_family(SPHERE, 37.5, ratios=(0.0, 0.6), phases_deg=(0.0, 90.0), amplitudes=(0.1, 0.5, 2.0),
                                levels=(0.3, 1.0), steps_per_cycle=120)


def test_batch_runs_each_path_as_if_alone(small_family):
    """The separator sample restores the virgin state exactly: batch and one-by-one runs are identical."""
    batch = PathBatch(small_family)
    T, N, W = batch.run(J4, chunks=3)
    for p, Tp, Np in zip(small_family, batch.split(T), batch.split(N)):
        r = p.simulate(J4)
        np.testing.assert_array_equal(Tp, r.T)
        np.testing.assert_array_equal(Np, r.N)
    for p, Wp in zip(small_family, batch.split(W)):
        np.testing.assert_array_equal(Wp, p.simulate(J4).friction_work)


@settings(max_examples=20, deadline=None)
@given(data=st.lists(st.tuples(st.floats(-2e-6, 2e-6), st.floats(0.0, 2.5e-6)), min_size=2, max_size=30),
       cut=st.integers(1, 29))
def test_batch_of_arbitrary_paths(data, cut):
    t, n = np.array(data).T
    cut = min(cut, len(t) - 1)
    ps = [paths.from_arrays(t, n=n), paths.from_arrays(t[::-1].copy(), n=n[::-1].copy())]
    if cut >= 2:
        ps.append(paths.from_arrays(t[:cut], n=n[:cut]))
    batch = PathBatch(ps)
    T, _, _ = batch.run(J4)
    for p, Tp in zip(ps, batch.split(T)):
        np.testing.assert_array_equal(Tp, p.simulate(J4).T)


def test_a_model_against_itself_is_exact(small_family):
    rep = accuracy(J4, J4, small_family)
    assert np.all(rep.force_difference == 0) and np.all(rep.normal_difference == 0)
    e = rep.energy_error
    assert np.all(e[~np.isnan(e)] == 0)


def test_energy_of_a_jenkins_array_on_a_loop(reference):
    """At constant n the J = 4 array dissipates sum 4 F_i (t_a - s_i)+ per cycle, Mindlin's formula the MDR's."""
    N, ta = 20.0, 0.6e-6
    loop = paths.loop(SPHERE, N, ta, steps_per_cycle=2000)
    rep = accuracy(J4, reference, [loop])
    n = float(SPHERE.approach(N))
    F = J4.mu * J4.kn * np.maximum(n - J4.gaps, 0.0)
    W = np.sum(4 * F * np.maximum(ta - F / J4.kt, 0.0))
    assert rep.energy[0] == pytest.approx(W, rel=1e-5)  # trapezoid on 2000 samples per cycle: measured 2e-7
    Ta = float(SPHERE.backbone(ta, N))
    assert rep.energy_reference[0] == pytest.approx(float(SPHERE.dissipation(Ta, N)), rel=1e-4)  # J = 800
    assert rep.energy_error[0] == pytest.approx(W / float(SPHERE.dissipation(Ta, N)) - 1, abs=1e-4)
    assert rep.peak[0] == pytest.approx(np.max(np.abs(loop.simulate(J4).T)))
    T, Tr = loop.simulate(J4).T[loop.steady], loop.simulate(reference).T[loop.steady]
    assert rep.force_difference[0] == pytest.approx(np.max(np.abs(T - Tr)) / np.max(np.abs(Tr)))


def test_finer_reference_agrees_with_coarser(reference, small_family):
    rep = accuracy(mdr(SPHERE, max_load=37.5, elements=200), reference, small_family)
    ok = ~rep.shakedown
    # MDR 200 vs 800 elements: measured worst 0.8 % energy (at the smallest amplitude), 1e-4 force
    assert np.nanmax(np.abs(rep.energy_error[ok])) < 0.02
    assert np.max(rep.force_difference) < 1e-3
    assert np.max(np.abs(rep.normal_difference)) < 1e-4


def test_shakedown_paths_have_no_energy_error(reference):
    """Small amplitude under a strongly varying load: the continuous contact stops slipping."""
    Nm, Na = 10.0, 9.0
    p = paths.variable_load_cycles(SPHERE, Nm, Na, 0.1 * float(SPHERE.gross_slip_displacement(Nm - Na)), 0.0)
    rep = accuracy(J4, reference, [p])
    assert rep.shakedown[0] and np.isnan(rep.energy_error[0])
    assert abs(rep.energy_reference[0]) < 1e-12 * rep.work_scale[0]
    assert "1 of them shakes down in the reference" in rep.summary_text()


def test_summary_names_the_worst_path(reference, small_family):
    rep = accuracy(J4, reference, small_family)
    rows = rep.summary()
    assert [r[0] for r in rows][0].startswith("energy per cycle")
    worst, k = rep.worst("force_difference")
    assert rows[2][1] == worst and rows[2][3] == small_family[k].label
    assert worst == np.max(rep.force_difference)
    text = rep.summary_text()
    assert "worst %" in text and f"{len(small_family)} paths" in text


def test_threshold_amplitude(reference, small_family):
    rep = accuracy(J4, reference, small_family)
    a = rep.threshold_amplitude(0.10)
    err = np.abs(rep.energy_error)
    amp = rep.param("amplitude")
    if np.isnan(a):
        assert np.nanmax(err[amp == amp.max()]) > 0.10
    else:
        assert np.all(np.nan_to_num(err[amp >= a], nan=np.inf) <= 0.10)
    assert rep.threshold_amplitude(1e9) == amp.min()


def test_reference_run_is_reused(reference, small_family):
    run = reference_run(reference, small_family)
    a = accuracy(J4, run)
    b = accuracy(J4, reference, small_family)
    np.testing.assert_array_equal(a.force_difference, b.force_difference)
    with pytest.raises(ValueError, match="ReferenceRun of other paths"):
        accuracy(J4, run, small_family[:3])


def test_csv_and_figures(reference, small_family, tmp_path):
    rep = accuracy(J4, reference, small_family)
    out = rep.to_csv(tmp_path / "acc.csv")
    lines = out.read_text().splitlines()
    assert lines[0].startswith("path,") and "energy_error [%]" in lines[0] and len(lines) == 1 + len(small_family)
    fig = rep.plot()
    assert len(fig.axes) >= 4 and "t_a / t_gs" in fig.axes[0].get_xlabel()
    ax = rep.plot_amplitude(label="J = 4")
    assert "energy error" in ax.get_ylabel()
    user = accuracy(J4, reference, [paths.paper_fig4(SPHERE, steps=50)])
    with pytest.raises(ValueError, match="plot\\(\\) needs paths from default_family"):
        user.plot()
    plt.close("all")


@pytest.mark.parametrize("call, exc, message", [
    (lambda r: accuracy(J4, r, []), ValueError, "paths must hold at least one Path"),
    (lambda r: accuracy(J4, r, [1, 2]), TypeError, r"paths\[0\] must be a microslip.paths.Path"),
    (lambda r: accuracy(J4, r, 3), TypeError, "paths must be a Path or a sequence of Path"),
    (lambda r: accuracy("model.json", r, paths.loop(SPHERE, 10.0, 1e-7)), TypeError, "model must be a MicroslipModel"),
    (lambda r: accuracy(J4, None, paths.loop(SPHERE, 10.0, 1e-7)), TypeError, "reference_model must be a Micro"),
    (lambda r: accuracy(J4, r), ValueError, "paths is required"),
    (lambda r: accuracy(J4, r, paths.loop(SPHERE, 10.0, 1e-7)).metric("energy"), ValueError,
     "name must be one of 'energy_error', 'peak_error'"),
    (lambda r: accuracy(J4, r, paths.loop(SPHERE, 10.0, 1e-7)).param("amplitdue"), ValueError,
     "name must be a path parameter, one of N_a, N_m, amplitude, "),
    (lambda r: accuracy(J4, r, paths.loop(SPHERE, 10.0, 1e-7)).where([np.nan]), ValueError,
     r"mask must be a boolean array of shape \(1,\)"),
    (lambda r: accuracy(J4, r, paths.loop(SPHERE, 10.0, 1e-7), progress="no"), TypeError,
     "progress must be True or False, got 'no'"),
    (lambda r: accuracy(J4, r, paths.loop(SPHERE, 10.0, 1e-7)).to_csv(1.0), TypeError,
     r"path must be a file name \(str or os.PathLike\), got 1.0"),
    (lambda r: accuracy(J4, r, paths.loop(SPHERE, 10.0, 1e-7)).where([False]), ValueError, "mask selects no path"),
    (lambda r: accuracy(J4, r, paths.loop(SPHERE, 10.0, 1e-7)).where([True, False]), ValueError,
     r"mask must be a boolean array of shape \(1,\)"),
])
def test_bad_input(reference, call, exc, message):
    with pytest.raises(exc, match=message):
        call(reference)


def test_load_beyond_the_reference_is_refused(reference):
    with pytest.raises(ValueError, match=r"paths\[0\] \(loop at N = 40 N.*max_load = 37.5 N the reference was built for"):
        accuracy(J4, reference, paths.loop(SPHERE, 40.0, 1e-7))


def test_cli_accuracy(tmp_path, capsys):
    from microslip.cli import main

    model = tmp_path / "j4.json"
    J4.save(model)
    out = tmp_path / "acc"
    status = main(["accuracy", str(model), "--out", str(out), "--mdr-elements", "200", "--steps-per-cycle", "16",
                   "--min-load", "7.5N", "--quiet"])
    assert status == 0
    printed = capsys.readouterr().out
    assert "all paths:" in printed and "paths with N >= 7.5 N" in printed and "450 paths" in printed
    for name in ("accuracy.csv", "summary.txt", "accuracy-maps.png", "accuracy-amplitude.png"):
        assert (out / name).stat().st_size > 0
    assert (out / "summary.txt").read_text().strip().splitlines()[-1] == printed.strip().splitlines()[-1]
    # the summary states the version, the date and every parameter of the run first
    from microslip.common._version import __version__

    head = (out / "summary.txt").read_text().split("\n\n")[0].splitlines()
    assert head[0] == f"microslip version: {__version__}" and head[1].startswith("date: 20")
    assert {"model: " + str(model), "reference: sphere", "loads up to: 37.5 N", "MDR elements: 200",
            "samples per cycle: 16", "min load: 7.5 N", "min amplitude: 0.5 t_gs(N_min)", "mu: 0.4"} <= set(head)


@pytest.mark.parametrize("args, message", [
    (["missing.json"], "model file 'missing.json' does not exist"),
    (["{model}", "--mdr-elements", "0"], "--mdr-elements must be an integer >= 1, got 0"),
    (["{model}", "--steps-per-cycle", "4"], "--steps-per-cycle must be an integer >= 8, got 4"),
])
def test_cli_accuracy_errors(tmp_path, capsys, args, message):
    from microslip.cli import main

    model = tmp_path / "j4.json"
    J4.save(model)
    assert main(["accuracy"] + [a.format(model=model) for a in args] + ["--quiet"]) == 2
    assert message in capsys.readouterr().err


def test_reproduce_sections(tmp_path):
    """The three accuracy sections of 'microslip reproduce' run, and their Markdown tables stay well formed."""
    from microslip.figures import accuracy as acc_section
    from microslip.figures import accuracy_amplitude, accuracy_sweep, reproduce

    reproduce(tmp_path, sections=[acc_section, accuracy_sweep, accuracy_amplitude], progress=False)
    md = (tmp_path / "report.md").read_text()
    for name in ("accuracy", "accuracy_sweep", "accuracy_amplitude"):
        assert (tmp_path / f"{name}.png").exists() and (tmp_path / f"{name}.csv").exists()
    assert "smallest J with both worst errors <= 2 %, optimal points | 11 |" in md  # README, "Accuracy"
    tables, previous = [], False
    for line in md.splitlines():  # consecutive '|' lines form a table
        if line.startswith("|"):
            if not previous:
                tables.append([])
            tables[-1].append(line)
        previous = line.startswith("|")
    assert len(tables) == 6  # run parameters, two accuracy summaries, the sweep, the amplitudes, the errors
    for t in tables:  # every row of a table has as many cells as its header (no '|' inside a cell)
        assert {line.count("|") for line in t} == {t[0].count("|")}, t[0]


def test_an_open_path_is_measured_by_the_energy_dissipated_not_the_work():
    """On the paper's Fig. 4 path (not closed) the work ∫ T dt also counts the elastic energy stored
    at the end; the accuracy report uses the friction work, which is the energy dissipated."""
    path = paths.paper_fig4(SPHERE)
    assert not path.periodic
    rep = accuracy(J4, J4, [path])
    r = path.simulate(J4)
    s = path.steady
    assert rep.energy[0] == pytest.approx(float(r.friction_work[s][1:].sum()), rel=1e-12)
    assert rep.energy[0] < 0.9 * float(np.trapezoid(r.T[s], r.t[s]))  # the stored energy is not counted
