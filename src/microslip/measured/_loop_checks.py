"""Checks that measured loops can be tuned on, and the friction coefficient from their slip forces (private).

The paper's array is a Masing, concave, rate-independent contact: loops that
never became steady, never reach gross slip, are far from Masing's rule or
stiffen again after softening (backlash) cannot be represented, and each
check says so with the numbers (:class:`~microslip.tuning.TuningError`).
"""

from __future__ import annotations

import numpy as np

from ..common import _checks
from ..common._binning import binned_means
from .loops import Loops
from ..tuning import TuningError

_BACKLASH_RATIO = 2.0  # a branch step stiffer than this x the softest before it: backlash


def loops_list(loops) -> list:
    """``loops`` (one :class:`Loops` or a sequence) as a non-empty list, each with a normal load."""
    if not isinstance(loops, Loops) and (isinstance(loops, (str, bytes)) or not hasattr(loops, "__iter__")):
        raise TypeError(f"loops must be microslip.loops.Loops or a sequence of them, got {type(loops).__name__}")
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


def normal_law(normal, needs=("approach", "normal_force")):
    """Check that ``normal`` provides the methods ``needs`` of a normal law; returns it."""
    missing = [name for name in needs if not callable(getattr(normal, name, None))]
    if missing:
        raise TypeError(f"normal must provide {' and '.join(f'{n}()' for n in needs)} of a normal law "
                        f"(e.g. microslip.Cylinder); {type(normal).__name__} lacks {', '.join(missing)}")
    return normal


def tuning_record(items, normal_load):
    """The record at ``normal_load`` (N, to 0.1 %), default the one at the highest load."""
    loads = np.array([L.normal_load for L in items])
    if normal_load is None:
        return items[int(np.argmax(loads))]
    N = _checks.positive_scalar("normal_load", normal_load)
    k = int(np.argmin(np.abs(loads - N)))
    if abs(loads[k] - N) > 1e-3 * N:
        raise ValueError(f"normal_load: no record at {N:g} N; the records are at {sorted(loads.tolist())} N")
    return items[k]


def check_loops(ref: Loops, masing_tolerance: float) -> None:
    """Refuse a tuning record that is not steady, not in gross slip or far from Masing's rule."""
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


def check_concave(x, y, source: str) -> None:
    """Refuse backbone points ``(x, y)`` (m, N) that stiffen again after softening (backlash)."""
    ratio, soft, stiff, band = points_backlash(x, y)
    if ratio > _BACKLASH_RATIO:
        raise TuningError(f"{source}: the branches are not concave (backlash): after softening to {soft:.4g} N/m "
                          f"(over {band * 1e6:.4g} µm of the branch) they stiffen again to {stiff:.4g} N/m, "
                          f"{ratio:.3g} times stiffer (a concave branch only softens; allowed up to "
                          f"{_BACKLASH_RATIO:g} for noise). The paper's array is concave and cannot represent it")


def backlash(loops: Loops) -> tuple[float, float, float, float]:
    """How much the steady branches stiffen again after softening (backlash, a dead band).

    The rise of the backbone points up to 90 % of their top force is split
    into 18 equal steps of force, the first from the reversal (``x = 0``);
    the secant stiffness of each is measured on the binned points. A
    concave branch only softens; with backlash it softens (free play) and
    then stiffens again.

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
    return points_backlash(*loops.backbone_points())


def points_backlash(x, y) -> tuple[float, float, float, float]:
    """:func:`backlash` of backbone points ``x`` (m, >= 0) and ``y`` (N), shape (P,).

    The points are averaged in 80 bins of ``x``, fewer (down to 10) when
    there are fewer than 10 points per bin (a single branch).
    """
    bins = int(np.clip(x.size // 10, 10, 80))
    count, (xb, yb) = binned_means(x, np.linspace(0.0, x.max(), bins + 1), x, y)
    keep = count > 0
    xb, yb = xb[keep], np.maximum.accumulate(yb[keep])
    levels = np.linspace(0.0, 0.9 * yb.max(), 19)
    xl = np.interp(levels, yb, xb)  # first crossing of each force level (yb made non-decreasing)
    # level 0 is the reversal, where every branch starts (x = y = 0): interpolating it would skip a
    # dead band, whose points sit at y = +-1 ulp of the slip force, or not, by the sign of that rounding
    xl[0] = 0.0
    dx = np.maximum(np.diff(xl), 1e-300)
    k = (levels[1] - levels[0]) / dx  # secant stiffness of backbone steps = of branch steps
    softest = np.minimum.accumulate(k)
    ratios = k[1:] / softest[:-1]
    j = int(np.argmax(ratios))
    i = int(np.argmin(k[:j + 1]))
    return float(ratios[j]), float(k[i]), float(k[j + 1]), float(2 * dx[i])


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
    items = [L for L in loops_list(loops) if L.summary()["gross_slip"]]
    if not items:
        raise TuningError("cannot fit mu: no record reaches gross slip (give mu)")
    N = np.array([L.normal_load for L in items])
    F = np.array([L.summary()["slip_force"] for L in items])
    mu = float(F @ N / (N @ N))
    return mu, float(np.sqrt(np.mean((F - mu * N) ** 2)))
