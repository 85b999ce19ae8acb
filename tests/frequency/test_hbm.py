"""Harmonic balance: exact Jacobian, closed forms, time integration, energy balance, the result object."""

import matplotlib

matplotlib.use("Agg")

import re
import sys
import warnings

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.optimize import brentq

from microslip import MicroslipModel, Sphere, tune
from microslip.frequency import (FrequencyResponse, HarmonicBalance, Structure, frequency_point,
                                 frequency_response, static_solution)
from microslip.frequency import UnderResolvedWarning, time_samples
from microslip.kernels import transient as _transient

from _paths import EXAMPLES

sys.path.insert(0, str(EXAMPLES))
from inclined_block import FORCE, compare, inclined_block, truncation  # noqa: E402  (the example is the test case)

JENKINS = MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0)  # slip force 1 N at an approach of 1 µm


def jenkins_oscillator(C=1.0):
    """The speed benchmark's 1-DOF oscillator: m = 1 kg, k = 1e4 N/m, c = 1 N s/m, Jenkins kt = 1e4 N/m, 1 N."""
    s = Structure(M=[[1.0]], C=[[C]], K=[[1e4]])
    s.add_contact(JENKINS, tangential=0, approach=1e-6)
    return s


@pytest.fixture(scope="module")
def inclined_curve():
    return frequency_response(inclined_block(), FORCE, (12000, 16500), harmonics=7)


# -- equations -----------------------------------------------------------------------------------

def test_compiled_residual_matches_numpy_twin_and_sparse_path():
    rng = np.random.default_rng(0)
    dense = HarmonicBalance(inclined_block(), FORCE, 3, samples=32)
    sparse = HarmonicBalance(inclined_block(sparse=True), FORCE, 3, samples=32)
    sparse.dense = False  # force the SciPy path even for this small problem
    sparse.Kx, sparse.Cx, sparse.Mx = (sp.csc_matrix(A) for A in (dense.Kx, dense.Cx, dense.Mx))
    x = rng.normal(size=dense.n) * 2e-7
    x[1] -= 2e-6  # closed on average
    R, J, Rw = dense.evaluate(x, 14000.0)
    for other in (dense.evaluate_reference(x, 14000.0), sparse.evaluate(x, 14000.0)):
        np.testing.assert_allclose(R, other[0], atol=1e-9)
        np.testing.assert_allclose(J, other[1].toarray() if sp.issparse(other[1]) else other[1], atol=1e-3)
        np.testing.assert_allclose(Rw, other[2], atol=1e-12)


def test_harmonic_balance_jacobian_matches_finite_differences():
    hb = HarmonicBalance(inclined_block(), FORCE, 3, samples=64)
    x = np.random.default_rng(1).normal(size=hb.n) * 3e-7
    x[1] -= 2e-6
    R, J, Rw = hb.evaluate(x, 15000.0)
    h = 1e-14
    fd = np.array([(hb.evaluate(x + h * e, 15000.0, jacobian=False) - hb.evaluate(x - h * e, 15000.0, jacobian=False))
                   / (2 * h) for e in np.eye(hb.n)]).T
    # stiffnesses ~1e7 N/m, central differences of ~10 N forces at h = 1e-14 m: ~1e-1 N/m noise
    np.testing.assert_allclose(J, fd, atol=1e-6 * 3e7)
    dw = 1e-3
    fdw = (hb.evaluate(x, 15000.0 + dw, jacobian=False) - hb.evaluate(x, 15000.0 - dw, jacobian=False)) / (2 * dw)
    np.testing.assert_allclose(Rw, fdw, rtol=1e-6, atol=1e-12)


# -- validation (a): Jenkins element against its describing function ------------------------------

def _describing_function_amplitudes(omega, F=2.0, m=1.0, k=1e4, c=1.0, kt=1e4, Fs=1.0):
    """Every amplitude A with |(k - m w^2 + i c w) A + k_DF(A) A| = F (single-harmonic balance)."""
    def k_df(A):
        if A <= Fs / kt:
            return kt
        beta = np.arccos(1 - 2 * Fs / (kt * A))
        a = kt / np.pi * (beta - np.sin(2 * beta) / 2)
        b = -4 * Fs / (np.pi * A) * (1 - Fs / (kt * A))
        return a - 1j * b

    g = lambda A: abs(k - m * omega**2 + 1j * c * omega + k_df(A)) * A - F  # noqa: E731
    grid = np.geomspace(1e-6, 1e-1, 4000)
    vals = np.array([g(A) for A in grid])
    return [brentq(g, grid[i], grid[i + 1], xtol=1e-16, rtol=1e-14)
            for i in np.flatnonzero(np.sign(vals[:-1]) != np.sign(vals[1:]))]


def test_single_harmonic_balance_matches_jenkins_describing_function():
    r = frequency_response(jenkins_oscillator(), [2.0], (60, 160), harmonics=1, samples=4096)
    amp = r.amplitude(0, 1)
    for k in range(0, r.points, max(1, r.points // 12)):
        roots = _describing_function_amplitudes(r.omega[k])
        err = min(abs(amp[k] - A) / A for A in roots)
        # 4096 samples: the AFT first harmonic is within ~1e-6 of the closed form (test_aft);
        # near the peak the amplitude is ~50 times more sensitive than the force
        assert err < 1e-4, (r.omega[k], amp[k], roots)


# -- validation (b): harmonic balance against time integration --------------------------------------

def test_harmonic_balance_matches_time_integration(inclined_curve):
    r = inclined_curve
    assert np.all(np.diff(r.omega) > 0)  # single-valued on this range: one steady state per frequency
    w_peak, _ = r.peak(0, 1)
    rows = compare(r, [12500.0, 14500.0, w_peak, 15900.0, 16400.0])
    for w, hb, ti, diff in rows:
        # measured up to 1.3e-4 (python examples/inclined_block.py); twice that allows for the explicit
        # integration's own error (2048 steps per period, steady to 1e-8), which is not zero
        assert abs(diff) < 2.6e-4, (w, hb, ti)
    # the peak of the curve is the peak of the steady states (not a point picked off the curve)
    assert rows[2][2] > max(rows[1][2], rows[3][2])


def test_truncation_error_falls_as_harmonics_grow(inclined_curve):
    w_peak, _ = inclined_curve.peak(0, 1)
    errors = dict(truncation(inclined_curve.structure, w_peak, harmonics=(1, 3, 7, 11)))
    errors = {H: abs(e) for H, e in errors.items()}
    assert errors[1] > errors[7] and errors[3] > errors[11]
    # measured at the peak (python examples/inclined_block.py): 9.0e-5 (H = 7) and 1.1e-5 (H = 11), about twice
    # allowed for the time integration's own error
    assert errors[7] < 2e-4 and errors[11] < 2.5e-5


def test_time_integration_kernel_matches_twin():
    s = inclined_block()
    model = s.contacts[0].model
    M, C, K = s.M, s.C, s.K
    dt = 2e-6
    A_inv = np.linalg.inv(M / dt**2 + C / (2 * dt))
    B1, B0 = 2 * M / dt**2, M / dt**2 - C / (2 * dt)
    Bt = s.contacts[0].tangential[:, None]
    Bn = s.contacts[0].normal[:, None]
    tau = np.arange(50) / 50 * 2 * np.pi
    force = np.outer(np.cos(tau), [20.0, 0.0]) + 37.5 * Bn[:, 0]
    q0 = np.array([-1e-6, 2e-6])
    out = np.empty((120, 2))
    q_prev, q, sl = q0.copy(), q0.copy(), np.zeros(4)
    _transient.integrate(A_inv, K, B1, B0, force, Bt, Bn, np.zeros(1), model.kt, model.kn, model.gaps,
                         np.array([0, 4]), np.array([model.mu]), sl, q_prev, q, 120, out)
    ref, _, q_ref, sl_ref = _transient.integrate_reference(A_inv, K, B1, B0, force, Bt, Bn, np.zeros(1), [model],
                                                           [np.zeros(4)], q0, q0, 120)
    np.testing.assert_allclose(out, ref, rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(sl, sl_ref[0], rtol=1e-9, atol=1e-15)


# -- validation (c): energy balance -----------------------------------------------------------------

def test_energy_balance_per_cycle(inclined_curve):
    r = inclined_curve
    balance = r.excitation_work - r.viscous_dissipation - r.contact_harmonic_work.sum(axis=1)
    # exact for the harmonics kept; Newton stops at a relative residual of 1e-9
    assert np.max(np.abs(balance)) < 1e-6 * np.max(r.excitation_work)
    assert np.all(r.viscous_dissipation > 0)
    assert np.all(r.contact_dissipation >= 0.0)  # friction work: never negative, zero while stuck
    assert np.max(r.contact_dissipation) > 0.1 * np.max(r.excitation_work)  # slipping near the peak
    # the friction work of the sampled period and the harmonics' work differ by the AFT's sampling
    # error (both fall like 1/samples^2): measured 3.3e-4 of the excitation's work at 128 samples on
    # this curve (8.1e-5 at 256), allowed twice that
    gap = np.abs(r.contact_dissipation - r.contact_harmonic_work).max(axis=1)
    assert np.max(gap / r.excitation_work) < 6.5e-4


def test_friction_work_converges_where_the_contact_slides_and_opens():
    """At the second mode the block's contact slides while its normal load varies, and an element opens.

    The work ``T_k (s_k - s_k-1)`` of each step converges like 1/samples there (it was 9.9 % low at 128
    samples, 2.6 % at 512); the trapezoidal rule converges like 1/samples^2.
    """
    s, omega = inclined_block(), 16918.0
    exact = frequency_point(s, FORCE, omega, harmonics=7, samples=8192).contact_harmonic_work[0, 0]
    errors = {}
    for samples in (128, 512):
        r = frequency_point(s, FORCE, omega, harmonics=7, samples=samples)
        n = time_samples(r.contact_n[0, 0], samples)
        assert np.any((n.min() < s.contacts[0].model.gaps) & (n.max() > s.contacts[0].model.gaps))  # it opens
        errors[samples] = abs(r.contact_dissipation[0, 0] / exact - 1)
    # measured 1.3e-3 and 3.4e-4 (the harmonics' work itself: 3.1e-4 and 6e-6), allowed about twice
    assert errors[128] < 3e-3 and errors[512] < 7e-4


def test_contact_dissipation_is_never_negative_when_the_contact_only_opens():
    """Shaken along its normal only, the inclined block's contact opens and closes but never slides."""
    s = inclined_block()
    normal = s.contacts[0].normal
    with pytest.warns(UnderResolvedWarning) as caught:  # the opening is under-resolved
        r = frequency_response(s, 5.0 * normal, (12000.0, 18000.0), harmonics=7)
    assert np.all(np.abs(r.contact_t[:, 0, :]) < 1e-12 * np.abs(r.contact_n[:, 0, 1:]).max())  # no sliding
    # was negative at 414 of 762 points, down to -0.68 % of the excitation work; now never negative, and
    # what remains is the friction work of tangential motion at rounding level (below 1e-12 of the normal
    # motion above): measured at most 2.4e-38 J, against works of order 1e-6 J
    assert r.points > 100 and np.all(r.contact_dissipation >= 0.0) and r.contact_dissipation.max() < 1e-30
    # once per curve, naming the contact, where it is worst and the samples that resolve it, and pointing
    # at the caller's line (it used to point inside the package and name no contact)
    [warning] = [w for w in caught if w.category is UnderResolvedWarning]
    assert re.match(r"contact 'sphere' opens and closes during the cycle faster than 128 samples per period "
                    r"resolve \(worst at omega = 13\d{3}(\.\d+)? rad/s\): .* samples=512 resolves it",
                    str(warning.message))
    assert warning.filename == __file__
    with warnings.catch_warnings():
        warnings.simplefilter("error", UnderResolvedWarning)  # the advice holds: 512 samples resolve it
        frequency_response(s, 5.0 * normal, (12000.0, 18000.0), harmonics=7, samples=512)


# -- statics, folds, the result object ---------------------------------------------------------------

def test_static_preload_as_force_and_as_approach():
    model = tune(Sphere.paper(), 37.5, elements=4)
    s = Structure(M=np.eye(2), C=None, K=np.diag([1e6, 0.0]))  # no structural stiffness along y
    s.add_contact(model, tangential=0, normal=1, preload=30.0)
    q = static_solution(s)
    assert float(model.normal_force(q[1])) == pytest.approx(30.0, rel=1e-9)
    s2 = Structure(M=np.eye(1), C=None, K=[[1e6]])
    s2.add_contact(model, tangential=0, approach=2e-6)
    r = frequency_response(s2, [1.0], (900, 1100), harmonics=3)
    assert r.contact_N[0, 0, 0] == pytest.approx(float(model.normal_force(2e-6)), rel=1e-12)


def test_turning_points_pass():
    r = frequency_response(inclined_block(), FORCE, (16500, 17500), harmonics=5)
    assert np.any(np.diff(r.omega) < 0)  # the second mode folds (an isola-like bend) and is followed
    assert r.omega[-1] == 17500


def test_result_object(tmp_path, inclined_curve):
    r = inclined_curve
    assert isinstance(r, FrequencyResponse)
    assert r.coefficients.shape == (r.points, 15, 2)
    assert r.contact_T.shape == (r.points, 1, 15)
    assert r.amplitude(0, 1).shape == (r.points,)
    rel = r.amplitude({0: 1.0, 1: -1.0}, 1)
    assert np.all(rel > 0)
    t, q = r.time_history(3, 0, samples=64)
    assert t.shape == q.shape == (64,)
    assert np.isclose(q.max() - r.coefficients[3, 0, 0], np.max(np.abs(q - r.coefficients[3, 0, 0])), rtol=0.2)
    ax = r.plot(0, 1, label="x")
    assert "rad/s" in ax.get_xlabel() and "µm" in ax.get_ylabel()
    path = r.to_csv(tmp_path / "curve.csv")
    lines = path.read_text().splitlines()
    assert lines[0].split(",")[:3] == ["omega [rad/s]", "f [Hz]", "q0 max [m]"]
    assert len(lines) == r.points + 1


@pytest.mark.parametrize("call, message", [
    (lambda s: frequency_response("s", [1.0], (1, 2)), "structure must be a microslip Structure, got str"),
    (lambda s: frequency_response(s, [1.0], 5.0), "omega must be a pair"),
    (lambda s: frequency_response(s, [1.0], (-1, 2)), "omega\\[0\\] must be positive"),
    (lambda s: frequency_response(s, [1.0], (2, 2)), "omega must span a range"),
    (lambda s: frequency_response(s, [1.0, 2.0], (1, 2)), "force must have one entry per DOF \\(1\\), got 2"),
    (lambda s: frequency_response(s, {3: [1.0]}, (1, 2), harmonics=2), "harmonic 3 is outside 0..harmonics = 2"),
    (lambda s: frequency_response(s, {0: [1.0]}, (1, 2)), "force must have a non-zero dynamic part"),
    (lambda s: frequency_response(s, [1.0], (1, 2), harmonics=0), "harmonics must be an integer >= 1, got 0"),
    (lambda s: frequency_response(s, [1.0], (1, 2), control={}), "control must be a StepControl"),
    (lambda s: frequency_response(s, [1.0], (1, 2), harmonics=3, samples=6), "samples must be at least"),
    (lambda s: frequency_response(s, {0: [1j], 1: [1.0]}, (1, 2)), "force\\[0\\] \\(the static force\\) must be real"),
])
def test_frequency_response_input_errors(call, message):
    with pytest.raises((ValueError, TypeError), match=message):
        call(jenkins_oscillator())


def test_amplitude_input_errors(inclined_curve):
    with pytest.raises(ValueError, match="harmonic must be at most harmonics = 7, got 9"):
        inclined_curve.amplitude(0, 9)
    with pytest.raises(ValueError, match="dof: DOF 5 is out of range"):
        inclined_curve.amplitude(5)
    with pytest.raises(ValueError, match="point must be below the number of points"):
        inclined_curve.time_history(10**6)
    with pytest.raises(ValueError, match="unit must be one of"):
        inclined_curve.plot(unit="ft")


def test_large_sparse_structure_matches_dense_solution(monkeypatch):
    """A 60-DOF chain (915 unknowns at H = 7: the sparse path) with a contact at its free end."""
    import microslip.frequency.equations.hbm as hbm

    n = 60
    k = 2e7 * (np.eye(n) * 2 - np.eye(n, k=1) - np.eye(n, k=-1))
    k[-1, -1] = 2e7
    M, K = sp.identity(n, format="csr") * 0.01, sp.csr_matrix(k)
    s = Structure(M, 1e-6 * K, K)
    s.add_contact(JENKINS, tangential=n - 1, approach=3e-6)
    f = np.zeros(n)
    f[-1] = 5.0
    sparse = frequency_point(s, f, 2000.0, harmonics=7)
    monkeypatch.setattr(hbm, "DENSE_LIMIT", 10**6)
    dense = frequency_point(s, f, 2000.0, harmonics=7)
    assert sparse.structure.sparse
    np.testing.assert_allclose(sparse.coefficients, dense.coefficients, rtol=1e-7, atol=1e-9 * np.abs(
        dense.coefficients).max())
    # the contact sticks at this level: its dissipation is zero up to rounding of the
    # harmonic products (excitation work is the natural scale of that rounding)
    scale = abs(float(sparse.excitation_work[0]))
    assert abs(sparse.contact_dissipation[0, 0] - dense.contact_dissipation[0, 0]) <= 1e-9 * scale
    assert sparse.contact_dissipation[0, 0] >= -1e-12 * scale


def test_linear_structure_without_contacts():
    s = Structure([[1.0]], [[2.0]], [[1e4]])
    r = frequency_response(s, [1.0], (50, 150), harmonics=2)
    w = r.omega
    exact = 1.0 / np.abs(1e4 - w**2 + 2j * w)
    np.testing.assert_allclose(r.amplitude(0, 1), exact, rtol=1e-9)
    # no second harmonic in a linear response: relative to the first (amplitudes are ~1e-4 m, so an absolute
    # tolerance of 1e-8 would have passed anything)
    assert np.max(r.amplitude(0, 2)) < 1e-12 * np.max(r.amplitude(0, 1))


def test_descending_sweep_and_progress(capsys):
    up = frequency_response(jenkins_oscillator(), [2.0], (60, 160), harmonics=3)
    down = frequency_response(jenkins_oscillator(), [2.0], (160, 60), harmonics=3, progress=True)
    assert down.omega[0] == 160 and down.omega[-1] == 60
    # same curve: the peaks agree to the resolution of the two point sets
    assert down.peak(0, 1)[1] == pytest.approx(up.peak(0, 1)[1], rel=1e-3)
    err = capsys.readouterr().err
    assert "[10/10] omega = 60 rad/s" in err and "frequency response:" in err
