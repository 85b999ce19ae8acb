"""Speed of one AFT call with its Jacobian (H = 7, 128 samples), against baselines measured in the same run.

Run:  python benchmarks/bench_aft.py

* microslip, compiled kernel as the harmonic balance calls it (preallocated outputs);
* microslip, public checked wrapper ``microslip.frequency.aft``;
* baseline 1: a NumPy AFT vectorised over the elements (loop over samples, periods until the
  state repeats) with a forward finite-difference Jacobian (2 (2H+1) + 1 AFT evaluations);
* baseline 2 (1 element, if pyHarm-os is installed: ``pip install -e .[bench]``): pyHarm's
  compiled Jenkins residual + analytic Jacobian on the same displacement.
Contacts: a Jenkins element (kt = 1e4 N/m, slip force 1 N) and the paper's sphere tuned with 100 elements.
"""

from __future__ import annotations

import sys
import time
import warnings
from pathlib import Path

import numpy as np

from microslip import MicroslipModel, Sphere, tune
from microslip.kernels import aft as _aft
from microslip.frequency import aft

H, NS = 7, 128
NB = 2 * H + 1


def best_time(fn, repeat=7, number=None):
    """Best mean time per call (s) over ``repeat`` rounds of ``number`` calls."""
    fn()
    if number is None:
        t0 = time.perf_counter()
        fn()
        number = max(1, int(0.05 / max(time.perf_counter() - t0, 1e-7)))
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        best = min(best, (time.perf_counter() - t0) / number)
    return best


def numpy_aft(model, xt, xn, E, P, max_periods=100):
    """Baseline: forces of the periodic state, vectorised over elements, Python loop over samples."""
    t = E @ xt
    n = E @ xn
    kt, kn, g, mu = model.kt, model.kn, model.gaps, model.mu
    lim0 = mu * kn * np.maximum(xn[0] - g, 0.0)
    s = xt[0] - np.clip(kt * xt[0], -lim0, lim0) / kt
    T = np.empty(t.size)
    N = (kn * np.maximum(n[:, None] - g, 0.0)).sum(axis=1)
    for _ in range(max_periods):
        start = s.copy()
        for k in range(t.size):
            lim = mu * kn * np.maximum(n[k] - g, 0.0)
            Ti = np.clip(kt * (t[k] - s), -lim, lim)
            s = t[k] - Ti / kt
            T[k] = Ti.sum()
        if np.array_equal(s, start):
            break
    return P @ T, P @ N


def numpy_aft_with_fd_jacobian(model, xt, xn, E, P, h=1e-12):
    FT, FN = numpy_aft(model, xt, xn, E, P)
    J = np.empty((2 * NB, 2 * NB))
    for q in range(NB):
        e = np.zeros(NB)
        e[q] = h
        J[:NB, q], J[NB:, q] = ((np.array(numpy_aft(model, xt + e, xn, E, P)) - (FT, FN)) / h)
        J[:NB, NB + q], J[NB:, NB + q] = ((np.array(numpy_aft(model, xt, xn + e, E, P)) - (FT, FN)) / h)
    return FT, FN, J


def cases():
    jenkins = MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0)
    xt1 = np.zeros(NB)
    xt1[1], xt1[2], xt1[5] = 3e-4, 1e-4, 2e-5
    xn1 = np.zeros(NB)
    xn1[0] = 1e-6
    sphere = Sphere.paper()
    big = tune(sphere, 37.5, elements=100)
    n0 = float(sphere.approach(37.5))
    xt = np.zeros(NB)
    xt[1], xt[2], xt[3] = 1.0e-6, 0.3e-6, 0.1e-6
    xn = np.zeros(NB)
    xn[0], xn[1] = n0, 0.2 * n0
    return [("1 element (Jenkins)", jenkins, xt1, xn1), ("100 elements (sphere, varying n)", big, xt, xn)]


def save(rows, pyharm=None) -> None:
    """Save the rows (and pyHarm's time when it ran) to benchmarks/results/bench_aft.json for the docs."""
    from _common import save_results

    table = {"caption": "AFT with Jacobian per call (µs), against a NumPy AFT with a finite-difference Jacobian "
                        "in the same run",
             "columns": ["contact", "compiled kernel (µs)", "public aft() (µs)", "NumPy + finite differences (µs)",
                         "ratio"],
             "rows": [[name, k * 1e6, p * 1e6, n * 1e6, n / k] for name, k, p, n in rows]}
    tables = [table]
    if pyharm is not None:
        tables.append({"caption": "1 Jenkins element: pyHarm's compiled residual and Jacobian",
                       "columns": ["pyHarm (µs)", "ratio to microslip's kernel"],
                       "rows": [[pyharm * 1e6, pyharm / rows[0][1]]]})
    figures = {"description": f"One AFT call with its Jacobian (H = {H}, {NS} samples per period, best of 7): a "
                              "Jenkins element and the paper's sphere tuned with 100 elements under a varying "
                              "normal load.", "command": "python benchmarks/bench_aft.py", "tables": tables}
    print(f"saved to {save_results('bench_aft', figures)}")


def main():
    warnings.filterwarnings("ignore", message=".*faster on contiguous arrays.*")  # pyHarm's numba warnings
    E, P, cos2, sin2, cum = _aft.tables(H, NS)
    print(f"AFT with Jacobian, H = {H}, {NS} samples per period (best of 7, microseconds per call)")
    rows = []
    for name, model, xt, xn in cases():
        out = (np.empty(NB), np.empty(NB), np.empty((NB, NB)), np.empty((NB, NB)), np.empty((NB, NB)))
        t_kernel = best_time(lambda: _aft._aft_contact(model.kt, model.kn, model.gaps, model.mu, xt, xn, E, P, cos2,
                                                       sin2, cum, 1000, *out))
        t_public = best_time(lambda: aft(model, xt, xn, samples=NS))
        t_numpy = best_time(lambda: numpy_aft_with_fd_jacobian(model, xt, xn, E, P), repeat=3)
        # same forces as the baseline (its periodic state is the same return mapping)
        FT, _, _ = numpy_aft_with_fd_jacobian(model, xt, xn, E, P)
        assert np.allclose(FT, aft(model, xt, xn, samples=NS).T, rtol=1e-9, atol=1e-9 * np.abs(FT).max())
        rows.append((name, t_kernel, t_public, t_numpy))
        print(f"{name:34s} kernel {t_kernel * 1e6:8.2f}   public aft() {t_public * 1e6:8.2f}   "
              f"NumPy + finite differences {t_numpy * 1e6:10.1f}   ratio {t_numpy / t_kernel:7.0f}x")
    try:
        from pyHarm.Elements.NodeToNodeElements.Jenkins import JenkinsJacobian, JenkinsResidual
    except Exception as exc:  # pragma: no cover - optional
        print(f"pyHarm not available ({type(exc).__name__}: {exc}); install with pip install -e .[bench]")
        save(rows)
        return rows
    # pyHarm's Jenkins element on the same displacement (its DFT layout: cos/sin per harmonic)
    tau = 2 * np.pi * np.arange(NS) / NS
    DFT = np.vstack([np.ones(NS)] + [f(h * tau) for h in range(1, H + 1) for f in (np.cos, np.sin)])
    DTF = DFT.T * np.r_[1.0 / NS, np.full(2 * H, 2.0 / NS)]
    Pslave = np.eye(NB)
    Pmaster = np.zeros((NB, NB))
    _, _, xt1, xn1 = cases()[0]
    Pdir = np.kron(np.eye(1), np.eye(NB))[None]
    args = (xt1, 1.0, Pdir, Pslave, Pmaster, 1.0, 1.0, 1e4, DFT, DTF)
    t_ph = best_time(lambda: (JenkinsResidual(*args), JenkinsJacobian(*args)))
    R, _ = JenkinsResidual(*args)
    assert np.allclose(R, aft(cases()[0][1], xt1, xn1, samples=NS).T, rtol=1e-9, atol=1e-12)
    print(f"{'1 element, pyHarm Jenkins':34s} residual + Jacobian {t_ph * 1e6:8.2f}   "
          f"ratio to microslip kernel {t_ph / rows[0][1]:5.0f}x")
    save(rows, t_ph)
    return rows


if __name__ == "__main__":
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from bench_frf import in_temporary_directory

    in_temporary_directory(main)
