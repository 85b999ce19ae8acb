"""Axisymmetric contact profiles and their equivalent plane profiles (method of dimensionality reduction).

An axisymmetric indenter with height ``f(r)`` (m) above its lowest point at
radius ``r`` (m) is, in the method of dimensionality reduction (Popov & Heß),
equivalent to a row of independent springs on a line whose gaps are::

    g(x) = |x| * integral_0^|x| f'(r) / sqrt(x^2 - r^2) dr
         = |x| * integral_0^(pi/2) f'(|x| sin th) d th        (r = |x| sin th)

The second form has a smooth integrand and is what the quadrature uses.
Closed forms:

* sphere of radius ``R`` (``f = r^2 / (2 R)``): ``g(x) = x^2 / R``;
* flat punch of radius ``b`` with edges rounded to radius ``rho``
  (``f = 0`` for ``r <= b``, ``(r - b)^2 / (2 rho)`` beyond):
  ``g(x) = |x| / rho * (sqrt(x^2 - b^2) - b arccos(b / |x|))`` for ``|x| > b``,
  0 inside.

Every profile provides ``height(r)`` and ``mdr(x)`` (both m of m, vectorised)
and ``scale`` (m), a length on which its shape changes (used to bracket the
contact radius).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
from scipy import integrate

from ..common import _checks


@dataclass(frozen=True)
class SphereProfile:
    """A sphere (paraboloid) of radius ``radius`` (m): ``f(r) = r^2 / (2 R)``, ``g(x) = x^2 / R``."""

    radius: float

    def __post_init__(self):
        object.__setattr__(self, "radius", _checks.positive_scalar("radius", self.radius))

    @property
    def scale(self) -> float:
        """Length scale of the shape (m): the radius."""
        return self.radius

    def height(self, r):
        """Height ``r^2 / (2 R)`` (m) at radius ``r`` (m)."""
        r = _checks.real_array("r", r)
        with np.errstate(over="ignore"):  # an overflow is refused just below
            return _checks.finite_result("r", r, r**2 / (2.0 * self.radius))

    def mdr(self, x):
        """Equivalent plane profile ``x^2 / R`` (m) at position ``x`` (m)."""
        x = _checks.real_array("x", x)
        with np.errstate(over="ignore"):
            return _checks.finite_result("x", x, x**2 / self.radius)


@dataclass(frozen=True)
class RoundedPunch:
    """A flat punch of radius ``flat_radius`` (m) whose edge is rounded to radius ``edge_radius`` (m).

    ``f(r) = 0`` for ``r <= b`` and ``(r - b)^2 / (2 rho)`` beyond (``b`` the
    flat radius, ``rho`` the edge radius); its MDR profile is in closed form
    (module docstring).
    """

    flat_radius: float
    edge_radius: float

    def __post_init__(self):
        object.__setattr__(self, "flat_radius",
                           _checks.positive_scalar("flat_radius", self.flat_radius, allow_zero=True))
        object.__setattr__(self, "edge_radius", _checks.positive_scalar("edge_radius", self.edge_radius))

    @property
    def scale(self) -> float:
        """Length scale of the shape (m): the larger of the two radii."""
        return max(self.flat_radius, self.edge_radius)

    def height(self, r):
        """Height (m) at radius ``r`` (m): 0 on the flat, ``(|r| - b)^2 / (2 rho)`` beyond."""
        r = np.abs(_checks.real_array("r", r))
        with np.errstate(over="ignore"):
            return _checks.finite_result("r", r, np.maximum(r - self.flat_radius, 0.0) ** 2 / (2.0 * self.edge_radius))

    def mdr(self, x):
        """Equivalent plane profile (m) at position ``x`` (m), closed form."""
        x = np.abs(_checks.real_array("x", x))
        b = self.flat_radius
        out = np.zeros_like(x)
        beyond = x > b
        xb = x[beyond]
        with np.errstate(over="ignore", invalid="ignore"):
            out[beyond] = xb / self.edge_radius * (np.sqrt(xb**2 - b**2) - b * np.arccos(b / xb))
        return _checks.finite_result("x", x, out)


@dataclass(frozen=True)
class AxisymmetricProfile:
    """Any axisymmetric profile ``f(r)``; its MDR profile is found by quadrature.

    Parameters
    ----------
    shape : callable
        ``f(r)``: height (m) of the indenter above its lowest point at radius
        ``r >= 0`` (m); vectorised over NumPy arrays, ``f(0) = 0``,
        non-decreasing.
    scale : float
        A length (m) on which the shape changes (e.g. a radius of curvature);
        used to step the search for the contact radius and the finite
        difference of ``f`` when ``slope`` is not given.
    slope : callable, optional
        ``f'(r)`` (-). Default: a central finite difference of ``shape``
        with step ``1e-6 * scale`` (the profile is taken as even in ``r``).
    breaks : sequence of float, optional
        Radii (m) where ``f'`` jumps or has a kink; the quadrature splits
        there (without them it still converges, more slowly, and SciPy may
        warn).

    Examples
    --------
    >>> p = AxisymmetricProfile(lambda r: r**2 / (2 * 5e-3), scale=5e-3)
    >>> round(float(p.mdr(1e-4) / (1e-4**2 / 5e-3)), 9)
    1.0
    """

    shape: Callable
    scale: float
    slope: Callable | None = None
    breaks: tuple = ()

    def __post_init__(self):
        if not callable(self.shape):
            raise TypeError(f"shape must be a callable f(r) returning heights in m, got {type(self.shape).__name__}")
        if self.slope is not None and not callable(self.slope):
            raise TypeError(f"slope must be a callable f'(r) or None, got {type(self.slope).__name__}")
        object.__setattr__(self, "scale", _checks.positive_scalar("scale", self.scale))
        breaks = _checks.positive_array("breaks", self.breaks, ndim=1)
        object.__setattr__(self, "breaks", tuple(float(b) for b in np.sort(breaks)))

    def height(self, r):
        """Height ``f(|r|)`` (m) at radius ``r`` (m)."""
        r = _checks.real_array("r", r)
        f = np.asarray(self.shape(np.abs(r)), dtype=float)
        if np.count_nonzero(np.isfinite(f)) != f.size:
            k = int(np.flatnonzero(~np.isfinite(f.ravel()))[0])
            raise ValueError(f"r = {float(np.abs(r).ravel()[k]):.6g} m: the profile's shape(r) is not finite there "
                             f"({float(f.ravel()[k])!r})")
        return f

    def _slope(self, r):
        if self.slope is not None:
            return np.asarray(self.slope(r), dtype=float)
        h = 1e-6 * self.scale
        return (np.asarray(self.shape(np.abs(r + h)), dtype=float)
                - np.asarray(self.shape(np.abs(r - h)), dtype=float)) / (2.0 * h)

    def mdr(self, x):
        """Equivalent plane profile (m) at position ``x`` (m), by adaptive quadrature.

        ``g(x) = |x| * integral_0^(pi/2) f'(|x| sin th) d th``. Raises
        ``ValueError`` if ``f`` is not finite where it is evaluated.
        """
        x = np.abs(_checks.real_array("x", x))
        flat = x.ravel()
        out = np.empty_like(flat)
        for k, xk in enumerate(flat):
            if xk == 0.0:
                out[k] = 0.0
                continue
            inner = [float(np.arcsin(b / xk)) for b in self.breaks if b < xk]
            value, _ = integrate.quad(lambda th: float(self._slope(xk * np.sin(th))), 0.0, np.pi / 2,
                                      points=inner or None, limit=200, epsabs=0.0, epsrel=1e-10)
            if not np.isfinite(value):
                raise ValueError(f"x = {xk:.6g} m: the slope of the profile (shape) is not finite below that radius")
            out[k] = xk * value
        return out.reshape(x.shape)


def as_profile(profile):
    """Return ``profile`` if it is a profile object, or wrap a callable ``f(r)`` (scale 1 mm)."""
    if hasattr(profile, "mdr") and hasattr(profile, "scale"):
        return profile
    if callable(profile):
        return AxisymmetricProfile(profile, scale=1e-3)
    raise TypeError("profile must be a SphereProfile, RoundedPunch, AxisymmetricProfile or a callable f(r) "
                    f"(heights in m), got {type(profile).__name__}")
