"""A jointed structure from a reduced joint model: :func:`jointed_structure`.

:func:`microslip.fe.lap_joint` builds the linear part (two plates, bolts, the reduction to relative
interface coordinates); this attaches the friction contacts on its interface and the bolts' clamping
load, and gives the structure its viscous damping.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

from ...common import _checks
from ...fe.joints import LapJoint
from ...fe.patches import PressureLaw, add_patch
from ...model import MicroslipModel
from .structure import Structure

__all__ = ["DEFAULT_LAW", "jointed_structure"]

#: the interface's default law per unit area: an elastic--dry-friction element per pair (steel on steel,
#: stiffnesses of the order measured on bolted steel interfaces)
DEFAULT_LAW = PressureLaw(kn_per_area=2e13, kt_per_area=1e13, mu=0.6)


def jointed_structure(joint: LapJoint, law=None, *, damping_ratio: float = 1e-3) -> Structure:
    """The structure of a reduced lap joint with a friction contact on every pair that is not tied.

    Parameters
    ----------
    joint : microslip.fe.LapJoint
        From :func:`microslip.fe.lap_joint`.
    law : PressureLaw or MicroslipModel, optional
        The contact law per unit area (see :func:`microslip.fe.add_patch`); default
        :data:`DEFAULT_LAW`. Each contact moves on the interface's plane (two tangential directions).
    damping_ratio : float, default 1e-3
        Viscous damping proportional to the stiffness without the contacts (``C = beta K``, the tied
        pairs' stiffness included) giving this
        damping ratio to the first mode of the structure with its contacts stuck and closed,
        ``0 <= damping_ratio < 1``.

    Returns
    -------
    Structure
        ``joint.ndof`` DOFs (dense), ``joint.contacts`` contacts named ``joint0``, ``joint1``, ... (in the
        order of ``joint.contact_pairs``), the bolts' clamping as its static force. The tied pairs around
        the bolts are held by the law's stiffness, stuck and closed (``kt`` along the tangents, ``kn`` along
        the normal, times each pair's area; linear: they neither slip nor open).

    Examples
    --------
    >>> from microslip.fe import lap_joint
    >>> from microslip.frequency import jointed_structure
    >>> structure = jointed_structure(lap_joint(30, modes=10))  # doctest: +SKIP
    """
    if not isinstance(joint, LapJoint):
        raise TypeError(f"joint must be a microslip.fe.LapJoint (from microslip.fe.lap_joint), got "
                        f"{type(joint).__name__}")
    if law is None:
        law = DEFAULT_LAW
    if not isinstance(law, (PressureLaw, MicroslipModel)):
        raise TypeError(f"law must be a PressureLaw or a MicroslipModel (per unit area), got {type(law).__name__}")
    zeta = _checks.in_range("damping_ratio", damping_ratio, 0.0, 1.0, hi_open=True)
    K = np.array(joint.K, dtype=float)
    for p in joint.tied_pairs:
        kt, kn = _stiffness_per_area(law)
        a = float(joint.patch.area[p])
        pair = joint.patch
        tie = a * (kt * (np.outer(pair.tangent1[p], pair.tangent1[p]) + np.outer(pair.tangent2[p], pair.tangent2[p]))
                   + kn * np.outer(pair.normal[p], pair.normal[p]))
        rows = list(joint.dofs[int(pair.nodes_a[p])])
        K[np.ix_(rows, rows)] += tie
    structure = Structure(joint.M, None, K)
    add_patch(structure, joint.contact_patch(), law, dofs=joint.dofs, name="joint", relative=True)
    structure.add_static_force(joint.bolt_force)
    if zeta > 0.0:
        stuck = structure.stuck_stiffness()
        lam, phi = sla.eigh(stuck, joint.M, subset_by_index=[0, 0])
        # phi^T C phi = 2 zeta omega for the mass-normalised mode phi
        structure.C = (2 * zeta * np.sqrt(lam[0]) / float(phi[:, 0] @ K @ phi[:, 0])) * K
    return structure


def _stiffness_per_area(law) -> tuple[float, float]:
    """``(kt, kn)`` per unit area (Pa/m) of a law: a PressureLaw's, or a MicroslipModel's summed over its elements."""
    if isinstance(law, PressureLaw):
        return law.kt_per_area, law.kn_per_area
    return float(np.sum(law.kt)), float(np.sum(law.kn))
