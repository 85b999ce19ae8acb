"""The march of a contact on its plane (time domain, private kernels) against its pure-Python twin."""

import numpy as np
import pytest

from _plane_twin import integrate_plane_reference, march_plane_reference
from microslip import MicroslipModel
from microslip.frequency import Structure
from microslip.kernels.plane_march import march_plane
from microslip.frequency.analyses.transient import PeriodMap


def _path(seed, steps=300, J=5):
    rng = np.random.default_rng(seed)
    model = MicroslipModel(rng.uniform(1, 3, J) * 1e6, rng.uniform(1, 3, J) * 1e7, np.sort(rng.uniform(0, 2e-6, J)),
                           mu=0.4)
    tau = np.linspace(0, 6 * np.pi, steps)
    t1 = 2e-6 * np.cos(tau) + 0.3e-6 * rng.normal(size=steps)
    t2 = 1e-6 * np.sin(1.5 * tau) + 0.3e-6 * rng.normal(size=steps)
    n = 1.2e-6 + 0.8e-6 * np.sin(0.7 * tau)  # elements open and close
    return model, t1, t2, n


@pytest.mark.parametrize("seed", range(6))
def test_march_equals_its_twin(seed):
    model, t1, t2, n = _path(seed)
    s = np.zeros((2, model.elements))
    T, N, Ti, cond = np.empty((t1.size, 2)), np.empty(t1.size), np.empty((t1.size, model.elements, 2)), \
        np.empty((t1.size, model.elements), dtype=np.int8)
    march_plane(model.kt, model.kn, model.gaps, model.mu, t1, t2, n, s, T, N, Ti, cond)
    Tr, Nr, Tir, condr, sr = march_plane_reference(model.kt, model.kn, model.gaps, model.mu, t1, t2, n,
                                                   np.zeros((2, model.elements)))
    assert set(np.unique(cond)) == {0, 1, 2}  # open, stick and slip all met
    np.testing.assert_array_equal(cond, condr)
    # the same return mapping, written with the stick radius (kernel) or the force (twin): to rounding
    np.testing.assert_allclose(T, Tr, rtol=0, atol=1e-12 * np.abs(Tr).max())
    np.testing.assert_allclose(Ti, Tir, rtol=0, atol=1e-12 * np.abs(Tr).max())
    np.testing.assert_allclose(N, Nr, rtol=1e-14)
    np.testing.assert_allclose(s, sr, rtol=0, atol=1e-12 * np.abs(t1).max())
    # the friction law on the plane, element by element
    assert np.all(np.hypot(Ti[..., 0], Ti[..., 1]) <= model.mu * model.kn * np.maximum(n[:, None] - model.gaps, 0)
                  * (1 + 1e-12))


def test_time_integration_equals_its_twin():
    s = Structure(np.eye(2), 20 * np.eye(2), np.diag([1e5, 1.2e5]))
    model = MicroslipModel([3e4, 2e4], [2e6, 2e6], [0.0, 0.4e-6], mu=0.5)
    s.add_contact(model, tangential=[{0: 1.0}, {1: 1.0}], approach=1e-6)
    scheme = PeriodMap(s, {1: [3.0, 2.0j]}, 360.0, 256)
    q_prev, q, sliders = scheme.start()
    assert sliders.shape == (2 * model.elements,)
    out = np.empty((scheme.steps, 2))
    ref = integrate_plane_reference(scheme.A_inv, scheme.K, scheme.B1, scheme.B0, scheme.f, scheme.Bt, scheme.Bt2,
                                    scheme.Bn, scheme.n0, [model], [sliders.reshape(2, -1)], q_prev, q, scheme.steps)
    scheme.integrate(q_prev, q, sliders, out)
    np.testing.assert_allclose(out, ref[0], rtol=0, atol=1e-12 * np.abs(ref[0]).max())
    np.testing.assert_allclose(sliders.reshape(2, -1), ref[3][0], rtol=0, atol=1e-12 * np.abs(ref[0]).max())
    assert np.abs(ref[3][0]).max() > 0  # the contact moved


def test_time_integration_from_rest_starts_from_the_static_part_of_the_excitation_only():
    """An array excitation is a first harmonic: the march starts at the static equilibrium under the
    preloads alone (it used to be loaded statically by the first harmonic's amplitudes, and a complex
    array was refused)."""
    from microslip import MicroslipModel, Structure
    from microslip.frequency import static_solution

    s = Structure(np.eye(2), 0.02 * np.eye(2), np.diag([1e4, 2e4]))
    s.add_contact(MicroslipModel(kt=[2e3], kn=[1e5], gaps=[0.0], mu=0.3), tangential=0, normal=1, preload=5.0)
    preloaded = static_solution(s)
    for force in ([3.0, 0.0], [3.0, 2.0j]):
        q_prev, q, _ = PeriodMap(s, force, 100.0, 64).start()
        np.testing.assert_array_equal(q, preloaded)
    q_prev, q, _ = PeriodMap(s, {0: [1.0, 0.0], 1: [3.0, 0.0]}, 100.0, 64).start()
    np.testing.assert_array_equal(q, static_solution(s, {0: [1.0, 0.0], 1: [3.0, 0.0]}))
    assert q[0] != preloaded[0]  # the static part does load it


@pytest.mark.parametrize("seed", range(3))
def test_the_march_is_simulate_s_own_bit_for_bit(seed):
    """The frequency package's march and ``simulate`` call the one element step
    (``_kernels.plane_step``), in the same order: every recorded quantity is equal, not just close
    (they used to compute the slip with different roundings)."""
    model, t1, t2, n = _path(seed)
    s = np.zeros((2, model.elements))
    T, N, Ti, cond = np.empty((t1.size, 2)), np.empty(t1.size), np.empty((t1.size, model.elements, 2)), \
        np.empty((t1.size, model.elements), dtype=np.int8)
    march_plane(model.kt, model.kn, model.gaps, model.mu, t1, t2, n, s, T, N, Ti, cond)
    r = model.simulate(np.column_stack([t1, t2]), n)
    assert set(np.unique(cond)) == {0, 1, 2}
    for got, want in ((T, r.T), (N, r.N), (Ti, r.Ti), (cond, r.condition), (s.T, r.state.sliders)):
        np.testing.assert_array_equal(got, want)
