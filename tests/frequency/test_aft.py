"""AFT of microslip contacts: compiled kernel vs twin, exact Jacobians, closed forms, input checks."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from _strategies import random_contact
from microslip import MicroslipModel, Sphere, tune
from microslip.frequency import aft, aft_batch, cycle_work, default_samples, time_samples
from microslip.kernels import aft as _aft
from microslip.frequency.aft import NotPeriodicError

JENKINS = MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0)  # slip force 1 N at n = 1 µm


def _random_case(seed, H=3, J=4):
    rng = np.random.default_rng(seed)
    model = random_contact(rng, J)
    nb = 2 * H + 1
    t = rng.normal(size=nb) * 1e-6
    n = rng.normal(size=nb) * 0.5e-6
    n[0] = rng.uniform(0.5, 2.5) * 1e-6  # some elements open part of the period, some always
    return model, t, n


def _finite_difference(model, t, n, Ns, h=1e-13):
    nb = t.size
    JTt = np.empty((nb, nb))
    JTn = np.empty((nb, nb))
    JNn = np.empty((nb, nb))
    for q in range(nb):
        e = np.zeros(nb)
        e[q] = h
        plus, minus = aft(model, t + e, n, samples=Ns), aft(model, t - e, n, samples=Ns)
        JTt[:, q] = (plus.T - minus.T) / (2 * h)
        plus, minus = aft(model, t, n + e, samples=Ns), aft(model, t, n - e, samples=Ns)
        JTn[:, q] = (plus.T - minus.T) / (2 * h)
        JNn[:, q] = (plus.N - minus.N) / (2 * h)
    return JTt, JTn, JNn


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), H=st.integers(0, 4), Ns=st.sampled_from([16, 33, 64]))
def test_kernel_matches_pure_python_twin(seed, H, Ns):
    model, t, n = _random_case(seed, H=H)
    r = aft(model, t, n, samples=Ns)
    FT, FN, JTt, JTn, JNn, periods = _aft.aft_reference(model.kt, model.kn, model.gaps, model.mu, t, n, Ns)
    scale_F = model.kt.sum() * 1e-6
    # same return mapping, same history convention; only the rounding of the slider update
    # and of the sums differs (relative 1e-12 of the force and stiffness scales)
    np.testing.assert_allclose(r.T, FT, atol=1e-12 * scale_F)
    np.testing.assert_allclose(r.N, FN, atol=1e-12 * model.kn.sum() * 1e-6)
    for a, b, k in ((r.dT_dt, JTt, model.kt.sum()), (r.dT_dn, JTn, model.kn.sum()), (r.dN_dn, JNn, model.kn.sum())):
        np.testing.assert_allclose(a, b, atol=1e-10 * k)
    if H:  # (with H = 0 every sample sits exactly on the slip limit reached in the static step:
        # rounding may call it a slip at sample k instead of a stick, which the kernel counts as
        # a new state (slider set at k) and the twin does not (same gradient); both are right)
        assert r.periods == periods


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_jacobian_matches_finite_differences(seed):
    model, t, n = _random_case(seed, H=3)
    r = aft(model, t, n, samples=64)
    JTt, JTn, JNn = _finite_difference(model, t, n, 64)
    # The AFT is piecewise linear in the coefficients; a 1e-13 m perturbation of 1e-6 m
    # amplitudes stays on one piece except by bad luck, so the match is to rounding
    # (central differences of ~1 N forces with h = 1e-13: about 1e-3 N/m of noise on 1e7 N/m).
    for exact, fd, k in ((r.dT_dt, JTt, model.kt.sum()), (r.dT_dn, JTn, model.kn.sum()), (r.dN_dn, JNn, model.kn.sum())):
        np.testing.assert_allclose(exact, fd, atol=1e-6 * k)


def test_jacobian_covers_stick_slip_and_open_states():
    model, t, n = _random_case(5, H=2)
    Ns = 64
    _, _, _, _, cond, _ = __import__("microslip.kernels.element", fromlist=["x"]).march_reference(
        model.kt, model.kn, model.gaps, model.mu, np.tile(time_samples(t, Ns), 3), np.tile(time_samples(n, Ns), 3),
        np.zeros(model.elements))
    seen = set(np.array(cond).ravel().tolist())
    assert seen == {0, 1, 2}  # the case above exercises all three derivative branches


def test_static_slip_propagates_through_the_slider():
    """An element that slips only in the static step keeps a force that depends on t0 and n0."""
    m = MicroslipModel(kt=[1e6], kn=[1e7], gaps=[0.0], mu=0.5)
    t = np.array([3e-6, 0.0, 0.0])  # static slip: kt t0 = 3 N > mu N = 1 N
    n = np.array([2e-7, 0.0, 0.0])
    r = aft(m, t, n, samples=32)
    assert np.isclose(r.T[0], 1.0)  # mu kn n0
    # T = kt (t - s) with s = t0 - mu kn n0 / kt: dT0/dt0 = 0, dT0/dn0 = mu kn
    assert abs(r.dT_dt[0, 0]) < 1e-6
    assert np.isclose(r.dT_dn[0, 0], 0.5e7)


def _jenkins_describing_function(A, k=1e4, Fs=1.0):
    """First harmonic of a Jenkins element under t = A cos(tau): (cos, sin) coefficients (N)."""
    if A <= Fs / k:
        return k * A, 0.0
    beta = np.arccos(1 - 2 * Fs / (k * A))
    return k * A / np.pi * (beta - np.sin(2 * beta) / 2), -4 * Fs / np.pi * (1 - Fs / (k * A))


@pytest.mark.parametrize("A", [5e-5, 1.5e-4, 3e-4, 1e-3])
def test_jenkins_first_harmonic_matches_describing_function(A):
    r = aft(JENKINS, [0.0, A, 0.0, 0.0, 0.0], [1e-6, 0, 0, 0, 0], samples=4096)
    a, b = _jenkins_describing_function(A)
    # 4096 samples: the stick-slip kinks are located to within 2 pi / 4096; the
    # rectangle-rule error of a kinked periodic function is O(1/Ns^2) ~ 1e-6 of k A
    assert abs(r.T[1] - a) < 2e-6 * 1e4 * A
    assert abs(r.T[2] - b) < 2e-6 * 1e4 * A
    assert np.isclose(r.dissipation([0.0, A, 0.0, 0.0, 0.0]), -np.pi * A * b, rtol=1e-12)


def test_jenkins_error_falls_like_one_over_samples_squared():
    A = 2.7e-4
    a, b = _jenkins_describing_function(A)
    errors = []
    for Ns in (64, 128, 256, 512, 1024):
        r = aft(JENKINS, [0.0, A, 0.0], [1e-6, 0, 0], samples=Ns)
        errors.append(np.hypot(r.T[1] - a, r.T[2] - b) / np.hypot(a, b))
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.mean(rates) > 1.5  # second order on average (single steps vary with where the kinks fall)
    assert errors[1] < 2e-3  # the default for H = 7 (128 samples) is within 0.2 % on the first harmonic


def test_periodicity_is_detected_not_assumed():
    """A slider that ratchets needs more than two periods; the march keeps going until it repeats."""
    m = MicroslipModel(kt=[1e6], kn=[1e7], gaps=[0.0], mu=0.3)
    # t and n in phase: the element slips forward while loaded, backward while unloaded
    t = np.array([0.0, 1e-6, 0.0, 0.0, 0.3e-6])
    n = np.array([1e-6, 0.8e-6, 0.0, 0.1e-6, 0.0])
    r = aft(m, t, n, samples=64)
    ref = _aft.aft_reference(m.kt, m.kn, m.gaps, m.mu, t, n, 64)
    assert r.periods == ref[-1] >= 2
    with pytest.raises(NotPeriodicError, match="max_periods = 1"):
        aft(m, t, n, samples=64, max_periods=1)


def test_batch_equals_single_calls():
    models, ts, ns = zip(*[_random_case(s, H=2, J=j) for s, j in ((0, 1), (1, 4), (2, 7))])
    r = aft_batch(list(models), np.array(ts), np.array(ns), samples=32)
    for c, (m, t, n) in enumerate(zip(models, ts, ns)):
        one = aft(m, t, n, samples=32)
        np.testing.assert_array_equal(r.T[c], one.T)
        np.testing.assert_array_equal(r.dT_dn[c], one.dT_dn)
        assert r.periods[c] == one.periods


def test_tuned_sphere_contact_with_many_elements():
    model = tune(Sphere.paper(), 37.5, elements=16)
    n0 = float(Sphere.paper().approach(37.5))
    t = np.zeros(15)
    t[1], t[2] = 1.0e-6, 0.3e-6
    n = np.zeros(15)
    n[0], n[1] = n0, 0.2 * n0
    r = aft(model, t, n)
    assert r.samples == 128 == default_samples(7)
    # the normal force is elastic: its static part is the load at the mean approach plus
    # the (positive) effect of the varying approach on the piecewise-linear curve
    assert r.N[0] >= float(model.normal_force(n0)) - 1e-9
    assert r.dissipation(t) > 0
    assert cycle_work(r.N, n) == pytest.approx(0.0, abs=1e-3 * r.dissipation(t))


def test_default_samples():
    assert [default_samples(h) for h in (0, 1, 2, 7, 8, 9, 20)] == [1, 32, 32, 128, 128, 256, 512]


@pytest.mark.parametrize("call, message", [
    (lambda: aft("model", [0, 1e-6, 0], [1e-6, 0, 0]), "model must be a microslip MicroslipModel, got str"),
    (lambda: aft(JENKINS, [0, 1e-6], [1e-6, 0]), "t must hold 2H \\+ 1 Fourier coefficients"),
    (lambda: aft(JENKINS, [0, 1e-6, 0], [1e-6, 0, 0, 0, 0]), "n must have the same shape as t \\(3,\\), got \\(5,\\)"),
    (lambda: aft(JENKINS, [0, np.nan, 0], [1e-6, 0, 0]), "t must be finite, got .*nan.* at flat index 1"),
    (lambda: aft(JENKINS, [0, 1e-6, 0, 0, 0], [1e-6, 0, 0, 0, 0], samples=4), "samples must be at least 2 \\* harmonics \\+ 1 = 5"),
    (lambda: aft(JENKINS, [0, 1e-6, 0], [1e-6, 0, 0], samples=2.5), "samples must be an integer, got 2.5"),
    (lambda: aft(JENKINS, [0, 1e-6, 0], [1e-6, 0, 0], max_periods=0), "max_periods must be an integer >= 1, got 0"),
    (lambda: aft_batch(JENKINS, [[0, 1e-6, 0]], [[1e-6, 0, 0]]), "models must be a non-empty sequence"),
    (lambda: aft_batch([JENKINS, 3], [[0, 1e-6, 0]] * 2, [[1e-6, 0, 0]] * 2), "models\\[1\\] must be a microslip"),
    (lambda: aft_batch([JENKINS], [[0, 1e-6, 0]] * 2, [[1e-6, 0, 0]] * 2), "t must have shape \\(len\\(models\\), 2H\\+1\\) = \\(1, 3\\)"),
    (lambda: time_samples([1.0, 2.0], 8), "coefficients must hold 2H \\+ 1"),
])
def test_input_errors_name_the_parameter(call, message):
    with pytest.raises((ValueError, TypeError), match=message):
        call()
