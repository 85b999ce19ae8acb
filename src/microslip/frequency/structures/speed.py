"""A structure whose stiffness depends on the rotation speed: ``K(Omega) = K0 + Omega^2 K1 (+ Omega^4 K2)``.

Finite-element models of blades are solved at a few rotation speeds (centrifugal
stiffening, spin softening); between them the stiffness is a polynomial in
``Omega^2`` through the given matrices. It is evaluated in Lagrange form in
``x = Omega^2``, ``K(Omega) = sum_i L_i(x) K_i``, so that at a given speed the
weights are exactly one and zero and the given matrix is reproduced bit for bit.
``M`` and ``C`` do not depend on the speed. An under-platform damper's
centrifugal load follows ``m r Omega^2``.
"""

from __future__ import annotations

import copy

import numpy as np
import scipy.sparse as sp

from ...common import _checks
from ...common.units import parse_quantity
from .cyclic import CyclicStructure, add_contact_terms, contact_terms
from .damper import UnderPlatformDamper
from .structure import Structure, check_symmetric


#: the largest rotation speed accepted (rad/s): ``Omega^4`` stays finite
MAX_SPEED = 1e75


def _speed(name: str, value) -> float:
    """A rotation speed (rad/s), a number or a string with a unit (``"3000 rpm"``), >= 0."""
    if isinstance(value, str):
        value = parse_quantity(value, "angular frequency", name=name)
    elif isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name} must be a rotation speed (rad/s, or a string such as '3000 rpm'), got "
                        f"{type(value).__name__}")
    value = _checks.positive_scalar(name, value, allow_zero=True)
    if value > MAX_SPEED:
        raise ValueError(f"{name} must be at most {MAX_SPEED:g} rad/s (its fourth power stays finite), got {value!r}")
    return value


def rotation_speeds(name: str, values) -> np.ndarray:
    """Rotation speeds (rad/s), ``(k,)``: numbers or strings with a unit, each >= 0 and finite."""
    if isinstance(values, (str, int, float)) or values is None:
        raise TypeError(f"{name} must be a sequence of rotation speeds (rad/s or strings such as '3000 rpm'), "
                        f"got {values!r}")
    out = np.array([_speed(f"{name}[{i}]", v) for i, v in enumerate(values)], dtype=float)
    _checks.size(name, out.size)
    return out


class SpeedModel:
    """Stiffness matrices at two or three rotation speeds, ``M`` and ``C`` fixed, and the contacts at any speed.

    Parameters
    ----------
    M, C : array_like or scipy.sparse matrix, shape (ndof, ndof)
        Mass (kg) and viscous damping (N s/m); ``C`` may be None.
    stiffness : sequence of 2 or 3 array_like or scipy.sparse matrices, shape (ndof, ndof)
        ``K`` (N/m) at each of ``speeds``, symmetric.
    speeds : sequence of 2 or 3 float or str
        The rotation speeds of ``stiffness`` (rad/s, or strings such as
        ``"3000 rpm"``), distinct and >= 0. Two speeds fit ``K0 + Omega^2 K1``,
        three ``K0 + Omega^2 K1 + Omega^4 K2``.
    contacts : Structure or callable, optional
        The contacts at each speed: a template structure (same DOFs) whose
        contacts and static forces are copied, or ``contacts(structure, omega)``
        returning the structure with its contacts (it may add them in place and
        return None).
    damper : UnderPlatformDamper, optional
        Attached at each speed (after ``contacts``) with the centrifugal load
        ``damper.mass * radius * Omega^2``.
    radius : float, optional
        Radius of the damper's centre of mass (m), > 0; needed with ``damper``.
    cyclic : mapping, optional
        ``sectors``, ``left``, ``right`` (and ``frame``, ``axis``, ``point``,
        ``coordinates``, ``nodes``) of :class:`CyclicStructure`: :meth:`at` then
        returns a sector. Default: those of ``contacts`` when it is a
        :class:`CyclicStructure` (a sector's template), else none.
    dof_map : microslip.fe.DofMap, optional
        Names of the DOFs.

    Examples
    --------
    >>> import numpy as np
    >>> m = SpeedModel(np.eye(2), None, [np.diag([1e6, 2e6]), np.diag([1.1e6, 2.3e6])], [0.0, "3000 rpm"])
    >>> np.array_equal(m.stiffness(m.speeds[1]), np.diag([1.1e6, 2.3e6]))
    True
    """

    def __init__(self, M, C, stiffness, speeds, *, contacts=None, damper=None, radius=None, cyclic=None,
                 dof_map=None):
        self.speeds = rotation_speeds("speeds", speeds)
        if self.speeds.size not in (2, 3):
            raise ValueError(f"speeds must hold 2 or 3 rotation speeds (K0 + Omega^2 K1 (+ Omega^4 K2)), got "
                             f"{self.speeds.size}")
        x = self.speeds ** 2
        for i in range(x.size):
            for j in range(i):
                if x[i] == x[j]:
                    raise ValueError(f"speeds must be distinct: speeds[{j}] and speeds[{i}] are both "
                                     f"{float(self.speeds[i])!r} rad/s")
        if isinstance(stiffness, (str, bytes)) or not hasattr(stiffness, "__len__"):
            raise TypeError(f"stiffness must be a sequence of {self.speeds.size} matrices, got "
                            f"{type(stiffness).__name__}")
        if len(stiffness) != self.speeds.size:
            raise ValueError(f"stiffness must hold one matrix per speed ({self.speeds.size}), got {len(stiffness)}")
        # M and C checked as a structure's (square, finite, symmetric, M positive definite), each K as its K
        base = Structure(M, C, M, dof_map=dof_map)
        self.M, self.C, self.dof_map = base.M, base.C, dof_map
        mats = []
        for i, K in enumerate(stiffness):
            try:
                mats.append(Structure(self.M, None, K).K)
            except (ValueError, TypeError) as exc:
                raise type(exc)(f"stiffness[{i}]: {exc}") from None
        if cyclic is None and isinstance(contacts, CyclicStructure):  # a sector's template: its symmetry and frame
            cyclic = contacts._cyclic_arguments()
        self._cyclic = None if cyclic is None else dict(_checks.mapping("cyclic", cyclic))
        if self._cyclic is not None:  # the symmetry checked once, on M
            try:
                CyclicStructure(self.M, None, self.M, dof_map=dof_map, **self._cyclic)
            except (ValueError, TypeError) as exc:
                raise type(exc)(f"cyclic: {exc}") from None
        for i, K in enumerate(mats):
            check_symmetric(f"stiffness[{i}]", K, dof_map)
        self.matrices = mats
        self._sparse = any(sp.issparse(K) for K in mats)
        if contacts is not None and not (isinstance(contacts, Structure) or callable(contacts)):
            raise TypeError(f"contacts must be a Structure (a template) or a callable (structure, omega), got "
                            f"{type(contacts).__name__}")
        if isinstance(contacts, Structure) and contacts.ndof != self.ndof:
            raise ValueError(f"contacts: the template structure has {contacts.ndof} DOFs, the model {self.ndof}")
        self.contacts = contacts
        if damper is not None and not isinstance(damper, UnderPlatformDamper):
            raise TypeError(f"damper must be an UnderPlatformDamper, got {type(damper).__name__}")
        self.damper = damper
        self.radius = None if radius is None else _checks.positive_scalar("radius", radius)
        if damper is not None and self.radius is None:
            raise ValueError("radius must be given (m) with damper: its centrifugal load is mass * radius * Omega^2")

    @property
    def ndof(self) -> int:
        """Number of degrees of freedom (without a damper's)."""
        return self.M.shape[0]

    def __repr__(self) -> str:
        return (f"SpeedModel(ndof={self.ndof}, speeds={self.speeds.tolist()} rad/s, "
                f"{'sparse' if self._sparse else 'dense'})")

    def weights(self, omega_rot) -> np.ndarray:
        """The Lagrange weights ``L_i(Omega^2)`` of the given matrices at ``omega_rot`` (rad/s), ``(k,)``.

        Exactly one and zeros at a given speed.
        """
        x = _speed("omega_rot", omega_rot) ** 2
        xs = self.speeds ** 2
        w = np.ones(xs.size)
        for i in range(xs.size):
            for j in range(xs.size):
                if j != i:
                    w[i] *= (x - xs[j]) / (xs[i] - xs[j])
        return w

    def coefficients(self) -> list:
        """``[K0, K1(, K2)]`` (N/m, N s^2/m, N s^4/m): ``K(Omega) = K0 + Omega^2 K1 (+ Omega^4 K2)``."""
        xs = self.speeds ** 2
        V = np.vander(xs, increasing=True)  # V[i, p] = x_i^p
        A = np.linalg.inv(V)  # coefficient p = sum_i A[p, i] K_i
        return [sum(A[p, i] * K for i, K in enumerate(self.matrices)) for p in range(xs.size)]

    def stiffness(self, omega_rot):
        """``K(omega_rot)`` (N/m), ``(ndof, ndof)``, dense or sparse like the given matrices."""
        omega = _speed("omega_rot", omega_rot)
        w = self.weights(omega)
        K = w[0] * self.matrices[0]
        for wi, Ki in zip(w[1:], self.matrices[1:]):
            K = K + wi * Ki
        K = K.tocsr() if sp.issparse(K) else np.asarray(K)
        if not np.isfinite(K.data if sp.issparse(K) else K).all():
            raise ValueError(f"omega_rot = {omega!r} rad/s is too large: K(omega_rot) overflows")
        return K

    def at(self, omega_rot, *, contacts: bool = True, damper: bool = True) -> Structure:
        """The structure at the rotation speed ``omega_rot`` (rad/s, or ``"3000 rpm"``).

        Parameters
        ----------
        omega_rot : float or str
            Rotation speed (rad/s), >= 0 (> 0 with a damper: it needs a load).
        contacts : bool, default True
            False: the bare structure (no contacts, no damper, no static force).
        damper : bool, default True
            False: without the model's damper (the contacts kept).

        Returns
        -------
        Structure or CyclicStructure
            ``M, C, K(omega_rot)`` with the contacts (copied from the template or
            added by the callback) and the damper, its load ``m r omega_rot^2``.
        """
        omega = _speed("omega_rot", omega_rot)
        contacts = _checks.flag("contacts", contacts)
        damper = _checks.flag("damper", damper)
        K = self.stiffness(omega)
        if self._cyclic is not None:
            s = CyclicStructure(self.M, self.C, K, dof_map=self.dof_map, **self._cyclic)
        else:
            s = Structure(self.M, self.C, K, dof_map=self.dof_map)
        if not contacts:
            return s
        if isinstance(self.contacts, Structure):
            for i, c in enumerate(self.contacts.contacts):
                add_contact_terms(s, c.model, *contact_terms(self.contacts, i), preload=c.preload,
                                  approach=c.approach, name=c.name)
            s.static_force = self.contacts.static_force.copy()
            if hasattr(self.contacts, "_dampers"):  # a damper attached to the template: its static balance
                s._dampers = self.contacts._dampers
        elif self.contacts is not None:
            out = self.contacts(s, omega)
            if out is not None:
                if not isinstance(out, Structure):
                    raise TypeError(f"contacts(structure, omega) must return a Structure or None, got "
                                    f"{type(out).__name__}")
                s = out
        if self.damper is not None and damper:
            if omega == 0.0:
                raise ValueError("omega_rot must be > 0 rad/s with a damper: its centrifugal load m r Omega^2 "
                                 "is what presses it against the platforms")
            d = copy.copy(self.damper)
            d.centrifugal_load = self.damper.mass * self.radius * omega * omega
            s = d.attach(s)
            self.damper.dofs, self.damper.names = d.dofs, d.names
        return s
