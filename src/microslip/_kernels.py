"""Compiled time-marching kernels of the microslip array (private).

Plain float64 arrays in, arrays out; no input checks here: the public
wrappers in :mod:`microslip.model` check everything before calling.

Each step follows the return mapping of DESIGN.md section 2 exactly::

    N_i   = kn_i * max(n - gaps_i, 0)
    trial = kt_i * (t - s_i)
    if |trial| > mu * N_i:  T_i = sign(trial) mu N_i,  s_i = t - T_i / kt_i   (slip)
    else:                   T_i = trial                                       (stick)

An element with ``N_i = 0`` is reported as open; numerically it follows the
same rule (its force is zero and its slider sits at ``t``).
"""

from __future__ import annotations

import numba as nb
import numpy as np

OPEN = 0
STICK = 1
SLIP = 2


@nb.njit(cache=True, nogil=True, inline="always")
def element_step(kt, kn, gap, mu, t, n, s):  # pragma: no cover - compiled
    """One element, one step: returns ``(T_i, N_i, slipped, new slider)``.

    Branch-free form of the return mapping: clipping the trial force to
    ``[-mu N_i, mu N_i]`` is the slip rule, and the slider moves only when
    the clip changed the force. Same arithmetic as the pure-Python twin.
    The slider lands at ``t - T_i / kt_i``, a function of the sample alone,
    so a periodic history gives an exactly periodic state.
    """
    Ni = kn * max(n - gap, 0.0)
    lim = mu * Ni
    trial = kt * (t - s)
    Ti = min(max(trial, -lim), lim)
    slipped = Ti != trial
    return Ti, Ni, slipped, (t - Ti / kt if slipped else s)


@nb.njit(cache=True, nogil=True, inline="always")
def friction_work(Ti, s_old, s_new):  # pragma: no cover - compiled
    """Work of the element's force on its slider's travel in one step (J).

    Zero in stick; in slip positive, since the slider moves the way the
    force points (the ``max`` only absorbs a rounding of the last unit when
    the travel is a few ulps). At constant ``N_i`` it is the exact
    dissipation of the step for a displacement linear between the samples.
    """
    return max(Ti * (s_new - s_old), 0.0)


@nb.njit(cache=True, nogil=True)
def march(kt, kn, gaps, mu, t, n, s, T, N, W, Ti, cond):  # pragma: no cover - compiled
    """March ``t``, ``n`` from slider state ``s`` (updated in place).

    Writes the total forces into ``T`` and ``N`` (shape ``(steps,)``) and,
    unless they are empty, the friction work of each step into ``W``
    (``(steps,)``), each element's force into ``Ti`` (``(steps, J)``,
    float64) and its condition into ``cond`` (``(steps, J)``, int8: 0 open,
    1 stick, 2 slip). What is recorded is fixed for the whole march, so the
    compiler splits the loop on it and an unrecorded output costs nothing.
    """
    work = W.shape[0] > 0
    elements = Ti.shape[0] > 0
    for k in range(t.shape[0]):
        tsum = 0.0
        nsum = 0.0
        wsum = 0.0
        for i in range(kt.shape[0]):
            s_old = s[i]
            Tk, Ni, slipped, s[i] = element_step(kt[i], kn[i], gaps[i], mu, t[k], n[k], s_old)
            tsum += Tk
            nsum += Ni
            if work:
                wsum += friction_work(Tk, s_old, s[i])
            if elements:
                Ti[k, i] = Tk
                cond[k, i] = (Ni > 0.0) * (1 + slipped)
        T[k] = tsum
        N[k] = nsum
        if work:
            W[k] = wsum


NO_WORK = np.empty(0)
NO_ELEMENTS = np.empty((0, 0))
NO_CONDITIONS = np.empty((0, 0), dtype=np.int8)


def march_reference(kt, kn, gaps, mu, t, n, s):
    """Slow, obviously correct pure-Python twin of :func:`march`.

    Used only by the tests. Returns ``(T, N, W, Ti, cond, s)`` as lists of
    Python floats and ints (``W``: friction work of each step, the force
    times the slider's travel); ``s`` is not modified.
    """
    s = [float(v) for v in s]
    T, N, W, Ti_all, cond_all = [], [], [], [], []
    for tk, nk in zip(t, n):
        row_T, row_c, row_W = [], [], []
        for i in range(len(kt)):
            Ni = kn[i] * max(nk - gaps[i], 0.0)
            trial = kt[i] * (tk - s[i])
            if abs(trial) > mu * Ni:
                Ti = mu * Ni if trial > 0 else -mu * Ni
                s_new = tk - Ti / kt[i]
                work = max(Ti * (s_new - s[i]), 0.0)
                s[i] = s_new
                c = SLIP
            else:
                Ti = trial
                work = 0.0
                c = STICK
            if Ni == 0.0:
                c = OPEN
            row_T.append(Ti)
            row_c.append(c)
            row_W.append(work)
        Ti_all.append(row_T)
        cond_all.append(row_c)
        T.append(sum(row_T))
        N.append(sum(kn[i] * max(nk - gaps[i], 0.0) for i in range(len(kt))))
        W.append(sum(row_W))
    return T, N, W, Ti_all, cond_all, s


def warm_up() -> None:
    """Compile (or load from cache) the kernel on a tiny input."""
    one = np.ones(1)
    z = np.zeros(1)
    march(one, one, z, 0.5, z, one, np.zeros(1), np.empty(1), np.empty(1), np.empty(1),
          np.empty((1, 1)), np.empty((1, 1), dtype=np.int8))
