"""Mistuned bladed disks: random blade stiffness scatter and the assembled disk.

A tuned disk of ``N`` identical sectors is solved on one sector under an
engine order (:class:`~microslip.frequency.CyclicStructure`). Real blades
differ slightly: blade ``s``'s stiffness is ``(1 + delta_s)`` times the nominal
one, ``delta_s`` drawn from ``normal(0, std)`` (:func:`blade_scatter`). This
breaks the cyclic symmetry, so the whole disk is assembled
(:func:`mistuned_disk`) and solved with a reduction on the contact and
excitation DOFs::

    disk = mistuned_disk(sector, blade_scatter(sector.sectors, 0.02, seed=1, sample=k))
    result = frequency_response(disk, sector.travelling_wave(force, eo), omega, reduction="exact")
    factor = blade_peaks(result, sector, tip).max() / tuned.peak(tip)[1]

where ``tuned = frequency_response(sector, force, omega, engine_order=eo)``:
the amplification factor (:func:`~microslip.frequency.analyses.blade_peaks.amplification_factor`), the largest blade
amplitude over the tuned one. For a linear disk (one mode family, weak
coupling) it does not exceed Whitehead's limit ``(1 + sqrt(N)) / 2``.
"""

from __future__ import annotations


import numpy as np

from ...common import _checks
from .cyclic import CyclicStructure, _dof_list
from .structure import Structure

#: the largest standard deviation :func:`blade_scatter` accepts: a blade stiffness scatter is a few percent;
#: at 0.25 a draw below -4 std (1 + delta <= 0) has a chance of 3e-5 per blade
MAX_STD = 0.25


def blade_scatter(sectors: int, std: float, *, seed: int, sample: int) -> np.ndarray:
    """Relative stiffness deviation of each blade, ``delta_s ~ normal(0, std)``, reproducible.

    Parameters
    ----------
    sectors : int
        Number of blades ``N`` (at least 3, as a :class:`~microslip.frequency.CyclicStructure`).
    std : float
        Standard deviation of the relative deviation (dimensionless, e.g.
        ``0.02`` for 2 %), ``0 <= std <= 0.25``.
    seed : int
        The study's random seed (``>= 0``).
    sample : int
        The Monte Carlo sample (``>= 0``): each ``(seed, sample)`` gives its own
        draw, the same on every machine and in any order
        (``numpy.random.default_rng([seed, sample])``).

    Returns
    -------
    ndarray, shape (sectors,)
        ``delta_s``: blade ``s``'s stiffness is ``(1 + delta_s)`` times the nominal one.

    Raises
    ------
    ValueError
        For ``std`` out of range, or a draw with ``1 + delta_s <= 0`` (a
        blade without stiffness: ``std`` far too large).
    """
    n = _checks.size("sectors", sectors, minimum=3)
    sd = _checks.in_range("std", std, 0.0, MAX_STD)
    seed = _checks.positive_int("seed", seed, minimum=0)
    sample = _checks.positive_int("sample", sample, minimum=0)
    delta = np.random.default_rng([seed, sample]).normal(0.0, 1.0, n) * sd
    _check_scatter("std", delta, n, f"std = {sd!r} (a blade stiffness scatter is a few percent)")
    return delta


def _check_scatter(name: str, delta: np.ndarray, sectors: int, hint: str) -> None:
    """Refuse a scatter with a blade of no stiffness, ``1 + delta_s <= 0``."""
    bad = np.flatnonzero(1.0 + delta <= 0.0)
    if bad.size:
        s = int(bad[0])
        raise ValueError(f"{name}: blade {s} of {sectors} would have 1 + delta = {float(1.0 + delta[s])!r} <= 0 with {hint}; "
                         f"expected a small relative scatter, 1 + delta > 0 for every blade")


def mistuned_disk(sector: CyclicStructure, scatter, *, blade_dofs=None) -> Structure:
    """The whole disk with blade ``s``'s stiffness scaled by ``1 + scatter[s]``.

    Parameters
    ----------
    sector : CyclicStructure
        The tuned sector (matrices in SI units, contacts, dampers, static forces).
    scatter : array_like, shape (sectors,)
        Relative stiffness deviation of each blade (dimensionless, from
        :func:`blade_scatter`); finite, ``1 + scatter > 0``.
    blade_dofs : array_like of int, optional
        The sector's DOFs whose stiffness is the blade's: entries ``K[i, j]``
        with ``i`` and ``j`` both in ``blade_dofs`` are scaled. Default every DOF
        of the sector; with an :class:`~microslip.frequency.UnderPlatformDamper`
        attached pass ``range(n)``, ``n`` the bare sector's DOFs, so the
        damper's DOFs keep their stiffness.

    Returns
    -------
    Structure
        As :meth:`CyclicStructure.assembled`: sector ``s``'s independent DOFs
        at ``s * len(sector.independent) + k``, every contact copied (named
        ``"<name>@<s>"``), preloads and static forces. Zero scatter gives the
        tuned disk exactly.
    """
    if not isinstance(sector, CyclicStructure):
        raise TypeError(f"sector must be a microslip CyclicStructure, got {type(sector).__name__}")
    delta = _checks.real_array("scatter", scatter)
    if delta.shape != (sector.sectors,):
        raise ValueError(f"scatter must have shape ({sector.sectors},), one value per sector, got shape {delta.shape}")
    _check_scatter("scatter", delta, sector.sectors, "this scatter")
    dofs = None
    if blade_dofs is not None:
        dofs = _dof_list("blade_dofs", blade_dofs, sector.ndof)
        if not dofs.size:
            raise ValueError("blade_dofs must name at least one DOF of the sector, got none")
    return sector.assembled(1.0 + delta, scaled_dofs=dofs)
