"""The damper design curve: peak response against the damper's centrifugal load.

For each load the damper is attached to the structure and the forced response
is followed over the frequency range; the curve of the peak response against the
load is the plot engineers use to choose a damper: at low load the damper slides
and damps little, at high load it sticks and the system stiffens, the optimum
lies between.
"""

from __future__ import annotations

import copy
import warnings
from dataclasses import dataclass, field

import numpy as np

from ...common import _checks
from ...common._io import write_csv
from ...common._progress import Progress
from ...common.report import plural
from ...common.errors import DesignPointWarning
from ..aft import NotPeriodicError
from ..numerics.continuation import ConvergenceError
from ..structures.damper import UnderPlatformDamper
from .response import (CurveInterrupted, FrequencyResponse, IncompleteCurveWarning, PeakOnEdgeWarning, edge_message,
                       frequency_response)
from ..structures.structure import Structure


#: what :attr:`DesignCurve.status` says of each load
STATUSES = ("peak", "incomplete curve", "peak on the range's edge", "failed")


@dataclass(frozen=True, eq=False)
class DesignCurve:
    """Peak response against the damper's centrifugal load (from :func:`damper_design_curve`).

    Attributes
    ----------
    loads : ndarray, shape (k,)
        Centrifugal loads of the damper (N).
    peak_amplitude : ndarray, shape (k,)
        Largest response of the output DOF over the frequency range (m): the
        largest deviation from its static value over a period (NaN where the
        forced response failed).
    peak_frequency : ndarray, shape (k,)
        Excitation frequency of that peak (rad/s; NaN where it failed).
    responses : list of FrequencyResponse
        The forced response at every load (None where it failed).
    dof : int
        The output DOF (numbered as in the structure without the damper).
    complete : ndarray of bool, shape (k,)
        The forced response reached the end of the frequency range (False: it
        stopped at ``StepControl.max_points``, or was interrupted).
    on_edge : ndarray of bool, shape (k,)
        The highest point of the forced response is an end of the curve
        (:meth:`FrequencyResponse.peak_on_edge
        <microslip.frequency.FrequencyResponse.peak_on_edge>`): the response
        still rises there and the resonance lies outside the range.
    errors : list of str, length k
        Why the forced response failed at each load ("" where it did not).

    A load whose curve is incomplete, whose highest point is on the range's
    edge or whose response failed has no trustworthy peak: :attr:`trusted` is
    False there, :attr:`optimum` leaves it out and :meth:`problems` says why.
    """

    loads: np.ndarray
    peak_amplitude: np.ndarray
    peak_frequency: np.ndarray
    responses: list = field(repr=False)
    dof: int = 0
    complete: np.ndarray | None = None
    on_edge: np.ndarray | None = None
    errors: list | None = None

    def __post_init__(self):
        k = np.size(self.loads)
        if self.complete is None:
            object.__setattr__(self, "complete", np.array([r is None or r.complete for r in self.responses]
                                                          if len(self.responses) == k else [True] * k, dtype=bool))
        if self.on_edge is None:
            object.__setattr__(self, "on_edge", np.zeros(k, dtype=bool))
        if self.errors is None:
            object.__setattr__(self, "errors", [""] * k)

    @property
    def trusted(self) -> np.ndarray:
        """``(k,)`` bool: the loads whose peak is a peak (a complete curve, its highest point inside the range)."""
        return self.complete & ~self.on_edge & np.array([not e for e in self.errors], dtype=bool)

    @property
    def status(self) -> list:
        """What each load's peak is, one of :data:`STATUSES`: ``"peak"`` (trusted), ``"incomplete curve"``,
        ``"peak on the range's edge"`` or ``"failed"``."""
        return [STATUSES[3] if e else STATUSES[1] if not c else STATUSES[2] if edge else STATUSES[0]
                for e, c, edge in zip(self.errors, self.complete, self.on_edge)]

    @property
    def optimum(self) -> tuple[float, float]:
        """``(load, peak)``: the load (N) with the lowest peak response (m), among the loads with a trusted peak.

        Raises
        ------
        ValueError
            When no load has one (:meth:`problems` says why).
        """
        trusted = self.trusted
        if not trusted.any():
            raise ValueError("the design curve has no optimum: no load has a trusted peak ("
                             + "; ".join(self.problems()) + ")")
        i = int(np.flatnonzero(trusted)[np.argmin(self.peak_amplitude[trusted])])
        return float(self.loads[i]), float(self.peak_amplitude[i])

    def problems(self) -> list:
        """One sentence per load left out of :attr:`optimum`: the load, why, and what to do."""
        out = []
        for k, status in enumerate(self.status):
            load = f"load {self.loads[k]:.4g} N"
            if status == "failed":
                out.append(f"{load}: the forced response failed: {self.errors[k]}")
            elif status == "incomplete curve":
                r = self.responses[k]
                reached = f" at omega = {r.omega[-1]:.6g} rad/s" if r is not None and r.points else ""
                out.append(f"{load}: the forced response stopped{reached} before the end of the frequency range, so "
                           f"its peak may lie beyond (raise the continuation's max_points)")
            elif status == "peak on the range's edge":
                w = self.peak_frequency[k]
                r = self.responses[k]
                low = r is not None and w <= min(r.omega[0], r.omega[-1])
                end, side, move = ("start", "below", "lower") if low else ("end", "above", "raise")
                out.append(f"{load}: the response is highest at the {end} of the frequency range ({w:.6g} rad/s, "
                           f"{w / (2 * np.pi):.6g} Hz) and still rises there: the resonance lies {side} it and the "
                           f"{self.peak_amplitude[k]:.4g} m there is no peak; {move} the {end} of the range past "
                           f"the resonance")
        return out

    def columns(self) -> dict:
        """The curve as named columns with units (for CSV), with each load's :attr:`status`."""
        return {"centrifugal load [N]": self.loads, "peak amplitude [m]": self.peak_amplitude,
                "peak frequency [rad/s]": self.peak_frequency,
                "peak frequency [Hz]": self.peak_frequency / (2 * np.pi),
                "complete [-]": self.complete.astype(int), "peak on edge [-]": self.on_edge.astype(int),
                "status": np.array(self.status)}

    def to_csv(self, path):
        """Write :meth:`columns` to ``path`` as CSV (atomically). Returns the path."""
        path = _checks.file_path("path", path)
        return write_csv(path, self.columns())

    def plot(self, ax=None, *, unit: str = "µm"):
        """Plot the peak response against the centrifugal load, the optimum marked and the loads left out of it
        crossed; returns the Axes."""
        import matplotlib.pyplot as plt

        from ...common.units import plot_factor

        factor = plot_factor(unit)
        if ax is None:
            _, ax = plt.subplots(figsize=(6, 4))
        trusted = self.trusted
        ax.plot(self.loads, np.where(trusted, self.peak_amplitude, np.nan) * factor, "o-", label="peak response")
        if not trusted.all():
            ax.plot(self.loads[~trusted], self.peak_amplitude[~trusted] * factor, "x", color="C3", ms=9,
                    label="no peak (incomplete curve, or highest on the range's edge)")
        if trusted.any():
            load, peak = self.optimum
            ax.plot([load], [peak * factor], "*", ms=14, label=f"lowest peak: {load:.4g} N")
        ax.set_xlabel("damper centrifugal load (N)")
        ax.set_ylabel(f"peak response of DOF {self.dof} ({unit})")
        ax.grid(True, alpha=0.3)
        ax.legend()
        return ax


def damper_design_curve(structure: Structure, damper: UnderPlatformDamper, loads, force, omega, *, dof: int,
                        harmonics: int = 5, progress: bool = False, **options) -> DesignCurve:
    """Peak forced response against the damper's centrifugal load, at one excitation level.

    Parameters
    ----------
    structure : Structure or CyclicStructure
        The structure without the damper.
    damper : UnderPlatformDamper
        The damper, with its interfaces (its own load is replaced by each of ``loads``).
    loads : array_like, shape (k,)
        Centrifugal loads to compute (N), positive.
    force : array_like or mapping
        Excitation of ``structure`` (N), as in :func:`frequency_response`
        (vectors of the structure's DOFs; the damper's DOFs are not excited).
    omega : (float, float)
        Frequency range (rad/s) around the resonance.
    dof : int
        The output DOF whose peak is read (of ``structure``).
    harmonics : int, default 5
        ``H``.
    progress : bool
        One line per load on standard error.
    **options
        Passed to :func:`frequency_response` (``engine_order``, ``reduction``, ``control``, ...).

    Returns
    -------
    DesignCurve
        Every load, each marked (:attr:`DesignCurve.status`): a forced response
        that fails at one load (Newton's method, a contact that never becomes
        periodic) leaves the others; a curve cut short or highest on an edge of
        the range gives no peak. Those loads are left out of the optimum.

    Raises
    ------
    CurveInterrupted
        On Ctrl-C (a ``KeyboardInterrupt``): its ``partial`` is the design curve
        of the loads finished, and of the one interrupted up to where its curve
        got (incomplete).

    Warns
    -----
    IncompleteCurveWarning, PeakOnEdgeWarning, DesignPointWarning
        For each load left out of the optimum (its curve cut short, highest on
        the range's edge, failed), naming the load.
    """
    if not isinstance(structure, Structure):
        raise TypeError(f"structure must be a microslip Structure, got {type(structure).__name__}")
    if not isinstance(damper, UnderPlatformDamper):
        raise TypeError(f"damper must be an UnderPlatformDamper, got {type(damper).__name__}")
    loads = _checks.positive_array("loads", loads, ndim=1, min_size=1)
    dof = _checks.positive_int("dof", dof, minimum=0)
    if dof >= structure.ndof:
        raise ValueError(f"dof: DOF {dof} is out of range for a structure with {structure.ndof} DOFs")
    if isinstance(force, dict):
        force = {h: structure.force_vector(v, f"force[{h}]") for h, v in force.items()}
    else:
        force = structure.force_vector(force, "force")
    report = Progress(loads.size, enabled=progress)
    responses: list[FrequencyResponse | None] = []
    peaks, where = np.full(loads.size, np.nan), np.full(loads.size, np.nan)
    edge, errors = np.zeros(loads.size, dtype=bool), [""] * loads.size

    def curve(k: int) -> DesignCurve:  # the loads up to k (excluded)
        return DesignCurve(loads[:k], peaks[:k], where[:k], responses[:k], dof, on_edge=edge[:k], errors=errors[:k])

    for k, load in enumerate(loads):
        d = copy.copy(damper)
        d.centrifugal_load = float(load)
        s = d.attach(structure)
        name = f"load {load:.4g} N"
        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                r = frequency_response(s, _padded(force, structure.ndof), omega, harmonics=harmonics, **options)
        except CurveInterrupted as exc:  # the curve so far, incomplete
            r = exc.partial
            responses.append(r)
            where[k], peaks[k] = _peak(r, dof, edge, k)
            raise CurveInterrupted(f"{name}: {exc}", curve(k + 1)) from None
        except KeyboardInterrupt:
            raise CurveInterrupted(f"interrupted before {name}", curve(k)) from None
        except (ConvergenceError, NotPeriodicError) as exc:
            errors[k] = str(exc)
            responses.append(None)
            warnings.warn(f"{name}: the forced response failed: {exc}; this load is left out of the design curve's "
                          f"optimum", DesignPointWarning, stacklevel=2)
            report.step(f"{name}: failed")
            continue
        for w in caught:  # the load's own warnings, the load named
            if issubclass(w.category, IncompleteCurveWarning):
                warnings.warn(f"{name}: {w.message}; this load is left out of the design curve's optimum",
                              IncompleteCurveWarning, stacklevel=2)
            else:
                warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
        responses.append(r)
        where[k], peaks[k] = _peak(r, dof, edge, k)
        if edge[k] and r.complete:  # an incomplete curve's warning says it already
            warnings.warn(f"{name}: {_edge_text(r, dof)}; this load is left out of the design curve's optimum",
                          PeakOnEdgeWarning, stacklevel=2)
        state = "" if r.complete and not edge[k] else " (incomplete curve)" if not r.complete else " (on the edge)"
        report.step(f"{name}: peak {peaks[k]:.4g} m at {where[k]:.6g} rad/s{state}")
    report.done(f"design curve: {plural(loads.size, 'load')}")
    return curve(loads.size)


def _peak(r: FrequencyResponse, dof: int, edge: np.ndarray, k: int) -> tuple[float, float]:
    """``r.peak(dof)``, its warning left to the caller, and ``edge[k]`` set when it lies on the range's edge."""
    edge[k] = r.peak_on_edge(dof)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PeakOnEdgeWarning)
        return r.peak(dof)


def _edge_text(r: FrequencyResponse, dof: int) -> str:
    return edge_message(r.omega, r.amplitude(dof), r.complete)


def _padded(force, ndof: int):
    """``force`` (vectors of ``ndof`` DOFs) with zeros for the damper's three DOFs (a vector, or a mapping's)."""
    if isinstance(force, dict):
        return {h: _padded(v, ndof) for h, v in force.items()}
    f = np.asarray(force)
    if f.shape != (ndof,):
        raise ValueError(f"force must be a vector of the structure's {ndof} DOFs (without the damper), "
                         f"got shape {f.shape}")
    out = np.zeros(ndof + 3, dtype=f.dtype)
    out[:f.size] = f
    return out
