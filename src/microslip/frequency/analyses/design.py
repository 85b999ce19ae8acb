"""The damper design curve: peak response against the damper's centrifugal load.

For each load the damper is attached to the structure and the forced response
is followed over the frequency range; the curve of the peak response against the
load is the plot engineers use to choose a damper: at low load the damper slides
and damps little, at high load it sticks and the system stiffens, the optimum
lies between.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field

import numpy as np

from ...common import _checks
from ...common._io import write_csv
from ...common._progress import Progress
from ..structures.damper import UnderPlatformDamper
from .response import FrequencyResponse, frequency_response
from ..structures.structure import Structure


@dataclass(frozen=True, eq=False)
class DesignCurve:
    """Peak response against the damper's centrifugal load (from :func:`damper_design_curve`).

    Attributes
    ----------
    loads : ndarray, shape (k,)
        Centrifugal loads of the damper (N).
    peak_amplitude : ndarray, shape (k,)
        Largest response of the output DOF over the frequency range (m): the
        largest deviation from its static value over a period.
    peak_frequency : ndarray, shape (k,)
        Excitation frequency of that peak (rad/s).
    responses : list of FrequencyResponse
        The forced response at every load.
    dof : int
        The output DOF (numbered as in the structure without the damper).
    """

    loads: np.ndarray
    peak_amplitude: np.ndarray
    peak_frequency: np.ndarray
    responses: list = field(repr=False)
    dof: int = 0

    @property
    def optimum(self) -> tuple[float, float]:
        """``(load, peak)``: the load (N) with the lowest peak response (m), among the loads computed."""
        i = int(np.argmin(self.peak_amplitude))
        return float(self.loads[i]), float(self.peak_amplitude[i])

    def columns(self) -> dict:
        """The curve as named columns with units (for CSV)."""
        return {"centrifugal load [N]": self.loads, "peak amplitude [m]": self.peak_amplitude,
                "peak frequency [rad/s]": self.peak_frequency,
                "peak frequency [Hz]": self.peak_frequency / (2 * np.pi)}

    def to_csv(self, path):
        """Write :meth:`columns` to ``path`` as CSV (atomically). Returns the path."""
        path = _checks.file_path("path", path)
        return write_csv(path, self.columns())

    def plot(self, ax=None, *, unit: str = "µm"):
        """Plot the peak response against the centrifugal load, the optimum marked; returns the Axes."""
        import matplotlib.pyplot as plt

        from ...common.units import plot_factor

        factor = plot_factor(unit)
        if ax is None:
            _, ax = plt.subplots(figsize=(6, 4))
        ax.plot(self.loads, self.peak_amplitude * factor, "o-", label="peak response")
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
    responses: list[FrequencyResponse] = []
    peaks, where = np.empty(loads.size), np.empty(loads.size)
    for k, load in enumerate(loads):
        d = copy.copy(damper)
        d.centrifugal_load = float(load)
        s = d.attach(structure)
        r = frequency_response(s, _padded(force, structure.ndof), omega, harmonics=harmonics, **options)
        where[k], peaks[k] = r.peak(dof)
        responses.append(r)
        report.step(f"load {load:.4g} N: peak {peaks[k]:.4g} m at {where[k]:.6g} rad/s")
    report.done(f"design curve: {loads.size} loads")
    return DesignCurve(loads, peaks, where, responses, dof)


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
