"""Delimited text tables whose header names each column and its unit (private).

A header cell reads ``name [unit]`` (``t [um]``, ``T [N]``) or just ``name``;
cells are separated by commas, semicolons, tabs or runs of spaces; lines
starting with ``#`` are comments. Values are converted to SI with
:func:`microslip.common.units.unit_factor`.

The text may be UTF-8, UTF-16 or UTF-32 with a byte-order mark, UTF-16
without one, UTF-8, or else Windows-1252 / Latin-1 (what spreadsheets and
acquisition software write); see :func:`read_text`.
"""

from __future__ import annotations

import codecs
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


# byte-order marks, longest first (the UTF-32 LE mark begins with the UTF-16 LE one)
_BOMS = ((codecs.BOM_UTF32_LE, "utf-32-le", "UTF-32"), (codecs.BOM_UTF32_BE, "utf-32-be", "UTF-32"),
         (codecs.BOM_UTF8, "utf-8", "UTF-8"), (codecs.BOM_UTF16_LE, "utf-16-le", "UTF-16"),
         (codecs.BOM_UTF16_BE, "utf-16-be", "UTF-16"))


def _utf16_without_bom(raw: bytes) -> str | None:
    """``"utf-16-le"``/``"utf-16-be"`` when ``raw`` looks like UTF-16 text without a mark, else None.

    Text in a Latin script written as UTF-16 has a zero byte in every other
    position (the high byte of each character); no 8-bit text does.
    """
    if len(raw) < 4 or len(raw) % 2:
        return None
    even, odd = raw[0::2].count(0), raw[1::2].count(0)
    half = len(raw) // 2
    if odd > 0.9 * half and even == 0:
        return "utf-16-le"
    if even > 0.9 * half and odd == 0:
        return "utf-16-be"
    return None


def read_text(path, what: str = "table") -> str:
    """The text of a file, its encoding found as spreadsheets and instruments write it.

    A byte-order mark (UTF-8, UTF-16, UTF-32) decides and is dropped; else
    UTF-16 without a mark is recognised by its zero bytes; else the text is
    read as UTF-8 and, failing that, as Windows-1252 and then Latin-1 (every
    byte is a Latin-1 character, so a ``µ`` written by an 8-bit program
    reads as ``µ``).

    Raises
    ------
    ValueError
        A file whose byte-order mark does not match its bytes, or a binary
        file (zero bytes); the message names the file, the encoding and
        the line.
    """
    path = Path(path)
    raw = path.read_bytes()
    found = next(((len(bom), enc, label) for bom, enc, label in _BOMS if raw.startswith(bom)), None)
    if found is None:
        guess = _utf16_without_bom(raw)
        found = (0, guess, "UTF-16 (no byte-order mark)") if guess else None
    if found is not None:
        skip, encoding, label = found
        body = raw[skip:]
        try:
            return body.decode(encoding)
        except UnicodeDecodeError as exc:
            line = body[:exc.start].decode(encoding, errors="replace").count("\n") + 1
            raise ValueError(f"{path}: the {what} reads as {label} but is not valid {label} near line {line} "
                             f"(byte {skip + exc.start}: {exc.reason}); save it again as UTF-8") from None
    if b"\0" in raw:
        raise ValueError(f"{path}: not a text {what}: it holds binary data (a zero byte at byte {raw.index(0)}); "
                         f"export it as CSV or text")
    for encoding in ("utf-8", "cp1252"):
        try:
            return raw.decode(encoding)
        except UnicodeDecodeError:
            continue
    return raw.decode("latin-1")  # never fails: every byte is a character


class Columns(dict):
    """``{name: raw values}`` of a table, which also knows where each row was in its file.

    Attributes
    ----------
    lines : ndarray of int, shape (rows,)
        The line number in the file (from 1) of each row.
    comments : list of str
        The comment lines above the header, as written (with their ``#``).
    """

    def __init__(self, items, lines, comments):
        super().__init__(items)
        self.lines = lines
        self.comments = comments


_SKIPPED = re.compile(r"^[^\S\n]*(?:#|$)", re.MULTILINE)  # a blank or comment line


def _lines(text: str):
    """``(header, body, numbers, comments)`` of a table's text.

    ``header`` is ``(line number, text)`` of the first line that is neither
    blank nor a comment (None if there is none); ``body`` the data lines
    after it and ``numbers`` their line numbers (from 1, as an editor counts
    them), shape (rows,); ``comments`` the comment lines above the header.
    """
    if "\r" in text:
        text = text.replace("\r\n", "\n").replace("\r", "\n")
    lines = text.split("\n")
    comments, h = [], 0
    while h < len(lines) and (not lines[h].strip() or lines[h].lstrip().startswith("#")):
        if lines[h].lstrip().startswith("#"):
            comments.append(lines[h].strip())
        h += 1
    if h == len(lines):
        return None, [], np.empty(0, dtype=np.int64), comments
    body = lines[h + 1:]
    while body and not body[-1].strip():
        body.pop()
    start = sum(len(line) + 1 for line in lines[:h + 1])  # offset of the first body line in the text
    end = start + sum(map(len, body)) + len(body) - 1
    if body and _SKIPPED.search(text, start, max(end, start)) is None:  # the usual file: every line is data
        return (h + 1, lines[h]), body, np.arange(h + 2, h + 2 + len(body)), comments
    kept = [(n, line) for n, line in enumerate(body, start=h + 2) if line.strip() and not line.lstrip().startswith("#")]
    return ((h + 1, lines[h]), [line for _, line in kept], np.array([n for n, _ in kept], dtype=np.int64),
            comments)


def read_table(path) -> tuple[Columns, dict[str, str]]:
    """Read a table into ``{name: values}`` (raw, not converted) and ``{name: unit}``.

    The first is a :class:`Columns`, a dict that also gives the file line of
    each row and the comment lines above the header.

    Raises
    ------
    FileNotFoundError
        No such file.
    ValueError
        Empty file, a header without data rows, a column name given twice,
        ragged rows, or a cell that is not a number (line and column
        named); text that cannot be decoded (see :func:`read_text`).
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"table file {str(path)!r} does not exist")
    header, body, numbers, comments = _lines(read_text(path))
    if header is None:
        raise ValueError(f"{path}: the file holds no header and no data")
    names, units = [], {}
    for cell in _split(header[1], header=True):
        m = _HEADER_CELL.match(cell)
        if not m:
            raise ValueError(f"{path}: cannot read the header cell {cell!r}; expected 'name [unit]'")
        if m.group(1) in units:
            raise ValueError(f"{path}: the header (line {header[0]}) names the column {m.group(1)!r} twice, as "
                             f"columns {names.index(m.group(1)) + 1} and {len(names) + 1}; rename one of them")
        names.append(m.group(1))
        units[m.group(1)] = (m.group(2) or "").strip()
    if not body:
        raise ValueError(f"{path}: no data rows: the header (line {header[0]}) names the columns {names}, "
                         f"but no line of numbers follows it")
    data = _fast_rows(body, len(names))
    if data is not None:
        return Columns({name: data[:, i] for i, name in enumerate(names)}, numbers, comments), units
    rows = []
    for number, line in zip(numbers.tolist(), body):  # numbers of the lines in the file
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
    return Columns({name: data[:, i] for i, name in enumerate(names)}, numbers, comments), units


def column_si(columns, units, name: str, kind: str, *, path="table", unit: str | None = None) -> np.ndarray:
    """Column ``name`` converted to SI; ``unit`` overrides the header's unit.

    Raises ``ValueError`` for a missing column, an unknown unit, or a value
    that is not finite (``nan``, ``inf``): the message names the file and
    the line (the data row when ``columns`` is a plain dict).
    """
    if name not in columns:
        raise ValueError(f"{path}: no column {name!r}; the columns are {list(columns)}")
    u = unit if unit is not None else units.get(name, "")
    try:
        factor = unit_factor(u, kind) if u else 1.0
    except ValueError as exc:
        raise ValueError(f"{path}: column {name!r}: {exc}") from None
    values = columns[name] * factor
    if np.count_nonzero(np.isfinite(values)) != values.size:
        i = int(np.flatnonzero(~np.isfinite(values))[0])
        lines = getattr(columns, "lines", None)
        where = f"line {int(lines[i])}" if lines is not None else f"data row {i + 1}"
        raise ValueError(f"{path}: {where}, column {name!r}: {float(columns[name][i])!r} is not a finite number")
    return values


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
