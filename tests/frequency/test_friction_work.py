"""The compiled energy dissipated per cycle by each contact equals a NumPy twin of its definition."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from microslip import Sphere, tune
from microslip.kernels.element import NO_CONDITIONS, NO_ELEMENTS, STICK, march
from microslip.kernels.aft import tables
from microslip.frequency.aft import friction_work, friction_work_plane, friction_work_plane_reference, pack_models

SPHERE = Sphere.paper()
MODELS = [tune(SPHERE, 37.5, elements=J) for J in (1, 4, 8, 3)]
APPROACH = float(SPHERE.approach(37.5))  # m
SLIP = float(SPHERE.gross_slip_displacement(37.5))  # m


def twin(models, xt, xn, synthesis, max_periods):
    """The definition step by step in NumPy: one contact at a time, periods until the sliders repeat."""
    work, opens = np.zeros(len(models)), np.zeros(len(models), dtype=bool)
    for c, m in enumerate(models):
        t, n = synthesis @ xt[c], synthesis @ xn[c]
        opens[c] = bool(np.any((n.min() <= m.gaps) & (n.max() > m.gaps)))
        s = np.zeros(m.elements)
        one = np.empty(1)
        march(m.kt, m.kn, m.gaps, m.mu, np.array([xt[c, 0]]), np.array([xn[c, 0]]), s, one, one.copy(),
              np.empty(0), NO_ELEMENTS, NO_CONDITIONS)
        Ti, cond = np.empty((t.size, m.elements)), np.empty((t.size, m.elements), dtype=np.int8)
        for _ in range(max_periods):
            before = s.copy()
            march(m.kt, m.kn, m.gaps, m.mu, t, n, s, np.empty(t.size), np.empty(t.size), np.empty(0), Ti, cond)
            if np.array_equal(before, s):
                break
        slider = t[:, None] - Ti / m.kt
        steps = 0.5 * (Ti + np.roll(Ti, 1, axis=0)) * (slider - np.roll(slider, 1, axis=0))
        work[c] = np.maximum(steps, 0.0)[cond != STICK].sum()
    return work, opens


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2 ** 32 - 1), st.floats(0.05, 4.0), st.floats(0.0, 1.2))
def test_the_compiled_friction_work_equals_its_twin(seed, size, swing):
    """From stick to gross slip (``size`` times the slip displacement) and with the contacts opening
    (``swing`` of the mean approach); the sums differ only in their order: 1e-12 of the largest."""
    rng = np.random.default_rng(seed)
    H, Ns = 3, 128
    E = tables(H, Ns)[0]
    xt = rng.normal(size=(len(MODELS), 2 * H + 1)) * size * SLIP
    xn = rng.normal(size=(len(MODELS), 2 * H + 1)) * swing * APPROACH / 3
    xn[:, 0] = APPROACH
    work, opens = friction_work(pack_models(MODELS), xt, xn, E, 1000)
    ref, ref_opens = twin(MODELS, xt, xn, E, 1000)
    np.testing.assert_array_equal(opens, ref_opens)
    assert (work >= 0).all()
    np.testing.assert_allclose(work, ref, rtol=0, atol=1e-12 * max(ref.max(), 1e-300))


def test_no_contacts_dissipate_nothing():
    work, opens = friction_work(pack_models([]), np.zeros((0, 7)), np.zeros((0, 7)), tables(3, 64)[0], 10)
    assert work.shape == (0,) and opens.shape == (0,)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2 ** 32 - 1), st.floats(0.05, 4.0), st.floats(0.0, 1.2))
def test_the_compiled_friction_work_on_planes_equals_its_twin(seed, size, swing):
    """Contacts moving on their planes (every other one; the others' entries left as they were), from stick to
    gross slip and opening: the compiled batch equals the NumPy loop over contacts to the order of the sums
    (1e-12 of the largest), and a contact on its plane moved along one direction dissipates what
    :func:`friction_work` gives for that direction."""
    rng = np.random.default_rng(seed)
    H, Ns = 3, 128
    E = tables(H, Ns)[0]
    nc = len(MODELS)
    xt, xt2 = (rng.normal(size=(nc, 2 * H + 1)) * size * SLIP for _ in range(2))
    xn = rng.normal(size=(nc, 2 * H + 1)) * swing * APPROACH / 3
    xn[:, 0] = APPROACH
    planar = np.arange(nc) % 2 == 0
    packed = pack_models(MODELS)
    work, opens = np.full(nc, -1.0), np.zeros(nc, dtype=bool)
    ref, ref_opens = work.copy(), opens.copy()
    friction_work_plane(packed, planar, xt, xt2, xn, E, 1000, work, opens)
    friction_work_plane_reference(packed, planar, xt, xt2, xn, E, 1000, ref, ref_opens)
    np.testing.assert_array_equal(opens, ref_opens)
    assert (work[planar] >= 0).all() and (work[~planar] == -1.0).all()
    np.testing.assert_allclose(work, ref, rtol=0, atol=1e-12 * max(ref.max(), 1e-300))
    along, _ = friction_work(packed, xt, xn, E, 1000)
    flat = np.zeros(nc)
    friction_work_plane(packed, planar, xt, np.zeros_like(xt2), xn, E, 1000, flat, opens)
    np.testing.assert_allclose(flat[planar], along[planar], rtol=1e-9, atol=1e-12 * max(along.max(), 1e-300))
