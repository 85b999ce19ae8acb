"""Speed of one AFT call with its Jacobian for a contact on its plane (J = 8, H = 7, 128 samples).

Run:  python benchmarks/bench_aft_plane.py

* microslip, the compiled kernel: per contact in one compiled call for a batch of ``BATCH`` identical contacts,
  as the harmonic balance evaluates its contacts (preallocated outputs), one call of the kernel from Python
  (the same, plus the call's dispatch of its 16 arguments), and the public checked wrapper
  ``microslip.frequency.aft_plane``;
* baseline, in the same run: a NumPy AFT on the plane vectorised over the elements (loop over the samples,
  plain periods until the sliders repeat to the kernel's tolerance) with a central finite-difference
  Jacobian (2 x 3 (2H + 1) evaluations);
* for scale, the one-direction ``aft`` of the same contact along the orbit's major axis.

The contact: the paper's sphere tuned with 8 elements at 37.5 N, its normal approach varying by +-20 %
around the mean. Orbits: a microslip ellipse (0.6 x 0.3 µm: the outer elements slip, the centre
sticks), and gross slip on an ellipse (3 x 1.5 µm) and on a circle (3 µm), every element slipping.
Times are the best of 7 rounds (microseconds per call); the machine is shared, so the ratio to the
baseline, measured in the same run, is the figure to compare.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from microslip import Sphere, tune
from microslip.kernels import aft as _aft, aft_plane as _aft_plane
from microslip.frequency import aft, aft_plane

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_aft import best_time  # noqa: E402  (the same timing in both AFT benchmarks)

H, NS, J = 7, 128, 8
NB = 2 * H + 1
#: contacts per compiled call in the batch timing
BATCH = 16
TOL_ULPS = _aft_plane.PERIODIC_ULPS


def numpy_aft_plane(model, x, xn, E, P, max_periods=100000):
    """Baseline: the forces of the periodic state, vectorised over the elements, a Python loop over samples."""
    t = E @ x.T  # (Ns, 2)
    n = E @ xn
    kt, kn, g, mu = model.kt, model.kn, model.gaps, model.mu
    r = mu * kn / kt  # stick radius per unit of n - g

    def step(tk, nk, s):
        closed = nk > g
        d = tk[None, :] - s
        size = np.hypot(d[:, 0], d[:, 1])
        rad = r * np.maximum(nk - g, 0.0)
        slip = closed & (size > rad)
        scale = np.where(slip, rad / np.where(slip, size, 1.0), 1.0)
        T = np.where(closed[:, None], kt[:, None] * d * scale[:, None], 0.0)
        s = np.where(closed[:, None], tk[None, :] - T / kt[:, None], tk[None, :])
        return T.sum(axis=0), s

    _, s = step(x[:, 0], xn[0], np.zeros((kt.size, 2)))
    tol = TOL_ULPS * np.finfo(float).eps * (np.abs(t).sum(axis=1).max() + (r * np.maximum(n.max() - g, 0)).max())
    T = np.empty((NS, 2))
    for _ in range(max_periods):
        start = s.copy()
        for k in range(NS):
            T[k], s = step(t[k], n[k], s)
        if np.abs(s - start).max() <= tol:
            break
    N = (kn * np.maximum(n[:, None] - g, 0.0)).sum(axis=1)
    return P @ T, P @ N


def numpy_aft_plane_with_fd_jacobian(model, x, xn, E, P, h=1e-13):
    FT, FN = numpy_aft_plane(model, x, xn, E, P)
    Jac = np.empty((3 * NB, 3 * NB))
    for b in range(3):
        for q in range(NB):
            cols = []
            for sign in (1.0, -1.0):
                xx, nn = x.copy(), xn.copy()
                if b < 2:
                    xx[b, q] += sign * h
                else:
                    nn[q] += sign * h
                T, N = numpy_aft_plane(model, xx, nn, E, P)
                cols.append(np.concatenate([T[:, 0], T[:, 1], N]))
            Jac[:, b * NB + q] = (cols[0] - cols[1]) / (2 * h)
    return FT, FN, Jac


def cases():
    sphere = Sphere.paper()
    model = tune(sphere, 37.5, elements=J)
    n0 = float(sphere.approach(37.5))
    xn = np.zeros(NB)
    xn[0], xn[1] = n0, 0.2 * n0
    out = []
    for name, a, b in (("microslip ellipse 0.6 x 0.3 µm", 0.6e-6, 0.3e-6),
                       ("gross slip ellipse 3 x 1.5 µm", 3e-6, 1.5e-6), ("gross slip circle 3 µm", 3e-6, 3e-6)):
        x = np.zeros((2, NB))
        x[0, 1], x[0, 3], x[1, 2] = a, 0.1 * a, b
        out.append((name, model, x, xn))
    return out


def batch_arguments(model, x1, x2, xn):
    """The arguments of ``aft_plane_batch`` for ``BATCH`` copies of one contact: the contacts' data (8 arrays)
    and the outputs (forces, Jacobians, periods)."""
    tile = (lambda a: np.tile(a, BATCH))
    rows = (lambda a: np.ascontiguousarray(np.tile(a, (BATCH, 1))))
    return (tile(model.kt), tile(model.kn), tile(model.gaps), np.arange(BATCH + 1) * model.elements,
            np.full(BATCH, model.mu), rows(x1), rows(x2), rows(xn), np.empty((BATCH, 3, NB)),
            np.empty((BATCH, 3, 3, NB, NB)), np.empty(BATCH, dtype=np.int64))


def main():
    tables = _aft.tables(H, NS)
    E, P = tables[0], tables[1]
    PT = _aft_plane.sweep_tables(H, NS)
    print(f"AFT on the contact plane with Jacobian, J = {J}, H = {H}, {NS} samples per period "
          f"(best of 7, microseconds per call)")
    rows = []
    for name, model, x, xn in cases():
        F, Jac = np.empty((3, NB)), np.empty((3, 3, NB, NB))
        x1, x2 = np.ascontiguousarray(x[0]), np.ascontiguousarray(x[1])
        periods = _aft_plane._aft_plane(model.kt, model.kn, model.gaps, model.mu, x1, x2, xn, *tables, PT, 1000, F,
                                        Jac)
        t_kernel = best_time(lambda: _aft_plane._aft_plane(model.kt, model.kn, model.gaps, model.mu, x1, x2, xn,
                                                           *tables, PT, 1000, F, Jac))
        batch = batch_arguments(model, x1, x2, xn)
        t_batch = best_time(lambda: _aft_plane.aft_plane_batch(*batch[:8], *tables, PT, 1000, *batch[8:])) / BATCH
        assert np.array_equal(batch[-2][-1], Jac) and np.array_equal(batch[-3][-1], F), name  # the same numbers
        t_public = best_time(lambda: aft_plane(model, x, xn, samples=NS))
        t_line = best_time(lambda: aft(model, x[0], xn, samples=NS))
        t_numpy = best_time(lambda: numpy_aft_plane_with_fd_jacobian(model, x, xn, E, P), repeat=2, number=1)
        # the baseline computes the same periodic forces and, to its differences, the same Jacobian
        FT, FN, Jfd = numpy_aft_plane_with_fd_jacobian(model, x, xn, E, P)
        scale = np.abs(FT).max()
        assert np.allclose(FT.T, F[:2], rtol=0, atol=1e-9 * scale), name
        exact = np.block([[Jac[a, b] for b in range(3)] for a in range(3)])
        assert np.allclose(exact, Jfd, rtol=0, atol=1e-5 * np.abs(exact).max()), name
        rows.append((name, t_batch, t_kernel, t_public, t_numpy, t_line, periods))
        print(f"{name:32s} periods {periods}   kernel per contact in a batch {t_batch * 1e6:5.1f}, "
              f"one call {t_kernel * 1e6:5.1f}   public aft_plane() {t_public * 1e6:5.1f}"
              f"   one direction aft() {t_line * 1e6:6.1f}   NumPy + finite differences {t_numpy * 1e3:8.1f} ms"
              f"   ratio {t_numpy / t_batch:7.0f}x")
    print("target:")
    for name, t_batch, *_ in rows:
        print(f"  under 40 µs per contact as the harmonic balance evaluates it, {name}: "
              f"{'met' if t_batch < 40e-6 else 'MISSED'} ({t_batch * 1e6:.1f} µs)")
    from _common import save_results

    table = {"caption": "AFT on the plane with its Jacobian, per contact (µs), against a NumPy AFT with a "
                        "finite-difference Jacobian in the same run",
             "columns": ["orbit", "periods", "kernel per contact in a batch (µs)", "one kernel call (µs)",
                         "public aft_plane() (µs)", "one-direction aft() (µs)", "NumPy + finite differences (ms)",
                         "ratio to the batch"],
             "rows": [[name, periods, b * 1e6, k * 1e6, pub * 1e6, line * 1e6, num * 1e3, num / b]
                      for name, b, k, pub, num, line, periods in rows]}
    figures = {"description": f"The AFT on the contact plane with its exact Jacobians: a J = {J} sphere contact, "
                              f"H = {H}, {NS} samples per period, normal load varying by 20 %, best of 7; per "
                              f"contact as the harmonic balance evaluates its contacts (one compiled call for "
                              f"{BATCH} contacts).",
               "command": "OPENBLAS_NUM_THREADS=1 python benchmarks/bench_aft_plane.py", "tables": [table]}
    print(f"saved to {save_results('bench_aft_plane', figures)}")
    return rows


if __name__ == "__main__":
    main()
