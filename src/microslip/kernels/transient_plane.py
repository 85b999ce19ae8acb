"""Compiled explicit time integration of a structure with contacts on their planes (private).

The scheme of :mod:`microslip.kernels.transient` (central differences), with
each contact either along one direction (:func:`microslip.kernels.element.march`) or
on its plane (:func:`microslip.kernels.plane_march.march_plane`, the
AFT's element update): ``t1 = Bt . q``, ``t2 = Bt2 . q``, and the contact's
force acts along ``Bt T1 + Bt2 T2 + Bn N``. ``sliders`` has shape
``(2, elements)``: both components of every slider (the second unused on a
contact along one direction).
"""

from __future__ import annotations

import numba as nb
import numpy as np

from .element import march
from .plane_march import march_plane
from .transient import advance, linear_rhs


@nb.njit(cache=True, nogil=True)
def integrate_plane(A_inv, K, B1, B0, force, Bt, Bt2, Bn, n0, planar, kt, kn, gaps, offsets, mu, sliders,
                    q_prev, q, steps, out):  # pragma: no cover - compiled
    """March ``steps`` steps; ``q_prev``, ``q`` and ``sliders`` (2, elements) are updated in place.

    As :func:`microslip.kernels.transient.integrate`, with the contacts'
    second directions ``Bt2`` and ``planar`` (bool, ``nc``).
    """
    ndof = q.shape[0]
    nc = Bt.shape[1]
    period = force.shape[0]
    work = np.empty((2, ndof))
    rhs, q_next = work[0], work[1]
    one = np.empty((5, 1))  # a single sample of the march: t1, t2, n, and the forces T1 (one direction), N
    t1, t2, n1, T1, N1 = one[0], one[1], one[2], one[3], one[4]
    T2 = np.empty((1, 2))  # the force on the plane
    W1, no_el, no_el2 = np.empty(0), np.empty((0, 0)), np.empty((0, 0, 2))  # nothing else recorded
    no_cond = np.empty((0, 0), dtype=np.int8)
    for k in range(steps):
        linear_rhs(force[k % period], K, B1, B0, q, q_prev, rhs)
        for c in range(nc):
            a = 0.0
            b = 0.0
            m = n0[c]
            for i in range(ndof):
                a += Bt[i, c] * q[i]
                b += Bt2[i, c] * q[i]
                m += Bn[i, c] * q[i]
            t1[0] = a
            t2[0] = b
            n1[0] = m
            lo = offsets[c]
            hi = offsets[c + 1]
            if planar[c]:
                march_plane(kt[lo:hi], kn[lo:hi], gaps[lo:hi], mu[c], t1, t2, n1, sliders[:, lo:hi], T2, N1,
                            no_el2, no_cond)
                for i in range(ndof):
                    rhs[i] -= Bt[i, c] * T2[0, 0] + Bt2[i, c] * T2[0, 1] + Bn[i, c] * N1[0]
            else:
                march(kt[lo:hi], kn[lo:hi], gaps[lo:hi], mu[c], t1, n1, sliders[0, lo:hi], T1, N1, W1, no_el,
                      no_cond)
                for i in range(ndof):
                    rhs[i] -= Bt[i, c] * T1[0] + Bn[i, c] * N1[0]
        advance(A_inv, rhs, q_prev, q, q_next, out[k])
