"""Side by side with tmdsimpy (MIT, not on PyPI): a contact's AFT and a nonlinear mode, same inputs, same run.

Run:  TMDSIMPY_PATH=/path/to/tmdsimpy OPENBLAS_NUM_THREADS=1 python benchmarks/bench_tmdsimpy.py
      ... bench_tmdsimpy.py --contacts 40            (the blade with 40 contacts: about two minutes)

tmdsimpy (Porter et al., https://github.com/tmd-lab/tmdsimpy) is imported from the local copy that
``TMDSIMPY_PATH`` names (its dependency jax installed); without it the benchmark times microslip alone and
says why the comparison was skipped.

(a) AFT with its Jacobian of one contact moving in its tangential direction and its normal direction
(harmonics 0-7, 128 samples): the paper's sphere tuned with J = 8 elements at 37.5 N, its normal approach
varying by +-20 % around the static one (the outer elements open and close) and its tangential motion
``a cos + 0.1 a cos 2 + 0.3 a sin 2`` with ``a`` = 0.6 µm (microslip) and 3 µm (gross slip). microslip: the
plane AFT (``aft_plane``'s compiled kernel as harmonic balance calls it, and the public wrapper), the motion
along a line at 30 degrees on the contact plane. tmdsimpy: one ``ElasticDryFriction2D`` per element (its
documented use: its JAX derivatives are dense, so one object per slider), each with that element's
``kt``, ``kn``, ``mu`` and its gap as ``meso_gap``, sliders starting at 0 (``u0 = 0``), the sum of their
``aft`` calls (forces and Jacobians). Both march the same return mapping from the same state, so the
forces must agree to rounding (checked to 1e-10 of the largest force, the Jacobians to 1e-8 of the largest
derivative).

(b) A nonlinear mode (extended periodic motion concept) of a Craig-Bampton-reduced scikit-fem blade
(``microslip.fe.blade``, about 10^3 DOFs, ``C = 2e-7 K``, its first bending mode) with a Jenkins contact
along x at each of ``--contacts`` platform nodes, kept physical, plus ``--modes`` fixed-interface modes:
both codes get the same reduced ``M``, ``C``, ``K``. Each contact is a Jenkins element at a fixed normal
load: microslip's array with one element (``kt`` the sum of the sphere's tuned stiffnesses, ``mu`` = 0.4,
the normal approach held at 37.5 N), tmdsimpy's ``VectorJenkins`` with the same ``kt`` and slip force
``mu N`` = 15 N. Harmonics 0-3, 128 samples per period, modal amplitude over three decades from 1e-7.
microslip: ``nonlinear_modes`` with its defaults (``reduction="auto"``, the continuation). tmdsimpy: its
``VibrationSystem.epmc_res`` and ``Continuation`` set up as its Brake-Reuss beam example (linear mode of
the stuck structure as the start, harmonic-wise conditioning, orthogonal corrector, ``ds`` 0.08 to 0.175,
its ``NonlinearSolver``), except ``DynamicCtoP`` off: with it on, the continuation turns back at the onset
of slip on this structure and does not reach the end of the range.

Amplitudes. tmdsimpy's ``10**la`` is the mass norm of the first harmonic, ``sqrt(c1' M c1 + s1' M s1)``;
microslip's modal amplitude ``a = phi' M z_1`` is its projection onto the stuck linear mode ``phi``, so
tmdsimpy's amplitude of a microslip point is ``a sqrt(modal_mass)`` (``NonlinearModes.modal_mass =
z_1^H M z_1 / a^2``). The two continuations step through different amplitudes, so the agreement is checked
at microslip's points: tmdsimpy's EPMC equations are solved at the matching ``la`` (its solver, tolerance
1e-13, started from its nearest continuation point, not timed), and frequency and damping ratio
``xi / (2 omega)`` (the same definition in both) are compared relatively (target 1e-4).

Times are wall times on a shared machine: the best of three runs for microslip, of ``--repeat`` (default 1)
for tmdsimpy; the ratios are what to compare. The figures are saved to ``benchmarks/results/bench_tmdsimpy.json``
(``_common.save_results``; without tmdsimpy, microslip's times alone and the reason the comparison was skipped).
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
from pathlib import Path

import numpy as np
import scipy.linalg as sla

from microslip import MicroslipModel, Sphere, Structure, nonlinear_modes, tune
from microslip.kernels import aft as _aft, aft_plane as _aft_plane
from microslip.frequency import aft_plane, craig_bampton

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import best_of, save_results  # noqa: E402
from bench_aft import best_time  # noqa: E402  (the same timing as the other AFT benchmarks)

LOAD = 37.5  # N, each contact's normal load
AFT_H, AFT_SAMPLES, AFT_ELEMENTS = 7, 128, 8
ANGLE = 30.0  # degrees: the line of the contact plane the tangential motion follows in microslip
MODE_H, MODE_SAMPLES = 3, 128
AMPLITUDE = (1e-7, 1e-4)  # kg^1/2 m
TARGET = 20.0  # times faster than tmdsimpy, AFT and mode
AGREEMENT = 1e-4  # relative, frequency and damping ratio
PEER_MODULES = ("tmdsimpy.jax.nlforces.elastic_dry_fric_2d", "tmdsimpy.nlforces.vector_jenkins",
                "tmdsimpy.vibration_system", "tmdsimpy.solvers", "tmdsimpy.continuation",
                "tmdsimpy.utils.harmonic")


def load_tmdsimpy():
    """``(modules, None)`` with tmdsimpy's modules by short name, or ``(None, why not)``."""
    root = os.environ.get("TMDSIMPY_PATH")
    if not root:
        return None, ("TMDSIMPY_PATH is not set (set it to a local copy of tmdsimpy, "
                      "https://github.com/tmd-lab/tmdsimpy, with jax installed)")
    sys.path.insert(0, root)
    try:
        return {name.rsplit(".", 1)[1]: importlib.import_module(name) for name in PEER_MODULES}, None
    except Exception as exc:  # tmdsimpy's own imports (jax) may fail too
        return None, f"tmdsimpy from TMDSIMPY_PATH={root!r} cannot be imported ({type(exc).__name__}: {exc})"
    finally:
        sys.path.remove(root)


# -- (a) the AFT ----------------------------------------------------------------------------------
def aft_cases():
    """``(name, model, line, normal)``: coefficients of the tangential motion along the line and of the normal."""
    sphere = Sphere.paper()
    model = tune(sphere, LOAD, elements=AFT_ELEMENTS)
    n0 = float(sphere.approach(LOAD))
    nb = 2 * AFT_H + 1
    xn = np.zeros(nb)
    xn[0], xn[1] = n0, 0.2 * n0
    out = []
    for name, a in (("microslip, 0.6 µm", 0.6e-6), ("gross slip, 3 µm", 3e-6)):
        line = np.zeros(nb)
        line[1], line[3], line[4] = a, 0.1 * a, 0.3 * a
        out.append((name, model, line, xn))
    return out


def peer_aft(peer, model, line, xn):
    """``(run, elements)``: a call summing tmdsimpy's element AFTs (forces, Jacobian), laid out as its DOFs (t, n)."""
    friction = peer["elastic_dry_fric_2d"].ElasticDryFriction2D
    elements = [friction(np.eye(2), np.eye(2), float(model.kt[i]), float(model.kn[i]), model.mu, u0=0.0,
                         meso_gap=float(model.gaps[i])) for i in range(model.kt.size)]
    U = np.column_stack([line, xn]).reshape(-1)  # tmdsimpy's layout: every DOF of a harmonic component together
    h = np.arange(AFT_H + 1)

    def run():
        F, J = 0.0, 0.0
        for element in elements:
            f, j, _ = element.aft(U, 1.0, h, Nt=AFT_SAMPLES)
            F, J = F + np.asarray(f), J + np.asarray(j)
        return F, J

    return run


def compare_aft(peer) -> list:
    tables = _aft.tables(AFT_H, AFT_SAMPLES)
    PT = _aft_plane.sweep_tables(AFT_H, AFT_SAMPLES)
    e = np.array([np.cos(np.radians(ANGLE)), np.sin(np.radians(ANGLE))])
    nb = 2 * AFT_H + 1
    print(f"(a) AFT with Jacobian of one contact, J = {AFT_ELEMENTS}, harmonics 0-{AFT_H}, {AFT_SAMPLES} samples "
          f"(best of 7, microseconds per call)")
    rows = []
    for name, model, line, xn in aft_cases():
        t = np.outer(e, line)
        t1, t2 = np.ascontiguousarray(t[0]), np.ascontiguousarray(t[1])
        F, Jac = np.empty((3, nb)), np.empty((3, 3, nb, nb))
        t_kernel = best_time(lambda: _aft_plane._aft_plane(model.kt, model.kn, model.gaps, model.mu, t1, t2, xn,
                                                           *tables, PT, 1000, F, Jac))
        t_public = best_time(lambda: aft_plane(model, t, xn, samples=AFT_SAMPLES))
        text = f"  {name:18s} microslip kernel {t_kernel * 1e6:6.1f}, public aft_plane() {t_public * 1e6:6.1f}"
        if peer is None:
            print(text)
            rows.append([name, t_kernel * 1e6, t_public * 1e6])
            continue
        run = peer_aft(peer, model, line, xn)
        t_peer = best_time(run, repeat=3)
        Fp, Jp = run()
        r = aft_plane(model, t, xn, samples=AFT_SAMPLES)
        T = e @ r.T  # the tangential force along the line
        scale = max(np.abs(T).max(), np.abs(r.N).max())
        force_error = max(np.abs(Fp[0::2] - T).max(), np.abs(Fp[1::2] - r.N).max()) / scale
        ours = np.zeros((2 * nb, 2 * nb))  # microslip's Jacobian along the line, in tmdsimpy's layout
        ours[0::2, 0::2] = np.einsum("a,abij,b->ij", e, r.dT_dt, e)
        ours[0::2, 1::2] = np.einsum("a,aij->ij", e, r.dT_dn)
        ours[1::2, 1::2] = r.dN_dn
        jacobian_error = np.abs(Jp - ours).max() / np.abs(ours).max()
        assert force_error < 1e-10 and jacobian_error < 1e-8, (name, force_error, jacobian_error)
        rows.append([name, t_kernel * 1e6, t_public * 1e6, t_peer * 1e6, t_peer / t_kernel, force_error,
                     jacobian_error])
        print(f"{text}, tmdsimpy {t_peer * 1e6:8.0f}: {t_peer / t_kernel:5.0f}x (target {TARGET:.0f}x: "
              f"{'met' if t_peer / t_kernel >= TARGET else 'MISSED'}); forces agree to {force_error:.1e}, "
              f"Jacobians to {jacobian_error:.1e} of the largest")
    return rows


# -- (b) the nonlinear mode -----------------------------------------------------------------------
def jenkins_blade(dofs: int, contacts: int, modes: int):
    """``(reduced structure, kt, slip force)``: the Craig-Bampton blade with Jenkins contacts (module docstring)."""
    from microslip.fe import blade

    kt = float(tune(Sphere.paper(), LOAD, elements=8).kt.sum())
    kn, mu = 1e9, 0.4  # kn only sets the approach that carries LOAD: the normal load is held
    jenkins = MicroslipModel([kt], [kn], [0.0], mu)
    b = blade(dofs, contact_nodes=contacts // 2)
    full = Structure(b.M, 2e-7 * b.K, b.K, dof_map=b.dof_map)
    for node in b.platform_nodes:
        full.add_contact(jenkins, tangential=f"{node}:x", approach=LOAD / kn)
    keep = [full.dof_index(f"{node}:x") for node in b.platform_nodes]
    return craig_bampton(full, keep, modes).structure, full.ndof, kt, mu * LOAD


class PeerMode:
    """tmdsimpy's EPMC of the same reduced structure: its equations, start and continuation."""

    def __init__(self, peer, structure: Structure, kt: float, slip: float):
        self.hutils = peer["harmonic"]
        M, C, K = (np.asarray(structure.M), np.asarray(structure.C), np.asarray(structure.K))
        self.n = n = M.shape[0]
        self.system = peer["vibration_system"].VibrationSystem(M, K, C=C)
        stuck = K.copy()
        for contact in structure.contacts:
            b = np.asarray(contact.tangential, dtype=float)
            Q = b.reshape(1, n)
            self.system.add_nl_force(peer["vector_jenkins"].VectorJenkins(Q, Q.T.copy(), kt, slip))
            stuck += kt * np.outer(b, b)
        lam, vectors = sla.eigh(stuck, M, subset_by_index=[0, 0])
        phi = vectors[:, 0] / np.sqrt(vectors[:, 0] @ M @ vectors[:, 0])
        self.h = np.arange(MODE_H + 1)
        nhc = self.hutils.Nhc(self.h)
        self.Fl = np.zeros(nhc * n)  # no static load; phase: phi' M c1 = 0 (the mode starts in the sines)
        self.Fl[n:2 * n] = M @ phi
        self.start = np.zeros(nhc * n + 2)
        self.start[2 * n:3 * n] = phi
        self.start[-2], self.start[-1] = np.sqrt(lam[0]), phi @ C @ phi
        self.solver = peer["solvers"].NonlinearSolver()
        self.Continuation = peer["continuation"].Continuation

    def residual(self, Uwxa):
        return self.system.epmc_res(Uwxa, self.Fl, self.h, Nt=MODE_SAMPLES)

    def solve_at(self, la, guess, xtol=None):
        """tmdsimpy's solution ``Uwx`` at ``log10`` amplitude ``la``."""
        fun = lambda Uwx: self.residual(np.append(Uwx, la))[0:2]  # noqa: E731
        X, _, _, sol = self.solver.nsolve(fun, guess, verbose=False, xtol=xtol)
        if not sol["success"]:
            raise RuntimeError(f"tmdsimpy's solver did not converge at la = {la}: {sol['message']}")
        return X

    def continuation(self, a0: float, a1: float):
        """Its points, one row ``[Uwx, la]`` each, from ``log10`` amplitude ``a0`` to ``a1``."""
        X = self.solve_at(a0, self.start)
        Uwxa0 = np.append(X, a0)
        CtoP = self.hutils.harmonic_wise_conditioning(Uwxa0, self.n, self.h, delta=1e-3)
        CtoP[-3:-1] = np.abs(Uwxa0[-3:-1])
        CtoP[-1] = abs(a1 - a0)
        config = {"DynamicCtoP": False, "TargetNfev": 4, "MaxSteps": 2000, "dsmin": 0.02, "dsmax": 0.175,
                  "verbose": -1, "xtol": 1e-6 * np.sqrt(Uwxa0.size), "corrector": "Ortho"}
        cont = self.Continuation(self.solver, ds0=0.08, CtoP=CtoP, config=config)
        return cont.continuation(self.residual, Uwxa0, a0, a1)


def compare_mode(peer, dofs: int, contacts: int, modes: int, repeat: int, ds_max: float | None = None) -> dict:
    structure, full_dofs, kt, slip = jenkins_blade(dofs, contacts, modes)
    print(f"(b) nonlinear mode 1 of the blade ({full_dofs} DOFs) reduced by Craig-Bampton to {structure.ndof} "
          f"({contacts} contact DOFs + {modes} modes), {contacts} Jenkins contacts (kt = {kt:.3g} N/m, slip force "
          f"{slip:.3g} N), harmonics 0-{MODE_H}, {MODE_SAMPLES} samples, modal amplitude {AMPLITUDE[0]:.0e} to "
          f"{AMPLITUDE[1]:.0e} kg^1/2 m")

    from microslip.frequency import StepControl

    control = None if ds_max is None else StepControl(ds_max=ds_max)

    def ours():
        return nonlinear_modes(structure, 1, AMPLITUDE, harmonics=MODE_H, samples=MODE_SAMPLES, control=control)

    ours()  # Numba's kernels loaded
    t_ours, mode = best_of(ours, 3)
    hz = 1 / (2 * np.pi)
    steps = "default step control" if ds_max is None else f"StepControl(ds_max={ds_max:g})"
    print(f"  microslip ({steps}): {t_ours:.3f} s, {mode.points} points ({1e3 * t_ours / mode.points:.2f} ms each), "
          f"{mode.omega[0] * hz:.1f} to {mode.omega[-1] * hz:.1f} Hz, damping ratio up to "
          f"{100 * mode.damping_ratio.max():.2f} %")
    figures = {"full_dofs": full_dofs, "reduced_dofs": structure.ndof, "contacts": contacts, "modes": modes,
               "microslip_seconds": t_ours, "microslip_points": int(mode.points),
               "frequency_hz": [float(mode.omega[0] * hz), float(mode.omega[-1] * hz)],
               "damping_ratio_max": float(mode.damping_ratio.max())}
    if peer is None:
        return figures
    other = PeerMode(peer, structure, kt, slip)
    a0, a1 = np.log10(AMPLITUDE)
    t_peer, curve = best_of(lambda: other.continuation(a0, a1), repeat)
    done = curve[-1, -1] >= a1 - 1e-9
    points = curve.shape[0]
    print(f"  tmdsimpy:  {t_peer:.3f} s, {points} points ({1e3 * t_peer / points:.2f} ms each), "
          f"{curve[0, -3] * hz:.1f} to {curve[-1, -3] * hz:.1f} Hz"
          f"{'' if done else f', STOPPED at 10^{curve[-1, -1]:.2f}'}: ratio {t_peer / t_ours:.1f}x per mode, "
          f"{(t_peer / points) / (t_ours / mode.points):.1f}x per point (target {TARGET:.0f}x: "
          f"{'met' if t_peer / t_ours >= TARGET else 'MISSED'})")
    # agreement at microslip's amplitudes, in tmdsimpy's normalisation
    la = np.log10(mode.modal_amplitude * np.sqrt(mode.modal_mass))
    picks = np.unique(np.linspace(0, mode.points - 1, 16).round().astype(int))
    dw, dz = [], []
    for k in picks:
        nearest = int(np.argmin(np.abs(curve[:, -1] - la[k])))
        X = other.solve_at(la[k], curve[nearest, :-1], xtol=1e-13)
        dw.append(X[-2] / mode.omega[k] - 1)
        dz.append(X[-1] / (2 * X[-2]) / mode.damping_ratio[k] - 1)
    worst_w, worst_z = float(np.max(np.abs(dw))), float(np.max(np.abs(dz)))
    figures.update({"tmdsimpy_seconds": t_peer, "tmdsimpy_points": int(points), "tmdsimpy_reached_end": bool(done),
                    "ratio_per_mode": t_peer / t_ours,
                    "ratio_per_point": (t_peer / points) / (t_ours / mode.points)})
    print(f"  at {picks.size} of microslip's amplitudes: frequency within {worst_w:.1e}, damping ratio within "
          f"{worst_z:.1e} (relative; target {AGREEMENT:.0e}: "
          f"{'met' if max(worst_w, worst_z) <= AGREEMENT else 'MISSED'})")
    # how well each curve's points resolve the mode: straight lines between them against a curve 4x finer
    from microslip.frequency.analyses.nonlinear_modes import default_control

    fine = default_control(*AMPLITUDE, chord_error=None).ds_max / 4  # the turn rule at 1/80 decade
    ref = nonlinear_modes(structure, 1, AMPLITUDE, harmonics=MODE_H, samples=MODE_SAMPLES,
                          control=StepControl(ds_initial=fine, ds_max=fine))
    la_ref = np.log10(ref.modal_amplitude * np.sqrt(ref.modal_mass))
    for name, la_c, w_c, z_c in (("microslip", la, mode.omega, mode.damping_ratio),
                                 ("tmdsimpy", curve[:, -1], curve[:, -3], curve[:, -2] / (2 * curve[:, -3]))):
        ew = np.max(np.abs(np.interp(la_ref, la_c, w_c) / ref.omega - 1))
        ez = np.max(np.abs(np.interp(la_ref, la_c, z_c) - ref.damping_ratio)) / ref.damping_ratio.max()
        print(f"  {name}'s points joined by straight lines, against {ref.points} points 4 times closer: frequency "
              f"within {ew:.1e} (relative), damping ratio within {ez:.1e} of its largest value")
        figures[f"{name} points joined, against a curve 4x finer"] = {"frequency": float(ew), "damping": float(ez)}
    figures.update({"frequency_difference": worst_w, "damping_difference": worst_z})
    return figures


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dofs", type=int, default=1000, help="blade size asked for (default 1000)")
    parser.add_argument("--contacts", type=int, default=8, help="Jenkins contacts, an even number (default 8)")
    parser.add_argument("--modes", type=int, default=10, help="fixed-interface modes kept (default 10)")
    parser.add_argument("--repeat", type=int, default=1, help="tmdsimpy's mode timed this many times (default 1)")
    parser.add_argument("--ds-max", type=float, default=None,
                        help="microslip's largest continuation step (StepControl.ds_max; default its default, 0.05)")
    args = parser.parse_args(argv)
    peer, why = load_tmdsimpy()
    print(f"load average {os.getloadavg()[0]:.2f} (2 cores shared)")
    if peer is None:
        print(f"tmdsimpy: not compared: {why}; microslip alone follows")
    aft_rows = compare_aft(peer)
    mode = compare_mode(peer, args.dofs, args.contacts, args.modes, args.repeat, args.ds_max)
    save(peer is not None, why, aft_rows, mode, args)
    return 0


def save(compared: bool, why: str | None, aft_rows: list, mode: dict, args) -> None:
    """The figures to ``benchmarks/results/bench_tmdsimpy.json``: the AFT table, the mode's figures."""
    columns = ["motion", "microslip kernel (µs)", "public aft_plane() (µs)"]
    if compared:
        columns += ["tmdsimpy (µs)", "ratio tmdsimpy / kernel", "force difference", "Jacobian difference"]
    defaults = {"dofs": 1000, "contacts": 8, "modes": 10, "repeat": 1, "ds_max": None}  # as main's parser
    options = "".join(f" --{k.replace('_', '-')} {v}" for k, v in vars(args).items() if v != defaults[k])
    figures = {"description": "microslip against tmdsimpy (run in the same process from TMDSIMPY_PATH): (a) one "
                              f"contact's AFT with its Jacobian, J = {AFT_ELEMENTS} sphere elements, harmonics "
                              f"0-{AFT_H}, {AFT_SAMPLES} samples; (b) the nonlinear mode (EPMC) of a Craig-Bampton "
                              f"blade with Jenkins contacts, harmonics 0-{MODE_H}, {MODE_SAMPLES} samples, modal "
                              f"amplitude {AMPLITUDE[0]:.0e} to {AMPLITUDE[1]:.0e} kg^1/2 m. Ratios are tmdsimpy's "
                              f"time over microslip's (target {TARGET:.0f}x)."
                              + ("" if compared else f" tmdsimpy NOT compared in this run: {why}; microslip's "
                                 "times alone."),
               "command": "TMDSIMPY_PATH=/path/to/tmdsimpy OPENBLAS_NUM_THREADS=1 python benchmarks/bench_tmdsimpy.py"
                          + options,
               "sizes": f"AFT best of 7 (tmdsimpy best of 3); mode best of 3 for microslip, of {args.repeat} for "
                        "tmdsimpy",
               "tmdsimpy_compared": compared,
               "tables": [{"caption": "(a) AFT with Jacobian, one call", "columns": columns, "rows": aft_rows},
                          {"caption": "(b) nonlinear mode", "columns": ["figure", "value"],
                           "rows": [[k, ", ".join(f"{x:.4g}" for x in v) if isinstance(v, list) else v]
                                    for k, v in _flat(mode)]}]}
    print(f"results: {save_results('bench_tmdsimpy', figures)}")


def _flat(figures: dict, prefix: str = "") -> list:
    """``(name, value)`` pairs of a nested dict, names joined by `` / ``."""
    out = []
    for key, value in figures.items():
        name = f"{prefix} / {key}" if prefix else key
        out += _flat(value, name) if isinstance(value, dict) else [(name, value)]
    return out


if __name__ == "__main__":
    sys.exit(main())
