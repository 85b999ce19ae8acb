"""The under-platform damper: a rigid body pressed by centrifugal force against two blade platforms.

In the plane of the disk (``x`` circumferential, ``y`` radial, outwards) the damper
has three DOFs, the translations ``X``, ``Y`` of its centre of mass and the small
rotation ``theta`` (rad, anticlockwise), carried as the arc ``R = arm * theta`` (m)
that it moves the contact farthest from the centre of mass (``arm``, its distance):
every unknown is then a length of the same order, so that the solver's one
displacement scale fits the rotation too (in radians it would be ``1 / arm`` times
larger, and its wanderings would dominate the continuation's steps). A point
``(px, py)`` of the damper (m, from its centre of mass) moves by
``(X - theta py, Y + theta px)``. Each interface has a normal
at the angle ``angle`` (rad, from ``x``), pointing from the damper into the
platform, ``nu = (cos, sin)``, and the tangent ``tau = (-sin, cos)``; its contacts
sit at given points of the damper, each a :class:`~microslip.model.MicroslipModel`
whose normal approach is ``nu . (u_damper - u_platform)`` and tangential
displacement ``tau . (u_damper - u_platform)``. A flat interface carries two or
more contacts across its width, so that the damper's rotation and a partial
lift-off (one contact's normal load reaching zero) appear; a curved one carries a
single line contact. The centrifugal load ``m r Omega^2`` is a static force on
``Y``; the static state is the equilibrium reached by loading every contact in
one proportional step from the unloaded, touching damper (the harmonic balance's
static convention), and :meth:`UnderPlatformDamper.static_balance` checks that
the forces and the moment on the damper sum to zero.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ...common import _checks
from ...model import MicroslipModel
from .cyclic import CyclicStructure, NextDof, add_contact_terms, contact_terms
from .structure import Structure

_AXES = ("x", "y")


@dataclass(frozen=True)
class DamperContact:
    """One contact of a damper interface (made by :meth:`UnderPlatformDamper.add_interface`).

    Attributes
    ----------
    interface : str
        Name of its interface.
    model : MicroslipModel
        Its contact law.
    point : (float, float)
        Position on the damper from its centre of mass (m).
    normal, tangent : (float, float)
        Unit normal (from the damper into the platform) and tangent of its interface.
    platform : dict
        The platform's DOFs at the point, ``{"x": dof, "y": dof}`` (an index, or
        ``disk.next(j)`` for the next sector's platform).
    """

    interface: str
    model: MicroslipModel
    point: tuple
    normal: tuple
    tangent: tuple
    platform: dict


def _platform_dof(name: str, value):
    if isinstance(value, NextDof):
        return value
    return _checks.positive_int(name, value, minimum=0)


class UnderPlatformDamper:
    """A rigid under-platform damper with its interfaces, to attach to a structure.

    Parameters
    ----------
    mass : float
        Mass (kg).
    inertia : float
        Moment of inertia about the centre of mass, out of the plane (kg m^2).
    centrifugal_load : float, optional
        The static radial load ``m r Omega^2`` (N), outwards (+y).
    speed, radius : float, optional
        Or the rotation speed (rad/s) and the radius of the centre of mass (m):
        ``centrifugal_load = mass * radius * speed**2``.
    damping : float, default 0
        Mass-proportional viscous damping of the damper body (1/s): ``C = damping
        * M`` on its DOFs. Without it a mode of the damper on its stuck contacts
        is undamped, and the response is unbounded where a harmonic of the
        excitation meets it (the harmonic balance then has no solution there).
    retention : float, default 0
        Stiffness of the features that keep the damper in its pocket (N/m): a
        spring from each of ``X``, ``Y`` and the arc ``R`` to the disk (a
        torsional ``retention * arm**2`` N m/rad). Where one contact stays open
        over the whole cycle and the others slide, nothing but friction holds
        the damper's mean position, and the continuation creeps through nearly
        singular points; a retention far below the contacts' normal stiffness
        (1e3 N/m against 2.3e7 N/m in ``tests/frequency/test_damper.py``) holds
        it without changing the response.

    Examples
    --------
    >>> from microslip import MicroslipModel
    >>> d = UnderPlatformDamper(0.02, 1e-6, centrifugal_load=300.0)
    >>> law = MicroslipModel([1e6], [1e8], [0.0], 0.5)
    >>> d.add_interface(law, points=[(-4e-3, 2e-3), (-2e-3, 4e-3)], angle=np.radians(135),
    ...                 platform=[{"x": 0, "y": 1}, {"x": 0, "y": 1}], name="flat")
    >>> len(d.contacts)
    2
    """

    def __init__(self, mass: float, inertia: float, *, centrifugal_load: float | None = None,
                 speed: float | None = None, radius: float | None = None, damping: float = 0.0,
                 retention: float = 0.0):
        self.mass = _checks.positive_scalar("mass", mass)
        self.inertia = _checks.positive_scalar("inertia", inertia)
        self.damping = _checks.positive_scalar("damping", damping, allow_zero=True)
        self.retention = _checks.positive_scalar("retention", retention, allow_zero=True)
        if centrifugal_load is not None:
            if speed is not None or radius is not None:
                raise ValueError("give centrifugal_load, or speed and radius, not both")
            self.centrifugal_load = _checks.positive_scalar("centrifugal_load", centrifugal_load, allow_zero=True)
        elif speed is not None and radius is not None:
            speed = _checks.positive_scalar("speed", speed, allow_zero=True)
            radius = _checks.positive_scalar("radius", radius)
            self.centrifugal_load = self.mass * radius * speed * speed
        else:
            raise ValueError("the damper needs its static load: centrifugal_load (N), or speed (rad/s) and radius (m)")
        self.contacts: list[DamperContact] = []

    def add_interface(self, models, *, points, angle: float, platform, name: str | None = None) -> None:
        """Add an interface: its contacts' laws, positions on the damper, normal angle and platform DOFs.

        Parameters
        ----------
        models : MicroslipModel or sequence of MicroslipModel
            One law for every point, or one per point.
        points : array_like, shape (k, 2)
            Contact positions on the damper from its centre of mass (m).
        angle : float
            Angle of the interface normal from the ``x`` axis (rad); the normal
            points from the damper into the platform.
        platform : mapping or sequence of mappings
            The platform's DOFs at each point, ``{"x": dof, "y": dof}`` (one
            mapping for all points, or one per point); a DOF is an index of the
            structure, or ``disk.next(j)`` for the next sector's platform.
        name : str, optional
            Label of the interface (default ``interface<i>``); its contacts are
            named ``<name><k>``.
        """
        pts = _checks.real_array("points", points, ndim=2)
        if pts.shape[1] != 2 or pts.shape[0] == 0:
            raise ValueError(f"points must have shape (k, 2) with k >= 1 (m), got {pts.shape}")
        k = pts.shape[0]
        if isinstance(models, MicroslipModel):
            models = [models] * k
        if not isinstance(models, Sequence) or len(models) != k or \
                not all(isinstance(m, MicroslipModel) for m in models):
            raise TypeError(f"models must be a MicroslipModel or a list of {k} (one per point), got {models!r}")
        a = _checks.real_scalar("angle", angle)
        if isinstance(platform, Mapping):
            platform = [platform] * k
        if not isinstance(platform, Sequence) or len(platform) != k:
            raise TypeError(f"platform must be a mapping {{'x': dof, 'y': dof}} or a list of {k} of them")
        plats = []
        for i, p in enumerate(platform):
            if not isinstance(p, Mapping) or set(p) != set(_AXES):
                raise ValueError(f"platform[{i}] must be a mapping with keys 'x' and 'y' (the platform's DOFs at "
                                 f"the point), got {p!r}")
            plats.append({ax: _platform_dof(f"platform[{i}]['{ax}']", p[ax]) for ax in _AXES})
        name = f"interface{len({c.interface for c in self.contacts})}" if name is None else name
        if not isinstance(name, str) or not name:
            raise TypeError(f"name must be a non-empty string, got {name!r}")
        if any(c.interface == name for c in self.contacts):
            raise ValueError(f"name {name!r} is already used by another interface")
        nu = (float(np.cos(a)), float(np.sin(a)))
        tau = (-nu[1], nu[0])
        for i in range(k):
            self.contacts.append(DamperContact(name, models[i], (float(pts[i, 0]), float(pts[i, 1])), nu, tau,
                                               plats[i]))

    @property
    def arm(self) -> float:
        """Distance of the contact farthest from the centre of mass (m): the rotation DOF is ``arm * theta``."""
        return max((float(np.hypot(*c.point)) for c in self.contacts), default=0.0) or 1.0

    def _direction(self, contact: DamperContact, axis, dofs) -> dict:
        """``{dof: coefficient}`` of ``axis . (u_damper(point) - u_platform)``."""
        X, Y, R = dofs
        px, py = contact.point
        out = {X: axis[0], Y: axis[1], R: (axis[1] * px - axis[0] * py) / self.arm}
        for coef, ax in zip(axis, _AXES):
            dof = contact.platform[ax]
            out[dof] = out.get(dof, 0.0) - coef
        return out

    def attach(self, structure: Structure) -> Structure:
        """A new structure: ``structure`` plus the damper's 3 DOFs (appended: X, Y, R), its contacts and load.

        Works on a plain :class:`Structure` (one blade pair, a rig with two
        platforms) and on a :class:`CyclicStructure` (the damper joins a sector to
        the next: name the next sector's platform DOFs with ``disk.next(j)``).
        The damper's DOFs are ``new.ndof - 3 + (0, 1, 2)`` (:attr:`dofs` after the call):
        ``X``, ``Y`` (m) and ``R = arm * theta`` (m; the rotation is ``R / arm`` rad).
        """
        if not isinstance(structure, Structure):
            raise TypeError(f"structure must be a microslip Structure, got {type(structure).__name__}")
        if not self.contacts:
            raise ValueError("the damper has no interface: add_interface first")
        cyclic = isinstance(structure, CyclicStructure)
        for c in self.contacts:
            for dof in c.platform.values():
                if isinstance(dof, NextDof) and not cyclic:
                    raise ValueError(f"interface {c.interface!r} names a next-sector DOF, which only a CyclicStructure "
                                     f"has")
                index = dof.dof if isinstance(dof, NextDof) else dof
                if index >= structure.ndof:
                    raise ValueError(f"interface {c.interface!r}: platform DOF {index} is out of range for a structure "
                                     f"with {structure.ndof} DOFs")
        n = structure.ndof
        extra = np.array([self.mass, self.mass, self.inertia / self.arm**2])  # R = arm theta
        M, C, K = (_grow(A, d) for A, d in ((structure.M, extra), (structure.C, self.damping * extra),
                                            (structure.K, np.full(3, self.retention))))
        if cyclic:
            out = CyclicStructure(M, C, K, **structure._cyclic_arguments())  # the same symmetry and frame
        else:
            out = Structure(M, C, K)
        _copy_contacts(structure, out)
        out.static_force[:n] = structure.static_force
        self.dofs = (n, n + 1, n + 2)
        taken = {c.name for c in out.contacts}
        # contacts named after their interface; another damper's on the structure: suffixed by this one's X DOF
        self.names = [f"{c.interface}{k}" for k, c in enumerate(self.contacts)]
        if taken.intersection(self.names):
            self.names = [f"{name}@{n}" for name in self.names]
        for c, name in zip(self.contacts, self.names):
            out.add_contact(c.model, tangential=self._direction(c, c.tangent, self.dofs),
                            normal=self._direction(c, c.normal, self.dofs), approach=0.0, name=name)
        load = np.zeros(out.ndof)
        load[n + 1] = self.centrifugal_load
        out.add_static_force(load)
        return out

    def static_balance(self, result) -> float:
        """The static forces and moment on the damper, ``|sum|`` relative to the centrifugal load.

        Parameters
        ----------
        result : FrequencyResponse
            A result of the structure returned by :meth:`attach`.

        Returns
        -------
        float
            ``max(|F_x|, |F_y|, |M_z| / arm) / load``, with :attr:`arm` the largest
            distance of a contact from the centre of mass: zero at equilibrium.
        """
        names = [c.name for c in result.structure.contacts]
        F = np.array([0.0, self.centrifugal_load])
        Mz = 0.0
        for c, name in zip(self.contacts, self.names):
            i = names.index(name)
            N0, T0 = result.static_normal_force[i], result.static_tangential_force[i]
            f = -(N0 * np.array(c.normal) + T0 * np.array(c.tangent))  # the platform pushes back on the damper
            F += f
            Mz += c.point[0] * f[1] - c.point[1] * f[0]
        return float(max(abs(F[0]), abs(F[1]), abs(Mz) / self.arm) / max(self.centrifugal_load, 1e-300))


def _grow(A, diagonal):
    """``A`` with three more rows and columns, ``diagonal`` on the new diagonal (same storage)."""
    if sp.issparse(A):
        return sp.block_diag([A, sp.diags(diagonal)], format="csr")
    n = A.shape[0]
    out = np.zeros((n + 3, n + 3))
    out[:n, :n] = A
    out[n:, n:] = np.diag(diagonal)
    return out


def _copy_contacts(source: Structure, target: Structure) -> None:
    """The contacts of ``source`` on ``target`` (same DOF numbers, more DOFs)."""
    for i, c in enumerate(source.contacts):
        add_contact_terms(target, c.model, *contact_terms(source, i), preload=c.preload, approach=c.approach,
                          name=c.name)
