"""Compiled explicit time integration of a structure with microslip contacts (private).

Central differences: with ``A = M/dt^2 + C/(2 dt)``,

``A q[k+1] = f[k] - K q[k] - F_c(q[k]) + (2 M/dt^2) q[k] - (M/dt^2 - C/(2 dt)) q[k-1]``

where ``F_c`` are the contact forces, marched one step with the same kernel
as :meth:`microslip.MicroslipModel.simulate` (:func:`microslip.kernels.element.march`).
Stable for ``dt < 2 / omega_max``.
"""

from __future__ import annotations

import numba as nb
import numpy as np

from .element import march, march_reference


@nb.njit(cache=True, nogil=True, inline="always")
def linear_rhs(fk, K, B1, B0, q, q_prev, rhs):  # pragma: no cover - compiled
    """``rhs = f_k - K q + B1 q - B0 q_prev``: the step's right-hand side before the contact forces."""
    ndof = q.shape[0]
    for i in range(ndof):
        acc = fk[i]
        for j in range(ndof):
            acc += (B1[i, j] - K[i, j]) * q[j] - B0[i, j] * q_prev[j]
        rhs[i] = acc


@nb.njit(cache=True, nogil=True, inline="always")
def advance(A_inv, rhs, q_prev, q, q_next, out_k):  # pragma: no cover - compiled
    """``q_next = A_inv rhs``, then ``(q_prev, q) <- (q, q_next)`` and ``out_k = q_next``."""
    ndof = q.shape[0]
    for i in range(ndof):
        acc = 0.0
        for j in range(ndof):
            acc += A_inv[i, j] * rhs[j]
        q_next[i] = acc
    for i in range(ndof):
        q_prev[i] = q[i]
        q[i] = q_next[i]
        out_k[i] = q_next[i]


@nb.njit(cache=True, nogil=True)
def integrate(A_inv, K, B1, B0, force, Bt, Bn, n0, kt, kn, gaps, offsets, mu, sliders,
              q_prev, q, steps, out):  # pragma: no cover - compiled
    """March ``steps`` steps; ``q_prev``, ``q`` and ``sliders`` are updated in place.

    ``B1 = 2 M / dt^2``, ``B0 = M / dt^2 - C / (2 dt)``; ``force`` has shape
    ``(period_steps, ndof)`` and is used cyclically from row 0; ``out``
    (``steps, ndof``) receives ``q`` after each step.
    """
    ndof = q.shape[0]
    nc = Bt.shape[1]
    period = force.shape[0]
    rhs = np.empty(ndof)
    t1 = np.empty(1)
    n1 = np.empty(1)
    T1 = np.empty(1)
    N1 = np.empty(1)
    W1 = np.empty(0)  # friction work and element forces not recorded
    no_el = np.empty((0, 0))
    no_cond = np.empty((0, 0), dtype=np.int8)
    q_next = np.empty(ndof)
    for k in range(steps):
        linear_rhs(force[k % period], K, B1, B0, q, q_prev, rhs)
        for c in range(nc):
            tc = 0.0
            nc_ = n0[c]
            for i in range(ndof):
                tc += Bt[i, c] * q[i]
                nc_ += Bn[i, c] * q[i]
            t1[0] = tc
            n1[0] = nc_
            lo = offsets[c]
            hi = offsets[c + 1]
            march(kt[lo:hi], kn[lo:hi], gaps[lo:hi], mu[c], t1, n1, sliders[lo:hi], T1, N1, W1, no_el, no_cond)
            for i in range(ndof):
                rhs[i] -= Bt[i, c] * T1[0] + Bn[i, c] * N1[0]
        advance(A_inv, rhs, q_prev, q, q_next, out[k])


def integrate_reference(A_inv, K, B1, B0, force, Bt, Bn, n0, models, sliders, q_prev, q, steps):
    """Slow, obviously correct pure-Python twin of :func:`integrate` (tests only).

    ``models`` is the list of contact models; ``sliders`` a list of arrays.
    Returns ``(out, q_prev, q, sliders)`` without modifying the inputs.
    """
    q_prev = np.array(q_prev, float)
    q = np.array(q, float)
    sliders = [np.array(s, float) for s in sliders]
    out = []
    for k in range(steps):
        rhs = force[k % len(force)] - K @ q + B1 @ q - B0 @ q_prev
        for c, model in enumerate(models):
            t = float(Bt[:, c] @ q)
            n = float(Bn[:, c] @ q + n0[c])
            T, N, _, _, _, sliders[c] = march_reference(model.kt, model.kn, model.gaps, model.mu, [t], [n], sliders[c])
            rhs = rhs - Bt[:, c] * T[0] - Bn[:, c] * N[0]
        q_prev, q = q, A_inv @ rhs
        out.append(q.copy())
    return np.array(out), q_prev, q, [np.asarray(s) for s in sliders]
