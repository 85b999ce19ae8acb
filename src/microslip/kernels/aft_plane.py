"""Compiled AFT of one contact on the contact plane: two tangential directions plus normal (private).

Plain float64 arrays in, arrays out; the checked public wrapper is
:func:`microslip.frequency.aft.aft_plane`. Fourier layout and tables as in
:mod:`microslip.kernels.aft`.

The element. Element ``i`` is an isotropic Jenkins slider on the plane: with
``r = mu kn_i (n - g_i) / kt_i`` (its stick radius, m) and ``d = t - s_i``
(2-vectors), it is open for ``n <= g_i`` (no force, ``s_i = t``), sticks for
``|d| <= r`` (``T_i = kt_i d``) and slips otherwise: ``u = d / |d|``,
``s_i = t - r u``, ``T_i = mu kn_i (n - g_i) u`` (the trial force returned
radially onto the disc of radius ``mu N_i``). Along a straight line this is
the one-direction return mapping of :mod:`microslip.kernels.element`, to the bit
(``d / |d|`` is exactly ``+-1`` there).

The march. As in one direction: the contact is closed at ``t = 0`` with every
slider at 0, the static part ``(c0 of t, c0 of n)`` is applied as one step,
then whole periods are marched. On the plane the periodic state is in general
reached only asymptotically (a circular orbit in gross slip), so an element is
periodic when its slider at the start of a period moves by at most
``32 eps`` times the size of the motion over one period. A slipping element
contracts by ``alpha = r / |d|`` per slip sample across its path, so an
element that barely slips would need thousands of periods: once its residual
falls, the march takes a Newton step on the fixed point of the period map,
``s <- s + (I - dPhi/ds)^-1 (Phi(s) - s)`` (only while ``1 - rho``, the
distance of the map's eigenvalue from 1, exceeds 1e-8). A step after which
the residual does not fall is replaced by the plain step and the next ones are
halved (after three halvings the element goes on plainly, or onto the corner
of its stick region it creeps towards: its fixed point lies across a change
of its slip pattern). An element that ends a period stuck
throughout, or nearly neutral, after a Newton step keeps the state the plain
march gives it (restarted from the static step and marched plainly): its
state depends on its history, and that history is the physical one.

Exact derivatives. With ``A_k`` the derivative of the slider after sample
``k`` with respect to the slider before it (``I`` in stick, ``alpha v v^T``
with ``v`` perpendicular to ``u`` in slip, 0 when open) and ``G_k`` its
derivative with respect to the sample's ``(t, n)`` (0 in stick,
``[I - alpha v v^T, -r/(n - g) u]`` in slip, ``[I, 0]`` when open),

``ds_k = A_k ds_(k-1) + G_k dx_k`` and ``dT_k = kt A_k (dt_k - ds_(k-1)) + mu kn u dn_k`` (slip only).

The local parts ``kt A_k dt_k`` and ``mu kn u dn_k`` give Jacobian blocks
``P diag(d) E``: each sample's sums ``d`` over the elements join the history
part's columns below (``d P[:, m]`` in column ``m``), and the normal force's
``dN/dn`` is taken as in one direction (product-to-sum identities).
The history part ``-kt A_k ds_(k-1)`` is gathered by one backward sweep per
element (all elements side by side): ``Y_(m-1) = (Y_m - kt P[:, m] (x) I) A_m`` is the coefficient of
``ds_m`` in the period's force coefficients, and each slip or open sample
adds ``Y_m G_m`` to its column ``m``; the columns are multiplied by the
basis rows at the end (one matrix product for the whole contact). The
periodic state closes the sweep: the slider at the start of the period is the
fixed point ``sigma = Phi(sigma, x)``, so ``dsigma = (I - Phi_s)^-1 Phi_x dx``
with ``Phi_s = A_(Ns-1) ... A_0`` (rank one if the element slips, zero if
it opens), which starts the sweep at ``Y_(Ns-1) = Z (I - Phi_s)^-1``, ``Z``
the coefficient of ``sigma`` accumulated forward. An element stuck through
the whole period (``Phi_s = I``) keeps the slider its history gave it: that
history is marched again with the slider's derivative carried forward
(rank-one updates, a few of them).

Rounding between processors. Plain numba loops, no hand-written vector code.
The period's element update is :func:`microslip.kernels.element.plane_step`, bit for
bit the same on every processor numba compiles for (``NUMBA_CPU_NAME``). The
samples of the motion (:func:`~microslip.kernels.aft._synthesise`), the
sums over the elements at each sample (:func:`_sample_sums`) and the normal
force's transform are compiled with ``fastmath``: their sums are reordered to
the processor's vector width and their products fused into multiply-adds where
it has them, so forces and Jacobians differ between processors by rounding
(measured: 4e-16 of the largest entry between a generic x86-64 and an AVX2
processor; ``tests/model/test_targets.py`` allows 1e-14). The sweep and the
products with the basis rows round every product and sum (no fused
multiply-add).
"""

from __future__ import annotations

import math
from functools import lru_cache

import numba as nb
import numpy as np

from .element import OPEN, SLIP, STICK, plane_step
from .aft import _aft_contact, _dft, _diagonal_jacobian, _synthesise, tables

#: the periodicity tolerance, in units of the motion's size times the machine epsilon
PERIODIC_ULPS = 32.0
#: a sample binds a slider on the edge of its stick region within this many periodicity tolerances
BIND = 1000.0
#: ``1 - rho`` (``rho`` the period map's eigenvalue) below which a plainly marched slider takes its
#: derivative from its history rather than from the fixed point (whose formula divides by ``1 - rho``)
FIXED_POINT_MARGIN = 1e-3
#: ``1 - rho`` above which a Newton step on the fixed point is taken (below, the fixed point is nearly neutral:
#: an element that touches its slip limit without slipping, whose state is its history's)
NEWTON_MARGIN = 1e-8


@nb.njit(cache=True, nogil=True, error_model="numpy")
def _step(rk, nk, t1, t2, s1, s2):  # pragma: no cover - compiled
    """One element, one sample: ``(code, s1, s2, alpha, q)``, the arithmetic of :func:`_period`.

    ``rk = mu kn / kt``, ``nk = n - gap``; the slider ``(s1, s2)`` before the
    sample. In slip ``alpha = r / |d|`` and ``q = 1 / |d|`` (``d = t - s``
    before the sample; the force is ``mu kn nk q d``); 0 otherwise. The
    element update is :func:`microslip.kernels.element.plane_step` (its force unused).
    """
    _, _, _, code, a1, a2, al, q = plane_step(1.0, rk, 0.0, 0.0, nk, t1, t2, s1, s2)
    if code != SLIP:
        return code, a1, a2, 0.0, 0.0
    return code, a1, a2, al, q


@nb.njit(cache=True, nogil=True, error_model="numpy")
def _static(rk, nk, t1, t2):  # pragma: no cover - compiled
    """The static step from the virgin slider ``(0, 0)``: ``(code, s1, s2, alpha, u1, u2)``."""
    return _step(rk, nk, t1, t2, 0.0, 0.0)


@nb.njit(cache=True, nogil=True, error_model="numpy")
def _history_derivative(rk, gi, t1, t2, n, x1_0, x2_0, xn_0, E, periods, D):  # pragma: no cover - compiled
    """Derivative ``D`` (2, 3, nb) of the slider after the static step and ``periods`` plain periods.

    Forward mode: ``D <- G_k (x) E[k] + A_k D`` (rank-one ``A_k``). Returns
    the slider and whether it ever slipped or opened (if not, ``D`` is zero).
    """
    nbasis = E.shape[1]
    Ns = E.shape[0]
    D[:] = 0.0
    d0 = D[0].reshape(3 * nbasis)  # each component's derivative as one row
    d1 = D[1].reshape(3 * nbasis)
    code, s1, s2, al, qq = _static(rk, xn_0 - gi, x1_0, x2_0)
    moved = code != STICK
    u1 = x1_0 * qq
    u2 = x2_0 * qq
    if code == OPEN:
        D[0, 0, 0] = 1.0
        D[1, 1, 0] = 1.0
    elif code == SLIP:
        v1 = -u2
        v2 = u1
        D[0, 0, 0] = 1.0 - al * v1 * v1
        D[0, 1, 0] = -al * v1 * v2
        D[1, 0, 0] = -al * v2 * v1
        D[1, 1, 0] = 1.0 - al * v2 * v2
        D[0, 2, 0] = -rk * u1
        D[1, 2, 0] = -rk * u2
    for _ in range(periods):
        for k in range(Ns):
            u1 = t1[k] - s1
            u2 = t2[k] - s2
            code, s1, s2, al, qq = _step(rk, n[k] - gi, t1[k], t2[k], s1, s2)
            u1 *= qq
            u2 *= qq
            if code == STICK:
                continue
            moved = True
            if code == OPEN:
                for b in range(3):
                    for q in range(nbasis):
                        D[0, b, q] = E[k, q] if b == 0 else 0.0
                        D[1, b, q] = E[k, q] if b == 1 else 0.0
                continue
            v1 = -u2
            v2 = u1
            for j in range(3 * nbasis):  # D <- alpha v v^T D: rows of both components at once (they vectorise)
                w = al * (v1 * d0[j] + v2 * d1[j])
                d0[j] = w * v1
                d1[j] = w * v2
            c00 = 1.0 - al * v1 * v1
            c01 = al * v1 * v2
            c10 = al * v2 * v1
            c11 = 1.0 - al * v2 * v2
            r1 = rk * u1
            r2 = rk * u2
            for q in range(nbasis):  # + G_k (x) E[k]
                e = E[k, q]
                D[0, 0, q] += c00 * e
                D[0, 1, q] -= c01 * e
                D[1, 0, q] -= c10 * e
                D[1, 1, q] += c11 * e
                D[0, 2, q] -= r1 * e
                D[1, 2, q] -= r2 * e
    return s1, s2, moved


#: float64 values per 64 bytes: the work arrays start on 64-byte boundaries (cache lines)
ALIGN = 8
#: the sweep's coefficient rows are padded with zeros to a multiple of this many values
PAD = 16


@lru_cache(maxsize=32)
def sweep_tables(H: int, Ns: int) -> np.ndarray:
    """The history part's tables, C-contiguous ``(2 Ns, nbp)`` (read-only, on a 64-byte boundary), ``nbp`` = ``2H+1``
    padded to :data:`PAD`.

    Rows ``0 .. Ns-1`` hold ``P.T``, rows ``Ns .. 2 Ns - 1`` ``E``
    (:func:`~microslip.kernels.aft.tables`); the padding columns are zero.
    """
    E, P, _, _, _ = tables(H, Ns)
    nbasis = 2 * H + 1
    shape = (2 * Ns, -(-nbasis // PAD) * PAD)
    raw = np.zeros(shape[0] * shape[1] + ALIGN)
    start = (-raw.ctypes.data % (8 * ALIGN)) // 8  # on a 64-byte boundary, as the work arrays (ALIGN)
    out = raw[start:start + shape[0] * shape[1]].reshape(shape)
    out[:Ns, :nbasis] = P.T
    out[Ns:, :nbasis] = E
    out.setflags(write=False)
    return out


@nb.njit(cache=True, nogil=True)
def march_work(J, Ns):  # pragma: no cover - compiled
    """The march's rows for ``J`` elements over ``Ns`` samples: ``(st (6, J), rec (6, Ns, J))``.

    ``st`` holds the sliders ``s1, s2`` and the period map's derivative
    ``C`` (4 rows, row-major 2x2 per element); ``rec`` the period's records
    (condition, ``alpha``, ``V1, V2``, the element's force ``Te1, Te2``),
    each ``(Ns, J)``.
    """
    return np.empty((6, J)), np.empty((6, Ns, J))


@nb.njit(cache=True, nogil=True)
def periodic_tolerance(rk, gaps, t1, t2, n):  # pragma: no cover - compiled
    """The march's periodicity tolerance (m): :data:`PERIODIC_ULPS` ulps of the largest tangential motion plus
    the largest stick radius over the period (``rk = mu kn / kt``; the samples ``t1, t2, n``)."""
    size = 0.0
    nmax = -np.inf
    for k in range(t1.shape[0]):
        size = max(size, abs(t1[k]) + abs(t2[k]))
        nmax = max(nmax, n[k])
    rmax = 0.0
    for i in range(rk.shape[0]):
        rmax = max(rmax, rk[i] * (nmax - gaps[i]))  # the largest stick radius (rk >= 0: at the largest n)
    return PERIODIC_ULPS * 2.220446049250313e-16 * (size + rmax)


@nb.njit(cache=True, nogil=True)
def _take(block, at, shape):  # pragma: no cover - compiled
    """The array of ``shape`` at ``block[at:]`` (a view) and the position of the next one, at the next
    :data:`ALIGN` boundary."""
    size = 1
    for extent in shape:
        size *= extent
    return block[at:at + size].reshape(shape), at + -(-size // ALIGN) * ALIGN


@nb.njit(cache=True, nogil=True, inline="always")
def _aligned_block(size):  # pragma: no cover - compiled
    """A float64 array of at least ``size`` values and the index of its first value on a 64-byte boundary."""
    block = np.empty(size + ALIGN)
    return block, (ALIGN - (block.ctypes.data // 8) % ALIGN) % ALIGN


@nb.njit(cache=True, nogil=True)
def _march_parameters(kt, kn, gaps, mu, rk):  # pragma: no cover - compiled
    """The rows :func:`period_march` reads, ``(5, J)``: ``kt, rk, mu kn, kn, gap``."""
    par = np.empty((5, kt.shape[0]))
    for i in range(kt.shape[0]):
        par[0, i] = kt[i]
        par[1, i] = rk[i]
        par[2, i] = mu * kn[i]
        par[3, i] = kn[i]
        par[4, i] = gaps[i]
    return par


@nb.njit(cache=True, nogil=True, error_model="numpy")
def period_march(par, st, rec, t1, t2, n):  # pragma: no cover - compiled
    """One period of the AFT's march on the plane for every element: :func:`microslip.kernels.element.plane_step` at each
    sample, with the period map's derivative.

    Rows of ``J`` elements, C-contiguous float64: ``par`` (5, J) ``kt, mu kn / kt, mu kn, kn, gap``; ``st``
    (6, J) the sliders ``s1, s2`` at the start of the period (updated to its end) and the period map's
    derivative so far ``C`` (2x2 per element, row-major, updated: ``alpha v v^T C`` in slip, unchanged in stick, 0
    when open); ``rec`` (6, Ns, J) receives at ``[:, k]`` the condition of sample ``k`` (0 open, 1 stick, 2 slip,
    as a float), ``alpha = r / |d|`` and ``v = (-d2, d1) / |d|`` of a slip (0 otherwise) and the element's force
    ``T1, T2``. ``t1, t2, n`` (Ns,) are the period's motion.
    """
    for k in range(t1.shape[0]):
        tx = t1[k]
        ty = t2[k]
        nk0 = n[k]
        for i in range(par.shape[1]):
            s1 = st[0, i]
            s2 = st[1, i]
            T1, T2, _, code, st[0, i], st[1, i], al, q = plane_step(par[0, i], par[1, i], par[2, i], par[3, i],
                                                                     nk0 - par[4, i], tx, ty, s1, s2)
            slip = code == SLIP
            stick = code == STICK  # C kept in stick, cleared when open
            v1 = -(ty - s2) * q
            v2 = (tx - s1) * q
            c0 = st[2, i]
            c1 = st[3, i]
            c2 = st[4, i]
            c3 = st[5, i]
            w1 = al * (v1 * c0 + v2 * c2)
            w2 = al * (v1 * c1 + v2 * c3)
            st[2, i] = v1 * w1 if slip else (c0 if stick else 0.0)
            st[3, i] = v1 * w2 if slip else (c1 if stick else 0.0)
            st[4, i] = v2 * w1 if slip else (c2 if stick else 0.0)
            st[5, i] = v2 * w2 if slip else (c3 if stick else 0.0)
            rec[0, k, i] = code
            rec[1, k, i] = al if slip else 0.0
            rec[2, k, i] = v1 if slip else 0.0
            rec[3, k, i] = v2 if slip else 0.0
            rec[4, k, i] = T1
            rec[5, k, i] = T2


@nb.njit(cache=True, nogil=True)
def start_weights(rec, nkt, weights, ends):  # pragma: no cover - compiled
    """Every element's coefficient ``Z = beta (x) I + z (x) w^T`` of its slider at the start of the period, as
    weights of the basis rows.

    ``Z = sum_k -kt P[:, k] (x) C_k`` with ``C_k = A_k ... A_0``: the identity up to the first slip, ``c_k l_k w^T``
    after it (``w`` the first slip's ``v``, ``l_k`` the last one's), zero from the first opening on. ``rec``
    (6, Ns, J) are the periodic period's records (:func:`period_march`), ``nkt`` (J) the elements' ``-kt``;
    ``weights`` (Ns, 3 J) receives at ``[k, i]`` the weight of ``P[:, k]`` in element ``i``'s ``beta`` and at
    ``[k, (1 + a) J + i]`` in its ``z_a``, so that one matrix product with ``P.T`` gives them all; ``ends``
    (5, J) receives ``w1, w2, c, l1, l2``: ``w``, and ``Phi_s = C_(Ns-1) = c l w^T`` (``c = 1``, ``l = w = 0``
    for an element that sticks throughout, whose ``Phi_s`` is the identity; ``c = 0`` once it opens).
    """
    J = nkt.shape[0]
    for i in range(J):
        f0 = nkt[i]
        w1 = w2 = l1 = l2 = 0.0
        cc = 1.0
        first = True  # no slip yet
        live = True  # not opened yet
        for k in range(rec.shape[1]):
            code = rec[0, k, i]
            on = live and code != OPEN
            slip = on and code == SLIP
            if slip:
                al = rec[1, k, i]
                v1 = rec[2, k, i]
                v2 = rec[3, k, i]
                cc = al if first else cc * (al * (v1 * l1 + v2 * l2))
                if first:
                    w1 = v1
                    w2 = v2
                l1 = v1
                l2 = v2
            elif not on:
                cc = 0.0
            still = first and not slip
            f = f0 * cc
            moved = on and not still
            weights[k, i] = f0 if on and still else 0.0
            weights[k, J + i] = f * l1 if moved else 0.0
            weights[k, 2 * J + i] = f * l2 if moved else 0.0
            first = still
            live = on
        ends[0, i], ends[1, i], ends[2, i], ends[3, i], ends[4, i] = w1, w2, cc, l1, l2


@nb.njit(cache=True, nogil=True)
def sample_coefficients(coefs, rec, KR, w, m):  # pragma: no cover - compiled
    """Every element's coefficients for sample ``m`` of the sweep.

    ``coefs`` (16, J) receives :data:`SAMPLE_COEFFICIENTS` of each element (the rows :func:`sample_rows` reads);
    ``rec`` (6, Ns, J) is the periodic period's records (:func:`period_march`: condition, ``alpha``, ``v``),
    ``KR`` (2, J) the elements' ``kt`` and ``rk = mu kn / kt``, ``w`` (3, J) the ``w`` of each element's
    ``Y = beta I + y w^T``, set to ``v`` by a slip, and whether its ``beta`` is known to be zero (1: after a slip
    or an opening; 0: not known, or after a stick) for ``full``, 1 when the ``beta`` terms are needed. With
    ``G = [I - alpha v v^T | -rk u]`` (``u = (v2, -v1)``; ``[I | 0]`` when open, where the records' ``alpha, v``
    are 0) and ``h = w^T G``: ``g = G`` (``g21 = g12``), ``cb = alpha``, ``cp = -alpha kt``, ``cy = alpha w.v``,
    ``sb = sp = 0``; in stick ``g = h = 0``, ``cb = cp = v = 0``, ``cy = sb = 1``, ``sp = -kt`` (``y`` kept,
    ``beta -= kt P[:, m]``).
    """
    for i in range(coefs.shape[1]):
        code = rec[0, m, i]
        w1 = w[0, i]
        w2 = w[1, i]
        if code == STICK:
            for r in range(12):
                coefs[r, i] = 0.0
            coefs[12, i] = 1.0
            coefs[13, i] = 1.0
            coefs[14, i] = -KR[0, i]
            coefs[15, i] = 1.0
            w[2, i] = 0.0
            continue
        al = rec[1, m, i]
        v1 = rec[2, m, i]
        v2 = rec[3, m, i]
        rk = KR[1, i]
        awv = al * (w1 * v1 + w2 * v2)
        coefs[0, i] = 1.0 - al * v1 * v1
        coefs[1, i] = -(al * v1 * v2)
        coefs[2, i] = -(rk * v2)
        coefs[3, i] = 1.0 - al * v2 * v2
        coefs[4, i] = rk * v1
        coefs[5, i] = w1 - awv * v1
        coefs[6, i] = w2 - awv * v2
        coefs[7, i] = -(rk * (w1 * v2 - w2 * v1))
        coefs[8, i] = al
        coefs[9, i] = -(al * KR[0, i])
        coefs[10, i] = v1
        coefs[11, i] = v2
        coefs[12, i] = awv
        coefs[13, i] = 0.0
        coefs[14, i] = 0.0
        coefs[15, i] = 1.0 - w[2, i]
        w[2, i] = 1.0
        if code == SLIP:
            w[0, i] = v1
            w[1, i] = v2


#: the rows of the sample sums :func:`sample_rows` reads (``local``, see :func:`_sample_sums`): the local
#: derivatives ``d11 = dT1/dt1, d12, d22, c1 = dT1/dn, c2 = dT2/dn`` in rows 3 to 7, one for each of its six
#: coefficient rows
LOCAL_ROWS = (3, 4, 6, 4, 5, 7)
#: the coefficients of one element at one sample in :func:`sample_rows`, in this order
SAMPLE_COEFFICIENTS = ("g11", "g12", "g13", "g22", "g23", "h1", "h2", "h3", "cb", "cp", "v1", "v2", "cy", "sb", "sp",
                       "full")


@nb.njit(cache=True, nogil=True)
def sample_rows(U, m, B, Y, PT, coefs, local, order, count):  # pragma: no cover - compiled
    """Sample ``m`` of the sweep for the elements ``order[:count]``, over the ``nbp`` columns.

    ``U`` (Ns, 6, nbp), ``B`` (J, nbp), ``Y`` (J, 2, nbp), ``PT`` (Ns, nbp), ``coefs`` (16, J) and ``local``
    (rows, Ns) C-contiguous float64, ``order`` int64. With element ``i``'s ``beta = B[i]``, ``y = Y[i]`` and
    coefficients ``coefs[:, i]`` (:data:`SAMPLE_COEFFICIENTS`, ``g21 = g12``; :func:`sample_coefficients`) and the
    sample's local derivative ``l_ab = local[LOCAL_ROWS[3a + b], m]``::

        U[m, 3a + b] = l_ab PT[m] + sum over the elements of (beta g_ab + y_a h_b)     (a = 0, 1; b = 0, 1, 2)
        y_a = (cb beta + cp PT[m]) v_a + cy y_a
        beta = sb beta + sp PT[m]

    An element whose ``full`` is 0 has ``beta = 0`` before and after (it slips or opens after a slip or an
    opening): its ``beta`` terms are left out. The sums in element order.
    """
    u = U[m]
    pt = PT[m]
    nbp = pt.shape[0]
    for r in range(6):
        lr = local[LOCAL_ROWS[r], m]
        for p in range(nbp):
            u[r, p] = lr * pt[p]
    for e in range(count):
        i = order[e]
        g11, g12, g13, g22, g23 = coefs[0, i], coefs[1, i], coefs[2, i], coefs[3, i], coefs[4, i]
        h1, h2, h3, cb, cp = coefs[5, i], coefs[6, i], coefs[7, i], coefs[8, i], coefs[9, i]
        v1, v2, cy, sb, sp = coefs[10, i], coefs[11, i], coefs[12, i], coefs[13, i], coefs[14, i]
        full = coefs[15, i] != 0.0  # the beta terms
        y1 = Y[i, 0]
        y2 = Y[i, 1]
        beta = B[i]
        for p in range(nbp):
            a1 = y1[p]
            a2 = y2[p]
            r0 = u[0, p] + a1 * h1
            r1 = u[1, p] + a1 * h2
            r2 = u[2, p] + a1 * h3
            r3 = u[3, p] + a2 * h1
            r4 = u[4, p] + a2 * h2
            r5 = u[5, p] + a2 * h3
            q = pt[p] * cp
            if full:
                bp = beta[p]
                r0 += bp * g11
                r1 += bp * g12
                r2 += bp * g13
                r3 += bp * g12
                r4 += bp * g22
                r5 += bp * g23
                q += cb * bp
                beta[p] = sb * bp + pt[p] * sp
            u[0, p], u[1, p], u[2, p], u[3, p], u[4, p], u[5, p] = r0, r1, r2, r3, r4, r5
            y1[p] = cy * a1 + q * v1
            y2[p] = cy * a2 + q * v2


@nb.njit(cache=True, nogil=True)
def columns_times_basis(U, E, out):  # pragma: no cover - compiled
    """``out = E.T @ U``: ``out[q, r] = sum over m of E[m, q] U[m, r]``, each sum in the order of ``m``.

    ``U`` (Ns, R), ``E`` (Ns, nq) and ``out`` (nq, R) C-contiguous float64 (the history columns times the basis
    rows, the start weights and the force samples times the projection's rows). Each product in the order
    ``U[m, r] E[m, q]``, each sum from zero in the order of ``m``, as
    :func:`microslip.kernels.aft._project` adds them.
    """
    out[:] = 0.0
    for m in range(U.shape[0]):
        u = U[m]
        for q in range(E.shape[1]):
            e = E[m, q]
            o = out[q]
            for r in range(u.shape[0]):
                o[r] += u[r] * e


@nb.njit(cache=True, nogil=True)
def _period_of(par, t1, t2, n, st, rec):  # pragma: no cover - compiled
    """:func:`_period` with the parameter rows of :func:`_march_parameters`."""
    for i in range(st.shape[1]):
        st[2, i] = 1.0
        st[3, i] = 0.0
        st[4, i] = 0.0
        st[5, i] = 1.0
    period_march(par, st, rec, t1, t2, n)


@nb.njit(cache=True, nogil=True)
def _period(kt, kn, gaps, mu, rk, t1, t2, n, st, rec):  # pragma: no cover - compiled
    """March every element over one period from the sliders ``st[0], st[1]`` (updated in place).

    Writes, per sample ``k`` and element ``i``, the condition ``rec[0, k, i]``
    (0 open, 1 stick, 2 slip), ``alpha = rec[1, k, i]`` and the
    perpendicular ``v = rec[2:4, k, i]`` of a slip (0 otherwise), and the
    element's force ``rec[4:6, k, i]``; ``st[2:6]`` receives the period
    map's derivative ``dPhi/ds`` (row-major 2x2 per element). The rows are
    :func:`march_work`'s. The element update is
    :func:`microslip.kernels.element.plane_step` (:func:`period_march`).
    """
    _period_of(_march_parameters(kt, kn, gaps, mu, rk), t1, t2, n, st, rec)


@nb.njit(cache=True, nogil=True)
def _binding_pair(t1, t2, n, gi, rk, s1, s2):  # pragma: no cover - compiled
    """The two samples nearest to binding the slider ``(s1, s2)``: ``(a, ga, b, gb)``.

    ``g = |s - t_k| - r_k`` (positive: outside sample ``k``'s disc); ``a`` the
    largest, ``b`` the largest among the samples whose direction from the
    slider is at least 1e-3 from ``a``'s (``b = -1``: none). ``a = -1`` when
    the element opens: it has no stick region.
    """
    a = -1
    ga = -np.inf
    for k in range(t1.shape[0]):
        nk = n[k] - gi
        if nk <= 0.0:
            return -1, ga, -1, ga
        g = math.hypot(t1[k] - s1, t2[k] - s2) - rk * nk
        if g > ga:
            ga = g
            a = k
    da = math.hypot(t1[a] - s1, t2[a] - s2)
    b = -1
    gb = -np.inf
    for k in range(t1.shape[0]):
        d = math.hypot(t1[k] - s1, t2[k] - s2)
        same_side = (t1[a] - s1) * (t1[k] - s1) + (t2[a] - s2) * (t2[k] - s2) > 0.0
        if same_side and abs((t1[a] - s1) * (t2[k] - s2) - (t2[a] - s2) * (t1[k] - s1)) < 1e-3 * d * da:
            continue  # a's own neighbour: its circle touches a's from inside, no corner
        g = d - rk * (n[k] - gi)
        if g > gb:
            gb = g
            b = k
    return a, ga, b, gb


@nb.njit(cache=True, nogil=True)
def _corner(t1, t2, n, gi, rk, s1, s2, tol):  # pragma: no cover - compiled
    """The two samples whose discs meet at ``(s1, s2)``, a corner of the element's stick region, or ``(-1, -1)``.

    The stick region is the intersection of the discs ``|s - t_k| <= r_k``; a
    slider that creeps onto it from outside lands on its edge, generically at
    a corner where two circles meet. There it is fixed by those two samples
    (not by its history): both within ``BIND`` tolerances of their circles
    (:func:`_binding_pair`).
    """
    a, ga, b, gb = _binding_pair(t1, t2, n, gi, rk, s1, s2)
    if a < 0 or b < 0 or ga < -BIND * tol or gb < -BIND * tol:
        return -1, -1
    return a, b


@nb.njit(cache=True, nogil=True)
def _corner_point(t1, t2, n, gi, rk, s1, s2):  # pragma: no cover - compiled
    """The corner of the stick region nearest a slider creeping onto it: ``(found, c1, c2)``.

    The two samples whose discs the slider ``(s1, s2)`` violates most
    (:func:`_binding_pair`); of the two points where their circles meet, the
    nearer one, if it lies in every disc (radii shrunk by 16 ulps).
    """
    a, _, b, _ = _binding_pair(t1, t2, n, gi, rk, s1, s2)
    if a < 0 or b < 0:
        return False, s1, s2
    shrink = 1.0 - 16 * 2.220446049250313e-16
    ra = rk * (n[a] - gi) * shrink
    rb = rk * (n[b] - gi) * shrink
    e1 = t1[b] - t1[a]
    e2 = t2[b] - t2[a]
    L = math.hypot(e1, e2)
    if L == 0.0 or L > ra + rb or L < abs(ra - rb):
        return False, s1, s2
    x = (L * L + ra * ra - rb * rb) / (2.0 * L)
    h = math.sqrt(max(ra * ra - x * x, 0.0))
    best = np.inf
    c1 = s1
    c2 = s2
    for side in (-1.0, 1.0):
        p1 = t1[a] + (x * e1 - side * h * e2) / L
        p2 = t2[a] + (x * e2 + side * h * e1) / L
        dist = math.hypot(p1 - s1, p2 - s2)
        if dist < best:
            best = dist
            c1 = p1
            c2 = p2
    for k in range(t1.shape[0]):
        if math.hypot(c1 - t1[k], c2 - t2[k]) > rk * (n[k] - gi):
            return False, s1, s2
    return True, c1, c2


@nb.njit(cache=True, nogil=True)
def _facing_point(t1, t2, n, gi, rk, s1, s2):  # pragma: no cover - compiled
    """The slider at the start of a period in which the element slips only at two samples whose discs are apart.

    ``(found, c1, c2)``: the two samples the slider ``(s1, s2)`` violates
    most (:func:`_binding_pair`), if their discs do not meet; the slider then
    goes back and forth between their nearest points, and at the start of
    the period it sits on the later sample's disc, at its point nearest the
    earlier one's. The next period checks it (its residual).
    """
    a, _, b, _ = _binding_pair(t1, t2, n, gi, rk, s1, s2)
    if a < 0 or b < 0:
        return False, s1, s2
    early = min(a, b)
    late = max(a, b)
    e1 = t1[early] - t1[late]
    e2 = t2[early] - t2[late]
    L = math.hypot(e1, e2)
    r_late = rk * (n[late] - gi)
    if L <= r_late + rk * (n[early] - gi):
        return False, s1, s2
    return True, t1[late] + r_late * e1 / L, t2[late] + r_late * e2 / L


@nb.njit(cache=True, nogil=True)
def _land(t1, t2, n, gi, rk, p1, p2, s1, s2, i):  # pragma: no cover - compiled
    """Put slider ``i`` (``s1[i], s2[i]``) where the plain march from ``(p1, p2)`` creeps to; False if not found.

    The slider creeps onto a corner of its stick region (:func:`_corner_point`:
    the two discs it violates most meet inside the others), or, when those
    two discs are apart and nearly touching, the element slips at those two
    samples only, its slider crossing between their nearest points
    (:func:`_facing_point`; the plain march nears it at ``1 - rho`` about
    the gap between the discs over their radius, 1e-5 per period and less).
    """
    found, c1, c2 = _corner_point(t1, t2, n, gi, rk, p1, p2)
    if not found:
        found, c1, c2 = _facing_point(t1, t2, n, gi, rk, p1, p2)
    if found:
        s1[i] = c1
        s2[i] = c2
    return found


@nb.njit(cache=True, nogil=True)
def _corner_derivative(t1, t2, rk, s1, s2, a, b, E, D):  # pragma: no cover - compiled
    """``D`` (2, 3, nb): the derivative of the corner where the circles of samples ``a`` and ``b`` meet.

    Each binding sample ``j`` keeps ``|t_j - s| = r_j``: ``u_j . ds = u_j . dt_j - rk dn_j``.
    """
    nbasis = E.shape[1]
    u = np.empty((2, 2))
    for row, j in enumerate((a, b)):
        d = math.hypot(t1[j] - s1, t2[j] - s2)
        u[row, 0] = (t1[j] - s1) / d
        u[row, 1] = (t2[j] - s2) / d
    det = u[0, 0] * u[1, 1] - u[0, 1] * u[1, 0]
    inv = np.empty((2, 2))
    inv[0, 0] = u[1, 1] / det
    inv[0, 1] = -u[0, 1] / det
    inv[1, 0] = -u[1, 0] / det
    inv[1, 1] = u[0, 0] / det
    for c in range(2):
        for q in range(nbasis):
            ea = E[a, q]
            eb = E[b, q]
            D[c, 0, q] = inv[c, 0] * u[0, 0] * ea + inv[c, 1] * u[1, 0] * eb
            D[c, 1, q] = inv[c, 0] * u[0, 1] * ea + inv[c, 1] * u[1, 1] * eb
            D[c, 2, q] = -rk * (inv[c, 0] * ea + inv[c, 1] * eb)


@nb.njit(cache=True, nogil=True, error_model="numpy")
def _march(kt, kn, gaps, mu, rk, x1, x2, xn, t1, t2, n, tol, max_periods, st, rec, count, tried, moving,
           corner):  # pragma: no cover - compiled
    """Static step, then periods until every element's slider repeats to ``tol`` (Newton-accelerated).

    On return the rows of :func:`_period` (``st``, ``rec``: :func:`march_work`) hold the periodic period;
    ``count[i]`` is the number of plain periods since element ``i`` last
    started from the static step, ``moving[i]`` the last of them in which it
    slipped or opened (0: none; it stuck through the later ones), ``tried[i]`` 1 if a Newton step brought it
    where it is, 2 if that is a corner of its stick region, the samples
    ``corner[:, i]`` fixing it. Returns the periods marched, ``-1`` past
    ``max_periods``.
    """
    J = kt.shape[0]
    s1 = st[0]
    s2 = st[1]
    C = st[2:]
    el = np.empty((8, J))
    b1, b2 = el[0], el[1]  # slider at the start of the period
    st1, st2 = el[2], el[3]  # after the static step (the restart point)
    prev = el[4]  # residual of the previous period
    p1, p2 = el[5], el[6]  # the plain step's end, when a Newton step was taken instead
    lam = el[7]  # the Newton steps' length, halved each time one does not reduce the residual
    newton = np.ones(J, dtype=np.int64)
    stepped = np.zeros(J, dtype=np.int64)  # 1: this period started from a Newton step
    par = _march_parameters(kt, kn, gaps, mu, rk)
    for i in range(J):
        _, a1, a2, _, _ = _step(rk[i], xn[0] - gaps[i], x1[0], x2[0], 0.0, 0.0)
        st1[i] = a1
        st2[i] = a2
        s1[i] = a1
        s2[i] = a2
        prev[i] = np.inf
        count[i] = 0
        moving[i] = 0
        tried[i] = 0
        lam[i] = 1.0
    periods = 0
    while True:
        for i in range(J):
            b1[i] = s1[i]
            b2[i] = s2[i]
        _period_of(par, t1, t2, n, st, rec)
        periods += 1
        done = True
        for i in range(J):
            count[i] += 1
            if C[0, i] != 1.0 or C[1, i] != 0.0 or C[2, i] != 0.0 or C[3, i] != 1.0:  # C = I: stuck throughout
                moving[i] = count[i]
            r1 = s1[i] - b1[i]
            r2 = s2[i] - b2[i]
            res = max(abs(r1), abs(r2))
            restart = False
            newton_step = stepped[i]
            stepped[i] = 0
            if tried[i] and 1.0 - (C[0, i] + C[3, i]) <= NEWTON_MARGIN:
                # stuck (C = I), or nearly neutral, through a period a Newton step led to: the Newton steps
                # closed in on a corner of its stick region, where the plain march ends too; or its state must be
                # its history's
                a, b = _corner(t1, t2, n, gaps[i], rk[i], s1[i], s2[i], tol) if res <= tol else (-1, -1)
                if a >= 0:
                    tried[i] = 2
                    corner[0, i] = a
                    corner[1, i] = b
                    continue
                # the Newton step took it into its stick region, off a corner: onto the corner the plain march it
                # replaced was creeping to (the next period checks it), else from the static step plainly
                if newton_step and _land(t1, t2, n, gaps[i], rk[i], p1[i], p2[i], s1, s2, i):
                    newton[i] = 0
                    res = np.inf
                else:
                    restart = True
            elif res <= tol:
                continue
            elif newton_step and res >= prev[i]:
                # the Newton step did not reduce the residual: back to the plain step it replaced, shorter steps
                s1[i] = p1[i]
                s2[i] = p2[i]
                lam[i] *= 0.5
                if lam[i] < 1.0 / 8:
                    # the fixed point lies across a change of the slip pattern: see _land (the next period checks
                    # where it puts the slider, see _corner), else plain periods
                    _land(t1, t2, n, gaps[i], rk[i], s1[i], s2[i], s1, s2, i)
                    newton[i] = 0
                res = np.inf
            elif newton[i] and count[i] >= 2 and res < prev[i] and 1.0 - (C[0, i] + C[3, i]) > NEWTON_MARGIN:
                if newton_step:
                    lam[i] = min(1.0, 2.0 * lam[i])  # the last step reduced the residual
                m11 = 1.0 - C[0, i]
                m12 = -C[1, i]
                m21 = -C[2, i]
                m22 = 1.0 - C[3, i]
                det = m11 * m22 - m12 * m21
                n1 = b1[i] + lam[i] * (m22 * r1 - m12 * r2) / det
                n2 = b2[i] + lam[i] * (-m21 * r1 + m11 * r2) / det
                if math.isfinite(n1) and math.isfinite(n2):
                    p1[i] = s1[i]
                    p2[i] = s2[i]
                    s1[i] = n1
                    s2[i] = n2
                    tried[i] = 1
                    stepped[i] = 1
            done = False
            prev[i] = res
            if restart:
                s1[i] = st1[i]
                s2[i] = st2[i]
                newton[i] = 0
                tried[i] = 0
                count[i] = 0
                moving[i] = 0
                prev[i] = np.inf
                stepped[i] = 0
        if done:
            return periods
        if periods >= max_periods:
            return -1


@nb.njit(cache=True, nogil=True, fastmath=True)
def _sample_sums(kt, kn, mu, rec, local):  # pragma: no cover - compiled
    """Each sample's sums over the elements of the periodic period (its records ``rec``, :func:`_period`).

    ``local`` (9, Ns) receives the forces ``T1, T2`` (rows 0, 1; row 2 is
    left for the normal force) and the local derivatives ``d11 = dT1/dt1,
    d12, d22`` (``kt I`` in stick, ``kt alpha v v^T`` in slip), ``c1 =
    dT1/dn, c2 = dT2/dn`` (``mu kn u`` in slip, ``u = (v2, -v1)``) and
    ``dN/dn`` (``kn`` while closed) in rows 3 to 8. Without branches: a
    slip's records ``alpha, v`` are 0 in stick and when open.
    """
    code, alpha, V1, V2, Te1, Te2 = rec[0], rec[1], rec[2], rec[3], rec[4], rec[5]
    for k in range(code.shape[0]):
        f1 = f2 = s11 = s12 = s22 = sc1 = sc2 = scl = 0.0
        for i in range(kt.shape[0]):
            c = code[k, i]
            stick = c == STICK
            f1 += Te1[k, i]
            f2 += Te2[k, i]
            scl += kn[i] if c != OPEN else 0.0
            a = kt[i] * alpha[k, i]
            v1 = V1[k, i]
            v2 = V2[k, i]
            s11 += kt[i] if stick else a * v1 * v1
            s12 += a * v1 * v2
            s22 += kt[i] if stick else a * v2 * v2
            g = mu * kn[i]
            sc1 += g * v2
            sc2 -= g * v1
        local[0, k] = f1
        local[1, k] = f2
        local[3, k] = s11
        local[4, k] = s12
        local[5, k] = s22
        local[6, k] = sc1
        local[7, k] = sc2
        local[8, k] = scl


@nb.njit(cache=True, nogil=True)
def _sweep(rec, KR, PT, B, Y, w, active, local, U):  # pragma: no cover - compiled
    """Backward sweep of the active elements together: ``U[m]`` (6, nbp) receives ``sum Y_m G_m`` over them and
    the sample's local derivatives.

    For element ``i``, ``Y = beta (x) I + y (x) w^T`` (``beta = B[i]``
    (nbp), ``y = Y[i]`` (2, nbp), ``w = w[:, i]``, all overwritten) is the
    coefficient of its slider at the end of the period; the form is kept
    through the sweep (a slip makes it ``y (x) v^T``, a stick adds
    ``-kt P[:, m]`` to ``beta``, an opening clears it). ``U[m, 3 a + b]`` is
    column ``m``'s coefficient row for output ``a`` and input ``b``. Each
    sample is two loops over the elements: their coefficients
    (:func:`sample_coefficients`, from the records ``rec`` of :func:`_period`
    and ``KR`` = ``kt, rk``), then their contributions to the column, with
    the sample's local derivatives (``local``, :func:`_sample_sums`) times
    ``P[:, m]``, and their new ``Y`` (:func:`sample_rows`).
    """
    Ns = PT.shape[0]
    order = np.empty(active.shape[0], dtype=np.int64)  # the active elements' indices
    count = 0
    for i in range(active.shape[0]):
        if active[i]:
            order[count] = i
            count += 1
    coefs = np.empty((16, w.shape[1]))
    for m in range(Ns - 1, -1, -1):
        sample_coefficients(coefs, rec, KR, w, m)
        sample_rows(U, m, B, Y, PT, coefs, local, order, count)


@nb.njit(cache=True, nogil=True, error_model="numpy")
def _aft_plane(kt, kn, gaps, mu, x1, x2, xn, E, P, cos2, sin2, cum, tabs, max_periods,
               F, Jac):  # pragma: no cover - compiled
    """AFT of one contact on the plane. Writes ``F`` (3, nb) and ``Jac`` (3, 3, nb, nb).

    ``F`` holds the coefficients of ``T1, T2, N``; ``Jac[a, b]`` the
    derivative of output ``a`` with respect to the coefficients of input
    ``b`` (``t1, t2, n``); ``tabs`` is :func:`sweep_tables` (``cum`` is not
    used). Returns
    the number of periods marched until every element was periodic, or
    ``-1`` if some element was not after ``max_periods``.
    """
    nbasis = x1.shape[0]
    Ns = E.shape[0]
    J = kt.shape[0]
    nbp = tabs.shape[1]
    # the work arrays, views of one block of memory (two dozen allocations cost about a microsecond a call)
    block, at = _aligned_block(15 * Ns + J + Ns * 6 * nbp + 3 * J * nbp + 17 * J + 7 * nbasis + 9 * Ns * J
                               + 3 * J * nbp + 3 * nbp + 2 * cos2.shape[0] + 6 * nbp * nbp + 20 * ALIGN)
    smp, at = _take(block, at, (3, Ns))  # the motion's samples
    rk, at = _take(block, at, (J,))
    U, at = _take(block, at, (Ns, 6, nbp))
    B, at = _take(block, at, (J, nbp))
    Y, at = _take(block, at, (J, 2, nbp))
    w, at = _take(block, at, (3, J))
    KR, at = _take(block, at, (2, J))
    D, at = _take(block, at, (2, 3, nbasis))
    wD, at = _take(block, at, (nbasis,))
    nkt, at = _take(block, at, (J,))
    weights, at = _take(block, at, (Ns, 3 * J))
    ends, at = _take(block, at, (5, J))
    BZ, at = _take(block, at, (3 * J, nbp))  # every element's beta (rows 0 .. J-1), z1 (J .. 2 J-1) and z2
    local, at = _take(block, at, (9, Ns))
    forces, at = _take(block, at, (Ns, 3))  # the samples of T1, T2, N, one row per sample
    Fp, at = _take(block, at, (3, nbp))
    CS, at = _take(block, at, (2, cos2.shape[0]))
    acc, at = _take(block, at, (nbp, 6 * nbp))  # acc[q, r nbp + p]
    st, at = _take(block, at, (6, J))  # the march's rows (march_work)
    rec, at = _take(block, at, (6, Ns, J))
    ivec = np.empty((6, J), dtype=np.int64)
    count, tried, moving, corner, active = ivec[0], ivec[1], ivec[2], ivec[3:5], ivec[5]
    t1 = smp[0]
    t2 = smp[1]
    n = smp[2]
    _synthesise(E, x1, t1)
    _synthesise(E, x2, t2)
    _synthesise(E, xn, n)
    s1, s2 = st[0], st[1]
    for i in range(J):
        rk[i] = mu * kn[i] / kt[i]
    tol = periodic_tolerance(rk, gaps, t1, t2, n)
    periods = _march(kt, kn, gaps, mu, rk, x1, x2, xn, t1, t2, n, tol, max_periods, st, rec, count, tried, moving,
                     corner)
    # -- the tangential outputs' derivatives: local and history parts -----------------------------------
    # column m's coefficients, times E[m] at the end; U[m, 3 a + b, p] for output a, input b
    # (rows of nbp values, padded with zeros)
    Jac[:2] = 0.0
    PT = tabs[:Ns]
    w[:] = 0.0  # w, and whether beta is known to be zero (not yet)
    for i in range(J):
        KR[0, i] = kt[i]
        KR[1, i] = rk[i]
        nkt[i] = -kt[i]
    start_weights(rec, nkt, weights, ends)
    columns_times_basis(PT, weights, BZ)
    for i in range(J):
        beta = B[i]
        y = Y[i]
        for p in range(nbp):
            beta[p] = BZ[i, p]
            y[0, p] = BZ[J + i, p]
            y[1, p] = BZ[2 * J + i, p]
        w1, w2, cc, l1, l2 = ends[0, i], ends[1, i], ends[2, i], ends[3, i], ends[4, i]
        w[0, i] = w1
        w[1, i] = w2
        stuck = w1 == 0.0 and w2 == 0.0 and cc == 1.0
        active[i] = 0 if stuck else 1
        rho = 1.0 if stuck else cc * (l1 * w1 + l2 * w2)  # the eigenvalue of Phi_s = c l w^T
        if tried[i] == 2 or (not tried[i] and 1.0 - rho < FIXED_POINT_MARGIN):
            # the slider at the start of the period is (nearly) neutral to the period map: at a corner of its
            # stick region, fixed by the two samples whose circles meet there; or stuck through the period, or
            # slipping so little that its state is the one its history gave it: the plain march from the
            # static step is repeated with the slider's derivative carried along.
            moved = True
            if tried[i] == 2:
                _corner_derivative(t1, t2, rk[i], s1[i], s2[i], corner[0, i], corner[1, i], E, D)
            else:
                # (the periods after the last in which it slipped or opened leave the derivative as it is)
                _, _, moved = _history_derivative(rk[i], gaps[i], t1, t2, n, x1[0], x2[0], xn[0], E,
                                                  min(count[i] - 1, moving[i]), D)
            for b in range(3 if moved else 0):  # (a slider that never moved has no derivative)
                for q in range(nbasis):
                    wD[q] = w1 * D[0, b, q] + w2 * D[1, b, q]
                for a in range(2):
                    for p in range(nbasis):
                        bp = beta[p]
                        yp = y[a, p]
                        row = Jac[a, b, p]
                        for q in range(nbasis):
                            row[q] += bp * D[a, b, q] + yp * wD[q]
            beta[:] = 0.0
            y[:] = 0.0
        elif cc != 0.0:
            # Y at the end of the period: Z (I - Phi_s)^-1 = Z + Z Phi_s / (1 - rho), still beta I + y w^T
            f = cc / (1.0 - rho)
            lw = l1 * w1 + l2 * w2
            for p in range(nbasis):
                y[0, p] += f * (beta[p] * l1 + lw * y[0, p])
                y[1, p] += f * (beta[p] * l2 + lw * y[1, p])
    _sample_sums(kt, kn, mu, rec, local)
    _sweep(rec, KR, PT, B, Y, w, active, local, U)
    # -- the forces and the normal force's derivative (local only) -------------------------------------
    for k in range(Ns):
        fn = 0.0
        for i in range(J):  # element after element, as along one direction: the same normal force to the bit
            fn += kn[i] * max(n[k] - gaps[i], 0.0)
        local[2, k] = fn
    for k in range(Ns):
        for a in range(3):
            forces[k, a] = local[a, k]
    columns_times_basis(PT, forces, Fp)
    for a in range(3):
        for p in range(nbasis):
            F[a, p] = Fp[a, p]
    _dft(cos2, sin2, local[8], CS[0], CS[1])
    _diagonal_jacobian(CS[0], CS[1], Ns, Jac[2, 2])
    Jac[2, :2] = 0.0
    # -- the columns times their basis rows: one matrix product ---------------------------------------
    columns_times_basis(U.reshape(Ns, 6 * nbp), tabs[Ns:], acc)
    for r in range(6):
        a = r // 3
        b = r % 3
        for p in range(nbasis):
            for q in range(nbasis):
                Jac[a, b, p, q] += acc[q, r * nbp + p]
    return periods


@nb.njit(cache=True, nogil=True)
def aft_plane_batch(kt, kn, gaps, offsets, mu, X1, X2, XN, E, P, cos2, sin2, cum, tabs, max_periods,
                    F, Jac, periods):  # pragma: no cover - compiled
    """AFT of many contacts on the plane; contact ``c`` owns elements ``offsets[c]:offsets[c+1]``.

    ``X1, X2, XN`` have shape ``(nc, nb)``, ``F`` ``(nc, 3, nb)``, ``Jac``
    ``(nc, 3, 3, nb, nb)``; ``periods`` (int64, ``nc``) receives each
    contact's period count (``-1``: not periodic within ``max_periods``).
    """
    for c in range(X1.shape[0]):
        a = offsets[c]
        b = offsets[c + 1]
        periods[c] = _aft_plane(kt[a:b], kn[a:b], gaps[a:b], mu[c], X1[c], X2[c], XN[c], E, P, cos2, sin2, cum, tabs,
                                max_periods, F[c], Jac[c])


def aft_mixed_batch(kt, kn, gaps, offsets, mu, planar, XT, XT2, XN, E, P, cos2, sin2, cum, tabs, max_periods,
                    FT, FN, JTt, JTn, JNn, FT2, JT12, JT21, JT22, JT2n, periods):
    """AFT of contacts along one direction and on their planes (``planar[c]``), in one call.

    The one-direction arrays as :func:`microslip.kernels.aft.aft_batch`
    (for a contact on its plane: its first direction's); ``FT2`` (nc, nb)
    the second tangential force, ``JT12, JT21, JT22, JT2n`` (nc, nb, nb) the
    derivatives of ``T1`` by ``t2``, ``T2`` by ``t1``, ``t2`` and ``n``
    (zero for a one-direction contact). Two compiled loops, the contacts on
    their planes and those along one direction: the second is compiled only
    where a structure has such contacts besides contacts on their planes.
    """
    _planes_batch(kt, kn, gaps, offsets, mu, planar, XT, XT2, XN, E, P, cos2, sin2, cum, tabs, max_periods,
                  FT, FN, JTt, JTn, JNn, FT2, JT12, JT21, JT22, JT2n, periods)
    if not planar.all():
        _lines_batch(kt, kn, gaps, offsets, mu, planar, XT, XN, E, P, cos2, sin2, cum, max_periods, FT, FN, JTt,
                     JTn, JNn, periods)


@nb.njit(cache=True, nogil=True)
def _planes_batch(kt, kn, gaps, offsets, mu, planar, XT, XT2, XN, E, P, cos2, sin2, cum, tabs, max_periods,
                  FT, FN, JTt, JTn, JNn, FT2, JT12, JT21, JT22, JT2n, periods):  # pragma: no cover - compiled
    """The contacts of :func:`aft_mixed_batch` on their planes."""
    nbasis = XT.shape[1]
    F = np.empty((3, nbasis))
    Jac = np.empty((3, 3, nbasis, nbasis))
    for c in range(XT.shape[0]):
        if not planar[c]:
            continue
        a = offsets[c]
        b = offsets[c + 1]
        periods[c] = _aft_plane(kt[a:b], kn[a:b], gaps[a:b], mu[c], XT[c], XT2[c], XN[c], E, P, cos2, sin2, cum,
                                tabs, max_periods, F, Jac)
        for p in range(nbasis):
            FT[c, p] = F[0, p]
            FT2[c, p] = F[1, p]
            FN[c, p] = F[2, p]
            for q in range(nbasis):
                JTt[c, p, q] = Jac[0, 0, p, q]
                JT12[c, p, q] = Jac[0, 1, p, q]
                JTn[c, p, q] = Jac[0, 2, p, q]
                JT21[c, p, q] = Jac[1, 0, p, q]
                JT22[c, p, q] = Jac[1, 1, p, q]
                JT2n[c, p, q] = Jac[1, 2, p, q]
                JNn[c, p, q] = Jac[2, 2, p, q]


@nb.njit(cache=True, nogil=True)
def _lines_batch(kt, kn, gaps, offsets, mu, planar, XT, XN, E, P, cos2, sin2, cum, max_periods,
                 FT, FN, JTt, JTn, JNn, periods):  # pragma: no cover - compiled
    """The contacts of :func:`aft_mixed_batch` along one direction."""
    for c in range(XT.shape[0]):
        if not planar[c]:
            a = offsets[c]
            b = offsets[c + 1]
            periods[c] = _aft_contact(kt[a:b], kn[a:b], gaps[a:b], mu[c], XT[c], XN[c], E, P, cos2, sin2, cum,
                                      max_periods, FT[c], FN[c], JTt[c], JTn[c], JNn[c])
