"""A reference contact built from measured hysteresis loops (the paper's Sect. 3).

The paper tunes its array on a branch of a steady measured loop at the
highest normal load: by Masing's rule the branch is the backbone scaled by
two about its reversal point. This module turns loops into a
:class:`~microslip.tuning.ContactReference`, so that
``tune(MeasuredContact.from_loops(...), N_tot, elements=J)`` works as for
the analytic sphere.

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

The backbone at a lower load
----------------------------
Only the curve at the tuning load ``N_ref`` is measured. At a load
``N < N_ref`` the reference uses the rule that holds for any elastic contact
of the Cattaneo--Mindlin kind, uncoupled and on a half-space (Ciavarella;
Jäger): the tangential force is ``mu`` times the normal force lost by the
stick zone, ``T(t, N) = mu [N - N_stick]``. In terms of the measured curve
``f`` this reads

    ``T(t, N) = f(x0 + t) - f(x0)``,  with ``f(x0) = mu (N_ref - N)``:

the backbone at ``N`` is the part of the backbone at ``N_ref`` beyond the
point where it has reached ``mu (N_ref - N)``. For a sphere it gives
Cattaneo--Mindlin at every load exactly (checked in the tests); it needs no
normal law, and its gross-slip displacement is ``x_gs - x0(N)``. Loads above
``N_ref`` cannot be predicted and raise an error.

The fitted curve is scaled by ``mu N_ref / plateau`` so that it reaches
``mu N_ref`` exactly, as :func:`~microslip.tune` requires; when ``mu`` is
fitted from the slip forces at all loads the scale differs from 1 by the
scatter of the slip forces (reported).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy import optimize

from . import _checks
from .loops import Loops
from .tuning import TuningError

_BINS = 160
_KNOTS = 8
_MICROSLIP_MIN = 1.05  # k0 x_gs / T_gs below this: no microslip region (1 for a single Jenkins element)
_BACKLASH_RATIO = 2.0  # a branch step stiffer than this x the softest before it: backlash
_MASING_TOLERANCE = 0.1
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
        x = np.asarray(x, dtype=float)
        flat = np.abs(x).ravel()
        flat = np.minimum(flat, self.gross_slip_displacement)
        return (np.sign(x).ravel() * (_ramps(flat, self.knots, self.exponents) @ self.weights)).reshape(x.shape)

    def slope(self, x):
        """Slope (N/m) at ``x >= 0`` (m)."""
        x = np.asarray(x, dtype=float)
        u = np.minimum(x.ravel()[:, None] / self.knots[None, :], 1.0)
        slope = (1.0 - u) ** (self.exponents - 1.0) @ self.weights
        return np.where(x.ravel() < self.gross_slip_displacement, slope, 0.0).reshape(x.shape)

    def inverse(self, T):
        """Displacement (m) at force ``T`` (N), ``0 <= T <= plateau`` (bisection, to round-off)."""
        T = np.asarray(T, dtype=float)
        lo = np.zeros(T.shape)
        hi = np.full(T.shape, self.gross_slip_displacement)
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            below = self(mid) < T
            lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
        return 0.5 * (lo + hi)

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
        Number of knots ``M`` of the fit (see the module docstring).

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
    M = _checks.positive_int("knots", knots, minimum=2)
    top = float(x.max())
    if not top > 0:
        raise ValueError("x must not be all zero")
    edges = np.linspace(0.0, top, _BINS + 1)
    which = np.minimum(np.digitize(x, edges) - 1, _BINS - 1)
    count = np.bincount(which, minlength=_BINS)
    keep = count > 0
    xb = (np.bincount(which, weights=x, minlength=_BINS)[keep] / count[keep])
    yb = (np.bincount(which, weights=y, minlength=_BINS)[keep] / count[keep])
    wb = np.sqrt(count[keep].astype(float))

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
    residual = float(np.sqrt(np.sum(count[keep] * (yb - _evaluate(xb, c, p, coef)) ** 2) / count[keep].sum()))
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
                          residual=residual, points=(xb, yb, count[keep]))


def _evaluate(x, c, p, coef):
    return coef[0] - coef[1] + _ramps(x, c, p) @ coef[2:]


@dataclass(frozen=True, eq=False)
class MeasuredContact:
    """A :class:`~microslip.tuning.ContactReference` from a measured branch and a normal law (SI units).

    Build it with :meth:`from_loops`. The backbone at the tuning load is the
    fitted branch scaled to reach ``mu * normal_load``; at lower loads see
    the module docstring (the part of that backbone beyond ``mu (N_ref - N)``).

    Parameters
    ----------
    fit : FittedBackbone
        The curve fitted to the branch at the tuning load.
    normal : object
        The normal law: ``approach(N) -> n`` and ``normal_force(n) -> N``
        (m, N), e.g. :class:`microslip.Cylinder`.
    mu : float
        Friction coefficient.
    normal_load : float
        Tuning load ``N_ref`` (N), where the branch was measured.
    """

    fit: FittedBackbone
    normal: object
    mu: float
    normal_load: float
    notes: dict = field(default_factory=dict)

    def __post_init__(self):
        object.__setattr__(self, "mu", _checks.positive_scalar("mu", self.mu))
        object.__setattr__(self, "normal_load", _checks.positive_scalar("normal_load", self.normal_load))
        for name in ("approach", "normal_force"):
            if not hasattr(self.normal, name):
                raise TypeError(f"normal must provide approach(N) and normal_force(n) (e.g. microslip.Cylinder), "
                                f"got {type(self.normal).__name__}")

    @property
    def scale(self) -> float:
        """Factor applied to the fitted curve so that it reaches ``mu N_ref``: ``mu N_ref / plateau``."""
        return self.mu * self.normal_load / self.fit.plateau

    # -- ContactReference -------------------------------------------------------
    def _x0(self, N):
        N = _checks.positive_array("N", N)
        if np.any(N > self.normal_load * (1 + 1e-12)):
            raise ValueError(f"N must not exceed the tuning load {self.normal_load:g} N, where the branch was "
                             f"measured (no data above it), got {float(np.max(N)):g} N")
        N = np.minimum(N, self.normal_load)
        return self.fit.inverse(self.mu * (self.normal_load - N) / self.scale), N

    def _f(self, x):
        return self.scale * self.fit(np.minimum(x, self.fit.gross_slip_displacement))

    def backbone(self, t, N):
        """Virgin tangential force (N) at displacement ``t`` (m), load ``0 < N <= normal_load`` (N); odd in ``t``."""
        t = _checks.real_array("t", t)
        x0, N = self._x0(N)
        return np.sign(t) * (self._f(x0 + np.abs(t)) - self._f(x0))

    def backbone_displacement(self, T, N):
        """Inverse of :meth:`backbone`: displacement (m) at force ``T`` (N), ``|T| <= mu N``."""
        T = _checks.real_array("T", T)
        x0, N = self._x0(N)
        limit = self.mu * N
        if np.any(np.abs(T) > limit * (1 + 1e-9)):
            raise ValueError(f"T must satisfy |T| <= mu*N (gross slip); it exceeds it by up to "
                             f"{float(np.max(np.abs(T) - limit)):.6g} N")
        target = (np.minimum(np.abs(T), limit) + self.mu * (self.normal_load - N)) / self.scale
        x = self.fit.inverse(np.minimum(target, self.fit.plateau))
        return np.sign(T) * np.maximum(x - x0, 0.0)

    def gross_slip_displacement(self, N):
        """Displacement (m) at which the backbone at load ``N`` (N) reaches ``mu N``."""
        x0, _ = self._x0(N)
        return self.fit.gross_slip_displacement - x0

    def approach(self, N):
        """Normal approach (m) at load ``N`` (N), from the normal law."""
        return self.normal.approach(N)

    def normal_force(self, n):
        """Normal load (N) at approach ``n`` (m), from the normal law."""
        return self.normal.normal_force(n)

    def branch(self, t, N, t_reversal, T_reversal):
        """Masing branch (N) at load ``N`` from the reversal ``(t_reversal, T_reversal)`` (m, N)."""
        from .reference import masing

        N = float(_checks.positive_scalar("N", N))
        return masing.branch(lambda x: self.backbone(x, N), t, t_reversal, T_reversal)

    # -- construction -----------------------------------------------------------
    @classmethod
    def from_loops(cls, loops, normal, *, mu=None, normal_load=None, knots: int = _KNOTS,
                   masing_tolerance: float = _MASING_TOLERANCE) -> "MeasuredContact":
        """Fit the reference on the steady loops at the highest normal load.

        Parameters
        ----------
        loops : Loops or sequence of Loops
            Analysed records (:func:`microslip.loops.analyse`), each with its
            ``normal_load``; the one at the highest load is tuned on, all of
            them give the friction coefficient when it is not given.
        normal : object
            Normal law, ``approach(N)`` and ``normal_force(n)``: e.g.
            :class:`microslip.Cylinder`. Its ``mu``, if set, is used.
        mu : float, optional
            Friction coefficient; default ``normal.mu``, else fitted from the
            slip forces (least squares through the origin of the slip force
            against the normal load, over the records in gross slip).
        normal_load : float, optional
            Tuning load (N); default the highest of the records (it must be
            one of them, to 0.1 %).
        knots : int, default 8
            Knots of the backbone fit.
        masing_tolerance : float, default 0.1
            Largest acceptable Masing error of the tuning record (fraction
            of the force amplitude).

        Raises
        ------
        TuningError
            The data cannot be represented: loops not steady, not in gross
            slip, far from Masing, backlash (a convex start after reversals),
            no microslip region. The message gives the numbers.
        """
        items = _loops_list(loops)
        ref = _tuning_record(items, normal_load)
        N_ref = float(ref.normal_load)
        _check_representable(ref, masing_tolerance)
        x, y = ref.backbone_points()
        fit = fit_backbone(x, y, knots=knots)
        if fit.microslip_ratio < _MICROSLIP_MIN:
            raise TuningError(
                f"{ref.record.source}: the branch has no microslip region: initial stiffness "
                f"{fit.initial_stiffness:.4g} N/m x gross-slip displacement {fit.gross_slip_displacement:.4g} m "
                f"/ slip force {fit.plateau:.4g} N = {fit.microslip_ratio:.3f} (1 for a single macroslip "
                f"element, 1.5 for Cattaneo-Mindlin; needs >= {_MICROSLIP_MIN}): model it with one element")
        notes = {"fit_residual": fit.residual, "fit_relative_residual": fit.relative_residual,
                 "masing_error": ref.masing_error, "masing_basis": ref.masing_basis}
        mu_given = mu if mu is not None else getattr(normal, "mu", None)
        if mu_given is None:
            mu_value, notes["mu_fit_residual"] = fit_mu(items)
            notes["mu_source"] = "fitted from the slip forces"
        else:
            mu_value = _checks.positive_scalar("mu", mu_given)
            notes["mu_source"] = "given"
        return cls(fit=fit, normal=normal, mu=mu_value, normal_load=N_ref, notes=notes)


def fit_mu(loops) -> tuple[float, float]:
    """Friction coefficient from the slip forces of records in gross slip.

    Least squares through the origin of the steady slip force ``(F+ - F-)/2``
    against the normal load.

    Parameters
    ----------
    loops : Loops or sequence of Loops
        Analysed records with their normal loads.

    Returns
    -------
    mu : float
    residual : float
        RMS residual of the slip forces about ``mu N`` (N).
    """
    items = [L for L in _loops_list(loops) if L.summary()["gross_slip"]]
    if not items:
        raise TuningError("cannot fit mu: no record reaches gross slip (give mu)")
    N = np.array([L.normal_load for L in items])
    F = np.array([L.summary()["slip_force"] for L in items])
    mu = float(F @ N / (N @ N))
    return mu, float(np.sqrt(np.mean((F - mu * N) ** 2)))


def _loops_list(loops) -> list:
    items = [loops] if isinstance(loops, Loops) else list(loops)
    if not items:
        raise ValueError("loops must hold at least one analysed record, got none")
    for L in items:
        if not isinstance(L, Loops):
            raise TypeError(f"loops must be microslip.loops.Loops (from loops.analyse), got {type(L).__name__}")
        if L.normal_load is None:
            raise ValueError(f"{L.record.source}: the normal load is unknown; give normal_load= to loops.read, "
                             f"an 'N [N]' column or a '# normal load = ... N' comment")
    return items


def _tuning_record(items, normal_load):
    loads = np.array([L.normal_load for L in items])
    if normal_load is None:
        return items[int(np.argmax(loads))]
    N = _checks.positive_scalar("normal_load", normal_load)
    k = int(np.argmin(np.abs(loads - N)))
    if abs(loads[k] - N) > 1e-3 * N:
        raise ValueError(f"normal_load: no record at {N:g} N; the records are at {sorted(loads.tolist())} N")
    return items[k]


def _check_representable(ref: Loops, masing_tolerance):
    src = ref.record.source
    s = ref.summary()
    if not ref.is_steady:
        raise TuningError(f"{src}: the loops never became steady: no two consecutive cycles agree within "
                          f"{100 * ref.options['steady_tolerance']:g} % in energy and amplitude "
                          f"(energies {np.array2string(ref.energy, precision=3)} J)")
    if not s["gross_slip"]:
        raise TuningError(f"{src}: the steady loops do not reach gross slip (the slope at the end of the "
                          f"branches is not below 10 % of the stick stiffness), so they give no slip force "
                          f"mu*N: test with a larger amplitude")
    if ref.masing_error > masing_tolerance:
        raise TuningError(f"{src}: the loops are far from Masing's rule: the branches differ from the backbone "
                          f"({ref.masing_basis}) by {100 * ref.masing_error:.3g} % of the force amplitude (RMS), "
                          f"more than the {100 * masing_tolerance:g} % allowed; the paper's array obeys Masing's "
                          f"rule and cannot represent them")
    ratio, soft, stiff, band = backlash(ref)
    if ratio > _BACKLASH_RATIO:
        raise TuningError(f"{src}: the branches are not concave (backlash): after softening to {soft:.4g} N/m "
                          f"(over {band * 1e6:.4g} µm of the branch) they stiffen again to {stiff:.4g} N/m, "
                          f"{ratio:.3g} times stiffer (a concave branch only softens; allowed up to "
                          f"{_BACKLASH_RATIO:g} for noise). The paper's array is concave and cannot represent it")


def backlash(loops: Loops) -> tuple[float, float, float, float]:
    """How much the steady branches stiffen again after softening (backlash, a dead band).

    The rise of the backbone points up to 90 % of their top force is split
    into 18 equal steps of force; the secant stiffness of each is measured
    on the binned points. A concave branch only softens; with backlash it
    softens (free play) and then stiffens again.

    Returns
    -------
    ratio : float
        Largest ``stiffness of a step / least stiffness of the steps before
        it`` (<= 1 for a concave branch, up to noise).
    soft, stiff : float
        Those two stiffnesses (N/m).
    dead_band : float
        Displacement travelled on the branch in the soft step (m).
    """
    x, y = loops.backbone_points()
    edges = np.linspace(0.0, x.max(), 81)
    which = np.minimum(np.digitize(x, edges) - 1, 79)
    count = np.bincount(which, minlength=80)
    keep = count > 0
    xb = np.bincount(which, weights=x, minlength=80)[keep] / count[keep]
    yb = np.maximum.accumulate(np.bincount(which, weights=y, minlength=80)[keep] / count[keep])
    levels = np.linspace(0.0, 0.9 * yb.max(), 19)
    xl = np.interp(levels, yb, xb)  # first crossing of each force level (yb made non-decreasing)
    dx = np.maximum(np.diff(xl), 1e-300)
    k = (levels[1] - levels[0]) / dx  # secant stiffness of backbone steps = of branch steps
    softest = np.minimum.accumulate(k)
    ratios = k[1:] / softest[:-1]
    j = int(np.argmax(ratios))
    i = int(np.argmin(k[:j + 1]))
    return float(ratios[j]), float(k[i]), float(k[j + 1]), float(2 * dx[i])
