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

from ..aft import MAX_PERIODS
from ..structures.structure import Structure
from .hbm import HarmonicBalance

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
        The condensed linear structure (from :func:`~microslip.frequency.reduction.choice.linear_part`); shared
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
