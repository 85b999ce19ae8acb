"""The exact continuous contact as a fine microslip array: the method of dimensionality reduction.

Popov & Heß's method of dimensionality reduction (MDR) maps the continuous
axisymmetric frictional contact (Hertz + Cattaneo--Mindlin +
Mindlin--Deresiewicz for a sphere) onto a row of independent springs on a
line ``-a..a``. A spring at ``x`` of width ``dx`` has

* normal stiffness ``E* dx`` and gap ``g(x)`` (the MDR profile, ``x^2 / R``
  for a sphere, see :mod:`microslip.reference.profiles`);
* tangential stiffness ``G*_P dx`` with ``G*_P = 4 G*`` (``1/G* = 2(2 - nu)/G``
  for identical bodies),

and obeys Coulomb's law with its own normal force. That is exactly the
paper's element, so a fine array of them -- a :class:`MDRModel`, which *is* a
:class:`~microslip.MicroslipModel` -- gives the exact continuous answer for
any history of normal approach and unidirectional tangential displacement,
with the same compiled kernel.

On the contact plane (``t`` of shape ``(steps, 2)``) every spring becomes an
isotropic Jenkins element of the plane, its trial force returned radially
onto its disc ``mu N_i``. Along a straight line through the rest position
(every increment of ``t`` parallel to it, e.g. :func:`microslip.paths.line`
at any angle) that is the
1D MDR along the line, so it is exact as above, whatever ``n`` does. On a
curved orbit it is the usual approximation, not an exact solution: the MDR
is derived for unidirectional tangential loading; applied spring by spring
on the plane, each spring's friction force follows that spring's own
stretch, whereas in the continuous contact the traction at each point is
set by the local slip of the two-dimensional contact area, which a row of
springs does not resolve. On a circle in gross slip the array's own energy
has a closed form: each spring slides round its own circle and dissipates
``2 pi mu N_i sqrt(R^2 - (mu N_i / kt_i)^2)`` per cycle
(``tests/reference/test_mdr_plane.py``).

The row is symmetric about ``x = 0``; the two springs at ``+x`` and ``-x``
always carry the same forces, so one element of width ``2 dx`` stands for
both. Element ``i`` (1-based) sits at the midpoint ``x_i = (i - 1/2) a_max / J``.
The array represents the contact only while the contact radius stays within
``a_max``: at approaches beyond ``g(a_max)`` -- loads beyond the
``max_load`` it was built for -- it would extrapolate, so it refuses them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import optimize

from ..common import _checks
from ..common.errors import LoadLimitError
from ..model import MicroslipModel, State, Step
from .profiles import SphereProfile, as_profile

#: relative slack on the approach limit, for round-off in approaches computed from loads
_APPROACH_RTOL = 1e-9


_DECREASING = ("profile: its MDR profile g(x) decreases somewhere in the contact; the method needs a "
               "non-decreasing g (an indenter whose contact grows with the load)")


@dataclass(frozen=True, eq=False, repr=False)
class MDRModel(MicroslipModel):
    """A microslip array that discretises a continuous contact (built by :func:`mdr`).

    Behaves as a :class:`~microslip.MicroslipModel` in every respect, except
    that approaches beyond ``max_approach`` raise :class:`LoadLimitError`
    instead of being extrapolated.

    Attributes
    ----------
    max_load : float
        Largest normal load (N) the array covers.
    max_approach : float
        Normal approach (m) at ``max_load``: ``g(a_max)``.
    contact_radius : float
        ``a_max`` (m), the half-length of the row.
    profile : object
        The profile discretised (see :mod:`microslip.reference.profiles`).
    """

    max_load: float = np.inf
    max_approach: float = np.inf
    contact_radius: float = np.inf
    profile: object = None

    def __repr__(self) -> str:
        return (f"MDRModel(J={self.elements}, mu={self.mu:g}, max_load={self.max_load:.6g} N, "
                f"max_approach={self.max_approach:.6g} m, contact_radius={self.contact_radius:.6g} m)")

    def check_approach(self, n) -> np.ndarray:
        """Return ``n`` (m) as a finite array, or raise :class:`LoadLimitError` beyond ``max_approach``."""
        n = _checks.real_array("n", n)
        if n.size and float(n.max()) > self.max_approach * (1.0 + _APPROACH_RTOL):
            k = int(np.argmax(n))
            raise LoadLimitError(
                f"n reaches {float(n.max()):.6g} m (at flat index {k}), beyond the approach "
                f"{self.max_approach:.6g} m of max_load = {self.max_load:.6g} N this MDR model was built for; "
                f"it would have to extrapolate past its outermost element. Build it with a larger "
                f"max_load (mdr(..., max_load=...)).")
        return n

    def element_normal_forces(self, n) -> np.ndarray:
        """As :meth:`MicroslipModel.element_normal_forces`; refuses ``n > max_approach``."""
        return super().element_normal_forces(self.check_approach(n))

    def simulate(self, t, n, state: State | None = None, *, per_element: bool = True, work: bool = True):
        """As :meth:`MicroslipModel.simulate`; refuses ``n > max_approach`` (:class:`LoadLimitError`).

        An MDR array has thousands of elements: for long histories pass
        ``per_element=False`` (``(steps, J)`` arrays of 10^5 steps x 2000
        elements take 1.8 GB) and, when no energy is wanted, ``work=False``.
        """
        self.check_approach(n)
        return super().simulate(t, n, state, per_element=per_element, work=work)

    def trial(self, state: State | None, t: float, n: float) -> Step:
        """As :meth:`MicroslipModel.trial`; refuses ``n > max_approach`` (:class:`LoadLimitError`)."""
        self.check_approach(n)
        return super().trial(state, t, n)

    def approach(self, N) -> np.ndarray:
        """As :meth:`MicroslipModel.approach`; refuses ``N > max_load`` (:class:`LoadLimitError`)."""
        N = _checks.positive_array("N", N, allow_zero=True)
        if N.size and float(N.max()) > self.max_load * (1.0 + _APPROACH_RTOL):
            raise LoadLimitError(f"N reaches {float(N.max()):.6g} N, beyond max_load = {self.max_load:.6g} N "
                                 "this MDR model was built for; build it with a larger max_load")
        return super().approach(N)

    def to_dict(self) -> dict:
        """Refused: the saved form of a plain array would lose the load limit (use :func:`mdr` again)."""
        raise TypeError("an MDRModel is not saved: its file would be a plain MicroslipModel without the "
                        "max_load it may be used up to; rebuild it with mdr(reference, max_load=..., "
                        "elements=...) instead")

    def as_reference(self) -> "MDRContact":
        """This array as a :class:`~microslip.tuning.ContactReference` (loads in N), for :func:`~microslip.tune`."""
        return MDRContact(self)


@dataclass(frozen=True)
class MDRContact:
    """A continuous contact given by its MDR array, seen as a reference: loads in, forces out.

    Satisfies :class:`~microslip.tuning.ContactReference`, so the paper's
    tuning and the load paths work for any axisymmetric profile, not only
    for the sphere's closed forms. Every quantity comes from the array at
    the approach that carries the load, exactly as the continuous contact.

    Parameters
    ----------
    model : MDRModel
        The array (from :func:`mdr`).
    """

    model: MDRModel

    def __post_init__(self):
        if not isinstance(self.model, MDRModel):
            raise TypeError(f"model must be an MDRModel (from microslip.mdr), got {type(self.model).__name__}")

    @property
    def mu(self) -> float:
        """Friction coefficient."""
        return self.model.mu

    @property
    def max_load(self) -> float:
        """Largest load (N) the array covers."""
        return self.model.max_load

    def approach(self, N):
        """Normal approach (m) at load ``N`` (N); refuses loads beyond ``max_load``."""
        return self.model.approach(N)

    def normal_force(self, n):
        """Normal force (N) at approach ``n`` (m); refuses approaches beyond the limit."""
        return self.model.normal_force(n)

    def backbone(self, t, N):
        """Virgin tangential force (N) at displacement ``t`` (m) and constant load ``N`` (N), broadcast."""
        _checks.broadcast(t=_checks.real_array("t", t), N=_checks.real_array("N", N))
        return self.model.backbone(t, self.approach(N))

    def gross_slip_displacement(self, N):
        """Displacement (m) at which every element slips at load ``N`` (N): ``max_i mu N_i / kt_i``."""
        Ni = self.model.element_normal_forces(self.approach(N))
        return (self.mu * Ni / self.model.kt).max(axis=-1)

    def backbone_displacement(self, T, N):
        """Inverse of :meth:`backbone` for ``|T| <= mu N`` (odd in ``T``); ``N`` a scalar load (N).

        The array's backbone is piecewise linear between the displacements
        at which its elements slip, so the inverse is exact interpolation.
        """
        T = _checks.real_array("T", T)
        N = _checks.positive_scalar("N", N)
        limit = self.mu * float(self.model.normal_force(self.approach(N)))
        if np.any(np.abs(T) > limit * (1 + 1e-12)):
            raise ValueError(f"T must satisfy |T| <= mu*N = {limit:.6g} N (gross slip), got up to "
                             f"{float(np.abs(T).max()):.6g} N")
        slips = np.unique(np.concatenate([[0.0], self.mu * self.model.element_normal_forces(self.approach(N))
                                          / self.model.kt]))
        forces = self.backbone(slips, N)
        return np.sign(T) * np.interp(np.abs(T), forces, slips)


def contact_radius(profile, E_star: float, normal_load: float) -> float:
    """Contact radius (m) of an axisymmetric profile at a normal load (N).

    Solves ``N = 2 E* (a g(a) - integral_0^a g(x) dx)`` (MDR normal law) for
    ``a``; closed form ``(3 N R / (4 E*))^(1/3)`` for a sphere.

    Parameters
    ----------
    profile : profile object or callable ``f(r)``
        The indenter (m of m).
    E_star : float
        Contact modulus (Pa).
    normal_load : float
        Normal load (N), positive.
    """
    profile = as_profile(profile)
    E_star = _checks.positive_scalar("E_star", E_star)
    load = _checks.positive_scalar("normal_load", normal_load)
    if isinstance(profile, SphereProfile):
        return float(np.cbrt(3.0 * load * profile.radius / (4.0 * E_star)))
    nodes, weights = np.polynomial.legendre.leggauss(96)

    def force(a):
        x = 0.5 * a * (nodes + 1.0)
        return 2.0 * E_star * (a * float(profile.mdr(a)) - 0.5 * a * float(np.dot(weights, profile.mdr(x))))

    hi = 1e-3 * profile.scale
    for _ in range(80):
        if force(hi) >= load:
            break
        if float(profile.mdr(2.0 * hi)) < float(profile.mdr(hi)):
            raise ValueError(_DECREASING)
        hi *= 2.0
    else:  # pragma: no cover - only for profiles that never carry the load
        raise ValueError(f"normal_load: the profile does not carry {load:g} N at any contact radius up to {hi:g} m")
    return float(optimize.brentq(lambda a: force(a) - load, 0.0, hi, xtol=1e-14 * hi, rtol=1e-12))


def mdr(reference, *, max_load, elements: int = 2000, profile=None) -> MDRModel:
    """Build the exact continuous contact as a fine microslip array (method of dimensionality reduction).

    Parameters
    ----------
    reference : Sphere or similar
        Provides the elastic constants ``E_star`` (Pa), ``G_star`` (Pa), the
        friction coefficient ``mu`` and, when ``profile`` is omitted, the
        sphere ``radius`` (m).
    max_load : float
        Largest normal load (N) the array must cover. Approaches beyond the
        one at this load raise :class:`LoadLimitError`.
    elements : int, default 2000
        Number of elements ``J`` (each stands for the pair at ``+x``, ``-x``).
        The measured errors against the closed forms fall as about ``J^-2``
        (table in ``tests/test_mdr.py``): with 1600 elements, Hertz's load
        within 2.3e-7, the Cattaneo--Mindlin backbone within 2.4e-7 of
        ``mu N``, Mindlin's energy per cycle within 5e-6 at
        ``T*/(mu N) = 0.5`` and 1.2e-4 at 0.1.
    profile : profile object or callable f(r), optional
        Axisymmetric indenter shape (see :mod:`microslip.reference.profiles`):
        a callable ``f(r)`` (m of m), or a ``SphereProfile``,
        ``RoundedPunch``, ``AxisymmetricProfile``. Default: the sphere of
        ``reference.radius``.

    Returns
    -------
    MDRModel
        ``kt = 2 G*_P dx``, ``kn = 2 E* dx``, ``gaps = g(x_i)`` at the
        midpoints ``x_i = (i - 1/2) dx`` of ``0..a_max``, ``dx = a_max / J``.

    Examples
    --------
    >>> from microslip import Sphere, mdr
    >>> sphere = Sphere.paper()
    >>> ref = mdr(sphere, max_load=50.0, elements=2000)
    >>> round(float(ref.normal_force(sphere.approach(37.5))), 4)
    37.5
    """
    missing = [k for k in ("E_star", "G_star", "mu") if not hasattr(reference, k)]
    if missing:
        raise TypeError(f"reference must provide E_star, G_star and mu (e.g. a Sphere); "
                        f"{type(reference).__name__} lacks {', '.join(missing)}")
    J = _checks.size("elements", elements, minimum=1)
    load = _checks.positive_scalar("max_load", max_load)
    if profile is None:
        if not hasattr(reference, "radius"):
            raise TypeError(f"give profile= for a reference without a radius ({type(reference).__name__})")
        profile = SphereProfile(reference.radius)
    profile = as_profile(profile)
    E_star = float(reference.E_star)
    G_P = 4.0 * float(reference.G_star)
    a = contact_radius(profile, E_star, load)
    dx = a / J
    x = (np.arange(J) + 0.5) * dx
    gaps = np.asarray(profile.mdr(x), dtype=float)
    if np.any(np.diff(gaps) < 0):
        raise ValueError(_DECREASING)
    kt, kn = np.full(J, 2.0 * G_P * dx), np.full(J, 2.0 * E_star * dx)
    # the limit is the profile's approach at a_max, or the array's own approach at max_load when the
    # midpoint rule puts that a hair beyond (relative ~1/J^2): both mean "the load it was built for"
    own = float(MicroslipModel(kt=kt, kn=kn, gaps=gaps, mu=float(reference.mu)).approach(load))
    return MDRModel(kt=kt, kn=kn, gaps=gaps, mu=float(reference.mu), max_load=load,
                    max_approach=max(float(profile.mdr(a)), own), contact_radius=a, profile=profile)
