"""Harmonic balance on the contact DOFs: the linear structure enters through its condensed dynamic stiffness.

The unknowns are the Fourier coefficients of the *retained* DOFs only: every DOF
a contact's tangential or normal direction uses, and every DOF the excitation
or a preload acts on. The rest of the structure is condensed per harmonic,

* ``reduction="exact"`` -- exactly (:class:`~.condensation.Condensation`: a
  sparse factorisation per harmonic and frequency), identical to the full
  solve to solver tolerance;
* ``reduction="modal"`` -- from ``modes`` normal modes plus the residual
  flexibility of the omitted ones (:class:`~.modal.ModalCondensation`: one
  eigensolution, then small dense algebra per frequency);
* ``reduction="none"`` -- no condensation (every DOF an unknown).

The residual is ``R = Z(omega) x + sum_c L_c F_c(L_c^T x) - f`` as for the
full equations (:class:`~.hbm.HarmonicBalance`, whose contact and AFT machinery
this class inherits), with ``Z(omega)`` the condensed block-diagonal operator.
"""

from __future__ import annotations

import numpy as np

from ...common import _checks
from ..aft import MAX_PERIODS
from ..reduction.condensation import Condensation
from .hbm import DENSE_LIMIT, HarmonicBalance
from ..reduction.modal import ModalCondensation
from ..structures.structure import Structure

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
    (``(2H+1) ndof <=`` :data:`~.hbm.DENSE_LIMIT`), unless the structure has
    at least :data:`FEW_RETAINED_MIN_DOFS` DOFs of which the equations would
    keep (``retained``, the DOFs the contacts, excitation and preloads use) at
    most a quarter: then ``"exact"``, as up to :data:`EXACT_LIMIT` DOFs;
    ``"modal"`` with :data:`DEFAULT_MODES` modes above.
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
        if (2 * harmonics + 1) * ndof <= DENSE_LIMIT and not few:
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


class ReducedHarmonicBalance(HarmonicBalance):
    """Harmonic balance equations on the retained DOFs of a structure.

    Parameters
    ----------
    structure : Structure
        The structure with its contacts.
    force : array_like or mapping
        Excitation (N), see :func:`~microslip.frequency.equations.hbm.excitation`.
    harmonics : int
        ``H`` (0: the static problem).
    linear : Condensation or ModalCondensation
        The condensed linear structure (from :func:`linear_part`); shared
        between the static and the dynamic problem.
    samples, max_periods
        As for :class:`~microslip.frequency.equations.hbm.HarmonicBalance`.

    Notes
    -----
    ``x`` holds the coefficients of the ``m`` retained DOFs, harmonic-major,
    ``n = (2H+1) m``; :meth:`full` recovers every DOF.
    """

    compiled = False

    def __init__(self, structure: Structure, force, harmonics: int, linear, *, samples: int | None = None,
                 max_periods: int = MAX_PERIODS):
        self.linear = linear
        self.retained = linear.retained
        self._setup(structure, force, harmonics, samples, max_periods, linear.m)
        outside = np.flatnonzero(np.any(self.f_ext != 0, axis=0))
        missing = np.setdiff1d(outside, self.retained)
        if missing.size:
            raise ValueError(f"force acts on DOF {int(missing[0])}, which the reduction does not keep")
        self.f_full = self.f_ext
        self.f_ext = self.f_ext[:, self.retained]
        self.f = self.f_ext.ravel()
        self.dense = True
        Bt, Bn, self.n0 = structure.contact_directions()
        self.Bt = np.ascontiguousarray(Bt[self.retained])
        self.Bn = np.ascontiguousarray(Bn[self.retained])
        self.Bt2 = np.ascontiguousarray(structure.second_tangential_directions()[self.retained])

    def dynamic_stiffness(self, omega: float):
        """The condensed ``Z(omega)``, dense ``(n, n)`` (N/m)."""
        return self.linear.operator(omega, self.H)[0]

    def _omega_derivative(self, x, omega: float) -> np.ndarray:
        """``dR/domega = Z'(omega) x`` (N s), shape ``(n,)``."""
        return self.linear.operator(omega, self.H)[1] @ x

    def stuck_stiffness(self) -> np.ndarray:
        """Static condensed stiffness plus every contact element closed and stuck (N/m), ``(m, m)``."""
        K = self.linear.operator(1.0, 0)[0].copy()
        for c, contact in enumerate(self.structure.contacts):
            for b, k in ((self.Bt[:, c], contact.model.kt.sum()), (self.Bn[:, c], contact.model.kn.sum()),
                         (self.Bt2[:, c], contact.model.kt.sum())):
                K += k * np.outer(b, b)
        return K

    def _full(self, x, omega: float) -> np.ndarray:
        """Coefficients of every DOF ``(2H+1, ndof)`` (m) from the reduced unknowns ``x``."""
        return self.linear.recover(np.reshape(x, (self.nb, self.ndof)), omega, self.H)

    def curve_quantities(self, xs, omegas) -> dict:
        """As :meth:`HarmonicBalance.curve_quantities`; the viscous dissipation from the energy balance.

        The work of the excitation is exact (it acts on retained DOFs); the
        energy dissipated by ``C`` is the excitation's work minus the
        contacts', which holds exactly at a harmonic balance solution.
        """
        out = super().curve_quantities(xs, omegas, viscous=False)
        out["viscous"] = out["excitation"] - out["contacts_harmonic"].sum(axis=-1)
        return out


def modal_error(linear: ModalCondensation, omega: float) -> float:
    """Relative difference (Frobenius) of the modal and the exact condensed first-harmonic stiffness at ``omega``.

    One sparse factorisation of the structure (through the exact condensation the
    modal one keeps for its static term, which has split the matrices already):
    the estimate reported with a modal result (at its peak frequency).
    """
    exact, _ = linear.static.harmonic(1, omega, derivative=False)
    modal, _ = linear.harmonic(1, omega, derivative=False)
    return float(np.linalg.norm(modal - exact) / np.linalg.norm(exact))
