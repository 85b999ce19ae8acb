"""A strict reader of Harwell-Boeing files: real assembled matrices, ``RUA`` and ``RSA`` (private).

The layout is that of Duff, Grimes and Lewis, "User's Guide for the Harwell-Boeing Sparse Matrix
Collection" (1992), which ANSYS ``HBMAT`` (``Form = ASCII``) writes and ``scipy.io.hb_read`` reads
for unsymmetric matrices only:

* line 1: title (72 characters) and key; line 2: the numbers of lines ``TOTCRD PTRCRD INDCRD VALCRD
  RHSCRD``; line 3: the type (``RUA`` real unsymmetric assembled, ``RSA`` real symmetric assembled:
  one triangle stored), rows, columns, entries, elemental entries (0); line 4: the Fortran formats of
  the pointers, indices, values (and right-hand sides); line 5 when ``RHSCRD > 0``;
* then ``PTRCRD`` lines of column pointers (1-based, ``NCOL + 1``), ``INDCRD`` lines of row indices,
  ``VALCRD`` lines of values, ``RHSCRD`` lines of right-hand sides (not read), each line holding fixed-
  width fields as its Fortran format says (``(16I5)``, ``(4E20.12)``, ``(1P,4D20.12)``, ...).

Every field is checked: a line count that disagrees with line 2, a field that is not a number, a
pointer that decreases, a row outside the matrix, an ``RSA`` entry on both sides of the diagonal are
refused with the line. ANSYS's binary form (``Form = BIN``) is not read.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from ._errors import FileFormatError
from ._limits import MAX_ENTRIES, MAX_ROWS
from ._sparse import compressed

_INT = re.compile(r"[+-]?[0-9]+")
_REAL = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eEdD][+-]?[0-9]+|[+-][0-9]+)?")
#: a Fortran format of one item repeated: (16I5), (1P,4E20.12), (1P4D20.12), (5F16.8)
_FORMAT = re.compile(r"\(\s*(?:[0-9]*P\s*,?\s*)?([0-9]*)\s*([IEDFG])\s*([0-9]+)(?:\.[0-9]+)?(?:E[0-9]+)?\s*\)",
                     re.IGNORECASE)


def _format(path: Path, text: str, what: str, integer: bool) -> tuple[int, int]:
    """``(items per line, width)`` of a Fortran format such as ``(16I5)``."""
    m = _FORMAT.fullmatch(text.strip())
    if not m or (m.group(2).upper() == "I") != integer:
        kind = "integers, e.g. (16I5)" if integer else "reals, e.g. (4E20.12)"
        raise FileFormatError(path, f"the {what} format {text.strip()!r} is not a Fortran format of {kind}", 4)
    per, width = int(m.group(1) or 1), int(m.group(3))
    if not (1 <= per <= 1000 and 1 <= width <= 100):
        raise FileFormatError(path, f"the {what} format {text.strip()!r} has {per} items of width {width} a line", 4)
    return per, width


def _header_ints(path: Path, line: str, no: int, names: list[str], start: int = 0) -> list[int]:
    out = []
    for i, name in enumerate(names):
        field = line[start + 14 * i:start + 14 * (i + 1)].strip() or "0"  # Fortran reads a blank field as 0
        if not _INT.fullmatch(field):
            raise FileFormatError(path, f"{name} {field[:20]!r} (columns {start + 14 * i + 1}-{start + 14 * i + 14}) "
                                        f"is not an integer: {line[:80]!r}", no)
        out.append(int(field))
        if not 0 <= out[-1] <= MAX_ENTRIES:
            raise FileFormatError(path, f"{name} = {out[-1]} must be from 0 to {MAX_ENTRIES:.0e}", no)
    return out


def _fields(path: Path, lines: list[str], first: int, count: int, fmt: tuple[int, int], n: int, what: str,
            integer: bool) -> np.ndarray:
    """``n`` numbers from ``count`` lines starting at index ``first`` of ``lines``, ``fmt`` items a line."""
    per, width = fmt
    if count != -(-n // per):
        raise FileFormatError(path, f"line 2 gives {count} lines of {what} but {n} {what} at {per} a line take "
                              f"{-(-n // per)}", 2)
    out = np.zeros(n, dtype=np.int64 if integer else np.float64)
    pattern = _INT if integer else _REAL
    for i in range(count):
        no, line = first + i + 1, lines[first + i]
        items = min(per, n - i * per)
        fields = line.split()  # numbers apart (as SciPy writes them), else Fortran's fixed widths
        if len(fields) != items:
            if len(line.rstrip()) > per * width or len(line.rstrip()) <= (items - 1) * width:
                raise FileFormatError(path, f"a line of {what} must hold {items} numbers (fields of {width} "
                                            f"characters), got {len(fields)}: {line[:80]!r}", no)
            fields = [line[j * width:(j + 1) * width].strip() for j in range(items)]
            if line[items * width:].strip():
                raise FileFormatError(path, f"characters after the {items} fields of {width} characters: "
                                            f"{line[:80]!r}", no)
        for j, field in enumerate(fields):
            if not pattern.fullmatch(field):
                kind = "an integer" if integer else "a number"
                raise FileFormatError(path, f"{what[:-1] if what.endswith('s') else what} {i * per + j + 1} "
                                            f"{field[:30]!r} is not {kind}: {line[:80]!r}", no)
            if integer:
                out[i * per + j] = int(field) if len(field) < 19 else -1
            else:
                if "e" not in field.lower() and "d" not in field.lower() and re.search(r"[0-9.][+-]", field):
                    field = re.sub(r"([0-9.])([+-])", r"\1e\2", field, count=1)  # Fortran drops the E of 1.0+100
                out[i * per + j] = v = float(field.replace("d", "e").replace("D", "e"))
                if not np.isfinite(v):
                    raise FileFormatError(path, f"value {i * per + j + 1} {field!r} is not finite", no)
    return out


def read(path: Path) -> sp.csr_matrix:
    """The matrix of a Harwell-Boeing ``RUA`` or ``RSA`` file (an ``RSA`` file made whole), CSR.

    Raises
    ------
    FileFormatError
        Not a real assembled Harwell-Boeing matrix, or a damaged one; the message names the line.
    """
    raw = path.read_bytes()
    try:
        text = raw.decode("ascii")
    except UnicodeDecodeError as err:
        raise FileFormatError(path, f"byte {err.start} is not text (ASCII): a damaged file, or a binary one (ANSYS "
                                    f"HBMAT writes text with Form = ASCII)",
                              raw.count(b"\n", 0, err.start) + 1) from None
    if not text.endswith("\n"):
        raise FileFormatError(path, "the file does not end with a line break: it may be truncated",
                              text.count("\n") + 1)
    lines = text.replace("\r\n", "\n").split("\n")[:-1]
    if len(lines) < 4:
        raise FileFormatError(path, f"a Harwell-Boeing file starts with 4 header lines; the file has {len(lines)}",
                              len(lines))
    tot, ptrcrd, indcrd, valcrd, rhscrd = _header_ints(path, lines[1], 2, ["TOTCRD", "PTRCRD", "INDCRD", "VALCRD",
                                                                          "RHSCRD"])
    if tot != ptrcrd + indcrd + valcrd + rhscrd:
        raise FileFormatError(path, f"TOTCRD = {tot} is not PTRCRD + INDCRD + VALCRD + RHSCRD = "
                                    f"{ptrcrd + indcrd + valcrd + rhscrd}", 2)
    kind = lines[2][:3].upper()
    if len(kind) < 3 or kind[0] not in "RCP" or kind[1] not in "SUHZR" or kind[2] not in "AE":
        raise FileFormatError(path, f"the matrix type {lines[2][:3]!r} is not a Harwell-Boeing type such as RUA or "
                                    f"RSA", 3)
    if kind not in ("RUA", "RSA"):
        raise FileFormatError(path, f"the matrix type {kind!r} is not read: real assembled matrices only, RUA "
                                    f"(unsymmetric) or RSA (symmetric, one triangle)", 3)
    nrow, ncol, nnz, nelt = _header_ints(path, lines[2], 3, ["NROW", "NCOL", "NNZERO", "NELTVL"], 14)
    if max(nrow, ncol) > MAX_ROWS or (kind == "RSA" and nrow != ncol):
        raise FileFormatError(path, f"a {nrow} x {ncol} {kind} matrix: at most {MAX_ROWS} rows and columns, square "
                                    f"when symmetric", 3)
    if nelt != 0:
        raise FileFormatError(path, f"NELTVL = {nelt}: an assembled matrix has no elemental entries", 3)
    ptrfmt = _format(path, lines[3][:16], "pointer", True)
    indfmt = _format(path, lines[3][16:32], "index", True)
    valfmt = _format(path, lines[3][32:52], "value", False)
    first = 4 + (rhscrd > 0)
    if len(lines) != first + tot:
        raise FileFormatError(path, f"line 2 declares {tot} lines after the header but the file has "
                                    f"{len(lines) - first}: {'truncated' if len(lines) < first + tot else 'damaged'}",
                              min(len(lines), first + tot))
    ptr = _fields(path, lines, first, ptrcrd, ptrfmt, ncol + 1, "pointers", True) - 1
    idx = _fields(path, lines, first + ptrcrd, indcrd, indfmt, nnz, "row indices", True) - 1
    val = _fields(path, lines, first + ptrcrd + indcrd, valcrd, valfmt, nnz, "values", False)
    try:
        compressed(path, kind, val, idx, ptr, (nrow, ncol), by_row=False, names=("values", "row indices",
                                                                                 "pointers"))
    except FileFormatError as err:  # name the lines where the arrays start
        raise FileFormatError(path, f"{err.what} (1-based in the file; pointers from line {first + 1}, row indices "
                                    f"from line {first + ptrcrd + 1})") from None
    cols = np.repeat(np.arange(ncol), np.diff(ptr))
    _, first_seen = np.unique(cols * nrow + idx, return_index=True)
    if first_seen.size != nnz:
        k = int(np.setdiff1d(np.arange(nnz), first_seen)[0])
        raise FileFormatError(path, f"entry (row {idx[k] + 1}, column {cols[k] + 1}) is stored twice (index {k + 1})")
    A = sp.csc_matrix((val, idx, ptr), shape=(nrow, ncol))
    if kind == "RSA":
        coo = A.tocoo()
        lower, upper = coo.row > coo.col, coo.row < coo.col
        if lower.any() and upper.any():
            k = int(np.flatnonzero(upper if lower[np.flatnonzero(lower | upper)[0]] else lower)[0])
            raise FileFormatError(path, f"entry (row {coo.row[k] + 1}, column {coo.col[k] + 1}) is on the other side "
                                        f"of the diagonal than those before it: an RSA file stores one triangle")
        A = A + sp.triu(A, 1).T if upper.any() else A + sp.tril(A, -1).T
    return sp.csr_matrix(A)
