"""Speed of the measured-loop path: reading + analysing 10^6 samples (< 2 s), tuning from loops (< 5 s).

Run:  python benchmarks/bench_loops.py

Each figure is printed with a baseline measured in the same run, so the ratio
is what carries over between machines:

* reading + analysing a 10^6-sample CSV, against ``numpy.loadtxt`` of the same
  file (the bare parse, no units, no analysis);
* tuning from loops (read + analyse the 5 shipped records, fit, tune with 6
  elements, validate at every load), against ``microslip.tune`` on the
  closed-form sphere with 6 elements.

Timings are the best of ``REPEATS`` runs after one warm-up run (which loads
the compiled kernels from numba's cache). The figures are saved to
``benchmarks/results/bench_loops.json`` (``_common.save_results``) for the docs.
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from microslip import Cylinder, Sphere, loops, tune, tune_on_loops
from microslip.loops.synthetic import dataset_files, normal_curve_file

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import save_results  # noqa: E402

SAMPLES = 1_000_000
REPEATS = 3


def best(fn, repeats=REPEATS):
    fn()
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def write_big_record(path: Path) -> None:
    """10^6 samples: 100 cycles of a 20-element sphere array with sensor noise."""
    sphere = Sphere.paper()
    model = tune(sphere, 37.5, elements=20)
    tau = np.arange(SAMPLES) / 10_000
    t = 1.5e-6 * np.sin(2 * np.pi * tau)
    T = model.simulate(t, float(sphere.approach(37.5)), per_element=False).T
    rng = np.random.default_rng(1)
    data = np.column_stack([tau * 1e-2, (t + rng.normal(0, 5e-9, SAMPLES)) * 1e6, T + rng.normal(0, 0.03, SAMPLES)])
    np.savetxt(path, data, delimiter=",", fmt="%.7g", header="time [s],t [um],T [N]", comments="")


def bench_read_and_analyse() -> list:
    """The row of the figures' table: task, its time (s), the baseline's (s), the ratio, the target (s)."""
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "big.csv"
        write_big_record(path)
        result = {}

        def ours():
            result["loops"] = loops.analyse(loops.read(path, normal_load=37.5))

        mine = best(ours)
        base = best(lambda: np.loadtxt(path, delimiter=",", skiprows=1))
        L = result["loops"]
        print(f"read + analyse {SAMPLES:.0e} samples ({L.cycles} cycles): {mine:.3f} s (target < 2 s); "
              f"baseline numpy.loadtxt alone (the bare parse of the same file): {base:.3f} s; read + analyse "
              f"takes {mine / base:.2f} x as long as loadtxt alone")
        return [f"read + analyse {SAMPLES:.0e} samples ({L.cycles} cycles)", mine, "numpy.loadtxt of the same file",
                base, mine / base, 2.0]


def bench_tune_from_loops() -> list:
    """The row of the figures' table, as :func:`bench_read_and_analyse`'s."""
    cylinder = Cylinder.from_file(normal_curve_file(), 10e-3, 5e-3, 200e9, 0.3)

    def ours():
        records = [loops.analyse(loops.read(p)) for p in dataset_files()]
        tune_on_loops(records, cylinder, elements=6)

    mine = best(ours)
    base = best(lambda: tune(Sphere.paper(), 37.5, elements=6))
    print(f"tune from loops (5 records, fit, tune J=6, validate): {mine:.3f} s (target < 5 s); "
          f"baseline tune(Sphere, J=6) alone: {base:.4f} s; tuning from loops takes {mine / base:.0f} x as long")
    return ["tune from loops (5 records, fit, tune J = 6, validate)", mine, "tune(Sphere.paper(), J = 6)", base,
            mine / base, 5.0]


def main() -> None:
    rows = [bench_read_and_analyse(), bench_tune_from_loops()]
    figures = {"description": "The measured-loop path: reading and analysing a 10^6-sample CSV record, and tuning "
                              "from the 5 shipped loop records, each against a baseline run in the same process "
                              "(ratio = this task's time / the baseline's; the baselines do less work, so the "
                              "ratio is a cost, not a speed-up).",
               "command": "python benchmarks/bench_loops.py",
               "sizes": f"best of {REPEATS} runs after one warm-up run",
               "tables": [{"caption": "time against a baseline in the same run, and the target",
                           "columns": ["task", "time (s)", "baseline", "baseline time (s)", "ratio",
                                       "target (s)"],
                           "rows": rows}]}
    print(f"saved to {save_results('bench_loops', figures)}")


if __name__ == "__main__":
    main()
