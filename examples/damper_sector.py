"""A nonlinear mode from files: a blade sector with an under-platform damper, ``microslip modes``.
=================================================================================================

The route of a user whose finite-element program wrote the sector's matrices: this script writes
the files such a user has, and ``microslip modes`` computes the mode from them with no Python.

The files, written into ``--out DIR``:

- ``M.mtx``, ``K.mtx``: the mass and stiffness matrices of one blade (Matrix Market, ``scipy.io.mmwrite``),
  the plane-stress blade of ``microslip.fe.blade`` (nickel alloy, 3 mm thick, a 16 mm shank under a
  6 mm platform; 408 DOFs by default), clamped at its root;
- ``dofs.csv``: the DOF map, one row ``node,component`` per matrix row (``DofMap.to_csv``), so the
  configuration names DOFs ``"58:x"``;
- ``flat.json``, ``curved.json``: the damper's contact laws (``MicroslipModel.save``), both tuned with
  8 elements at 1000 N: the flat face a punch with rounded edges (1 mm flat, 5 mm edge radius, by the
  method of dimensionality reduction), the curved face a 10 mm sphere; blade E = 200 GPa, nu = 0.3 on
  damper E = 225 GPa, nu = 0.29, mu = 0.5;
- ``config.toml``: 12 sectors (``[cyclic]``, the blades joined through the damper only, so no boundary
  DOFs), damping ``C = 2e-7 K`` (``rayleigh``), a curved-flat damper (5 g, 2e-8 kg m^2, damping
  100 1/s, 100 N centrifugal load) whose flat face presses on this blade's right overhang through two
  contacts and whose curved face presses on the next blade's left overhang (``"next:3:x"``), the faces'
  normals 40 degrees from the radial direction; ``[modes]``: the first mode in nodal diameter 3 from
  1e-9 to 1e-4 kg^1/2 m with harmonics 0-3.

Then::

    python examples/damper_sector.py --out sector     # writes the files above (a few seconds)
    microslip modes sector/config.toml --out sector/mode

``microslip modes`` prints the linear mode (2176.69 Hz, contacts stuck), the frequency and damping ratio at
the last amplitude and where the damping peaks (about 2.6 % near 4.8e-6 kg^1/2 m), and each contact's static
state; it writes ``modes.csv`` (frequency, damping ratio and the harmonics of the DOFs of ``[output] plot``
and ``[modes] dof`` at every amplitude, SI units), ``modes.png`` and ``report.html``/``report.md``. With
harmonics 0-3 the damper's contacts go from stuck to sliding and lifting off, and at 2.14e-5 kg^1/2 m the
mode turns back in amplitude: a fold, where ``nonlinear_modes`` ends it with an ``IncompleteCurveWarning``
naming it (214 points, the whole command about 40 s on two shared cores); the command then exits with status
1, the results up to there written (``[modes] folds = "follow"`` follows the curve beyond the fold, where
the damper's mean position drifts). With ``harmonics = 1`` the mode goes on to its fold near 6.6e-5 kg^1/2 m,
where the damper comes loose (see the nonlinear modes guide). The mode is the one ``nonlinear_modes`` computes
from the same numbers, point for point (``tests/cli/test_damper_sector_cli.py``). ``[continuation]
max_points = 250`` caps it (its other keys keep the mode's own steps, sized by the chord rule).

``--run`` runs the command from this script; ``--quick`` makes a smaller case, harmonics 0-1 over 1e-7 to
5e-6 kg^1/2 m (about 140 points, seconds; the gallery runs ``--quick --run``).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
import scipy.io

from microslip import Sphere, mdr, tune
from microslip.fe import blade
from microslip.reference.profiles import RoundedPunch

SECTORS, NODAL_DIAMETER = 12, 3
AMPLITUDE = (1e-9, 1e-4)  # kg^1/2 m
QUICK = (1e-7, 5e-6)  # kg^1/2 m: from stuck to the damper sliding, with harmonics 0-1 (the gallery)
PAIR = dict(E=200e9, nu=0.3, E2=225e9, nu2=0.29, mu=0.5)  # blade (nickel alloy) on damper (cobalt alloy)
TUNING_LOAD = 1000.0  # N
ANGLE = 40.0  # degrees: the faces' normals from the radial direction

CONFIG = """title = "Blade sector with an under-platform damper"

[structure]
M = "M.mtx"
K = "K.mtx"
rayleigh = [0.0, 2e-7]                  # C = 2e-7 s K
dof_map = "dofs.csv"                    # rows named "node:component"

[cyclic]
sectors = {sectors}
left = []                               # the blades touch only through the damper
right = []
engine_order = {diameter}

[[damper]]
mass = 0.005                            # kg
inertia = 2e-8                          # kg m^2
centrifugal_load = "100N"
damping = 100.0                         # 1/s
[[damper.interface]]                    # flat face on this blade's right overhang: two contacts
name = "flat"
model = "flat.json"
points = [[{fx0!r}, {fy0!r}], [{fx1!r}, {fy1!r}]]   # m, from the centre of mass
angle = {flat_angle:g}
platform = [{{x = "{f0}:x", y = "{f0}:y"}}, {{x = "{f1}:x", y = "{f1}:y"}}]
[[damper.interface]]                    # curved face on the next blade's left overhang
name = "curved"
model = "curved.json"
points = [[{cx!r}, {cy!r}]]
angle = {curved_angle:g}
platform = {{x = "next:{c}:x", y = "next:{c}:y"}}

[sweep]
harmonics = {harmonics}

[modes]
amplitude = [{a0:g}, {a1:g}]
nodal_diameter = {diameter}
dof = "{tip}:x"

[output]
plot = ["{tip}:x", "{f0}:x"]
"""


def contact_laws(elements: int = 8):
    """``(flat, curved)``: the flat face's law (a rounded punch, MDR) and the curved face's (a sphere)."""
    punch = mdr(Sphere(radius=5e-3, **PAIR), max_load=TUNING_LOAD, elements=2000, profile=RoundedPunch(1e-3, 5e-3))
    return (tune(punch.as_reference(), TUNING_LOAD, elements=elements),
            tune(Sphere(radius=10e-3, **PAIR), TUNING_LOAD, elements=elements))


def write_files(folder, dofs: int = 300, harmonics: int = 3, amplitude=AMPLITUDE) -> Path:
    """Write the sector's matrices, DOF map, contact laws and configuration into ``folder``.

    Parameters
    ----------
    folder : str or Path
        Where the files go (created if missing).
    dofs : int, default 300
        The blade's target size (``microslip.fe.blade``; the mesh it makes is at least 408 DOFs).
    harmonics : int, default 3
        ``[sweep] harmonics``.
    amplitude : (float, float), default (1e-9, 1e-4)
        ``[modes] amplitude``, the modal amplitude range (kg^1/2 m).

    Returns
    -------
    Path
        The configuration file, ``folder / "config.toml"``.
    """
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    b = blade(dofs, shank_width=0.016, platform_height=0.006)
    scipy.io.mmwrite(folder / "M.mtx", b.M)
    scipy.io.mmwrite(folder / "K.mtx", b.K)
    b.dof_map.to_csv(folder / "dofs.csv")
    flat, curved = contact_laws()
    flat.save(folder / "flat.json")
    curved.save(folder / "curved.json")
    right, left = b.node_sets["platform_right"], b.node_sets["platform_left"]  # outer edge first
    tilt = np.radians(ANGLE)
    mid, lift = float(4e-3 / np.tan(tilt)), float(2e-3 * np.tan(tilt))  # normals through the centre of mass
    text = CONFIG.format(sectors=SECTORS, diameter=NODAL_DIAMETER, harmonics=harmonics, a0=amplitude[0],
                         a1=amplitude[1], fx0=-6e-3, fy0=mid - lift, fx1=-2e-3, fy1=mid + lift, cx=4e-3, cy=mid,
                         flat_angle=90.0 + ANGLE, curved_angle=90.0 - ANGLE, f0=right[2], f1=right[0], c=left[1],
                         tip=b.tip_node)
    path = folder / "config.toml"
    path.write_text(text)
    return path


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description="Write a blade sector's files for microslip modes (and run it).")
    parser.add_argument("--out", default="damper_sector", help="folder of the files (default: damper_sector)")
    parser.add_argument("--dofs", type=int, default=300, help="the blade's target size (default 300: 408 DOFs)")
    parser.add_argument("--harmonics", type=int, default=3, help="[sweep] harmonics (default 3)")
    parser.add_argument("--quick", action="store_true", help=f"harmonics 1 over {QUICK[0]:g} to {QUICK[1]:g} kg^1/2 m")
    parser.add_argument("--run", action="store_true", help="then run: microslip modes OUT/config.toml --out OUT/mode")
    args = parser.parse_args(argv)
    config = write_files(args.out, args.dofs, 1 if args.quick else args.harmonics, QUICK if args.quick else AMPLITUDE)
    mode = Path(args.out) / "mode"
    print(f"wrote {config} and the files it names; run: microslip modes {config} --out {mode}")
    if not args.run:
        return 0
    from microslip.cli import main as microslip

    return microslip(["modes", str(config), "--out", str(mode)])


if __name__ == "__main__":
    status = main()
    if status:  # the command's exit status (1: the mode stopped early, its results written)
        sys.exit(status)
