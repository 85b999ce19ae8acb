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
  and their conditions), and obtaining that fresh memory from the system (the kernel clears every
  page) costs about three quarters of the march itself on this machine over 10^6 steps.

The load path: the paper's sphere tuned with J elements, an elliptical orbit (semi-axes 1.2 and
0.72 times the gross-slip displacement at the tuning load) and a normal approach cycling between
0.3 and 1 times the tuning approach (elements open, close, stick and slide round).

Run ``python benchmarks/bench_plane.py`` (about half a minute); ``--steps`` shortens it.
Targets: >= 2e8 element updates/s at J = 16 and >= 100 x the NumPy march.
"""

from __future__ import annotations

import numpy as np

from bench_simulate import MODES, arguments, best_time, print_row, save, time_modes  # as along one direction
from microslip import Sphere, tune
from microslip.kernels import element as _kernels
from microslip.kernels.element import warm_up

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


def main(argv=None) -> int:
    args = arguments(argv, __doc__.split("\n")[0], "microslip simulate on the contact plane", repeat=7,
                     elements=[4, 16, 64])
    sphere = Sphere.paper()
    warm_up()
    results = []
    for J in args.elements:
        model = tune(sphere, N_TOT, elements=J)
        t, n = load_path(sphere, args.steps)
        base_rate, rows = time_modes(model, (t, n), load_path(sphere, args.baseline_steps), numpy_march, args.repeat)
        results += [(J, label, rate, rate / base_rate) for label, rate in rows]
        out = (np.ones((args.steps, 2)), np.ones(args.steps), np.ones(args.steps), np.ones((args.steps, J, 2)),
               np.ones((args.steps, J), dtype=np.int8))  # allocated and touched once

        def kernel_alone():
            _kernels.march_plane(model.kt, model.kn, model.gaps, model.mu, t, n, np.zeros((J, 2)), *out)

        elapsed = best_time(kernel_alone, args.repeat)
        rate = args.steps * J / elapsed
        results.append((J, "kernel, outputs reused", rate, rate / base_rate))
        print_row(J, "kernel, outputs reused", elapsed, rate, base_rate)

    print("\ntargets:")
    at16 = [r for r in results if r[0] == 16]
    for r in at16:
        print(f"  >= 2e8 element updates/s at J = 16, {r[1]}: {'met' if r[2] >= 2e8 else 'MISSED'} ({r[2]:.3g})")
    for r in at16:
        if r[1] == MODES[-1][0]:
            print(f"  >= 100x the NumPy march at J = 16 (the same output, totals only): "
                  f"{'met' if r[3] >= 100 else 'MISSED'} ({r[3]:.0f}x)")
    save("bench_plane", "MicroslipModel.simulate on the contact plane: an elliptical orbit on which elements open, "
         "close, stick and slide round, against the same radial return in plain NumPy (vectorised over the elements, "
         "a Python loop over the steps, checked against simulate); the kernel alone with its outputs reused.",
         args, results)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
