"""Sphere pressed on a plane: Hertz, Cattaneo--Mindlin, Masing and Mindlin--Deresiewicz.

Both bodies are of the same elastic material (the paper's benchmark: a steel
sphere on a steel plane). For identical bodies

* ``1/E* = 2 (1 - nu^2) / E`` (Hertz),
* ``G = E / (2 (1 + nu))`` and ``1/G* = 2 (2 - nu) / G`` (Cattaneo--Mindlin).

All quantities are SI: m, N, Pa, J. Every method is vectorised over NumPy
arrays and broadcasts its arguments.

Note on the paper: it prints E = 200 MPa for steel; that is a typo for
200 GPa (with 200 GPa the gross-slip displacement at 37.5 N is 1.1 µm, as
in its Fig. 2a).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..common import _checks
from . import masing, mindlin
from .materials import check_second_body, contact_moduli


@dataclass(frozen=True)
class Sphere:
    """A sphere of radius ``radius`` pressed on a plane (the same material, or another).

    Parameters
    ----------
    radius : float
        Sphere radius R (m). The paper's benchmark: 5e-3 (d = 10 mm).
    E : float
        Young's modulus (Pa). Steel: 200e9.
    nu : float
        Poisson's ratio, in (-1, 0.5].
    mu : float
        Friction coefficient, positive.
    E2, nu2 : float, optional
        Young's modulus (Pa) and Poisson's ratio of the plane when it is of
        another material (e.g. a nickel-alloy blade platform under a cobalt-alloy
        damper); both or neither (identical bodies, the default).

    Examples
    --------
    >>> from microslip import Sphere
    >>> s = Sphere(radius=5e-3, E=200e9, nu=0.3, mu=0.4)
    >>> round(s.gross_slip_displacement(37.5) * 1e6, 3)   # µm
    1.145
    """

    radius: float
    E: float
    nu: float
    mu: float
    E2: float | None = None
    nu2: float | None = None

    def __post_init__(self):
        object.__setattr__(self, "radius", _checks.positive_scalar("radius", self.radius))
        object.__setattr__(self, "E", _checks.positive_scalar("E", self.E))
        object.__setattr__(self, "nu", _checks.in_range("nu", self.nu, -1.0, 0.5, lo_open=True))
        object.__setattr__(self, "mu", _checks.positive_scalar("mu", self.mu))
        if self.E2 is not None or self.nu2 is not None:
            E2, nu2 = check_second_body(self.E, self.nu, self.E2, self.nu2)
            object.__setattr__(self, "E2", E2)
            object.__setattr__(self, "nu2", nu2)

    @classmethod
    def paper(cls) -> "Sphere":
        """The paper's benchmark: d = 10 mm, steel E = 200 GPa (not MPa), nu = 0.3, mu = 0.4."""
        return cls(radius=5e-3, E=200e9, nu=0.3, mu=0.4)

    # -- elastic constants -------------------------------------------------
    @property
    def E_star(self) -> float:
        """Contact modulus ``E*`` (Pa): ``E / (2 (1 - nu^2))`` for identical bodies, see :mod:`.materials`."""
        return contact_moduli(self.E, self.nu, *check_second_body(self.E, self.nu, self.E2, self.nu2))[0]

    @property
    def G(self) -> float:
        """Shear modulus ``E / (2 (1 + nu))`` (Pa)."""
        return self.E / (2.0 * (1.0 + self.nu))

    @property
    def G_star(self) -> float:
        """Tangential contact modulus ``G*`` (Pa), ``G / (2 (2 - nu))`` for identical bodies; initial stiffness
        is ``8 G* a``."""
        return contact_moduli(self.E, self.nu, *check_second_body(self.E, self.nu, self.E2, self.nu2))[1]

    # -- Hertz ------------------------------------------------------------
    def _load(self, N):
        return _checks.positive_array("N", N, allow_zero=True)

    def contact_radius(self, N):
        """Hertz contact radius ``a = (3 N R / (4 E*))^(1/3)`` (m) at normal load ``N`` (N)."""
        N = self._load(N)
        return np.cbrt(3.0 * N * self.radius / (4.0 * self.E_star))

    def approach(self, N):
        """Hertz normal approach ``delta = a^2 / R`` (m) at normal load ``N`` (N)."""
        return self.contact_radius(N) ** 2 / self.radius

    def normal_force(self, n):
        """Hertz normal force ``N = 4/3 E* sqrt(R) n^(3/2)`` (N) at approach ``n`` (m); 0 for ``n <= 0``."""
        n = _checks.real_array("n", n)
        with np.errstate(over="ignore"):  # an overflow is refused just below
            N = 4.0 / 3.0 * self.E_star * np.sqrt(self.radius) * np.maximum(n, 0.0) ** 1.5
        return _checks.finite_result("n", n, N)

    def normal_stiffness(self, N):
        """Hertz normal stiffness ``dN/dn = 2 a E*`` (N/m) at normal load ``N`` (N)."""
        return 2.0 * self.E_star * self.contact_radius(N)

    # -- Cattaneo--Mindlin (constant N) -----------------------------------
    def tangential_stiffness(self, N):
        """Initial tangential stiffness ``8 G* a`` (N/m) at normal load ``N`` (N)."""
        return 8.0 * self.G_star * self.contact_radius(N)

    def gross_slip_displacement(self, N):
        """Tangential displacement at gross slip, ``3 mu N / (16 G* a)`` (m), at load ``N`` (N)."""
        N = self._load(N)
        a = self.contact_radius(N)
        with np.errstate(invalid="ignore", divide="ignore"):
            out = np.where(N > 0, 3.0 * self.mu * N / (16.0 * self.G_star * np.where(a > 0, a, 1.0)), 0.0)
        return out

    def backbone(self, t, N):
        """Virgin (Cattaneo--Mindlin) tangential force (N) at displacement ``t`` (m), load ``N`` (N).

        ``T = mu N (1 - (1 - t/t_gs)^(3/2))`` for ``|t| <= t_gs``, ``mu N`` beyond
        (odd in ``t``), with ``t_gs`` the gross-slip displacement.
        """
        t = _checks.real_array("t", t)
        N = self._load(N)
        _checks.broadcast(t=t, N=N)
        tgs = self.gross_slip_displacement(N)
        with np.errstate(invalid="ignore", divide="ignore"):
            x = np.where(tgs > 0, np.minimum(np.abs(t) / np.where(tgs > 0, tgs, 1.0), 1.0), 1.0)
        return np.sign(t) * self.mu * N * (1.0 - (1.0 - x) ** 1.5)

    def backbone_displacement(self, T, N):
        """Inverse of :meth:`backbone`: displacement (m) at tangential force ``T`` (N), ``|T| <= mu N``.

        ``t = t_gs (1 - (1 - |T|/(mu N))^(2/3))``, odd in ``T``.
        """
        T = _checks.real_array("T", T)
        N = self._load(N)
        _checks.broadcast(T=T, N=N)
        limit = self.mu * N
        if np.any(np.abs(T) > limit * (1 + 1e-12)):
            worst = np.max(np.abs(T) - limit)
            raise ValueError(f"T must satisfy |T| <= mu*N (gross slip); it exceeds it by up to {worst:.6g} N")
        with np.errstate(invalid="ignore", divide="ignore"):
            x = np.where(limit > 0, np.minimum(np.abs(T) / np.where(limit > 0, limit, 1.0), 1.0), 0.0)
        return np.sign(T) * self.gross_slip_displacement(N) * (1.0 - (1.0 - x) ** (2.0 / 3.0))

    def branch(self, t, N, t_reversal, T_reversal):
        """Masing unloading/reloading branch (N) from the reversal ``(t_reversal, T_reversal)``.

        ``T = T_r + 2 f((t - t_r)/2)`` with ``f`` the backbone at load ``N`` (N); the
        reversal is a point the contact can reach, ``|T_reversal| <= mu N``.
        """
        N = float(_checks.positive_scalar("N", N))
        T_r = _checks.real_scalar("T_reversal", T_reversal)
        if abs(T_r) > self.mu * N * (1 + 1e-12):
            raise ValueError(f"T_reversal must satisfy |T_reversal| <= mu*N = {self.mu * N:.6g} N (no force beyond "
                             f"gross slip), got {T_r:.6g} N")
        return masing.branch(lambda x: self.backbone(x, N), t, t_reversal, T_reversal)

    def loop(self, amplitude, N, points: int = 401):
        """Steady hysteresis loop of displacement amplitude ``amplitude`` (m) at load ``N`` (N).

        Returns
        -------
        t, T : ndarray, shape (2 * points - 1,)
            From ``+amplitude`` down to ``-amplitude`` and back up (m, N).
        """
        N = float(_checks.positive_scalar("N", N))
        return masing.loop(lambda x: self.backbone(x, N), amplitude, points)

    def dissipation(self, T_amplitude, N):
        """Energy dissipated per cycle (J) for a tangential force amplitude ``T_amplitude`` (N).

        Mindlin's result for ``x = T*/(mu N) <= 1``::

            W = 9 mu^2 N^2 / (10 a G*) * (1 - (1-x)^(5/3) - (5x/6) (1 + (1-x)^(2/3)))

        (checked against the numerically integrated Masing loop in the tests),
        evaluated as ``9 T*^2 / (10 a G*) * bracket / x^2`` with the bracket's
        series below ``x = 0.1``: the bracket is ``5 x^3 / 162 + ...``, and its
        closed form would lose every digit to cancellation at small ``x``.
        """
        Ta = _checks.positive_array("T_amplitude", T_amplitude, allow_zero=True)
        N = _checks.positive_array("N", N)
        x = Ta / (self.mu * N)
        if np.any(x > 1 + 1e-12):
            raise ValueError("T_amplitude must not exceed mu*N (the gross-slip force); "
                             f"got T_amplitude/(mu N) up to {np.max(x):.6g}")
        x = np.minimum(x, 1.0)
        a = self.contact_radius(N)
        W = 9.0 * Ta**2 / (10.0 * a * self.G_star) * _mindlin_bracket_over_x2(x)
        return _checks.finite_result("T_amplitude", Ta, W)

    # -- Mindlin--Deresiewicz (normal load raised at constant T) ----------
    def raised_load_path(self, T, N, dN, T_A):
        """Displacement (m) along the Mindlin--Deresiewicz path of the paper's Fig. 4a.

        Path: from O, ``T`` rises to ``T_A`` at constant load ``N`` (point A);
        the load is raised to ``N + dN`` at constant ``T``; then ``T`` rises
        again, on the virgin curve at ``N + dN`` shifted to start at A up to
        the join point B (``T_B = T_A + mu dN``), on that curve itself beyond.
        :func:`microslip.reference.mindlin.raised_load_path` applied to this
        sphere: ``T`` (N), ``0 <= T <= mu (N + dN)``; ``N``, ``dN`` (N);
        ``T_A`` (N), ``0 <= T_A <= mu N``; returns an array shaped like ``T``.
        """
        return mindlin.raised_load_path(self, T, N, dN, T_A)

    def join_point(self, N, dN, T_A):
        """Point B where the raised-load path joins the virgin curve at ``N + dN``.

        Returns
        -------
        t_B, T_B : float
            ``T_B = T_A + mu dN`` (N) and its displacement (m).
        """
        return mindlin.join_point(self, N, dN, T_A)


def _binomial(p: float, k: int) -> float:
    """Generalised binomial coefficient ``C(p, k)``."""
    out = 1.0
    for i in range(k):
        out *= (p - i) / (i + 1)
    return out


#: the bracket of Mindlin's energy, 1 - (1-x)^(5/3) - (5x/6) (1 + (1-x)^(2/3)) = sum_k c_k x^k (k >= 3):
#: c_k = -C(5/3, k) (-1)^k - (5/6) C(2/3, k-1) (-1)^(k-1); below x = 0.1, 24 terms reach round-off (x^22 < 1e-22)
_BRACKET_SERIES = np.array([-_binomial(5 / 3, k) * (-1) ** k - 5 / 6 * _binomial(2 / 3, k - 1) * (-1) ** (k - 1)
                            for k in range(3, 27)])


def _mindlin_bracket_over_x2(x):
    """Mindlin's bracket divided by ``x^2`` (0 at ``x = 0``), to round-off for every ``x`` in ``[0, 1]``."""
    x = np.asarray(x, dtype=float)
    small = x < 0.1
    with np.errstate(invalid="ignore", divide="ignore"):
        closed = (1.0 - (1.0 - x) ** (5.0 / 3.0) - (5.0 * x / 6.0) * (1.0 + (1.0 - x) ** (2.0 / 3.0))) / x**2
    series = np.polynomial.polynomial.polyval(x, np.concatenate([[0.0], _BRACKET_SERIES]))
    return np.where(small, series, closed)
