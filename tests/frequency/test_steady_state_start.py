"""Time integration started on a harmonic balance solution: ``steady_state(..., start=...)``."""

import numpy as np
import pytest

from microslip import MicroslipModel
from microslip.frequency import Structure, frequency_point, frequency_response, steady_state

OMEGA = 130.0  # rad/s, below the stuck resonance sqrt(2e4) = 141 rad/s (damping 0.7 %)


def oscillator(mu: float) -> Structure:
    """1 kg on 1e4 N/m with a Jenkins contact of 1e4 N/m at 1 N normal load: slips at mu N."""
    s = Structure(M=[[1.0]], C=[[2.0]], K=[[1e4]])
    s.add_contact(MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=mu), tangential=0, approach=1e-6)
    return s


def test_started_on_the_solution_it_is_there_after_two_periods():
    """A contact that never slips (mu N = 1000 N): linear, so one harmonic is the exact solution.

    From it, two periods of 1024 steps stay within the scheme's error of it (measured 4.7e-6, on
    the way to the scheme's own periodic solution 1.7e-5 away: central differences shift the
    resonance by (omega dt)^2 / 24, amplified near it; 1.1e-6 at 4096 steps, like dt^2); from
    rest the start-up transient still changes the first harmonic by 30 %.
    """
    s = oscillator(1e3)
    hb = frequency_point(s, [0.8], OMEGA, harmonics=1)
    on = steady_state(s, [0.8], OMEGA, steps_per_period=1024, harmonics=1, max_periods=2, start=hb)
    rest = steady_state(s, [0.8], OMEGA, steps_per_period=1024, harmonics=1, max_periods=2)
    a = hb.amplitude(0, 1)[0]
    assert on.amplitude(0, 1) == pytest.approx(a, rel=2.5e-5)
    assert abs(rest.amplitude(0, 1) / a - 1) > 0.2
    np.testing.assert_allclose(on.q[-1], hb.time_history(0, 0, samples=1024)[1][0], rtol=2.5e-5)  # at tau = 0 again


def test_an_element_that_slips_every_cycle_forgets_where_it_started():
    """mu N = 1 N, slipping every cycle: both starts reach one steady state (measured 4e-10 apart).

    Harmonic balance (H = 15, 1024 samples) is 6.0e-6 from it: the time step's error at 1024
    steps (about 7e-6: the difference falls to 1e-6 at 4096 steps) plus the truncation.
    """
    s = oscillator(1.0)
    hb = frequency_point(s, [0.8], OMEGA, harmonics=15, samples=1024)
    on = steady_state(s, [0.8], OMEGA, steps_per_period=1024, harmonics=1, tolerance=1e-9, start=hb)
    rest = steady_state(s, [0.8], OMEGA, steps_per_period=1024, harmonics=1, tolerance=1e-9)
    assert on.converged and rest.converged and on.periods < rest.periods
    assert on.amplitude(0, 1) == pytest.approx(rest.amplitude(0, 1), rel=1e-8)
    assert hb.amplitude(0, 1)[0] == pytest.approx(on.amplitude(0, 1), rel=1.5e-5)


def test_a_reduced_solution_is_recovered_to_every_dof():
    """A solution with reduction='exact' keeps only the contact and excitation DOFs: the start recovers the rest."""
    M = np.diag([1.0, 0.5, 0.5])
    K = np.array([[3e4, -1e4, -1e4], [-1e4, 2e4, -1e4], [-1e4, -1e4, 2e4]])
    s = Structure(M, 1e-4 * K, K)
    s.add_contact(MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0), tangential=0, approach=1e-6)
    reduced = frequency_point(s, [0.8, 0.0, 0.0], 150.0, harmonics=3, reduction="exact")
    full = frequency_point(s, [0.8, 0.0, 0.0], 150.0, harmonics=3, reduction="none")
    assert reduced.dofs.tolist() == [0]
    a = steady_state(s, [0.8, 0.0, 0.0], 150.0, steps_per_period=256, harmonics=3, max_periods=1, start=reduced)
    b = steady_state(s, [0.8, 0.0, 0.0], 150.0, steps_per_period=256, harmonics=3, max_periods=1, start=full)
    # the two solutions agree to Newton's tolerance (1e-9), and so do the periods integrated from them
    np.testing.assert_allclose(a.q, b.q, rtol=0, atol=1e-7 * np.max(np.abs(b.q)))


@pytest.mark.parametrize("start, error, message", [
    ("abc", TypeError, "start must be None or a FrequencyResponse \\(from frequency_point\\), got str"),
    (lambda: frequency_response(oscillator(1.0), [0.8], (120.0, 130.0), harmonics=1), ValueError,
     r"start must be a solution at one frequency \(frequency_point\), got a curve of \d+ points"),
    (lambda: frequency_point(Structure(np.eye(2), None, np.eye(2) * 1e4), [1.0, 0.0], 50.0, harmonics=1),
     ValueError, "start must be a solution of a structure with the same 1 DOFs, got one with 2"),
])
def test_start_is_checked(start, error, message):
    start = start() if callable(start) else start
    with pytest.raises(error, match=message):
        steady_state(oscillator(1.0), [0.8], OMEGA, steps_per_period=64, harmonics=1, start=start)
