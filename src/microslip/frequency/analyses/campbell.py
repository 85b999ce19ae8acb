"""Over rotation speed: the Campbell diagram (stuck and free systems, engine-order lines) and a damper's peak response.

* :func:`campbell` -- the natural frequencies of a :class:`~..structures.speed.SpeedModel`
  against rotation speed with its contacts stuck at their static state (the
  elements closed there add their ``kt`` and ``kn``, as a nonlinear mode's
  linear start does) and without contacts, the engine-order lines
  ``f = EO Omega / 2 pi``, and their crossings found by root-finding
  (``brentq`` on ``f_mode(Omega) - EO Omega / 2 pi``, each evaluation an
  eigen-solve at that speed). For a cyclic sector (``SpeedModel(...,
  cyclic=)``) the frequencies of each nodal diameter ``d`` (the sector's
  matrices in that diameter, :meth:`~..structures.cyclic.CyclicStructure.matrices`),
  and an engine order crosses only the diameter it excites
  (:func:`excited_diameter`: ``EO = +-d mod N``);
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
from scipy.optimize import brentq

from ...common._numeric import eigsh_repeatable
from ...common import _checks
from ...common._io import write_csv
from ...common._progress import Progress
from ..equations.epmc import stuck_matrices
from ..structures.speed import SpeedModel, rotation_speeds
from .design import DesignCurve, damper_design_curve
from .response import static_solution

SYSTEMS = ("stuck", "free")
RPM = 60.0 / (2.0 * np.pi)  # rpm per rad/s
DENSE = 2000  # DOFs up to which the eigen-solve is dense


def excited_diameter(engine_order: int, sectors: int) -> int:
    """The nodal diameter (0 to ``N // 2``) an engine order excites on a disk of ``N`` sectors.

    A travelling-wave excitation of engine order ``k`` puts sector ``s + 1``
    ``2 pi k / N`` behind sector ``s``: only the modes of diameter ``d`` with
    ``k = d`` or ``k = -d`` (mod ``N``) respond (aliasing: ``k`` and ``N - k``,
    ``k + N``, ... excite the same diameter).

    Parameters
    ----------
    engine_order : int
        ``k >= 0``.
    sectors : int
        ``N >= 3``.

    Examples
    --------
    >>> [excited_diameter(k, 8) for k in (1, 4, 7, 9, 12)]
    [1, 4, 1, 1, 4]
    """
    k = _checks.positive_int("engine_order", engine_order, minimum=0)
    n = _checks.positive_int("sectors", sectors, minimum=3)
    return min(k % n, n - k % n)


def _stuck_systems(structure, diameters) -> list:
    """``[(K, M), ...]`` per diameter (``[None]``: a plain structure): the contacts stuck at the static state."""
    q0 = static_solution(structure) if structure.contacts else np.zeros(structure.ndof)
    return [(K, M) for M, _, K in (stuck_matrices(structure, q0, d) for d in diameters)]


def eigenfrequencies(K, M, modes: int) -> np.ndarray:
    """The ``modes`` lowest natural frequencies (rad/s), ``(modes,)``, of ``K phi = w^2 M phi`` (0 where ``w^2 <= 0``).

    ``K`` (N/m) and ``M`` (kg), ``(n, n)``, real symmetric or complex Hermitian (a nodal diameter's), dense or
    sparse.
    """
    n = K.shape[0]
    if n <= DENSE:
        Kd = K.toarray() if sp.issparse(K) else np.asarray(K)
        Md = M.toarray() if sp.issparse(M) else np.asarray(M)
        lam = sla.eigh(0.5 * (Kd + Kd.conj().T), Md, eigvals_only=True, subset_by_index=[0, modes - 1])
    else:
        Ms = sp.csc_matrix(M)
        scale = float(np.median(np.abs(K.diagonal())) / np.median(np.abs(Ms.diagonal())))
        lam = np.sort(eigsh_repeatable(sp.csc_matrix(K), k=modes, M=Ms, sigma=-1e-6 * scale, which="LM",
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
        ``{"stuck" | "free": ndarray}``: natural frequencies (rad/s) of the
        system with its contacts stuck at the static state, and without
        contacts; shape ``(k, modes)``, or ``(k, D, modes)`` for a cyclic
        sector (``[:, i]`` the modes of nodal diameter ``nodal_diameters[i]``).
    engine_orders : ndarray of int, shape (e,)
        The engine orders drawn, ``f = EO Omega / 2 pi``.
    crossings : list of dict
        One per crossing: ``system``, ``mode`` (1: the lowest, of its diameter
        for a cyclic sector), ``engine_order``, ``speed`` (rad/s) and
        ``frequency`` (rad/s, ``= EO speed``); for a cyclic sector also
        ``nodal_diameter`` (the one the engine order excites, :func:`excited_diameter`).
    nodal_diameters : ndarray of int, shape (D,), or None
        A cyclic sector's nodal diameters (None: a plain structure).
    sectors : int or None
        A cyclic sector's number of sectors ``N`` (None: a plain structure).
    """

    speeds: np.ndarray
    frequencies: dict = field(repr=False)
    engine_orders: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    crossings: list = field(default_factory=list)
    nodal_diameters: np.ndarray | None = None
    sectors: int | None = None

    def hertz(self, system: str = "stuck") -> np.ndarray:
        """Natural frequencies of ``system`` ("stuck" or "free") in Hz, ``(k, modes)`` (``(k, D, modes)`` cyclic)."""
        system = _checks.one_of("system", system, tuple(self.frequencies))
        return self.frequencies[system] / (2 * np.pi)

    def _curves(self):
        """``(system, diameter or None, mode index, frequencies (k,) rad/s)`` of every curve."""
        for system, f in self.frequencies.items():
            if self.nodal_diameters is None:
                for j in range(f.shape[1]):
                    yield system, None, j, f[:, j]
            else:
                for i, d in enumerate(self.nodal_diameters):
                    for j in range(f.shape[2]):
                        yield system, int(d), j, f[:, i, j]

    def columns(self) -> dict:
        """The curves (one row per speed) and the crossings (padded), as named columns with units (for CSV).

        A curve's column is ``"<system> mode <j> [Hz]"``, for a cyclic sector
        ``"<system> ND <d> mode <j> [Hz]"``; the crossings' columns start with
        ``"crossing"``.
        """
        out = {"speed [rad/s]": self.speeds, "speed [rpm]": self.speeds * RPM}
        for system, d, j, f in self._curves():
            nd = "" if d is None else f"ND {d} "
            out[f"{system} {nd}mode {j + 1} [Hz]"] = f / (2 * np.pi)
        x = self.crossings
        out.update({"crossing system": np.array([c["system"] for c in x], dtype=str)})
        if self.nodal_diameters is not None:
            out["crossing nodal diameter [-]"] = np.array([c["nodal_diameter"] for c in x], dtype=int)
        out.update({"crossing mode [-]": np.array([c["mode"] for c in x], dtype=int),
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
        """Modes against speed (rpm; stuck solid, free dashed), engine-order lines and crossings (Hz); the Axes.

        One colour per mode, or per nodal diameter for a cyclic sector (its
        crossings marked in that colour, labelled with the diameter).
        """
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(7, 5))
        rpm = self.speeds * RPM
        styles = {"stuck": "-", "free": "--"}
        cyclic = self.nodal_diameters is not None
        labelled = set()
        for system, d, j, f in self._curves():
            key = (system, d) if cyclic else (system,)
            colour = f"C{(list(self.nodal_diameters).index(d) if cyclic else j) % 10}"
            label = None if key in labelled else (f"{system} ND {d}" if cyclic else system)
            labelled.add(key)
            ax.plot(rpm, f / (2 * np.pi), styles[system], color=colour, label=label, lw=1.0)
        top = max(float(np.max(f)) for f in self.frequencies.values()) / (2 * np.pi) if self.frequencies else 1.0
        for eo in self.engine_orders:
            ax.plot(rpm, eo * self.speeds / (2 * np.pi), ":", color="0.5", lw=0.8)
            text = f"EO{eo}" if not cyclic else f"EO{eo} (ND {excited_diameter(int(eo), self.sectors)})"
            ax.annotate(text, (rpm[-1], eo * self.speeds[-1] / (2 * np.pi)), fontsize=7, color="0.4")
        if self.crossings:
            ax.plot([c["speed"] * RPM for c in self.crossings],
                    [c["frequency"] / (2 * np.pi) for c in self.crossings], "o", mfc="none", color="k",
                    label="crossings")
        ax.set_ylim(0.0, 1.1 * top)
        ax.set_xlabel("rotation speed (rpm)")
        ax.set_ylabel("frequency (Hz)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7 if cyclic else None)
        return ax


def _diameters(sector, nodal_diameters) -> list:
    """The nodal diameters asked, checked against the sector (``[None]`` for a plain structure)."""
    if sector is None:
        if nodal_diameters is not None:
            raise ValueError(f"nodal_diameters is only for a cyclic sector (SpeedModel(..., cyclic=)); this model is "
                             f"not cyclic, got nodal_diameters = {nodal_diameters!r}")
        return [None]
    top = sector.sectors // 2
    if nodal_diameters is None:
        return list(range(top + 1))
    if isinstance(nodal_diameters, (str, bytes, int, float)) or not hasattr(nodal_diameters, "__len__"):
        raise TypeError(f"nodal_diameters must be a sequence of integers (0 to {top}), got {nodal_diameters!r}")
    out = []
    for i, d in enumerate(nodal_diameters):
        d = _checks.positive_int(f"nodal_diameters[{i}]", d, minimum=0)
        if d > top:
            raise ValueError(f"nodal_diameters[{i}] must be at most {top} (N // 2 for N = {sector.sectors} sectors: "
                             f"diameter d and N - d are the same modes), got {d}")
        if d in out:
            raise ValueError(f"nodal_diameters must be distinct: {d} is given twice")
        out.append(d)
    if not out:
        raise ValueError("nodal_diameters must hold at least one nodal diameter")
    return sorted(out)


def campbell(model: SpeedModel, speeds, *, modes: int = 6, engine_orders=(1, 2, 3, 4, 5, 6),
             contacts: str = "both", nodal_diameters=None, progress: bool = False) -> CampbellDiagram:
    """The Campbell diagram of a speed-dependent structure, or of a cyclic sector's nodal diameters.

    Parameters
    ----------
    model : SpeedModel
        The structure at any speed; with ``cyclic=`` a sector of a disk of
        ``N`` sectors, whose modes are solved in each nodal diameter.
    speeds : array_like, shape (k,)
        Rotation speeds (rad/s, or strings such as ``"3000 rpm"``), >= 0,
        increasing, at least 2.
    modes : int, default 6
        Number of modes per system (per nodal diameter for a cyclic sector).
    engine_orders : sequence of int, default 1..6
        Engine orders (>= 1) of the lines ``f = EO Omega / 2 pi``.
    contacts : {"both", "stuck", "free"}
        The systems: contacts stuck at their static state, no contacts, or both.
    nodal_diameters : sequence of int, optional
        Cyclic sector only: the diameters solved (0 to ``N // 2``); default
        all. An engine order's crossings are looked for only in the diameter
        it excites (:func:`excited_diameter`), when that one is solved.
    progress : bool, default False
        One line per speed and system on standard error, and a note while
        the crossings are refined.

    Returns
    -------
    CampbellDiagram
        Each crossing of a mode with an engine-order line between consecutive
        speeds, refined by ``brentq`` (each function evaluation an eigen-solve
        at that speed; the static state solved again there for the stuck system)
        to ``1e-13`` relative in speed. Modes are numbered by ascending
        frequency at each speed (no tracking through veerings); in a diameter
        ``0 < d < N/2`` each frequency stands for a pair of modes (the
        forward and backward travelling waves), counted once.

    Examples
    --------
    >>> import numpy as np
    >>> K0 = np.array([[2e6, -1e6], [-1e6, 1e6]])
    >>> m = SpeedModel(np.eye(2), None, [K0, K0 + 1e5 * np.eye(2)], [0.0, 1000.0])
    >>> d = campbell(m, np.linspace(0.0, 2000.0, 5), modes=2, engine_orders=[1], contacts="free")
    >>> [(c["mode"], round(c["speed"], 1)) for c in d.crossings]
    [(1, 651.5), (2, 1705.6)]
    """
    if not isinstance(model, SpeedModel):
        raise TypeError(f"model must be a microslip SpeedModel, got {type(model).__name__}")
    speeds = rotation_speeds("speeds", speeds)
    if speeds.size < 2 or np.any(np.diff(speeds) <= 0):
        raise ValueError(f"speeds must be at least 2 increasing rotation speeds (rad/s), got {speeds.tolist()}")
    contacts = _checks.one_of("contacts", contacts, ("both",) + SYSTEMS)
    systems = SYSTEMS if contacts == "both" else (contacts,)
    if isinstance(engine_orders, (str, bytes, int, float)) or not hasattr(engine_orders, "__len__"):
        raise TypeError(f"engine_orders must be a sequence of integers, got {engine_orders!r}")
    eos = np.array([_checks.positive_int(f"engine_orders[{i}]", e) for i, e in enumerate(engine_orders)], dtype=int)
    progress = _checks.flag("progress", progress)
    sector = model.at(float(speeds[0]), contacts=False) if model._cyclic is not None else None
    diameters = _diameters(sector, nodal_diameters)
    with_damper = model.damper is not None
    free = model.ndof if sector is None else sector.independent.size
    modes = _checks.positive_int("modes", modes)
    sizes = {"free": free, "stuck": free + 3 * with_damper}
    limit = min(n if n <= DENSE else n - 1 for n in (sizes[system] for system in systems))
    if modes > limit:
        where = "" if sector is None else " in a nodal diameter: the sector's DOFs besides its right boundary"
        raise ValueError(f"modes must be at most {limit} (the DOFs of the systems{where}), got {modes}")
    if speeds[0] == 0.0 and with_damper and "stuck" in systems:
        raise ValueError("speeds must be > 0 rad/s for the stuck system with a damper: its load m r Omega^2 is zero "
                         "at rest")

    def freqs(system: str, omega: float, which) -> np.ndarray:
        """``(len(which), modes)`` natural frequencies (rad/s) of ``system`` at ``omega`` in the diameters ``which``."""
        s = model.at(omega, contacts=system == "stuck")
        return np.array([eigenfrequencies(K, M, modes) for K, M in _stuck_systems(s, which)])

    report = Progress(len(systems) * (speeds.size + 1), enabled=progress)
    table, crossings = {}, []
    for system in systems:
        rows = []
        for w in speeds:
            report.step(f"{system} system at {w:.6g} rad/s ({w * RPM:.6g} rpm)")
            rows.append(freqs(system, w, diameters))
        f = np.array(rows)  # (k, D, modes)
        table[system] = f[:, 0] if sector is None else f
        report.step(f"{system} system: the crossings")
        for i, d in enumerate(diameters):
            for j in range(modes):
                for eo in eos:
                    if d is not None and excited_diameter(int(eo), sector.sectors) != d:
                        continue  # this engine order does not excite diameter d
                    g = f[:, i, j] - eo * speeds
                    found = []
                    for k in range(speeds.size - 1):
                        if g[k] == 0.0:
                            found.append(float(speeds[k]))
                        elif g[k] * g[k + 1] < 0.0:
                            report.note(f"refining {system} mode {j + 1}{'' if d is None else f' ND {d}'} x EO{eo} "
                                        f"near {speeds[k]:.6g} rad/s")
                            found.append(brentq(lambda w: freqs(system, w, [d])[0, j] - eo * w, speeds[k],
                                                speeds[k + 1], xtol=1e-13 * float(speeds[k + 1]),
                                                rtol=4 * np.finfo(float).eps, maxiter=200))
                    if g[-1] == 0.0:
                        found.append(float(speeds[-1]))
                    for root in found:
                        crossing = {"system": system, "mode": j + 1, "engine_order": int(eo), "speed": float(root),
                                    "frequency": float(eo * root)}
                        if d is not None:
                            crossing["nodal_diameter"] = d
                        crossings.append(crossing)
    report.done("Campbell diagram")
    crossings.sort(key=lambda c: (c["system"], c["speed"]))
    if sector is None:
        return CampbellDiagram(speeds, table, eos, crossings)
    return CampbellDiagram(speeds, table, eos, crossings, np.array(diameters, dtype=int), sector.sectors)


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
