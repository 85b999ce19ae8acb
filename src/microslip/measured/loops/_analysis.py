"""Loop analysis: reversals, cycles, steadiness, per-cycle measures, Masing check (private).

Definitions (all in SI units)
-----------------------------
reversal
    A point where the tangential displacement changes direction, found with a
    hysteresis threshold so that sensor noise never makes one (see
    :func:`microslip.loops._kernels.reversals`); its position is refined by a
    local quadratic fit of ``t`` (vertex) and the mean of ``T`` around it.
branch
    The samples between two successive reversals; *ascending* when it ends
    at a maximum of ``t``.
cycle
    Two successive branches, from one reversal to the next of the same kind.
energy
    The loop area ``∮ T dt`` of a cycle, the path closed by the chord from its
    last to its first sample (so a small drift does not bias it).
stick stiffness
    Least-squares slope of ``T`` against ``t`` from a reversal until the force
    has changed by ``stick_fraction`` of the branch's force excursion (at
    least 3 samples), with the variance of ``t`` corrected for its noise
    (estimated from second differences): the stiffness of the stick portion
    just after it.
slip force
    Mean force over the last ``slip_fraction`` of the displacement stroke of
    a branch (positive on ascending, negative on descending branches); the
    branch is in *gross slip* there when the slope over the same window is
    below 10 % of its stick stiffness.
steady
    A cycle is steady when its energy and amplitude are within
    ``steady_tolerance`` of the median energy of the cycles at full amplitude
    (within the same tolerance of the 95th percentile of the amplitudes).
    The steady cycles are the longest run of consecutive such cycles (the
    latest one on a tie), so ramps of amplitude at the start and the end of
    a test are left out.
Masing check
    The steady branches, in coordinates relative to their reversal point and
    halved, ``((t - t_r)/2, (T - T_r)/2)`` oriented positive, are compared with
    the backbone: the virgin (first-loading) curve when the record starts from
    rest, otherwise the branches of the other direction (for a Masing contact
    both are the backbone). The number is the RMS difference of the binned
    curves over their common range, as a fraction of the force amplitude.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...common import _checks
from ...common._binning import binned_means
from ...common.errors import LoopError
from . import _kernels


_SIGN_ADVICE = ("T must be the tangential force acting along t, so that the loops run clockwise in the "
                "t-T plane and the energy dissipated, the loop area (closed integral of T dt), is positive: "
                "negate the force (change its sign in the file, or loops.Record(t=r.t, T=-r.T, ...))")
_GROSS_SLIP_RATIO = 0.1  # end slope below this fraction of the stick stiffness: gross slip
#: the per-cycle arrays of :class:`Loops`, shape (C,), whose steady mean :meth:`Loops.steady_mean` gives
PER_CYCLE = ("energy", "amplitude", "force_amplitude", "slip_force_positive", "slip_force_negative",
             "stiffness_after_min", "stiffness_after_max", "slip_force", "stick_stiffness")
_MASING_BINS = 24


@dataclass(frozen=True, eq=False)
class Loops:
    """The analysed hysteresis loops of one record (SI units).

    Attributes
    ----------
    record : Record
        The data analysed.
    reversal_index : ndarray of int, shape (R,)
        Sample index of each reversal.
    reversal_kind : ndarray of int, shape (R,)
        +1 at a maximum of ``t``, -1 at a minimum.
    reversal_t, reversal_T : ndarray, shape (R,)
        Refined reversal points (m, N).
    energy : ndarray, shape (C,)
        Energy dissipated in each cycle (J).
    amplitude : ndarray, shape (C,)
        Displacement amplitude (half the peak-to-peak) of each cycle (m).
    force_amplitude : ndarray, shape (C,)
        Force amplitude (half the peak-to-peak) of each cycle (N).
    slip_force_positive, slip_force_negative : ndarray, shape (C,)
        Slip force on the ascending / descending branch of each cycle (N);
        the negative one is negative.
    stiffness_after_min, stiffness_after_max : ndarray, shape (C,)
        Stick stiffness just after the minimum / maximum reversal of each
        cycle (N/m).
    gross_slip : ndarray of bool, shape (C,)
        Both branches of the cycle end in gross slip.
    steady_from, steady_to : int
        The steady cycles are ``steady_from <= c < steady_to`` (0-based).
    is_steady : bool
        True when at least two consecutive cycles agree (or the record holds
        a single cycle); False means ``steady_from..steady_to`` is the single
        cycle closest to the reference, and the loops never settled.
    masing_error : float
        Masing check: RMS difference between the steady branches and the
        backbone, as a fraction of the force amplitude (0 for a Masing contact).
    masing_basis : str
        ``"virgin curve"`` or ``"branch symmetry"``: what the branches were
        compared with.
    options : dict
        The analysis options used.
    """

    record: Record
    reversal_index: np.ndarray
    reversal_kind: np.ndarray
    reversal_t: np.ndarray
    reversal_T: np.ndarray
    energy: np.ndarray
    amplitude: np.ndarray
    force_amplitude: np.ndarray
    slip_force_positive: np.ndarray
    slip_force_negative: np.ndarray
    stiffness_after_min: np.ndarray
    stiffness_after_max: np.ndarray
    gross_slip: np.ndarray
    steady_from: int
    steady_to: int
    is_steady: bool
    masing_error: float
    masing_basis: str
    options: dict

    # -- summaries ---------------------------------------------------------
    @property
    def cycles(self) -> int:
        """Number of complete cycles ``C``."""
        return self.energy.size

    @property
    def steady(self) -> slice:
        """Slice selecting the steady cycles in the per-cycle arrays."""
        return slice(self.steady_from, self.steady_to)

    @property
    def normal_load(self) -> float | None:
        """Normal load of the record (N), if known."""
        return self.record.normal_load

    def cycle_bounds(self, cycle: int) -> tuple[int, int]:
        """Sample indices ``(first, last)`` of cycle ``cycle`` (inclusive)."""
        c = _checks.positive_int("cycle", cycle, minimum=0)
        if c >= self.cycles:
            raise ValueError(f"cycle must be < {self.cycles} (the number of complete cycles), got {c}")
        return int(self.reversal_index[2 * c]), int(self.reversal_index[2 * c + 2])

    @property
    def centre(self) -> tuple[float, float]:
        """Mean centre ``(t_c, T_c)`` of the steady loops (m, N): the offsets of the sensors."""
        j = np.arange(2 * self.steady_from, 2 * self.steady_to + 1)
        rt, rT = self.reversal_t[j], self.reversal_T[j]
        return float(0.5 * (rt.max() + rt.min())), float(0.5 * (rT.max() + rT.min()))

    def steady_mean(self, name: str) -> float:
        """Mean over the steady cycles of a per-cycle attribute (e.g. ``"energy"``), one of :data:`PER_CYCLE`."""
        if name not in PER_CYCLE:
            raise ValueError(f"name must be a per-cycle attribute, one of {list(PER_CYCLE)}, got {name!r}")
        return float(np.mean(getattr(self, name)[self.steady]))

    @property
    def slip_force(self) -> np.ndarray:
        """Offset-free slip force of each cycle, ``(F+ - F-)/2`` (N), shape (C,)."""
        return 0.5 * (self.slip_force_positive - self.slip_force_negative)

    @property
    def stick_stiffness(self) -> np.ndarray:
        """Mean stick stiffness after the two reversals of each cycle (N/m), shape (C,)."""
        return 0.5 * (self.stiffness_after_min + self.stiffness_after_max)

    def summary(self) -> dict:
        """Means over the steady cycles: energy (J), amplitude (m), slip force (N), stiffness (N/m), ..."""
        return {
            "normal_load": self.normal_load,
            "cycles": self.cycles,
            "steady_from": self.steady_from,
            "steady_to": self.steady_to,
            "is_steady": self.is_steady,
            "energy": self.steady_mean("energy"),
            "amplitude": self.steady_mean("amplitude"),
            "force_amplitude": self.steady_mean("force_amplitude"),
            "slip_force": float(np.mean(self.slip_force[self.steady])),
            "slip_force_positive": self.steady_mean("slip_force_positive"),
            "slip_force_negative": self.steady_mean("slip_force_negative"),
            "stick_stiffness": float(np.mean(self.stick_stiffness[self.steady])),
            "gross_slip": bool(np.all(self.gross_slip[self.steady])),
            "masing_error": self.masing_error,
            "masing_basis": self.masing_basis,
        }

    # -- branches -----------------------------------------------------------
    @property
    def branches(self) -> int:
        """Number of branches, one fewer than the reversals (the complete cycles hold ``2 C`` of them)."""
        return self.reversal_index.size - 1

    def branch(self, number: int) -> tuple[np.ndarray, np.ndarray]:
        """Samples ``(t, T)`` of branch ``number`` (from reversal ``number`` to the next).

        Parameters
        ----------
        number : int
            ``0 <= number <`` :attr:`branches`; branches ``2 c`` and
            ``2 c + 1`` make up cycle ``c``.

        Returns
        -------
        t, T : ndarray, shape (S,)
            Displacement (m) and force (N) from the reversal to the next, both included.
        """
        number = _checks.positive_int("number", number, minimum=0)
        if number >= self.branches:
            raise ValueError(f"number must be < {self.branches} (the number of branches, between the "
                             f"{self.branches + 1} reversals), got {number}")
        a, b = int(self.reversal_index[number]), int(self.reversal_index[number + 1])
        return self.record.t[a:b + 1], self.record.T[a:b + 1]

    def backbone_points(self, cycles=None) -> tuple[np.ndarray, np.ndarray]:
        """Points of the backbone implied by Masing's rule, from the branches of ``cycles``.

        Each branch from reversal ``(t_r, T_r)`` gives ``x = |t - t_r| / 2``,
        ``y = sign * (T - T_r) / 2`` (positive for both directions).

        Parameters
        ----------
        cycles : slice or sequence of int, optional
            Default: the steady cycles.

        Returns
        -------
        x : ndarray, shape (P,)
            Half the displacement travelled from the reversal (m), >= 0.
        y : ndarray, shape (P,)
            Half the force change from the reversal (N).
        """
        return _points(self, _branch_numbers(self, cycles))

    # -- plotting --------------------------------------------------------------
    def plot(self, ax=None, *, cycle: int | None = None):
        """Plot the loops (grey), a steady cycle and its two branches (coloured), the reversals.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Where to draw; a new figure is made if omitted.
        cycle : int, optional
            Cycle to highlight; default the last steady one.

        Returns
        -------
        matplotlib.axes.Axes
        """
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(6, 4.4))
        um = 1e6
        r = self.record
        ax.plot(r.t * um, r.T, color="0.75", lw=0.6, label="record")
        c = self.steady_to - 1 if cycle is None else cycle
        a, _ = self.cycle_bounds(c)
        for b, color in zip((2 * c, 2 * c + 1), ("tab:blue", "tab:red")):
            t, T = self.branch(b)
            kind = "ascending" if self.reversal_kind[b + 1] > 0 else "descending"
            ax.plot(t * um, T, color=color, lw=1.4, label=f"cycle {c + 1}: {kind} branch")
        ax.plot(self.reversal_t * um, self.reversal_T, "k.", ms=4, label="reversals")
        ax.set_xlabel("tangential displacement t (µm)")
        ax.set_ylabel("tangential force T (N)")
        load = f", N = {self.normal_load:.4g} N" if self.normal_load else ""
        ax.set_title(f"{r.source}{load}: {self.cycles} cycles, steady "
                     f"{self.steady_from + 1}-{self.steady_to}", fontsize=9)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        return ax


def _branch_numbers(loops: Loops, cycles) -> list[int]:
    if cycles is None:
        cycles = range(loops.steady_from, loops.steady_to)
    elif isinstance(cycles, slice):
        cycles = range(loops.cycles)[cycles]
    elif isinstance(cycles, (str, bytes)) or not np.iterable(cycles):
        raise TypeError(f"cycles must be a slice or a sequence of cycle numbers, got {cycles!r}")
    cycles = list(cycles)
    if not cycles:
        raise ValueError(f"cycles must select at least one of the {loops.cycles} cycles, got {cycles!r}")
    out = []
    for c in cycles:
        c = _checks.positive_int("cycles: each cycle", c, minimum=0)
        if not 0 <= c < loops.cycles:
            raise ValueError(f"cycles: cycle {c} does not exist (0..{loops.cycles - 1})")
        out += [2 * c, 2 * c + 1]
    return out


def find_reversals(t, threshold) -> tuple[np.ndarray, np.ndarray]:
    """Reversal points of ``t`` with the hysteresis threshold ``threshold`` (same unit as ``t``).

    Returns
    -------
    index : ndarray of int64, shape (R,)
    kind : ndarray of int64, shape (R,)
        +1 maximum, -1 minimum, alternating.
    """
    t = _checks.real_array("t", t, ndim=1, min_size=2)
    h = _checks.positive_scalar("threshold", threshold)
    index = np.empty(t.size, dtype=np.int64)
    kind = np.empty(t.size, dtype=np.int64)
    count = _kernels.reversals(t, h, index, kind)
    return index[:count].copy(), kind[:count].copy()


#: what :func:`analyse` reads of a :class:`~microslip.loops.Record` (the record module imports this one)
_RECORD_FIELDS = ("t", "T", "time", "N", "normal_load", "source")


def analyse(record: Record, *, threshold: float = 0.1, stick_fraction: float = 0.1,
            slip_fraction: float = 0.1, steady_tolerance: float = 0.05, noise_correction: bool = True) -> Loops:
    """Analyse the hysteresis loops of a record.

    Parameters
    ----------
    record : Record
        From :func:`microslip.loops.read` (or built from arrays in SI units).
    threshold : float, default 0.1
        Reversal threshold as a fraction of the robust peak-to-peak range of
        ``t`` (0.5th to 99.5th percentile): displacement noise below it never
        makes a reversal.
    stick_fraction : float, default 0.1
        Part of a branch's force excursion over which the stick stiffness
        after a reversal is fitted.
    slip_fraction : float, default 0.1
        Last part of a branch's displacement stroke over which its slip
        force is averaged.
    steady_tolerance : float, default 0.05
        Relative tolerance on energy and amplitude for a cycle to count as
        steady.
    noise_correction : bool, default True
        Correct the stick stiffness for the noise of ``t`` (errors in
        variables). Turn it off when ``T`` was computed from the noisy ``t``
        itself (a model driven by a measured displacement), where there is
        nothing to correct.

    Returns
    -------
    Loops

    Raises
    ------
    LoopError
        The record contains no complete cycle (fewer than three reversals).
    """
    if not all(hasattr(record, name) for name in _RECORD_FIELDS):
        raise TypeError(f"record must be a microslip.loops.Record (from loops.read), got {type(record).__name__}")
    threshold = _checks.in_range("threshold", threshold, 0.0, 0.5, lo_open=True)
    stick_fraction = _checks.in_range("stick_fraction", stick_fraction, 0.0, 1.0, lo_open=True)
    slip_fraction = _checks.in_range("slip_fraction", slip_fraction, 0.0, 1.0, lo_open=True)
    steady_tolerance = _checks.positive_scalar("steady_tolerance", steady_tolerance)
    noise_correction = _checks.flag("noise_correction", noise_correction)
    t, T = record.t, record.T
    lo, hi = np.percentile(t, [0.5, 99.5])
    if not hi > lo:
        raise LoopError(f"{record.source}: the displacement does not vary (robust range {hi - lo:.3g} m): "
                        f"no loops to analyse")
    index, kind = find_reversals(t, threshold * (hi - lo))
    if index.size < 3:
        raise LoopError(f"{record.source}: the record contains no complete cycle: {index.size} reversal(s) "
                        f"found, a cycle needs 3 (threshold {threshold:g} of the displacement range "
                        f"{(hi - lo) * 1e6:.4g} µm)")
    R = index.size if index.size % 2 == 1 else index.size - 1  # end on a complete cycle
    index, kind = index[:R], kind[:R]
    w = max(1, int(round(0.015 * np.median(np.diff(index)))))
    rt, rT = _refine(t, T, index, w)
    branch = _branch_measures(t, T, index, rt, rT, stick_fraction, slip_fraction,
                              noise_level(t) if noise_correction else 0.0)
    C = (R - 1) // 2
    energy = _cycle_energy(t, T, index[0:R - 2:2], index[2:R:2])
    amplitude = 0.25 * (np.abs(np.diff(rt))[0::2] + np.abs(np.diff(rt))[1::2])
    force_amplitude = 0.25 * (np.abs(np.diff(rT))[0::2] + np.abs(np.diff(rT))[1::2])
    first_up = kind[1] > 0  # the first branch of every cycle ascends
    up, down = (slice(0, None, 2), slice(1, None, 2)) if first_up else (slice(1, None, 2), slice(0, None, 2))
    stiff, slip, _, gross = branch
    steady_from, steady_to, is_steady = _steady(energy, amplitude, steady_tolerance)
    steady = slice(steady_from, steady_to)
    stick = 0.5 * (stiff[up][:C] + stiff[down][:C])[steady].mean()
    if energy[steady].mean() < 0 and stick < 0:
        raise LoopError(f"{record.source}: force sign reversed: loop energy < 0 ({energy[steady].mean():.4g} J per "
                        f"steady cycle) and stick stiffness < 0 ({stick:.4g} N/m). {_SIGN_ADVICE}")
    loops = Loops(
        record=record, reversal_index=index, reversal_kind=kind, reversal_t=rt, reversal_T=rT,
        energy=energy, amplitude=amplitude, force_amplitude=force_amplitude,
        slip_force_positive=slip[up][:C], slip_force_negative=slip[down][:C],
        stiffness_after_min=stiff[up][:C], stiffness_after_max=stiff[down][:C],
        gross_slip=(gross[0::2] & gross[1::2])[:C], steady_from=steady_from, steady_to=steady_to,
        is_steady=is_steady,
        masing_error=np.nan, masing_basis="",
        options={"threshold": threshold, "stick_fraction": stick_fraction, "slip_fraction": slip_fraction,
                 "steady_tolerance": steady_tolerance, "noise_correction": bool(noise_correction)},
    )
    error, basis = _masing(loops)
    object.__setattr__(loops, "masing_error", error)
    object.__setattr__(loops, "masing_basis", basis)
    return loops


def _refine(t, T, index, w):
    """Reversal points refined: the means of ``t`` and ``T`` over ±w samples around each one.

    Near a reversal ``t`` is stationary, so the mean lies within ``c w^2`` of
    the peak (``c`` its curvature per sample squared, 0.05 % of the amplitude
    for 400 samples per cycle) while the noise drops by ``sqrt(2w + 1)``.
    """
    rows = np.clip(index[:, None] + np.arange(-w, w + 1)[None, :], 0, t.size - 1)
    return t[rows].mean(axis=1), T[rows].mean(axis=1)


def noise_level(x) -> float:
    """Robust standard deviation of the sample-to-sample noise of a smooth, densely sampled signal.

    From the second differences, ``var(d2 x) = 6 sigma^2`` for white noise,
    with the median absolute deviation (the smooth part contributes
    ``x'' dt^2``, negligible at tens of samples per cycle).
    """
    d2 = np.diff(x, 2)
    return float(1.4826 * np.median(np.abs(d2 - np.median(d2))) / np.sqrt(6.0)) if d2.size else 0.0


def _slopes(t, T, a, b, sigma_t=0.0):
    """Least-squares slope of T on t over the inclusive sample windows [a, b] (vectorised).

    The variance of ``t`` is corrected for its noise ``sigma_t`` (errors in
    variables), which would otherwise flatten the slope by
    ``var(t) / (var(t) + sigma_t^2)``.
    """
    tc = t - t.mean()
    Tc = T - T.mean()
    cs = [np.concatenate([[0.0], np.cumsum(v)]) for v in (tc, Tc, tc * tc, tc * Tc)]
    n = (b - a + 1).astype(float)
    sx, sy, sxx, sxy = (c[b + 1] - c[a] for c in cs)
    raw = n * sxx - sx * sx
    den = np.maximum(raw - n * n * sigma_t**2, 0.25 * raw)  # never correct by more than a factor 4
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(den > 0, (n * sxy - sx * sy) / np.where(den > 0, den, 1.0), 0.0)


def _branch_measures(t, T, index, rt, rT, stick_fraction, slip_fraction, sigma_t):
    """Stick stiffness after each reversal, slip force and slope at each branch end, gross-slip flag."""
    a, b = index[:-1], index[1:]
    out = np.empty(a.size, dtype=np.int64)
    _kernels.window_ends(T, a, b, stick_fraction * np.abs(np.diff(rT)), out)
    stick_end = np.minimum(np.maximum(out, a + 2), b)
    stiffness = _slopes(t, T, a, stick_end, sigma_t)
    _kernels.window_ends(t, b, a, slip_fraction * np.abs(np.diff(rt)), out)
    slip_start = np.maximum(np.minimum(out, b - 2), a)
    csT = np.concatenate([[0.0], np.cumsum(T)])
    slip_force = (csT[b + 1] - csT[slip_start]) / (b - slip_start + 1)
    end_slope = _slopes(t, T, slip_start, b)
    gross = np.abs(end_slope) < _GROSS_SLIP_RATIO * np.abs(stiffness)
    return stiffness, slip_force, end_slope, gross


def _cycle_energy(t, T, start, end):
    """Loop area of each cycle, ``∮ T dt``, closed by the chord from the last sample to the first."""
    inc = np.concatenate([[0.0], np.cumsum(0.5 * (T[1:] + T[:-1]) * np.diff(t))])
    closing = 0.5 * (T[end] + T[start]) * (t[start] - t[end])
    return inc[end] - inc[start] + closing


def _steady(energy, amplitude, tol):
    """``(first, stop, settled)``: the longest run of cycles agreeing with the full-amplitude reference."""
    full = np.abs(amplitude / np.percentile(amplitude, 95) - 1.0) <= tol
    ref_E = np.median(energy[full]) if full.any() else np.median(energy)
    ref_A = np.median(amplitude[full]) if full.any() else np.median(amplitude)
    ok = (np.abs(energy / ref_E - 1.0) <= tol) & (np.abs(amplitude / ref_A - 1.0) <= tol)
    best, best_len, start = None, 0, None
    for c, good in enumerate(np.append(ok, False)):
        if good and start is None:
            start = c
        elif not good and start is not None:
            if c - start >= best_len:
                best, best_len = start, c - start
            start = None
    if best_len >= 2 or (best_len == 1 and energy.size == 1):
        return best, best + best_len, True
    c = int(np.argmin(np.abs(energy / ref_E - 1.0)))
    return c, c + 1, False


def _masing(loops: Loops) -> tuple[float, str]:
    """Masing check (see the module docstring): RMS difference / force amplitude, and the basis."""
    B = loops.steady_mean("force_amplitude")
    virgin = _virgin_points(loops)
    branches = _branch_numbers(loops, None)
    if virgin is not None:
        xb, yb = loops.backbone_points()
        xr, yr = virgin
        basis = "virgin curve"
    else:
        up = [b for b in branches if loops.reversal_kind[b + 1] > 0]
        down = [b for b in branches if loops.reversal_kind[b + 1] < 0]
        xb, yb = _points(loops, up)
        xr, yr = _points(loops, down)
        basis = "branch symmetry"
    top = min(xb.max(), xr.max())
    edges = np.linspace(0.0, top, _MASING_BINS + 1)
    cb, (mb,) = binned_means(xb, edges, yb)
    cr, (mr,) = binned_means(xr, edges, yr)
    both = (cb > 0) & (cr > 0)
    if not both.any() or not B > 0:
        return float("inf"), basis
    return float(np.sqrt(np.mean((mb[both] - mr[both]) ** 2)) / B), basis


def _points(loops, branches):
    xs, ys = [], []
    for b in branches:
        t, T = loops.branch(b)
        x, y = _halved(t, T, loops.reversal_t[b], loops.reversal_T[b], float(loops.reversal_kind[b + 1]))
        xs.append(x)
        ys.append(y)
    return np.concatenate(xs), np.concatenate(ys)


def _halved(t, T, t_r, T_r, s):
    """Masing's backbone points of a branch from the reversal ``(t_r, T_r)`` going the way ``s`` (+1 or -1)."""
    return np.maximum(s * (t - t_r) / 2.0, 0.0), s * (T - T_r) / 2.0  # noise can cross the reversal


def _virgin_points(loops: Loops):
    """The first-loading curve ``(x, y)`` when the record starts from rest near the loop centre, else None."""
    r = loops.record
    first = int(loops.reversal_index[0])
    if first < 3:
        return None
    t_c, T_c = loops.centre
    A = loops.steady_mean("amplitude")
    B = loops.steady_mean("force_amplitude")
    t0, T0 = r.t[0], r.T[0]
    s = float(loops.reversal_kind[0])
    x = s * (r.t[:first + 1] - t0)
    y = s * (r.T[:first + 1] - T0)
    at_rest = abs(T0 - T_c) < 0.1 * B and abs(t0 - t_c) < 0.2 * A
    if not at_rest or x.max() < 0.5 * A:
        return None
    return x, y
