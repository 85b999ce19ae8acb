"""A strict Matrix Market reader (private; :mod:`._formats` calls it).

Every line is checked before a number is taken from it, so a damaged file is refused with its line
rather than read leniently: ``4.0e+0x`` is not read as 4.0, a line with a missing or an extra value
is not read in part, and a size line declaring more entries than the file holds is refused before
anything is allocated.

* banner ``%%MatrixMarket matrix coordinate|array real|double|integer|complex|pattern
  general|symmetric|skew-symmetric|hermitian``, then comment lines (``%``), then the size line
  (``rows columns entries`` for coordinates, ``rows columns`` for an array);
* one entry per line, exactly as many as declared, the last line ended by a line break (a file cut
  inside its last line could otherwise end on a shorter number): ``row column value`` (1-based) in coordinate
  format, ``value`` in column order in array format (two numbers for a complex value); a symmetric
  file stores one triangle (entries on both sides of the diagonal are refused).
"""

from __future__ import annotations

import io
import re
from pathlib import Path

import numpy as np
import scipy.io
import scipy.sparse as sp

from ._errors import FileFormatError
from ._limits import MAX_ROWS

_INDEX = r"[0-9]+"
_INTEGER = r"-?[0-9]+"
_REAL = r"-?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"
#: field -> the numbers of one value
_VALUE = {"real": (_REAL,), "double": (_REAL,), "integer": (_INTEGER,), "complex": (_REAL, _REAL)}
_SYMMETRIES = ("general", "symmetric", "skew-symmetric", "hermitian")
_SEP = r"[ \t]+"


def _describe(fmt: str, field: str) -> str:
    value = "real imaginary" if field == "complex" else "value"
    return f"row column {value}" if fmt == "coordinate" else value


def read(path: Path) -> np.ndarray | sp.csr_matrix:
    """The matrix of a Matrix Market file: CSR for coordinates, dense for an array.

    Raises
    ------
    FileFormatError
        Not a Matrix Market matrix, or a damaged one: the message names the line.
    """
    try:
        text = path.read_bytes().decode("utf-8")
    except UnicodeDecodeError as err:
        line = path.read_bytes().count(b"\n", 0, err.start) + 1
        raise FileFormatError(path, f"byte {err.start} is not text (UTF-8): a damaged file", line) from None
    lines = text.replace("\r\n", "\n").split("\n")
    banner = lines[0].split()
    if len(banner) != 5 or banner[0].lower() != "%%matrixmarket" or banner[1].lower() != "matrix":
        raise FileFormatError(path, f"not a Matrix Market matrix: the first line must be '%%MatrixMarket matrix "
                                    f"FORMAT FIELD SYMMETRY', got {lines[0][:80]!r}", 1)
    if not text.endswith("\n"):  # a cut inside the last line could leave a shorter number, still a number
        raise FileFormatError(path, "the file does not end with a line break: it may be truncated (if its last line "
                                    "is complete, end it with a line break)", len(lines))
    fmt, field, symmetry = (b.lower() for b in banner[2:])
    if fmt not in ("coordinate", "array"):
        raise FileFormatError(path, f"format {banner[2]!r} is not 'coordinate' or 'array'", 1)
    if field == "pattern":
        raise FileFormatError(path, "a pattern file holds the positions of entries but no values; expected a "
                                    "real matrix", 1)
    if field not in _VALUE:
        raise FileFormatError(path, f"field {banner[3]!r} is not one of real, double, integer, complex", 1)
    if symmetry not in _SYMMETRIES:
        raise FileFormatError(path, f"symmetry {banner[4]!r} is not one of {', '.join(_SYMMETRIES)}", 1)
    no = 1
    while no < len(lines) and (lines[no].startswith("%") or not lines[no].strip()):
        no += 1
    if no == len(lines):
        raise FileFormatError(path, "the file ends before the size line (truncated)", no)
    size = lines[no].split()
    wanted = 3 if fmt == "coordinate" else 2
    if len(size) != wanted or not all(re.fullmatch(_INDEX, s) for s in size):
        spelled = "rows columns entries" if fmt == "coordinate" else "rows columns"
        raise FileFormatError(path, f"the size line must be '{spelled}' ({wanted} non-negative integers), got "
                                    f"{lines[no][:80]!r}", no + 1)
    nrows, ncols = int(size[0]), int(size[1])
    if max(nrows, ncols) > MAX_ROWS:
        raise FileFormatError(path, f"declares a {nrows} x {ncols} matrix; at most {MAX_ROWS} rows and columns "
                                    f"are read", no + 1)
    if symmetry != "general" and nrows != ncols:
        raise FileFormatError(path, f"a {symmetry} matrix must be square, got {nrows} x {ncols}", no + 1)
    if fmt == "coordinate":
        entries = int(size[2])
    else:
        entries = {"general": nrows * ncols, "skew-symmetric": nrows * (nrows - 1) // 2}.get(
            symmetry, nrows * (nrows + 1) // 2)
    first = no + 1  # index in `lines` of the first entry
    data = "\n".join(lines[first:]).rstrip()
    held = data.count("\n") + 1 if data else 0
    numbers = ((_INDEX, _INDEX) if fmt == "coordinate" else ()) + _VALUE[field]
    good = "[ \t]*" + _SEP.join(f"(?:{n})" for n in numbers) + "[ \t]*"
    bad = re.compile(rf"^(?!{good}$).*$", re.M).search(data) if data else None
    if bad is not None:
        line = data.count("\n", 0, bad.start())
        ends = " (the last line: the file may be truncated)" if line == held - 1 and held <= entries else ""
        raise FileFormatError(path, _why(bad.group(0), numbers, _describe(fmt, field)) + ends, first + line + 1)
    if held < entries:
        raise FileFormatError(path, f"the size line (line {no + 1}) declares {entries} entries but the file holds "
                                    f"{held}: truncated", first + held)
    if held > entries:
        raise FileFormatError(path, f"more entries than the {entries} the size line (line {no + 1}) declares",
                              first + entries + 1)
    if fmt == "coordinate":
        rows, cols, v = _entries(path, lines, field)
    elif entries:
        values = np.loadtxt(io.StringIO(data), dtype=np.float64, ndmin=2, comments=None)
        v = values[:, 0] + 1j * values[:, 1] if field == "complex" else values[:, 0]
    else:
        v = np.zeros(0)
    if not np.isfinite(v).all():
        k = int(np.flatnonzero(~np.isfinite(v))[0])
        raise FileFormatError(path, f"the value {v[k].item()!r} is not finite", first + k + 1)
    if fmt == "array":
        return _array(v, nrows, ncols, symmetry)
    return _coordinate(path, rows, cols, v, nrows, ncols, symmetry, first)


def _entries(path: Path, lines: list[str], field: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Rows, columns (from 0) and values in the file's order, parsed by scipy once every line is checked.

    The banner is read as ``general``: a symmetric file's entries come back as stored, one triangle.
    """
    text = "\n".join([f"%%MatrixMarket matrix coordinate {field} general"] + lines[1:])
    try:
        A = scipy.io.mmread(io.StringIO(text))
    except ValueError as err:  # an index outside the matrix, as scipy says it
        m = re.match(r"Line (\d+): (.*)", str(err))
        raise FileFormatError(path, m.group(2) if m else str(err), int(m.group(1)) if m else None) from None
    return A.row.astype(np.int64), A.col.astype(np.int64), A.data.astype(np.complex128 if field == "complex"
                                                                           else np.float64)


def _why(line: str, numbers: tuple, spelled: str) -> str:
    """Why a data line does not match: the count of items or the first item that is not a number."""
    items = line.split()
    if len(items) != len(numbers):
        return f"expected '{spelled}' ({len(numbers)} items), got {len(items)}: {line[:80]!r}"
    for item, pattern, name in zip(items, numbers, spelled.split()):
        if not re.fullmatch(pattern, item):
            kind = "an index (1, 2, ...)" if pattern == _INDEX else "a number"
            return f"the {name} {item[:40]!r} is not {kind}: {line[:80]!r}"
    return f"not '{spelled}': {line[:80]!r}"  # pragma: no cover - a character the items do not show


def _array(v: np.ndarray, n: int, m: int, symmetry: str) -> np.ndarray:
    if symmetry == "general":
        return v.reshape(m, n).T.copy()
    A = np.zeros((n, n), dtype=v.dtype)
    cols, rows = np.triu_indices(n, 1 if symmetry == "skew-symmetric" else 0)  # column order of the lower triangle
    A[rows, cols] = v
    off = rows != cols
    A[cols[off], rows[off]] = {"symmetric": v, "skew-symmetric": -v, "hermitian": np.conj(v)}[symmetry][off]
    return A


def _coordinate(path, rows, cols, v, nrows, ncols, symmetry, first) -> sp.csr_matrix:
    for name, idx, count in (("row", rows, nrows), ("column", cols, ncols)):
        out = (idx < 0) | (idx >= count)
        if out.any():
            k = int(np.flatnonzero(out)[0])
            raise FileFormatError(path, f"{name} {idx[k] + 1} is outside the matrix's {count} {name}s (1..{count})",
                                  first + k + 1)
    if symmetry != "general":
        lower, upper = rows > cols, rows < cols
        if symmetry == "skew-symmetric" and (rows == cols).any():
            k = int(np.flatnonzero(rows == cols)[0])
            raise FileFormatError(path, "a skew-symmetric file has no diagonal entries", first + k + 1)
        if lower.any() and upper.any():
            side = lower if lower[np.flatnonzero(lower | upper)[0]] else upper
            k = int(np.flatnonzero((lower | upper) & ~side)[0])
            raise FileFormatError(path, f"entry ({rows[k] + 1}, {cols[k] + 1}) is on the other side of the diagonal "
                                        f"than those before it: a {symmetry} file stores one triangle", first + k + 1)
        off = rows != cols
        mirror = {"symmetric": v, "skew-symmetric": -v, "hermitian": np.conj(v)}[symmetry][off]
        rows, cols, v = (np.concatenate([rows, cols[off]]), np.concatenate([cols, rows[off]]),
                         np.concatenate([v, mirror]))
    return sp.csr_matrix((v, (rows, cols)), shape=(nrows, ncols))
