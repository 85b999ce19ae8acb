"""Speed of ``MicroslipModel.simulate`` against a plain NumPy per-step march, measured in one run.

What is measured
----------------
* Element updates per second (steps x J / wall time) of ``simulate`` for J = 4, 16 and 256
  elements over 10^6 steps, in three modes: ``per_element=True`` (records every element's
  force and condition, and the friction work), ``per_element=False`` (totals and friction
  work) and ``per_element=False, work=False`` (the total forces only: the same output as the
  NumPy baseline). Best of ``--repeat`` runs; the first,
  compiling call is excluded (numba caches the kernels on disk anyway).
* The same for a plain NumPy implementation of the same return mapping: vectorised over the
  elements, a Python loop over the steps. It is run on fewer steps (``--baseline-steps``,
  2*10^4 by default) because it is slow; its cost per step does not depend on the number of
  steps, so its updates per second are compared directly. It is checked against ``simulate``.
* The cost of one 100-step ``simulate`` call with J = 4, input checks and result objects
  included (``timeit``, best of repeats).

The load path: the paper's sphere tuned with J elements, a tangential displacement cycling
at 1.2 times the gross-slip amplitude and a normal approach cycling between 0.3 and 1.1 times
the tuning approach (elements open, close, stick and slip).

Run ``python benchmarks/bench_simulate.py`` (about a minute); ``--steps`` shortens it.
Targets (issue 2): >= 3e8 element updates/s for J >= 16, >= 200 x the NumPy baseline,
a 100-step call under 50 µs.
"""

from __future__ import annotations

import argparse
import platform
import time
import timeit

import numpy as np

from _common import save_results
from microslip import Sphere, tune
from microslip.kernels.element import warm_up

N_TOT = 37.5


def load_path(sphere, steps, cycles=None):
    """t (m) cycling at 1.2 x the gross-slip displacement; n (m) between 0.3 and 1.1 n_tot."""
    cycles = cycles if cycles is not None else max(1, steps // 1000)
    k = np.arange(steps)
    t = 1.2 * float(sphere.gross_slip_displacement(N_TOT)) * np.sin(2 * np.pi * cycles * k / steps)
    n_tot = float(sphere.approach(N_TOT))
    n = n_tot * (0.7 + 0.4 * np.sin(2 * np.pi * 0.37 * cycles * k / steps + 0.5))
    return t, n


def numpy_march(model, t, n):
    """The return mapping of DESIGN.md section 2 in plain NumPy: one vectorised update per step."""
    kt, kn, gaps, mu = model.kt, model.kn, model.gaps, model.mu
    s = np.zeros(model.elements)
    T = np.empty(t.size)
    N = np.empty(t.size)
    for k in range(t.size):
        Ni = kn * np.maximum(n[k] - gaps, 0.0)
        lim = mu * Ni
        trial = kt * (t[k] - s)
        Ti = np.clip(trial, -lim, lim)
        s = np.where(Ti != trial, t[k] - Ti / kt, s)
        T[k] = Ti.sum()
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


def time_modes(model, path, baseline_path, numpy_march, repeat):
    """Updates per second of ``simulate`` in every mode of :data:`MODES` on ``path`` and of ``numpy_march``
    on ``baseline_path`` (checked against ``simulate`` first); prints a row per mode.

    Returns ``(baseline rate, [(mode, rate), ...])``.
    """
    (t, n), (tb, nb) = path, baseline_path
    J = model.elements
    T_base, N_base = numpy_march(model, tb, nb)  # the baseline computes the same numbers
    ref = model.simulate(tb, nb, per_element=False)
    scale = float(np.abs(ref.T).max())
    assert np.allclose(T_base, ref.T, rtol=0, atol=1e-12 * scale), "NumPy baseline disagrees with simulate"
    assert np.allclose(N_base, ref.N, rtol=1e-13, atol=0), "NumPy baseline disagrees with simulate"
    base_rate = tb.shape[0] * J / best_time(lambda: numpy_march(model, tb, nb), max(1, repeat - 1))
    rows = []
    for label, options in MODES:
        model.simulate(t[:10], n[:10], **options)  # compiled (or loaded) already
        elapsed = best_time(lambda: model.simulate(t, n, **options), repeat)
        rows.append((label, t.shape[0] * J / elapsed))
        print_row(J, label, elapsed, rows[-1][1], base_rate)
    return base_rate, rows


def print_row(J, label, elapsed, rate, base_rate):
    print(f"{J:>5} {label:>22} {elapsed:>9.3f} {rate:>10.3g} {base_rate:>15.3g} {rate / base_rate:>6.0f}x")


def arguments(argv, description, title, *, repeat, elements):
    """The options shared by the march benchmarks, parsed; prints ``title``, the machine and the table's header."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--steps", type=int, default=1_000_000, help="steps of the compiled march (default 1e6)")
    parser.add_argument("--baseline-steps", type=int, default=20_000,
                        help="steps of the NumPy baseline (default 2e4)")
    parser.add_argument("--repeat", type=int, default=repeat, help=f"repeats, best time kept (default {repeat})")
    parser.add_argument("--elements", type=int, nargs="+", default=elements, help="values of J")
    args = parser.parse_args(argv)
    print(f"{title} on {platform.processor() or platform.machine()}, "
          f"Python {platform.python_version()}, NumPy {np.__version__}")
    print(f"compiled: {args.steps:.0e} steps; NumPy baseline: {args.baseline_steps:.0e} steps "
          f"(its cost per step is independent of the number of steps); best of {args.repeat}\n")
    header = (f"{'J':>5} {'records':>22} {'time (s)':>9} {'updates/s':>10} "
              f"{'NumPy updates/s':>15} {'ratio':>7}")
    print(header)
    print("-" * len(header))
    return args


def save(name: str, description: str, args, results, more_tables=()) -> None:
    """Save the rates of :func:`time_modes` (``(J, mode, rate, ratio)`` rows) and further tables with the run's
    sizes (benchmarks/results/<name>.json, rendered by the documentation's performance page)."""
    rows = [[J, label, rate, rate / ratio, ratio] for J, label, rate, ratio in results]
    tables = [{"caption": "element updates per second, against the NumPy march in the same run",
               "columns": ["J", "records", "updates/s", "NumPy updates/s", "ratio"], "rows": rows}, *more_tables]
    sizes = (f"{args.steps} steps of the compiled march, {args.baseline_steps} of the NumPy baseline, "
             f"best of {args.repeat}")
    figures = {"description": description, "command": f"python benchmarks/{name}.py", "sizes": sizes,
               "tables": tables}
    print(f"saved to {save_results(name, figures)}")


def main(argv=None) -> int:
    args = arguments(argv, __doc__.split("\n")[0], "microslip simulate benchmark", repeat=5, elements=[4, 16, 256])
    sphere = Sphere.paper()
    warm_up()
    results = []
    for J in args.elements:
        model = tune(sphere, N_TOT, elements=J)
        base_rate, rows = time_modes(model, load_path(sphere, args.steps), load_path(sphere, args.baseline_steps),
                                     numpy_march, args.repeat)
        results += [(J, label, rate, rate / base_rate) for label, rate in rows]

    model = tune(sphere, N_TOT, elements=4)
    t100, n100 = load_path(sphere, 100, cycles=1)
    model.simulate(t100, n100)
    number = 2000
    call = min(timeit.repeat(lambda: model.simulate(t100, n100), number=number, repeat=7)) / number
    call_totals = min(timeit.repeat(lambda: model.simulate(t100, n100, per_element=False, work=False),
                                    number=number, repeat=7)) / number
    print(f"\n100-step simulate call, J = 4, checks included: {call * 1e6:.1f} µs "
          f"(totals only: {call_totals * 1e6:.1f} µs)")

    print("\ntargets (issue 2):")
    big = [r for r in results if r[0] >= 16]
    ok_rate = all(r[2] >= 3e8 for r in big)
    ok_ratio = all(r[3] >= 200 for r in results if r[1] == MODES[-1][0])
    print(f"  >= 3e8 element updates/s for J >= 16: {'met' if ok_rate else 'MISSED'} "
          f"(lowest {min(r[2] for r in big):.3g})" if big else "  (no J >= 16 measured)")
    same = [r for r in results if r[1] == MODES[-1][0]]
    print(f"  >= 200x the NumPy baseline (same output, totals only): {'met' if ok_ratio else 'MISSED'} "
          f"(lowest {min(r[3] for r in same):.0f}x)")
    print(f"  100-step call < 50 µs:               {'met' if call < 50e-6 else 'MISSED'} ({call * 1e6:.1f} µs)")
    call_table = {"caption": "one 100-step simulate call, J = 4, input checks and result objects included "
                             f"(timeit, best of 7 x {number} calls)",
                  "columns": ["records", "time per call (µs)"],
                  "rows": [["everything", call * 1e6], ["totals only", call_totals * 1e6]]}
    save("bench_simulate", "MicroslipModel.simulate on the paper's sphere tuned with J elements, on a path on which "
         "elements stick, slip, open and close, in three recording modes, against the same return mapping in plain "
         "NumPy (vectorised over the elements, a Python loop over the steps, checked against simulate).",
         args, results, [call_table])
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
