"""Stability of harmonic balance solutions (Hill's method): closed form, folds, time integration."""

import sys

import numpy as np
import pytest

from microslip import MicroslipModel
from microslip.frequency import HarmonicBalance, Structure, frequency_response, steady_state
from microslip.frequency.stability import floquet_exponents
from _paths import EXAMPLES

sys.path.insert(0, str(EXAMPLES))
from inclined_block import FORCE, inclined_block  # noqa: E402  (the example is the test case)


def test_a_linear_oscillator_has_its_damped_eigenvalues_as_exponents():
    m, c, k = 1.0, 2.0, 1e4
    s = Structure([[m]], [[c]], [[k]])
    r = frequency_response(s, [1.0], (50, 150), harmonics=2)
    assert r.stable is not None and r.stable.all() and r.bifurcations == []
    hb = HarmonicBalance(s, [1.0], 2)
    exact = -c / (2 * m) + 1j * np.sqrt(k / m - (c / (2 * m)) ** 2)
    for i in (0, r.points // 2, r.points - 1):
        w = r.omega[i]
        lam = floquet_exponents(hb, r.coefficients[i].ravel(), w)
        # Hill's exponents are the eigenvalues modulo i omega (the principal strip |Im| <= omega / 2)
        shifted = exact.imag - w * np.round(exact.imag / w)
        np.testing.assert_allclose(sorted(lam.imag), sorted([shifted, -shifted]), rtol=0, atol=1e-9 * w)
        np.testing.assert_allclose(lam.real, -c / (2 * m), rtol=1e-9)


@pytest.fixture(scope="module")
def fold_curve():
    return frequency_response(inclined_block(), FORCE, (16500, 17500), harmonics=5)


def test_the_branch_past_a_fold_is_unstable(fold_curve):
    r = fold_curve
    turn = int(np.flatnonzero(np.diff(np.sign(np.diff(r.omega))) != 0)[0]) + 1  # first point past the turn
    assert r.stable[:turn - 1].all()  # the branch up to the fold is stable
    assert not r.stable[turn + 1:turn + 10].any()  # the branch that turns back is unstable
    kind, w, _ = r.bifurcations[0]
    assert kind == "fold" and abs(w - r.omega[turn]) < 2 * abs(r.omega[turn] - r.omega[turn - 1])


def test_time_integration_reaches_the_stable_points_and_not_the_unstable_ones(fold_curve):
    r = fold_curve
    unstable = int(np.flatnonzero(~r.stable)[5])
    w = float(r.omega[unstable])
    # at this frequency the curve has three solutions; time integration from rest settles on a stable one
    ti = steady_state(r.structure, FORCE, w, steps_per_period=1024, tolerance=1e-7)
    a_ti = ti.amplitude(0, 1)
    on_curve = np.flatnonzero(np.abs(np.diff(np.sign(r.omega - w))) > 0)  # the crossings of omega = w
    amps = r.amplitude(0, 1)
    crossings = [(amps[i], bool(r.stable[i])) for i in on_curve]
    assert len(crossings) >= 3
    nearest = min(crossings, key=lambda c: abs(c[0] - a_ti))
    assert nearest[1], "time integration settled on an unstable branch"
    # on that branch: H = 5 against the exact steady state, measured 2.9e-3 here (the force has kinks)
    assert abs(nearest[0] / a_ti - 1) < 5e-3
    assert abs(amps[unstable] / a_ti - 1) > 0.02  # and not on the unstable one


def test_stability_is_written_and_drawn(fold_curve, tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    cols = fold_curve.columns()
    np.testing.assert_array_equal(cols["stable [-]"], fold_curve.stable.astype(int))
    ax = fold_curve.plot(0, 1)
    assert any(line.get_linestyle() == "--" for line in ax.get_lines())  # the unstable branch dashed


def test_a_reduced_curve_gets_the_stability_of_the_full_equations(fold_curve):
    exact = frequency_response(inclined_block(), FORCE, (16500, 17500), harmonics=5, reduction="exact")
    assert exact.reduction == "exact" and exact.stable is not None
    turn = int(np.flatnonzero(np.diff(np.sign(np.diff(exact.omega))) != 0)[0]) + 1
    assert exact.stable[:turn - 1].all() and not exact.stable[turn + 1:turn + 10].any()
    assert exact.bifurcations[0][0] == "fold"
    assert exact.bifurcations[0][1] == pytest.approx(fold_curve.bifurcations[0][1], rel=1e-4)


@pytest.fixture(scope="module")
def chain():
    """Six masses in a chain (modes from 10781 to 86844 rad/s), a Jenkins contact at the free end (slip force 1 N,
    forced with 5 N: it slips every cycle)."""
    n = 6
    k = 2e7 * (np.eye(n) * 2 - np.eye(n, k=1) - np.eye(n, k=-1))
    k[-1, -1] = 2e7
    s = Structure(0.01 * np.eye(n), 1e-6 * k, k)
    s.add_contact(MicroslipModel(kt=[1e6], kn=[1e8], gaps=[0.0], mu=1.0), tangential=n - 1, approach=1e-8)
    f = np.zeros(n)
    f[-1] = 5.0
    return s, f


def test_modes_above_the_harmonics_give_no_spurious_instability(chain):
    """At 3000 rad/s with H = 2 every mode lies above (H + 1/2) omega = 7500 rad/s: none has a copy in the strip
    |Im| <= omega / 2 that the harmonics resolve. The eigenvalues nearest that strip are then inaccurate copies at
    the edge of the truncation (one with a real part of +588 1/s here), which must not be taken as exponents."""
    s, f = chain
    r = frequency_response(s, f, (3000, 3100), harmonics=2)
    assert r.contact_dissipation[0, 0] > 0  # the contact slips: the harmonics are coupled, the check is not trivial
    hb = HarmonicBalance(s, f, 2)
    for p in (0, r.points - 1):
        lam = floquet_exponents(hb, r.coefficients[p].ravel(), r.omega[p])
        assert np.all(np.abs(lam.imag) <= r.omega[p] / 2 * (1 + 1e-3))
    assert r.stable.all()
    # time integration from rest settles on this solution: it attracts, so it is stable. Within the H = 2
    # truncation (8.0e-3 measured; H = 3 gives 2.6e-4)
    ti = steady_state(s, f, 3000.0, steps_per_period=512, harmonics=1)
    assert ti.converged
    assert ti.amplitude(5, 1) == pytest.approx(r.amplitude(5, 1)[0], rel=1.5e-2)
