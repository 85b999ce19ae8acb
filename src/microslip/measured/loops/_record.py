"""Measured records of tangential displacement and force, and the file readers (private).

Two layouts are read:

* delimited text (CSV, semicolons, tabs or spaces) whose header names each
  column with its unit, ``time [s], t [um], T [N], N [N]``; lines starting
  with ``#`` are comments, and a comment ``# normal load = 36.6 N`` gives the
  normal load of the whole file; UTF-8, UTF-16 and 8-bit (Windows-1252,
  Latin-1) text are read, with or without a byte-order mark;
* the JSON layout of the ARTS-Lab band friction damper data set
  (``{"data": [[time, displacement, friction force, velocity, actuator
  force 1, actuator force 2], ...], "displacement units": "in", ...}``).

Everything is converted to SI (m, N, s).
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...common import _checks
from ...common._table import column_si, header_unit, read_table, read_text
from ...common.units import parse_quantity, unit_factor
from ._analysis import analyse

#: column names tried, in order, for each role when ``columns`` does not name one
DEFAULT_COLUMNS = {
    "t": ("t", "x", "u", "displacement", "tangential displacement"),
    "T": ("T", "F", "force", "friction force", "tangential force"),
    "time": ("time", "Time", "TIME"),
    "N": ("N", "normal load", "normal force"),
}
_KIND = {"t": "length", "T": "force", "time": "time", "N": "force"}
MIN_SAMPLES = 16
_LOAD_COMMENT = re.compile(r"^#\s*normal[ _]load\s*[:=]\s*(.+?)\s*$", re.IGNORECASE)

# The damper JSON: column order of its "data" matrix and the key giving each unit.
_DAMPER_COLUMNS = ("time", "displacement", "friction force", "velocity", "actuator force 1",
                   "actuator force 2")
_DAMPER_UNIT_KEYS = {"time": "time units", "displacement": "displacement units",
                     "friction force": "friction force units", "actuator force 1": "actuator force units",
                     "actuator force 2": "actuator force units"}


@dataclass(frozen=True, eq=False)
class Record:
    """One measured record of tangential displacement and force (SI units).

    Attributes
    ----------
    t : ndarray, shape (samples,)
        Tangential relative displacement (m).
    T : ndarray, shape (samples,)
        Tangential (friction) force (N).
    time : ndarray, shape (samples,), or None
        Time of each sample (s), when the file gives it.
    N : ndarray, shape (samples,), or None
        Measured normal load (N), when the file gives it.
    normal_load : float or None
        The normal load of the record (N): given by the caller, by a
        ``# normal load = ...`` comment, or the mean of ``N``.
    source : str
        Where it came from (file name), for messages and legends.
    """

    t: np.ndarray
    T: np.ndarray
    time: np.ndarray | None = None
    N: np.ndarray | None = None
    normal_load: float | None = None
    source: str = "record"

    def __post_init__(self):
        if not isinstance(self.source, str):
            raise TypeError(f"source must be a str (a file name, for messages), got {self.source!r}")
        t = _checks.real_array("t", self.t, ndim=1)
        T = _checks.real_array("T", self.T, ndim=1)
        if T.shape != t.shape:
            raise ValueError(f"T must have the same length as t ({t.size}), got {T.size}")
        if t.size < MIN_SAMPLES:
            raise ValueError(f"{self.source}: too few samples: {t.size}; a record needs at least "
                             f"{MIN_SAMPLES} to hold a complete cycle")
        object.__setattr__(self, "t", t)
        object.__setattr__(self, "T", T)
        for name in ("time", "N"):
            value = getattr(self, name)
            if value is not None:
                arr = _checks.real_array(name, value, ndim=1)
                if arr.shape != t.shape:
                    raise ValueError(f"{name} must have the same length as t ({t.size}), got {arr.size}")
                object.__setattr__(self, name, arr)
        if self.normal_load is not None:
            object.__setattr__(self, "normal_load", _checks.positive_scalar("normal_load", self.normal_load))

    @property
    def samples(self) -> int:
        """Number of samples."""
        return self.t.size

    def analyse(self, **options):
        """Loop analysis of this record: see :func:`microslip.loops.analyse`."""
        return analyse(self, **options)

    def plot(self, ax=None, **kwargs):
        """Plot the force (N) against the displacement (µm); returns the Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(5.5, 4))
        ax.plot(self.t * 1e6, self.T, lw=0.8, **kwargs)
        ax.set_xlabel("tangential displacement t (µm)")
        ax.set_ylabel("tangential force T (N)")
        ax.set_title(self.source)
        ax.grid(True, alpha=0.3)
        return ax


def python_option(kind: str, role: str) -> tuple[str, str]:
    """How a Python caller of :func:`read` gives the column (``kind="column"``) or the unit (``"unit"``) of ``role``.

    Returns ``(name, example)`` for messages, e.g. ``("columns['T']",
    "columns={'T': ...}")``. Other callers (the command line) pass their
    own function to :func:`read_with_options`, returning None for a role
    they cannot give.
    """
    key = "columns" if kind == "column" else "units"
    return f"{key}[{role!r}]", f"{key}={{{role!r}: ...}}"


def read(path, *, columns=None, units=None, normal_load=None) -> Record:
    """Read a measured record of hysteresis loops, converted to SI.

    Parameters
    ----------
    path : str or Path
        A delimited text file (``.csv``, ``.txt``, ``.dat``, ...) whose header
        names the columns and their units, e.g. ``time [s], t [um], T [N]``;
        or a ``.json`` file in the layout of the ARTS-Lab friction damper data
        (displacement in inches, friction force in kips; the normal load is
        taken as the sum of its two band-tensioning actuator forces; that data
        set is CC BY-SA 4.0 and is not shipped with microslip).
    columns : dict, optional
        Column name for each role, overriding the defaults: ``{"t": ...}``
        tangential displacement, ``{"T": ...}`` tangential force,
        ``{"time": ...}``, ``{"N": ...}`` normal load (the last two optional).
        Default names tried: ``t, x, u, displacement`` / ``T, F, force`` /
        ``time`` / ``N, normal load``.
    units : dict, optional
        Unit for a role whose column has none in the header, e.g.
        ``{"t": "um", "T": "N"}``. It never overrides the header: a unit
        that differs from the header's raises ``ValueError``.
    normal_load : float or str, optional
        Normal load of the whole record (N, or a string with its unit such as
        ``"36.6N"``). Default: a ``# normal load = 36.6 N`` comment in the
        file, else the mean of the ``N`` column, else unknown (``None``).

    Returns
    -------
    Record
        ``t`` (m), ``T`` (N), ``time`` (s), ``N`` (N), each shape ``(samples,)``.

    Raises
    ------
    FileNotFoundError
        No such file.
    ValueError
        A missing column (the message lists those present), a column name
        given twice in the header, an unknown unit or one of the wrong
        kind, a column without a unit, a unit in ``units`` that conflicts
        with the header's, a cell that is not a number or not finite (line
        and column named), a header without data rows, too few samples,
        text that cannot be decoded (the file named).
    """
    return read_with_options(path, python_option, columns=columns, units=units, normal_load=normal_load)


def read_with_options(path, option, *, columns=None, units=None, normal_load=None) -> Record:
    """:func:`read`, its messages naming the caller's own way to give a column or a unit.

    ``option(kind, role)`` returns ``(name, example)`` or None: see
    :func:`python_option`.
    """
    path = _checks.file_path("path", path)
    columns = _role_map("columns", columns)
    units = _role_map("units", units)
    if not path.is_file():
        raise FileNotFoundError(f"loops file {str(path)!r} does not exist")
    if path.suffix.lower() == ".json":
        table, table_units = _read_damper_json(path)
        comment_load = None
        defaults = {"t": ("displacement",), "T": ("friction force",), "time": ("time",), "N": ("actuator force sum",)}
    else:
        table, table_units = read_table(path)
        comment_load = _comment_load(path, table.comments)
        defaults = DEFAULT_COLUMNS
    data = {}
    for role in ("t", "T", "time", "N"):
        name = _pick_column(path, table, role, columns.get(role), defaults[role], option("column", role),
                            required=role in ("t", "T"))
        if name is None:
            continue
        unit_option = option("unit", role)
        unit = header_unit(table_units, name, units.get(role), _KIND[role], path=path,
                           option=unit_option[0] if unit_option else "the unit given")
        if not unit:
            raise ValueError(f"{path}: column {name!r} ({_KIND[role]}) has no unit in the header; write it as "
                             f"'{name} [unit]'" + (f" or give {unit_option[1]}" if unit_option else ""))
        data[role] = column_si(table, table_units, name, _KIND[role], path=path, unit=unit)
    if normal_load is not None:
        load = parse_quantity(normal_load, "force", name="normal_load")
    elif comment_load is not None:
        load = comment_load
    elif "N" in data:
        load = float(np.mean(data["N"]))
    else:
        load = None
    return Record(t=data["t"], T=data["T"], time=data.get("time"), N=data.get("N"), normal_load=load,
                  source=path.name)


def _role_map(name, value) -> dict:
    if value is None:
        return {}
    if not isinstance(value, dict):
        raise TypeError(f"{name} must be a dict keyed by role ('t', 'T', 'time', 'N'), got {type(value).__name__}")
    bad = sorted(set(value) - set(_KIND))
    if bad:
        raise ValueError(f"{name}: unknown role(s) {bad}; expected keys among {sorted(_KIND)}")
    return dict(value)


def _pick_column(path, table, role, given, defaults, option, *, required):
    """The column of ``role``: ``given`` (by ``option``, for messages), else the first of ``defaults`` present."""
    if given is not None:
        if given not in table:
            by = f"given by {option[0]}" if option else f"asked for {role!r}"
            raise ValueError(f"{path}: no column {given!r} ({by}); the columns are {list(table)}")
        return given
    for name in defaults:
        if name in table:
            return name
    if required:
        advice = f"name it with {option[1]}" if option else "rename it in the header"
        raise ValueError(f"{path}: no column for {role!r} ({_KIND[role]}): looked for {list(defaults)}, the "
                         f"columns are {list(table)}; {advice}")
    return None


def _comment_load(path, comments):
    """The load of a ``# normal load = 36.6 N`` comment above the header, else None."""
    for line in comments:
        m = _LOAD_COMMENT.match(line)
        if m:
            return parse_quantity(m.group(1).replace(" ", ""), "force", name=f"{path}: normal load comment")
    return None


def _read_damper_json(path):
    """The ARTS-Lab damper JSON as ``({name: raw values}, {name: unit})``."""
    try:
        doc = json.loads(read_text(path, "JSON file"))
    except json.JSONDecodeError as exc:
        raise ValueError(f"{path}: not valid JSON ({exc})") from None
    if not isinstance(doc, dict) or "data" not in doc:
        raise ValueError(f"{path}: expected a JSON object with a 'data' matrix (the ARTS-Lab friction damper "
                         f"layout), got keys {list(doc) if isinstance(doc, dict) else type(doc).__name__}")
    try:
        data = np.asarray(doc["data"], dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{path}: 'data' must be a matrix of numbers") from None
    if data.ndim != 2 or data.shape[1] != len(_DAMPER_COLUMNS):
        raise ValueError(f"{path}: 'data' must have {len(_DAMPER_COLUMNS)} columns {list(_DAMPER_COLUMNS)}, "
                         f"got shape {data.shape}")
    table = {name: data[:, i] for i, name in enumerate(_DAMPER_COLUMNS)}
    units = {}
    for name, key in _DAMPER_UNIT_KEYS.items():
        if key not in doc:
            raise ValueError(f"{path}: missing the key {key!r} giving the unit of {name!r}")
        units[name] = str(doc[key])
    # the normal-load proxy: both band-tensioning actuators pull on the band
    try:
        factor = unit_factor(units["actuator force 1"], "force")
    except ValueError as exc:
        raise ValueError(f"{path}: actuator force units: {exc}") from None
    table["actuator force sum"] = (table["actuator force 1"] + table["actuator force 2"]) * factor
    units["actuator force sum"] = "N"
    return table, units
