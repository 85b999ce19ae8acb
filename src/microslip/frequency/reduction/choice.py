"""Which reduction a solve uses, and the condensed linear structure it builds.

``reduction="auto" | "none" | "exact" | "modal"`` of the solvers is resolved here
(:func:`choose_reduction`, :func:`cyclic_reduction` for a sector), the DOFs the
equations keep are found (:func:`retained_dofs`, :func:`cyclic_retained`) and
the linear structure is condensed onto them (:func:`linear_part`,
:func:`cyclic_linear_part`: a sector in each harmonic's nodal diameter).
"""

from __future__ import annotations

import numpy as np

from ...common import _checks
from ..numerics.blas import DENSE_LIMIT
from ..structures.cyclic import CyclicStructure
from ..structures.structure import Structure
from .condensation import Condensation
from .cyclic_modal import CyclicModalCondensation
from .modal import ModalCondensation

REDUCTIONS = ("auto", "none", "exact", "modal")
#: DOFs up to which ``"auto"`` condenses exactly (above: modal)
EXACT_LIMIT = 5000
#: DOFs from which ``"auto"`` condenses a small dense structure that keeps at most a quarter of them: a nonlinear
#: mode of a 40-DOF chain with 4 contacts took 0.67 s on every DOF against 0.27 s condensed (60 DOFs, 6
#: contacts: 4.8 s against 0.75 s), its forced response 0.40 s against 0.16 s; at 20 DOFs with 4 contacts both
#: about equal, at 10 DOFs with 2 every DOF was faster (0.06 against 0.09 s)
FEW_RETAINED_MIN_DOFS = 20
#: normal modes ``"auto"`` keeps for a modal reduction
DEFAULT_MODES = 60
#: share of the DOFs the equations would keep above which a structure is interface-dominated: ``"auto"`` then
#: condenses nothing (a condensation that keeps most DOFs costs more than it removes)
INTERFACE_SHARE = 0.5
#: unknowns ``(2H+1) ndof`` up to which an interface-dominated structure is solved on every DOF with its
#: Jacobian in parts (:mod:`~microslip.frequency.equations.interface`): now and then it factorises the dense
#: Schur complement of the contact unknowns, the size of the matrix the exact condensation would factorise
#: at every Newton iteration (at this limit, about 5 GB in double precision while it is assembled)
INTERFACE_LIMIT = 26000


def interface_dominated(structure: Structure, harmonics: int, retained: int | None) -> bool:
    """True when the contacts, excitation and preloads use more than :data:`INTERFACE_SHARE` of the DOFs and the
    equations on every DOF are above the small dense size (:data:`~microslip.frequency.numerics.blas.DENSE_LIMIT`)
    and at most :data:`INTERFACE_LIMIT` unknowns."""
    n = (2 * harmonics + 1) * structure.ndof
    return retained is not None and retained > INTERFACE_SHARE * structure.ndof and DENSE_LIMIT < n <= INTERFACE_LIMIT


def retained_dofs(structure: Structure, f_ext: np.ndarray) -> np.ndarray:
    """DOFs the reduced equations keep: those the contacts' directions or the excitation/preloads touch."""
    Bt, Bn, _ = structure.contact_directions()
    used = np.any(Bt != 0, axis=1) | np.any(Bn != 0, axis=1) | np.any(f_ext != 0, axis=0)
    used |= np.any(structure.second_tangential_directions() != 0, axis=1)
    return np.flatnonzero(used)


def choose_reduction(structure: Structure, harmonics: int, reduction: str, modes,
                     retained: int | None = None) -> tuple[str, int | None]:
    """``(reduction, modes)`` checked, ``"auto"`` resolved by size.

    ``"auto"``: ``"none"`` while the full dense equations are small
    (``(2H+1) ndof <=`` :data:`~microslip.frequency.numerics.blas.DENSE_LIMIT`), unless the structure has
    at least :data:`FEW_RETAINED_MIN_DOFS` DOFs of which the equations would
    keep (``retained``, the DOFs the contacts, excitation and preloads use) at
    most a quarter: then ``"exact"``, as up to :data:`EXACT_LIMIT` DOFs;
    ``"modal"`` with :data:`DEFAULT_MODES` modes above. An interface-dominated
    structure (:func:`interface_dominated`: the equations would keep most
    DOFs) is not condensed: ``"none"``.
    """
    if not isinstance(reduction, str) or reduction not in REDUCTIONS:
        raise ValueError(f"reduction must be one of {', '.join(map(repr, REDUCTIONS))}, got {reduction!r}")
    ndof = structure.ndof
    if modes is not None:
        modes = _checks.positive_int("modes", modes)
        if modes >= ndof:
            raise ValueError(f"modes must be below the number of DOFs ({ndof}), got {modes}")
        if reduction not in ("modal", "auto"):
            raise ValueError(f"modes is used only with reduction='modal', got reduction={reduction!r}")
        if reduction == "auto":
            reduction = "modal"
    if reduction == "auto":
        few = retained is not None and ndof >= FEW_RETAINED_MIN_DOFS and 4 * retained <= ndof
        if (2 * harmonics + 1) * ndof <= DENSE_LIMIT and not few or interface_dominated(structure, harmonics, retained):
            reduction = "none"
        elif ndof <= EXACT_LIMIT:
            reduction = "exact"
        else:
            reduction = "modal"
    if reduction == "modal" and modes is None:
        modes = min(DEFAULT_MODES, ndof - 1)
    return reduction, (modes if reduction == "modal" else None)


def linear_part(structure: Structure, retained, reduction: str, modes):
    """The condensation of ``structure`` onto ``retained``: a Condensation or a ModalCondensation."""
    C = structure.C
    if reduction == "exact":
        return Condensation(structure.M, C, structure.K, retained)
    return ModalCondensation(structure.M, C, structure.K, retained, modes)


def modal_error(linear: ModalCondensation, omega: float) -> float:
    """Relative difference (Frobenius) of the modal and the exact condensed first-harmonic stiffness at ``omega``.

    One sparse factorisation of the structure (through the exact condensation the
    modal one keeps for its static term, which has split the matrices already):
    the estimate reported with a modal result (at its peak frequency).
    """
    exact, _ = linear.static.harmonic(1, omega, derivative=False)
    modal, _ = linear.harmonic(1, omega, derivative=False)
    return float(np.linalg.norm(modal - exact) / np.linalg.norm(exact))


def cyclic_retained(disk: CyclicStructure, loads: np.ndarray) -> np.ndarray:
    """Sector DOFs the equations keep: those of the contacts (own and next sector) and of the loads."""
    Bt, Bn, _ = disk.contact_directions()
    Btn, Bnn = disk.contact_directions_next()
    used = (np.any(Bt != 0, axis=1) | np.any(Bn != 0, axis=1) | np.any(Btn != 0, axis=1)
            | np.any(Bnn != 0, axis=1) | np.any(loads != 0, axis=0))
    on_right = np.intersect1d(np.flatnonzero(np.any(loads != 0, axis=0)), disk.right)
    if on_right.size:
        raise ValueError(f"force: DOF {int(on_right[0])} is on the right boundary (the next sector's left one); "
                         f"apply the force to the matching left DOF instead")
    return np.flatnonzero(used)


def cyclic_reduction(disk: CyclicStructure, reduction: str, modes) -> tuple[str, int | None]:
    """``(reduction, modes)`` of a sector, checked; ``"auto"``: exact up to ``EXACT_LIMIT`` independent DOFs.

    A sector is always condensed onto its retained DOFs (``"none"`` is refused).
    """
    if not isinstance(reduction, str) or reduction not in ("auto", "exact", "modal"):
        raise ValueError(f"a CyclicStructure is solved with reduction='exact' or 'modal' (the sector condensed in "
                         f"each harmonic's nodal diameter) or 'auto'; got reduction={reduction!r}")
    n = disk.independent.size
    if modes is not None:
        modes = _checks.positive_int("modes", modes)
        if modes >= n:
            raise ValueError(f"modes must be below the sector's {n} independent DOFs (all but the right boundary), "
                             f"got {modes}")
        if reduction == "exact":
            raise ValueError("modes is used only with reduction='modal', got reduction='exact'")
        reduction = "modal"
    if reduction == "auto":
        reduction = "exact" if n <= EXACT_LIMIT else "modal"
    if reduction == "modal" and modes is None:
        modes = min(DEFAULT_MODES, n - 1)
    return reduction, modes


def cyclic_linear_part(disk: CyclicStructure, loads: np.ndarray, engine_order: int, reduction: str = "exact",
                       modes: int | None = None, harmonics: int = 0):
    """The sector condensed onto its retained DOFs, in each harmonic's nodal diameter (independent numbering).

    ``reduction="exact"``: a :class:`Condensation`; ``"modal"``: a
    :class:`~.cyclic_modal.CyclicModalCondensation` with ``modes`` modes per
    diameter, those of harmonics ``1..harmonics`` computed now.
    """
    retained = cyclic_retained(disk, loads)
    position = np.searchsorted(disk.independent, retained)
    phases = {}

    def diameter(h):  # without boundary DOFs the sector's matrices are those of diameter 0 in every diameter
        return disk.phase(h, engine_order) if disk.left.size else 0.0

    def matrices(h):
        phi = diameter(h)
        if phi not in phases:
            phases[phi] = disk.matrices(phi)
        return phases[phi]

    M0 = matrices(0)[0]
    exact = Condensation(M0, None, None, position, harmonic_matrices=matrices)
    if reduction == "exact":
        return exact
    return CyclicModalCondensation(exact, matrices, diameter, harmonics, modes)
