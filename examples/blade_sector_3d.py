"""A 3D blade sector with an under-platform damper: exported as Nastran DMIG, read back, reduced, spun up.
=======================================================================================================

What an engineer does with a commercial code's matrices, end to end, with the model meshed here:

1. **Mesh and assemble** one blade of a 24-blade disk in 3D with scikit-fem (trilinear hexahedra; nickel
   alloy, E = 200 GPa, nu = 0.3, 8190 kg/m^3): a 8 mm x 12 mm shank on the rim (radius 100 mm), a
   24 mm x 3 mm platform, a 3 mm thick, 40 mm tall airfoil, all 10 mm deep along the disk's axis (z).
   The sector lies in the global Cartesian frame, turned so that the gap between this blade's platform
   and the next one's is on the +y axis (the next blade is this one turned by 2 pi / 24 about z).
2. **Prestress at speed**: the centrifugal body force ``rho Omega^2 r`` at 10 000 rpm solved statically
   (root clamped), its stresses give the geometric (stress-stiffening) matrix; with the spin softening
   ``-Omega^2 M`` on the in-plane DOFs, ``K(Omega) = K0 + Omega^2 K1``.
3. **Export** ``MAAX``, ``KAAX0`` (at rest) and ``KAAXW`` (at 10 000 rpm) as Nastran DMIG entries with
   pyNastran's writer (a punch file ``blade_sector.pch``, grid and component per row), as a Nastran
   run would punch them.
4. **Read back** with ``microslip.fe.read_matrices`` (the DOF map comes from the file), **reduce** by
   Craig--Bampton at the operating speed onto the damper's platform nodes (x, y) and the tip (x) plus
   fixed-interface modes, and **assemble cyclically in the Cartesian frame**
   (``CyclicStructure(frame="cartesian")``): the next blade's platform DOFs are the global components
   turned by 2 pi / 24.
5. A **curved-flat under-platform damper** (5 g) between this blade's platform (flat face, two contacts,
   a rounded flat punch by MDR) and the next blade's (curved face, one contact), faces inclined at 40
   degrees, mu = 0.5, laws tuned with 8 elements; its centrifugal load ``m r Omega^2`` follows the speed
   (``SpeedModel``).
6. **Forced response** under an engine-order 3 travelling wave at the tips (0.2 N), and the **damper
   design curve** (peak tip response against the damper's load) at the operating speed.

Run ``python examples/blade_sector_3d.py [--out DIR] [--quick]`` (600 DOFs, six loads: about 30 s of
computing; ``--quick``: 270 DOFs and two loads, about 15 s). It writes ``blade_sector_3d.png`` and
``blade_sector.pch`` into ``DIR`` (default: ``./microslip-examples``).
"""

from __future__ import annotations

import time
import warnings
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import scipy.sparse as sp

from microslip import Sphere, mdr, tune
from microslip.fe import natural_frequencies, read_matrices
from microslip.frequency import (CyclicStructure, SpeedModel, StepControl, Structure, UnderPlatformDamper,
                                 UnderResolvedWarning, craig_bampton, damper_design_curve, frequency_response)
from microslip.reference.profiles import RoundedPunch

SECTORS, ENGINE_ORDER = 24, 3
RIM = 0.100  # m: the disk's rim radius, where the shank is clamped
E, NU, RHO = 200e9, 0.3, 8190.0  # nickel alloy
SPEED = 10000 * 2 * np.pi / 60  # rad/s: the operating speed, 10 000 rpm
TIP_FORCE = 0.2  # N, along x at every blade tip
PAIR = dict(E=200e9, nu=0.3, E2=225e9, nu2=0.29, mu=0.5)  # blade on damper (cobalt alloy)
TUNING_LOAD = 1000.0  # N
ANGLE = np.radians(40.0)  # the faces' normals from the radial direction
DAMPER_MASS, DAMPER_INERTIA = 0.005, 2e-8  # kg, kg m^2
LOADS = [100.0, 200.0, 400.0, 800.0, 1600.0, 3200.0]  # N: damper loads of the design curve
QUICK_LOADS = [100.0, 800.0]
MM = 1e-3


def mesh(quick: bool):
    """The blade's hexahedral mesh in the global frame (m), turned by -pi / SECTORS about z."""
    from skfem import MeshHex

    x = np.array([-12, -8, -4, -1.5, 1.5, 4, 8, 12]) * MM  # platform edges, shank, airfoil faces
    y = RIM + np.array([0, 6, 12, 15, 25, 35, 45, 55] if quick else
                       [0, 4, 8, 12, 13.5, 15, 20, 25, 30, 35, 40, 45, 50, 55]) * MM
    z = np.linspace(0.0, 10 * MM, 3 if quick else 4)
    m = MeshHex.init_tensor(x, y, z)
    c = m.p[:, m.t].mean(axis=1)
    height, side = c[1] - RIM, np.abs(c[0])
    blade = (((height < 12 * MM) & (side < 4 * MM)) | ((height > 12 * MM) & (height < 15 * MM))
             | ((height > 15 * MM) & (side < 1.5 * MM)))
    m = m.remove_elements(np.flatnonzero(~blade))
    turn = -np.pi / SECTORS
    rot = np.array([[np.cos(turn), -np.sin(turn), 0], [np.sin(turn), np.cos(turn), 0], [0, 0, 1]])
    return MeshHex(rot @ m.p, m.t), rot


def assemble(m):
    """``(M, K0, K1, basis)``: mass, stiffness at rest and its change per Omega^2 (stress stiffening, spin
    softening), every node's x, y, z (skfem's vector numbering)."""
    from skfem import Basis, BilinearForm, ElementHex1, ElementVector, LinearForm, condense, solve
    from skfem.helpers import ddot, dot, grad, mul, sym_grad, trace
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    basis = Basis(m, ElementVector(ElementHex1()))
    lam, mu = lame_parameters(E, NU)
    K0 = linear_elasticity(lam, mu).assemble(basis)

    @BilinearForm
    def mass(u, v, w):
        return RHO * dot(u, v)

    @BilinearForm
    def in_plane_mass(u, v, w):  # spin softening acts on the motion across the axis
        return RHO * (u[0] * v[0] + u[1] * v[1])

    @LinearForm
    def centrifugal(v, w):  # rho r per unit Omega^2, radially out from the z axis
        return RHO * (w.x[0] * v[0] + w.x[1] * v[1])

    M = mass.assemble(basis)
    root = basis.get_dofs(lambda p: np.hypot(p[0], p[1]) < RIM + 1e-9).all()
    u = solve(*condense(K0, centrifugal.assemble(basis), D=root))  # the static displacement per Omega^2

    @BilinearForm
    def geometric(du, v, w):  # sigma_ij d_i du_k d_j v_k, sigma from the centrifugal state
        eps = sym_grad(w["u"])
        sigma = 2 * mu * eps + lam * trace(eps) * np.eye(3)[:, :, None, None]
        return ddot(mul(grad(du), sigma), grad(v))

    K1 = geometric.assemble(basis, u=basis.interpolate(u)) - in_plane_mass.assemble(basis)
    free = np.setdiff1d(np.arange(basis.N), root)
    return M, K0, K1, basis, free


def export(path: Path, M, K0, K1, basis, free):
    """M, K(0) and K(SPEED) of the free DOFs as Nastran DMIG entries (pyNastran's writer), lower triangles."""
    from pyNastran.bdf.bdf import BDF

    dofs = basis.nodal_dofs  # (3, nodes): the DOF of each node's x, y, z
    grid = np.empty((basis.N, 2), dtype=int)
    grid[dofs.T.ravel(), 0] = np.repeat(np.arange(dofs.shape[1]) + 1, 3)  # grid ids from 1
    grid[dofs.T.ravel(), 1] = np.tile([1, 2, 3], dofs.shape[1])
    model = BDF(debug=None)
    for name, A in (("MAAX", M), ("KAAX0", K0), ("KAAXW", K0 + SPEED ** 2 * K1)):
        low = sp.tril(sp.csr_matrix(A)[free][:, free]).tocoo()
        g = grid[free]
        model.add_dmig(name, 6, 2, 0, 0, 0, [tuple(g[j]) for j in low.col], [tuple(g[i]) for i in low.row],
                       Real=low.data)
    path.parent.mkdir(parents=True, exist_ok=True)
    model.write_bdf(str(path), size=16, is_double=True, enddata=False)
    return {(int(n), int(c)): k for k, (n, c) in enumerate(grid)}


def node_near(m, local_xyz, rot) -> int:
    """The grid id (from 1) of the node nearest to a point given in the blade's own frame (m)."""
    target = rot @ np.asarray(local_xyz)
    return int(np.argmin(np.linalg.norm(m.p.T - target, axis=1))) + 1


def contact_laws(elements: int = 8):
    """``(flat, curved)``: the flat face's law (a rounded punch, MDR) and the curved face's, tuned at 1000 N."""
    punch = mdr(Sphere(radius=5e-3, **PAIR), max_load=TUNING_LOAD, elements=2000, profile=RoundedPunch(1e-3, 5e-3))
    return (tune(punch.as_reference(), TUNING_LOAD, elements=elements),
            tune(Sphere(radius=10e-3, **PAIR), TUNING_LOAD, elements=elements))


def damper(s: CyclicStructure, laws, load: float, centre, points) -> UnderPlatformDamper:
    """The curved-flat damper: flat face on this blade's platform (reduced DOFs 0-3), curved face on the next
    blade's (its DOFs 4, 5); ``points`` (3, 2) are the contacts' positions, ``centre`` its centre of mass (m)."""
    flat, curved = laws
    d = UnderPlatformDamper(DAMPER_MASS, DAMPER_INERTIA, centrifugal_load=load, damping=100.0)
    rel = np.asarray(points) - np.asarray(centre)
    d.add_interface(flat, points=rel[:2], angle=np.pi / 2 - ANGLE, platform=[{"x": 0, "y": 1}, {"x": 2, "y": 3}],
                    name="flat")
    d.add_interface(curved, points=rel[2:], angle=np.pi / 2 + ANGLE, platform={"x": s.next(4), "y": s.next(5)},
                    name="curved")
    return d


def main(out=Path("microslip-examples"), quick: bool = False) -> dict:
    start = time.perf_counter()
    out = Path(out)
    m, rot = mesh(quick)
    M, K0, K1, basis, free = assemble(m)
    punch = out / "blade_sector.pch"
    export(punch, M, K0, K1, basis, free)
    exported = time.perf_counter() - start

    # -- what a user of a commercial code does from here: read, reduce, assemble, spin ------------------------------
    at_rest = read_matrices(punch, names={"M": "MAAX", "K": "KAAX0"})
    at_speed = read_matrices(punch, names={"M": "MAAX", "K": "KAAXW"})
    dofs = at_rest.dof_map
    under = RIM + 12 * MM  # the platform's underside
    flat = [node_near(m, (-12 * MM, under, 5 * MM), rot), node_near(m, (-8 * MM, under, 5 * MM), rot)]
    curved = node_near(m, (12 * MM, under, 5 * MM), rot)  # on the next blade, this node turned by 2 pi / 24
    tip = node_near(m, (1.5 * MM, RIM + 55 * MM, 5 * MM), rot)
    keep = [dofs.index(f"{n}:{c}") for n in (*flat, curved) for c in "xy"] + [dofs.index(f"{tip}:x")]
    C = 2e-7 * at_rest.K  # stiffness-proportional damping
    # reduced at the operating speed; the sector's symmetry is given to the reduced model (SpeedModel's cyclic)
    cb = craig_bampton(Structure(at_rest.M, C, at_speed.K, dof_map=dofs), keep, modes=10 if quick else 20)
    T = cb.recovery
    stiffness = [T.T @ (at_rest.K @ T), T.T @ (at_speed.K @ T)]
    stiffness = [(A + A.T) / 2 for A in stiffness]
    reduced = cb.structure
    cyclic = dict(sectors=SECTORS, left=[], right=[], frame="cartesian", coordinates=np.zeros((2, 0, 3)),
                  nodes=[(0, 1), (2, 3), (4, 5)])  # the platform nodes' x, y turn with the sector
    xyz = {n: m.p[:, n - 1] for n in (*flat, curved)}
    turned = np.array([[np.cos(2 * np.pi / SECTORS), -np.sin(2 * np.pi / SECTORS)],
                       [np.sin(2 * np.pi / SECTORS), np.cos(2 * np.pi / SECTORS)]]) @ xyz[curved][:2]
    points = [xyz[flat[0]][:2], xyz[flat[1]][:2], turned]  # the curved face's node on the next blade
    centre = (0.0, float(np.mean([p[1] for p in points])) - 4 * MM)
    laws = contact_laws()
    d = damper(CyclicStructure(reduced.M, None, reduced.K, **cyclic), laws, 1.0, centre, points)
    model = SpeedModel(reduced.M, reduced.C, stiffness, [0.0, SPEED], damper=d, radius=float(np.hypot(*centre)),
                       cyclic=cyclic)
    bare = model.at(SPEED, damper=False)
    w = 2 * np.pi * natural_frequencies(bare.M, bare.K, 2)  # rad/s
    w_rest = 2 * np.pi * natural_frequencies(bare.M, stiffness[0], 1)[0]
    band = (0.85 * w[0], 1.6 * w[0])
    force = np.zeros(bare.ndof)
    force[6] = TIP_FORCE
    load = d.mass * model.radius * SPEED ** 2
    loads = QUICK_LOADS if quick else LOADS
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnderResolvedWarning)
        spun = model.at(SPEED)
        response = frequency_response(spun, np.append(force, np.zeros(3)), band, harmonics=3,
                                      engine_order=ENGINE_ORDER, control=StepControl(max_points=10000))
        curve = damper_design_curve(bare, damper(bare, laws, loads[0], centre, points), loads, force, band, dof=6,
                                    harmonics=3, engine_order=ENGINE_ORDER, control=StepControl(max_points=10000))
        undamped = frequency_response(bare, force, band, harmonics=1, engine_order=ENGINE_ORDER)
    elapsed = time.perf_counter() - start

    out.mkdir(parents=True, exist_ok=True)
    figure = out / "blade_sector_3d.png"
    fig, (ax, ax_d) = plt.subplots(1, 2, figsize=(12, 4.6), gridspec_kw={"width_ratios": [1.5, 1]})
    hz = 1 / (2 * np.pi)
    ax.semilogy(response.omega * hz, response.amplitude(6) * 1e6, color="C0",
                label=f"damper at 10 000 rpm ({load:.0f} N)")
    ax.semilogy(undamped.omega * hz, undamped.amplitude(6) * 1e6, "--", color="0.4", label="no damper")
    ax.set_xlabel("excitation frequency f (Hz)")
    ax.set_ylabel("blade tip: max |x - x0| over a period (µm)")
    ax.set_title(f"3D sector read from DMIG, {SECTORS} blades, EO {ENGINE_ORDER}, {TIP_FORCE:g} N at each tip",
                 fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ax_d.plot(curve.loads, curve.peak_amplitude * 1e6, "o-", color="k")
    ax_d.axvline(load, ls=":", color="C0", label="the load at 10 000 rpm")
    ax_d.set_xscale("log")
    ax_d.set_xlabel("damper's centrifugal load (N)")
    ax_d.set_ylabel("peak of the blade tip (µm)")
    ax_d.set_title("Design curve at 10 000 rpm", fontsize=10)
    ax_d.grid(True, which="both", alpha=0.3)
    ax_d.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(figure, dpi=120)
    plt.close(fig)
    print(f"mesh: {m.p.shape[1]} nodes, {m.t.shape[1]} hexahedra, {free.size} free DOFs (root clamped)")
    print(f"exported {len(dofs)} DOFs to {punch} in {exported:.1f} s; read back {len(dofs)} DOFs ({dofs.names[0]} ...)")
    print(f"first mode at rest {w_rest * hz:.0f} Hz, at 10 000 rpm {w[0] * hz:.0f} Hz (stress stiffening and spin "
          f"softening); reduced to {reduced.ndof} DOFs")
    print(f"damper load at 10 000 rpm: {load:.0f} N; peak {response.peak(6)[1] * 1e6:.4g} µm at "
          f"{response.peak(6)[0] * hz:.1f} Hz; without damper {undamped.peak(6)[1] * 1e6:.4g} µm")
    print("load (N)   peak (µm)   at (Hz)")
    for L, a, f in zip(curve.loads, curve.peak_amplitude, curve.peak_frequency):
        print(f"{L:8.4g}   {a * 1e6:9.4g}   {f * hz:7.1f}")
    print(f"{elapsed:.1f} s; wrote {figure}")
    return {"dofs": dofs, "at_rest": at_rest, "at_speed": at_speed, "M": M, "K0": K0, "K1": K1, "free": free,
            "basis": basis, "model": model, "response": response, "curve": curve, "no_damper": undamped,
            "frequencies": (w_rest, w[0]), "load": load, "punch": punch}


if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(description="A 3D blade sector with an under-platform damper, exported as "
                                                 "Nastran DMIG, read back, reduced, spun up (writes "
                                                 "blade_sector_3d.png and blade_sector.pch).")
    parser.add_argument("--out", default="microslip-examples", help="folder to write into")
    parser.add_argument("--quick", action="store_true", help="a coarse mesh and two damper loads")
    args = parser.parse_args()
    main(Path(args.out), quick=args.quick)
