"""The compiled kernels against their slow pure-Python twin.

Both follow the same return mapping with the same floating-point operations
in the same order (the compiled one branch-free, clipping the trial force;
the twin with an ``if``), so they must agree bit for bit, including at ties
(a trial force exactly at the friction limit sticks in both).
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from _strategies import UM, lengths_array, models, paths
from microslip import MicroslipModel
from microslip.kernels import element as _kernels
from microslip.model import OPEN, SLIP, STICK


def compiled(model, t, n, s0):
    steps, J = t.size, model.elements
    s = np.array(s0, dtype=float)
    T, N, W = np.empty(steps), np.empty(steps), np.empty(steps)
    Ti, cond = np.empty((steps, J)), np.empty((steps, J), dtype=np.int8)
    _kernels.march(model.kt, model.kn, model.gaps, model.mu, t, n, s, T, N, W, Ti, cond)
    s_tot = np.array(s0, dtype=float)
    T_tot, N_tot, W_tot = np.empty(steps), np.empty(steps), np.empty(steps)
    _kernels.march(model.kt, model.kn, model.gaps, model.mu, t, n, s_tot, T_tot, N_tot, W_tot,
                   _kernels.NO_ELEMENTS, _kernels.NO_CONDITIONS)
    return T, N, W, Ti, cond, s, T_tot, N_tot, W_tot, s_tot


def assert_twins_agree(model, t, n, s0):
    s0 = np.asarray(s0, dtype=float)
    s0_copy = s0.copy()
    T_ref, N_ref, W_ref, Ti_ref, cond_ref, s_ref = _kernels.march_reference(
        model.kt, model.kn, model.gaps, model.mu, t, n, s0)
    np.testing.assert_array_equal(s0, s0_copy)  # the twin does not touch its input state
    T, N, W, Ti, cond, s, T_tot, N_tot, W_tot, s_tot = compiled(model, t, n, s0)
    np.testing.assert_array_equal(T, T_ref)
    np.testing.assert_array_equal(N, N_ref)
    np.testing.assert_array_equal(W, W_ref)
    np.testing.assert_array_equal(W_tot, W_ref)
    np.testing.assert_array_equal(Ti, np.array(Ti_ref).reshape(Ti.shape))
    np.testing.assert_array_equal(cond, np.array(cond_ref).reshape(cond.shape))
    np.testing.assert_array_equal(s, s_ref)
    np.testing.assert_array_equal(T_tot, T_ref)
    np.testing.assert_array_equal(N_tot, N_ref)
    np.testing.assert_array_equal(s_tot, s_ref)
    return np.array(cond_ref)


@settings(max_examples=150, deadline=None)
@given(model=models(), path=paths(), data=st.data())
def test_compiled_kernels_equal_twin_bit_for_bit(model, path, data):
    t, n = path
    s0 = lengths_array(data.draw, model.elements, -3 * UM, 3 * UM)
    assert_twins_agree(model, t, n, s0)


@st.composite
def random_walks(draw):
    """Long random walks in (t, n) in which n wanders across all the gaps."""
    size = draw(st.integers(50, 300))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    t = np.cumsum(rng.normal(0.0, 0.3 * UM, size))
    n = 1 * UM + np.cumsum(rng.normal(0.0, 0.3 * UM, size))
    return t, n


@settings(max_examples=40, deadline=None)
@given(model=models(max_elements=12), path=random_walks())
def test_twins_agree_on_random_walks(model, path):
    assert_twins_agree(model, *path, np.zeros(model.elements))


def test_twins_agree_where_elements_open_and_close_again():
    model = MicroslipModel(kt=[8e6, 5e6, 3e6], kn=[1e7, 7e6, 3e6], gaps=[0.0, 0.9e-6, 1.5e-6], mu=0.4)
    k = np.arange(2000)
    t = 1.5 * UM * np.sin(2 * np.pi * k / 97)
    n = 1.0 * UM + 1.2 * UM * np.sin(2 * np.pi * k / 331)  # from -0.2 µm to 2.2 µm
    cond = assert_twins_agree(model, t, n, np.zeros(3))
    for i in range(3):  # every element is open, then closed, then open again...
        closes = np.flatnonzero((cond[:-1, i] == OPEN) & (cond[1:, i] != OPEN))
        opens = np.flatnonzero((cond[:-1, i] != OPEN) & (cond[1:, i] == OPEN))
        assert closes.size >= 3 and opens.size >= 3
    assert (cond == STICK).any() and (cond == SLIP).any()


def test_simulate_uses_the_compiled_kernel_with_the_same_numbers():
    model = MicroslipModel(kt=[8e6, 5e6], kn=[1e7, 7e6], gaps=[0.0, 0.9e-6], mu=0.4)
    rng = np.random.default_rng(1)
    t, n = rng.uniform(-2, 2, 500) * UM, rng.uniform(-0.5, 2, 500) * UM
    r = model.simulate(t, n)
    T_ref, N_ref, W_ref, Ti_ref, cond_ref, s_ref = _kernels.march_reference(
        model.kt, model.kn, model.gaps, model.mu, t, n, np.zeros(2))
    np.testing.assert_array_equal(r.T, T_ref)
    np.testing.assert_array_equal(r.friction_work, W_ref)
    np.testing.assert_array_equal(r.Ti, Ti_ref)
    np.testing.assert_array_equal(r.condition, cond_ref)
    np.testing.assert_array_equal(r.state.sliders, s_ref)


def compiled_plane(model, t, n, s0, per_element=True):
    steps, J = t.shape[0], model.elements
    s = np.array(s0, dtype=float)
    T, N, W = np.empty((steps, 2)), np.empty(steps), np.empty(steps)
    if per_element:
        Ti, cond = np.empty((steps, J, 2)), np.empty((steps, J), dtype=np.int8)
    else:
        Ti, cond = _kernels.NO_PLANE_ELEMENTS, _kernels.NO_CONDITIONS
    _kernels.march_plane(model.kt, model.kn, model.gaps, model.mu, t, n, s, T, N, W, Ti, cond)
    return T, N, W, Ti, cond, s


def assert_plane_twins_agree(model, t, n, s0):
    s0 = np.asarray(s0, dtype=float)
    s0_copy = s0.copy()
    ref = _kernels.march_plane_reference(model.kt, model.kn, model.gaps, model.mu, t, n, s0)
    np.testing.assert_array_equal(s0, s0_copy)  # the twin does not touch its input state
    T, N, W, Ti, cond, s = compiled_plane(model, t, n, s0)
    for got, want in zip((T, N, W, Ti, cond, s), ref):
        np.testing.assert_array_equal(got, np.array(want).reshape(got.shape))
    T_tot, N_tot, W_tot, _, _, s_tot = compiled_plane(model, t, n, s0, per_element=False)
    for got, want in zip((T_tot, N_tot, W_tot, s_tot), (T, N, W, s)):
        np.testing.assert_array_equal(got, want)
    return cond


@st.composite
def plane_walks(draw):
    """Random walks on the plane, n wandering across all the gaps."""
    size = draw(st.integers(50, 300))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    t = np.cumsum(rng.normal(0.0, 0.3 * UM, (size, 2)), axis=0)
    n = 1 * UM + np.cumsum(rng.normal(0.0, 0.3 * UM, size))
    return t, n


@settings(max_examples=150, deadline=None)
@given(model=models(), path=paths(), data=st.data())
def test_compiled_plane_kernel_equals_twin_bit_for_bit(model, path, data):
    """Same floating-point operations in the same order (the compiled one vectorised over the
    elements with selects, the twin with an ``if``), so equal bit for bit, ties included."""
    t1, n = path
    t = np.column_stack([t1, lengths_array(data.draw, t1.size, -3 * UM, 3 * UM)])
    s0 = lengths_array(data.draw, 2 * model.elements, -3 * UM, 3 * UM).reshape(-1, 2)
    assert_plane_twins_agree(model, t, n, s0)


@settings(max_examples=40, deadline=None)
@given(model=models(max_elements=12), path=plane_walks())
def test_plane_twins_agree_on_random_walks(model, path):
    assert_plane_twins_agree(model, *path, np.zeros((model.elements, 2)))


@settings(max_examples=60, deadline=None)
@given(model=models(max_elements=8), path=plane_walks(), exponent=st.floats(-320.0, -140.0))
def test_plane_twins_agree_at_tiny_magnitudes(model, path, exponent):
    """Paths, gaps and sliders scaled to 1e-320..1e-140 m, on both sides of the 3e-151 m below which
    the element scales the stretch before squaring it, subnormals included: still bit for bit."""
    scale = 10.0 ** exponent / UM
    tiny = MicroslipModel(kt=model.kt, kn=model.kn, gaps=model.gaps * scale, mu=model.mu)
    t, n = path
    assert_plane_twins_agree(tiny, t * scale, n * scale, t[:model.elements][::-1] * 0.5 * scale
                             if t.shape[0] >= model.elements else np.zeros((model.elements, 2)))


def test_plane_twins_agree_where_elements_open_and_close_again_on_an_orbit():
    model = MicroslipModel(kt=[8e6, 5e6, 3e6], kn=[1e7, 7e6, 3e6], gaps=[0.0, 0.9e-6, 1.5e-6], mu=0.4)
    k = np.arange(2000)
    t = 1.5 * UM * np.column_stack([np.cos(2 * np.pi * k / 97), 0.5 * np.sin(2 * np.pi * k / 97)])
    n = 1.0 * UM + 1.2 * UM * np.sin(2 * np.pi * k / 331)
    cond = assert_plane_twins_agree(model, t, n, np.zeros((3, 2)))
    for i in range(3):
        closes = np.flatnonzero((cond[:-1, i] == OPEN) & (cond[1:, i] != OPEN))
        assert closes.size >= 3
    assert (cond == STICK).any() and (cond == SLIP).any()


def test_simulate_on_the_plane_uses_the_compiled_kernel_with_the_same_numbers():
    model = MicroslipModel(kt=[8e6, 5e6], kn=[1e7, 7e6], gaps=[0.0, 0.9e-6], mu=0.4)
    rng = np.random.default_rng(1)
    t, n = rng.uniform(-2, 2, (500, 2)) * UM, rng.uniform(-0.5, 2, 500) * UM
    r = model.simulate(t, n)
    T, N, W, Ti, cond, s = _kernels.march_plane_reference(model.kt, model.kn, model.gaps, model.mu, t, n,
                                                           np.zeros((2, 2)))
    np.testing.assert_array_equal(r.T, T)
    np.testing.assert_array_equal(r.friction_work, W)
    np.testing.assert_array_equal(r.Ti, Ti)
    np.testing.assert_array_equal(r.condition, cond)
    np.testing.assert_array_equal(r.state.sliders, s)


def test_kernels_are_compiled_and_cached():
    _kernels.warm_up()
    for kernel in (_kernels.march, _kernels.march_plane, _kernels.plane_tangents):
        assert kernel.signatures  # compiled for float64 arrays
        assert type(kernel._cache).__name__ != "NullCache"  # cache=True


@st.composite
def plane_marches(draw):
    """Arrays of 1..40 elements (any multiple of the vector width or not) on paths of 0..60 samples.

    The displacements lie on a coarse lattice (0.25 µm), so samples repeat and an element may see a
    zero stretch or a trial force exactly at its friction limit; ``n`` goes from below every gap (all
    open) to above all of them.
    """
    J = draw(st.integers(1, 40))
    steps = draw(st.integers(0, 60))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    kt, kn = 10 ** rng.uniform(5, 8, J), 10 ** rng.uniform(5, 8, J)
    gaps = rng.uniform(0, 2 * UM, J)
    if draw(st.booleans()):
        gaps = np.sort(gaps)
    mu = draw(st.floats(0.05, 1.0))
    if draw(st.booleans()):
        t = 0.25 * UM * rng.integers(-12, 13, (steps, 2)).astype(float)
        n = 0.25 * UM * rng.integers(-4, 13, steps).astype(float)
        s0 = 0.25 * UM * rng.integers(-12, 13, (J, 2)).astype(float)
    else:
        t = np.cumsum(rng.normal(0.0, 0.3 * UM, (steps, 2)), axis=0)
        n = 1 * UM + np.cumsum(rng.normal(0.0, 0.3 * UM, steps))
        s0 = np.zeros((J, 2))
    return MicroslipModel(kt=kt, kn=kn, gaps=gaps, mu=mu), t, n, s0


def bits(a):
    """The array's bytes: equal bit for bit (``-0.0`` differs from ``0.0``, a NaN is equal to itself)."""
    return np.ascontiguousarray(a).view(np.uint8)


@settings(max_examples=100, deadline=None)
@given(case=plane_marches())
def test_plane_march_equals_the_twin_bit_for_bit_on_arrays_of_1_to_40_elements(case):
    """Every output, exactly (``-0.0`` apart from ``0.0``), recording every element or the totals only, on
    arrays of any size and on lattice paths where stretches vanish and trial forces land on the disc's edge."""
    model, t, n, s0 = case
    steps, J = t.shape[0], model.elements
    want = _kernels.march_plane_reference(model.kt, model.kn, model.gaps, model.mu, t, n, s0)
    shapes = ((steps, 2), (steps,), (steps,), (steps, J, 2), (steps, J), (J, 2))
    want = [np.array(w, dtype=np.int8 if i == 4 else float).reshape(shape)
            for i, (w, shape) in enumerate(zip(want, shapes))]
    for per_element in (True, False):
        got = compiled_plane(model, t, n, s0, per_element)
        for i, (a, b) in enumerate(zip(got, want)):
            if per_element or i not in (3, 4):
                np.testing.assert_array_equal(bits(a), bits(b))
