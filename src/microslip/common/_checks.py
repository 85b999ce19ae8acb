"""Input checks shared by the public entry points (private).

Every check raises ``ValueError`` (or ``TypeError``) with a message that
names the parameter, shows the offending value and says what is expected.
"""

from __future__ import annotations

import numpy as np


def _show(value) -> str:
    text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


def real_array(name: str, value, *, ndim: int | None = None, min_size: int = 0) -> np.ndarray:
    """Return ``value`` as a finite float64 array, or raise naming ``name``.

    Integers and floats are accepted; strings, booleans, complex numbers
    and objects are refused rather than converted.
    """
    if isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must be an array of real numbers, got {_show(value)}")
    try:
        raw = np.asarray(value)
    except (TypeError, ValueError):  # ragged nested sequences
        raise TypeError(f"{name} must be an array of real numbers, got {_show(value)}") from None
    if raw.dtype.kind not in "iuf":
        raise TypeError(f"{name} must be an array of real numbers, got {_show(value)}")
    arr = raw.astype(np.float64, copy=False)
    if ndim is not None and arr.ndim != ndim:
        raise ValueError(f"{name} must be {ndim}-D, got shape {arr.shape}")
    if arr.size < min_size:
        raise ValueError(f"{name} must have at least {min_size} value(s), got {arr.size}")
    # count_nonzero rather than .all(): half the cost on the small arrays of the hot paths
    if np.count_nonzero(np.isfinite(arr)) != arr.size:
        bad = np.flatnonzero(~np.isfinite(arr.ravel()))[0]
        raise ValueError(
            f"{name} must be finite, got {float(arr.ravel()[bad])!r} at flat index {bad}"
        )
    return arr


def positive_array(name: str, value, *, ndim: int | None = None, min_size: int = 0,
                   allow_zero: bool = False) -> np.ndarray:
    """Finite array whose entries are all > 0 (or >= 0 with ``allow_zero``)."""
    arr = real_array(name, value, ndim=ndim, min_size=min_size)
    bad = arr < 0 if allow_zero else arr <= 0
    if bad.any():
        i = int(np.flatnonzero(bad.ravel())[0])
        what = "non-negative" if allow_zero else "positive"
        raise ValueError(f"{name} must be {what}, got {float(arr.ravel()[i])!r} at flat index {i}")
    return arr


def real_scalar(name: str, value) -> float:
    """A finite Python float, or raise naming ``name``."""
    if isinstance(value, (bool, np.bool_, str, bytes)):
        raise TypeError(f"{name} must be a real number, got {_show(value)}")
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a real number, got {_show(value)}") from None
    if not np.isfinite(x):
        raise ValueError(f"{name} must be finite, got {x!r}")
    return x


def positive_scalar(name: str, value, *, allow_zero: bool = False) -> float:
    """A finite float > 0 (or >= 0 with ``allow_zero``)."""
    x = real_scalar(name, value)
    if x < 0 or (x == 0 and not allow_zero):
        what = "non-negative" if allow_zero else "positive"
        raise ValueError(f"{name} must be {what}, got {x!r}")
    return x


def in_range(name: str, value, lo: float, hi: float, *, lo_open=False, hi_open=False) -> float:
    """A finite float in the interval ``[lo, hi]`` (ends open as asked)."""
    x = real_scalar(name, value)
    below = x <= lo if lo_open else x < lo
    above = x >= hi if hi_open else x > hi
    if below or above:
        left = "(" if lo_open else "["
        right = ")" if hi_open else "]"
        raise ValueError(f"{name} must lie in {left}{lo}, {hi}{right}, got {x!r}")
    return x


def positive_pair(name: str, value, what: str) -> tuple[float, float]:
    """Two positive finite numbers ``(a, b)``; ``what`` describes them in the message (e.g. ``"(lo, hi) in N"``)."""
    try:
        a, b = value
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a pair {what}, got {_show(value)}") from None
    return positive_scalar(f"{name}[0]", a), positive_scalar(f"{name}[1]", b)


def positive_int(name: str, value, *, minimum: int = 1) -> int:
    """An integer >= ``minimum``."""
    if type(value) is not int and (  # a plain int passes at once (the hot paths)
            isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer))):
        raise TypeError(f"{name} must be an integer, got {_show(value)}")
    if value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value}")
    return int(value)


#: the largest size (samples, elements, points, ...) an entry point accepts: 1e7 float64 values are 80 MB,
#: so a size typed with a few zeros too many is refused instead of allocating gigabytes
MAX_SIZE = 10_000_000


def size(name: str, value, *, minimum: int = 1, maximum: int = MAX_SIZE) -> int:
    """An integer size in ``[minimum, maximum]``, refused before anything is allocated."""
    n = positive_int(name, value, minimum=minimum)
    if n > maximum:
        raise ValueError(f"{name} must be at most {maximum} (a size: larger ones would need gigabytes), got {n}")
    return n


def flag(name: str, value) -> bool:
    """``True`` or ``False`` (NumPy booleans too); strings such as ``"no"``, numbers and None are refused."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise TypeError(f"{name} must be True or False, got {_show(value)}")


def text(name: str, value, *, allow_empty: bool = False) -> str:
    """A string (non-empty unless ``allow_empty``)."""
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a string, got {_show(value)}")
    if not value and not allow_empty:
        raise ValueError(f"{name} must not be empty")
    return value


def one_of(name: str, value, choices) -> str:
    """``value`` if it is one of ``choices`` (strings), else raise naming ``name`` and listing them."""
    if not isinstance(value, str) or value not in choices:
        raise ValueError(f"{name} must be one of {', '.join(map(repr, choices))}, got {_show(value)}")
    return value


def mapping(name: str, value) -> dict:
    """A copy of a mapping (``dict`` or any ``collections.abc.Mapping``)."""
    from collections.abc import Mapping

    if not isinstance(value, Mapping):
        raise TypeError(f"{name} must be a mapping (dict), got {_show(value)}")
    return dict(value)


def file_path(name: str, value):
    """A ``pathlib.Path`` from a ``str`` or ``os.PathLike`` file name."""
    import os
    from pathlib import Path

    if isinstance(value, (str, os.PathLike)) and str(value):
        return Path(value)
    raise TypeError(f"{name} must be a file name (str or os.PathLike), got {_show(value)}")


def broadcast(**arrays) -> tuple:
    """The shape the named arrays broadcast to, or a ``ValueError`` naming them and their shapes."""
    shapes = {k: np.shape(v) for k, v in arrays.items()}
    try:
        return np.broadcast_shapes(*shapes.values())
    except ValueError:
        listed = " and ".join(f"{k} (shape {s})" for k, s in shapes.items())
        raise ValueError(f"{listed} must have shapes that broadcast together") from None


def finite_result(name: str, value, result):
    """``result`` if it is finite; else a ``ValueError``: ``name`` (whose ``value`` gave it) is too large."""
    out = np.asarray(result)
    if np.count_nonzero(np.isfinite(out)) != out.size:
        largest = float(np.max(np.abs(np.asarray(value, dtype=float))))
        raise ValueError(f"{name} is too large: {largest:.6g} gives a result beyond the floating-point range "
                         "(about 1.8e308)")
    return result


def close_spelling(key, accepted) -> str:
    """``"; did you mean 'x'?"`` for the accepted key closest to ``key`` (case ignored), else ``""``."""
    import difflib

    lowered = {str(a).lower(): a for a in accepted}
    close = difflib.get_close_matches(str(key).lower(), list(lowered), n=1, cutoff=0.6)
    return f"; did you mean {lowered[close[0]]!r}?" if close else ""


def known_keys(where: str, keys, accepted) -> None:
    """Refuse any key not in ``accepted``, naming ``where``, the key, a close spelling and the accepted keys.

    ``where`` says what holds the keys (e.g. ``"model file 'm.json'"``), so
    that a misspelt key is never silently ignored.
    """
    import difflib

    accepted = [str(a) for a in accepted]
    unknown = [str(k) for k in keys if str(k) not in accepted]
    if unknown:
        named = []
        for k in unknown:
            close = difflib.get_close_matches(k, accepted, n=1, cutoff=0.6)
            named.append(f"{k!r}" + (f" (did you mean {close[0]!r}?)" if close else ""))
        raise ValueError(f"{where}: unknown key{'s' if len(unknown) > 1 else ''} {', '.join(named)}; the accepted "
                         f"keys are {', '.join(accepted)}")
