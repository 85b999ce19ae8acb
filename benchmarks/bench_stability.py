"""The cost of stability along a reduced curve: the structured solver against its baseline and the formed problem.

Run:  python benchmarks/bench_stability.py            (H = 5; about a minute)
      python benchmarks/bench_stability.py --repeat 3 --harmonics 7

The case is the 1000-DOF scikit-fem blade of ``bench_fe_scale.py`` with 10 platform contacts, H = 5, its
exact-reduced forced response over 1200-1800 Hz. Above ``stability.WHOLE_LIMIT`` unknowns the stability of
an exact reduction is that of a 60-mode modal model of the structure (660 unknowns at H = 5), so this is the
modal Hill problem at every point. In one process, after a warm-up curve (Numba's kernels loaded):

* the curve without stability (``stability=False``);
* the same curve with stability by the structured solver (the default: the problem is never formed, the
  linear part is inverted per harmonic and the contacts go through a capacitance system of the retained
  unknowns, the Arnoldi iteration starts from the previous point's eigenvectors; points far inside the stable
  region skipped, ``stability.FAR`` / ``SKIP_RUN``);
* the same with every point computed (``stability.assess(..., every_point=True)``);
* the same curve with stability by the structured solver as it was at commit :data:`BASELINE` (its module loaded
  from git under another name: every point computed);
* the same curve with stability from the formed problem (``stability.assess(..., method="full")``: the
  problem assembled and factorised at every point, as before the structured solver).

A second, smaller case shows the path the structured solver does not take: the 300-DOF blade (456 DOFs) with 10
contacts at H = 3 has a whole-structure Hill problem of 3192 unknowns, below ``stability.WHOLE_LIMIT``, which is
formed and factorised (sparse) at every point; timed as it is, and with ``WHOLE_LIMIT`` lowered so that its
stability comes from the structured 60-mode modal model (the verdicts of both compared point by point).

Each is timed ``--repeat`` times, best of; wall time and this process's CPU time are both printed (the machine
is shared: CPU time moves less with its load). The ratios are "stability adds X of the curve". Then the
verdicts of the methods at every point of one curve are compared: points with equal verdicts, the
bifurcations (kinds and frequencies printed), and the largest difference of the leading exponents relative to
omega at the points computed by both; the same on a curve with two folds (the structured-solver tests' inclined
block with an arm), whose verdict changes along it.
"""

from __future__ import annotations

import argparse
import functools
import os
import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import save_results  # noqa: E402
from bench_fe_scale import RANGE, blade_case  # noqa: E402

#: stability may add at most this share of the curve's time (issue 26, item 6)
TARGET = 0.5
#: the commit whose structured solver is the baseline (main before the skipping: every point computed)
BASELINE = "71e9e55"


def baseline_assess():
    """``assess`` of the stability module at :data:`BASELINE`, loaded from git as a module of the same package."""
    import importlib.util
    import subprocess

    root = Path(__file__).resolve().parents[1]
    source = subprocess.run(["git", "show", f"{BASELINE}:src/microslip/frequency/analyses/stability.py"], cwd=root,
                            check=True, capture_output=True, text=True).stdout
    name = "microslip.frequency.analyses._stability_baseline"
    spec = importlib.util.spec_from_loader(name, loader=None)
    module = importlib.util.module_from_spec(spec)
    module.__package__ = "microslip.frequency.analyses"
    sys.modules[name] = module
    exec(compile(source, f"{BASELINE}:stability.py", "exec"), module.__dict__)
    return module.assess


def timed(fn, repeat: int):
    """``(wall s, cpu s, result)``: the best of ``repeat`` calls of ``fn()``."""
    wall, cpu, out = np.inf, np.inf, None
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        out = fn()
        wall, cpu = min(wall, time.perf_counter() - t0), min(cpu, time.process_time() - c0)
    return wall, cpu, out


def whole_structure(repeat: int) -> dict:
    """The 456-DOF blade at H = 3: stability on the whole structure (formed, as it is) and on the structured modal
    model (``WHOLE_LIMIT`` lowered), against the curve alone; CPU seconds and the verdict agreement."""
    from microslip import frequency_response
    from microslip.frequency.analyses import stability

    structure, force, _, _ = blade_case(300, 10)
    run = lambda stability=True: frequency_response(structure, force, RANGE, harmonics=3,  # noqa: E731
                                                    reduction="exact", stability=stability)
    run(stability=False)
    alone = timed(lambda: run(stability=False), repeat)[1]
    _, whole, a = timed(run, repeat)
    limit = stability.WHOLE_LIMIT
    stability.WHOLE_LIMIT = 0
    try:
        _, modal, b = timed(run, repeat)
    finally:
        stability.WHOLE_LIMIT = limit
    equal = int(np.count_nonzero(a.stable == b.stable))
    gap = float(np.nanmax(np.abs(a.leading_exponent - b.leading_exponent) / a.omega))
    print(f"{structure.ndof}-DOF blade, H = 3, {a.points} points, cpu s: curve {alone:.3f}; whole structure "
          f"(formed) adds {(whole - alone) / alone:.0%}; 60-mode modal model (structured) adds "
          f"{(modal - alone) / alone:.0%}; verdicts equal at {equal} of {a.points}, leading exponents within "
          f"{gap:.1e} of omega (the modal model leaves out the omitted modes' damping)")
    return {"dofs": structure.ndof, "points": int(a.points), "curve": alone, "whole": whole, "modal": modal,
            "equal_verdicts": equal, "leading_gap_over_omega": gap}


def agreement(stability, baseline, hb, xs, omegas) -> dict:
    """The skipping solver's verdicts, bifurcations (kind, frequency) and leading exponents at the points it computes
    against every point computed, the :data:`BASELINE` solver and the formed problem, printed; and how many points
    it computed."""
    new = stability.assess(hb, xs, omegas)
    computed = int(np.count_nonzero(np.isfinite(new[1])))
    print(f"skipping: {computed} of {omegas.size} points computed; bifurcations "
          f"{[(b.kind, round(b.omega / 2 / np.pi, 6)) for b in new[2]]} (kind, Hz)")
    out = {"computed": computed, "points": int(omegas.size),
           "bifurcations": [(b.kind, b.omega / 2 / np.pi, b.point) for b in new[2]]}
    for key, other in (("every point", stability.assess(hb, xs, omegas, every_point=True)),
                       ("baseline", baseline(hb, xs, omegas)),
                       ("full", stability.assess(hb, xs, omegas, method="full"))):
        equal = int(np.count_nonzero(new[0] == other[0]))
        gap = np.nanmax(np.minimum(np.abs(new[1] - other[1]), np.abs(new[1] - np.conj(other[1]))) / omegas)
        same = [(b.kind, round(b.point, 6)) for b in new[2]] == [(b.kind, round(b.point, 6)) for b in other[2]]
        print(f"against {key}: verdicts equal at {equal} of {omegas.size} points "
              f"({int(np.count_nonzero(~other[0]))} unstable); bifurcations {'the same' if same else 'DIFFER'} "
              f"{[(b.kind, round(b.omega / 2 / np.pi, 6)) for b in other[2]]}; leading exponents within {gap:.1e} "
              f"of omega at the points computed")
        out[key] = {"equal_verdicts": equal, "same_bifurcations": same, "leading_gap_over_omega": float(gap),
                    "bifurcations": [(b.kind, b.omega / 2 / np.pi, b.point) for b in other[2]]}
    return out


def fold_case(stability, baseline) -> dict:
    """The agreement of :func:`agreement` on a curve whose verdict changes: the inclined block with a stiff arm of the
    structured-solver tests (two folds, an unstable branch between them; 5 modes, H = 5), with ``DENSE_LIMIT``
    lowered in both modules so that its 55 unknowns go to the structured solver."""
    tests = Path(__file__).resolve().parents[1] / "tests"
    sys.path[:0] = [str(tests), str(tests / "frequency")]
    from test_stability_structured import block_with_arm  # the test's case, not a copy of it

    from microslip import frequency_response
    from microslip.frequency.analyses.response import MAX_PERIODS, _equations

    structure, force = block_with_arm()
    curve = frequency_response(structure, force, (16000.0, 17500.0), harmonics=5, reduction="modal", modes=5,
                               stability=False)
    _, hb, _ = _equations(structure, force, 5, None, MAX_PERIODS, "modal", 5)
    limits = stability.DENSE_LIMIT, baseline.__globals__["DENSE_LIMIT"]
    stability.DENSE_LIMIT = baseline.__globals__["DENSE_LIMIT"] = 10
    try:
        print(f"inclined block with an arm, 5 modes, H = 5, {curve.points} points:")
        return agreement(stability, baseline, hb, curve.coefficients.reshape(curve.points, -1), curve.omega)
    finally:
        stability.DENSE_LIMIT, baseline.__globals__["DENSE_LIMIT"] = limits


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--harmonics", type=int, default=5)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args(argv)
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    from microslip import frequency_response
    from microslip.frequency.analyses import response, stability

    H = args.harmonics
    structure, force, _, _ = blade_case(1000, 10)
    run = lambda stability=True: frequency_response(structure, force, RANGE, harmonics=H,  # noqa: E731
                                                    reduction="exact", stability=stability)
    captured = {}
    assess = response.assess

    def spy(hb, xs, omegas, method="structured"):
        captured["args"] = (hb, xs, omegas)
        return assess(hb, xs, omegas, method)

    warnings.simplefilter("ignore")  # an under-resolved contact energy is not what is measured here
    run(stability=False)  # warm-up
    baseline = baseline_assess()
    variants = {"without": (lambda: run(stability=False), None), "structured": (run, spy),
                "every": (run, functools.partial(assess, every_point=True)),
                "baseline": (run, baseline), "full": (run, functools.partial(assess, method="full"))}
    rows = {key: (np.inf, np.inf, None) for key in variants}
    try:  # in rounds, each variant once per round (the machine's load drifts less between them), best of
        for _ in range(args.repeat):
            for key, (fn, assessor) in variants.items():
                if assessor is not None:
                    response.assess = assessor
                w, c, out = timed(fn, 1)
                rows[key] = (min(rows[key][0], w), min(rows[key][1], c), out)
    finally:
        response.assess = assess
    points = int(rows["without"][2].points)

    print(f"1000-DOF blade, 10 contacts, exact reduction, H = {H}, {points} points "
          f"(best of {args.repeat}; load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores)")
    print(f"{'':40}{'wall s':>9}{'cpu s':>9}{'adds (wall)':>13}{'adds (cpu)':>12}")
    base_w, base_c = rows["without"][:2]
    figures = {"H": H, "points": points, "dofs": structure.ndof, "target_adds": TARGET, "baseline_commit": BASELINE}
    for key, label in (("without", "curve without stability"), ("full", "with stability, formed problem"),
                       ("baseline", f"with stability, structured at {BASELINE}"),
                       ("every", "with stability, every point"), ("structured", "with stability, skipping")):
        w, c = rows[key][:2]
        adds = ("", "") if key == "without" else (f"{(w - base_w) / base_w:13.0%}", f"{(c - base_c) / base_c:12.0%}")
        print(f"{label:40}{w:9.3f}{c:9.3f}{adds[0]:>13}{adds[1]:>12}")
        figures[key] = {"wall": w, "cpu": c}
    for clock in ("wall", "cpu"):
        alone = figures["without"][clock]
        full, before, every, new = (figures[k][clock] - alone for k in ("full", "baseline", "every", "structured"))
        figures[f"adds_{clock}"] = {"full": full / alone, "baseline": before / alone, "every": every / alone,
                                    "structured": new / alone,
                                    "speed_up_over_full": full / new if new > 0 else float("inf"),
                                    "speed_up_over_baseline": before / new if new > 0 else float("inf")}
    print(f"stability itself {figures['adds_cpu']['speed_up_over_baseline']:.2f}x faster than at {BASELINE}, "
          f"{figures['adds_cpu']['speed_up_over_full']:.1f}x than the formed problem (cpu); target: stability adds "
          f"at most {TARGET:.0%} -> {'met' if figures['adds_cpu']['structured'] <= TARGET else 'missed'} (cpu)")

    hb, xs, omegas = captured["args"]
    figures["agreement"] = {"blade": agreement(stability, baseline, hb, xs, omegas),
                            "folds": fold_case(stability, baseline)}
    figures["whole_structure"] = whole_structure(args.repeat)
    print("saved", save_results("stability", figures))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
