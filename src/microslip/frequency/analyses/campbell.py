"""Over rotation speed: the Campbell diagram (stuck and free systems, engine-order lines) and a damper's peak response.

* :func:`campbell` -- the natural frequencies of a :class:`~..structures.speed.SpeedModel`
  against rotation speed with its contacts stuck at their static state (the
  elements closed there add their ``kt`` and ``kn``, as a nonlinear mode's
  linear start does) and without contacts, the engine-order lines
  ``f = EO Omega / 2 pi``, and their crossings found by root-finding
  (``brentq`` on ``f_mode(Omega) - EO Omega / 2 pi``, each evaluation an
  eigen-solve at that speed);
* :func:`damper_speed_curve` -- the peak forced response against rotation
  speed for one damper, its load ``m r Omega^2`` (:func:`damper_design_curve`
  at each speed).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.optimize import brentq

from ...common import _checks
from ...common._io import write_csv
from ..structures.cyclic import CyclicStructure
from ..structures.speed import SpeedModel, rotation_speeds
from .design import DesignCurve, damper_design_curve
from .response import static_solution

SYSTEMS = ("stuck", "free")
RPM = 60.0 / (2.0 * np.pi)  # rpm per rad/s
DENSE = 2000  # DOFs up to which the eigen-solve is dense


def _stuck(structure):
    """``K`` plus the stiffness of the contact elements closed at the static state (N/m)."""
    K = structure.K.copy()
    if not structure.contacts:
        return K
    q0 = static_solution(structure)
    Bt, Bn, n0 = structure.contact_directions()
    Bt2 = structure.second_tangential_directions()
    for c, contact in enumerate(structure.contacts):
        closed = Bn[:, c] @ q0 + n0[c] > contact.model.gaps
        pairs = [(Bt[:, c], contact.model.kt[closed].sum()), (Bn[:, c], contact.model.kn[closed].sum())]
        if contact.planar:
            pairs.append((Bt2[:, c], contact.model.kt[closed].sum()))
        for b, k in pairs:
            if k and sp.issparse(K):
                col = sp.csr_matrix(b[:, None])
                K = K + k * (col @ col.T)
            elif k:
                K = K + k * np.outer(b, b)
    return K


def eigenfrequencies(K, M, modes: int) -> np.ndarray:
    """The ``modes`` lowest natural frequencies (rad/s), ``(modes,)``, of ``K phi = w^2 M phi`` (0 where ``w^2 <= 0``)."""
    n = K.shape[0]
    if n <= DENSE:
        Kd = K.toarray() if sp.issparse(K) else np.asarray(K)
        Md = M.toarray() if sp.issparse(M) else np.asarray(M)
        lam = sla.eigh(0.5 * (Kd + Kd.T), Md, eigvals_only=True, subset_by_index=[0, modes - 1])
    else:
        Ms = sp.csc_matrix(M)
        scale = float(np.median(np.abs(K.diagonal())) / np.median(np.abs(Ms.diagonal())))
        lam = np.sort(spla.eigsh(sp.csc_matrix(K), k=modes, M=Ms, sigma=-1e-6 * scale, which="LM",
                                 return_eigenvectors=False))
    return np.sqrt(np.maximum(lam, 0.0))


@dataclass(frozen=True, eq=False)
class CampbellDiagram:
    """Natural frequencies against rotation speed, engine-order lines and their crossings (from :func:`campbell`).

    Attributes
    ----------
    speeds : ndarray, shape (k,)
        Rotation speeds (rad/s).
    frequencies : dict
        ``{"stuck" | "free": ndarray (k, modes)}``: natural frequencies (rad/s)
        of the system with its contacts stuck at the static state, and without
        contacts.
    engine_orders : ndarray of int, shape (e,)
        The engine orders drawn, ``f = EO Omega / 2 pi``.
    crossings : list of dict
        One per crossing: ``system``, ``mode`` (1: the lowest), ``engine_order``,
        ``speed`` (rad/s) and ``frequency`` (rad/s, ``= EO speed``).
    """

    speeds: np.ndarray
    frequencies: dict = field(repr=False)
    engine_orders: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    crossings: list = field(default_factory=list)

    def hertz(self, system: str = "stuck") -> np.ndarray:
        """Natural frequencies of ``system`` ("stuck" or "free") in Hz, ``(k, modes)``."""
        system = _checks.one_of("system", system, tuple(self.frequencies))
        return self.frequencies[system] / (2 * np.pi)

    def columns(self) -> dict:
        """The curves (one row per speed) and the crossings (padded), as named columns with units (for CSV)."""
        out = {"speed [rad/s]": self.speeds, "speed [rpm]": self.speeds * RPM}
        for system, f in self.frequencies.items():
            for j in range(f.shape[1]):
                out[f"{system} mode {j + 1} [Hz]"] = f[:, j] / (2 * np.pi)
        x = self.crossings
        out.update({"crossing system": np.array([c["system"] for c in x], dtype=str),
                    "crossing mode [-]": np.array([c["mode"] for c in x], dtype=int),
                    "crossing engine order [-]": np.array([c["engine_order"] for c in x], dtype=int),
                    "crossing speed [rad/s]": np.array([c["speed"] for c in x], dtype=float),
                    "crossing speed [rpm]": np.array([c["speed"] * RPM for c in x], dtype=float),
                    "crossing frequency [Hz]": np.array([c["frequency"] / (2 * np.pi) for c in x], dtype=float)})
        return out

    def to_csv(self, path):
        """Write :meth:`columns` to ``path`` as CSV (atomically). Returns the path."""
        path = _checks.file_path("path", path)
        return write_csv(path, self.columns())

    def plot(self, ax=None):
        """Modes against speed (rpm; stuck solid, free dashed), engine-order lines and crossings (Hz); the Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(7, 5))
        rpm = self.speeds * RPM
        styles = {"stuck": "-", "free": "--"}
        for system, f in self.frequencies.items():
            for j in range(f.shape[1]):
                ax.plot(rpm, f[:, j] / (2 * np.pi), styles[system], color=f"C{j % 10}",
                        label=f"{system}" if j == 0 else None)
        top = max(float(np.max(f)) for f in self.frequencies.values()) / (2 * np.pi) if self.frequencies else 1.0
        for eo in self.engine_orders:
            ax.plot(rpm, eo * self.speeds / (2 * np.pi), ":", color="0.5", lw=0.8)
            ax.annotate(f"EO{eo}", (rpm[-1], eo * self.speeds[-1] / (2 * np.pi)), fontsize=7, color="0.4")
        if self.crossings:
            ax.plot([c["speed"] * RPM for c in self.crossings],
                    [c["frequency"] / (2 * np.pi) for c in self.crossings], "o", mfc="none", color="k",
                    label="crossings")
        ax.set_ylim(0.0, 1.1 * top)
        ax.set_xlabel("rotation speed (rpm)")
        ax.set_ylabel("frequency (Hz)")
        ax.grid(True, alpha=0.3)
        ax.legend()
        return ax


def campbell(model: SpeedModel, speeds, *, modes: int = 6, engine_orders=(1, 2, 3, 4, 5, 6),
             contacts: str = "both") -> CampbellDiagram:
    """The Campbell diagram of a speed-dependent structure.

    Parameters
    ----------
    model : SpeedModel
        The structure at any speed (a plain structure: a cyclic sector's modes
        belong to a nodal diameter, not handled here).
    speeds : array_like, shape (k,)
        Rotation speeds (rad/s, or strings such as ``"3000 rpm"``), >= 0,
        increasing, at least 2.
    modes : int, default 6
        Number of modes per system.
    engine_orders : sequence of int, default 1..6
        Engine orders (>= 1) of the lines ``f = EO Omega / 2 pi``.
    contacts : {"both", "stuck", "free"}
        The systems: contacts stuck at their static state, no contacts, or both.

    Returns
    -------
    CampbellDiagram
        Each crossing of a mode with an engine-order line between consecutive
        speeds, refined by ``brentq`` (each function evaluation an eigen-solve
        at that speed; the static state solved again there for the stuck system)
        to ``1e-13`` relative in speed. Modes are numbered by ascending
        frequency at each speed (no tracking through veerings).
    """
    if not isinstance(model, SpeedModel):
        raise TypeError(f"model must be a microslip SpeedModel, got {type(model).__name__}")
    if model._cyclic is not None:
        raise ValueError("model: a cyclic sector's Campbell diagram needs a nodal diameter per engine order, which "
                         "campbell does not handle; give the model without cyclic=")
    speeds = rotation_speeds("speeds", speeds)
    if speeds.size < 2 or np.any(np.diff(speeds) <= 0):
        raise ValueError(f"speeds must be at least 2 increasing rotation speeds (rad/s), got {speeds.tolist()}")
    contacts = _checks.one_of("contacts", contacts, ("both",) + SYSTEMS)
    systems = SYSTEMS if contacts == "both" else (contacts,)
    if isinstance(engine_orders, (str, bytes, int, float)) or not hasattr(engine_orders, "__len__"):
        raise TypeError(f"engine_orders must be a sequence of integers, got {engine_orders!r}")
    eos = np.array([_checks.positive_int(f"engine_orders[{i}]", e) for i, e in enumerate(engine_orders)], dtype=int)
    with_damper = model.damper is not None
    ndof = model.ndof + 3 * with_damper
    modes = _checks.positive_int("modes", modes)
    sizes = {"free": model.ndof, "stuck": ndof}
    limit = min(n if n <= DENSE else n - 1 for n in (sizes[system] for system in systems))
    if modes > limit:
        raise ValueError(f"modes must be at most {limit} (the DOFs of the systems), got {modes}")
    if speeds[0] == 0.0 and with_damper and "stuck" in systems:
        raise ValueError("speeds must be > 0 rad/s for the stuck system with a damper: its load m r Omega^2 is zero "
                         "at rest")

    def freqs(system: str, omega: float) -> np.ndarray:
        if system == "free":
            s = model.at(omega, contacts=False)
            return eigenfrequencies(s.K, s.M, modes)
        s = model.at(omega)
        return eigenfrequencies(_stuck(s), s.M, modes)

    table, crossings = {}, []
    for system in systems:
        f = np.array([freqs(system, w) for w in speeds])
        table[system] = f
        for j in range(modes):
            for eo in eos:
                g = f[:, j] - eo * speeds
                for k in range(speeds.size - 1):
                    if g[k] == 0.0:
                        root = float(speeds[k])
                    elif g[k] * g[k + 1] < 0.0:
                        root = brentq(lambda w: freqs(system, w)[j] - eo * w, speeds[k], speeds[k + 1],
                                      xtol=1e-13 * float(speeds[k + 1]), rtol=4 * np.finfo(float).eps, maxiter=200)
                    else:
                        continue
                    crossings.append({"system": system, "mode": j + 1, "engine_order": int(eo), "speed": root,
                                      "frequency": float(eo * root)})
                if g[-1] == 0.0:
                    crossings.append({"system": system, "mode": j + 1, "engine_order": int(eo),
                                      "speed": float(speeds[-1]), "frequency": float(eo * speeds[-1])})
    crossings.sort(key=lambda c: (c["system"], c["speed"]))
    return CampbellDiagram(speeds, table, eos, crossings)


@dataclass(frozen=True, eq=False)
class SpeedCurve(DesignCurve):
    """Peak response against rotation speed for one damper (from :func:`damper_speed_curve`).

    As :class:`DesignCurve` (its ``loads`` the damper's centrifugal load ``m r
    Omega^2`` at each speed, N), plus ``speeds`` (rad/s), ``(k,)``.
    """

    speeds: np.ndarray | None = None

    @property
    def worst(self) -> tuple[float, float]:
        """``(speed, peak)``: the speed (rad/s) with the highest trusted peak response (m)."""
        trusted = self.trusted
        if not trusted.any():
            raise ValueError("the speed curve has no trusted peak (" + "; ".join(self.problems()) + ")")
        i = int(np.flatnonzero(trusted)[np.argmax(self.peak_amplitude[trusted])])
        return float(self.speeds[i]), float(self.peak_amplitude[i])

    def columns(self) -> dict:
        """The curve as named columns with units (for CSV), speeds first."""
        return {"speed [rad/s]": self.speeds, "speed [rpm]": self.speeds * RPM, **super().columns()}

    def plot(self, ax=None, *, unit: str = "µm"):
        """Plot the peak response against the rotation speed (rpm), the untrusted peaks crossed; the Axes."""
        import matplotlib.pyplot as plt

        from ...common.units import plot_factor

        factor = plot_factor(unit)
        if ax is None:
            _, ax = plt.subplots(figsize=(6, 4))
        trusted = self.trusted
        rpm = self.speeds * RPM
        ax.plot(rpm, np.where(trusted, self.peak_amplitude, np.nan) * factor, "o-", label="peak response")
        if not trusted.all():
            ax.plot(rpm[~trusted], self.peak_amplitude[~trusted] * factor, "x", color="C3", ms=9,
                    label="no peak (incomplete curve, highest on the range's edge, or failed)")
        ax.set_xlabel("rotation speed (rpm)")
        ax.set_ylabel(f"peak response of DOF {self.dof} ({unit})")
        ax.grid(True, alpha=0.3)
        ax.legend()
        return ax


def damper_speed_curve(model: SpeedModel, speeds, force, omega, *, dof: int, harmonics: int = 5,
                       progress: bool = False, **options) -> SpeedCurve:
    """Peak forced response against rotation speed for the model's damper, its load ``m r Omega^2``.

    Parameters
    ----------
    model : SpeedModel
        With its ``damper`` and ``radius``.
    speeds : array_like, shape (k,)
        Rotation speeds (rad/s, or strings such as ``"3000 rpm"``), > 0.
    force : array_like or mapping
        Excitation of the structure without the damper (N), as in
        :func:`damper_design_curve`.
    omega : array_like, shape (2,) or (k, 2)
        Frequency range (rad/s), one for every speed or one per speed.
    dof : int
        The output DOF (of the structure without the damper).
    harmonics : int, default 5
        ``H``.
    progress : bool
        One line per speed on standard error.
    **options
        Passed to :func:`frequency_response`.

    Returns
    -------
    SpeedCurve
        Each speed marked as :func:`damper_design_curve` marks a load (peak,
        incomplete curve, peak on the range's edge, failed), with its warnings.
    """
    if not isinstance(model, SpeedModel):
        raise TypeError(f"model must be a microslip SpeedModel, got {type(model).__name__}")
    if model.damper is None:
        raise ValueError("model must carry a damper (SpeedModel(..., damper=, radius=)) for a damper speed curve")
    speeds = rotation_speeds("speeds", speeds)
    _checks.positive_array("speeds", speeds, ndim=1, min_size=1)
    bands = _checks.positive_array("omega", omega)
    if bands.shape == (2,):
        bands = np.tile(bands, (speeds.size, 1))
    if bands.shape != (speeds.size, 2):
        raise ValueError(f"omega must be a frequency range (2,) or one per speed ({speeds.size}, 2) in rad/s, got "
                         f"shape {bands.shape}")
    progress = _checks.flag("progress", progress)
    d = model.damper
    parts = []
    for k, w in enumerate(speeds):
        s = model.at(w, damper=False)
        load = d.mass * model.radius * w * w
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            parts.append(damper_design_curve(s, d, [load], force, tuple(bands[k]), dof=dof, harmonics=harmonics,
                                             progress=progress, **options))
        for x in caught:  # each warning names the speed
            warnings.warn(f"speed {w:.6g} rad/s ({w * RPM:.6g} rpm): {x.message}", x.category, stacklevel=2)
    cat = np.concatenate
    return SpeedCurve(cat([p.loads for p in parts]), cat([p.peak_amplitude for p in parts]),
                      cat([p.peak_frequency for p in parts]), [r for p in parts for r in p.responses], parts[0].dof,
                      complete=cat([p.complete for p in parts]), on_edge=cat([p.on_edge for p in parts]),
                      errors=[e for p in parts for e in p.errors], speeds=speeds)
