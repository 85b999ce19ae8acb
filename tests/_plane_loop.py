"""The march on the contact plane one element at a time, compiled (tests only).

:func:`march_plane_elementwise` is the loop :func:`microslip.kernels.element.march_plane` ran before it was
written in vector form (:mod:`microslip.kernels.plane_lanes`): each element through
:func:`microslip.kernels.element.plane_step`, one at a time, the sums added in element order. Compiled, so
that the vector form can be compared with it bit for bit on many long marches of up to 40 elements
(the pure-Python twin, :func:`microslip.kernels.element.march_plane_reference`, is too slow for that).
"""

from __future__ import annotations

import numba as nb
import numpy as np

from microslip.kernels.element import OPEN, SLIP, STICK, plane_step, plane_work


@nb.njit(nogil=True, error_model="numpy")
def march_plane_elementwise(kt, kn, gaps, mu, t, n, s, T, N, W, Ti, cond):  # pragma: no cover - compiled
    """:func:`microslip.kernels.element.march_plane` one element at a time: the same arguments, the same numbers.

    Each step updates the elements in one loop into scratch rows, copies the
    records from the rows, then adds the rows in element order.
    """
    work = W.shape[0] > 0
    elements = Ti.shape[0] > 0
    J = kt.shape[0]
    scratch = np.empty((7, J))
    sx = scratch[0]  # the sliders, one component per row (contiguous: the element loop vectorises)
    sy = scratch[1]
    fx = scratch[2]
    fy = scratch[3]
    fn = scratch[4]
    fw = scratch[5]
    slips = scratch[6]  # 1.0 where the element slipped (a float row: an int8 one stops the vectorisation)
    sx[:] = s[:, 0]
    sy[:] = s[:, 1]
    for k in range(t.shape[0]):
        tx = t[k, 0]
        ty = t[k, 1]
        nk = n[k]
        for i in range(J):  # no store into the strided records here: that would stop the vectorisation
            sx_old = sx[i]
            sy_old = sy[i]
            Tx, Ty, Ni, code, sx[i], sy[i], _, _ = plane_step(kt[i], mu * kn[i] / kt[i], mu * kn[i], kn[i],
                                                              nk - gaps[i], tx, ty, sx_old, sy_old)
            fx[i] = Tx
            fy[i] = Ty
            fn[i] = Ni
            slips[i] = 1.0 if code == SLIP else 0.0
            fw[i] = plane_work(Tx, Ty, sx_old, sy_old, sx[i], sy[i])  # always: a branch here slows the loop
        if elements:
            for i in range(J):
                Ti[k, i, 0] = fx[i]
                Ti[k, i, 1] = fy[i]
                cond[k, i] = OPEN if fn[i] == 0.0 else (SLIP if slips[i] > 0.0 else STICK)
        txsum = 0.0
        tysum = 0.0
        nsum = 0.0
        for i in range(J):
            txsum += fx[i]
            tysum += fy[i]
            nsum += fn[i]
        T[k, 0] = txsum
        T[k, 1] = tysum
        N[k] = nsum
        if work:
            wsum = 0.0
            for i in range(J):
                wsum += fw[i]
            W[k] = wsum
    s[:, 0] = sx
    s[:, 1] = sy
