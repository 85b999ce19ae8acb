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
from ..reduction.cyclic_modal import CyclicModalCondensation
from .hbm import excitation
from .reduced import DEFAULT_MODES, EXACT_LIMIT, ReducedHarmonicBalance


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
        """Coefficients of every sector DOF ``(2H+1, ndof)`` (m), the right boundary from the left one."""
        disk = self.structure
        ind = self._independent(x, omega)
        out = np.zeros((self.nb, disk.ndof))
        out[:, disk.independent] = ind
        out[:, disk.right] = self.P @ ind[:, np.searchsorted(disk.independent, disk.left)]
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


def cyclic_equations(disk: CyclicStructure, force, static_force, H, engine_order, samples, max_periods,
                     reduction: str = "exact", modes: int | None = None):
    """``(static, dynamic, (reduction, modes))``: the equations of a sector, sharing one condensation."""
    reduction, modes = cyclic_reduction(disk, reduction, modes)
    loads = excitation(disk, force, H)
    loads[0] += disk.preload_force()
    linear = cyclic_linear_part(disk, loads, engine_order, reduction, modes, H)
    return (CyclicHarmonicBalance(disk, static_force, 0, engine_order, linear),
            CyclicHarmonicBalance(disk, force, H, engine_order, linear, samples=samples, max_periods=max_periods),
            (reduction, modes))
