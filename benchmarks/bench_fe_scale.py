"""Speed and memory at finite-element scale: forced responses of scikit-fem blades from 10^3 to 10^5 DOFs.

Run:  python benchmarks/bench_fe_scale.py              (10^3, 10^4, 10^5 DOFs and pyHarm; 20-30 minutes)
      python benchmarks/bench_fe_scale.py --quick      (10^3 DOFs only, no pyHarm; 5-10 minutes)
      python benchmarks/bench_fe_scale.py --sizes 1e3,1e5 --harmonics 5 --contacts 40 --no-pyharm

The structure: ``microslip.fe.blade(dofs, contact_nodes=n)`` (plane stress, nickel alloy, clamped
root; 10^3 DOFs ask for ``dofs=1000`` and get what the grid gives), damping ``C = 2e-7 K``
(0.085 % of critical at the first bending mode). Contacts: one on each of the ``2 n`` platform nodes
(10 or 40), the paper's sphere (d = 10 mm, steel, mu = 0.4) tuned with J = 8 elements at 37.5 N,
acting along x (the chord) with the normal load held at 37.5 N (``approach=model.approach(37.5)``).
Excitation: 1 N per contact, ``F cos(omega t)`` along x at the airfoil's tip. Frequency range
1200-1800 Hz: the first bending resonance, between the free blade (1352 Hz) and the blade with its
contacts stuck (1599 Hz with 10 contacts, 1643 Hz with 40). H = 5 and 7 harmonics, the default
samples per period (64 and 128) and continuation settings.

Every case runs in a fresh Python process (its peak memory is that process's ``ru_maxrss``: model
building with scikit-fem included), with ``OPENBLAS_NUM_THREADS=1`` (the machine's 2 cores are
shared; timings vary with its load, which is printed), after a small warm-up curve (Numba's
compiled kernels loaded). Reported per case:

* ``curve``: ``frequency_response`` from the structure to the result (reduction, static state,
  continuation, the stability of every point, result), its own ``elapsed``; in the comparison with
  the full solve the curves are timed without stability (``stability=False``: Hill's method on the
  full equations costs as much as their continuation), and the reduced ones again with it;
* ``reduction``: building the linear part (``reduction="modal"``: the eigensolution and residual
  flexibilities; ``"exact"``: splitting the matrices; the exact condensation factorises per
  frequency, or computes the held structure's modes once along a curve, inside ``continuation``);
* ``continuation``: the pseudo-arclength continuation alone, and its number of points;
* the first-harmonic peak of the tip's x displacement and, for ``"modal"``, the result's
  ``reduction_error`` (its estimate of the modal error).

Against the full solve (10^3 DOFs, 10 contacts, in one process): the curve with ``reduction="none"``,
``"exact"`` and ``"modal"``; then, since the curves' points fall at other frequencies, each
reduction is solved at the peak frequency of the exact curve (``frequency_point``) and compared
with the full solve there.

Against pyHarm (when ``pyHarm-os`` is installed, the ``bench`` extra): pyHarm's harmonic-domain
matrices are dense (``np.kron`` of the full matrices), so the comparison runs on the smallest blade
(``--pyharm-dofs``, default 300) with the same structure, contacts (each contact's 8 elements as 8
Jenkins elements, slip force ``mu kn (approach - gap)``) and excitation; pyHarm's ``NLdofs``
reductor, its default solver and nondimensionalisation (lc = 10 µm, wc = 10^4 rad/s), and a
solution-count stopper after ``--pyharm-points`` points, as its cost per point is what can be
measured in reasonable time. microslip's curve is timed on the same structure and solved at
pyHarm's frequencies to check that both solve the same equations.

The figures are saved to ``benchmarks/results/bench_fe_scale.json`` (``--quick``: ``bench_fe_scale_quick.json``)
by ``_common.save_results``, for the docs: the full solve's table per H (the ratio ``none / this`` is the
speed-up over ``reduction="none"`` in the same process), the scale table and the targets' ratios.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import in_temporary_directory, peak, pyharm_missing, run_pyharm, save_results  # noqa: E402

LOAD = 37.5  # N, each contact's normal load
ELEMENTS = 8
DAMPING = 2e-7  # s: C = DAMPING K
FORCE_PER_CONTACT = 1.0  # N
RANGE = (2 * np.pi * 1200.0, 2 * np.pi * 1800.0)  # rad/s
SIZES = (1e3, 1e4, 1e5)
TARGETS = {"ratio_full": 100.0, "curve_1e5": 60.0, "continuation_1e5": 5.0, "memory_1e5": 4.0,
           "ratio_pyharm": 20.0}


# -- the structure -------------------------------------------------------------------------------------
def blade_case(dofs: int, contacts: int):
    """``(structure, force, tip, model)``: the blade with ``contacts`` contacts (see the module docstring)."""
    from microslip import Sphere, Structure, tune
    from microslip.fe import blade

    model = tune(Sphere.paper(), LOAD, elements=ELEMENTS)
    b = blade(dofs, contact_nodes=contacts // 2)
    structure = Structure(b.M, DAMPING * b.K, b.K, dof_map=b.dof_map)
    for node in b.platform_nodes:
        structure.add_contact(model, tangential=f"{node}:x", approach=float(model.approach(LOAD)),
                              name=f"platform {node}")
    tip = structure.dof_index(f"{b.tip_node}:x")
    force = np.zeros(structure.ndof)
    force[tip] = FORCE_PER_CONTACT * contacts
    return structure, force, tip, model


def warm_up():
    """A small curve, so that Numba's compiled kernels are loaded before anything is timed."""
    from microslip import frequency_response

    structure, force, _, _ = blade_case(300, 2)
    for H in (5, 7):
        frequency_response(structure, force, RANGE, harmonics=H, reduction="exact")


def timed_curve(structure, force, tip, H: int, reduction: str, keep: bool = False, stability: bool = True):
    """One curve with the time of its reduction and of its continuation (wrapped, then restored)."""
    from microslip import frequency_response
    from microslip.frequency.analyses import response
    from microslip.frequency.equations import build

    spent = {"reduction": 0.0, "continuation": 0.0}

    def timing(name, fn):
        def wrapper(*args, **kwargs):
            t0 = time.perf_counter()
            try:
                return fn(*args, **kwargs)
            finally:
                spent[name] += time.perf_counter() - t0
        return wrapper

    saved = build.linear_part, response.continuation  # where frequency_response's path calls them
    build.linear_part = timing("reduction", saved[0])
    response.continuation = timing("continuation", saved[1])
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # an under-resolved contact energy is not what is measured here
            r = frequency_response(structure, force, RANGE, harmonics=H, reduction=reduction, stability=stability)
    finally:
        build.linear_part, response.continuation = saved
    w, a = r.peak(tip, harmonic=1)
    out = {"reduction": r.reduction, "modes": r.modes, "curve": r.elapsed, "setup": spent["reduction"],
           "continuation": spent["continuation"], "points": int(r.points), "complete": bool(r.complete),
           "peak_omega": w, "peak": a, "reduction_error": r.reduction_error}
    return (out, r) if keep else out


def process_memory_gb() -> float:
    """This process's peak resident memory (GB; ``ru_maxrss`` is in kB on Linux)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024 ** 2


# -- the cases, each in its own process ---------------------------------------------------------------
def case_scale(dofs: int, contacts: int, H: int, reduction: str) -> dict:
    warm_up()
    t0 = time.perf_counter()
    structure, force, tip, _ = blade_case(dofs, contacts)
    out = {"dofs": structure.ndof, "contacts": contacts, "H": H, "build": time.perf_counter() - t0}
    out.update(timed_curve(structure, force, tip, H, reduction))
    out["memory"] = process_memory_gb()
    return out


def tip_amplitudes(structure, force, tip, H: int, reduction: str, omegas, guesses) -> np.ndarray:
    """First-harmonic amplitude (m) of the tip, solved with ``reduction`` at each of ``omegas``.

    Newton's method starts from ``guesses`` (every DOF's coefficients, ``(2H+1, ndof)`` each: a
    neighbouring solution); ``frequency_point`` starts from the stuck structure instead, which does
    not converge this close to the peak. Uses the solver's internals (``_equations``, ``newton``).
    """
    from microslip.frequency.aft import MAX_PERIODS
    from microslip.frequency.numerics.continuation import newton
    from microslip.frequency.analyses.response import _equations

    _, hb, _ = _equations(structure, force, H, None, MAX_PERIODS, reduction, None)
    dofs = getattr(hb, "retained", np.arange(structure.ndof))
    column = int(np.flatnonzero(dofs == tip)[0])
    out = []
    for omega, guess in zip(omegas, guesses):
        x0 = np.ascontiguousarray(guess[:, dofs]).ravel()
        x, _ = newton(hb, x0, float(omega), r_scale=float(np.max(np.abs(hb.f))),
                      x_scale=float(np.max(np.abs(x0))))
        X = x.reshape(hb.nb, hb.ndof)
        out.append(np.hypot(X[1, column], X[2, column]))
    return np.array(out)


def case_full(H: int) -> dict:
    """10^3 DOFs, 10 contacts: the curve with every reduction, then each solved at the exact curve's top points.

    The three points around the top of the exact curve are solved with every reduction (from the
    exact solution there) and the peak read from them the same way (``FrequencyResponse.peak``'s
    parabola in arclength, :func:`_common.peak`): the curves' own points fall at other frequencies, so
    their peaks also differ by where the points fall.
    """
    warm_up()
    structure, force, tip, _ = blade_case(1000, 10)
    out = {"dofs": structure.ndof, "H": H}
    curves = {}
    for reduction in ("exact", "modal", "none"):
        out[reduction], curves[reduction] = timed_curve(structure, force, tip, H, reduction, keep=True,
                                                        stability=False)
    for reduction in ("exact", "modal"):  # the same curve with the stability of every point
        out[reduction]["with_stability"] = timed_curve(structure, force, tip, H, reduction)["curve"]
    exact = curves["exact"]
    k = int(np.argmax(exact.amplitude(tip, 1)))
    points = [k - 1, k, k + 1]
    omegas = exact.omega[points]
    guesses = [exact.recovery(j) for j in points]
    out["omega_star"] = float(omegas[1])
    for reduction in ("exact", "modal", "none"):
        amp = tip_amplitudes(structure, force, tip, H, reduction, omegas, guesses)
        out[reduction]["top"] = peak(omegas, amp, float(np.ptp(omegas)))
    out["memory"] = process_memory_gb()
    return out


def pyharm_inputs(structure, force, tip, model, H: int, samples: int, points: int) -> dict:
    """pyHarm's input for the same structure: one DOF per node, each contact element a Jenkins element."""
    M, C, K = (A.toarray() for A in (structure.M, structure.C, structure.K))
    normal = np.maximum(model.kn * (model.approach(LOAD) - model.gaps), 0.0)  # each element's normal force
    connectors = {}
    for c, contact in enumerate(structure.contacts):
        dof = int(np.flatnonzero(structure.contact_directions()[0][:, c])[0])
        for j in np.flatnonzero(normal > 0):
            connectors[f"contact{c}_element{j}"] = {
                "type": "Jenkins", "connect": {"blade": [dof]}, "dirs": [0], "k": float(model.kt[j]),
                "mu": float(model.mu), "N0": float(normal[j])}
    connectors["force"] = {"type": "CosinusForcing", "connect": {"blade": [tip]}, "dirs": [0],
                           "amp": float(force[tip])}
    return {
        "system": {"type": "Base", "nh": H, "nti": samples, "adim": {"status": True, "lc": 1e-5, "wc": 1e4}},
        "substructures": {"blade": {"type": "substructure", "ndofs": 1, "matrix": {"M": M, "K": K, "C": C}}},
        "connectors": connectors,
        "analysis": {"frf": {"study": "frf", "puls_inf": RANGE[0], "puls_sup": RANGE[1], "ds0": 0.05,
                             "ds_max": 0.05, "ds_min": 1e-8, "reductors": [{"type": "NLdofs"}], "verbose": False,
                             "stopper": "solnumber", "stopper_options": {"max_solutions": points}}},
    }


def case_pyharm(dofs: int, H: int, points: int) -> dict:
    """pyHarm on the ``dofs`` blade for ``points`` points against microslip's whole curve on the same blade."""
    from microslip.frequency import frequency_point
    from microslip.frequency.aft import default_samples

    warm_up()
    structure, force, tip, model = blade_case(dofs, 10)
    mine = timed_curve(structure, force, tip, H, "exact")
    samples = default_samples(H)
    inputs = pyharm_inputs(structure, force, tip, model, H, samples, points)
    elapsed, X, maestro = in_temporary_directory(lambda: run_pyharm(inputs))
    dofs_table = maestro.system.expl_dofs
    rows = [int(np.flatnonzero((dofs_table["node_num"] == tip) & (dofs_table["harm"] == 1)
                               & (dofs_table["cs"] == cs))[0]) for cs in ("c", "s")]
    omega = X[:, -1] * 1e4
    amp = np.hypot(X[:, rows[0]], X[:, rows[1]]) * 1e-5
    diffs = []
    for w, a in zip(omega, amp):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            one = frequency_point(structure, force, float(w), harmonics=H, reduction="exact")
        diffs.append(abs(float(one.amplitude(tip, 1)[0]) / a - 1))
    return {"dofs": structure.ndof, "H": H, "microslip": mine, "pyharm_seconds": elapsed,
            "pyharm_points": int(X.shape[0]), "pyharm_omega": omega.tolist(), "same_solution": max(diffs),
            "memory": process_memory_gb()}


CASES = {"scale": case_scale, "full": case_full, "pyharm": case_pyharm}


def in_child(kind: str, **kwargs) -> dict:
    """Run ``CASES[kind](**kwargs)`` in a fresh Python process; its result (JSON on the last line of stdout)."""
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    before = os.getloadavg()[0]
    proc = subprocess.run([sys.executable, __file__, "--case", json.dumps({"kind": kind, **kwargs})],
                          env=env, capture_output=True, text=True)
    if proc.returncode:
        raise RuntimeError(f"case {kind} {kwargs} failed:\n{proc.stderr[-3000:]}")
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    out["load"] = (before, os.getloadavg()[0])
    return out


# -- report -------------------------------------------------------------------------------------------
def load_note(out: dict) -> str:
    return f"load {out['load'][0]:.1f} -> {out['load'][1]:.1f}"


def report_full(out: dict) -> float:
    H, ex, mo, no = out["H"], out["exact"], out["modal"], out["none"]
    print(f"\n10^3 DOFs ({out['dofs']}), 10 contacts, H = {H}: every reduction in one process ({load_note(out)}, "
          f"peak memory {out['memory']:.2f} GB)")
    print(f"  {'reduction':9} {'curve s':>8} {'contin. s':>9} {'points':>6} {'none / this':>11} "
          f"{'its peak µm':>12} {'top-3 peak µm':>14} {'vs none':>9} {'with stability s':>16}")
    for name, r in (("none", no), ("exact", ex), ("modal", mo)):
        extra = f"{r['with_stability']:16.2f}" if "with_stability" in r else f"{'-':>16}"
        print(f"  {name:9} {r['curve']:8.2f} {r['continuation']:9.2f} {r['points']:6d} "
              f"{no['curve'] / r['curve']:10.0f}x {r['peak'] * 1e6:12.6f} {r['top'] * 1e6:14.8f} "
              f"{r['top'] / no['top'] - 1:+9.1e} {extra}")
    print("  curve s: without stability (stability=False); with stability s: the same curve with Hill's method "
          "at every point (exact: on a 60-mode modal model of the blade, above 4000 unknowns)")
    print(f"  its peak: read from its own curve; top-3 peak: read from the exact curve's three top frequencies "
          f"(around {out['omega_star']:.1f} rad/s) solved with each reduction; modal: {mo['modes']} modes, "
          f"reduction_error estimate {mo['reduction_error']:.1e}")
    return no["curve"] / ex["curve"]


def report_scale(rows: list) -> None:
    print(f"\n  {'DOFs':>7} {'cont.':>5} {'H':>2} {'reduction':>10} {'build s':>8} {'reduction s':>11} "
          f"{'curve s':>8} {'contin. s':>9} {'points':>6} {'memory GB':>9} {'peak µm':>9} {'error est.':>10}  load")
    for r in rows:
        name = r["reduction"] + (f" {r['modes']}" if r["modes"] else "")
        err = f"{r['reduction_error']:.1e}" if r["reduction_error"] is not None else "-"
        print(f"  {r['dofs']:7d} {r['contacts']:5d} {r['H']:2d} {name:>10} {r['build']:8.1f} {r['setup']:11.2f} "
              f"{r['curve']:8.2f} {r['continuation']:9.2f} {r['points']:6d} {r['memory']:9.2f} "
              f"{r['peak'] * 1e6:9.4f} {err:>10}  {load_note(r)}")


def report_pyharm(out: dict) -> float:
    mine = out["microslip"]
    per_point_mine = mine["curve"] / mine["points"]
    per_point_ph = out["pyharm_seconds"] / out["pyharm_points"]
    print(f"\npyHarm (NLdofs reductor) on the {out['dofs']}-DOF blade, 10 contacts of 8 Jenkins elements, "
          f"H = {out['H']} ({load_note(out)}, peak memory {out['memory']:.2f} GB)")
    print(f"  pyHarm: {out['pyharm_seconds']:.1f} s for its first {out['pyharm_points']} points "
          f"({per_point_ph:.1f} s per point)")
    print(f"  microslip: {mine['curve']:.2f} s for the whole curve, {mine['points']} points "
          f"({per_point_mine * 1e3:.1f} ms per point)")
    print(f"  same solutions: largest relative difference at pyHarm's points {out['same_solution']:.1e}")
    ratio = per_point_ph / per_point_mine
    print(f"  RATIO pyHarm / microslip per point: {ratio:.0f}x (pyHarm's curve at microslip's {mine['points']} "
          f"points would take {per_point_ph * mine['points'] / 3600:.1f} h)")
    return ratio


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="10^3 DOFs only")
    parser.add_argument("--sizes", default=None, help="comma-separated DOF counts (default 1e3,1e4,1e5)")
    parser.add_argument("--contacts", default="10,40", help="comma-separated contact counts (default 10,40)")
    parser.add_argument("--harmonics", default="5,7", help="comma-separated H (default 5,7)")
    parser.add_argument("--no-full", action="store_true", help="skip the comparison with reduction='none'")
    parser.add_argument("--no-pyharm", action="store_true", help="skip the comparison with pyHarm")
    parser.add_argument("--pyharm-dofs", type=int, default=300, help="blade size for pyHarm (default 300)")
    parser.add_argument("--pyharm-points", type=int, default=2, help="pyHarm's points (default 2)")
    parser.add_argument("--case", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.case:  # a child process: one case, its result as JSON on the last line
        spec = json.loads(args.case)
        print(json.dumps(CASES[spec.pop("kind")](**spec)))
        return 0

    sizes = [1e3] if args.quick else [float(s) for s in (args.sizes or "1e3,1e4,1e5").split(",")]
    contacts = [int(c) for c in args.contacts.split(",")]
    harmonics = [int(h) for h in args.harmonics.split(",")]
    print(f"bench_fe_scale: {os.cpu_count()} cores, load {os.getloadavg()[0]:.1f} at the start; "
          f"each case in its own process with OPENBLAS_NUM_THREADS=1")
    summary, fulls, pyharm = {}, [], None
    load_before = os.getloadavg()[0]
    if not args.no_full and 1e3 in sizes:
        for H in harmonics:
            fulls.append(in_child("full", H=H))
            summary[f"ratio_full H={H}"] = report_full(fulls[-1])
    rows = []
    print("\nScale (reduction='auto': exact up to 5000 DOFs, modal with 60 modes above; "
          "every point's stability included):")
    for size in sizes:
        for nc in contacts:
            for H in harmonics:
                rows.append(in_child("scale", dofs=int(size), contacts=nc, H=H, reduction="auto"))
                report_scale(rows[-1:])
    if args.quick and not args.no_pyharm:
        print("\n--quick: the comparison with pyHarm is skipped (10-15 minutes; run without --quick)")
    elif not args.no_pyharm:
        missing = pyharm_missing()
        if missing:
            print(f"\npyHarm is not installed ({missing.split(':')[0]}); install the bench extra to compare. Skipped.")
        else:
            pyharm = in_child("pyharm", dofs=args.pyharm_dofs, H=harmonics[0], points=args.pyharm_points)
            summary["ratio_pyharm"] = report_pyharm(pyharm)
    big = [r for r in rows if r["dofs"] > 5e4 and r["contacts"] == 40]
    print("\nTargets:")
    for key, value in summary.items():
        goal = TARGETS["ratio_pyharm" if key.startswith("ratio_pyharm") else "ratio_full"]
        print(f"  {key}: {value:.0f}x (target >= {goal:.0f}x) {'met' if value >= goal else 'MISSED'}")
    for r in big:
        for key, value, unit in (("curve_1e5", r["curve"], "s"), ("continuation_1e5", r["continuation"], "s"),
                                 ("memory_1e5", r["memory"], "GB")):
            goal = TARGETS[key]
            print(f"  {key} H={r['H']}: {value:.2f} {unit} (target < {goal:g} {unit}) "
                  f"{'met' if value < goal else 'MISSED'}")
    by_size = {}
    for r in rows:
        by_size.setdefault((r["contacts"], r["H"]), []).append((r["dofs"], r["points"]))
    print("  continuation points by size (contacts, H): "
          + "; ".join(f"{k}: " + ", ".join(f"{d} DOFs {p}" for d, p in v) for k, v in by_size.items()))
    save(args, argv, load_before, summary, fulls, rows, pyharm)
    return 0


def save(args, argv, load_before: float, summary: dict, fulls: list, rows: list, pyharm: dict | None) -> None:
    """The figures printed, to ``benchmarks/results/bench_fe_scale[_quick].json``."""
    tables = [{"caption": "the targets' ratios (speed-up over the baseline in the same process)",
               "columns": ["ratio", "value", "target"],
               "rows": [[k, v, TARGETS["ratio_pyharm" if k.startswith("ratio_pyharm") else "ratio_full"]]
                        for k, v in summary.items()]}] if summary else []
    for out in fulls:
        no = out["none"]
        tables.append({"caption": f"{out['dofs']} DOFs, 10 contacts, H = {out['H']}: every reduction in one process "
                                  f"(load {out['load'][0]:.1f} to {out['load'][1]:.1f}, peak memory "
                                  f"{out['memory']:.2f} GB); curves without stability, then with it",
                       "columns": ["reduction", "curve (s)", "continuation (s)", "points", "none / this",
                                   "its peak (µm)", "top-3 peak (µm)", "vs none", "with stability (s)"],
                       "rows": [[name, r["curve"], r["continuation"], r["points"], no["curve"] / r["curve"],
                                 r["peak"] * 1e6, r["top"] * 1e6, r["top"] / no["top"] - 1,
                                 r.get("with_stability", "-")]
                                for name, r in (("none", no), ("exact", out["exact"]), ("modal", out["modal"]))]})
    tables.append({"caption": "scale: reduction='auto', every point's stability included, each case in its own "
                              "process",
                   "columns": ["DOFs", "contacts", "H", "reduction", "build (s)", "reduction (s)", "curve (s)",
                               "continuation (s)", "points", "memory (GB)", "peak (µm)", "error estimate", "load"],
                   "rows": [[r["dofs"], r["contacts"], r["H"], r["reduction"] + (f" {r['modes']}" if r["modes"] else ""),
                             r["build"], r["setup"], r["curve"], r["continuation"], r["points"], r["memory"],
                             r["peak"] * 1e6, r["reduction_error"] if r["reduction_error"] is not None else "-",
                             f"{r['load'][0]:.1f} to {r['load'][1]:.1f}"] for r in rows]})
    if pyharm is not None:
        mine = pyharm["microslip"]
        tables.append({"caption": f"pyHarm (NLdofs reductor) against microslip on the {pyharm['dofs']}-DOF blade, "
                                  f"H = {pyharm['H']}, per point",
                       "columns": ["pyHarm (s)", "pyHarm points", "microslip curve (s)", "microslip points",
                                   "ratio per point", "same solution"],
                       "rows": [[pyharm["pyharm_seconds"], pyharm["pyharm_points"], mine["curve"], mine["points"],
                                 summary["ratio_pyharm"], pyharm["same_solution"]]]})
    argv = sys.argv[1:] if argv is None else list(argv)
    pyharm_note = ("pyHarm compared" if pyharm is not None else
                   "pyHarm not compared (--quick, --no-pyharm, or not installed)")
    figures = {"description": "Forced responses of scikit-fem blades with sphere contacts (J = 8) at finite-element "
                              "scale: the curve with reduction 'exact' and 'modal' against the full solve "
                              "(reduction='none', the baseline, same process), time and memory from 10^3 DOFs up; "
                              + pyharm_note + ".",
               "command": "python benchmarks/bench_fe_scale.py" + "".join(f" {a}" for a in argv),
               "sizes": f"load average {load_before:.2f} at the start; each case in a fresh process with "
                        "OPENBLAS_NUM_THREADS=1",
               "tables": tables}
    print(f"results: {save_results('bench_fe_scale' + ('_quick' if args.quick else ''), figures)}")


if __name__ == "__main__":
    sys.exit(main())
