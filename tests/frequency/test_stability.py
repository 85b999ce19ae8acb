"""Stability by Hill's method: linear closed forms, the strip of exponents, reductions, a fold against time
integration and shooting, the result object and the frf report."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot  # noqa: E402  (after the backend)

import sys

import numpy as np
import pytest

from microslip import MicroslipModel
from microslip.kernels.element import NO_CONDITIONS, NO_ELEMENTS, NO_WORK, march
from microslip.frequency import (HarmonicBalance, Structure, frequency_point, frequency_response, steady_state,
                                 time_samples)
from microslip.frequency.analyses.response import _equations
from microslip.frequency.analyses.stability import Bifurcation, floquet_exponents
from microslip.frequency.analyses.transient import PeriodMap

from _paths import EXAMPLES

sys.path.insert(0, str(EXAMPLES))
from inclined_block import FORCE, inclined_block  # noqa: E402  (the example is the test case)


def multipliers(exponents, omega):
    """Floquet multipliers ``exp(lambda T)``: exponents are defined modulo ``i omega``, multipliers are not."""
    return np.exp(np.asarray(exponents) * 2 * np.pi / omega)


def matched(a, b):
    """Largest distance from a multiplier of ``a`` to the nearest one of ``b`` (and back)."""
    d = np.abs(np.asarray(a)[:, None] - np.asarray(b)[None, :])
    return max(d.min(axis=1).max(), d.min(axis=0).max())


def damped_eigenvalues(M, C, K):
    """The eigenvalues of ``M q'' + C q' + K q = 0`` (1/s)."""
    n = K.shape[0]
    return np.linalg.eigvals(np.block([[np.zeros((n, n)), np.eye(n)],
                                       [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]]))


# -- linear structures: Hill's exponents are the damped eigenvalues ------------------------------------

def test_one_dof_exponents_are_the_damped_eigenvalues():
    m, c, k = 1.0, 2.0, 1e4
    s = Structure([[m]], [[c]], [[k]])
    w0, zeta = np.sqrt(k / m), c / (2 * np.sqrt(k * m))
    exact = -zeta * w0 + 1j * w0 * np.sqrt(1 - zeta**2) * np.array([1, -1])
    r = frequency_response(s, [1.0], (30, 260), harmonics=3)
    assert r.stable.all() and r.bifurcations == []
    hb = HarmonicBalance(s, [1.0], 3)
    for p in range(0, r.points, 7):
        w = r.omega[p]
        lam = floquet_exponents(hb, r.coefficients[p].ravel(), w)
        # the real parts exactly, the imaginary parts modulo omega (the copy nearest the real axis is kept)
        np.testing.assert_allclose(np.sort(lam.real), [-zeta * w0] * 2, rtol=1e-9)
        assert np.all(np.abs(lam.imag) <= w / 2 * (1 + 1e-12))
        assert matched(multipliers(lam, w), multipliers(exact, w)) < 1e-9
        assert r.leading_exponent[p].real == pytest.approx(-zeta * w0, rel=1e-9)


def test_stuck_contact_exponents_are_those_of_the_stuck_structure():
    """Two DOFs and a contact that never slips: a linear structure with the contact's stiffness added."""
    jenkins = MicroslipModel(kt=[5e3], kn=[1e6], gaps=[0.0], mu=1.0)
    s = Structure(np.diag([1.0, 0.5]), [[1.0, -0.5], [-0.5, 0.5]], [[2e4, -1e4], [-1e4, 1e4]])
    s.add_contact(jenkins, tangential={0: 1.0, 1: -1.0}, approach=1e-3)  # slip force 1000 N, far above
    r = frequency_point(s, [1.0, 0.0], 150.0, harmonics=3)
    assert r.stable.tolist() == [True]
    exact = damped_eigenvalues(s.M, s.C, s.stuck_stiffness())
    lam = floquet_exponents(HarmonicBalance(s, [1.0, 0.0], 3), r.coefficients[0].ravel(), 150.0)
    assert lam.size == 4
    assert matched(multipliers(lam, 150.0), multipliers(exact, 150.0)) < 1e-9


# -- the strip |Im| <= omega / 2 and the reductions ------------------------------------------------------

@pytest.fixture(scope="module")
def chain():
    """Six masses in a chain (modes from 10781 to 86844 rad/s), a Jenkins contact at the free end (slip force 1 N,
    forced with 5 N: it slips every cycle); interior DOFs to condense."""
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


@pytest.mark.parametrize("reduction, modes, tolerance", [
    ("exact", None, 1e-9),  # the same equations: identical to solver tolerance
    # 5 of 6 modes: the omitted one (~88000 rad/s) enters quasi-statically, a relative error of
    # (2 x 8000 / 88000)^2 ~ 3e-2 on its own contribution, itself ~1e-3 of the end's flexibility; measured: the
    # multipliers move by 2.5e-7
    ("modal", 5, 1e-5),
])
@pytest.mark.parametrize("dense_limit", [None, 10])  # 10: the reduced problem by shift-invert Arnoldi, sparse
def test_reduced_equations_give_the_exponents_of_the_whole_structure(chain, reduction, modes, tolerance,
                                                                    dense_limit, monkeypatch):
    import microslip.frequency.analyses.stability as stability

    s, f = chain
    w = 8000.0  # the first mode (10781 rad/s) is within the strip of the kept harmonics (below 2.5 omega)
    full = frequency_point(s, f, w, harmonics=2, reduction="none")
    _, hb_full, _ = _equations(s, f, 2, None, 1000, "none", None)
    a = floquet_exponents(hb_full, full.coefficients[0].ravel(), w)  # every eigenvalue, dense
    if dense_limit is not None:
        monkeypatch.setattr(stability, "DENSE_LIMIT", dense_limit)
    reduced = frequency_point(s, f, w, harmonics=2, reduction=reduction, modes=modes)
    _, hb_red, _ = _equations(s, f, 2, None, 1000, reduction, modes)
    b = floquet_exponents(hb_red, reduced.coefficients[0].ravel(), w)
    assert reduced.stable.tolist() == full.stable.tolist() == [True]
    # the contact slips: its exponents are not the linear chain's (the check would pass trivially if stuck)
    assert full.contact_dissipation[0, 0] > 0
    assert a.size == b.size >= 2
    assert matched(multipliers(a, w), multipliers(b, w)) < tolerance


def fe_blade(force: float):
    """The scikit-fem blade of about 400 DOFs, a Jenkins contact (x tangential, y normal, 50 N preload) at
    each of its two contact nodes under the platform, ``force`` (N) along x at the tip."""
    from microslip.fe import blade

    b = blade(300, contact_nodes=1)
    s = Structure(b.M, 2e-7 * b.K, b.K, dof_map=b.dof_map)
    for node in b.platform_nodes:
        s.add_contact(MicroslipModel(kt=[2e6], kn=[2e8], gaps=[0.0], mu=0.1), tangential={f"{node}:x": 1.0},
                      normal={f"{node}:y": 1.0}, preload=50.0)
    return s, s.force_vector({f"{b.tip_node}:x": force})


def test_a_finite_element_model_gets_the_same_exponents_from_every_reduction():
    """384 DOFs, H = 3: Hill problems of 2688 unknowns (every DOF, or the whole structure behind an exact
    reduction), solved by sparse shift-invert Arnoldi, and of 140 (a modal reduction with 20 modes)."""
    from microslip.frequency.analyses.stability import one_blas_thread

    s, f = fe_blade(12.0)
    w = 9800.0  # below the first resonance of the blade held by its stuck contacts
    # one BLAS thread for the solves as well as the eigenvalues: on a loaded 2-core machine OpenBLAS's threads
    # make the small dense algebra of the reductions 5-40 times slower (9 s instead of 1.5 s); nothing else changes
    with one_blas_thread():
        none, exact, modal = (frequency_point(s, f, w, harmonics=3, reduction=r, modes=m)
                              for r, m in (("none", None), ("exact", None), ("modal", 20)))
    assert none.contact_dissipation[0].min() > 0  # both contacts slip
    assert none.stable.tolist() == exact.stable.tolist() == modal.stable.tolist() == [True]
    # the same eigenvalues, assembled two ways (the whole Jacobian; the structure's plus the reduced contact
    # Jacobian at the retained DOFs): agreement to the Arnoldi tolerance
    assert exact.leading_exponent[0] == pytest.approx(none.leading_exponent[0], rel=1e-8)
    # the modal model leaves out the damping of the omitted modes (their residual flexibility is static): the
    # real part moves by 0.15 1/s of -94 (measured), 1e-4 in the multipliers
    assert matched(multipliers(modal.leading_exponent, w), multipliers(exact.leading_exponent, w)) < 5e-4
    assert modal.leading_exponent[0].real == pytest.approx(exact.leading_exponent[0].real, rel=5e-3)


@pytest.mark.parametrize("w", [9000.0, 9800.0])
def test_a_large_exact_reduction_gets_its_exponents_from_a_modal_model_of_the_structure(w, monkeypatch):
    """Above WHOLE_LIMIT unknowns an exact reduction's Hill problem is that of a 60-mode modal model (the
    whole one costs a sparse factorisation per point); here the limit is lowered so both can be compared."""
    from microslip.frequency.analyses import stability

    s, f = fe_blade(12.0)
    with stability.one_blas_thread():
        whole = frequency_point(s, f, w, harmonics=3, reduction="exact")
        monkeypatch.setattr(stability, "WHOLE_LIMIT", 0)
        modal = frequency_point(s, f, w, harmonics=3, reduction="exact")
    assert whole.stable.tolist() == modal.stable.tolist() == [True]
    # measured 1.14e-5 and 1.08e-5 of omega: the real part moves by 0.1 1/s of -196 and -94, the damping of
    # the omitted modes, which the modal model leaves out
    assert abs(modal.leading_exponent[0] - whole.leading_exponent[0]) < 2e-5 * w
    assert modal.leading_exponent[0] != whole.leading_exponent[0]  # the modal model was used


def test_a_singular_hill_problem_is_solved_off_its_singular_point(monkeypatch):
    """An undamped oscillator whose natural frequency is twice the excitation's: the second harmonic's block of
    ``J0`` is exactly zero (a pair of exponents at 0, as at a fold), so shift-invert at 0 has no factorisation."""
    import scipy.sparse as sp

    import microslip.frequency.analyses.stability as stability
    from microslip.frequency.equations.hbm import harmonic_operators

    w, H = 100.0, 3
    D, W = harmonic_operators(H)
    I = np.eye(2 * H + 1)
    J0 = 4 * w**2 * I - w**2 * W  # K = (2 omega)^2, M = 1, C = 0
    assert np.linalg.matrix_rank(J0) == 2 * H + 1 - 2
    monkeypatch.setattr(stability, "DENSE_LIMIT", 0)
    for matrix in (J0, sp.csc_matrix(J0)):
        lam = stability.HillProblem(matrix, 2 * w * D, I, 1, w).exponents()
        # the exponents of +-2i omega, shifted by -+2i omega: both at 0 (to the Arnoldi tolerance)
        np.testing.assert_allclose(lam, [0.0, 0.0], atol=1e-6 * w)


# -- a fold: stability against time integration and shooting ---------------------------------------------

@pytest.fixture(scope="module")
def fold_curve():
    """The inclined block's second mode bends back on itself (the contact's normal load varies along the cycle).

    512 AFT samples: the kinks of the contact force are located to 1/512 of a period, which the leading
    multiplier needs to agree with shooting to 1e-2 (at 128 samples it moves by up to 1.7e-2).
    """
    return frequency_response(inclined_block(), FORCE, (16500, 17500), harmonics=5, samples=512)


def test_points_between_the_two_folds_are_unstable(fold_curve):
    r = fold_curve
    assert [b.kind for b in r.bifurcations] == ["fold", "fold"]
    first, second = r.bifurcations
    index = np.arange(r.points)
    np.testing.assert_array_equal(r.stable, (index < first.point) | (index > second.point))
    assert (~r.stable).sum() >= 10
    # each fold is where the curve turns back: within one step of the extreme frequency around it
    for fold, extreme in ((first, np.max), (second, np.min)):
        near = slice(int(fold.point) - 3, int(fold.point) + 5)
        step = np.max(np.abs(np.diff(r.omega[near])))
        assert abs(fold.omega - extreme(r.omega[near])) <= step
    # between them three solutions coexist at one frequency
    w = 0.5 * (first.omega + second.omega)
    assert np.count_nonzero(np.diff(np.sign(r.omega - w))) == 3


def hb_state(scheme, coefficients):
    """``[q_prev, q, sliders]`` of a harmonic balance solution at time 0 for the explicit scheme.

    The sliders come from marching the contact along the solution's displacement history (three periods
    after the static step from the virgin state, as the AFT does), so that they are periodic.
    """
    q = time_samples(coefficients.T, scheme.steps).T  # (steps, ndof) at tau_k = 2 pi k / steps
    kt, kn, gaps, offsets, mu = scheme.packed
    sliders = np.zeros(kt.size)
    for i in range(len(scheme.structure.contacts)):
        lo, hi = offsets[i], offsets[i + 1]
        t = q @ scheme.Bt[:, i]
        n = q @ scheme.Bn[:, i] + scheme.n0[i]
        path_t = np.concatenate([[coefficients[0] @ scheme.Bt[:, i]], np.tile(np.roll(t, -1), 3)])
        path_n = np.concatenate([[coefficients[0] @ scheme.Bn[:, i] + scheme.n0[i]], np.tile(np.roll(n, -1), 3)])
        march(kt[lo:hi], kn[lo:hi], gaps[lo:hi], mu[i], path_t, path_n, sliders[lo:hi], np.empty(path_t.size),
              np.empty(path_t.size), NO_WORK, NO_ELEMENTS, NO_CONDITIONS)
    return np.concatenate([q[-1], q[0], sliders])


def shooting(scheme, z, scale, iterations=8):
    """The periodic orbit of the one-period map near ``z`` and its monodromy matrix (central differences).

    Newton's method on ``P(z) - z = 0``; least squares because sliders of elements that never slip are
    neutral (multiplier 1: any of their positions is periodic).
    """
    h = 1e-7 * scale  # the map is piecewise linear; central differences are exact while no event moves

    def monodromy(z):
        J = np.empty((z.size, z.size))
        for j in range(z.size):
            e = np.zeros(z.size)
            e[j] = h
            J[:, j] = (scheme.period(z + e) - scheme.period(z - e)) / (2 * h)
        return J

    for _ in range(iterations):
        r = scheme.period(z) - z
        if np.max(np.abs(r)) < 1e-12 * scale:
            break
        z = z + np.linalg.lstsq(monodromy(z) - np.eye(z.size), -r, rcond=1e-10)[0]
    assert np.max(np.abs(scheme.period(z) - z)) < 1e-10 * scale
    return z, monodromy(z)


@pytest.fixture(scope="module")
def checked_points(fold_curve):
    """Upper branch, the middle of the unstable branch, lower branch (all near 17000 rad/s), and one far off."""
    r = fold_curve
    first, second = (int(b.point) for b in r.bifurcations)
    return r, [first - 6, (first + second) // 2, second + 8, r.points - 3]


def test_stability_agrees_with_floquet_multipliers_from_shooting(checked_points):
    r, points = checked_points
    verdicts = []
    for p in points:
        w = r.omega[p]
        scheme = PeriodMap(r.structure, FORCE, w, 1024)
        scale = np.max(np.abs(r.coefficients[p, 1:]))
        z, J = shooting(scheme, hb_state(scheme, r.coefficients[p]), scale)
        # the shooting orbit is the harmonic balance solution (to its truncation and sampling errors)
        q0 = r.coefficients[p].sum(axis=0) - r.coefficients[p, 2::2].sum(axis=0)  # c0 + sum a_h: time 0
        assert np.max(np.abs(z[2:4] - q0)) < 0.01 * scale
        shoot = np.linalg.eigvals(J)
        shoot = shoot[np.abs(shoot - 1) > 1e-7]  # neutral sliders of elements that never slip
        shoot = shoot[np.argsort(-np.abs(shoot))]
        hill = multipliers(r.leading_exponent[p], w)
        verdicts.append((bool(r.stable[p]), bool(np.abs(shoot[0]) < 1)))
        # the leading multipliers: Hill's linearises the friction forces for periodic perturbations and samples
        # them at 512 points, shooting marches 1024 steps, so the kinks of the force fall up to 1/512 of a period
        # apart; measured apart by at most 1.8e-3 at these points (1.7e-2 with 128 samples), and every tested
        # one is at least 0.02 from the unit circle, so a 1e-2 tolerance decides the verdict unambiguously
        assert abs(abs(shoot[0]) - 1) > 0.02
        assert np.min(np.abs(shoot - hill)) < 0.01, (w, shoot[:3], hill)
        assert abs(abs(shoot[0]) - abs(hill)) < 0.01
    assert [v[0] for v in verdicts] == [True, False, True, True]
    assert all(hb == shoot for hb, shoot in verdicts)


def test_time_integration_stays_near_stable_points_and_leaves_unstable_ones(checked_points):
    r, points = checked_points
    for p in points:
        w = r.omega[p]
        scheme = PeriodMap(r.structure, FORCE, w, 1024)
        scale = np.max(np.abs(r.coefficients[p, 1:]))
        z = hb_state(scheme, r.coefficients[p])
        z[:4] += 1e-3 * scale * np.array([1.0, -0.5, 1.0, -0.5])  # a small kick on top of the truncation error
        q_prev, q, sliders = z[:2].copy(), z[2:4].copy(), z[4:].copy()
        out = np.empty((scheme.steps, 2))
        for _ in range(300):  # the leading multipliers are 0.97 and 1.04: e^-9 and e^+12 over 300 periods
            scheme.integrate(q_prev, q, sliders, out)
        phase = 2 * np.pi * (np.arange(scheme.steps) + 1) / scheme.steps
        a1 = np.hypot(*(2 / scheme.steps * np.array([np.cos(phase), np.sin(phase)]) @ out[:, 0]))
        change = abs(a1 / r.amplitude(0, 1)[p] - 1)
        if r.stable[p]:
            assert change < 0.01, (w, change)  # back on the solution (harmonic balance vs time: ~1e-3)
        else:
            assert change > 0.1, (w, change)  # gone to the upper or the lower branch


def test_time_integration_from_rest_settles_on_a_stable_branch(fold_curve):
    r = fold_curve
    unstable = int(np.flatnonzero(~r.stable)[5])
    w = float(r.omega[unstable])
    # at this frequency the curve has three solutions; time integration from rest settles on a stable one
    ti = steady_state(r.structure, FORCE, w, steps_per_period=1024, tolerance=1e-7)
    a_ti = ti.amplitude(0, 1)
    on_curve = np.flatnonzero(np.abs(np.diff(np.sign(r.omega - w))) > 0)  # the crossings of omega = w
    amps = r.amplitude(0, 1)
    # the amplitude where the curve crosses omega = w, between two points (linearly), and its stability there
    f = [(w - r.omega[i]) / (r.omega[i + 1] - r.omega[i]) for i in on_curve]
    crossings = [(amps[i] + t * (amps[i + 1] - amps[i]), bool(r.stable[i] and r.stable[i + 1]))
                 for i, t in zip(on_curve, f)]
    assert len(crossings) >= 3
    nearest = min(crossings, key=lambda c: abs(c[0] - a_ti))
    assert nearest[1], "time integration settled on an unstable branch"
    # on that branch: H = 5 and 512 samples against the steady state of 1024 steps, measured 7.4e-4 here (2.9e-3
    # with 128 samples: the force has kinks, which the samples locate)
    assert abs(nearest[0] / a_ti - 1) < 3e-3
    assert abs(amps[unstable] / a_ti - 1) > 0.02  # and not on the unstable one


def test_a_reduced_curve_has_the_folds_of_the_full_one(fold_curve):
    exact = frequency_response(inclined_block(), FORCE, (16500, 17500), harmonics=5, samples=512,
                               reduction="exact")
    assert exact.reduction == "exact"
    assert [b.kind for b in exact.bifurcations] == ["fold", "fold"]
    for a, b in zip(exact.bifurcations, fold_curve.bifurcations):
        assert a.omega == pytest.approx(b.omega, rel=1e-4)  # the same equations; the points may differ a little


# -- the eigensolvers ------------------------------------------------------------------------------------

def test_iterative_and_sparse_eigensolvers_agree_with_the_dense_one(fold_curve, monkeypatch):
    import scipy.sparse as sp

    import microslip.frequency.analyses.stability as stability

    r = fold_curve
    p = int(r.bifurcations[0].point) + 5  # an unstable point: a real exponent > 0
    hb = HarmonicBalance(inclined_block(), FORCE, 5, samples=512)
    x = r.coefficients[p].ravel()
    dense = floquet_exponents(hb, x, r.omega[p])
    sparse_hb = HarmonicBalance(inclined_block(sparse=True), FORCE, 5, samples=512)
    sparse_hb.dense = False  # the SciPy path with sparse Jacobians, as for a large structure
    sparse_hb.Kx, sparse_hb.Cx, sparse_hb.Mx = (sp.csc_matrix(A) for A in (hb.Kx, hb.Cx, hb.Mx))
    monkeypatch.setattr(stability, "DENSE_LIMIT", 10)  # 22 unknowns: shift-invert Arnoldi
    for other in (floquet_exponents(hb, x, r.omega[p]), floquet_exponents(sparse_hb, x, r.omega[p])):
        assert dense[0].real > 0 and other.size == dense.size
        # the same eigenvalues from two solvers: agreement to the Arnoldi tolerance (1e-10) times the scale
        assert matched(other, dense) < 1e-6 * r.omega[p]


# -- the result object, plot, CSV, checks ----------------------------------------------------------------

def test_unstable_stretches_are_dashed_and_flagged_in_the_csv(fold_curve, tmp_path):
    r = fold_curve
    ax = r.plot(0, 1, label="x")
    lines = ax.get_lines()
    assert [line.get_linestyle() for line in lines] == ["-", "--"]
    assert lines[0].get_color() == lines[1].get_color()
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["x"]
    solid, dashed = (np.isfinite(line.get_ydata()) for line in lines)
    np.testing.assert_array_equal(solid, r.stable)
    assert dashed[~r.stable].all()  # every unstable point dashed (and the stable ends of the dashed stretch)
    matplotlib.pyplot.close(ax.figure)
    cols = r.columns()
    np.testing.assert_array_equal(cols["stable [-]"], r.stable.astype(int))
    assert np.all((cols["growth rate [1/s]"] > 0) == ~r.stable)
    data = np.genfromtxt(r.to_csv(tmp_path / "c.csv"), delimiter=",", names=True)
    np.testing.assert_array_equal(data["stable_"], r.stable.astype(int))
    np.testing.assert_allclose(data["growth_rate_1s"], r.leading_exponent.real, rtol=1e-6)


def test_stability_can_be_switched_off_and_is_checked():
    s = Structure([[1.0]], [[2.0]], [[1e4]])
    r = frequency_response(s, [1.0], (50, 150), harmonics=2, stability=False)
    assert r.stable is None and r.leading_exponent is None and r.bifurcations == []
    assert "stable [-]" not in r.columns()
    ax = r.plot(0)
    assert [line.get_linestyle() for line in ax.get_lines()] == ["-"]
    matplotlib.pyplot.close(ax.figure)
    for call in (lambda: frequency_response(s, [1.0], (50, 150), stability="yes"),
                 lambda: frequency_point(s, [1.0], 100.0, stability=1)):
        with pytest.raises(TypeError, match="stability must be True or False, got"):
            call()


def test_bifurcation_interpolation():
    b = Bifurcation("fold", 10.0, 1.25)
    assert b.interpolate([0.0, 4.0, 8.0]) == pytest.approx(5.0)


def test_a_hill_problem_too_large_is_not_assessed(chain, monkeypatch):
    import microslip.frequency.analyses.stability as stability

    s, f = chain
    monkeypatch.setattr(stability, "HILL_LIMIT", 10)  # the whole chain's Hill problem has 6 x 5 = 30 unknowns
    r = frequency_point(s, f, 8000.0, harmonics=2, reduction="exact")
    assert r.stable is None and r.leading_exponent is None
    assert "stable [-]" not in r.columns()


def test_frf_report_lists_unstable_stretches_and_folds(tmp_path, capsys):
    import shutil

    from microslip.cli import main

    shutil.copy(EXAMPLES / "sphere_4_elements.json", tmp_path / "sphere_4_elements.json")
    text = (EXAMPLES / "inclined_block.toml").read_text()
    assert "omega = [12000, 18000]" in text and "harmonics = 7" in text and "samples = 256" in text
    (tmp_path / "b.toml").write_text(text.replace("omega = [12000, 18000]", "omega = [16500, 17500]")
                                     .replace("harmonics = 7", "harmonics = 5").replace("samples = 256", "samples = 512"))
    assert main(["frf", str(tmp_path / "b.toml"), "--out", str(tmp_path / "out"), "--quiet"]) == 0
    report = (tmp_path / "out" / "report.md").read_text()
    # the two folds of the fold_curve fixture (the same configuration): 17070 and 16893 rad/s, 2716.8 and 2688.6 Hz
    # (the report's unit)
    assert "points are unstable (dashed in the plot), from 2688" in report and "The curve has 2 folds." in report
    assert "| fold | 1707" in report and "| fold | 1689" in report
    assert "points are unstable" in capsys.readouterr().out
    data = np.genfromtxt(tmp_path / "out" / "frf.csv", delimiter=",", names=True)
    assert 0 < data["stable_"].sum() < data.size
