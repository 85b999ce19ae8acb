"""Speed of a bladed disk's forced response: one cyclic sector against the whole assembled disk, same run.

Run:  python benchmarks/bench_cyclic.py [--disk-points K]
      python benchmarks/bench_cyclic.py --quick     (blades of about 2000 DOFs, the disk's first 4 points)

The model: a disk of 24 identical blades clamped in a rigid disk, each the plane-stress scikit-fem
blade of ``microslip.fe.blade`` with about 10^4 DOFs (shank 16 mm wide, platform 6 mm thick), and
between every pair of neighbouring blades an under-platform damper (5 g) with two flat faces
inclined at 40 degrees, two contacts on each (4 contacts), each a flat punch with rounded edges
(MDR reference, nickel alloy on cobalt alloy, mu = 0.5) tuned with J = 8 elements; centrifugal load
150 N; 0.5 N at every blade tip, engine order 3; H = 5 harmonics, 128 samples per period.

Three timings, each of a whole forced-response curve (8000 to 20000 rad/s, around the first
blade mode stiffened by the damper), reduction set-up included:

1. the 10^4-DOF finite-element sector, ``reduction="modal"`` with 10 modes per nodal diameter
   (the speed target: under 5 s);
2. the same sector reduced first by Craig--Bampton (the platform's contact nodes and the tip kept,
   20 fixed-interface modes), ``reduction="exact"``;
3. the assembled 24-sector disk of those Craig--Bampton blades (``CyclicStructure.assembled``),
   ``reduction="exact"``: the same reduction as 2, solved as one structure. Its harmonic balance
   has 24 times the sector's unknowns, and a Newton step costs about 24^3 times the sector's
   linear solve, so only its first K points are computed (``--disk-points``, default 6); sector
   2 is timed over the same stretch of frequencies, and the ratio of those two times is the
   measured speed-up (the whole curve's would be larger: the disk's set-up, a few dense solves of
   its size, weighs less over more points, and its continuation takes smaller steps in its
   24 times longer vector of unknowns).

The whole disk of 10^4-DOF blades (2.4e5 DOFs, 240 modes) is not run: its modal set-up alone
needs about 10 GB and tens of minutes on this machine.
Both solutions are checked against each other at the points the disk computed.

The figures are saved to ``benchmarks/results/bench_cyclic.json`` (``--quick``: ``bench_cyclic_quick.json``)
by ``_common.save_results``, for the docs.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
import warnings
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # small dense blocks: BLAS threads only fight

import numpy as np  # noqa: E402

from microslip import Sphere, mdr, tune  # noqa: E402
from microslip.fe import blade  # noqa: E402
from microslip.frequency import (CyclicStructure, StepControl, UnderPlatformDamper, craig_bampton,  # noqa: E402
                                 frequency_point, frequency_response)
from microslip.reference.profiles import RoundedPunch  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import save_results  # noqa: E402

SECTORS, ENGINE_ORDER, HARMONICS = 24, 3, 5
LOAD, TIP_FORCE = 150.0, 0.5  # N
RANGE = (8000.0, 20000.0)  # rad/s
ANGLE = np.radians(40.0)  # the faces' inclination from the circumferential direction
PITCH = 0.044  # m between neighbouring blades at the platform


def contact_law():
    """A flat punch with rounded edges (1 mm flat, 5 mm edge radius), nickel alloy on cobalt alloy, J = 8."""
    pair = Sphere(radius=5e-3, E=200e9, nu=0.3, mu=0.5, E2=225e9, nu2=0.29)  # E*, G*, mu of the pair
    reference = mdr(pair, max_load=1000.0, elements=2000, profile=RoundedPunch(1e-3, 5e-3)).as_reference()
    return tune(reference, 1000.0, elements=8)


def fe_blade(dofs=10000):
    return blade(dofs, shank_width=0.016, platform_height=0.006)


def contact_dofs(b):
    """Sector DOFs: the right overhang's outer and inner contact nodes, the left's, the tip (x)."""
    right, left = b.node_sets["platform_right"], b.node_sets["platform_left"]
    nodes = [right[2], right[0], left[0], left[2]]  # x = 16, 20, -20, -16 mm
    dofs = [b.dof_map.index(f"{n}:{c}") for n in nodes for c in "xy"]
    return dofs + [b.dof_map.index(f"{b.tip_node}:x")]


def damper(disk, platform):
    """The damper: its left face on this blade's right overhang, its right face on the next blade's left one.

    ``platform``: the sector DOFs of :func:`contact_dofs`' first eight entries (x, y of four nodes).
    """
    d = UnderPlatformDamper(0.005, 2e-8, centrifugal_load=LOAD, damping=100.0)
    law = contact_law()
    # the faces' midpoints lie on their normals through the centre of mass: equal static loads on a rigid pair
    mid = 4e-3 / np.tan(ANGLE)
    left = [(-6e-3, mid - 2e-3 * np.tan(ANGLE)), (-2e-3, mid + 2e-3 * np.tan(ANGLE))]
    on = [{"x": platform[0], "y": platform[1]}, {"x": platform[2], "y": platform[3]}]
    d.add_interface(law, points=left, angle=np.pi / 2 + ANGLE, platform=on, name="left")
    nxt = [{"x": disk.next(platform[4]), "y": disk.next(platform[5])},
           {"x": disk.next(platform[6]), "y": disk.next(platform[7])}]
    d.add_interface(law, points=[(-x, y) for x, y in left][::-1], angle=np.pi / 2 - ANGLE, platform=nxt,
                    name="right")
    return d


def sectors(dofs=10000):
    """``(fe, cb, tip_fe, tip_cb)``: the finite-element sector and its Craig--Bampton twin with dampers, tips."""
    b = fe_blade(dofs)
    dofs = contact_dofs(b)
    fe = CyclicStructure(b.M, 2e-7 * b.K, b.K, sectors=SECTORS, left=[], right=[])
    cb = craig_bampton(fe, dofs, modes=20).structure  # kept DOFs first, in the order of dofs
    fe_s = damper(fe, dofs[:8]).attach(fe)
    cb_s = damper(cb, list(range(8))).attach(cb)
    return fe_s, cb_s, dofs[8], 8, b.ndof


def force(s, tip):
    f = np.zeros(s.ndof)
    f[tip] = TIP_FORCE
    return f


def curve(structure, f, reduction, modes=None, points=None, omega=RANGE, **kw):
    control = StepControl(max_points=points) if points else None
    start = time.perf_counter()
    cpu = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a curve cut at max_points; contacts opening within the AFT's resolution
        r = frequency_response(structure, f, omega, harmonics=HARMONICS, reduction=reduction, modes=modes,
                               control=control, **kw)
    return r, time.perf_counter() - start, time.process_time() - cpu


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--disk-points", type=int, default=None,
                        help="points of the whole disk's curve computed (default 6; --quick: 4)")
    parser.add_argument("--quick", action="store_true", help="blades of about 2000 DOFs, the disk's first 4 points")
    args = parser.parse_args()
    dofs = 2000 if args.quick else 10000
    if args.disk_points is None:
        args.disk_points = 4 if args.quick else 6
    print(f"load average {os.getloadavg()[0]:.2f} ({os.cpu_count()} cores)")
    fe, cb, tip_fe, tip_cb, ndof = sectors(dofs)
    print(f"sector: {ndof} blade DOFs + 3 damper DOFs, {len(fe.contacts)} contacts of J = "
          f"{fe.contacts[0].model.elements}; H = {HARMONICS}, EO = {ENGINE_ORDER}, N = {SECTORS}")
    curve(cb, force(cb, tip_cb), "exact", engine_order=ENGINE_ORDER, points=3)  # compile the kernels first

    r_fe, wall, cpu = curve(fe, force(fe, tip_fe), "modal", modes=10, engine_order=ENGINE_ORDER)
    w, a = r_fe.peak(tip_fe)
    print(f"1. FE sector, modal (10 modes per diameter): {r_fe.points} points in {wall:.2f} s "
          f"(CPU {cpu:.2f} s); peak {a * 1e6:.3f} µm at {w:.0f} rad/s; reduction error {r_fe.reduction_error:.1e}")

    r_cb, wall_cb, cpu_cb = curve(cb, force(cb, tip_cb), "exact", engine_order=ENGINE_ORDER)
    w_cb, a_cb = r_cb.peak(tip_cb)
    print(f"2. Craig-Bampton sector ({cb.ndof} DOFs), exact: {r_cb.points} points in {wall_cb:.2f} s "
          f"(CPU {cpu_cb:.2f} s); peak {a_cb * 1e6:.3f} µm at {w_cb:.0f} rad/s "
          f"({a_cb / a - 1:+.1e} from the FE sector's)")

    K = args.disk_points
    whole = cb.assembled()
    wave = cb.travelling_wave(force(cb, tip_cb), ENGINE_ORDER)
    r_disk, wall_disk, cpu_disk = curve(whole, wave, "exact", points=K)
    reached = float(r_disk.omega[-1])
    r_k, wall_k, cpu_k = curve(cb, force(cb, tip_cb), "exact", engine_order=ENGINE_ORDER, omega=(RANGE[0], reached))
    check = frequency_point(cb, force(cb, tip_cb), reached, harmonics=HARMONICS, engine_order=ENGINE_ORDER)
    tip = r_disk.dof_coefficients(tip_cb)[-1]
    diff = np.abs(check.dof_coefficients(tip_cb)[0] - tip).max() / np.abs(tip).max()
    print(f"3. whole disk ({whole.ndof} DOFs, {len(whole.contacts)} contacts), exact: its first {r_disk.points} "
          f"points, {RANGE[0]:.0f} to {reached:.0f} rad/s, in {wall_disk:.2f} s (CPU {cpu_disk:.2f} s); the "
          f"sector's curve over the same range: {r_k.points} points in {wall_k:.3f} s (CPU {cpu_k:.3f} s); "
          f"the tips at {reached:.0f} rad/s agree to {diff:.1e}")
    print(f"   speed-up, measured over the same stretch of the curve: {wall_disk / wall_k:.0f}x "
          f"(CPU {cpu_disk / cpu_k:.0f}x)")
    rows = [["1. FE sector, modal (10 modes per diameter)", ndof + 3, r_fe.points, RANGE[1], wall, cpu],
            ["2. Craig-Bampton sector, exact", cb.ndof, r_cb.points, RANGE[1], wall_cb, cpu_cb],
            [f"3. whole disk of 2., exact, first {r_disk.points} points", whole.ndof, r_disk.points, reached,
             wall_disk, cpu_disk],
            ["2. over the same stretch as 3.", cb.ndof, r_k.points, reached, wall_k, cpu_k]]
    name = "bench_cyclic" + ("_quick" if args.quick else "")
    figures = {"description": f"A bladed disk of {SECTORS} blades with under-platform dampers, engine order "
                              f"{ENGINE_ORDER}, H = {HARMONICS}: forced-response curves from {RANGE[0]:.0f} rad/s "
                              "of one cyclic sector against the whole assembled disk (the baseline, same run, the "
                              "same Craig-Bampton blades, the disk's first points only); speed-up = the disk's "
                              "time / the sector's over the same stretch of frequencies.",
               "command": "python benchmarks/bench_cyclic.py" + (" --quick" if args.quick else "")
                          + (f" --disk-points {args.disk_points}" if args.disk_points != (4 if args.quick else 6)
                             else ""),
               "sizes": f"blade of {ndof} DOFs (asked for {dofs}), {len(fe.contacts)} contacts of J = "
                        f"{fe.contacts[0].model.elements} per sector, Craig-Bampton sector of {cb.ndof} DOFs, "
                        f"disk of {whole.ndof} DOFs",
               "tables": [{"caption": "curves (wall and CPU time, s)",
                           "columns": ["curve", "DOFs", "points", "to (rad/s)", "wall (s)", "CPU (s)"],
                           "rows": rows},
                          {"caption": "speed-up of the sector over the whole disk, same stretch, and agreement",
                           "columns": ["wall ratio", "CPU ratio", "tips' difference at the last point",
                                       "peak, FE sector (µm)", "peak, Craig-Bampton sector (µm)",
                                       "modal reduction error"],
                           "rows": [[wall_disk / wall_k, cpu_disk / cpu_k, float(diff), a * 1e6, a_cb * 1e6,
                                     float(r_fe.reduction_error)]]}]}
    print(f"results: {save_results(name, figures)}")


if __name__ == "__main__":
    main()
