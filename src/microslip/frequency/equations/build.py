"""The one place where a structure becomes its harmonic balance equations.

Every analysis (forced responses, the static state, nonlinear modes, stability)
asks :func:`build_equations` for a static problem and a dynamic one that share
one condensation of the linear structure. A cyclic sector is a case of the same
path: its reduction is chosen and its linear part condensed in each harmonic's
nodal diameter (:mod:`~microslip.frequency.reduction.choice`), and its
equations are :class:`~.cyclic_balance.CyclicHarmonicBalance`.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..aft import MAX_PERIODS
from ..reduction.choice import (choose_reduction, cyclic_linear_part, cyclic_reduction, interface_dominated,
                                linear_part, retained_dofs)
from ..structures.cyclic import CyclicStructure
from ..structures.structure import Structure
from .cyclic_balance import CyclicHarmonicBalance
from .epmc import DampedBalance, DampedCyclicBalance, DampedReducedBalance
from .hbm import HarmonicBalance, excitation
from .interface import InterfaceBalance
from .reduced import ReducedHarmonicBalance


class Equations(NamedTuple):
    """A static problem and the harmonic balance equations, sharing one condensation.

    Attributes
    ----------
    static : HarmonicBalance
        The static problem (``H = 0``) under the static force.
    dynamic : HarmonicBalance
        The harmonic balance equations with ``H`` harmonics (with the damping
        ``C - xi M`` of a nonlinear mode when built ``damped``).
    reduction : str
        ``"none"``, ``"exact"`` or ``"modal"``: ``"auto"`` resolved.
    modes : int or None
        Modes of a modal reduction.
    """

    static: HarmonicBalance
    dynamic: HarmonicBalance
    reduction: str
    modes: int | None


def build_equations(structure: Structure, force, static_force, harmonics: int, *, engine_order: int | None = None,
                    samples: int | None = None, max_periods: int = MAX_PERIODS, reduction: str = "auto",
                    modes: int | None = None, damped: bool = False) -> Equations:
    """The static and the dynamic equations of ``structure`` (arguments checked by the caller).

    Parameters
    ----------
    structure : Structure or CyclicStructure
        The structure with its contacts (a sector: solved in ``engine_order``'s
        nodal diameters).
    force : array_like or mapping
        Excitation (N), see :func:`~.hbm.excitation`; ``{}`` for a nonlinear mode.
    static_force : mapping
        The static part of ``force`` (N), for the static problem.
    harmonics : int
        ``H``.
    engine_order : int or None
        A sector's engine order (a nonlinear mode's nodal diameter); None for
        a structure that is not cyclic.
    samples, max_periods
        The AFT's samples per period and its largest number of periods.
    reduction : {"auto", "none", "exact", "modal"}
        See :func:`~microslip.frequency.reduction.choice.choose_reduction`.
    modes : int or None
        Modes of a modal reduction.
    damped : bool
        The dynamic equations carry the damping ``C - xi M`` of the extended
        periodic motion concept (:mod:`~.epmc`).

    Returns
    -------
    Equations
    """
    loads = excitation(structure, force, harmonics)
    loads[0] += structure.preload_force()
    kw = dict(samples=samples, max_periods=max_periods)
    if isinstance(structure, CyclicStructure):
        reduction, modes = cyclic_reduction(structure, reduction, modes)
        if damped and reduction == "modal":
            raise ValueError("reduction: a sector's nonlinear mode is condensed exactly in each harmonic's nodal "
                             "diameter; use reduction='exact' or 'auto' (a modal condensation of a sector with the "
                             "mode's negative damping is not available)")
        linear = cyclic_linear_part(structure, loads, engine_order, reduction, modes, harmonics)
        dynamic = DampedCyclicBalance if damped else CyclicHarmonicBalance
        return Equations(CyclicHarmonicBalance(structure, static_force, 0, engine_order, linear),
                         dynamic(structure, force, harmonics, engine_order, linear, **kw), reduction, modes)
    retained = retained_dofs(structure, loads)
    reduction, modes = choose_reduction(structure, harmonics, reduction, modes, retained.size)
    if reduction == "none" and interface_dominated(structure, harmonics, retained.size):
        # every DOF an unknown, the Jacobian in its parts (harmonic blocks, contacts) for the solvers
        dynamic = InterfaceBalance(structure, {} if damped else force, harmonics, **kw)
        return Equations(HarmonicBalance(structure, static_force, 0), dynamic, reduction, modes)
    if reduction == "none":
        dynamic = DampedBalance(structure, harmonics, **kw) if damped else HarmonicBalance(structure, force, harmonics,
                                                                                            **kw)
        return Equations(HarmonicBalance(structure, static_force, 0), dynamic, reduction, modes)
    linear = linear_part(structure, retained, reduction, modes)
    dynamic = DampedReducedBalance if damped else ReducedHarmonicBalance
    return Equations(ReducedHarmonicBalance(structure, static_force, 0, linear),
                     dynamic(structure, force, harmonics, linear, **kw), reduction, modes)


def release_friction(static: HarmonicBalance) -> HarmonicBalance:
    """The static problem ``static`` (``H = 0``) with its contacts' friction released, in place; returned.

    The contacts' tangential directions are taken out of the problem: they
    carry no tangential force and add no tangential stiffness, so its
    solution is the frictionless static equilibrium (the normal loads, which
    do not depend on the tangential displacement, are the contacts' own).
    """
    if static.H != 0:
        raise ValueError(f"static must be a static problem (H = 0), got H = {static.H}")
    for name in ("Bt", "Bt2", "Bt_next", "Gt"):  # the one- and two-direction, and a sector's next-sector, forms
        if hasattr(static, name):
            setattr(static, name, np.zeros_like(getattr(static, name)))
    return static
