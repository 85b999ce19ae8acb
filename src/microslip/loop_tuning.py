"""Tuning on measured loops, end to end, and validation at the other measured loads.

:func:`tune_on_loops` takes analysed loops at several normal loads and a
normal law, builds the :class:`~microslip.measured.MeasuredContact` reference
on the steady loops at the highest load, tunes the paper's array on it
(:func:`microslip.tune`, unchanged) and predicts the loops at every measured
load (:func:`validate`): the paper's claim is that a model tuned at the
highest load reproduces the lower ones. :meth:`LoopTuning.report` writes all
of it as HTML and Markdown.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import _checks
from .loops import Loops, Record, analyse
from .measured import MeasuredContact, _loops_list
from .model import MicroslipModel
from .tuning import TuningPoints, tune, tuning_points

_UM = 1e6


@dataclass(frozen=True, eq=False)
class LoadValidation:
    """Measured and predicted loops at one normal load.

    Attributes
    ----------
    normal_load : float
        The load (N).
    measured, predicted : Loops
        Analysis of the measured record and of the model driven by its
        displacement (offset removed) at the approach of the normal law.
    """

    normal_load: float
    measured: Loops
    predicted: Loops

    def _rel(self, key):
        m, p = self.measured.summary()[key], self.predicted.summary()[key]
        return (p - m) / m

    @property
    def energy_error(self) -> float:
        """Relative difference of the energy per steady cycle, predicted vs measured."""
        return self._rel("energy")

    @property
    def slip_force_error(self) -> float:
        """Relative difference of the slip force ``(F+ - F-)/2``."""
        return self._rel("slip_force")

    @property
    def stiffness_error(self) -> float:
        """Relative difference of the stick stiffness after reversals."""
        return self._rel("stick_stiffness")


@dataclass(frozen=True, eq=False)
class Validation:
    """Predicted against measured loops at every measured load (highest first)."""

    loads: tuple

    HEADERS = ("N (N)", "energy meas. (µJ)", "energy pred. (µJ)", "diff (%)", "slip force meas. (N)",
               "slip force pred. (N)", "diff (%)", "stick stiffness meas. (N/µm)", "pred. (N/µm)", "diff (%)")

    def rows(self) -> list:
        """Table rows matching :attr:`HEADERS` (energies in µJ, stiffness in N/µm, differences in %)."""
        out = []
        for v in self.loads:
            m, p = v.measured.summary(), v.predicted.summary()
            out.append([f"{v.normal_load:.4g}", m["energy"] * 1e6, p["energy"] * 1e6, 100 * v.energy_error,
                        m["slip_force"], p["slip_force"], 100 * v.slip_force_error,
                        m["stick_stiffness"] / 1e6, p["stick_stiffness"] / 1e6, 100 * v.stiffness_error])
        return out

    def worst(self) -> dict:
        """Largest absolute relative differences over the loads: energy, slip_force, stiffness."""
        return {k: max(abs(getattr(v, f"{k}_error")) for v in self.loads)
                for k in ("energy", "slip_force", "stiffness")}

    def plot(self, ax=None):
        """Measured steady cycles (grey) and the predicted ones (coloured) at every load; returns the Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(6.4, 4.6))
        colors = plt.get_cmap("plasma")(np.linspace(0.0, 0.8, len(self.loads)))
        for v, color in zip(self.loads, colors):
            t_c, T_c = v.measured.centre
            for loops, style, label, shift in ((v.measured, dict(color="0.6", lw=2.2), None, (t_c, T_c)),
                                               (v.predicted, dict(color=color, lw=1.1, ls="--"),
                                                f"N = {v.normal_load:.3g} N", (0.0, 0.0))):
                a, b = loops.cycle_bounds(loops.steady_to - 1)
                ax.plot((loops.record.t[a:b + 1] - shift[0]) * _UM, loops.record.T[a:b + 1] - shift[1],
                        label=label, **style)
        ax.plot([], [], color="0.6", lw=2.2, label="measured")
        ax.set_xlabel("tangential displacement t (µm)")
        ax.set_ylabel("tangential force T (N)")
        ax.set_title("measured (grey, offsets removed) and predicted (dashed) steady loops", fontsize=9)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
        return ax


def validate(model: MicroslipModel, normal, loops) -> Validation:
    """Drive ``model`` with each measured displacement record and compare the loops.

    Parameters
    ----------
    model : MicroslipModel
        The tuned array.
    normal : object
        Normal law, ``approach(N)`` (m of N): the approach at each load.
    loops : Loops or sequence of Loops
        Analysed records with their normal loads.

    Returns
    -------
    Validation
        Highest load first. Each record's displacement is shifted by its
        loop centre (the sensor offset); the model's loops are analysed with
        the same options as the measured ones, without the correction for
        displacement noise (the model's force follows the noisy
        displacement exactly).
    """
    if not isinstance(model, MicroslipModel):
        raise TypeError(f"model must be a MicroslipModel, got {type(model).__name__}")
    items = sorted(_loops_list(loops), key=lambda L: -L.normal_load)
    out = []
    for L in items:
        n = float(normal.approach(L.normal_load))
        t = L.record.t - L.centre[0]
        r = model.simulate(t, n, per_element=False)
        rec = Record(t=t, T=r.T, time=L.record.time, normal_load=L.normal_load,
                     source=f"model at {L.normal_load:.4g} N")
        options = dict(L.options, noise_correction=False)  # the model's T is exact for the t it is given
        out.append(LoadValidation(L.normal_load, L, analyse(rec, **options)))
    return Validation(tuple(out))


def raised_load_path(reference, T, N, dN, T_A):
    """Displacement (m) along the path of the paper's Fig. 4a on any reference obeying Mindlin--Deresiewicz.

    ``T`` rises to ``T_A`` at load ``N``; the load is raised to ``N + dN`` at
    constant ``T``; ``T`` rises again. Until ``T - T_A`` reaches ``mu dN`` the
    curve is the backbone at ``N + dN`` shifted to start at A; beyond, the
    backbone at ``N + dN`` itself (Mindlin and Deresiewicz; DESIGN.md §2).

    Parameters
    ----------
    reference : ContactReference
        Gives ``mu`` and ``backbone_displacement(T, N)``.
    T : array_like
        Tangential force (N), ``0 <= T <= mu (N + dN)``.
    N, dN, T_A : float
        Load (N), its increment (N) and the force at which it is raised (N).
    """
    N = _checks.positive_scalar("N", N)
    dN = _checks.positive_scalar("dN", dN, allow_zero=True)
    T_A = _checks.positive_scalar("T_A", T_A, allow_zero=True)
    if T_A > reference.mu * N:
        raise ValueError(f"T_A must not exceed mu*N = {reference.mu * N:g} N, got {T_A:g} N")
    T = _checks.real_array("T", T)
    mu, N2 = reference.mu, N + dN
    before = reference.backbone_displacement(np.clip(T, 0, mu * N), N)
    tA = reference.backbone_displacement(T_A, N)
    shifted = tA + reference.backbone_displacement(np.clip(T - T_A, 0, mu * N2), N2)
    joined = reference.backbone_displacement(np.clip(T, 0, mu * N2), N2)
    return np.where(T <= T_A, before, np.where(T <= T_A + mu * dN, shifted, joined))


@dataclass(frozen=True, eq=False)
class LoopTuning:
    """A model tuned on measured loops, with its reference, points and validation.

    Attributes
    ----------
    reference : MeasuredContact
        The fitted reference (backbone, normal law, mu).
    model : MicroslipModel
        The tuned array.
    points : TuningPoints
        The points on the fitted backbone (m, N).
    loops : tuple of Loops
        The analysed records, highest load first.
    validation : Validation
        Predicted against measured loops at every load.
    """

    reference: MeasuredContact
    model: MicroslipModel
    points: TuningPoints
    loops: tuple
    validation: Validation

    @property
    def tuned_loops(self) -> Loops:
        """The record the model was tuned on (highest load)."""
        return self.loops[0]

    # -- figures ------------------------------------------------------------------
    def plot_branch(self, ax=None):
        """The measured steady branches (as ``2 x backbone``), the fitted curve and the tuning points."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(6, 4.4))
        x, y = self.tuned_loops.backbone_points()
        fit, ref = self.reference.fit, self.reference
        grid = np.linspace(0.0, x.max(), 300)
        ax.plot(2 * x * _UM, 2 * y, ",", color="0.55", alpha=0.5)
        ax.plot([], [], ".", color="0.55", label="measured steady branches (from each reversal)")
        ax.plot(2 * grid * _UM, 2 * ref.backbone(grid, ref.normal_load), "k-", lw=1.8,
                label=f"fitted concave branch (RMS residual {100 * fit.relative_residual:.2g} % of slip force)")
        ax.plot(2 * self.points.t * _UM, 2 * self.points.T, "s", mfc="none", mec="tab:green", mew=2, ms=8,
                label="tuning points")
        ax.plot(2 * grid * _UM, 2 * self.model.backbone(grid, self.points.approach), "--", color="tab:red",
                lw=1.4, label=f"tuned array, J = {self.model.elements}")
        ax.set_xlabel("displacement from reversal (µm)")
        ax.set_ylabel("force change from reversal (N)")
        ax.set_title(f"branch at N = {ref.normal_load:.4g} N (Masing: 2 x backbone)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, loc="lower right")
        return ax

    def plot_elements(self, normal_load=None, ax=None):
        """Paper Fig. 6a-b: the measured loop, the model's loop and each element's loop at a load (N)."""
        import matplotlib.pyplot as plt

        from .figures.case import element_colors

        if ax is None:
            _, ax = plt.subplots(figsize=(6, 4.4))
        v = self._validation_at(normal_load)
        L = v.measured
        a, b = L.cycle_bounds(L.steady_to - 1)
        t_c, T_c = L.centre
        t = L.record.t - t_c
        ax.plot(t[a:b + 1] * _UM, L.record.T[a:b + 1] - T_c, color="0.6", lw=2.5, label="measured (offsets removed)")
        r = self.model.simulate(t, float(self.reference.approach(v.normal_load)))
        ax.plot(t[a:b + 1] * _UM, r.T[a:b + 1], "k--", lw=1.3, label="model")
        for i, color in enumerate(element_colors(self.model.elements)):
            ax.plot(t[a:b + 1] * _UM, r.Ti[a:b + 1, i], color=color, lw=1, label=f"element {i + 1}")
        ax.set_xlabel("tangential displacement t (µm)")
        ax.set_ylabel("tangential force T (N)")
        ax.set_title(f"N = {v.normal_load:.4g} N" + (" (tuned)" if v is self.validation.loads[0] else " (predicted)"))
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, ncol=2)
        return ax

    def plot_normal(self, ax=None, *, others=()):
        """Paper Fig. 6c: the normal law, the array's normal curve and each element's spring.

        Parameters
        ----------
        others : sequence of (label, normal law)
            Further laws to draw for comparison (e.g. Palmgren, Lundberg--Sjövall).
        """
        import matplotlib.pyplot as plt

        from .figures.case import element_colors

        if ax is None:
            _, ax = plt.subplots(figsize=(6, 4.4))
        n_tot = self.points.approach
        n = np.linspace(0.0, 1.05 * n_tot, 300)
        name = getattr(self.reference.normal, "law_name", "normal law")
        ax.plot(n * _UM, self.reference.normal_force(n), "k-", lw=2, label=f"{name} (tuned on)")
        for label, law in others:
            ax.plot(n * _UM, law.normal_force(n), ":", lw=1.5, label=label)
        ax.plot(n * _UM, self.model.normal_force(n), "--", color="tab:red", lw=1.5, label="tuned array")
        Ni = self.model.element_normal_forces(n)
        for i, color in enumerate(element_colors(self.model.elements)):
            ax.plot(n * _UM, Ni[:, i], color=color, lw=1, label=f"element {i + 1}")
        ax.set_xlabel("normal approach n (µm)")
        ax.set_ylabel("normal force N (N)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
        return ax

    def transition(self, N=None, dN=None, at: float = 0.5, points: int = 400) -> dict:
        """The Fig. 4-like path on the tuned model and on the reference: load raised from N to N + dN.

        Defaults: ``N`` the lowest measured load, ``N + dN`` the highest;
        the load is raised when ``T = at * mu * N``.

        Returns
        -------
        dict
            ``t_model``, ``T_model`` (m, N) along the model's path;
            ``t_reference``, ``T_reference`` the reference's; ``N``, ``dN``, ``T_A``.
        """
        loads = [L.normal_load for L in self.loops]
        N = min(loads) if N is None else _checks.positive_scalar("N", N)
        dN = max(loads) - N if dN is None else _checks.positive_scalar("dN", dN)
        ref, mu = self.reference, self.reference.mu
        T_A = _checks.in_range("at", at, 0.0, 1.0) * mu * N
        t_A = float(ref.backbone_displacement(T_A, N))
        t_end = 1.2 * float(ref.gross_slip_displacement(N + dN))
        n1, n2 = float(ref.approach(N)), float(ref.approach(N + dN))
        k = points // 3
        t = np.concatenate([np.linspace(0.0, t_A, k), np.full(k, t_A), np.linspace(t_A, t_end, points - 2 * k)])
        n = np.concatenate([np.full(k, n1), np.linspace(n1, n2, k), np.full(points - 2 * k, n2)])
        r = self.model.simulate(t, n)
        T_ref = np.linspace(0.0, mu * (N + dN), points)
        return {"t_model": t, "T_model": r.T, "t_reference": raised_load_path(ref, T_ref, N, dN, T_A),
                "T_reference": T_ref, "N": N, "dN": dN, "T_A": T_A}

    def plot_transition(self, ax=None, **kwargs):
        """Plot :meth:`transition` (paper Fig. 4a, for this contact); returns the Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(6, 4.4))
        d = self.transition(**kwargs)
        ax.plot(d["t_reference"] * _UM, d["T_reference"], "k-", lw=2, label="reference (Mindlin-Deresiewicz rule)")
        ax.plot(d["t_model"] * _UM, d["T_model"], "--", color="tab:red", lw=1.5, label="tuned array")
        ax.axhline(d["T_A"], color="0.6", lw=0.8, ls=":")
        ax.set_xlabel("tangential displacement t (µm)")
        ax.set_ylabel("tangential force T (N)")
        ax.set_title(f"load raised from {d['N']:.3g} N to {d['N'] + d['dN']:.3g} N at T = {d['T_A']:.3g} N")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
        return ax

    def _validation_at(self, normal_load):
        if normal_load is None:
            return self.validation.loads[0]
        N = _checks.positive_scalar("normal_load", normal_load)
        for v in self.validation.loads:
            if abs(v.normal_load - N) <= 1e-3 * N:
                return v
        raise ValueError(f"normal_load: no record at {N:g} N; the loads are "
                         f"{[round(v.normal_load, 4) for v in self.validation.loads]} N")

    # -- report -------------------------------------------------------------------
    def report(self, out_dir, *, stem: str = "report", title: str | None = None) -> tuple[Path, Path]:
        """Write ``stem.html`` and ``stem.md`` (and the PNG figures, prefixed with ``stem``) into ``out_dir``."""
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        from .report import Report

        ref, fit = self.reference, self.reference.fit
        rep = Report(title or "microslip: model tuned on measured loops")
        rep.text(f"Records: {', '.join(L.record.source for L in self.loops)}. Tuned at N = {ref.normal_load:.4g} N "
                 f"with J = {self.model.elements} elements, points evenly spaced in force unless given; "
                 f"normal law: {getattr(ref.normal, 'law_name', type(ref.normal).__name__)}; "
                 f"mu = {ref.mu:.4g} ({ref.notes.get('mu_source', 'given')}).")
        rep.heading("Measured loops")
        rep.table(["record", "N (N)", "cycles", "steady", "energy (µJ)", "amplitude (µm)", "slip force (N)",
                   "stick stiffness (N/µm)", "Masing error (%)", "Masing basis"],
                  [[L.record.source, L.normal_load, L.cycles, f"{L.steady_from + 1}-{L.steady_to}",
                    L.summary()["energy"] * 1e6, L.summary()["amplitude"] * _UM, L.summary()["slip_force"],
                    L.summary()["stick_stiffness"] / 1e6, 100 * L.masing_error, L.masing_basis] for L in self.loops])
        figures = [("loops", "the record at the tuning load, its steady cycle and branches",
                    lambda ax: self.tuned_loops.plot(ax=ax)),
                   ("branch", "fitted branch and tuning points", lambda ax: self.plot_branch(ax=ax)),
                   ("elements", "per-element loops at the tuning load (paper Fig. 6a)",
                    lambda ax: self.plot_elements(ax=ax)),
                   ("elements-low", "per-element loops at the lowest load, predicted (paper Fig. 6b)",
                    lambda ax: self.plot_elements(self.validation.loads[-1].normal_load, ax=ax)),
                   ("normal", "normal force-approach curve and the elements' springs (paper Fig. 6c)",
                    lambda ax: self.plot_normal(ax=ax)),
                   ("validation", "measured and predicted loops at every load", lambda ax: self.validation.plot(ax=ax)),
                   ("transition", "load raised at constant T (paper Fig. 4a, for this contact)",
                    lambda ax: self.plot_transition(ax=ax))]
        rep.heading("Fit and tuning")
        rep.text(f"Concave fit of the branch: RMS residual {fit.residual:.3g} N ({100 * fit.relative_residual:.2g} % "
                 f"of the slip force), initial stiffness {fit.initial_stiffness / 1e6:.4g} N/µm, gross slip at "
                 f"{2 * fit.gross_slip_displacement * _UM:.4g} µm from the reversal, microslip ratio "
                 f"{fit.microslip_ratio:.3g} (1 = a single macroslip element, 1.5 = Cattaneo-Mindlin); "
                 f"Masing error {100 * ref.notes.get('masing_error', float('nan')):.2g} %.")
        rep.table(["element", "kt (N/µm)", "kn (N/µm)", "gap (µm)", "slips at t (µm)"],
                  [[i + 1, self.model.kt[i] / 1e6, self.model.kn[i] / 1e6, self.model.gaps[i] * _UM,
                    self.points.t[::-1][i] * _UM] for i in range(self.model.elements)])
        for name, caption, draw in figures:
            if name == "validation":
                rep.heading("Validation at the other loads")
                rep.table(list(Validation.HEADERS), self.validation.rows(),
                          caption="predicted by the model tuned at the highest load, against the measured records")
            fig, ax = plt.subplots(figsize=(6.4, 4.6))
            draw(ax)
            fig.tight_layout()
            rep.figure(fig, f"{stem}-{name}", caption, out_dir)
            plt.close(fig)
        return rep.write(out_dir, stem)


def tune_on_loops(loops, normal, *, elements=None, forces=None, displacements=None, mu=None,
                  normal_load=None, masing_tolerance: float = 0.1) -> LoopTuning:
    """Tune the paper's array on measured loops and validate it at every measured load.

    Parameters
    ----------
    loops : Loops or sequence of Loops
        Analysed records (:func:`microslip.loops.analyse`), each with its normal load.
    normal : object
        Normal law with ``approach(N)`` and ``normal_force(n)`` (e.g. :class:`microslip.Cylinder`).
    elements, forces, displacements
        The tuning points, as in :func:`microslip.tune` (default ``elements=4``).
    mu : float, optional
        Friction coefficient; default ``normal.mu``, else fitted from the slip forces.
    normal_load : float, optional
        Tuning load (N); default the highest record's.
    masing_tolerance : float, default 0.1
        See :meth:`MeasuredContact.from_loops`.

    Returns
    -------
    LoopTuning

    Examples
    --------
    >>> from microslip import Cylinder, loops, tune_on_loops
    >>> from microslip.loops.synthetic import dataset_files, normal_curve_file
    >>> records = [loops.analyse(loops.read(p)) for p in dataset_files()]
    >>> result = tune_on_loops(records, Cylinder(10e-3, 5e-3, 200e9, 0.3, law="palmgren"), elements=6)
    >>> result.model.elements, round(result.reference.mu, 2)
    (6, 0.4)
    """
    items = sorted(_loops_list(loops), key=lambda L: -L.normal_load)
    reference = MeasuredContact.from_loops(items, normal, mu=mu, normal_load=normal_load,
                                           masing_tolerance=masing_tolerance)
    if elements is None and forces is None and displacements is None:
        elements = 4
    N_tot = reference.normal_load
    points = tuning_points(reference, N_tot, forces=forces, displacements=displacements, elements=elements)
    model = tune(reference, N_tot, forces=forces, displacements=displacements, elements=elements)
    usable = [L for L in items if L.normal_load <= N_tot * (1 + 1e-9)]
    return LoopTuning(reference, model, points, tuple(items), validate(model, normal, usable))
