"""Energy per cycle on orbits of the contact plane: tuned arrays against the fine MDR reference (sphere).

For the paper's sphere (d = 10 mm, steel, mu = 0.4) tuned at 37.5 N, the energy dissipated per
steady cycle on a circle, an ellipse (semi-minor axis half the semi-major, major axis at 30°) and,
for comparison, a straight line of the same semi-major amplitude (the one-direction loop), by

* the paper's array (J = 4, even force points),
* the array with the stored optimised points (J = 11, tuned for 7.5-37.5 N),
* the MDR reference with 2000 elements, each an isotropic Jenkins element on the plane.

Along a straight line the MDR is the exact continuous contact (Cattaneo-Mindlin, Mindlin-Deresiewicz);
on a curved orbit the MDR applied element by element on the plane is the usual approximation of it
(the continuous contact's tractions need not point along each spring's own stretch), so the columns
below compare the arrays with that approximation, not with an exact solution.

Sizes are multiples of the gross-slip displacement t_gs at the orbit's lowest load. Loads: constant
37.5 N and 15 N, and N = 22.5 + 15 sin(tau + 90°) N. Each orbit starts with a turn spiralling out
of the centre and is repeated until the energy of a cycle changes by less than 1e-6 of it (at most
80 cycles; on the plane an element slipping on a near-circular orbit settles geometrically, not in
a finite number of cycles). The reference's own errors are printed too: 1000 against 2000
elements, and the step (1440 against 2880 samples per cycle: the march is first order in the step
on the plane).

Run::

    python scripts/plane_energy.py            # about 1 minute on 2 shared cores
    python scripts/plane_energy.py --quick    # two orbits, fewer samples (the test runs this)
"""

from __future__ import annotations

import argparse

import numpy as np

from microslip import Sphere, mdr, paths, tune

SPHERE = Sphere.paper()
N_TOT = 37.5
LOADS = [(37.5, 0.0), (15.0, 0.0), (22.5, 15.0)]  # (N_m, N_a), N
SIZES = (0.25, 0.5, 1.0, 2.0)
SHAPES = ("circle", "ellipse", "line")


def orbit(shape, size, Nm, Na, steps_per_cycle):
    """One cycle of the orbit (with its lead-in for circles and ellipses), N = N_m + N_a sin(tau + 90°)."""
    common = dict(cycles=1, steps_per_cycle=steps_per_cycle)
    if shape == "circle":
        return paths.circle(SPHERE, size, Nm, Na, 90.0, **common)
    if shape == "ellipse":
        return paths.ellipse(SPHERE, size, 0.5 * size, Nm, Na, 90.0, angle_deg=30.0, **common)
    return paths.line(SPHERE, size, Nm, Na, 90.0, angle_deg=30.0, **common)


def energy_per_cycle(model, path, rtol=1e-6, max_cycles=80):
    """Friction work of the steady cycle (J) and the relative change of the last cycle."""
    r = model.simulate(path.t, path.n, per_element=False)
    t, n = path.t[path.steady][1:], path.n[path.steady][1:]  # one cycle; its first sample closes the previous
    W = r.friction_work[path.steady][1:].sum()
    change = np.inf
    for _ in range(max_cycles):
        r = model.simulate(t, n, state=r.state, per_element=False)
        previous, W = W, r.friction_work.sum()
        change = abs(W - previous) / W if W > 0 else float(previous > 0)
        if change < rtol:
            break
    return W, change


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="two orbits, 360 samples per cycle, 400 elements")
    args = parser.parse_args(argv)
    steps = 360 if args.quick else 1440
    loads, sizes, shapes = (LOADS[:1], SIZES[2:3], SHAPES[:2]) if args.quick else (LOADS, SIZES, SHAPES)
    models = {"J = 4 (paper)": tune(SPHERE, N_TOT, elements=4),
              "J = 11 (optimised)": tune(SPHERE, N_TOT, elements=11, load_range=(7.5, N_TOT))}
    reference = mdr(SPHERE, max_load=N_TOT, elements=400 if args.quick else 2000)
    coarse = mdr(SPHERE, max_load=N_TOT, elements=200 if args.quick else 1000)
    print(f"energy per cycle on the contact plane, sphere tuned at {N_TOT} N; reference MDR with "
          f"{reference.elements} elements, {steps} samples per cycle")
    header = (f"{'load (N)':>16} {'orbit':>8} {'size':>6} {'MDR (µJ)':>9} " + " ".join(f"{m:>19}" for m in models)
              + f" {'MDR: J/2':>9} {'MDR: step/2':>11} {'settled':>8}")
    print(header)
    print("-" * len(header))
    worst = {m: {s: 0.0 for s in shapes} for m in models}
    for Nm, Na in loads:
        t_gs = float(SPHERE.gross_slip_displacement(Nm - Na))
        for x in sizes:
            for shape in shapes:
                path = orbit(shape, x * t_gs, Nm, Na, steps)
                W, change = energy_per_cycle(reference, path)
                errors = []
                for name, model in models.items():
                    Wm, c = energy_per_cycle(model, path)
                    change = max(change, c)
                    errors.append(100 * (Wm / W - 1))
                    worst[name][shape] = max(worst[name][shape], abs(errors[-1]), key=abs)
                W_coarse, _ = energy_per_cycle(coarse, path)
                W_fine, _ = energy_per_cycle(reference, orbit(shape, x * t_gs, Nm, Na, 2 * steps))
                load = f"{Nm:g}" if Na == 0 else f"{Nm:g} + {Na:g} sin"
                print(f"{load:>16} {shape:>8} {x:>4g}tg {W * 1e6:>9.4g} " + " ".join(f"{e:>18.3g}%" for e in errors)
                      + f" {100 * (W_coarse / W - 1):>8.2g}% {100 * (W_fine / W - 1):>10.2g}% {change:>8.0e}")
    print("\nlargest |energy error| against the MDR reference (%):")
    for name in models:
        print(f"  {name}: " + ", ".join(f"{shape} {worst[name][shape]:.3g}" for shape in shapes))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
