"""The damper design curve: peak response against the centrifugal load."""

import csv

import numpy as np
import pytest
from scipy.linalg import eigvals

from microslip.frequency import ConvergenceError, StepControl, frequency_response
from microslip.frequency import contact_cycle, damper_design_curve
from microslip.frequency.analyses import design as design_module
from microslip.frequency.analyses import response as response_module
from microslip.frequency.analyses.design import DesignPointWarning
from microslip.frequency.analyses.response import CurveInterrupted, IncompleteCurveWarning, PeakOnEdgeWarning
from test_damper import blade_pair, damper  # the blade pair with its damper

LOADS = [3.0, 5.0, 20.0, 300.0]  # N: the damper slides through the cycle (3 N), partly (5, 20 N), sticks (300 N)
RANGE = (3000.0, 5000.0)  # rad/s: the blades' mode with the damper sliding (3.9 krad/s) to the stuck one (4.4)


def antiphase(ndof=6, amplitude=0.5):
    """The two tips pushed in antiphase (N): the mode in which the platforms move apart and the damper works."""
    f = np.zeros(ndof)
    f[2], f[5] = amplitude, -amplitude
    return f


@pytest.fixture(scope="module")
def curve():
    # 128 samples resolve the contacts' slip at 3 and 5 N (64 leave their energy uncertain by 2e-3 of the work)
    return damper_design_curve(blade_pair(), damper(), LOADS, antiphase(), RANGE, dof=2, harmonics=3, samples=128)


def test_each_point_is_the_peak_of_the_forced_response_at_that_load(curve):
    assert list(curve.loads) == LOADS and len(curve.responses) == 4
    r = frequency_response(damper(load=20.0).attach(blade_pair()), antiphase(9), RANGE, harmonics=3, samples=128)
    assert r.peak(2) == (curve.peak_frequency[2], curve.peak_amplitude[2])
    i = int(np.argmin(curve.peak_amplitude))
    assert curve.optimum == (LOADS[i], curve.peak_amplitude[i])


def test_the_curve_runs_from_a_sliding_damper_to_a_stuck_one(curve):
    assert all(r.complete for r in curve.responses)  # every curve reaches the end of the range: no stall
    sliding, stuck = curve.responses[0], curve.responses[-1]
    k = int(np.argmax(sliding.amplitude(2)))
    # at 3 N the damper slides through the cycle: every contact in gross slip over 90 % of the period at the
    # peak (92 to 95 % measured, never open), its first harmonic the square wave's, 4/pi mu N0 (1.25 to 1.32
    # measured), and the contacts dissipate most of the excitation's work (88 % measured)
    mu = damper().contacts[0].model.mu
    for c in range(3):
        fractions = contact_cycle(sliding, c, k).fractions()
        assert fractions["gross slip"] > 0.9 and fractions["lift-off"] == 0.0
    T1 = np.hypot(sliding.contact_T[k, :, 1], sliding.contact_T[k, :, 2])
    assert np.all(T1 > 1.1 * mu * sliding.contact_N[k, :, 0])
    assert sliding.contact_dissipation[k].sum() > 0.5 * sliding.excitation_work[k]
    # at 300 N it sticks: the peak is the linear structure's resonance with the closed elements' stick stiffnesses
    s = stuck.structure
    K = s.K.copy()
    Bt, Bn, n0 = s.contact_directions()
    q0 = stuck.coefficients[0, 0]
    for c, contact in enumerate(s.contacts):
        closed = Bn[:, c] @ q0 + n0[c] > contact.model.gaps
        K += contact.model.kt[closed].sum() * np.outer(Bt[:, c], Bt[:, c])
        K += contact.model.kn[closed].sum() * np.outer(Bn[:, c], Bn[:, c])
    w = np.sqrt(np.sort(eigvals(K, s.M).real))
    w_stuck = w[np.argmin(np.abs(w - curve.peak_frequency[-1]))]
    # within 1e-3 (1.2e-5 measured); the 20 N peak, partly sliding, is 1 % lower
    assert abs(curve.peak_frequency[-1] / w_stuck - 1) < 1e-3
    # the optimum lies between: at 5 N, far below the stuck peak (5.3 against 113 um measured); at 3 N the
    # sliding damper's friction force, mu N, is too small to hold the resonance down (13.5 um measured)
    assert curve.optimum[0] == 5.0 and curve.peak_amplitude[1] < 0.1 * curve.peak_amplitude[-1]
    assert curve.peak_amplitude[0] > 2 * curve.peak_amplitude[1]


def test_the_curve_writes_csv_and_plots(curve, tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    rows = list(csv.reader(line for line in open(curve.to_csv(tmp_path / "design.csv")) if not line.startswith("#")))
    assert rows[0][0] == "centrifugal load [N]" and len(rows) == 5
    np.testing.assert_allclose([float(r[1]) for r in rows[1:]], curve.peak_amplitude, rtol=1e-12)
    assert curve.plot().get_xlabel() == "damper centrifugal load (N)"


@pytest.mark.parametrize("kwargs, message", [
    ({"loads": [-1.0]}, "loads"),
    ({"dof": 99}, "dof: DOF 99 is out of range for a structure with 6 DOFs"),
    ({"force": np.zeros(9)}, "force must have one entry per DOF \\(6\\), got 9"),
])
def test_design_curve_arguments_are_checked(kwargs, message):
    f = antiphase()
    args = dict(loads=LOADS, force=f, dof=2)
    args.update(kwargs)
    with pytest.raises(ValueError, match=message):
        damper_design_curve(blade_pair(), damper(), args["loads"], args["force"], (3000.0, 5000.0), dof=args["dof"])


# -- loads without a peak: cut short, highest on the range's edge, failed, interrupted ----------------------------
# With one harmonic: the damper at 5 N peaks at 4072 rad/s (7.24 um), stuck at 300 N at 4400 rad/s (113 um).

def interrupt_after(monkeypatch, points: int, call: int = 1):
    """Ctrl-C (KeyboardInterrupt) in the ``call``-th continuation once its curve has ``points`` points."""
    real = response_module.continuation
    calls = [0]

    def continuation(*args, callback=None, **kwargs):
        calls[0] += 1
        this = calls[0]

        def announce(value, count):
            callback(value, count)
            if this == call and count >= points:
                raise KeyboardInterrupt

        return real(*args, callback=announce, **kwargs)

    monkeypatch.setattr(response_module, "continuation", continuation)


@pytest.mark.filterwarnings("ignore:load .* the continuation stopped")
def test_a_curve_cut_short_is_marked_and_left_out_of_the_optimum():
    with pytest.warns(IncompleteCurveWarning, match="load 300 N: the continuation stopped at max_points = 5 points"):
        cut = damper_design_curve(blade_pair(), damper(), [5.0, 300.0], antiphase(), RANGE, dof=2, harmonics=1,
                                  control=StepControl(max_points=5))
    assert not cut.complete.any() and not cut.trusted.any() and cut.status == ["incomplete curve"] * 2
    with pytest.raises(ValueError, match="no optimum: no load has a trusted peak \\(load 5 N: the forced response "
                                         "stopped at omega = "):
        cut.optimum
    # 200 points follow the 5 N curve to the end (132 points), not the 300 N one (336)
    curve = damper_design_curve(blade_pair(), damper(), [5.0, 300.0], antiphase(), RANGE, dof=2, harmonics=1,
                                control=StepControl(max_points=200))
    assert list(curve.complete) == [True, False] and curve.status == ["peak", "incomplete curve"]
    assert curve.optimum == (5.0, curve.peak_amplitude[0])
    assert "load 300 N: the forced response stopped at omega = " in curve.problems()[0]


def test_a_peak_on_the_range_edge_is_marked_and_left_out_of_the_optimum(tmp_path):
    with pytest.warns(PeakOnEdgeWarning, match="load 300 N: the highest point of the curve is the end of the "
                                               "frequency range \\(omega = 4200 rad/s"):
        curve = damper_design_curve(blade_pair(), damper(), [5.0, 300.0], antiphase(), (3000.0, 4200.0), dof=2,
                                    harmonics=1)
    assert list(curve.on_edge) == [False, True] and curve.peak_frequency[1] == 4200.0
    # the stuck damper's response at 4200 rad/s, on the flank of its resonance (4400), is below the 5 N peak
    # (5.76 against 7.24 um): taken for a peak it would be the optimum
    assert curve.peak_amplitude[1] < curve.peak_amplitude[0]
    assert curve.optimum == (5.0, curve.peak_amplitude[0])
    assert curve.problems() == [f"load 300 N: the response is highest at the end of the frequency range (4200 rad/s, "
                                f"668.451 Hz) and still rises there: the resonance lies above it and the "
                                f"{curve.peak_amplitude[1]:.4g} m there is no peak; raise the end of the range past "
                                f"the resonance"]
    rows = list(csv.DictReader(open(curve.to_csv(tmp_path / "design.csv"))))
    assert [r["status"] for r in rows] == ["peak", "peak on the range's edge"]
    assert [r["peak on edge [-]"] for r in rows] == ["0", "1"] and [r["complete [-]"] for r in rows] == ["1", "1"]
    # the forced response says so itself; peak() keeps its return type and warns
    edge, inside = curve.responses[1], curve.responses[0]
    assert edge.peak_on_edge(2) and not inside.peak_on_edge(2)
    with pytest.warns(PeakOnEdgeWarning, match="the end of the frequency range"):
        assert edge.peak(2) == (4200.0, edge.amplitude(2)[-1])


def fail_at(monkeypatch, call: int, message: str):
    """The ``call``-th forced response of a design curve fails with a ConvergenceError saying ``message``."""
    real, calls = design_module.frequency_response, []

    def failing(*args, **kwargs):
        calls.append(1)
        if len(calls) == call:
            raise ConvergenceError(message)
        return real(*args, **kwargs)

    monkeypatch.setattr(design_module, "frequency_response", failing)


@pytest.mark.filterwarnings("ignore:load .* the continuation stopped")
def test_a_load_that_fails_leaves_the_others(monkeypatch):
    fail_at(monkeypatch, 2, "Newton's method did not converge at omega = 3000 rad/s")
    with pytest.warns(DesignPointWarning, match="load 300 N: the forced response failed: Newton's method did not"):
        curve = damper_design_curve(blade_pair(), damper(), [5.0, 300.0, 20.0], antiphase(), RANGE, dof=2,
                                    harmonics=1, control=StepControl(max_points=5))
    assert curve.status == ["incomplete curve", "failed", "incomplete curve"] and curve.responses[1] is None
    assert np.isnan(curve.peak_amplitude[1]) and np.isfinite(curve.peak_amplitude[[0, 2]]).all()
    assert curve.problems()[1] == ("load 300 N: the forced response failed: Newton's method did not converge at "
                                   "omega = 3000 rad/s")


def test_an_interrupted_design_keeps_the_loads_finished(monkeypatch):
    interrupt_after(monkeypatch, 4, call=2)
    with pytest.raises(CurveInterrupted, match="^load 300 N: interrupted at omega = .* after 4 points") as info:
        damper_design_curve(blade_pair(), damper(), [5.0, 300.0, 20.0], antiphase(), RANGE, dof=2, harmonics=1)
    assert isinstance(info.value, KeyboardInterrupt)  # a script stops as before
    partial = info.value.partial
    assert list(partial.loads) == [5.0, 300.0] and list(partial.complete) == [True, False]
    assert partial.responses[1].points == 4 and partial.status == ["peak", "incomplete curve"]
    assert partial.optimum == (5.0, partial.peak_amplitude[0])
