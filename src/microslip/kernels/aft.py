"""Compiled alternating frequency--time (AFT) kernel of one microslip contact (private).

Plain float64 arrays in, arrays out; the checked public wrappers are in
:mod:`microslip.frequency.aft`.

Fourier layout. A periodic signal of phase ``tau = omega t`` is stored as the
``nb = 2H + 1`` real coefficients ``[c0, a1, b1, a2, b2, ..., aH, bH]`` of
``c0 + sum_h a_h cos(h tau) + b_h sin(h tau)``. :func:`tables` gives the
synthesis matrix ``E`` (samples at ``tau_k = 2 pi k / Ns``, ``k < Ns``, are
``E @ c``), the projection ``P`` (``P[p, k] = w_p E[k, p]`` with
``w_0 = 1/Ns``, ``w_p = 2/Ns``), the cosines and sines of harmonics
``0..2H`` and ``cum[k, p] = sum_{j < k} P[p, j]``, which projects a run of
samples in O(nb).

The march. The contact is taken closed at ``t = 0`` with no tangential force
(every slider at 0). The static part ``(c0 of t, c0 of n)`` is applied first
as one monotonic step from that virgin state; then whole periods are marched
with the return mapping of :mod:`microslip.kernels.element` until the state at the
end of a period equals the state at its start (each element separately).
That happens after finitely many periods: a slip sets the slider to one of
the ``2 Ns`` values ``t_k -+ mu N_k / kt`` whatever it was before, and the
period map of a play operator (a composition of clips) is non-decreasing, so
the sequence of slider positions is monotone in a finite set and stops. The
comparison is therefore exact, with no tolerance.

Exact derivatives. A slipping element carries ``T_i = sign mu kn_i (n_k - g_i)``,
whose derivative involves ``n`` at the current sample only. A sticking
element carries ``T_i = kt_i (t_k - s_i)``, where the slider was set at its
last slip, sample ``m``: ``s_i = t_m - sign mu kn_i (n_m - g_i) / kt_i``
(``t_m`` if it was open at ``m``). So ``dT_i = kt_i (dt_k - dt_m) + sign mu kn_i dn_m``:
a diagonal part and a part in column ``m``, constant over the stick run. The
last slip may lie in an earlier period (same phase, same basis row) or in the
static step (column ``Ns``, basis row ``e0``); an element that never slipped
keeps ``s_i = 0``. Open elements carry nothing and have no derivative. The
Jacobians are then

* diagonal parts ``P diag(d) E``, from the discrete Fourier transform of
  ``d`` at harmonics ``0..2H`` and product-to-sum identities (O(Ns H + H^2));
* column parts, accumulated per stick run ``a <= k < b`` as ``coef * (cum[b] - cum[a])``
  in column ``m`` and multiplied by the basis row of ``m`` at the end.
"""

from __future__ import annotations

from functools import lru_cache

import numba as nb
import numpy as np

from .element import OPEN, SLIP, STICK

SLIP_NEG = 3  # slip with a negative force (SLIP: positive)
NEVER = -1  # "last slip" of an element that never slipped


@lru_cache(maxsize=32)
def tables(H: int, Ns: int) -> tuple[np.ndarray, ...]:
    """Fourier tables for ``H`` harmonics and ``Ns`` samples (read-only arrays).

    Returns
    -------
    E : ndarray, shape (Ns, 2H+1)
        Synthesis: samples ``= E @ coefficients``.
    P : ndarray, shape (2H+1, Ns)
        Projection: coefficients ``= P @ samples`` (``P @ E = I`` for ``Ns > 2H``).
    cos2, sin2 : ndarray, shape (2H+1, Ns)
        ``cos(j tau_k)``, ``sin(j tau_k)`` for ``j = 0..2H`` (products of two kept harmonics).
    cum : ndarray, shape (Ns+1, 2H+1)
        ``cum[k] = P[:, :k].sum(axis=1)``.
    """
    tau = 2.0 * np.pi * np.arange(Ns) / Ns
    nbasis = 2 * H + 1
    j = np.arange(nbasis)
    cos2 = np.cos(np.outer(j, tau))
    sin2 = np.sin(np.outer(j, tau))
    E = np.empty((Ns, nbasis))
    E[:, 0] = 1.0
    E[:, 1::2] = cos2[1:H + 1].T
    E[:, 2::2] = sin2[1:H + 1].T
    w = np.full(nbasis, 2.0 / Ns)
    w[0] = 1.0 / Ns
    P = np.ascontiguousarray(E.T * w[:, None])
    cum = np.zeros((Ns + 1, nbasis))
    np.cumsum(P.T, axis=0, out=cum[1:])
    out = (np.ascontiguousarray(E), P, cos2, sin2, cum)
    for a in out:
        a.setflags(write=False)
    return out


@nb.njit(cache=True, nogil=True, fastmath=True)
def _synthesise(E, x, out):  # pragma: no cover - compiled
    for k in range(E.shape[0]):
        acc = 0.0
        for q in range(E.shape[1]):
            acc += E[k, q] * x[q]
        out[k] = acc


@nb.njit(cache=True, nogil=True, fastmath=True)
def _dft(cos2, sin2, d, C, S):  # pragma: no cover - compiled
    """``C[j] = sum_k d_k cos(j tau_k)``, ``S[j]`` likewise with sines."""
    for j in range(cos2.shape[0]):
        c = 0.0
        s = 0.0
        for k in range(cos2.shape[1]):
            c += cos2[j, k] * d[k]
            s += sin2[j, k] * d[k]
        C[j] = c
        S[j] = s


@nb.njit(cache=True, nogil=True)
def _project(P, x, y, X, Y):  # pragma: no cover - compiled
    """``X = P @ x``, ``Y = P @ y``, each sum in sample order (no reassociation).

    Four rows at a time: eight independent sums overlap in the pipeline.
    """
    nrow = P.shape[0]
    Ns = P.shape[1]
    p = 0
    while p + 3 < nrow:
        a0 = 0.0
        a1 = 0.0
        a2 = 0.0
        a3 = 0.0
        b0 = 0.0
        b1 = 0.0
        b2 = 0.0
        b3 = 0.0
        for k in range(Ns):
            xk = x[k]
            yk = y[k]
            a0 += P[p, k] * xk
            b0 += P[p, k] * yk
            a1 += P[p + 1, k] * xk
            b1 += P[p + 1, k] * yk
            a2 += P[p + 2, k] * xk
            b2 += P[p + 2, k] * yk
            a3 += P[p + 3, k] * xk
            b3 += P[p + 3, k] * yk
        X[p] = a0
        X[p + 1] = a1
        X[p + 2] = a2
        X[p + 3] = a3
        Y[p] = b0
        Y[p + 1] = b1
        Y[p + 2] = b2
        Y[p + 3] = b3
        p += 4
    for p in range(p, nrow):
        a = 0.0
        b = 0.0
        for k in range(Ns):
            a += P[p, k] * x[k]
            b += P[p, k] * y[k]
        X[p] = a
        Y[p] = b


@nb.njit(cache=True, nogil=True)
def _diagonal_jacobian(C, S, Ns, out):  # pragma: no cover - compiled
    """``out = P diag(d) E`` (shape ``(nb, nb)``) from the DFT ``C, S`` of ``d`` at ``0..2H``.

    Product-to-sum identities: ``cos p cos q = (cos(p-q) + cos(p+q)) / 2`` etc.
    """
    H = (out.shape[0] - 1) // 2
    inv = 1.0 / Ns
    out[0, 0] = C[0] * inv
    for q in range(1, H + 1):
        out[0, 2 * q - 1] = C[q] * inv
        out[0, 2 * q] = S[q] * inv
        out[2 * q - 1, 0] = 2.0 * C[q] * inv
        out[2 * q, 0] = 2.0 * S[q] * inv
    for p in range(1, H + 1):
        for q in range(1, H + 1):
            dm = p - q if p >= q else q - p
            s_pq = S[p - q] if p >= q else -S[q - p]  # S at the signed index p - q
            out[2 * p - 1, 2 * q - 1] = (C[dm] + C[p + q]) * inv
            out[2 * p - 1, 2 * q] = (S[p + q] - s_pq) * inv
            out[2 * p, 2 * q - 1] = (S[p + q] + s_pq) * inv
            out[2 * p, 2 * q] = (C[dm] - C[p + q]) * inv


@nb.njit(cache=True, nogil=True)
def _aft_contact(kt, kn, gaps, mu, xt, xn, E, P, cos2, sin2, cum, max_periods,
                 FT, FN, JTt, JTn, JNn):  # pragma: no cover - compiled
    """AFT of one contact. Writes ``FT, FN`` (nb) and ``JTt, JTn, JNn`` (nb, nb).

    Returns the number of periods marched until every element was periodic,
    or ``-1`` if some element was still changing after ``max_periods``.
    """
    nbasis = xt.shape[0]
    Ns = E.shape[0]
    J = kt.shape[0]
    work = np.zeros((8, Ns))  # one allocation for the per-sample work arrays
    t = work[0]
    n = work[1]
    _synthesise(E, xt, t)
    _synthesise(E, xn, n)
    Tsum = work[2]
    Nsum = work[3]
    dstick = work[4]   # sum of kt over sticking elements
    dslip = work[5]    # sum of sign mu kn over slipping elements
    dclosed = work[6]  # sum of kn over closed elements
    U = np.empty((2, Ns + 1, nbasis))  # rows zeroed when first used
    Ut = U[0]
    Un = U[1]
    used = np.zeros(Ns + 1, dtype=np.bool_)
    code = np.empty(Ns, dtype=np.int8)  # 0 open, 1 stick, 2 slip with T > 0, 3 slip with T < 0
    runs = np.empty((3, Ns), dtype=np.int64)
    run_a = runs[0]  # stick runs of one element: samples a <= k < b,
    run_b = runs[1]  # slider set at sample m with slip force derivative c
    run_m = runs[2]
    run_c = work[7]
    t0 = xt[0]
    n0 = xn[0]
    worst = 0
    for i in range(J):
        kti = kt[i]
        kni = kn[i]
        gi = gaps[i]
        mukn = mu * kni
        rk = mu * kni / kti  # half-width of the stick band per unit of n - gap
        # -- static step from the virgin state (slider at 0) --------------
        r = rk * max(n0 - gi, 0.0)
        s = 0.0
        m = NEVER
        sig = 0.0  # sign of the force at the last slip (0: open there)
        if n0 <= gi:
            s = t0
            m = Ns
        elif t0 > r:
            s = t0 - r
            m = Ns
            sig = 1.0
        elif t0 < -r:
            s = t0 + r
            m = Ns
            sig = -1.0
        # -- whole periods until the state repeats ------------------------
        periods = 0
        s_start = s
        m_start = m
        sig_start = sig
        while True:
            s_start = s
            m_start = m
            sig_start = sig
            matched = False
            for k in range(Ns):
                tk = t[k]
                nk = n[k] - gi
                if nk <= 0.0:
                    c = OPEN
                    s = tk
                    sig = 0.0
                else:
                    r = rk * nk
                    d = tk - s
                    if d > r:
                        c = SLIP
                        s = tk - r
                        sig = 1.0
                    elif d < -r:
                        c = SLIP_NEG
                        s = tk + r
                        sig = -1.0
                    else:
                        code[k] = STICK
                        continue
                m = k
                if periods > 0 and code[k] == c:
                    matched = True  # the same state as one period ago from here on
                    break
                code[k] = c
            periods += 1
            if matched or (s == s_start and m == m_start and sig == sig_start):
                break
            if periods >= max_periods:
                worst = -1
                break
        if worst >= 0 and periods > worst:
            worst = periods
        # -- forces and derivative data of the periodic period ------------
        # (it started from the state saved at its start)
        s = s_start
        m = m_start
        cn = sig_start * mukn
        run = -1  # first sample of the current stick run, -1 when none
        nruns = 0
        for k in range(Ns + 1):
            c = code[k] if k < Ns else OPEN
            if c != STICK and run >= 0:
                if m != NEVER:  # slider set at sample m: a run in column m
                    run_a[nruns] = run
                    run_b[nruns] = k
                    run_m[nruns] = m
                    run_c[nruns] = cn
                    nruns += 1
                run = -1
            if k == Ns:
                break
            if c == STICK:
                Nsum[k] += kni * (n[k] - gi)
                dclosed[k] += kni
                Tsum[k] += kti * (t[k] - s)
                dstick[k] += kti
                if run < 0:
                    run = k
            elif c == OPEN:
                s = t[k]
                m = k
                cn = 0.0
            else:
                nk = n[k] - gi
                Nsum[k] += kni * nk
                dclosed[k] += kni
                cn = mukn if c == SLIP else -mukn
                Tsum[k] += cn * nk
                dslip[k] += cn
                s = t[k] - rk * nk if c == SLIP else t[k] + rk * nk
                m = k
        for j in range(nruns):
            col = run_m[j]
            a = run_a[j]
            b = run_b[j]
            cj = run_c[j]
            if not used[col]:
                used[col] = True
                Ut[col] = 0.0
                Un[col] = 0.0
            for q in range(nbasis):
                seg = cum[b, q] - cum[a, q]
                Ut[col, q] -= kti * seg
                Un[col, q] += cj * seg
    # -- back to Fourier coefficients -------------------------------------
    _project(P, Tsum, Nsum, FT, FN)
    CS = np.empty((2, nbasis))
    C = CS[0]
    S = CS[1]
    _dft(cos2, sin2, dstick, C, S)
    _diagonal_jacobian(C, S, Ns, JTt)
    _dft(cos2, sin2, dslip, C, S)
    _diagonal_jacobian(C, S, Ns, JTn)
    _dft(cos2, sin2, dclosed, C, S)
    _diagonal_jacobian(C, S, Ns, JNn)
    for col in range(Ns + 1):
        if used[col]:
            if col == Ns:  # the static step: basis row e0
                for p in range(nbasis):
                    JTt[p, 0] += Ut[col, p]
                    JTn[p, 0] += Un[col, p]
            else:
                for p in range(nbasis):
                    ut = Ut[col, p]
                    un = Un[col, p]
                    for q in range(nbasis):
                        JTt[p, q] += ut * E[col, q]
                        JTn[p, q] += un * E[col, q]
    return worst


@nb.njit(cache=True, nogil=True)
def aft_batch(kt, kn, gaps, offsets, mu, XT, XN, E, P, cos2, sin2, cum, max_periods,
              FT, FN, JTt, JTn, JNn, periods):  # pragma: no cover - compiled
    """AFT of many contacts; contact ``c`` owns elements ``offsets[c]:offsets[c+1]``.

    ``XT, XN, FT, FN`` have shape ``(nc, nb)``; ``JTt, JTn, JNn`` shape
    ``(nc, nb, nb)``; ``periods`` (int64, ``nc``) receives each contact's
    period count (``-1``: not periodic within ``max_periods``).
    """
    for c in range(XT.shape[0]):
        a = offsets[c]
        b = offsets[c + 1]
        periods[c] = _aft_contact(kt[a:b], kn[a:b], gaps[a:b], mu[c], XT[c], XN[c], E, P, cos2, sin2,
                                  cum, max_periods, FT[c], FN[c], JTt[c], JTn[c], JNn[c])


def aft_reference(kt, kn, gaps, mu, xt, xn, Ns, max_periods=1000):
    """Slow, obviously correct pure-Python twin of :func:`_aft_contact` (tests only).

    Forward-mode differentiation: every slider carries its full gradient
    with respect to ``(xt, xn)`` through the march, and the force samples'
    gradients are projected with an explicit DFT matrix. Returns
    ``(FT, FN, JTt, JTn, JNn, periods)``.
    """
    nbasis = len(xt)
    tau = [2.0 * np.pi * k / Ns for k in range(Ns)]

    def phi(q, x):
        if q == 0:
            return 1.0
        h = (q + 1) // 2
        return np.cos(h * x) if q % 2 == 1 else np.sin(h * x)

    E = np.array([[phi(q, x) for q in range(nbasis)] for x in tau])  # (Ns, nb)
    zero = np.zeros(nbasis)
    t = E @ np.asarray(xt, float)
    n = E @ np.asarray(xn, float)
    T = np.zeros(Ns)
    N = np.zeros(Ns)
    dT_dt = np.zeros((Ns, nbasis))
    dT_dn = np.zeros((Ns, nbasis))
    dN_dn = np.zeros((Ns, nbasis))
    e0 = np.eye(nbasis)[0]
    worst = 0
    for i in range(len(kt)):
        # the return mapping of DESIGN.md divided by kt_i: slip when |t - s| > r = mu N_i / kt_i
        rk = mu * kn[i] / kt[i]
        # static step from the virgin state: slider 0, gradient 0
        s, ds_t, ds_n = 0.0, zero.copy(), zero.copy()
        r = rk * max(xn[0] - gaps[i], 0.0)
        if xn[0] <= gaps[i]:
            s, ds_t, ds_n = xt[0], e0.copy(), zero.copy()
        elif abs(xt[0]) > r:
            sign = 1.0 if xt[0] > 0 else -1.0
            s = xt[0] - sign * r
            ds_t, ds_n = e0.copy(), -sign * rk * e0
        periods = 0
        while True:
            start = (s, ds_t.copy(), ds_n.copy())
            rows = []
            for k in range(Ns):
                Ni = kn[i] * max(n[k] - gaps[i], 0.0)
                dNi = kn[i] * E[k] if Ni > 0.0 else zero
                if Ni == 0.0:  # open: no force, slider follows t
                    Ti, dTt, dTn = 0.0, zero, zero
                    s, ds_t, ds_n = t[k], E[k].copy(), zero.copy()
                else:
                    r = rk * (n[k] - gaps[i])
                    if abs(t[k] - s) > r:  # slip
                        sign = 1.0 if t[k] > s else -1.0
                        Ti, dTt, dTn = sign * mu * Ni, zero, sign * mu * dNi
                        s = t[k] - sign * r
                        ds_t, ds_n = E[k].copy(), -sign * rk * E[k]
                    else:  # stick
                        Ti, dTt, dTn = kt[i] * (t[k] - s), kt[i] * (E[k] - ds_t), -kt[i] * ds_n
                rows.append((Ti, dTt, dTn, Ni, dNi))
            periods += 1
            if s == start[0] and np.array_equal(ds_t, start[1]) and np.array_equal(ds_n, start[2]):
                break
            if periods >= max_periods:
                worst = -1
                break
        worst = periods if worst >= 0 and periods > worst else worst
        for k, (Ti, dTt, dTn, Ni, dNi) in enumerate(rows):
            T[k] += Ti
            N[k] += Ni
            dT_dt[k] += dTt
            dT_dn[k] += dTn
            dN_dn[k] += dNi
    w = np.full(nbasis, 2.0 / Ns)
    w[0] = 1.0 / Ns
    P = E.T * w[:, None]
    return P @ T, P @ N, P @ dT_dt, P @ dT_dn, P @ dN_dn, worst

