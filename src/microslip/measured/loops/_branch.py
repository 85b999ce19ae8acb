"""One measured branch of a steady loop, seen as twice the backbone by Masing's rule (private).

:func:`analyse_branch` measures a branch given on its own (not as part of a
record of cycles) with the definitions of :mod:`microslip.loops._analysis`:
:meth:`microslip.MeasuredContact.from_branch` tunes on it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...common import _checks
from ._analysis import _SIGN_ADVICE, LoopError, _branch_measures, _halved, _refine, find_reversals, noise_level
from ._record import MIN_SAMPLES


@dataclass(frozen=True, eq=False)
class Branch:
    """One measured branch of a steady loop, read as twice the backbone by Masing's rule (SI units).

    Attributes
    ----------
    x : ndarray, shape (P,)
        Half the displacement travelled from the reversal (m), >= 0.
    y : ndarray, shape (P,)
        Half the force change from the reversal (N), positive.
    ascending : bool
        True when ``t`` rises along the branch.
    reversal : tuple of float
        The refined reversal point ``(t_r, T_r)`` it starts from (m, N).
    stick_stiffness : float
        Slope of ``T`` on ``t`` just after the reversal (N/m), as in :func:`analyse`.
    slip_force : float
        Mean force over the last ``slip_fraction`` of the stroke (N).
    end_slope : float
        Slope over that last part (N/m).
    gross_slip : bool
        ``|end_slope|`` below 10 % of the stick stiffness: the branch ends in gross slip.
    """

    x: np.ndarray
    y: np.ndarray
    ascending: bool
    reversal: tuple
    stick_stiffness: float
    slip_force: float
    end_slope: float
    gross_slip: bool


def analyse_branch(t, T, *, threshold: float = 0.1, stick_fraction: float = 0.1, slip_fraction: float = 0.1,
                   source: str = "branch") -> Branch:
    """Measure one branch given as samples from a reversal to the next.

    The reversal is the extreme of ``t`` in the first quarter of the samples
    (samples before it are dropped), refined by a quadratic in the sample
    number fitted to ``t`` and ``T`` over the next 6 % of the samples and
    extrapolated to it; the stick stiffness, slip force and gross-slip flag are those of
    :func:`analyse`, the points ``(x, y)`` those of
    :meth:`Loops.backbone_points`.

    Parameters
    ----------
    t : array_like, shape (S,)
        Tangential displacement along the branch (m), rising or falling.
    T : array_like, shape (S,)
        Tangential force (N).
    threshold, stick_fraction, slip_fraction : float
        As in :func:`analyse`; ``t`` must not reverse by more than
        ``threshold`` of its range.
    source : str
        Name for messages.

    Returns
    -------
    Branch

    Raises
    ------
    LoopError
        ``t`` does not vary, holds more than one branch, or the force sign
        is reversed (``T`` falls as ``t`` rises after the reversal).
    """
    t = _checks.real_array("t", t, ndim=1, min_size=MIN_SAMPLES)
    T = _checks.real_array("T", T, ndim=1, min_size=MIN_SAMPLES)
    if T.size != t.size:
        raise ValueError(f"t and T must have the same length, got {t.size} and {T.size}")
    threshold = _checks.in_range("threshold", threshold, 0.0, 0.5, lo_open=True)
    stick_fraction = _checks.in_range("stick_fraction", stick_fraction, 0.0, 1.0, lo_open=True)
    slip_fraction = _checks.in_range("slip_fraction", slip_fraction, 0.0, 1.0, lo_open=True)
    lo, hi = np.percentile(t, [0.5, 99.5])
    if not hi > lo:
        raise LoopError(f"{source}: the displacement does not vary (robust range {hi - lo:.3g} m): no branch")
    index, _ = find_reversals(t, threshold * (hi - lo))
    if index.size:
        raise LoopError(f"{source}: t must hold one branch (from a reversal to the next), but it reverses at "
                        f"sample {int(index[0])} (t = {t[index[0]]:.6g} m): pass the samples of one ascending or "
                        f"descending branch")
    s = 1.0 if np.median(t[-5:]) > np.median(t[:5]) else -1.0
    start = int(np.argmin(s * t[:max(t.size // 4, 1)]))
    t, T = t[start:], T[start:]
    index = np.array([0, t.size - 1], dtype=np.int64)
    w = max(2, int(round(0.03 * t.size)))
    rt, rT = _refine(t, T, index, w)
    # the branch starts at its reversal: a centred mean (as in analyse) is not available there, and a
    # one-sided one would sit off the reversal by the drift of t; a quadratic in the sample number,
    # exact for a ramp and for the stationary t of a sine, extrapolated to the first sample is not
    head = np.arange(2 * w + 1)
    rt[0], rT[0] = (np.polyval(np.polyfit(head, v[:head.size], 2), 0.0) for v in (t, T))
    stiffness, slip_force, end, gross = _branch_measures(t, T, index, rt, rT, stick_fraction, slip_fraction,
                                                         noise_level(t))
    if stiffness[0] < 0:
        raise LoopError(f"{source}: force sign reversed: T {'falls' if s > 0 else 'rises'} as t "
                        f"{'rises' if s > 0 else 'falls'} after the reversal (stick stiffness "
                        f"{stiffness[0]:.4g} N/m < 0). {_SIGN_ADVICE}")
    x, y = _halved(t, T, rt[0], rT[0], s)
    return Branch(x=x, y=y, ascending=s > 0, reversal=(float(rt[0]), float(rT[0])),
                  stick_stiffness=float(stiffness[0]), slip_force=float(slip_force[0]), end_slope=float(end[0]),
                  gross_slip=bool(gross[0]))
