"""Cost of running a design study on Dask: the overhead per case against a plain loop, and 2 workers against 1.

Run:  python benchmarks/bench_sweep.py [--cases N]
      python benchmarks/bench_sweep.py --quick      (8 cases, 2 interleaved runs)

The study: the blade pair with an under-platform damper of the tests (``tests/study/conftest.py``),
tips excited in antiphase, 3000 to 5000 rad/s, H = 3, the damper's centrifugal load from 40 N to
300 N and two excitation levels (``--cases`` of them, default 20, about 1-2 s each).

Timed in the same process, each on warm code (numba's compiled kernels loaded, every worker has
solved one case first, one small study has been written once so that the table and Zarr libraries are
loaded; the clusters' start-up and that warm-up are timed apart, a cost paid once per session),
interleaved ``--repeat`` times (this machine's speed drifts by several percent within a minute) and the
best of each kept:

1. the baseline: the cases one after the other, each configuration built by ``Study.configuration``
   and solved by ``frequency_response`` in a plain loop, BLAS on one thread, in this process;
2. the same loop run as one task on the 1-worker cluster's worker process: the plain loop in the
   very process that solves the study's cases, so that the comparison with 3. sees only what the
   study adds, not where the operating system places a process (a new process ran the same loop
   -1 % to +5 % apart from this one);
3. ``microslip.sweep`` on a local cluster of 1 worker process: everything a study does (the study sent
   to the worker, one task per case, every finished case written to its file, the summary table
   and the Zarr store; the HTML report, a fixed cost, is left out);
4. the same on 2 worker processes.

Also timed once: the same loop in a fresh process spawned as Dask spawns its workers, without Dask.

Printed: the overhead per case, the sweep on 1 worker over the loop on the same worker (target under
5 %) and over the loop in this process, and the throughput of 2 workers over 1 worker (target at least
1.7 on this 2-core machine). Every curve is checked equal to the loop's bit for bit. The figures are saved to
``benchmarks/results/bench_sweep.json`` (``--quick``: ``bench_sweep_quick.json``) by ``_common.save_results``.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
from _common import save_results  # noqa: E402
sys.path[:0] = [str(ROOT / "tests"), str(ROOT / "tests" / "frequency"), str(ROOT / "tests" / "cli"),
                str(ROOT / "tests" / "study")]


def _files(folder: Path, cases: int) -> Path:
    """The damper pair's configuration and a study of ``cases`` cases in ``folder`` (``study_<cases>.toml``)."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("study_conftest", ROOT / "tests" / "study" / "conftest.py")
    conftest = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(conftest)
    conftest.write_damper_pair(folder, omega=(3000, 5000))
    loads = np.geomspace(40, 300, cases // 2)
    study = folder / f"study_{cases}.toml"
    study.write_text('base = "pair.toml"\n[vary]\n"damper.centrifugal_load" = ['
                     + ", ".join(f'"{x:.4g}N"' for x in loads) + ']\n"excitation.scale" = [1.0, 1.5]\n')
    return study


def _loop(study, cases):
    from threadpoolctl import threadpool_limits

    from microslip.frequency import frequency_response
    from microslip.study.solve import frf_arguments

    out = []
    with threadpool_limits(1):
        for case in cases:
            cfg = study.configuration(case)
            out.append(frequency_response(cfg.structure, cfg.force, cfg.omega, **frf_arguments(cfg)))
    return out


def _loop_timed(study, cases) -> float:
    """Seconds for :func:`_loop` of ``cases`` after one warm-up case (in whatever process runs it)."""
    _loop(study, cases[:1])
    return _loop_seconds(study, cases)


def _loop_seconds(study, cases) -> float:
    """Seconds for :func:`_loop` of ``cases`` (on warm code), in whatever process runs it."""
    t0 = time.perf_counter()
    _loop(study, cases)
    return time.perf_counter() - t0


def _in_fresh_process(study, cases) -> float:
    """:func:`_loop_timed` in a new process started as Dask starts its workers (spawn), without Dask."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn")) as pool:
        return pool.submit(_loop_timed, study, cases).result()


def _cluster(n: int):
    from dask.distributed import Client

    from microslip.study.engine import local_cluster

    cluster = local_cluster(n)
    return cluster, Client(cluster)


def _warm(client, study) -> None:
    """Every worker solves the study's first case once (imports, compiled kernels loaded)."""
    from microslip.study.solve import solve_case

    case = study.cases()[0]
    workers = list(client.scheduler_info()["workers"])
    client.gather([client.submit(solve_case, study, case, workers=[w], pure=False, allow_other_workers=False)
                   for w in workers])


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--cases", type=int, default=None, help="number of cases (even, default 20; --quick 8)")
    parser.add_argument("--repeat", type=int, default=None,
                        help="interleaved runs of each; the best counts (default 3; --quick 2)")
    parser.add_argument("--quick", action="store_true", help="8 cases, 2 interleaved runs")
    args = parser.parse_args(argv)
    defaults = (8, 2) if args.quick else (20, 3)
    command = "python benchmarks/bench_sweep.py" + (" --quick" if args.quick else "") + "".join(
        f" --{k} {v}" for k, v, d in (("cases", args.cases, defaults[0]), ("repeat", args.repeat, defaults[1]))
        if v is not None and v != d)
    args.cases = defaults[0] if args.cases is None else args.cases
    args.repeat = defaults[1] if args.repeat is None else args.repeat
    if args.cases < 2 or args.cases % 2:
        parser.error(f"--cases must be an even number of at least 2, got {args.cases}")
    load_before = os.getloadavg()[0]
    from microslip.study import load_study, sweep

    print(f"load average {os.getloadavg()[0]:.2f}; {os.cpu_count()} cores")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        study = load_study(_files(tmp, args.cases))
        cases = study.cases()
        _loop(study, cases[:1])  # warm-up: compiled kernels loaded
        clusters = {}
        startup = {}
        for n in (1, 2):
            t0 = time.perf_counter()
            clusters[n] = _cluster(n)
            _warm(clusters[n][1], study)
            startup[n] = time.perf_counter() - t0
            print(f"{n} worker{'s' if n > 1 else ''}: cluster started and one case solved on each worker in "
                  f"{time.perf_counter() - t0:.2f} s")
        t0 = time.perf_counter()
        (tmp / "small").mkdir()
        small = load_study(_files(tmp / "small", 2))
        sweep(small, clusters[1][1], out=tmp / "small" / "out", report=False)
        print(f"a study of 2 cases written once (the table and Zarr libraries loaded): {time.perf_counter() - t0:.2f} s")
        loops, on_worker, sweeps, loop = [], [], {1: [], 2: []}, None
        for r in range(args.repeat):  # interleaved: the machine's slow spells fall on every kind alike
            t0 = time.perf_counter()
            loop = _loop(study, cases)
            loops.append(time.perf_counter() - t0)
            on_worker.append(clusters[1][1].submit(_loop_seconds, study, cases, pure=False).result())
            for n, (cluster, client) in clusters.items():
                t0 = time.perf_counter()
                result = sweep(study, client, out=tmp / f"out{n}-{r}", report=False)
                sweeps[n].append(time.perf_counter() - t0)
                assert result.computed == len(cases) and not result.failed
                same = all(np.array_equal(result.curve(k)["omega"], x.omega) for k, x in enumerate(loop))
                assert same, "a curve differs from the loop's"
            print(f"run {r + 1}: loop {loops[-1]:.2f} s (on the worker {on_worker[-1]:.2f} s), sweep on 1 worker "
                  f"{sweeps[1][-1]:.2f} s, on 2 workers "
                  f"{sweeps[2][-1]:.2f} s ({len(cases)} cases; every curve equal to the loop's bit for bit)")
        for cluster, client in clusters.values():
            client.close()
            cluster.close()
        t_fresh = _in_fresh_process(study, cases)
        t_loop, t_worker, t1, t2 = min(loops), min(on_worker), min(sweeps[1]), min(sweeps[2])
        print(f"the same loop in a fresh process without Dask (spawned as the workers are): {t_fresh:.2f} s "
              f"({100 * (t_fresh / t_loop - 1):+.1f} % against the loop's best)")
        print(f"overhead per case (best of {args.repeat} each, the whole study: case files, summary and Zarr store "
              f"included), the sweep on 1 worker against the same loop on that worker: {100 * (t1 / t_worker - 1):+.1f} %"
              f" (target under 5 %); against the loop in this process: {100 * (t1 / t_loop - 1):+.1f} %")
        print(f"throughput, 2 workers over 1: {t1 / t2:.2f}x (target at least 1.7x)")
        print(f"load average {os.getloadavg()[0]:.2f}")
    rows = [["loop in this process (the baseline)", t_loop, t_loop / len(cases), 1.0],
            ["the same loop on the 1-worker cluster's worker", t_worker, t_worker / len(cases), t_worker / t_loop],
            ["the same loop in a fresh spawned process (run once)", t_fresh, t_fresh / len(cases), t_fresh / t_loop],
            ["sweep on 1 worker", t1, t1 / len(cases), t1 / t_loop],
            ["sweep on 2 workers", t2, t2 / len(cases), t2 / t_loop]]
    figures = {"description": "A design study (the blade pair with an under-platform damper, H = 3) run by "
                              "microslip.sweep on a local Dask cluster against the same cases in a plain loop in "
                              "the same process (the baseline) and on the worker; every curve equal to the loop's "
                              "bit for bit.",
               "command": command,
               "sizes": f"{len(cases)} cases, best of {args.repeat} interleaved runs; load average "
                        f"{load_before:.2f} at the start",
               "tables": [{"caption": "the whole study (s), best of the interleaved runs",
                           "columns": ["run", "time (s)", "per case (s)", "/ the loop in this process"],
                           "rows": rows},
                          {"caption": "the ratios the targets are set on",
                           "columns": ["overhead, sweep on 1 worker / loop on that worker - 1 (target < 0.05)",
                                       "throughput, 2 workers / 1 (target >= 1.7)",
                                       "cluster start-up and warm-up, 1 worker (s)", "the same, 2 workers (s)"],
                           "rows": [[t1 / t_worker - 1, t1 / t2, startup[1], startup[2]]]}]}
    print(f"results: {save_results('bench_sweep' + ('_quick' if args.quick else ''), figures)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
