"""Invariants of the microslip array on random models and random load paths (hypothesis).

The element update is a projection ("clamp") of the slider position onto the
interval ``[t - mu N_i / kt_i, t + mu N_i / kt_i]``; most bounds below follow
from that, and the comments say how.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from _strategies import UM, lengths_array, models, paths
from microslip.model import OPEN

EPS = np.finfo(float).eps


@settings(max_examples=100, deadline=None)
@given(model=models(), path=paths())
def test_friction_law_and_non_negative_normal_forces(model, path):
    r = model.simulate(*path)
    Ni = r.Ni
    assert (Ni >= 0).all() and (r.N >= 0).all()
    # The element force is the trial force clipped to +-mu*N_i, and Response.Ni repeats the
    # kernel's arithmetic, so the element bound holds exactly, without tolerance.
    assert (np.abs(r.Ti) <= model.mu * Ni).all()
    # The totals are sums of J terms: each sum (T, N) has a relative rounding error of at
    # most (J - 1) eps of the sum of magnitudes, and mu * sum(N_i) differs from
    # sum(mu * N_i) by another J eps, hence the tolerance 4 J eps (mu N); below the smallest normal
    # float (subnormal forces, ~1e-308 N) rounding is absolute, hence the floor of J such units.
    assert (np.abs(r.T) <= model.mu * r.N * (1 + 4 * model.elements * EPS)
            + 4 * model.elements * np.finfo(float).tiny).all()
    # an element without normal force is open and carries nothing
    open_ = r.condition == OPEN
    np.testing.assert_array_equal(open_, Ni == 0)
    assert (r.Ti[open_] == 0).all()


def periodic_response(model, t, n, max_periods=4):
    """Run the closed path ``(t, n)`` (one period, the last sample closing it) until the state
    repeats; return the response over the last period and the number of periods run."""
    state = model.simulate(t, n).state
    for periods in range(2, max_periods + 1):
        r = model.simulate(t, n, state)
        if np.array_equal(r.state.sliders, state.sliders):
            return r, periods
        state = r.state
    raise AssertionError(f"the state did not become periodic within {max_periods} periods")


def work_over_period(r):
    """Trapezoidal ∫ T dt over one period; the period's last sample also precedes its first."""
    t = np.concatenate([[r.t[-1]], r.t])
    T = np.concatenate([[r.T[-1]], r.T])
    return float(np.trapezoid(T, t)), float(np.sum(np.abs(T[1:] * np.diff(t))))


@st.composite
def closed_paths(draw, staircase=False, constant_n=False):
    """Vertices of a closed path; the march returns to its first vertex at the end of a period."""
    size = draw(st.integers(2, 8))
    t = lengths_array(draw, size, -3 * UM, 3 * UM)
    n = lengths_array(draw, size, -0.5 * UM, 3 * UM)
    if constant_n:
        n[:] = n[0]
    if staircase:
        # t moves at constant n, then n moves at constant t: (t0, n_last), (t0, n0), (t1, n0), ...
        t, n = np.repeat(t, 2), np.roll(np.repeat(n, 2), 1)
    return t, n


@settings(max_examples=100, deadline=None)
@given(model=models(), path=st.one_of(closed_paths(constant_n=True), closed_paths(staircase=True)))
def test_dissipation_is_non_negative_when_n_holds_still_while_t_moves(model, path):
    """Per element and step, the trapezoidal work ½(T_{k-1}+T_k)(t_k-t_{k-1}) equals the change of
    the stored energy T²/(2 kt) plus ½(T_{k-1}+T_k)(s_k-s_{k-1}). At constant n a slip moves the
    slider in the direction of T_k and |T_{k-1}| <= mu N_i = |T_k|, so the last term is >= 0; on a
    step of n at constant t the trial force is T_{k-1}, of the sign of T_k and of the slider's move.
    Over a period the stored energy returns, so the work is >= 0 up to the rounding of the sum."""
    r, _ = periodic_response(model, *path)
    work, magnitude = work_over_period(r)
    assert work >= -8 * r.t.size * EPS * magnitude


@settings(max_examples=100, deadline=None)
@given(model=models(), path=closed_paths())
def test_dissipation_over_any_closed_path_is_bounded_below(model, path):
    """On a general path (t and n moving together) the term ½(T_{k-1}+T_k)(s_k-s_{k-1}) above can be
    negative only on a step that reverses an element from one sign to slip in the other; then
    |T_{k-1}| <= kt |Δt| and |Δs| <= |Δt|, so the term is >= -½ kt Δt². Hence the work over a period
    is >= -½ sum(kt) sum(Δt²), which vanishes as the path is refined (O(1/m) for m sub-steps):
    the continuous model never produces energy. The state is periodic after one period, because
    the period's update of each slider is a composition of clamps, itself a clamp."""
    t, n = path
    for m in (1, 16):
        tc, nc = np.concatenate([[t[-1]], t]), np.concatenate([[n[-1]], n])
        tr, nr = refine(tc, nc, m)
        r, periods = periodic_response(model, tr, nr)
        assert periods == 2
        work, magnitude = work_over_period(r)
        dt = np.diff(np.concatenate([[tr[-1]], tr]))
        bound = 0.5 * model.kt.sum() * np.sum(dt**2)
        assert work >= -bound - 8 * tr.size * EPS * magnitude


def refine(t, n, m):
    """Split each segment of the path (t[k-1], n[k-1]) -> (t[k], n[k]) into m equal sub-steps.

    Returns the refined path without its first sample; the original samples
    t[1:], n[1:] sit at indices m-1, 2m-1, ... (np.linspace keeps the end points exact).
    """
    tr = np.concatenate([np.linspace(t[k], t[k + 1], m + 1)[1:] for k in range(t.size - 1)])
    nr = np.concatenate([np.linspace(n[k], n[k + 1], m + 1)[1:] for k in range(n.size - 1)])
    return tr, nr


@settings(max_examples=60, deadline=None)
@given(model=models(), path=paths(min_size=2, max_size=10))
def test_response_converges_as_the_path_is_refined(model, path):
    """Error bound: within a straight sub-step the exact slider is swept by the moving interval
    [t - mu N_i/kt, t + mu N_i/kt], whose ends are linear in the sub-step except at the kink
    where the element opens or closes (at most once per segment). The discrete clamp is exact
    when the ends move monotonically, and otherwise off by at most their variation,
    kt|Δt| + mu kn|Δn| in force; the errors of clamps add without growing (a clamp is
    1-Lipschitz). So |T_m - T_exact| <= (sum(kt) TV(t) + mu sum(kn) TV(n)) / m at the samples."""
    t, n = path
    t0, n0 = np.concatenate([[0.0], t]), np.concatenate([[n[0]], n])
    tv = model.kt.sum() * np.abs(np.diff(t0)).sum() + model.mu * model.kn.sum() * np.abs(np.diff(n0)).sum()
    fine = 1024
    T_fine = model.simulate(*refine(t0, n0, fine)).T[fine - 1::fine]
    rounding = 1e-9 * (model.mu * model.normal_force(n0.max()) + model.kt.sum() * np.abs(t0).max())
    for m in (1, 4, 32):
        T_m = model.simulate(*refine(t0, n0, m)).T[m - 1::m]
        err = np.abs(T_m - T_fine).max()
        assert err <= tv * (1 / m + 1 / fine) + rounding


@settings(max_examples=60, deadline=None)
@given(model=models(), path=paths(min_size=2, max_size=10))
def test_refinement_is_exact_at_constant_normal_load(model, path):
    """At constant n the interval ends move monotonically on every straight sub-step, so the
    refined march is exact: equal at the shared samples up to rounding (the slider after a
    slip, t - mu N_i/kt, is recomputed at each sub-step: a few ulps of the force scale)."""
    t, _ = path
    n = path[1][0]
    t0 = np.concatenate([[0.0], t])
    coarse = model.simulate(t, n)
    scale = model.mu * model.normal_force(n) + model.kt.sum() * np.abs(t0).max()
    for m in (2, 7, 64):
        tr, _ = refine(t0, t0, m)
        fine = model.simulate(tr, n)
        np.testing.assert_allclose(fine.T[m - 1::m], coarse.T, rtol=0, atol=1e-12 * scale)
        np.testing.assert_allclose(fine.Ti[m - 1::m], coarse.Ti, rtol=0, atol=1e-12 * scale)


@settings(max_examples=60, deadline=None)
@given(model=models(), path=paths(min_size=2, max_size=10), data=st.data())
def test_rate_independence_extra_samples_on_a_straight_segment(model, path, data):
    """Inserting samples anywhere on a straight segment of t at constant n (the load is only
    traversed more finely, at any rate) does not change the response at the original samples."""
    t, n = path
    k = data.draw(st.integers(1, t.size - 1))
    n = n.copy()
    n[k] = n[k - 1]
    fractions = np.sort(data.draw(st.lists(st.floats(0.0, 1.0), min_size=1, max_size=20)))
    inserted = t[k - 1] + fractions * (t[k] - t[k - 1])
    t2 = np.concatenate([t[:k], inserted, t[k:]])
    n2 = np.concatenate([n[:k], np.full(inserted.size, n[k]), n[k:]])
    keep = np.r_[0:k, k + inserted.size:t2.size]
    base = model.simulate(t, n)
    dense = model.simulate(t2, n2)
    scale = model.mu * model.normal_force(n.max()) + model.kt.sum() * np.abs(t).max()
    np.testing.assert_allclose(dense.T[keep], base.T, rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(dense.state.sliders, base.state.sliders, rtol=1e-12, atol=1e-12 * 3 * UM)


@settings(max_examples=100, deadline=None)
@given(model=models(), path=paths(min_size=1, max_size=40))
def test_friction_work_is_never_negative_on_any_path(model, path):
    """Friction dissipates, on any path, closed or not, whatever the normal approach does: every
    slider moves the way its force points. Checked independently of the kernel's own bookkeeping:
    each slider position is rebuilt from the element forces, ``s = t - T_i / kt_i`` (exact in slip;
    in stick, and for an open element, equal to the held position up to the rounding of that
    formula), and the product of each force with its slider's travel must not be negative beyond
    that rounding; the kernel's per-step friction work must equal the sum of those products."""
    t, n = path
    r = model.simulate(t, n)
    s = t[:, None] - r.Ti / model.kt                      # (steps, J) rebuilt slider positions
    s_prev = np.vstack([np.zeros((1, model.elements)), s[:-1]])  # every slider starts at 0
    power = r.Ti * (s - s_prev)                           # force times travel, per element and step
    # rounding of both rebuilt positions: a few ulps of the |t| and |T_i| / kt_i they come from, times |T_i|
    scale = np.abs(t)[:, None] + np.abs(r.Ti) / model.kt
    scale_prev = np.vstack([np.zeros((1, model.elements)), scale[:-1]])
    tol = 8 * EPS * np.abs(r.Ti) * (scale + scale_prev)
    assert (power >= -tol).all()
    np.testing.assert_allclose(r.friction_work, np.maximum(power, 0.0).sum(axis=1),
                               rtol=0, atol=float(tol.sum(axis=1).max()) + 1e-300)
    assert (r.friction_work >= 0).all() and r.dissipation >= 0


@settings(max_examples=60, deadline=None)
@given(model=models(), path=closed_paths(constant_n=True))
def test_dissipation_per_cycle_at_constant_n_does_not_depend_on_the_steps(model, path):
    """At constant n the friction work of a step is the exact dissipation of the continuous model
    for a displacement linear between the samples, so the steady cycle's dissipation is the same
    however finely the path is sampled (up to the rounding of the sums), and the trapezoidal work
    over the cycle converges to it."""
    t, n = path
    tc, nc = np.concatenate([[t[-1]], t]), np.concatenate([[n[-1]], n])
    results = {}
    for m in (1, 7, 200):
        tr, nr = refine(tc, nc, m)
        results[m], _ = periodic_response(model, tr, nr)
    scale = model.mu * model.kn.sum() * (np.abs(n).max() + np.abs(model.gaps).max()) * np.abs(t).max() * t.size
    for m in (7, 200):
        assert abs(results[m].dissipation - results[1].dissipation) <= 1e-9 * scale + 1e-30
    # trapezoidal work on 200 sub-steps: its error is at most one slip kink per element and segment,
    # each worth below (sum kt) h^2 / 2 with h the sub-step; the bound below is that estimate
    fine = results[200]
    work, _ = work_over_period(fine)
    h = np.abs(np.diff(np.concatenate([[fine.t[-1]], fine.t]))).max()
    assert abs(work - fine.dissipation) <= model.kt.sum() * h**2 * t.size * model.elements + 1e-9 * scale
