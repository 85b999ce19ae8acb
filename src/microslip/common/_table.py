"""Delimited text tables whose header names each column and its unit (private).

A header cell reads ``name [unit]`` (``t [um]``, ``T [N]``) or just ``name``;
cells are separated by commas, semicolons, tabs or runs of spaces; lines
starting with ``#`` are comments. Values are converted to SI with
:func:`microslip.common.units.unit_factor`.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from .units import unit_factor

_HEADER_CELL = re.compile(r"^\s*([^\[\]]+?)\s*(?:\[\s*([^\]]*)\s*\])?\s*$")


def _split(line: str, header: bool = False) -> list[str]:
    for sep in (",", ";", "\t"):
        if sep in line:
            return [c.strip() for c in line.split(sep)]
    if header:  # space-separated: keep each "[unit]" with the name before it
        return re.findall(r"[^\s\[\]]+(?:\s*\[[^\]]*\])?|\S+", line)
    return line.split()


def _fast_rows(lines: list[str], width: int):
    """All data lines parsed at C speed, or None when any line is unusual (then the slow path names it)."""
    if not lines:
        return None
    sep = next((c for c in (",", ";", "\t") if c in lines[0]), None)
    try:
        data = np.loadtxt(lines, delimiter=sep, ndmin=2, dtype=float)
    except ValueError:
        return None
    return data if data.shape[1] == width else None


def read_table(path) -> tuple[dict[str, np.ndarray], dict[str, str]]:
    """Read a table into ``{name: values}`` (raw, not converted) and ``{name: unit}``.

    Raises
    ------
    FileNotFoundError
        No such file.
    ValueError
        Empty file, ragged rows, or a cell that is not a number (row and
        column named).
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"table file {str(path)!r} does not exist")
    lines = [(number, ln) for number, ln in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1)
             if ln.strip() and not ln.lstrip().startswith("#")]
    if not lines:
        raise ValueError(f"{path}: the file holds no header and no data")
    names, units = [], {}
    for cell in _split(lines[0][1], header=True):
        m = _HEADER_CELL.match(cell)
        if not m:
            raise ValueError(f"{path}: cannot read the header cell {cell!r}; expected 'name [unit]'")
        names.append(m.group(1))
        units[m.group(1)] = (m.group(2) or "").strip()
    data = _fast_rows([line for _, line in lines[1:]], len(names))
    if data is not None:
        return {name: data[:, i] for i, name in enumerate(names)}, units
    rows = []
    for number, line in lines[1:]:  # numbers of the lines in the file
        cells = _split(line)
        if len(cells) != len(names):
            raise ValueError(f"{path}: line {number} has {len(cells)} cells, the header names {len(names)}")
        row = []
        for name, cell in zip(names, cells):
            try:
                row.append(float(cell))
            except ValueError:
                raise ValueError(f"{path}: line {number}, column {name!r}: {cell!r} is not a number") from None
        rows.append(row)
    data = np.array(rows, dtype=float).reshape(len(rows), len(names))
    return {name: data[:, i] for i, name in enumerate(names)}, units


def column_si(columns, units, name: str, kind: str, *, path="table", unit: str | None = None) -> np.ndarray:
    """Column ``name`` converted to SI; ``unit`` overrides the header's unit."""
    if name not in columns:
        raise ValueError(f"{path}: no column {name!r}; the columns are {list(columns)}")
    u = unit if unit is not None else units.get(name, "")
    try:
        factor = unit_factor(u, kind) if u else 1.0
    except ValueError as exc:
        raise ValueError(f"{path}: column {name!r}: {exc}") from None
    return columns[name] * factor


def header_unit(units, name: str, given: str | None, kind: str, *, path="table", option="unit") -> str:
    """The unit of column ``name``: the header's; ``given`` only fills in a header without one.

    A ``given`` unit that differs from the header's (a different SI factor)
    is refused rather than silently preferred: a ``t [um]`` column read with
    ``mm`` would be 1000 times off.

    Parameters
    ----------
    units : dict
        ``{name: unit}`` from :func:`read_table` (``""`` when the header gives none).
    name : str
        The column.
    given : str or None
        The unit given apart from the file (an option), if any.
    kind : str
        Its dimension (see :func:`microslip.common.units.unit_factor`).
    path, option : str
        For messages: the file and how ``given`` was given (e.g. ``"--unit"``).

    Returns
    -------
    str
        The unit to read the column in (``""``: none, SI).
    """
    header = units.get(name, "")
    if not given or not header or given == header:
        return header or (given or "")
    try:
        same = unit_factor(given, kind) == unit_factor(header, kind)
    except ValueError:
        same = False
    if not same:
        raise ValueError(f"{path}: column {name!r} is in {header!r} by its header, but {option} gives {given!r}; "
                         f"{option} only applies to a column whose header has no unit: drop it, or correct the "
                         f"header")
    return header
