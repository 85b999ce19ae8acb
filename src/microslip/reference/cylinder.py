"""Cylinder pressed on a plane along a generatrix (line contact): normal approach laws.

For a line contact the elastic half-space gives no finite normal approach,
so the approach--load curve is semi-empirical (Harris, *Rolling Bearing
Analysis*, as used by the paper's Sect. 3):

* **Palmgren**: ``delta[mm] = 3.84e-5 Q^0.9 / l^0.8`` (Q in N, l in mm),
  fitted to steel on steel; ``E`` and ``nu`` do not enter it;
* **Lundberg--Sjövall**: ``delta = 2 Q (1 - nu^2) / (pi E l) * ln(pi l^2 E / (Q (1 - nu^2)))``
  (SI). Its inverse ``Q(delta)`` has no elementary form; writing
  ``u = Q (1 - nu^2) / (pi l^2 E)`` it reads ``-u ln u = delta / (2 l)``, solved
  with the ``k = -1`` branch of Lambert's W (``u = exp(W_{-1}(-delta/(2l)))``);
  for two materials ``E / (1 - nu^2)`` becomes the pair's ``2 E*`` (:mod:`.materials`),
  valid while ``delta < 2 l / e`` (far beyond any elastic load);
* a **table** of measured (approach, load) pairs, interpolated with a
  monotone cubic (PCHIP), inverted by bisection on the same interpolant so
  that ``normal_force(approach(N)) == N`` to round-off.

The tangential behaviour of a finite cylinder has no closed form: it comes
from measured loops (:class:`microslip.MeasuredContact`), which also give
``mu`` when it is not known.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy import interpolate, special

from ..common import _checks
from ..common._numeric import invert_increasing
from .materials import check_second_body, contact_moduli

LAWS = ("palmgren", "lundberg")
_PALMGREN = 3.84e-5  # mm N^-0.9 mm^0.8 (Harris)


@dataclass(frozen=True)
class Cylinder:
    """A cylinder of length ``length`` and radius ``radius`` pressed on a plane of the same material.

    Parameters
    ----------
    length : float
        Length of the line of contact l (m). The paper: 10e-3.
    radius : float
        Cylinder radius R (m). The paper: 5e-3 (d = 10 mm).
    E : float
        Young's modulus of the cylinder (Pa), and of the flat unless ``E2`` is
        given. Steel: 200e9.
    nu : float
        Poisson's ratio, in (-1, 0.5].
    mu : float, optional
        Friction coefficient; ``None`` when it is to be fitted from measured
        slip forces.
    law : {"palmgren", "lundberg"} or array_like, shape (k, 2)
        The approach--load law: Palmgren's (Harris), Lundberg--Sjövall's, or
        a table of ``(approach m, load N)`` rows, both strictly increasing
        (a row ``(0, 0)`` is added when the table does not start at zero load).
    E2, nu2 : float, optional
        Young's modulus (Pa) and Poisson's ratio of the flat when it is of
        another material; both or neither (identical bodies, the default).
        Lundberg--Sjövall's law and the contact half-width use the pair's ``E*``.

    Examples
    --------
    >>> from microslip import Cylinder
    >>> c = Cylinder(length=10e-3, radius=5e-3, E=200e9, nu=0.3, mu=0.4)
    >>> round(float(c.approach(36.6)) * 1e9, 1)   # nm, Palmgren
    155.4
    >>> round(float(c.normal_force(c.approach(36.6))), 9)
    36.6
    """

    length: float
    radius: float
    E: float
    nu: float
    mu: float | None = None
    law: object = "palmgren"
    E2: float | None = None
    nu2: float | None = None
    _table: object = field(default=None, init=False, repr=False, compare=False)

    def __post_init__(self):
        object.__setattr__(self, "length", _checks.positive_scalar("length", self.length))
        object.__setattr__(self, "radius", _checks.positive_scalar("radius", self.radius))
        object.__setattr__(self, "E", _checks.positive_scalar("E", self.E))
        object.__setattr__(self, "nu", _checks.in_range("nu", self.nu, -1.0, 0.5, lo_open=True))
        if self.mu is not None:
            object.__setattr__(self, "mu", _checks.positive_scalar("mu", self.mu))
        if self.E2 is not None or self.nu2 is not None:
            E2, nu2 = check_second_body(self.E, self.nu, self.E2, self.nu2)
            object.__setattr__(self, "E2", E2)
            object.__setattr__(self, "nu2", nu2)
        if isinstance(self.law, str):
            if self.law not in LAWS:
                raise ValueError(f"law must be one of {list(LAWS)} or a table of (approach, load) rows, "
                                 f"got {self.law!r}")
        else:
            object.__setattr__(self, "_table", _Table(self.law))
            object.__setattr__(self, "law", "table")

    @classmethod
    def from_file(cls, path, length, radius, E, nu, mu=None, *, E2=None, nu2=None) -> "Cylinder":
        """A cylinder whose normal law is the table in ``path``.

        The file is CSV/text with a header naming the columns ``n`` (approach)
        and ``N`` (load) with their units, e.g. ``n [um], N [N]``; values are
        converted to SI. The other parameters are as for :class:`Cylinder`.
        """
        from ..common._table import column_si, read_table

        path = _checks.file_path("path", path)
        columns, units = read_table(path)
        rows = np.column_stack([column_si(columns, units, "n", "length", path=path),
                                column_si(columns, units, "N", "force", path=path)])
        return cls(length, radius, E, nu, mu, rows, E2, nu2)

    @property
    def law_name(self) -> str:
        """Readable name of the normal law."""
        return {"palmgren": "Palmgren (Harris)", "lundberg": "Lundberg-Sjövall", "table": "measured table"}[self.law]

    @property
    def E_star(self) -> float:
        """Contact modulus ``E*`` (Pa): ``E / (2 (1 - nu^2))`` for identical bodies, see :mod:`.materials`."""
        return contact_moduli(self.E, self.nu, *check_second_body(self.E, self.nu, self.E2, self.nu2))[0]

    def with_mu(self, mu) -> "Cylinder":
        """The same cylinder with friction coefficient ``mu``."""
        law = self.law if self._table is None else self._table.rows
        return Cylinder(self.length, self.radius, self.E, self.nu, mu, law, self.E2, self.nu2)

    # -- normal law ---------------------------------------------------------
    def approach(self, N):
        """Normal approach (m) at normal load ``N`` (N), same shape as ``N``; 0 at ``N = 0``."""
        N = _checks.positive_array("N", N, allow_zero=True)
        if self.law == "palmgren":
            l_mm = self.length * 1e3
            return 1e-3 * _PALMGREN * N**0.9 / l_mm**0.8
        if self.law == "lundberg":
            Ep = 2.0 * self.E_star  # E / (1 - nu^2) for identical bodies
            A = np.pi * self.length**2 * Ep
            with np.errstate(divide="ignore", invalid="ignore"):
                out = 2.0 * N / (np.pi * Ep * self.length) * np.log(A / np.where(N > 0, N, 1.0))
            return np.where(N > 0, out, 0.0)
        return self._table.approach(N)

    def normal_force(self, n):
        """Normal load (N) at normal approach ``n`` (m), same shape; 0 for ``n <= 0``."""
        n = _checks.real_array("n", n)
        m = np.maximum(n, 0.0)
        if self.law == "palmgren":
            l_mm = self.length * 1e3
            with np.errstate(over="ignore"):  # an overflow is refused just below
                return _checks.finite_result("n", n, (m * 1e3 * l_mm**0.8 / _PALMGREN) ** (1.0 / 0.9))
        if self.law == "lundberg":
            y = m / (2.0 * self.length)
            if np.any(y > 1.0 / np.e):
                raise ValueError(f"n must stay below 2 l / e = {2 * self.length / np.e:.6g} m for the "
                                 f"Lundberg-Sjövall law, got up to {float(np.max(m)):.6g} m")
            u = np.exp(np.real(special.lambertw(-np.where(y > 0, y, 1e-300), k=-1)))
            return np.where(y > 0, u * np.pi * self.length**2 * 2.0 * self.E_star, 0.0)
        return self._table.normal_force(m)

    def normal_stiffness(self, N):
        """Normal stiffness ``dN/dn`` (N/m) at load ``N`` (N), ``N > 0``."""
        N = _checks.positive_array("N", N)
        if self.law == "palmgren":
            return N / (0.9 * self.approach(N))
        if self.law == "lundberg":
            Ep = 2.0 * self.E_star
            A = np.pi * self.length**2 * Ep
            return np.pi * Ep * self.length / (2.0 * (np.log(A / N) - 1.0))
        return self._table.stiffness(self.approach(N))

    def contact_half_width(self, N):
        """Hertz half-width of the contact strip ``b = sqrt(4 N R / (pi l E*))`` (m) at load ``N`` (N)."""
        N = _checks.positive_array("N", N, allow_zero=True)
        return np.sqrt(4.0 * N * self.radius / (np.pi * self.length * self.E_star))


class _Table:
    """Monotone (PCHIP) approach--load curve through measured rows."""

    def __init__(self, rows):
        arr = _checks.real_array("law", rows)
        if arr.ndim != 2 or arr.shape[1] != 2 or arr.shape[0] < 2:
            raise ValueError(f"law: a table must have shape (k, 2) with k >= 2 rows of (approach m, load N), "
                             f"got shape {arr.shape}")
        n, N = arr[:, 0], arr[:, 1]
        if np.any(n < 0) or np.any(N < 0):
            raise ValueError("law: approaches and loads in the table must be non-negative")
        if N[0] > 0:
            n, N = np.concatenate([[0.0], n]), np.concatenate([[0.0], N])
        for name, v, unit in (("approach", n, "m"), ("load", N, "N")):
            bad = np.flatnonzero(np.diff(v) <= 0)
            if bad.size:
                i = int(bad[0])
                raise ValueError(f"law: the table is not monotone: {name} of row {i + 2} ({v[i + 1]:.6g} {unit}) "
                                 f"does not exceed row {i + 1} ({v[i]:.6g} {unit}); both columns must increase")
        self.rows = np.column_stack([n, N])
        self._f = interpolate.PchipInterpolator(n, N, extrapolate=False)
        self._df = self._f.derivative()

    def _check(self, what, value, top, unit):
        if np.any(value > top * (1 + 1e-12)):
            raise ValueError(f"{what} beyond the table: up to {float(np.max(value)):.6g} {unit}, the table ends "
                             f"at {top:.6g} {unit}")

    def normal_force(self, n):
        n0, n1 = self.rows[0, 0], self.rows[-1, 0]
        self._check("n", n, n1, "m")
        return np.where(n <= n0, 0.0, self._f(np.clip(n, n0, n1)))

    def stiffness(self, n):
        n0, n1 = self.rows[0, 0], self.rows[-1, 0]
        return self._df(np.clip(n, n0, n1))

    def approach(self, N):
        N = np.asarray(N, dtype=float)
        self._check("N", N, self.rows[-1, 1], "N")
        k = np.clip(np.searchsorted(self.rows[:, 1], N, side="right") - 1, 0, len(self.rows) - 2)
        x = invert_increasing(self._f, N, self.rows[k, 0], self.rows[k + 1, 0])  # the monotone interpolant
        return np.where(N <= 0, 0.0, x)
