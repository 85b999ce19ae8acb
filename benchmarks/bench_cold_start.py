"""Cold start: the first forced response of a fresh Python process, with an empty numba cache and with a warm one.

Run:  OPENBLAS_NUM_THREADS=1 python benchmarks/bench_cold_start.py        (about two minutes)

Two cases, each in fresh processes (``python bench_cold_start.py --case NAME``):

* ``one direction``: the first ``frequency_response`` of a Jenkins oscillator (bench_frf's: 1 kg, 1e4 N/m,
  one element, 2 N from 60 to 160 rad/s, H = 7, 128 samples, stability on as by default);
* ``plane``: the first ``frequency_response`` of a contact moving on its plane (tests/frequency/
  test_plane_contacts.py's puck: one mass on two springs, a 3-element contact, 1.6 N at 30 degrees from
  330 to 440 rad/s, H = 5, stability on).

Each case is run with ``NUMBA_CACHE_DIR`` set to a new, empty temporary folder (cold: numba compiles every
kernel the call reaches), then again with that folder, now filled (warm: numba loads them). Printed per
run: ``import microslip`` (s), the first call (s) and the whole process as its parent sees it (s, the
interpreter's start included); the cold/warm ratio of the first call and of the process. Cold runs: best of
``--cold`` (each in a new folder), warm runs: best of ``--warm``. The figures and the machine's details go to
``benchmarks/results/bench_cold_start.json``. The machine is shared: its load average is saved with them.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
CASES = ("one direction", "plane")


def _one_direction():
    from microslip import MicroslipModel, Structure, frequency_response

    s = Structure(M=[[1.0]], C=[[1.0]], K=[[1e4]])
    s.add_contact(MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0), tangential=0, approach=1e-6)
    return lambda: frequency_response(s, [2.0], (60.0, 160.0), harmonics=7)


def _plane():
    import numpy as np

    from microslip import MicroslipModel, Structure, frequency_response

    model = MicroslipModel(kt=[3e4, 2e4, 1e4], kn=[2e6, 2e6, 2e6], gaps=[0.0, 0.3e-6, 0.6e-6], mu=0.5)
    kx, ky, zeta = 1e5, 1.2e5, 0.01
    s = Structure(np.eye(2), np.diag([2 * zeta * np.sqrt(kx), 2 * zeta * np.sqrt(ky)]), np.diag([kx, ky]))
    s.add_contact(model, tangential=[{0: 1.0}, {1: 1.0}], approach=1e-6, name="puck")
    force = 1.6 * np.array([np.cos(np.radians(30)), np.sin(np.radians(30))])
    return lambda: frequency_response(s, force, (330.0, 440.0), harmonics=5)


def child(case: str) -> dict:
    """In a fresh process: ``import microslip`` and the case's first forced response, timed (s)."""
    t0 = time.perf_counter()
    import microslip  # noqa: F401

    imported = time.perf_counter() - t0
    call = {"one direction": _one_direction, "plane": _plane}[case]()
    t1 = time.perf_counter()
    curve = call()
    return {"import": imported, "first call": time.perf_counter() - t1, "points": int(curve.omega.size)}


def run(case: str, cache: str) -> dict:
    """One fresh process on the numba cache folder ``cache``: :func:`child`'s times and the process's (s)."""
    env = dict(os.environ, NUMBA_CACHE_DIR=cache, OPENBLAS_NUM_THREADS=os.environ.get("OPENBLAS_NUM_THREADS", "1"))
    t0 = time.perf_counter()
    done = subprocess.run([sys.executable, str(Path(__file__).resolve()), "--case", case], env=env,
                          capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if done.returncode:
        raise RuntimeError(f"case {case!r} failed:\n{done.stderr[-3000:]}")
    return {**json.loads(done.stdout.strip().splitlines()[-1]), "process": wall}


def best(runs: list[dict]) -> dict:
    """The smallest of each time over ``runs``."""
    return {key: min(r[key] for r in runs) for key in ("import", "first call", "process")}


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--case", choices=CASES, help="run one case in this process and print its times (JSON)")
    parser.add_argument("--cold", type=int, default=2, help="cold runs per case, each on a new empty cache")
    parser.add_argument("--warm", type=int, default=3, help="warm runs per case")
    args = parser.parse_args(argv)
    if args.case:
        print(json.dumps(child(args.case)))
        return {}
    sys.path.insert(0, str(HERE))
    from _common import save_results

    figures = {}
    print("first forced response of a fresh process (s; best of "
          f"{args.cold} cold, {args.warm} warm; the machine's load is saved with the figures)")
    print(f"{'case':15s} {'cache':6s} {'import':>8s} {'first call':>11s} {'process':>9s}")
    for case in CASES:
        cold_runs, warm_runs = [], []
        for _ in range(args.cold):
            with tempfile.TemporaryDirectory(prefix="numba-cache-") as cache:
                cold_runs.append(run(case, cache))
                if not warm_runs:  # the warm runs load what the first cold run compiled
                    warm_runs = [run(case, cache) for _ in range(args.warm)]
        row = {"cold": best(cold_runs), "warm": best(warm_runs), "points": cold_runs[0]["points"]}
        row["ratio first call"] = row["cold"]["first call"] / row["warm"]["first call"]
        row["ratio process"] = row["cold"]["process"] / row["warm"]["process"]
        figures[case] = row
        for kind in ("cold", "warm"):
            r = row[kind]
            print(f"{case:15s} {kind:6s} {r['import']:8.2f} {r['first call']:11.2f} {r['process']:9.2f}")
        print(f"{case:15s} cold / warm: first call {row['ratio first call']:.1f}x, "
              f"process {row['ratio process']:.1f}x ({row['points']} points)")
    print(f"saved to {save_results('bench_cold_start', figures)}")
    return figures


if __name__ == "__main__":
    main()
