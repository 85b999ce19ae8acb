"""Speed of ``MicroslipModel.simulate`` on the contact plane against a NumPy per-step march, in one run.

What is measured
----------------
* Element updates per second (steps x J / wall time) of ``simulate`` with ``t`` of shape
  ``(steps, 2)`` for J = 4, 16 and 64 over 10^6 steps, in three modes: ``per_element=True``
  (every element's force on the plane, its condition, the friction work), ``per_element=False``
  (totals and friction work) and ``per_element=False, work=False`` (the total forces only: the
  output of the NumPy baseline). Best of ``--repeat`` runs; the compiling call is excluded.
* The same physics in plain NumPy: the radial return of every element vectorised over the
  elements, a Python loop over the steps, on ``--baseline-steps`` steps (2*10^4; its cost per
  step does not depend on the number of steps), checked against ``simulate``.

* The compiled kernel alone in the first mode, writing into output arrays allocated and touched
  beforehand: ``simulate`` allocates 272 bytes per step at J = 16 (the element forces on the plane
  and their conditions), and touching that fresh memory the first time costs about as much as the
  march itself on this machine.

The load path: the paper's sphere tuned with J elements, an elliptical orbit (semi-axes 1.2 and
0.72 times the gross-slip displacement at the tuning load) and a normal approach cycling between
0.3 and 1 times the tuning approach (elements open, close, stick and slide round).

Run ``python benchmarks/bench_plane.py`` (about a minute); ``--steps`` shortens it.
Targets: >= 2e8 element updates/s at J = 16 and >= 100 x the NumPy march.
"""

from __future__ import annotations

import argparse
import platform
import time

import numpy as np

from microslip import Sphere, _kernels, tune
from microslip._kernels import warm_up

N_TOT = 37.5


def load_path(sphere, steps, cycles=None):
    """t (m, (steps, 2)) on an ellipse of 1.2 x 0.72 t_gs; n (m) between 0.3 and 1 n_tot."""
    cycles = cycles if cycles is not None else max(1, steps // 1000)
    tau = 2 * np.pi * cycles * np.arange(steps) / steps
    a = 1.2 * float(sphere.gross_slip_displacement(N_TOT))
    t = np.column_stack([a * np.cos(tau), 0.6 * a * np.sin(tau)])
    n = float(sphere.approach(N_TOT)) * (0.65 + 0.35 * np.sin(0.37 * tau + 0.5))
    return t, n


def numpy_march(model, t, n):
    """The radial return on the plane in plain NumPy: one vectorised update of the J elements per step."""
    kt, kn, gaps, mu = model.kt, model.kn, model.gaps, model.mu
    s = np.zeros((model.elements, 2))
    T = np.empty((t.shape[0], 2))
    N = np.empty(t.shape[0])
    with np.errstate(invalid="ignore", divide="ignore"):
        for k in range(t.shape[0]):
            Ni = kn * np.maximum(n[k] - gaps, 0.0)
            lim = mu * Ni
            d = t[k] - s
            size = np.sqrt(d[:, 0] ** 2 + d[:, 1] ** 2)
            slip = kt * size > lim
            g = np.where(slip, lim / size, kt)[:, None]
            Ti = np.where((Ni > 0)[:, None], g * d, 0.0)
            s = np.where((Ni == 0)[:, None], t[k], np.where(slip[:, None], t[k] - Ti / kt[:, None], s))
            T[k] = Ti.sum(axis=0)
            N[k] = Ni.sum()
    return T, N


def best_time(fn, repeat):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


MODES = [("elements + work", {}), ("totals + work", {"per_element": False}),
         ("totals only", {"per_element": False, "work": False})]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--steps", type=int, default=1_000_000, help="steps of the compiled march (default 1e6)")
    parser.add_argument("--baseline-steps", type=int, default=20_000,
                        help="steps of the NumPy baseline (default 2e4)")
    parser.add_argument("--repeat", type=int, default=7, help="repeats, best time kept (default 7)")
    parser.add_argument("--elements", type=int, nargs="+", default=[4, 16, 64], help="values of J")
    args = parser.parse_args(argv)

    sphere = Sphere.paper()
    warm_up()
    print(f"microslip simulate on the contact plane, {platform.processor() or platform.machine()}, "
          f"Python {platform.python_version()}, NumPy {np.__version__}")
    print(f"compiled: {args.steps:.0e} steps; NumPy baseline: {args.baseline_steps:.0e} steps; best of {args.repeat}\n")
    header = f"{'J':>5} {'records':>22} {'time (s)':>9} {'updates/s':>10} {'NumPy updates/s':>15} {'ratio':>7}"
    print(header)
    print("-" * len(header))
    results = []
    for J in args.elements:
        model = tune(sphere, N_TOT, elements=J)
        t, n = load_path(sphere, args.steps)
        tb, nb = load_path(sphere, args.baseline_steps)
        T_base, N_base = numpy_march(model, tb, nb)
        ref = model.simulate(tb, nb, per_element=False)
        scale = float(np.abs(ref.T).max())
        assert np.allclose(T_base, ref.T, rtol=0, atol=1e-12 * scale), "NumPy baseline disagrees with simulate"
        assert np.allclose(N_base, ref.N, rtol=1e-13, atol=0), "NumPy baseline disagrees with simulate"
        base_rate = args.baseline_steps * J / best_time(lambda: numpy_march(model, tb, nb), max(1, args.repeat // 2))
        for label, options in MODES:
            model.simulate(t[:10], n[:10], **options)
            elapsed = best_time(lambda: model.simulate(t, n, **options), args.repeat)
            rate = args.steps * J / elapsed
            results.append((J, label, rate, rate / base_rate))
            print(f"{J:>5} {label:>22} {elapsed:>9.3f} {rate:>10.3g} {base_rate:>15.3g} {rate / base_rate:>6.0f}x")
        out = (np.ones((args.steps, 2)), np.ones(args.steps), np.ones(args.steps), np.ones((args.steps, J, 2)),
               np.ones((args.steps, J), dtype=np.int8))  # allocated and touched once

        def kernel_alone():
            _kernels.march_plane(model.kt, model.kn, model.gaps, model.mu, t, n, np.zeros((J, 2)), *out)

        elapsed = best_time(kernel_alone, args.repeat)
        rate = args.steps * J / elapsed
        results.append((J, "kernel, outputs reused", rate, rate / base_rate))
        print(f"{J:>5} {'kernel, outputs reused':>22} {elapsed:>9.3f} {rate:>10.3g} {base_rate:>15.3g} "
              f"{rate / base_rate:>6.0f}x")

    print("\ntargets:")
    at16 = [r for r in results if r[0] == 16]
    for r in at16:
        print(f"  >= 2e8 element updates/s at J = 16, {r[1]}: {'met' if r[2] >= 2e8 else 'MISSED'} ({r[2]:.3g})")
    same = [r for r in results if r[1] == MODES[-1][0]]
    lowest = min(r[3] for r in same)
    print(f"  >= 100x the NumPy march (same output, totals only): {'met' if lowest >= 100 else 'MISSED'} "
          f"(lowest {lowest:.0f}x)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
