"""The under-platform damper: a rigid body pressed by centrifugal force against two blade platforms.

In the plane of the disk (``x`` circumferential, ``y`` radial, outwards) the damper
has three DOFs, the translations ``X``, ``Y`` of its centre of mass and the small
rotation ``theta`` (rad, anticlockwise), carried as the arc ``R = arm * theta`` (m)
that it moves the contact farthest from the centre of mass (``arm``, its distance):
every unknown is then a length of the same order, so that the solver's one
displacement scale fits the rotation too (in radians it would be ``1 / arm`` times
larger, and its wanderings would dominate the continuation's steps). A point
``(px, py)`` of the damper (m, from its centre of mass) moves by
``(X - theta py, Y + theta px)``. Each interface has a normal at an angle from
``x`` (``angle_deg`` in degrees, as the configuration's ``angle``, or ``angle`` in
radians), pointing from the damper into the platform, ``nu = (cos, sin)``, and the
tangent ``tau = (-sin, cos)``; its contacts sit at given points of the damper, each a
:class:`~microslip.model.MicroslipModel` whose normal approach is
``nu . (u_damper - u_platform)`` and tangential displacement
``tau . (u_damper - u_platform)``. A flat interface carries two or more contacts
across its width, so that the damper's rotation and a partial lift-off (one
contact's normal load reaching zero) appear; a curved one carries a single line
contact. A damper with one contact per face (a cylinder between two flat faces)
can roll: no contact's normal approach changes in that motion, and only friction
holds it, so it needs a ``retention`` (:meth:`UnderPlatformDamper.attach` says so).

The centrifugal load ``m r Omega^2`` is a static force on ``Y``. The static state
is the harmonic balance's for every contact (:mod:`microslip.frequency.aft`): each
contact is closed to its static normal approach ``n0`` and then moved tangentially
to ``t0`` at that approach, one step from the virgin contact (every slider at
zero). A real damper is loaded otherwise: the centrifugal load grows with the
speed, and each contact's ``t`` and ``n`` grow together, so an element with a gap
closes only when ``n`` reaches it, with part of ``t`` already there, and carries
less tangential force than the static step gives it. That load ramp is the
physical path; the static step is what the harmonic balance solves (it is every
contact's static convention in the package, not the damper's alone). The two
agree for every element that slides at the static state (its force is
``mu N_i`` either way) and for the elements without a gap; they differ where
elements with a gap stick. Measured on the test damper spun up in 50 load steps
(``tests/frequency/test_damper.py``): not at all with ``mu = 0.4`` (every contact
slides at its static state), by 2.4 % of the load on a contact's ``N0`` and
1.5 % on its ``T0`` with ``mu = 3`` at 50 N. It matters to the steady state only
where those elements stick through the whole cycle (an element that slips
forgets its static force). :meth:`UnderPlatformDamper.static_balance` checks that
the forces and the moment on the damper, its retention included, sum to zero.
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.optimize import nnls

from ...common import _checks
from ...common.errors import OneSidedDamperWarning
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


@dataclass(frozen=True)
class _Attachment:
    """What :meth:`UnderPlatformDamper.attach` put on a structure: the damper's contacts, their names, its DOFs,
    its ``arm`` (m) and its centrifugal load (N) then; the structure keeps it (``structure._dampers``)."""

    contacts: tuple
    names: tuple
    dofs: tuple
    arm: float
    load: float


def _platform_dof(name: str, value):
    if isinstance(value, NextDof):
        return value
    return _checks.positive_int(name, value, minimum=0)


#: an angle given in radians (``angle``) larger than this is taken for degrees and refused
_RADIANS_LIMIT = 2 * np.pi


def _interface_angle(angle_deg, angle) -> float:
    """The normal's angle (rad) from ``angle_deg`` (degrees) or ``angle`` (radians): exactly one of them."""
    if (angle_deg is None) == (angle is None):
        raise TypeError("angle_deg: give the interface normal's angle from x, either angle_deg (degrees, as the "
                        "configuration's angle) or angle (radians), one of them"
                        + (f"; got angle_deg={angle_deg!r} and angle={angle!r}" if angle is not None else ""))
    if angle_deg is not None:
        return float(np.radians(_checks.real_scalar("angle_deg", angle_deg)))
    a = _checks.real_scalar("angle", angle)
    if abs(a) > _RADIANS_LIMIT:
        raise ValueError(f"angle is in radians, got {a!r} (beyond 2 pi): for an angle in degrees give "
                         f"angle_deg={a!r}")
    return a


def _load(value, source: str = "") -> float:
    """The centrifugal load (N), > 0: an unloaded damper has no static state to vibrate about."""
    load = _checks.positive_scalar("centrifugal_load", value, allow_zero=True)
    if load == 0.0:
        raise ValueError(f"centrifugal_load must be > 0 N, got 0{source}: only the centrifugal load presses the "
                         f"damper against its platforms; unloaded, its contacts touch without force, every element "
                         f"is open, and nothing holds the damper (it rattles in its pocket)")
    return load


class UnderPlatformDamper:
    """A rigid under-platform damper with its interfaces, to attach to a structure.

    Parameters
    ----------
    mass : float
        Mass (kg).
    inertia : float
        Moment of inertia about the centre of mass, out of the plane (kg m^2).
    centrifugal_load : float, optional
        The static radial load ``m r Omega^2`` (N), outwards (+y), > 0: it is
        what presses the damper against its platforms.
    speed, radius : float, optional
        Or the rotation speed (rad/s, > 0) and the radius of the centre of mass
        (m): ``centrifugal_load = mass * radius * speed**2``.
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
        it without changing the response. A damper with one contact per face
        (a cylinder between two flat faces) rolls, held by friction alone, and
        needs one.

    Examples
    --------
    >>> from microslip import MicroslipModel
    >>> d = UnderPlatformDamper(0.02, 1e-6, centrifugal_load=300.0)
    >>> law = MicroslipModel([1e6], [1e8], [0.0], 0.5)
    >>> d.add_interface(law, points=[(-4e-3, 2e-3), (-2e-3, 4e-3)], angle_deg=135,
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
            self.centrifugal_load = _load(centrifugal_load)
        elif speed is not None and radius is not None:
            speed = _checks.positive_scalar("speed", speed)
            radius = _checks.positive_scalar("radius", radius)
            self.centrifugal_load = _load(self.mass * radius * speed * speed, " (mass * radius * speed**2 underflows)")
        else:
            raise ValueError("the damper needs its static load: centrifugal_load (N), or speed (rad/s) and radius (m)")
        self.contacts: list[DamperContact] = []

    def add_interface(self, models, *, points, platform, angle_deg: float | None = None, angle: float | None = None,
                      name: str | None = None) -> None:
        """Add an interface: its contacts' laws, positions on the damper, normal angle and platform DOFs.

        Parameters
        ----------
        models : MicroslipModel or sequence of MicroslipModel
            One law for every point, or one per point.
        points : array_like, shape (k, 2)
            Contact positions on the damper from its centre of mass (m).
        platform : mapping or sequence of mappings
            The platform's DOFs at each point, ``{"x": dof, "y": dof}`` (one
            mapping for all points, or one per point), two different DOFs; a DOF
            is an index of the structure, or ``disk.next(j)`` for the next
            sector's platform.
        angle_deg : float
            Angle of the interface normal from the ``x`` axis (degrees, as the
            configuration's ``angle``); the normal points from the damper into
            the platform.
        angle : float
            Or that angle in radians (as before ``angle_deg``), ``|angle| <= 2 pi``:
            a larger value is refused as degrees given by mistake. Give one of
            ``angle_deg`` and ``angle``.
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
        a = _interface_angle(angle_deg, angle)
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
            if plats[-1]["x"] == plats[-1]["y"]:
                raise ValueError(f"platform[{i}]: 'x' and 'y' name the same DOF ({p['x']!r}): the platform's "
                                 f"circumferential and radial motions at the point are two DOFs")
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
        The new structure remembers the damper (its contacts, DOFs and load), so
        that :meth:`static_balance` finds it in any result solved on it.

        Raises
        ------
        ValueError
            No interface; a platform DOF out of range, or of the next sector on a
            plain structure; a :attr:`centrifugal_load` that is not > 0. Without a
            retention: a motion of the damper that changes no contact's normal
            approach (one contact per face: the damper rolls, held by friction
            alone), or interfaces whose normals and friction cannot hold the
            centrifugal load (a normal pointing the wrong way, an angle in the
            wrong unit).

        Warns
        -----
        UserWarning
            On a :class:`CyclicStructure`, when every face of the damper touches
            the same sector (no face, or every face, names ``disk.next``): the
            damper then joins a blade to itself.
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
        load = _load(self.centrifugal_load)
        if self.retention == 0.0:
            self._check_held()
        if cyclic:
            _warn_same_sector(self.contacts)
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
        force = np.zeros(out.ndof)
        force[n + 1] = load
        out.add_static_force(force)
        out._dampers = getattr(structure, "_dampers", ()) + (
            _Attachment(tuple(self.contacts), tuple(self.names), self.dofs, self.arm, load),)
        return out

    def _check_held(self) -> None:
        """Refuse a damper that its contacts cannot hold without a retention (a rolling one, or a wrong normal)."""
        arm = self.arm
        rows = np.array([(*c.normal, (c.normal[1] * c.point[0] - c.normal[0] * c.point[1]) / arm)
                         for c in self.contacts])
        _, sv, vt = np.linalg.svd(rows)
        held = int(np.count_nonzero(sv > 1e-6 * sv[0]))
        stiffest = max(float(c.model.kn.sum()) for c in self.contacts)
        retain = f"give the damper a retention (N/m; e.g. retention={1e-4 * stiffest:.2g}, 1e-4 of its stiffest " \
                 f"contact's normal stiffness, holds it without changing the response)"
        if held < 3:
            dX, dY, dR = vt[-1]
            theta = dR / arm
            if abs(dR) > 1e-6 * max(abs(dX), abs(dY)):
                centre = np.round(np.array([-dY, dX]) / theta * 1e3, 6) + 0.0  # mm, rounded to 1 nm
                motion = f"the rotation about the point ({centre[0]:.3g}, {centre[1]:.3g}) mm of the damper"
            else:
                motion = f"the translation along ({dX:.3g}, {dY:.3g})"
            raise ValueError(f"the damper's contacts hold only {held} of its 3 motions by their normal stiffness: "
                             f"{motion} changes no contact's normal approach ({len(self.contacts)} contacts; with one "
                             f"per face the damper rolls, as a cylinder between two flat faces does), so only "
                             f"friction holds it, and where its contacts slide nothing does: {retain}, or put two "
                             f"contacts across a flat face")
        # a push of the platform on the damper: along -nu, within the friction cone; their sum must balance the load
        pushes = []
        for c in self.contacts:
            nu, tau, beta = np.array(c.normal), np.array(c.tangent), float(np.arctan(c.model.mu))
            for side in (1.0, -1.0):
                e = -(np.cos(beta) * nu + side * np.sin(beta) * tau)
                pushes.append((e[0], e[1], (c.point[0] * e[1] - c.point[1] * e[0]) / arm))
        _, residual = nnls(np.array(pushes).T, np.array([0.0, -1.0, 0.0]))
        if residual > 1e-9:
            faces = {}
            for c in self.contacts:
                faces.setdefault(c.interface, float(np.degrees(np.arctan2(c.normal[1], c.normal[0]))))
            listed = ", ".join(f"{name!r} at {deg:.4g}°" for name, deg in faces.items())
            raise ValueError(f"the damper cannot be held against its platforms: no normal forces on its interfaces "
                             f"(normals {listed} from x, pointing from the damper into its platform) with friction "
                             f"forces within mu N balance the centrifugal load (outwards, +y) and its moment. Check "
                             f"the normals' directions and the angles' unit: add_interface takes angle_deg in "
                             f"degrees (as the configuration's angle) or angle in radians; or {retain}")

    def static_balance(self, result) -> float:
        """The static forces and moment on the damper, ``|sum|`` relative to its centrifugal load.

        Parameters
        ----------
        result : FrequencyResponse
            A result solved on a structure this damper, or a copy of it with
            the same interfaces, was attached to (:meth:`attach`;
            :func:`~microslip.frequency.damper_design_curve`'s responses too).
            The load is the one the damper had when attached to that structure.

        Returns
        -------
        float
            ``max(|F_x|, |F_y|, |M_z| / arm) / load``: the centrifugal load (and
            any static force on the damper's DOFs), the contacts' static forces and
            the retention's spring force on the damper's static displacement,
            with ``arm`` the largest distance of a contact from the centre of
            mass: zero at equilibrium.

        Raises
        ------
        TypeError
            ``result`` is not a solved response.
        ValueError
            ``result``'s structure does not carry this damper, or (with a
            retention) the result does not carry its static displacement.
        """
        structure = getattr(result, "structure", None)
        if not isinstance(structure, Structure) or not hasattr(result, "static_normal_force"):
            raise TypeError(f"result must be a FrequencyResponse solved on a structure this damper was attached to, "
                            f"got {type(result).__name__}")
        found = [a for a in getattr(structure, "_dampers", ()) if a.contacts == tuple(self.contacts)]
        if not found:
            raise ValueError(f"result: its structure ({structure!r}) carries no damper with this damper's interfaces "
                             f"({', '.join(dict.fromkeys(c.interface for c in self.contacts))}): pass a result "
                             f"solved on the structure that attach() returned")
        if len(found) > 1:
            raise ValueError(f"result: its structure carries this damper {len(found)} times (DOFs "
                             f"{', '.join(str(a.dofs) for a in found)}): its balance is ambiguous")
        a = found[0]
        names = [c.name for c in structure.contacts]
        index = [names.index(name) for name in a.names]
        N0 = np.asarray(result.static_normal_force, dtype=float)[index]
        T0 = np.asarray(result.static_tangential_force, dtype=float)[index]
        dofs = list(a.dofs)
        g = structure.preload_force()[dofs]  # generalised forces on X, Y and R = arm theta (N)
        for c, N, T in zip(a.contacts, N0, T0):
            f = -(N * np.array(c.normal) + T * np.array(c.tangent))  # the platform pushes back on the damper
            g += (f[0], f[1], (c.point[0] * f[1] - c.point[1] * f[0]) / a.arm)
        K = structure.K[dofs][:, dofs]
        K = K.toarray() if sp.issparse(K) else np.asarray(K)
        if np.any(K):  # the retention's springs, on the damper's static displacement
            g -= K @ _static_displacement(result, dofs)
        return float(np.max(np.abs(g)) / a.load)


def _static_displacement(result, dofs) -> np.ndarray:
    """The static displacement (m) of ``dofs`` in ``result`` (its ``static_coefficients``)."""
    q = getattr(result, "static_coefficients", None)
    where = {int(d): i for i, d in enumerate(getattr(result, "dofs", ()))}
    if q is None or not all(d in where for d in dofs):
        raise ValueError("result: it does not carry the damper's static displacement (static_coefficients), which "
                         "the retention's force needs: pass a result of frequency_response or frequency_point")
    return np.real(np.asarray(q)[[where[d] for d in dofs]])


def _warn_same_sector(contacts) -> None:
    """Warn when every face of a damper on a sector touches the same sector's platforms."""
    faces: dict = {}
    for c in contacts:
        faces.setdefault(c.interface, set()).update(isinstance(d, NextDof) for d in c.platform.values())
    kinds = set().union(*faces.values())
    if len(kinds) == 1:
        which = "the next sector's (disk.next)" if kinds == {True} else "this sector's"
        warnings.warn(f"every face of the damper ({', '.join(map(repr, faces))}) touches {which} platform: the "
                      f"damper joins a blade to itself; a damper between blades names the next sector's platform "
                      f"DOFs on one face, with disk.next(j) (\"next:j\" in the configuration)",
                      OneSidedDamperWarning, stacklevel=3)


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
