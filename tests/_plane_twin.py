"""Slow, obviously correct pure-Python twin of the AFT on the contact plane (tests only).

Element by element, sample by sample, with the return mapping written out and
forward-mode derivatives: every slider carries its full gradient with respect
to the coefficients ``(x1, x2, xn)`` through the static step and every period.
Plain periods (no acceleration) until both the slider and its gradient repeat
to rounding; the force samples' gradients are then projected with an explicit
DFT matrix.
"""

from __future__ import annotations

import math

import numpy as np


def basis(nbasis: int, Ns: int) -> np.ndarray:
    """``E[k, q]``: basis function ``q`` (1, cos tau, sin tau, cos 2 tau, ...) at ``tau_k = 2 pi k / Ns``."""
    E = np.empty((Ns, nbasis))
    for k in range(Ns):
        tau = 2.0 * math.pi * k / Ns
        for q in range(nbasis):
            h = (q + 1) // 2
            E[k, q] = 1.0 if q == 0 else (math.cos(h * tau) if q % 2 else math.sin(h * tau))
    return E


def step(kt, kn, gap, mu, t, n, s, dt, dn, ds):
    """One element, one sample, with gradients: ``(T, dT, N, dN, s, ds)``.

    ``t``, ``s`` are 2-vectors; ``dt`` ``(2, m)``, ``dn`` ``(m,)`` and ``ds``
    ``(2, m)`` their gradients with respect to the ``m`` unknowns.
    """
    if n - gap <= 0.0:  # open: no force, the slider follows t
        return np.zeros(2), np.zeros_like(ds), 0.0, np.zeros_like(dn), t.copy(), dt.copy()
    N = kn * (n - gap)
    dN = kn * dn
    r = mu * N / kt  # the stick radius
    dr = mu * dN / kt
    d = t - s
    size = math.hypot(d[0], d[1])
    if size <= r:  # stick
        return kt * d, kt * (dt - ds), N, dN, s.copy(), ds.copy()
    # slip: the trial force kt d returned radially onto the disc of radius mu N
    u = d / size
    grad_d = dt - ds
    du = (np.eye(2) - np.outer(u, u)) @ grad_d / size  # derivative of d / |d|
    T = mu * N * u
    dT = mu * np.outer(u, dN) + mu * N * du
    s_new = t - r * u
    ds_new = dt - np.outer(u, dr) - r * du
    return T, dT, N, dN, s_new, ds_new


def aft_plane_reference(kt, kn, gaps, mu, x1, x2, xn, Ns, max_periods=20000):
    """``(F (3, nb), Jac (3, 3, nb, nb), periods)`` as :func:`microslip.kernels.aft_plane._aft_plane`."""
    x1, x2, xn = (np.asarray(x, float) for x in (x1, x2, xn))
    nb = x1.size
    E = basis(nb, Ns)
    m = 3 * nb
    zero = np.zeros((nb,))
    # samples and their gradients with respect to [x1, x2, xn]
    t = np.stack([E @ x1, E @ x2], axis=1)
    n = E @ xn
    dts = [np.array([np.concatenate([E[k], zero, zero]), np.concatenate([zero, E[k], zero])]) for k in range(Ns)]
    dns = [np.concatenate([zero, zero, E[k]]) for k in range(Ns)]
    e0 = np.eye(nb)[0]
    dt0 = np.array([np.concatenate([e0, zero, zero]), np.concatenate([zero, e0, zero])])
    dn0 = np.concatenate([zero, zero, e0])
    size = max(abs(t[k, 0]) + abs(t[k, 1]) for k in range(Ns))
    rmax = max(mu * kn[i] / kt[i] * (n[k] - gaps[i]) for i in range(len(kt)) for k in range(Ns))
    tol = 32 * np.finfo(float).eps * (size + rmax)
    T = np.zeros((Ns, 2))
    dT = np.zeros((Ns, 2, m))
    N = np.zeros(Ns)
    dN = np.zeros((Ns, m))
    worst = 0
    for i in range(len(kt)):
        s = np.zeros(2)
        ds = np.zeros((2, m))
        _, _, _, _, s, ds = step(kt[i], kn[i], gaps[i], mu, np.array([x1[0], x2[0]]), xn[0], s, dt0, dn0, ds)
        periods = 0
        while True:
            start, dstart = s.copy(), ds.copy()
            rows = []
            for k in range(Ns):
                Ti, dTi, Ni, dNi, s, ds = step(kt[i], kn[i], gaps[i], mu, t[k], n[k], s, dts[k], dns[k], ds)
                rows.append((Ti, dTi, Ni, dNi))
            periods += 1
            if (np.max(np.abs(s - start)) <= tol and np.max(np.abs(ds - dstart)) <= 1e-14 * max(1.0, np.abs(ds).max())):
                break
            if periods >= max_periods:
                worst = -1
                break
        worst = -1 if worst < 0 else max(worst, periods)
        for k, (Ti, dTi, Ni, dNi) in enumerate(rows):
            T[k] += Ti
            dT[k] += dTi
            N[k] += Ni
            dN[k] += dNi
    P = np.linalg.pinv(E)  # the least-squares fit of the kept harmonics to the samples
    F = np.array([P @ T[:, 0], P @ T[:, 1], P @ N])
    Jac = np.zeros((3, 3, nb, nb))
    for a in range(2):
        G = P @ dT[:, a, :]  # (nb, 3 nb)
        for b in range(3):
            Jac[a, b] = G[:, b * nb:(b + 1) * nb]
    G = P @ dN
    Jac[2, 2] = G[:, 2 * nb:]
    return F, Jac, worst


def march_plane_reference(kt, kn, gaps, mu, t1, t2, n, s):
    """Twin of :func:`microslip.kernels.plane_march.march_plane`: ``(T (steps, 2), N, Ti, cond, s)``.

    The radial return written out with plain floats, one element and one sample at a time.
    """
    s = [[float(s[0][i]), float(s[1][i])] for i in range(len(kt))]
    T, N, Ti, cond = [], [], [], []
    for k in range(len(t1)):
        row_T, row_c = [], []
        for i in range(len(kt)):
            Ni = kn[i] * max(n[k] - gaps[i], 0.0)
            if Ni == 0.0:  # open: no force, the slider follows t
                s[i] = [t1[k], t2[k]]
                row_T.append((0.0, 0.0))
                row_c.append(0)
                continue
            trial = (kt[i] * (t1[k] - s[i][0]), kt[i] * (t2[k] - s[i][1]))
            size = math.hypot(*trial)
            if size > mu * Ni:  # slip: back onto the disc of radius mu N_i, along the trial force
                force = (mu * Ni * trial[0] / size, mu * Ni * trial[1] / size)
                s[i] = [t1[k] - force[0] / kt[i], t2[k] - force[1] / kt[i]]
                row_c.append(2)
            else:
                force = trial
                row_c.append(1)
            row_T.append(force)
        Ti.append(row_T)
        cond.append(row_c)
        T.append([sum(f[0] for f in row_T), sum(f[1] for f in row_T)])
        N.append(sum(kn[i] * max(n[k] - gaps[i], 0.0) for i in range(len(kt))))
    return np.array(T), np.array(N), np.array(Ti), np.array(cond), np.array(s).T


def integrate_plane_reference(A_inv, K, B1, B0, force, Bt, Bt2, Bn, n0, models, sliders, q_prev, q, steps):
    """Twin of :func:`microslip.kernels.transient_plane.integrate_plane` (every contact on its plane).

    ``sliders`` is a list of ``(2, J)`` arrays. Returns ``(out, q_prev, q, sliders)``.
    """
    q_prev, q = np.array(q_prev, float), np.array(q, float)
    sliders = [np.array(s, float) for s in sliders]
    out = []
    for k in range(steps):
        rhs = force[k % len(force)] - K @ q + B1 @ q - B0 @ q_prev
        for c, m in enumerate(models):
            T, N, _, _, sliders[c] = march_plane_reference(m.kt, m.kn, m.gaps, m.mu, [Bt[:, c] @ q], [Bt2[:, c] @ q],
                                                           [Bn[:, c] @ q + n0[c]], sliders[c])
            rhs = rhs - Bt[:, c] * T[0, 0] - Bt2[:, c] * T[0, 1] - Bn[:, c] * N[0]
        q_prev, q = q, A_inv @ rhs
        out.append(q.copy())
    return np.array(out), q_prev, q, sliders
