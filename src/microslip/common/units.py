"""Units: SI conversion factors and quantities written with a unit suffix.

The API works in SI (m, N, Pa, s, J). Files and the command line may use
other units; these helpers turn ``"10mm"``, ``"2.5 um"``, ``"30N"``,
``"200GPa"`` into SI floats and name what is wrong when they cannot.
"""

from __future__ import annotations

import re

# factor to SI, by unit symbol; grouped by dimension
_UNITS = {
    "length": {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "μm": 1e-6, "nm": 1e-9, "cm": 1e-2,
               "in": 0.0254, "mil": 2.54e-5},
    "force": {"N": 1.0, "kN": 1e3, "mN": 1e-3, "lbf": 4.4482216152605, "lb": 4.4482216152605,
              "kip": 4448.2216152605, "kips": 4448.2216152605},
    "pressure": {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9, "psi": 6894.757293168},
    "time": {"s": 1.0, "ms": 1e-3, "us": 1e-6, "µs": 1e-6, "min": 60.0},
    "stiffness": {"N/m": 1.0, "N/mm": 1e3, "N/um": 1e6, "N/µm": 1e6},
    "frequency": {"Hz": 1.0, "kHz": 1e3},  # cycles per second; times 2 pi for rad/s
    "angular frequency": {"rad/s": 1.0, "rpm": 2.0 * 3.141592653589793 / 60.0},  # rpm: revolutions per minute
    "energy": {"J": 1.0, "mJ": 1e-3, "uJ": 1e-6, "µJ": 1e-6},
    "mass": {"kg": 1.0, "g": 1e-3},
    "moment of inertia": {"kg*m^2": 1.0, "kg*mm^2": 1e-6, "g*mm^2": 1e-9, "g*cm^2": 1e-7},
    "rate": {"1/s": 1.0},
    "dimensionless": {"-": 1.0, "": 1.0, "1": 1.0},
}

_NUMBER = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(\S*)\s*$")


def unit_factor(unit: str, kind: str | None = None) -> float:
    """SI factor of ``unit`` (e.g. ``"um"`` -> 1e-6), optionally of a given ``kind``.

    Parameters
    ----------
    unit : str
        Unit symbol, such as ``"mm"``, ``"N"``, ``"GPa"``, ``"in"``, ``"kip"``.
    kind : str, optional
        One of ``length``, ``force``, ``pressure``, ``time``, ``stiffness``,
        ``frequency`` (Hz), ``angular frequency`` (rad/s; ``rpm``, revolutions
        per minute, is ``2 pi / 60`` rad/s: a rotation speed), ``energy``,
        ``dimensionless``; the unit must be of it. Hz and rad/s are distinct
        kinds: converting one into the other needs the factor ``2 pi``, which
        a unit factor cannot carry.

    Raises
    ------
    ValueError
        Unknown unit, or a unit of another kind (the message lists the known ones).
    """
    kinds = [kind] if kind else list(_UNITS)
    if kind is not None and kind not in _UNITS:
        raise ValueError(f"kind must be one of {sorted(_UNITS)}, got {kind!r}")
    for k in kinds:
        if unit in _UNITS[k]:
            return _UNITS[k][unit]
    known = ", ".join(u for k in kinds for u in _UNITS[k] if u)
    what = f"{kind} unit" if kind else "unit"
    other = [k for k in _UNITS if unit in _UNITS[k]]
    hint = f" ({unit!r} is a unit of {other[0]})" if other else ""
    raise ValueError(f"unknown {what} {unit!r}; expected one of: {known}{hint}")


def parse_quantity(text, kind: str, *, name: str = "value", default_unit: str | None = None) -> float:
    """Parse ``"10mm"`` (or a bare number with ``default_unit``) into an SI float.

    Parameters
    ----------
    text : str or float
        The quantity: a number followed by a unit symbol, spaces allowed.
    kind : str
        Dimension expected (see :func:`unit_factor`).
    name : str
        What the quantity is, for error messages (e.g. ``"--length"``).
    default_unit : str, optional
        Unit assumed for a bare number; without it a bare number is SI.
    """
    if isinstance(text, (int, float)) and not isinstance(text, bool):
        return float(text) * (unit_factor(default_unit, kind) if default_unit else 1.0)
    match = _NUMBER.match(str(text))
    if not match:
        raise ValueError(f"{name}: cannot read {text!r} as a number with a {kind} unit (e.g. '10mm')")
    number, unit = match.groups()
    if not unit:
        return float(number) * (unit_factor(default_unit, kind) if default_unit else 1.0)
    try:
        return float(number) * unit_factor(unit, kind)
    except ValueError as exc:
        raise ValueError(f"{name}: {exc}") from None


#: units a report may choose from, smallest first, per kind
_DISPLAY = {"energy": ("nJ", "µJ", "mJ", "J"), "length": ("nm", "µm", "mm", "m"), "force": ("mN", "N", "kN")}
_UNITS["energy"]["nJ"] = 1e-9


def display_unit(values, kind: str) -> tuple[str, float]:
    """``(unit, factor)`` to show SI ``values`` in: the unit in which the largest magnitude lies in [1, 1000).

    ``values * factor`` are then in ``unit``; one unit serves a whole table or plot.
    """
    import numpy as np

    if kind not in _DISPLAY:
        raise ValueError(f"kind must be one of {sorted(_DISPLAY)}, got {kind!r}")
    big = float(np.max(np.abs(np.asarray(values, dtype=float)), initial=0.0))
    if big == 0.0:  # nothing to scale: the SI unit
        return next(u for u in _DISPLAY[kind] if _UNITS[kind][u] == 1.0), 1.0
    choice = _DISPLAY[kind][0]
    for unit in _DISPLAY[kind]:
        if big >= _UNITS[kind][unit]:
            choice = unit
    return choice, 1.0 / _UNITS[kind][choice]


def plot_factor(unit: str) -> float:
    """The factor that turns metres into ``unit`` (a length unit) for a plot; the error names ``unit``."""
    try:
        return 1.0 / unit_factor(unit, "length")
    except ValueError as exc:
        raise ValueError(f"unit must be one of the length units, got {unit!r} ({exc})") from None


def parse_fraction(text, *, name: str = "value") -> float:
    """Parse a fraction written as a fraction (``"0.02"``) or a percentage (``"2%"``, ``"2 %"``) into a float.

    A bare number is a fraction, so one above 1 is refused rather than
    guessed (``2`` could mean 2 % or 200 %): the message shows both
    spellings of what was probably meant.

    Parameters
    ----------
    text : str or float
        The value.
    name : str
        What it is, for error messages (e.g. ``"--energy-target"``).

    Returns
    -------
    float
        The fraction (``0.02`` for 2 %); its sign and size are the caller's to check.
    """
    if isinstance(text, (int, float)) and not isinstance(text, bool):
        number, percent = float(text), False
    else:
        match = _NUMBER.match(str(text))
        if not match or match.group(2) not in ("", "%"):
            raise ValueError(f"{name}: cannot read {text!r} as a fraction such as 0.02 or a percentage such as 2%")
        number, percent = float(match.group(1)), match.group(2) == "%"
    if percent:
        return number / 100.0
    if number > 1.0:
        raise ValueError(f"{name}: {text!r} is a fraction above 1 (fractions: 0.02 means 2 %); write {number:g}% for "
                         f"{number:g} percent, or {number / 100:g}")
    return number
