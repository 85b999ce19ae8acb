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

On the contact plane (two tangential components, :func:`plane_step`,
:func:`march_plane`) each element is an isotropic Jenkins slider: the trial
force ``kt_i (t - s_i)`` is returned radially onto the disc of radius
``mu N_i``::

    d = t - s_i                                   (a vector of the plane)
    if kt_i |d| > mu N_i:  T_i = mu N_i d / |d|,  s_i = t - T_i / kt_i     (slip)
    else:                  T_i = kt_i d                                    (stick)

On a line of the plane this is the one-direction rule, to rounding (the step
computes ``|d|`` and ``d / |d|`` where the line clips).

Plain numba loops, no hand-written vector code. Their arithmetic is additions,
products, divisions and square roots, each rounded by IEEE 754, with no
``fastmath``: the compiler neither fuses a product and a sum into one
multiply-add nor reorders a sum, so the marches give the same numbers bit for
bit on every processor numba compiles for (``NUMBA_CPU_NAME``; vectors of any
width or none), equal to their pure-Python twins (``tests/model/test_targets.py``
compares a generic x86-64 and an AVX2 target with the host).
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

OPEN = 0
STICK = 1
SLIP = 2
#: the smallest ``|d|^2`` (m^2) :func:`plane_step` divides by (``2^-1000``: its reciprocal is finite)
DD2_MIN = 2.0 ** -1000
#: a stretch and stick radius all below this (m, ``2^-500``, 3e-151 m) are scaled by :data:`TINY_SCALE` in
#: :func:`plane_step`: their squares would underflow (to zero below 1e-162 m, losing digits above)
TINY = 2.0 ** -500
#: the power of two (exact) that scales a tiny stretch and radius: the smallest subnormal stretch becomes
#: ``2^-474`` (its square normal), the largest tiny one ``2^100`` (its square far from overflowing)
TINY_SCALE = 2.0 ** 600
#: the cap on the ``q = 1 / |d|`` :func:`plane_step` returns: finite for a subnormal stretch (below ``2^-1023`` m)
Q_MAX = 2.0 ** 1023


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


@nb.njit(cache=True, nogil=True, inline="always", error_model="numpy")
def plane_step(kt, rk, mkn, kn, nk, tx, ty, sx, sy):  # pragma: no cover - compiled
    """One element on the contact plane, one step: ``(Tx, Ty, N_i, code, new sx, new sy, alpha, q)``.

    Parameters (float): ``kt``, ``kn`` (N/m), ``rk = mu kn / kt`` and
    ``mkn = mu kn`` (computed once per element by the caller, as
    ``(mu * kn) / kt`` and ``mu * kn``), ``nk = n - gap`` (m), the sample
    ``tx``, ``ty`` (m) and the slider ``sx``, ``sy`` (m) before the step.
    Returns the element's force (N), its normal force (N), its condition
    (``OPEN``, ``STICK``, ``SLIP``), the slider after the step (m) and, in
    slip, ``alpha = r / |d|`` and ``q = 1 / |d|`` (meaningless otherwise).

    Radial return with the stick radius ``r = rk nk``: with ``d = t - s``,
    the element is open for ``nk <= 0`` (no force, the slider at ``t``),
    sticks for ``|d|^2 <= r^2`` (``T = kt d``) and slips otherwise:
    ``q = sqrt(|d|^2) (1 / |d|^2)`` (``1 / |d|``: a square root and a
    division side by side, not one after the other, which shortens the
    wait of a march on its slider by a third), ``s = t - (r d) q`` (``r d``
    is ready before ``q``), ``T = (mkn nk q) d``. ``|d|^2`` is ``dx^2 + dy^2``: the callers keep
    displacements below 1e100 m, so it never overflows.

    Tiny stretches: when ``|dx|``, ``|dy|`` and ``r`` are all below
    :data:`TINY` (3e-151 m), their squares would underflow (below 1e-162 m
    both are zero and the element would stick with ``|T| >> mu N_i``), so
    ``d`` and ``r`` are first multiplied by :data:`TINY_SCALE` (a power of
    two: exact), ``e = scale d``, ``q = sqrt(|e|^2) (scale^-1 / |e|^2)``
    (``1 / (scale |e|)``), ``s = t - (r_s e) q`` (``r_s = scale r``) and
    ``T = mkn nk (e / |e|)`` (not ``(mkn nk / |e|) e``, which underflows),
    so that the force is on the edge of the disc to rounding down to the
    smallest subnormal stretch. Above :data:`TINY` the scale is 1 and every
    number is the unscaled formula's, bit for bit. The ``q`` returned is
    ``1 / |d|``, capped at :data:`Q_MAX` for a subnormal stretch;
    ``DD2_MIN`` keeps it finite at ``d = 0`` (in stick).

    The one element update of the package on the plane: ``march_plane``
    (:func:`MicroslipModel.simulate <microslip.model.MicroslipModel.simulate>`),
    the AFT's periods and the frequency package's marches call it, so they
    agree bit for bit. Written with selects and no branch, so that a loop
    over elements calling it vectorises (see :func:`march_plane`).
    """
    closed = nk > 0.0
    r = rk * nk
    dx = tx - sx
    dy = ty - sy
    tiny = max(abs(dx), abs(dy), r) < TINY  # the squares below would underflow
    scale = TINY_SCALE if tiny else 1.0  # a power of two (exact); 1 above TINY: the unscaled numbers, bit for bit
    unscale = 1.0 / TINY_SCALE if tiny else 1.0  # exact too
    ex = dx * scale
    ey = dy * scale
    rs = r * scale
    dd2 = ex * ex + ey * ey
    slipped = dd2 > rs * rs
    q = math.sqrt(dd2) * (unscale / max(dd2, DD2_MIN))  # 1 / (scale |e|), e = scale d
    qe = q * scale  # 1 / |e|
    al = rs * qe
    g = mkn * nk * q
    f = mkn * nk
    # slip: (mkn nk / |d|) d, unless tiny: mu N_i (e / |e|), without the underflow of mu N_i / |e|
    Tx = ((f * (ex * qe) if tiny else g * dx) if slipped else kt * dx) if closed else 0.0
    Ty = ((f * (ey * qe) if tiny else g * dy) if slipped else kt * dy) if closed else 0.0
    new_sx = (tx - (rs * ex) * q if slipped else sx) if closed else tx  # rs e while q is computed: a shorter wait
    new_sy = (ty - (rs * ey) * q if slipped else sy) if closed else ty
    code = (SLIP if slipped else STICK) if closed else OPEN
    return Tx, Ty, kn * max(nk, 0.0), code, new_sx, new_sy, al, min(qe * scale, Q_MAX)


@nb.njit(cache=True, nogil=True, inline="always", error_model="numpy")
def plane_tangent(kt, kn, gap, mu, tx, ty, n, sx, sy):  # pragma: no cover - compiled
    """Consistent tangent of :func:`plane_step` at the same arguments: ``(Kxx, Kxy, Kyy, Dx, Dy)``.

    ``K = dT/dt`` (N/m, symmetric 2x2) and ``D = dT/dn`` (N/m, a vector):
    ``kt I`` and ``0`` in stick; ``(mu N_i / |d|) (I - u u^T)`` and
    ``mu kn u`` in slip (``u = d / |d|``); zero for an open element. The
    derivatives with respect to the slider before the step are ``-K``; the
    slider after the step, ``s' = t - T / kt``, has ``ds'/dt = I - K / kt``,
    ``ds'/ds = K / kt``, ``ds'/dn = -D / kt``. The condition is the
    step's own (:func:`plane_step`, the same arithmetic).
    """
    mkn = mu * kn
    nk = n - gap
    dx = tx - sx
    dy = ty - sy
    _, _, _, code, _, _, _, q = plane_step(kt, mkn / kt, mkn, kn, nk, tx, ty, sx, sy)
    if code == OPEN:
        return 0.0, 0.0, 0.0, 0.0, 0.0
    if code == SLIP:
        ux = dx * q
        uy = dy * q
        g = mkn * nk * q
        return g * (1.0 - ux * ux), -g * ux * uy, g * (1.0 - uy * uy), mkn * ux, mkn * uy
    return kt, 0.0, kt, 0.0, 0.0


@nb.njit(cache=True, nogil=True, error_model="numpy")
def plane_tangents(kt, kn, gaps, mu, tx, ty, n, s, out):  # pragma: no cover - compiled
    """The array's consistent tangent for the step to ``(tx, ty, n)`` from sliders ``s`` (``(J, 2)``).

    Writes ``out = (Kxx, Kxy, Kyy, Dx, Dy)``: the sums of :func:`plane_tangent` over the elements.
    """
    for j in range(5):
        out[j] = 0.0
    for i in range(kt.shape[0]):
        kxx, kxy, kyy, ddx, ddy = plane_tangent(kt[i], kn[i], gaps[i], mu, tx, ty, n, s[i, 0], s[i, 1])
        out[0] += kxx
        out[1] += kxy
        out[2] += kyy
        out[3] += ddx
        out[4] += ddy


@nb.njit(cache=True, nogil=True, inline="always")
def plane_work(Tx, Ty, sx_old, sy_old, sx_new, sy_new):  # pragma: no cover - compiled
    """Work of the element's force on its slider's travel in one step on the plane (J).

    Zero in stick; in slip the slider moves along the force, so the product
    is positive (the ``max`` only absorbs a rounding of the last unit).
    """
    return max(Tx * (sx_new - sx_old) + Ty * (sy_new - sy_old), 0.0)


@nb.njit(cache=True, nogil=True, error_model="numpy")
def march_plane(kt, kn, gaps, mu, t, n, s, T, N, W, Ti, cond):  # pragma: no cover - compiled
    """March the plane history ``t`` (shape ``(steps, 2)``), ``n`` from sliders ``s`` (``(J, 2)``, in place).

    As :func:`march`, with ``T`` of shape ``(steps, 2)`` and, unless empty,
    ``Ti`` of shape ``(steps, J, 2)``; ``N``, ``W`` ``(steps,)`` and ``cond``
    ``(steps, J)`` as there (an element is recorded open where its ``N_i``
    is zero).

    Each sample updates every element with :func:`plane_step` (``mu kn / kt``
    and ``mu kn`` computed as ``(mu * kn) / kt`` and ``mu * kn``) in one
    loop over contiguous scratch rows, copies the records from the rows, then
    adds the rows in element order, as the twin
    (:func:`march_plane_reference`) does: equal to it bit for bit. Only
    IEEE-rounded operations without fused multiply-adds or reordered sums, so
    the numbers are the same on every processor numba compiles for.
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
    for i in range(J):
        sx[i] = s[i, 0]
        sy[i] = s[i, 1]
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
    for i in range(J):
        s[i, 0] = sx[i]
        s[i, 1] = sy[i]


NO_WORK = np.empty(0)
NO_ELEMENTS = np.empty((0, 0))
NO_CONDITIONS = np.empty((0, 0), dtype=np.int8)
NO_PLANE_ELEMENTS = np.empty((0, 0, 2))


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


def march_plane_reference(kt, kn, gaps, mu, t, n, s):
    """Slow, obviously correct pure-Python twin of :func:`march_plane`.

    ``t`` is a sequence of ``(tx, ty)`` pairs and ``s`` of ``J`` pairs (m);
    returns ``(T, N, W, Ti, cond, s)`` as lists (``T`` of pairs, ``Ti`` of
    lists of pairs); ``s`` is not modified.
    """
    s = [[float(v[0]), float(v[1])] for v in s]
    T, N, W, Ti_all, cond_all = [], [], [], [], []
    for (tx, ty), nk in zip(t, n):
        row_T, row_c, row_W, row_N = [], [], [], []
        for i in range(len(kt)):
            depth = nk - gaps[i]  # n - gap: open at or below zero
            Ni = kn[i] * max(depth, 0.0)
            r = mu * kn[i] / kt[i] * depth  # the stick radius mu N_i / kt
            dx, dy = tx - s[i][0], ty - s[i][1]  # the stretch d = t - s
            tiny = max(abs(dx), abs(dy), r) < TINY  # their squares would underflow: scale by a power of two
            scale = TINY_SCALE if tiny else 1.0
            ex, ey, rs = dx * scale, dy * scale, r * scale  # e = scale d, exact
            d2 = ex * ex + ey * ey
            if depth <= 0.0:  # open: no force, the slider at t
                Tx, Ty, new, c = 0.0, 0.0, [tx, ty], OPEN
            elif d2 > rs * rs:  # the trial force kt d leaves the disc: back onto its edge along d
                q = math.sqrt(d2) * ((1.0 / scale) / max(d2, DD2_MIN))  # 1 / (scale |e|), as plane_step computes it
                if tiny:  # mu N_i e / |e|
                    qe = q * scale
                    Tx, Ty = mu * kn[i] * depth * (ex * qe), mu * kn[i] * depth * (ey * qe)
                else:  # (mu N_i / |d|) d
                    g = mu * kn[i] * depth * q
                    Tx, Ty = g * dx, g * dy
                new, c = [tx - rs * ex * q, ty - rs * ey * q], SLIP
            else:
                Tx, Ty, new, c = kt[i] * dx, kt[i] * dy, s[i], STICK
            row_W.append(max(Tx * (new[0] - s[i][0]) + Ty * (new[1] - s[i][1]), 0.0))
            s[i] = new
            row_T.append((Tx, Ty))
            row_c.append(c)
            row_N.append(Ni)
        Ti_all.append(row_T)
        cond_all.append(row_c)
        Tx_sum = Ty_sum = N_sum = W_sum = 0.0  # added in the kernel's order (no compensated sum)
        for (Tx, Ty), Ni, work in zip(row_T, row_N, row_W):
            Tx_sum, Ty_sum, N_sum, W_sum = Tx_sum + Tx, Ty_sum + Ty, N_sum + Ni, W_sum + work
        T.append((Tx_sum, Ty_sum))
        N.append(N_sum)
        W.append(W_sum)
    return T, N, W, Ti_all, cond_all, s


def warm_up() -> None:
    """Compile (or load from cache) the kernel on a tiny input."""
    one = np.ones(1)
    z = np.zeros(1)
    march(one, one, z, 0.5, z, one, np.zeros(1), np.empty(1), np.empty(1), np.empty(1),
          np.empty((1, 1)), np.empty((1, 1), dtype=np.int8))
    march_plane(one, one, z, 0.5, np.zeros((1, 2)), one, np.zeros((1, 2)), np.empty((1, 2)), np.empty(1),
                np.empty(1), np.empty((1, 1, 2)), np.empty((1, 1), dtype=np.int8))
    plane_tangents(one, one, z, 0.5, 0.0, 0.0, 1.0, np.zeros((1, 2)), np.empty(5))
