"""A smooth, increasing, concave curve fitted to the backbone points of measured branches.

The backbone fit
----------------
A raw branch is noisy and not exactly concave, and the paper's equations
need a concave curve (every element stiffness is a drop in slope). The
backbone points ``(x, y)`` of the steady branches (half the displacement and
half the force change from each reversal) are averaged in 160 bins of
``x`` and fitted, by weighted non-negative least squares, with

    ``y(x) = c0 + sum_{m,q} w_mq (c_m / p_q) (1 - (1 - min(x / c_m, 1))^p_q)``,  ``w_mq >= 0``,
    knots ``c_m = m x_gs / M`` (m = 1..M), exponents ``p_q`` in 1.02, 1.1, 1.25, 1.5, 2, 3,

a sum of Cattaneo--Mindlin-like ramps, each increasing, strictly concave
below its knot and flat beyond it, with unit initial slope (``c0`` absorbs
the bias of the reversal points and is dropped). Any such sum is increasing
and concave with a continuous slope, strictly so up to its last knot (whose
ramp spans the whole range), where it reaches its plateau, the gross-slip
force. The family holds Cattaneo--Mindlin's curve (``p = 1.5``) and the
curve of any contact with a power normal law ``N ~ n^p`` exactly. The last knot ``x_gs`` is found by
minimising the residual over it (a scan on a logarithmic grid refined by a
bounded 1-D search). Where a curve meets its plateau tangentially its end
is ill-determined by noisy data, so the fitted curve is cut where it comes
within 0.1 % of its plateau: that point is the gross-slip displacement and
the force there the gross-slip force (the cut keeps it concave). The RMS residual of the
binned points is reported (:attr:`FittedBackbone.residual`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy import optimize

from ..common import _checks
from ..common._binning import binned_means
from ..common._numeric import invert_increasing
from ..tuning import TuningError

_BINS = 160
_KNOTS = 8
_PLATEAU_CUT = 1e-3  # gross slip: where the fit comes within this fraction of its plateau


_EXPONENTS = np.array([1.02, 1.1, 1.25, 1.5, 2.0, 3.0])


def _ramps(x, knots, exponents):
    """Basis ``(c / p) (1 - (1 - min(x / c, 1))^p)`` for paired ``knots`` and ``exponents``, shape (P, K)."""
    u = np.minimum(x[:, None] / knots[None, :], 1.0)
    return (knots / exponents)[None, :] * (1.0 - (1.0 - u) ** exponents[None, :])


@dataclass(frozen=True, eq=False)
class FittedBackbone:
    """A smooth, increasing, concave curve fitted to backbone points (SI units).

    Attributes
    ----------
    knots : ndarray, shape (K,)
        Knots ``c`` (m) of the ramps with non-zero weight.
    exponents : ndarray, shape (K,)
        Their exponents ``p``.
    weights : ndarray, shape (K,)
        Their weights ``w`` (N/m), positive; the initial slope is their sum.
    gross_slip_displacement : float
        Displacement at which the curve reaches its plateau (m).
    plateau : float
        The plateau, the gross-slip force (N).
    offset : float
        Constant fitted along (N), dropped from the curve: the mean bias of
        the reversal points.
    residual : float
        RMS residual of the binned points (N).
    points : tuple of ndarray
        The binned points ``(x, y, count)`` that were fitted.
    """

    knots: np.ndarray
    exponents: np.ndarray
    weights: np.ndarray
    gross_slip_displacement: float
    plateau: float
    offset: float
    residual: float
    points: tuple = field(repr=False)

    @property
    def initial_stiffness(self) -> float:
        """Slope at the origin (N/m)."""
        return float(self.weights.sum())

    @property
    def microslip_ratio(self) -> float:
        """``initial stiffness * x_gs / plateau``: 1 for one Jenkins element, 1.5 for Cattaneo--Mindlin."""
        return self.initial_stiffness * self.gross_slip_displacement / self.plateau

    @property
    def relative_residual(self) -> float:
        """:attr:`residual` as a fraction of the plateau."""
        return self.residual / self.plateau

    def __call__(self, x):
        """Force (N) at displacement ``x`` (m), odd in ``x``, flat beyond gross slip."""
        x = _checks.real_array("x", x)
        flat = np.abs(x).ravel()
        flat = np.minimum(flat, self.gross_slip_displacement)
        return (np.sign(x).ravel() * (_ramps(flat, self.knots, self.exponents) @ self.weights)).reshape(x.shape)

    def slope(self, x):
        """Slope (N/m) at ``x >= 0`` (m)."""
        x = _checks.positive_array("x", x, allow_zero=True)
        u = np.minimum(x.ravel()[:, None] / self.knots[None, :], 1.0)
        slope = (1.0 - u) ** (self.exponents - 1.0) @ self.weights
        return np.where(x.ravel() < self.gross_slip_displacement, slope, 0.0).reshape(x.shape)

    def inverse(self, T):
        """Displacement (m) at force ``T`` (N), ``0 <= T <= plateau`` (bisection, to round-off).

        ``T`` may exceed the plateau by a relative 1e-9 (round-off), and is
        then taken as the plateau.
        """
        T = _checks.positive_array("T", T, allow_zero=True)
        if np.any(T > self.plateau * (1 + 1e-9)):
            raise ValueError(f"T must not exceed the plateau {self.plateau:.6g} N (the gross-slip force), got "
                             f"{float(np.max(T)):.6g} N")
        return invert_increasing(self, np.minimum(T, self.plateau), 0.0, self.gross_slip_displacement)

    def plot(self, ax=None):
        """Plot the binned points and the fitted curve (force in N against µm); returns the Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(5.5, 4))
        x, y, _ = self.points
        grid = np.linspace(0.0, max(x.max(), self.gross_slip_displacement), 300)
        ax.plot(x * 1e6, y, ".", color="0.5", ms=3, label="measured (binned, Masing: branch / 2)")
        ax.plot(grid * 1e6, self(grid), "k-", lw=1.6,
                label=f"concave fit (RMS residual {100 * self.relative_residual:.2g} %)")
        ax.set_xlabel("half displacement from reversal (µm)")
        ax.set_ylabel("half force change T (N)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        return ax


def fit_backbone(x, y, *, knots: int = _KNOTS) -> FittedBackbone:
    """Fit a smooth, increasing, concave curve through backbone points.

    Parameters
    ----------
    x : array_like, shape (P,)
        Displacement from the origin (m), >= 0 (e.g. half the displacement
        from a reversal).
    y : array_like, shape (P,)
        Force (N) at each ``x``.
    knots : int, default 8
        Number of knots ``M`` of the fit (see the module docstring), 2 to 160
        (the bins the points are averaged in).

    Returns
    -------
    FittedBackbone
    """
    x = _checks.real_array("x", x, ndim=1, min_size=8)
    y = _checks.real_array("y", y, ndim=1, min_size=8)
    if x.size != y.size:
        raise ValueError(f"x and y must have the same length, got {x.size} and {y.size}")
    if np.any(x < 0):
        raise ValueError(f"x must be >= 0 (displacement from the reversal), got {x.min():.6g} m")
    M = _checks.size("knots", knots, minimum=2, maximum=_BINS)
    top = float(x.max())
    if not top > 0:
        raise ValueError("x must not be all zero")
    edges = np.linspace(0.0, top, _BINS + 1)
    count, (xb, yb) = binned_means(x, edges, x, y)
    keep = count > 0
    xb, yb, count = xb[keep], yb[keep], count[keep]
    wb = np.sqrt(count.astype(float))

    def solve(x_gs):
        c = np.repeat(x_gs * np.arange(1, M + 1) / M, _EXPONENTS.size)
        p = np.tile(_EXPONENTS, M)
        A = np.column_stack([np.ones_like(xb), -np.ones_like(xb), _ramps(xb, c, p)]) * wb[:, None]
        coef, _ = optimize.nnls(A, yb * wb, maxiter=50 * A.shape[1])
        return c, p, coef

    def cost(log_x):
        c, p, coef = solve(np.exp(log_x))
        return float(np.sum((wb * (yb - _evaluate(xb, c, p, coef))) ** 2))

    grid = np.linspace(np.log(0.03 * top), np.log(top), 36)
    costs = [cost(g) for g in grid]
    k = int(np.argmin(costs))
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]
    best = optimize.minimize_scalar(cost, bounds=(lo, hi), method="bounded", options={"xatol": 1e-4})
    log_x = best.x if best.fun < costs[k] else grid[k]
    c, p, coef = solve(np.exp(log_x))
    residual = float(np.sqrt(np.sum(count * (yb - _evaluate(xb, c, p, coef)) ** 2) / count.sum()))
    w = coef[2:]
    active = w > 1e-12 * w.max() if w.max() > 0 else w > 0
    if not active.any():
        raise TuningError("the backbone points do not rise: the fitted curve is flat (no stick stiffness)")
    c, p, w = c[active], p[active], w[active]
    full = float(w @ (c / p))
    grid = np.linspace(0.0, float(c.max()), 4001)
    values = _ramps(grid, c, p) @ w
    cut = float(grid[np.argmax(values >= (1.0 - _PLATEAU_CUT) * full)])
    return FittedBackbone(knots=c, exponents=p, weights=w, gross_slip_displacement=cut,
                          plateau=float((_ramps(np.array([cut]), c, p) @ w)[0]), offset=float(coef[0] - coef[1]),
                          residual=residual, points=(xb, yb, count))


def _evaluate(x, c, p, coef):
    return coef[0] - coef[1] + _ramps(x, c, p) @ coef[2:]
