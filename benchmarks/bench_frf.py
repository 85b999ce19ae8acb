"""Speed of a whole forced-response curve, microslip against pyHarm in the same run.

Run:  OPENBLAS_NUM_THREADS=1 python benchmarks/bench_frf.py      (about a minute)
The comparison with pyHarm runs when ``pyHarm-os`` is installed (it is the ``bench`` extra of
pyproject.toml); without it the microslip part runs and the comparison is skipped with a message: the
curve's time is then absolute, and the ratios printed are the stability costs below (the same curve
with and without Hill's method, in the same run).

The problem (same for both codes): a 1-DOF oscillator m = 1 kg, k = 1e4 N/m, c = 1 N s/m with
one Jenkins element kt = 1e4 N/m, slip force 1 N, excitation 2 N cos(omega t), omega from 60 to
160 rad/s, H = 7 harmonics, 128 time samples per period.

Accuracy: each code's curve must give the peak of the first-harmonic amplitude within 1e-4
(relative) of a converged reference (microslip with very small continuation steps). The peak
is read from each curve the same way (a parabola through the highest point and its two
neighbours, in arclength). pyHarm's step is refined (ds = 0.05, 0.04, 0.03, ...) until it
meets the bar, with its nondimensionalisation set like microslip's scaling (lc = 5 mm,
wc = 100 rad/s) so that its arclength measures the amplitude too; the time of the first run
that meets the bar is the one compared. Both codes are warmed up (JIT compilation) first.
The solutions are also compared point by point (microslip solved at pyHarm's frequencies).

A second figure: the curve of a blade with a 16-element microslip damper (examples/blade_damper.py
with the sphere contact tuned with 16 elements; normal load 37.5 N, all 16 elements closed), at the
excitation level of the optimum of the 4-element damper (7 N: the elements slip one after the other
along the curve), H = 7, 128 samples.

The cost of stability (Hill's method at every point): each curve timed with and without it in the
same run (the curves above are timed without it: pyHarm computes none), the RATIO printed; also on
a reduced finite-element curve (the scikit-fem blade of about 1000 DOFs, a Jenkins contact at each of
its four platform nodes, H = 5; needs the fe extra), with reduction="exact" (Hill's problem of the
whole structure, 11000 unknowns) and "modal" (40 modes, 440 unknowns). Run it with
OPENBLAS_NUM_THREADS=1 on a shared machine (OpenBLAS's threads slow the reductions' small dense algebra).

The figures are saved to ``benchmarks/results/bench_frf.json`` by ``_common.save_results``, for the docs.
"""

from __future__ import annotations

import os
import sys
import time
import warnings
from pathlib import Path

import numpy as np

from microslip import MicroslipModel, Structure, frequency_response
from microslip.frequency import StepControl, frequency_point

sys.path.insert(0, str(Path(__file__).resolve().parent))
import _common  # noqa: E402  (the benchmarks' shared helpers, next to this file)
from _common import best_of, in_temporary_directory, pyharm_missing, run_pyharm, save_results  # noqa: E402

A_TOL = 1e-4
#: the rows of the saved table of stability costs: curve, points, without (s), with (s), ratio, unstable, bifurcations
STABILITY_ROWS = []


def jenkins_oscillator() -> Structure:
    s = Structure(M=[[1.0]], C=[[1.0]], K=[[1e4]])
    s.add_contact(MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0), tangential=0, approach=1e-6)
    return s


def peak(omega, amp):
    """Peak amplitude (m), read as :func:`_common.peak` does with the 100 rad/s frequency scale."""
    return _common.peak(omega, amp, 100.0)


def microslip_curve(control=None, stability=False):
    """The curve alone (pyHarm computes no stability), or with Hill's stability at every point."""
    return frequency_response(jenkins_oscillator(), [2.0], (60.0, 160.0), harmonics=7, samples=128, control=control,
                              stability=stability)


def stability_cost(label, run, t_curve, repeat=5):
    """Time of ``run(stability=True)`` against the curve alone (``t_curve``, s); the RATIO with / without."""
    t, r = best_of(lambda: run(stability=True), repeat)
    print(f"{label} with stability (Hill's method at every point): {t * 1e3:.1f} ms, "
          f"+{(t - t_curve) / r.points * 1e3:.3f} ms per point; RATIO with / without {t / t_curve:.2f}x "
          f"({int((~r.stable).sum())} of {r.points} points unstable, {len(r.bifurcations)} bifurcations)")
    STABILITY_ROWS.append([label, int(r.points), t_curve, t, t / t_curve, int((~r.stable).sum()),
                           len(r.bifurcations)])
    return r


def pyharm_input(ds):
    node = {"connect": {"sub": [0]}, "dirs": [0]}
    return {
        "system": {"type": "Base", "nh": 7, "nti": 128, "adim": {"status": True, "lc": 5e-3, "wc": 100.0}},
        "substructures": {"sub": {"type": "onlydofs", "nnodes": 1, "ndofs": 1, "matching": [0]}},
        "connectors": {
            "mass": {"type": "GOElement", "dto": 2, "xo": 1, "k": 1.0, **node},
            "spring": {"type": "LinearSpring", "k": 1e4, **node},
            "damper": {"type": "LinearDamper", "k": 1.0, **node},
            "jenkins": {"type": "Jenkins", "k": 1e4, "mu": 1.0, "N0": 1.0, **node},
            "force": {"type": "CosinusForcing", "amp": 2.0, **node},
        },
        "analysis": {"frf": {"study": "frf", "puls_inf": 60.0, "puls_sup": 160.0, "ds0": ds, "ds_max": ds,
                             "ds_min": 1e-8, "verbose": False}},
    }


def pyharm_curve(ds):
    """(seconds, omega, first-harmonic amplitude, points) of a pyHarm run."""
    elapsed, X, _ = run_pyharm(pyharm_input(ds))
    omega = X[:, -1] * 100.0  # undo the nondimensionalisation (wc = 100 rad/s, lc = 5 mm)
    amp = np.hypot(X[:, 1], X[:, 2]) * 5e-3
    keep = (omega >= 60.0) & (omega <= 160.0)
    return elapsed, omega[keep], amp[keep], int(keep.sum())


def main():
    warnings.filterwarnings("ignore")
    print(f"load average {os.getloadavg()[0]:.2f} ({os.cpu_count()} cores)")
    # reference: microslip with very small steps
    ref = microslip_curve(StepControl(ds_max=0.002, max_angle=0.01, max_points=100000))
    a_ref = peak(ref.omega, ref.amplitude(0, 1))
    microslip_curve()  # warm-up
    t_ms, curve = best_of(microslip_curve)
    err_ms = peak(curve.omega, curve.amplitude(0, 1)) / a_ref - 1
    print(f"reference peak amplitude {a_ref * 1e3:.7f} mm ({ref.points} points)")
    print(f"microslip: {t_ms * 1e3:7.1f} ms for {curve.points} points "
          f"({t_ms / curve.points * 1e3:.3f} ms per point), peak error {err_ms:+.1e}")
    assert abs(err_ms) < A_TOL
    stability_cost("1-DOF Jenkins oscillator", lambda stability: microslip_curve(stability=stability), t_ms)
    figures = {"description": "A whole forced-response curve: a 1-DOF Jenkins oscillator (H = 7, 128 samples), "
                              "against pyHarm to the same peak accuracy in the same run when pyHarm is installed; "
                              "a blade with a 16-element microslip damper; the cost of the stability of every "
                              "point (Hill's method), each curve with and without it in the same run, also on a "
                              "reduced finite-element blade.",
               "command": "OPENBLAS_NUM_THREADS=1 python benchmarks/bench_frf.py",
               "sizes": f"1-DOF oscillator: reference peak from {ref.points} points; best of 5 runs "
                        "(finite-element blade: best of 2)",
               "oscillator": {"microslip_seconds": t_ms, "points": int(curve.points), "peak_error": err_ms,
                              "peak_tolerance": A_TOL}}
    figures["oscillator"].update(compare_with_pyharm(t_ms, a_ref))
    figures["blade with a 16-element damper"] = sixteen_element_damper()
    figures["finite-element blade"] = reduced_fe_stability()
    tables = [{"caption": "the 1-DOF oscillator's curve", "columns": ["figure", "value"],
               "rows": [[k, v] for k, v in figures.pop("oscillator").items()]}]
    for key in ("blade with a 16-element damper", "finite-element blade"):
        if figures.get(key):
            tables.append({"caption": key, "columns": ["figure", "value"],
                           "rows": [[k, v] for k, v in figures.pop(key).items()]})
        figures.pop(key, None)
    tables.append({"caption": "the cost of stability: each curve with and without Hill's method, same run",
                   "columns": ["curve", "points", "without (s)", "with (s)", "ratio with / without",
                               "unstable points", "bifurcations"], "rows": STABILITY_ROWS})
    figures["tables"] = tables
    print(f"results: {save_results('bench_frf', figures)}")


def compare_with_pyharm(t_ms, a_ref):
    """pyHarm's curve to the same peak accuracy, timed, and the ratio to microslip's time ``t_ms``."""
    missing = pyharm_missing()
    if missing:
        print(f"pyHarm is not installed ({missing.split(':')[0]}); install the bench extra to compare. Skipped.")
        return {"pyharm": f"not compared: pyHarm cannot be imported here ({missing.split(':')[0]})"}
    pyharm_curve(0.2)  # warm-up: JIT compilation of pyHarm's kernels
    for ds in (0.05, 0.04, 0.03, 0.02, 0.01):
        t_ph, w, a, pts = pyharm_curve(ds)
        err_ph = peak(w, a) / a_ref - 1
        print(f"pyHarm ds = {ds}: {t_ph * 1e3:7.1f} ms for {pts} points ({t_ph / pts * 1e3:.3f} ms per point), "
              f"peak error {err_ph:+.1e}")
        if abs(err_ph) < A_TOL:
            break
    else:
        print("pyHarm did not reach the accuracy bar; the last run is compared")
    # the two codes solve the same equations: microslip at pyHarm's frequencies
    diffs = []
    for k in np.linspace(1, len(w) - 2, 6).astype(int):
        one = frequency_point(jenkins_oscillator(), [2.0], w[k], harmonics=7, samples=128)
        diffs.append(abs(one.amplitude(0, 1)[0] / a[k] - 1))
    print(f"same solutions: largest relative difference at 6 of pyHarm's points {max(diffs):.1e}")
    print(f"RATIO pyHarm / microslip, same peak accuracy: {t_ph / t_ms:.0f}x")
    return {"pyharm_seconds": t_ph, "pyharm_points": pts, "pyharm_ds": ds, "pyharm_peak_error": err_ph,
            "same_solution": max(diffs), "ratio_pyharm_over_microslip": t_ph / t_ms}


def sixteen_element_damper():
    """The blade of examples/blade_damper.py with its damper tuned with 16 elements, timed."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))
    from blade_damper import blade_with_damper

    blade = blade_with_damper(elements=16)
    run = lambda stability=False: frequency_response(blade, [0.0, 7.0], (4000.0, 12000.0), harmonics=7,  # noqa: E731
                                                     samples=128, stability=stability)
    run()
    t16, r16 = best_of(run)
    slipping = np.count_nonzero(r16.contact_dissipation[:, 0] > 1e-6 * r16.excitation_work)
    print(f"blade with a 16-element damper (F = 7 N, H = 7, 128 samples): {t16 * 1e3:.1f} ms for {r16.points} "
          f"points ({slipping} with the contact dissipating); static state N0 = "
          f"{r16.static_normal_force[0]:.4g} N, T0 = {r16.static_tangential_force[0]:.2g} N, "
          f"{r16.static_closed_elements[0]} of 16 elements closed")
    stability_cost("blade, 16-element damper", run, t16)
    return {"seconds": t16, "points": int(r16.points), "points_dissipating": int(slipping),
            "closed_elements": int(r16.static_closed_elements[0])}


def reduced_fe_stability():
    """Stability on a reduced finite-element curve: exact (the whole structure's Hill problem) and modal."""
    try:
        from microslip.fe import blade
    except ImportError as exc:
        print(f"the fe extra is not installed ({exc}): the finite-element stability case is skipped")
        return {}
    b = blade(1000, contact_nodes=2)
    s = Structure(b.M, 2e-7 * b.K, b.K, dof_map=b.dof_map)
    for node in b.platform_nodes:
        s.add_contact(MicroslipModel(kt=[2e6], kn=[2e8], gaps=[0.0], mu=0.1), tangential={f"{node}:x": 1.0},
                      normal={f"{node}:y": 1.0}, preload=50.0)
    f = s.force_vector({f"{b.tip_node}:x": 12.0})
    out = {"dofs": s.ndof, "contacts": len(s.contacts)}
    for reduction, modes in (("exact", None), ("modal", 40)):
        def run(stability=False):
            return frequency_response(s, f, (7000.0, 11000.0), harmonics=5, reduction=reduction, modes=modes,
                                      stability=stability)

        t, r = best_of(run, repeat=2)
        slipping = np.count_nonzero(r.contact_dissipation.max(axis=1) > 0)
        print(f"FE blade, {s.ndof} DOFs, 4 contacts, H = 5, reduction = {reduction!r}"
              + (f" ({modes} modes)" if modes else "") + f": curve alone {t:.2f} s for {r.points} points "
              f"({slipping} with a contact slipping)")
        with_stability = stability_cost(f"FE blade {reduction}" + (f" ({modes} modes)" if modes else ""), run, t,
                                        repeat=2)
        out[f"{reduction}: points"] = int(r.points)
        if reduction == "exact":
            out.update(whole_structure_hill(run, with_stability))
    return out


def whole_structure_hill(run, modal):
    """An exact reduction's stability from the modal model (``modal``: the curve with the default, on that
    model here) against the whole structure's."""
    from microslip.frequency.analyses import stability

    saved = stability.WHOLE_LIMIT
    stability.WHOLE_LIMIT = 10 ** 9
    try:
        t0 = time.perf_counter()
        whole = run(stability=True)
        t_whole = time.perf_counter() - t0
    finally:
        stability.WHOLE_LIMIT = saved
    same = bool(np.array_equal(modal.stable, whole.stable))
    gap = float(np.max(np.abs(modal.leading_exponent - whole.leading_exponent) / modal.omega))
    moved = max((abs(a.omega - b.omega) / b.omega for a, b in zip(modal.bifurcations, whole.bifurcations)),
                default=0.0)
    print(f"  the same curve with Hill's method on the whole structure: {t_whole:.2f} s; the same verdict at every "
          f"point: {same}; leading exponents within {gap:.1e} of omega; bifurcations "
          f"{[b.kind for b in whole.bifurcations]} moved by {moved:.1e} in frequency")
    return {"exact, Hill's method on the whole structure (s)": t_whole, "same verdict at every point": same,
            "leading exponents' difference / omega": gap, "bifurcations moved (relative)": float(moved)}


if __name__ == "__main__":
    in_temporary_directory(main)
