"""Each blade's peak in a mistuned disk's response, and the amplification over the tuned disk.

A mistuned disk (:mod:`~microslip.frequency.structures.mistuning`) is solved
whole; :func:`blade_peaks` reads every blade's peak of one sector DOF from the
curve and :func:`amplification_factor` divides the largest by the tuned
sector's peak.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ...common import _checks
from ..structures.cyclic import CyclicStructure
from ..structures.structure import direction
from .response import FrequencyResponse, curve_peak


def blade_amplitudes(result: FrequencyResponse, sector: CyclicStructure, dof, *,
                     harmonic: int | None = None) -> np.ndarray:
    """The amplitude of one sector DOF in every blade of an assembled disk, along the curve (m).

    Parameters
    ----------
    result, sector, dof, harmonic
        As :func:`blade_peaks`.

    Returns
    -------
    ndarray, shape (points, sectors)
        Column ``s``: :meth:`FrequencyResponse.amplitude` of that DOF in sector ``s``.
    """
    if not isinstance(result, FrequencyResponse):
        raise TypeError(f"result must be a FrequencyResponse, got {type(result).__name__}")
    if not isinstance(sector, CyclicStructure):
        raise TypeError(f"sector must be a microslip CyclicStructure, got {type(sector).__name__}")
    whole = sector.sectors * sector.independent.size
    if result.engine_order is not None or result.structure.ndof != whole:
        raise ValueError(f"result must be a response of the whole disk assembled from sector ({sector.sectors} "
                         f"sectors, {whole} DOFs), got one of {result.structure.ndof} DOFs"
                         + (f" solved as a sector (engine_order = {result.engine_order})"
                            if result.engine_order is not None else ""))
    b = direction("dof", dof, sector.ndof, dof_map=sector.dof_map)
    if harmonic is not None:
        h = _checks.positive_int("harmonic", harmonic, minimum=1)
        if h > result.harmonics:
            raise ValueError(f"harmonic must be at most harmonics = {result.harmonics}, got {h}")
    # the DOF of blade s in its own frame, on the whole disk's DOFs (turned into the global frame in a Cartesian one)
    ws = [sector._sector_map(s).T @ b for s in range(sector.sectors)]
    full = _holding(result, np.concatenate([np.flatnonzero(w) for w in ws]))
    out = np.empty((result.points, sector.sectors))
    for s, w in enumerate(ws):
        out[:, s] = full.amplitude(w, harmonic)
    return out


def blade_peaks(result: FrequencyResponse, sector: CyclicStructure, dof, *, harmonic: int | None = None) -> np.ndarray:
    """The peak amplitude of one sector DOF in every blade of an assembled disk (m).

    Parameters
    ----------
    result : FrequencyResponse
        A response of the disk of :func:`mistuned_disk` (or
        :meth:`CyclicStructure.assembled`) of ``sector``.
    sector : CyclicStructure
        The sector the disk was assembled from.
    dof : int, str or mapping
        A DOF of the sector (index, name ``"node:component"`` with a DOF map,
        or ``{dof: coefficient}`` for a relative displacement), as
        :meth:`FrequencyResponse.amplitude` takes it.
    harmonic : int, optional
        ``h >= 1``: amplitude of harmonic ``h``; None: the largest deviation
        from the static value over a period.

    Returns
    -------
    ndarray, shape (sectors,)
        Blade ``s``'s peak (m): the highest point of that DOF's curve in
        sector ``s``, refined by a parabola as :meth:`FrequencyResponse.peak`,
        so a tuned disk gives the sector solution's ``peak(dof)`` in every
        blade. With ``harmonic=None`` the maximum over a period is taken on
        256 samples, each blade at its own phase of the travelling wave: a
        tuned disk's blades then differ by up to ``1 - cos(pi / 256)``
        (7.5e-5) of the amplitude (exactly equal with ``harmonic``).
    """
    curves = blade_amplitudes(result, sector, dof, harmonic=harmonic)
    return np.array([curve_peak(result.omega, curves[:, s])[1] for s in range(sector.sectors)])


def _holding(result: FrequencyResponse, needed: np.ndarray) -> FrequencyResponse:
    """``result`` itself when it holds the ``needed`` DOFs, else a copy holding them, recovered once per point."""
    needed = np.unique(needed)
    if np.isin(needed, result.dofs).all():
        return result
    if result.recovery is None:
        raise ValueError("dof: this result keeps only its retained DOFs and cannot recover others")
    coefficients = np.array([result.recovery(k)[:, needed] for k in range(result.points)])
    return replace(result, coefficients=coefficients, dofs=needed, recovery=None)


def amplification_factor(result: FrequencyResponse, tuned: FrequencyResponse, sector: CyclicStructure, dof, *,
                         harmonic: int | None = None) -> float:
    """The largest blade peak of a mistuned disk over the tuned sector's peak (dimensionless).

    Parameters
    ----------
    result : FrequencyResponse
        The disk's response (:func:`mistuned_disk` solved with the force of
        :meth:`CyclicStructure.travelling_wave`).
    tuned : FrequencyResponse
        ``sector``'s own response under the same force and engine order
        (``frequency_response(sector, force, omega, engine_order=eo)``).
    sector, dof, harmonic
        As :func:`blade_peaks`.

    Returns
    -------
    float
        ``max_s blade_peaks[s] / tuned.peak(dof)`` amplitude: 1 for a tuned disk.
    """
    if not isinstance(tuned, FrequencyResponse):
        raise TypeError(f"tuned must be the FrequencyResponse of the cyclic sector, got {type(tuned).__name__}")
    if tuned.engine_order is None:
        raise ValueError(f"tuned must be the response of the cyclic sector (solved with engine_order), got one of a "
                         f"structure of {tuned.structure.ndof} DOFs without an engine order")
    peaks = blade_peaks(result, sector, dof, harmonic=harmonic)
    reference = tuned.peak(dof, harmonic)[1]
    if not reference > 0:
        raise ValueError(f"tuned: the sector's peak amplitude of dof {dof!r} is {reference!r} m; expected > 0")
    return float(peaks.max() / reference)
