"""Compiled residual and Jacobian of the dense harmonic balance equations (private).

The same equations as :meth:`microslip.frequency.equations.hbm.HarmonicBalance.evaluate_reference`
(the NumPy twin used by the tests and by sparse structures), in one call:
no temporaries, no Python overhead, which matters for small structures
where a Newton iteration costs a few microseconds.
"""

from __future__ import annotations

import numba as nb
import numpy as np

from .aft import _aft_contact


@nb.njit(cache=True, nogil=True)
def evaluate_dense(x, omega, Kx, Cx, Mx, MD, xi, lo, hi, f, Bt, Bn, n0, t0, kt, kn, gaps, offsets, mu,
                   E, P, cos2, sin2, cum, max_periods, jacobian,
                   R, J, Rw, FT, FN, JTt, JTn, JNn, periods):  # pragma: no cover - compiled
    """Write ``R`` (n), and if ``jacobian`` ``J`` (n, n) and ``Rw`` (n).

    ``x`` is harmonic-major: ``x[p * ndof + i]`` is coefficient ``p`` of DOF ``i``.
    The linear part is ``Kx + omega (Cx - xi MD) - omega^2 Mx`` (``MD`` is read
    only when ``xi`` is not zero); row ``r`` of each of these matrices is zero
    outside the columns ``lo[r] <= s < hi[r]`` (the harmonic it belongs to), so
    only those are read and the rest of ``J``'s row is set to zero. Contact
    ``c`` sees ``t = Bt[:, c] . q - t0[c]`` and ``n = Bn[:, c] . q + n0[c]``.
    Returns the smallest period count of the contacts (``-1``: one was not periodic).
    """
    n = x.shape[0]
    ndof = Bt.shape[0]
    nc = Bt.shape[1]
    nbasis = n // ndof
    w2 = omega * omega
    wxi = omega * xi
    damped = xi != 0.0
    for r in range(n):
        acc = -f[r]
        accw = 0.0
        if jacobian:
            for s in range(lo[r]):
                J[r, s] = 0.0
            for s in range(hi[r], n):
                J[r, s] = 0.0
        for s in range(lo[r], hi[r]):
            z = Kx[r, s] + omega * Cx[r, s] - w2 * Mx[r, s]
            if damped:
                z -= wxi * MD[r, s]
            acc += z * x[s]
            if jacobian:
                J[r, s] = z
                zw = Cx[r, s] - 2.0 * omega * Mx[r, s]
                if damped:
                    zw -= xi * MD[r, s]
                accw += zw * x[s]
        R[r] = acc
        Rw[r] = accw
    worst = max_periods
    xt = np.empty(nbasis)
    xn = np.empty(nbasis)
    for c in range(nc):
        for p in range(nbasis):
            a = 0.0
            b = 0.0
            for i in range(ndof):
                a += x[p * ndof + i] * Bt[i, c]
                b += x[p * ndof + i] * Bn[i, c]
            xt[p] = a
            xn[p] = b
        xn[0] += n0[c]
        xt[0] -= t0[c]
        lo = offsets[c]
        hi = offsets[c + 1]
        k = _aft_contact(kt[lo:hi], kn[lo:hi], gaps[lo:hi], mu[c], xt, xn, E, P, cos2, sin2, cum,
                         max_periods, FT[c], FN[c], JTt[c], JTn[c], JNn[c])
        periods[c] = k
        worst = min(worst, k)
        for i in range(ndof):
            bti = Bt[i, c]
            bni = Bn[i, c]
            if bti == 0.0 and bni == 0.0:
                continue
            for p in range(nbasis):
                R[p * ndof + i] += FT[c, p] * bti + FN[c, p] * bni
            if not jacobian:
                continue
            for j in range(ndof):
                btj = Bt[j, c]
                bnj = Bn[j, c]
                if btj == 0.0 and bnj == 0.0:
                    continue
                ctt = bti * btj
                ctn = bti * bnj
                cnn = bni * bnj
                for p in range(nbasis):
                    row = p * ndof + i
                    for q in range(nbasis):
                        J[row, q * ndof + j] += ctt * JTt[c, p, q] + ctn * JTn[c, p, q] + cnn * JNn[c, p, q]
    return worst
