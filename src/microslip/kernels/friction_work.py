"""Compiled energy dissipated per cycle by each contact, along one direction or on its plane (private).

Plain float64 arrays in and out; the checked wrappers are
:func:`microslip.frequency.aft.friction_work` and :func:`~microslip.frequency.aft.friction_work_plane`,
which state the definition.
"""

from __future__ import annotations

import numba as nb
import numpy as np

from .element import STICK, march
from .plane_march import march_plane, periodic_state


@nb.njit(cache=True, nogil=True)
def friction_work_batch(kt, kn, gaps, offsets, mu, t, n, t0, n0, max_periods, work, opens):  # pragma: no cover
    """Each contact's friction work per cycle into ``work`` (J) and whether it opens into ``opens``.

    ``t``, ``n`` (shape ``(nc, Ns)``): each contact's samples over the period
    (m); ``t0``, ``n0`` (``(nc,)``): their means, the static step from the
    virgin state; the elements of contact ``c`` are ``offsets[c]:offsets[c+1]``
    of ``kt``, ``kn``, ``gaps`` (N/m, N/m, m). Periods are marched from the
    static state until the sliders repeat (at most ``max_periods``), then the
    last period's steps give the work, as :func:`~microslip.frequency.aft.friction_work`
    describes.
    """
    nc = offsets.shape[0] - 1
    Ns = t.shape[1]
    one_t, one_n = np.empty(1), np.empty(1)
    T1, N1 = np.empty(1), np.empty(1)
    T, N = np.empty(Ns), np.empty(Ns)
    no_work = np.empty(0)
    no_elements = np.empty((0, 0))
    no_conditions = np.empty((0, 0), dtype=np.int8)
    for c in range(nc):
        lo, hi = offsets[c], offsets[c + 1]
        J = hi - lo
        k, kn_c, g = kt[lo:hi], kn[lo:hi], gaps[lo:hi]
        t_c, n_c = t[c], n[c]
        n_min, n_max = n_c.min(), n_c.max()
        opens[c] = False
        for i in range(J):
            if n_min <= g[i] and n_max > g[i]:
                opens[c] = True
        s = np.zeros(J)
        one_t[0], one_n[0] = t0[c], n0[c]
        march(k, kn_c, g, mu[c], one_t, one_n, s, T1, N1, no_work, no_elements, no_conditions)
        Ti = np.empty((Ns, J))
        cond = np.empty((Ns, J), dtype=np.int8)
        before = np.empty(J)
        for _ in range(max_periods):
            before[:] = s
            march(k, kn_c, g, mu[c], t_c, n_c, s, T, N, no_work, Ti, cond)
            same = True
            for i in range(J):
                if before[i] != s[i]:
                    same = False
                    break
            if same:
                break
        total = 0.0
        for m in range(Ns):
            p = m - 1 if m > 0 else Ns - 1  # the step into sample 0 starts from the last sample
            for i in range(J):
                if cond[m, i] != STICK:  # the slider at each sample: T = kt (t - s) in every condition
                    step = 0.5 * (Ti[m, i] + Ti[p, i]) * ((t_c[m] - Ti[m, i] / k[i]) - (t_c[p] - Ti[p, i] / k[i]))
                    total += max(step, 0.0)
        work[c] = total


@nb.njit(cache=True, nogil=True)
def friction_work_plane_batch(kt, kn, gaps, offsets, mu, planar, xt, xt2, xn, synthesis, max_periods, work, opens,
                              periods):  # pragma: no cover - compiled
    """:func:`friction_work_batch` of the contacts that move on their planes (``planar[c]``), from the coefficients
    ``xt``, ``xt2``, ``xn`` (``(nc, 2H+1)``, m) and the synthesis table ``(Ns, 2H+1)``: the AFT's periodic
    state, one period marched, the work ``(T_k-1 + T_k) . (s_k - s_k-1) / 2`` of each element's force on its
    slider's travel summed over the steps where the slider moves, each step's floored at zero. ``periods[c]``
    receives the periods the state took (``-1``: not periodic within ``max_periods``; its work is not written).
    """
    Ns = synthesis.shape[0]
    for c in range(offsets.shape[0] - 1):
        if not planar[c]:
            continue
        lo, hi = offsets[c], offsets[c + 1]
        J = hi - lo
        k, kn_c, g = kt[lo:hi], kn[lo:hi], gaps[lo:hi]
        s = np.empty((2, J))
        periods[c] = periodic_state(k, kn_c, g, mu[c], xt[c], xt2[c], xn[c], synthesis, max_periods, s)
        if periods[c] < 0:
            continue
        t1, t2, n = synthesis @ xt[c], synthesis @ xt2[c], synthesis @ xn[c]
        n_min, n_max = n.min(), n.max()
        opens[c] = False
        for i in range(J):
            if n_min <= g[i] and n_max > g[i]:
                opens[c] = True
        Ti, cond = np.empty((Ns, J, 2)), np.empty((Ns, J), dtype=np.int8)
        march_plane(k, kn_c, g, mu[c], t1, t2, n, s, np.empty((Ns, 2)), np.empty(Ns), Ti, cond)
        total = 0.0
        for m in range(Ns):
            p = m - 1 if m > 0 else Ns - 1  # the step into sample 0 starts from the last sample
            for i in range(J):
                if cond[m, i] != STICK:  # the slider at each sample: T = kt (t - s) in every condition
                    step = 0.5 * ((Ti[m, i, 0] + Ti[p, i, 0]) * ((t1[m] - Ti[m, i, 0] / k[i])
                                                                 - (t1[p] - Ti[p, i, 0] / k[i]))
                                  + (Ti[m, i, 1] + Ti[p, i, 1]) * ((t2[m] - Ti[m, i, 1] / k[i])
                                                                   - (t2[p] - Ti[p, i, 1] / k[i])))
                    total += max(step, 0.0)
        work[c] = total
