"""Compiled march of a contact on its plane, sample by sample, from given sliders (private).

The element update is :func:`microslip.kernels.element.plane_step`, the AFT's and
``MicroslipModel.simulate``'s own, so that a period marched here from the AFT's periodic state
(:func:`periodic_state`) repeats the forces harmonic balance used. Used for a
contact's cycle at a point (:mod:`~microslip.frequency.analyses.contact_cycle`), its
friction work per cycle and the time integration of structures with contacts
on their planes (:mod:`~microslip.frequency.analyses.transient`).

Its loop is kept apart from :func:`microslip.kernels.element.march_plane` (the same
step, the same order of the sums, so the same numbers bit for bit): the time
integration calls it once per time step with one sample, where that march's
scratch rows (allocated per call, so that its element loop vectorises) would
cost more than the step, and it takes the sliders as ``(2, J)`` rows.
"""

from __future__ import annotations

import numba as nb
import numpy as np

from .element import plane_step
from .aft import _synthesise
from .aft_plane import _march, march_work, periodic_tolerance

#: an empty array for the per-element records a caller does not want
NO_ELEMENTS = np.empty((0, 0, 2))
NO_CONDITIONS = np.empty((0, 0), dtype=np.int8)


@nb.njit(cache=True, nogil=True, error_model="numpy")
def march_plane(kt, kn, gaps, mu, t1, t2, n, s, T, N, Ti, cond):  # pragma: no cover - compiled
    """March samples ``(t1, t2, n)`` (m) from sliders ``s`` ``(2, J)`` (m, updated in place).

    Writes the total forces ``T`` ``(steps, 2)`` and ``N`` ``(steps,)`` (N);
    unless empty, each element's force ``Ti`` ``(steps, J, 2)`` (N) and
    condition ``cond`` ``(steps, J)`` (0 open, 1 stick, 2 slip).
    """
    record = (Ti.shape[0] > 0, cond.shape[0] > 0)  # each element's force, its condition
    for k in range(t1.shape[0]):
        T[k, 0] = T[k, 1] = N[k] = 0.0
        for i in range(kt.shape[0]):
            mkn = mu * kn[i]
            g1, g2, Ni, c, s[0, i], s[1, i], _, _ = plane_step(kt[i], mkn / kt[i], mkn, kn[i], n[k] - gaps[i], t1[k],
                                                               t2[k], s[0, i], s[1, i])
            N[k] += Ni
            T[k, 0] += g1
            T[k, 1] += g2
            if record[0]:
                Ti[k, i, 0] = g1
                Ti[k, i, 1] = g2
            if record[1]:
                cond[k, i] = c


@nb.njit(cache=True, nogil=True)
def periodic_state(kt, kn, gaps, mu, x1, x2, xn, E, max_periods, s):  # pragma: no cover - compiled
    """The sliders ``s`` ``(2, J)`` (m) at the start of the AFT's periodic period (its march, its tolerance).

    ``x1, x2, xn`` are the coefficients of the motion, ``E`` the synthesis
    table of the samples. Returns the periods marched (``-1``: not periodic
    within ``max_periods``).
    """
    smp = np.empty((3, E.shape[0]))
    _synthesise(E, x1, smp[0])
    _synthesise(E, x2, smp[1])
    _synthesise(E, xn, smp[2])
    return periodic_state_of_samples(kt, kn, gaps, mu, x1[0], x2[0], xn[0], smp[0], smp[1], smp[2], max_periods, s)


@nb.njit(cache=True, nogil=True)
def periodic_state_of_samples(kt, kn, gaps, mu, m1, m2, mn, t1, t2, n, max_periods, s):  # pragma: no cover
    """:func:`periodic_state` of the samples ``t1, t2, n`` of a period whose mean is ``(m1, m2, mn)`` (m)."""
    Ns = t1.shape[0]
    J = kt.shape[0]
    rk = mu * kn / kt
    tol = periodic_tolerance(rk, gaps, t1, t2, n)
    ivec = np.empty((3, J), dtype=np.int64)
    st, rec = march_work(J, Ns)
    x1 = np.array([m1])
    x2 = np.array([m2])
    xn = np.array([mn])
    periods = _march(kt, kn, gaps, mu, rk, x1, x2, xn, t1, t2, n, tol, max_periods, st, rec, ivec[0], ivec[1],
                     ivec[2], np.empty((2, J), dtype=np.int64))
    # the march ends with the periodic period; its start is one period back from the end, to 32 ulps
    s[:] = st[:2, :J]
    return periods


def static_sliders(model, t1, t2, n) -> np.ndarray:
    """The sliders ``(2, J)`` (m) after the static step from the virgin state to ``(t1, t2, n)``."""
    s = np.zeros((2, model.elements))
    march_plane(model.kt, model.kn, model.gaps, model.mu, np.array([t1]), np.array([t2]), np.array([n]), s,
                np.empty((1, 2)), np.empty(1), NO_ELEMENTS, NO_CONDITIONS)
    return s
