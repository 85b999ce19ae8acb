"""Benchmark: the exact MDR reference (2000 elements) over 10^5 steps, against a plain NumPy march.

Run: ``python benchmarks/bench_mdr.py``. Prints the time of the compiled march
(``MicroslipModel.simulate(..., per_element=False, work=False)``: the totals, as the baseline) and of a baseline measured
in the same run: the same return mapping written as a NumPy-vectorised loop over
the steps (each step one set of array operations on the 2000 elements). Both
give the same forces (checked). Target: the compiled march under 2 s.
"""

from __future__ import annotations

import time

import numpy as np

from microslip import Sphere, mdr


def numpy_march(model, t, n):
    """Baseline: one NumPy-vectorised return-mapping step per sample."""
    kt, kn, gaps, mu = model.kt, model.kn, model.gaps, model.mu
    s = np.zeros(model.elements)
    T = np.empty(t.size)
    for k in range(t.size):
        lim = mu * kn * np.maximum(n[k] - gaps, 0.0)
        trial = kt * (t[k] - s)
        Ti = np.clip(trial, -lim, lim)
        s = np.where(Ti != trial, t[k] - Ti / kt, s)
        T[k] = Ti.sum()
    return T


def main(steps: int = 100_000, elements: int = 2000) -> None:
    sphere = Sphere.paper()
    ref = mdr(sphere, max_load=37.5, elements=elements)
    tau = np.linspace(0.0, 40 * np.pi, steps)  # 20 cycles, the normal load varying out of phase
    N = 20.0 + 15.0 * np.sin(tau + np.pi / 2)
    t = 1.5 * float(sphere.gross_slip_displacement(5.0)) * np.sin(tau)
    n = sphere.approach(N)
    ref.simulate(t[:10], n[:10], per_element=False, work=False)  # compile / load the kernel cache

    t0 = time.perf_counter()
    r = ref.simulate(t, n, per_element=False, work=False)
    compiled = time.perf_counter() - t0

    t0 = time.perf_counter()
    T_np = numpy_march(ref, t, n)
    baseline = time.perf_counter() - t0

    assert np.allclose(r.T, T_np, rtol=0, atol=1e-9 * np.max(np.abs(T_np))), "the two marches disagree"
    print(f"MDR reference: {elements} elements, {steps} steps ({elements * steps:.3g} element-steps)")
    print(f"  compiled kernel (simulate, totals only): {compiled:8.3f} s   (target < 2 s)")
    print(f"  baseline: NumPy-vectorised per-step march     : {baseline:8.3f} s")
    print(f"  speed-up: {baseline / compiled:.1f}x   [{'PASS' if compiled < 2.0 else 'FAIL'}]")


if __name__ == "__main__":
    main()
