"""Benchmark: the whole default accuracy report of one model, against a path-by-path baseline.

Run: ``python benchmarks/bench_accuracy.py``. Times ``microslip accuracy`` on the
paper's J = 4 model (450 paths of the default family, the exact MDR reference
with 2000 elements, CSV, summary and both figures), and a baseline measured in
the same run that computes the same metrics path by path: each model run
separately on each path (``Path.simulate``) and the metrics with ``np.trapezoid``
per path. Both give the same numbers (checked). Target: the report under 60 s.
"""

from __future__ import annotations

import contextlib
import io
import tempfile
import time
from pathlib import Path

import numpy as np

from microslip import Sphere, mdr, paths, tune
from microslip.accuracy import accuracy, reference_run
from microslip.cli import main as cli


def baseline(model, reference, family):
    """Energy errors and force differences, one path and one model at a time."""
    energy, force = [], []
    for p in family:
        T = p.simulate(model).T[p.steady]
        Tr = p.simulate(reference).T[p.steady]
        t = p.t[p.steady]
        with np.errstate(invalid="ignore", divide="ignore"):  # shakedown paths: W_ref = 0
            energy.append(np.trapezoid(T, t) / np.trapezoid(Tr, t) - 1)
        force.append(np.max(np.abs(T - Tr)) / np.max(np.abs(Tr)))
    return np.array(energy), np.array(force)


def main() -> None:
    sphere = Sphere.paper()
    model = tune(sphere, 37.5, elements=4)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "j4.json"
        model.save(path)
        ref = mdr(sphere, max_load=37.5, elements=50)
        ref.simulate(np.zeros(3), 0.0, per_element=False)  # compile / load the kernel cache
        t0 = time.perf_counter()
        with contextlib.redirect_stdout(io.StringIO()):
            status = cli(["accuracy", str(path), "--out", str(Path(tmp) / "acc"), "--min-load", "7.5N", "--quiet"])
        report_time = time.perf_counter() - t0
        assert status == 0

    family = paths.default_family(sphere, 37.5)
    reference = mdr(sphere, max_load=37.5, elements=2000)
    t0 = time.perf_counter()
    rep = accuracy(model, reference, family)
    batch_time = time.perf_counter() - t0
    t0 = time.perf_counter()
    energy, force = baseline(model, reference, family)
    base_time = time.perf_counter() - t0
    ok = ~rep.shakedown
    assert np.allclose(rep.energy_error[ok], energy[ok], rtol=1e-9, atol=1e-12)
    assert np.allclose(rep.force_difference, force, rtol=1e-12)

    # the optimiser's case: the reference is run once, the small model many times
    run = reference_run(reference, family)
    cached = [(p, Tr[p.steady]) for p, Tr in zip(family, run.batch.split(run.T))]
    repeats = 20
    t0 = time.perf_counter()
    for _ in range(repeats):
        accuracy(model, run)
    model_batch = (time.perf_counter() - t0) / repeats
    t0 = time.perf_counter()
    for _ in range(repeats):
        for p, Tr in cached:
            T = p.simulate(model).T[p.steady]
            np.trapezoid(T, p.t[p.steady])
            np.max(np.abs(T - Tr))
    model_base = (time.perf_counter() - t0) / repeats

    print(f"default accuracy report, J = 4 model, {len(family)} paths, MDR reference with 2000 elements")
    print(f"  'microslip accuracy' end to end (CSV, summary, 2 figures): {report_time:7.2f} s   (target < 60 s)")
    print(f"  metrics only, batched (accuracy())                      : {batch_time:7.2f} s")
    print(f"  baseline: same metrics path by path (Path.simulate)     : {base_time:7.2f} s")
    print(f"  speed-up of the batch over the baseline: {base_time / batch_time:.2f}x   "
          f"[{'PASS' if report_time < 60 else 'FAIL'}]")
    print("one evaluation of the J = 4 model against a cached reference run (what the optimiser repeats):")
    print(f"  batched (accuracy(model, ReferenceRun)): {1e3 * model_batch:7.1f} ms")
    print(f"  baseline, path by path                 : {1e3 * model_base:7.1f} ms")
    print(f"  speed-up: {model_base / model_batch:.1f}x")


if __name__ == "__main__":
    main()
