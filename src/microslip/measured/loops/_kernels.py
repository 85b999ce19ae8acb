"""Compiled kernels of the loop analysis (private).

Plain float64/int64 arrays in, arrays out; no input checks (the public
functions in :mod:`microslip.loops` check everything). Each kernel has a
slow, obviously correct pure-Python twin (``*_reference``) used by the tests.
"""

from __future__ import annotations

import numba as nb
import numpy as np


@nb.njit(cache=True, nogil=True)
def reversals(x, h, out_index, out_kind):  # pragma: no cover - compiled
    """Reversal points of ``x`` with a hysteresis (zig-zag) threshold ``h``.

    A maximum is confirmed once ``x`` has fallen by more than ``h`` below the
    running maximum since the last minimum (and vice versa), so noise smaller
    than ``h`` never creates a reversal. The start of the record is not a
    reversal unless ``x`` first moved away from it by more than ``h`` and came
    back (then the extremum reached is one).

    Writes the sample index of each reversal into ``out_index`` and its kind
    (+1 maximum, -1 minimum) into ``out_kind``; returns how many were found.
    """
    n = x.shape[0]
    count = 0
    i_hi = 0
    i_lo = 0
    direction = 0
    x0 = x[0]
    for i in range(1, n):
        v = x[i]
        if direction == 0:
            if v > x[i_hi]:
                i_hi = i
            if v < x[i_lo]:
                i_lo = i
            if v - x[i_lo] > h:
                direction = 1
                if x0 - x[i_lo] > h:
                    out_index[count] = i_lo
                    out_kind[count] = -1
                    count += 1
                i_hi = i
            elif x[i_hi] - v > h:
                direction = -1
                if x[i_hi] - x0 > h:
                    out_index[count] = i_hi
                    out_kind[count] = 1
                    count += 1
                i_lo = i
        elif direction == 1:
            if v > x[i_hi]:
                i_hi = i
            elif x[i_hi] - v > h:
                out_index[count] = i_hi
                out_kind[count] = 1
                count += 1
                direction = -1
                i_lo = i
        else:
            if v < x[i_lo]:
                i_lo = i
            elif v - x[i_lo] > h:
                out_index[count] = i_lo
                out_kind[count] = -1
                count += 1
                direction = 1
                i_hi = i
    return count


def reversals_reference(x, h):
    """Pure-Python twin of :func:`reversals`: returns ``(indices, kinds)`` as lists."""
    x = [float(v) for v in x]
    found = []
    direction = 0
    hi = lo = 0
    for i in range(1, len(x)):
        if direction == 0:
            hi = i if x[i] > x[hi] else hi
            lo = i if x[i] < x[lo] else lo
            if x[i] - x[lo] > h:
                if x[0] - x[lo] > h:
                    found.append((lo, -1))
                direction, hi = 1, i
            elif x[hi] - x[i] > h:
                if x[hi] - x[0] > h:
                    found.append((hi, 1))
                direction, lo = -1, i
        elif direction == 1:
            if x[i] > x[hi]:
                hi = i
            elif x[hi] - x[i] > h:
                found.append((hi, 1))
                direction, lo = -1, i
        else:
            if x[i] < x[lo]:
                lo = i
            elif x[i] - x[lo] > h:
                found.append((lo, -1))
                direction, hi = 1, i
    return [i for i, _ in found], [k for _, k in found]


@nb.njit(cache=True, nogil=True)
def window_ends(x, starts, stops, thresholds, out):  # pragma: no cover - compiled
    """For each ``k``, the first index ``i`` from ``starts[k]`` towards ``stops[k]``
    (either direction) with ``|x[i] - x[starts[k]]| >= thresholds[k]``.

    Writes it into ``out[k]``; ``stops[k]`` when no sample gets that far.
    """
    for k in range(starts.shape[0]):
        a = starts[k]
        b = stops[k]
        step = 1 if b >= a else -1
        ref = x[a]
        lim = thresholds[k]
        i = a
        while i != b and abs(x[i] - ref) < lim:
            i += step
        out[k] = i


def window_ends_reference(x, starts, stops, thresholds):
    """Pure-Python twin of :func:`window_ends`; returns a list."""
    out = []
    for a, b, lim in zip(starts, stops, thresholds):
        a, b = int(a), int(b)
        step = 1 if b >= a else -1
        found = b
        for i in range(a, b, step):
            if abs(float(x[i]) - float(x[a])) >= lim:
                found = i
                break
        out.append(found)
    return out


def warm_up() -> None:
    """Compile (or load from cache) both kernels on a tiny input."""
    idx = np.empty(4, dtype=np.int64)
    kind = np.empty(4, dtype=np.int64)
    reversals(np.array([0.0, 1.0, 0.0, 1.0]), 0.5, idx, kind)
    window_ends(np.array([0.0, 1.0]), np.zeros(1, np.int64), np.ones(1, np.int64), np.ones(1), np.empty(1, np.int64))
