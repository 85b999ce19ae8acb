"""Bolt and contact prestress, the jointed-structure procedure: :func:`prestress`.

A static step under the static loads (the contacts' preloads, the structure's
static forces such as centrifugal loads, and a given static load) with a chosen
friction state, then the dynamic analysis starting from that state:

* ``friction="released"`` -- the static step is frictionless (the contacts
  carry no tangential force, as when a joint is assembled and its bolts
  tightened while it may slide), then each contact's sliders are reset at its
  static displacement: the dynamic analysis begins stuck at the prestressed
  state with no tangential force;
* ``friction="stuck"`` -- the sliders stay at the unloaded state, the contacts
  are loaded from there with the rest of the static load (an element whose
  force would pass ``mu N`` slips statically), and the dynamic analysis goes
  on from that state.

The forced responses (:func:`~.response.frequency_response`,
:func:`~.response.frequency_point`), nonlinear modes
(:func:`~.nonlinear_modes.nonlinear_modes`) and time integration
(:func:`~.transient.steady_state`) take the result as ``prestress=``; it also
gives the prestressed structure's linear modes and a damping fitted on them
(:class:`~.prestressed.Prestress`).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ...common import _checks
from ...model import frozen
from ..aft import MAX_PERIODS
from ..equations.build import release_friction
from ..structures.cyclic import CyclicStructure
from ..structures.structure import Structure
from .prestressed import FRICTION_STATES, Prestress, _copy_structure
from .response import _equations, _static_state


def prestress(structure: Structure, load=None, *, friction: str = "released", reduction: str = "auto",
              modes: int | None = None, tolerance: float = 1e-10) -> Prestress:
    """The static state of a structure under its static loads with a chosen friction state.

    Parameters
    ----------
    structure : Structure or CyclicStructure
        The structure with its contacts; their ``preload`` and the structure's
        static forces (:meth:`~microslip.frequency.Structure.add_static_force`,
        e.g. centrifugal loads) are static loads of the prestress. A cyclic
        sector is prestressed as every sector of its disk (the static loads
        the same on every sector: nodal diameter 0).
    load : array_like or mapping, optional
        A further static load (N): ``ndof`` values or ``{dof: N}`` (DOF
        indices, or names ``"node:component"`` with a DOF map), real.
    friction : {"released", "stuck"}, default "released"
        ``"released"``: the static step without friction (no tangential
        contact force), then every contact's sliders reset at its static
        displacement, so the dynamic analysis starts stuck there with no
        tangential force. ``"stuck"``: the sliders held at the unloaded
        state, the contacts loaded tangentially from there (an element whose
        force would pass ``mu N_i`` slips statically).
    reduction, modes
        How the static problem is solved, as in
        :func:`~microslip.frequency.frequency_response` (the retained DOFs
        solved, then every DOF recovered).
    tolerance : float, default 1e-10
        Relative residual of Newton's method on the static problem.

    Returns
    -------
    Prestress
        The static state, the structure the dynamic analyses then solve
        (:attr:`Prestress.prestressed`), its linear modes (:meth:`Prestress.modes`).

    Raises
    ------
    TypeError, ValueError
        A parameter of the wrong type or value (the message names it); a
        structure with a direction that nothing but friction holds (it has no
        static equilibrium with the friction released).
    ConvergenceError
        When Newton's method fails on the static problem.

    Examples
    --------
    >>> p = prestress(structure, friction="released")                     # doctest: +SKIP
    >>> print(p.summary())                                                 # doctest: +SKIP
    >>> r = frequency_response(structure, force, (900, 1100), prestress=p)  # doctest: +SKIP
    """
    if not isinstance(structure, Structure):
        raise TypeError(f"structure must be a microslip Structure, got {type(structure).__name__}")
    cyclic = isinstance(structure, CyclicStructure)
    friction = _checks.one_of("friction", friction, FRICTION_STATES)
    tolerance = _checks.in_range("tolerance", tolerance, 0.0, 1.0, lo_open=True, hi_open=True)
    f = np.zeros(structure.ndof) if load is None else structure.force_vector(load, "load")
    if np.iscomplexobj(f):
        raise TypeError(f"load (a static force) must be real, got {_checks._show(load)}")
    loaded = _copy_structure(structure)
    loaded.static_force = structure.static_force + f
    # a sector's static state is the same in every sector: its diameter 0, which engine order 0 solves
    static, _, (reduction, _) = _equations(loaded, {}, 0, None, MAX_PERIODS, reduction, modes,
                                           engine_order=0 if cyclic else None)
    if friction == "released":
        release_friction(static)
    x, N0, T0, closed, T0_2 = _static_state(static, tolerance=tolerance)
    q = static._full(x, 1.0)[0]
    Bt, Bn, n0 = structure.contact_directions()
    if cyclic:  # the next sector stands as this one does, in its own frame
        Bt_next, Bn_next = structure.contact_directions_next()
        Bt, Bn = Bt + Bt_next, Bn + Bn_next
    t, t2, n = q @ Bt, q @ structure.second_tangential_directions(), q @ Bn + n0
    if friction == "released":  # every slider reset where its contact stands: no force, stuck from there
        loaded.contacts = [replace(c, reference=float(t[i]), reference2=float(t2[i]) if c.planar else 0.0)
                           for i, c in enumerate(structure.contacts)]
    return Prestress(structure, loaded, friction, frozen(f), frozen(q), frozen(N0), frozen(T0), frozen(T0_2),
                     np.array(closed, dtype=np.int64), frozen(t), frozen(t2), frozen(n), reduction)
