"""Harmonic balance of one sector of a cyclic structure under an engine-order excitation.

The unknowns are the coefficients of the sector's retained DOFs (those its
contacts, the excitation and the preloads use; never a right-boundary DOF), the
rest of the sector condensed per harmonic in that harmonic's nodal diameter,
on the complex Hermitian sector matrices of
:meth:`~.cyclic.CyclicStructure.matrices`: exactly
(:class:`~.condensation.Condensation`, a sparse factorisation per harmonic and
frequency) or from that diameter's modes plus the residual flexibility of the
others (:class:`~.cyclic_modal.CyclicModalCondensation`, one eigensolution per
diameter, then small dense algebra). A contact's displacement
is ``G x`` with ``G = I (x) b_own^T + P (x) b_next^T``, ``P`` the phase lag from one
sector to the next in the real harmonic layout (blocks ``[[c, -s], [s, c]]`` with
``c, s = cos, sin(phi_h)``); its force acts on the sector through ``G^T`` (the
next sector's share returns through the previous sector's contact), and its
Jacobian is ``G^T (dF/dx) G``, assembled for all contacts in one product.
"""

from __future__ import annotations

import numpy as np

from ...common import _checks
from ..aft import MAX_PERIODS
from ..reduction.condensation import Condensation
from ..structures.cyclic import CyclicStructure
from .reduced import ReducedHarmonicBalance


def phase_operator(disk: CyclicStructure, H: int, engine_order: int) -> np.ndarray:
    """``P`` (``(2H+1, 2H+1)``): a sector's harmonic coefficients seen on the next sector."""
    P = np.zeros((2 * H + 1, 2 * H + 1))
    P[0, 0] = 1.0
    for h in range(1, H + 1):
        phi = disk.phase(h, engine_order)
        c, s = np.cos(phi), np.sin(phi)
        a, b = 2 * h - 1, 2 * h
        P[a, a], P[a, b], P[b, a], P[b, b] = c, -s, s, c
    return P


class CyclicHarmonicBalance(ReducedHarmonicBalance):
    """Harmonic balance equations of one sector under an engine-order excitation.

    Parameters
    ----------
    disk : CyclicStructure
        The sector and its contacts.
    force : array_like or mapping
        Excitation of this sector (N), on its DOFs (not the right boundary).
    harmonics : int
        ``H``.
    engine_order : int
        ``EO >= 0``: harmonic ``h`` lives in nodal diameter ``h EO mod N``.
    linear : Condensation or CyclicModalCondensation
        From :func:`cyclic_linear_part` (shared by the static and dynamic problems).
    samples, max_periods
        As for :class:`~microslip.frequency.equations.hbm.HarmonicBalance`.
    """

    def __init__(self, disk: CyclicStructure, force, harmonics: int, engine_order: int, linear: Condensation, *,
                 samples: int | None = None, max_periods: int = MAX_PERIODS):
        self.linear = linear
        self.engine_order = engine_order
        self._setup(disk, force, harmonics, samples, max_periods, linear.m)
        self.retained = disk.independent[linear.retained]  # sector numbering
        self.f_full = self.f_ext
        self.f_ext = self.f_ext[:, self.retained]
        self.f = self.f_ext.ravel()
        self.dense = True
        Bt, Bn, self.n0 = disk.contact_directions()
        Btn, Bnn = disk.contact_directions_next()
        self.Bt, self.Bn = (np.ascontiguousarray(B[self.retained]) for B in (Bt, Bn))
        self.Bt_next, self.Bn_next = (np.ascontiguousarray(B[self.retained]) for B in (Btn, Bnn))
        self.P = phase_operator(disk, self.H, engine_order)
        eye = np.eye(self.nb)[None, :, :, None]
        self.Gt = (eye * self.Bt.T[:, None, None, :] + self.P[None, :, :, None] * self.Bt_next.T[:, None, None, :]
                   ).reshape(self.nc, self.nb, self.n)
        self.Gn = (eye * self.Bn.T[:, None, None, :] + self.P[None, :, :, None] * self.Bn_next.T[:, None, None, :]
                   ).reshape(self.nc, self.nb, self.n)

    def _local(self, x) -> tuple[np.ndarray, np.ndarray]:
        """Coefficients of every contact's ``t`` and ``n`` (m), each ``(nc, 2H+1)``: own and next-sector DOFs."""
        xt = np.ascontiguousarray(self.Gt @ x)
        xn = np.ascontiguousarray(self.Gn @ x)
        xn[:, 0] += self.n0
        xt[:, 0] -= self.t_ref
        return xt, xn

    def _contact_residual(self) -> np.ndarray:
        return np.einsum("cpk,cp->k", self.Gt, self.FT) + np.einsum("cpk,cp->k", self.Gn, self.FN)

    def _contact_jacobian(self):
        nc, nb, n = self.nc, self.nb, self.n
        Gt, Gn = self.Gt.reshape(nc * nb, n), self.Gn.reshape(nc * nb, n)
        At = (self.JTt @ self.Gt + self.JTn @ self.Gn).reshape(nc * nb, n)
        An = (self.JNn @ self.Gn).reshape(nc * nb, n)
        return Gt.T @ At + Gn.T @ An

    def static_directions(self) -> tuple[np.ndarray, np.ndarray]:
        """Each contact's static directions on the retained DOFs ``(Bt, Bn)``, ``(m, nc)``: own plus next sector."""
        return self.Bt + self.Bt_next, self.Bn + self.Bn_next

    def stuck_stiffness(self) -> np.ndarray:
        """Static condensed stiffness plus every contact element closed and stuck (N/m), ``(m, m)``."""
        K = self.linear.operator(1.0, 0)[0].copy()
        Bt, Bn = self.static_directions()
        for c, contact in enumerate(self.structure.contacts):
            K += contact.model.kt.sum() * np.outer(Bt[:, c], Bt[:, c])
            K += contact.model.kn.sum() * np.outer(Bn[:, c], Bn[:, c])
        return K

    def _full(self, x, omega: float) -> np.ndarray:
        """Coefficients of every sector DOF ``(2H+1, ndof)`` (m), the right boundary from the left one (``P``, then
        :attr:`~.cyclic.CyclicStructure.boundary_rotation`)."""
        disk = self.structure
        ind = self._independent(x, omega)
        out = np.zeros((self.nb, disk.ndof))
        out[:, disk.independent] = ind
        left = self.P @ ind[:, np.searchsorted(disk.independent, disk.left)]
        out[:, disk.right] = (disk.boundary_rotation @ left.T).T  # turned by R in the Cartesian frame
        return out

    def _independent(self, x, omega: float) -> np.ndarray:
        """Coefficients of the sector's independent DOFs ``(2H+1, len(independent))`` (m) from the unknowns."""
        return self.linear.recover(np.reshape(x, (self.nb, self.ndof)), omega, self.H)


def check_engine_order(structure, engine_order):
    """``engine_order`` checked against the structure: required for a cyclic one, refused otherwise."""
    cyclic = isinstance(structure, CyclicStructure)
    if engine_order is None:
        if cyclic:
            raise ValueError("engine_order must be given for a CyclicStructure (the excitation's travelling wave, "
                             "an integer >= 0)")
        return None
    if not cyclic:
        raise ValueError("engine_order is only for a CyclicStructure; this structure is not cyclic")
    return _checks.positive_int("engine_order", engine_order, minimum=0)
