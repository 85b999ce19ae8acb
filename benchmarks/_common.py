"""Helpers the benchmarks share: timing, reading a peak off a curve, running pyHarm (an optional comparison),
saving a benchmark's figures with the machine's details.

pyHarm (``pyHarm-os``, the ``bench`` extra of pyproject.toml) is imported only inside these helpers, so a
benchmark runs its microslip part without it.
"""

from __future__ import annotations

import datetime
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

#: where :func:`save_results` writes, one JSON file per benchmark
RESULTS = Path(__file__).resolve().parent / "results"
#: the repository the benchmarks belong to (for :func:`baseline_source`)
REPO = Path(__file__).resolve().parent.parent


def baseline_source(commit: str) -> Path:
    """``src`` of ``commit`` exported once (``git archive``) into a temporary folder, for a baseline run in a
    subprocess; the folder is kept, so its numba cache stays warm between runs."""
    root = Path(tempfile.gettempdir()) / f"microslip-baseline-{commit}"
    if not (root / "src" / "microslip").is_dir():
        root.mkdir(parents=True, exist_ok=True)
        archive = subprocess.run(["git", "-C", str(REPO), "archive", commit, "src"], capture_output=True, check=True)
        subprocess.run(["tar", "-x", "-C", str(root)], input=archive.stdout, check=True)
    return root / "src"


def best_of(fn, repeat=5):
    """``(seconds, result)``: the best wall time of ``repeat`` calls of ``fn()`` and the last result."""
    best, result = np.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        result = fn()
        best = min(best, time.perf_counter() - t0)
    return best, result


def peak(omega, amp, omega_scale):
    """Peak amplitude: a parabola through the highest point and its neighbours, in arclength.

    ``omega_scale`` (rad/s) makes frequency and relative amplitude weigh alike in the arclength.
    """
    omega, amp = np.asarray(omega), np.asarray(amp)
    i = int(np.argmax(amp))
    if i == 0 or i == amp.size - 1:
        return float(amp[i])
    w, a = omega[i - 1:i + 2], amp[i - 1:i + 2]
    s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(w) / omega_scale, np.diff(a) / amp[i]))])
    p = np.polyfit(s, a, 2)
    return float(np.polyval(p, -p[1] / (2 * p[0])))


def pyharm_missing() -> str | None:
    """None when pyHarm can be imported, else why not (for the message that skips the comparison).

    Imported from a temporary directory: importing pyHarm writes a '.pyHarm' folder into the
    working directory.
    """
    def attempt():
        try:
            import pyHarm  # noqa: F401
        except Exception as exc:  # pyHarm's own imports (jax, numba) may fail too
            return f"{type(exc).__name__}: {exc}"
        return None

    return in_temporary_directory(attempt)


def in_temporary_directory(fn):
    """Run ``fn()`` from a temporary working directory: pyHarm writes a '.pyHarm' folder there."""
    here = os.getcwd()
    with tempfile.TemporaryDirectory() as tmp:
        os.chdir(tmp)
        try:
            return fn()
        finally:
            os.chdir(here)


def run_pyharm(inputs: dict, study: str = "frf"):
    """``(seconds, X, maestro)``: pyHarm's ``Maestro(inputs).operate()`` timed, its accepted solutions, itself.

    ``X`` has one row per accepted point: pyHarm's (possibly nondimensional) unknowns, the
    frequency last. Setting up the system (``Maestro(...)``) is not timed.
    """
    import logging

    import pyHarm

    logging.disable(logging.CRITICAL)
    maestro = pyHarm.Maestro(inputs)
    t0 = time.perf_counter()
    maestro.operate()
    elapsed = time.perf_counter() - t0
    return elapsed, np.array([s.x for s in maestro.nls[study].SolList if s.flag_accepted]), maestro


def machine() -> dict:
    """The machine and software a benchmark ran on: processor (its model and numba's target, which
    ``NUMBA_CPU_NAME`` changes), cores, load, operating system, Python, numba, llvmlite, NumPy, SciPy, microslip,
    the date (UTC)."""
    import llvmlite
    import numba
    import scipy

    import microslip

    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as fh:
            cpu = next(line.split(":", 1)[1].strip() for line in fh if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return {"cpu": cpu, "numba_target": numba.config.CPU_NAME or llvmlite.binding.get_host_cpu_name(),
            "cores": os.cpu_count(), "load_average": list(os.getloadavg()) if hasattr(os, "getloadavg") else None,
            "system": platform.platform(), "python": sys.version.split()[0], "numba": numba.__version__,
            "llvmlite": llvmlite.__version__, "numpy": np.__version__, "scipy": scipy.__version__,
            "microslip": microslip.__version__,
            "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")}


def save_results(name: str, figures: dict) -> Path:
    """Write ``figures`` (JSON-serialisable) and :func:`machine` to ``results/<name>.json``, atomically (a
    temporary file renamed: never half written). Returns the file's path."""
    from microslip.common._io import atomic_write

    text = json.dumps({"benchmark": name, "machine": machine(), "figures": figures}, indent=1) + "\n"
    return atomic_write(RESULTS / f"{name}.json", text)
