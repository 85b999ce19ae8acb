"""Strict readers of Nastran OUTPUT4 (OP4) files, text and binary (private; :mod:`._formats` calls them).

An OP4 file holds matrices one after the other. Each is a header (columns, rows -- negative for
the BIGMAT layout --, form, type 1-4 = real/complex in single/double precision, an 8-character name
and, in a text file, the Fortran format of the values, e.g. ``1P,3E23.16``), one record per column
holding a nonzero (``ICOL IROW NW``: dense from row ``IROW``, or sparse when ``IROW = 0``: strings
of consecutive rows, each after a header naming its first row), and an end record ``ICOL = NCOL + 1``.
Nastran writes the columns in order; pyNastran in any order: each column once, each row once.
A binary file stores each of these as a Fortran record (its byte count before and after it).

Every line (text) or record (binary) is checked before a number is taken from it: a value that is
not a number of the format, a line of the wrong length or with a value missing, rows or columns
outside the matrix or given twice, counts that disagree with the values present, a file that ends
inside a matrix. The messages name the line, or the byte where the record starts.

``NW`` and the string headers count 4-byte words (Nastran); pyNastran's text writer counts values
instead. Each matrix must follow one of these conventions throughout.
"""

from __future__ import annotations

import bisect
import math
import re
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from ._errors import FileFormatError
from ._limits import MAX_ENTRIES, MAX_ROWS

#: matrix type -> (binary dtype code, words per value, complex)
KINDS = {1: ("f4", 1, False), 2: ("f8", 2, False), 3: ("c8", 2, True), 4: ("c16", 4, True)}
#: rows above which a matrix uses the BIGMAT layout whatever its header says
BIGMAT_ROWS = 65535

_INTS = re.compile(r"[ \t]*[+-]?[0-9]+(?:[ \t]+[+-]?[0-9]+){0,2}[ \t]*")
_FORMAT = re.compile(r"[ \t]*(?:[0-9]*P,)?[ \t]*([0-9]+)[ \t]*[EDed]([0-9]+)\.([0-9]+)[ \t]*")
_NUMBER = re.compile(r" *[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[EeDd][+-]?[0-9]{1,3}|[+-][0-9]{3})")


def read(path: Path) -> dict:
    """``{name: matrix}`` of every matrix in the file (dense ``ndarray`` or CSR, as stored).

    Raises
    ------
    FileFormatError
        A damaged or inconsistent file, or two matrices of one name.
    """
    raw = path.read_bytes()
    head = raw[:4]
    for endian in "<>":
        if len(head) == 4 and int(np.frombuffer(head, endian + "i4")[0]) == 24:
            return _Binary(path, raw, endian).read()
        if len(head) == 4 and int(np.frombuffer(head, endian + "i4")[0]) == 48:
            raise FileFormatError(path, "a binary OP4 file with 64-bit integers; write it with 32-bit integers "
                                        "(or as text)")
    return _Text(path, raw).read()


class _Matrix:
    """The strings of rows of one matrix as its records give them, checked as they come; the values
    are converted once, at the end (:meth:`matrix`)."""

    def __init__(self, path, name, ncols, nrows, kind, where):
        if kind not in KINDS:
            raise FileFormatError(path, f"matrix {name!r}: type {kind} is not 1, 2, 3 or 4 (real or complex, single "
                                        f"or double precision)", *where)
        if ncols < 1 or nrows == 0:
            raise FileFormatError(path, f"matrix {name!r}: declares {ncols} columns and {nrows} rows", *where)
        self.path, self.name, self.ncols = path, name, ncols
        self.big, self.nrows = nrows < 0 or nrows > BIGMAT_ROWS, abs(nrows)
        if max(self.ncols, self.nrows) > MAX_ROWS:
            raise FileFormatError(path, f"matrix {name!r}: declares {self.nrows} x {ncols}; at most {MAX_ROWS} rows "
                                        f"and columns are read", *where)
        code, self.words, self.complex = KINDS[kind]
        self.per_value = 2 if self.complex else 1  # numbers per value in a text file
        self.starts, self.lengths, self.cols, self.wheres = [], [], [], []  # one entry per string of rows
        self.dense, self.columns, self.first = None, set(), 0
        self.conventions = {"words", "values"}

    def column(self, icol, irow, where):
        """A column record starts (columns may come in any order -- pyNastran writes them so --, once each)."""
        if not 1 <= icol <= self.ncols or icol in self.columns:
            raise FileFormatError(self.path, f"matrix {self.name!r}: column {icol} is outside 1..{self.ncols} or "
                                             f"given twice", *where)
        self.columns.add(icol)
        self.first = len(self.starts)
        if self.dense is None:
            self.dense = irow != 0
        elif self.dense != (irow != 0):
            raise FileFormatError(self.path, f"matrix {self.name!r}: column {icol} is "
                                             f"{'sparse (IROW = 0)' if irow == 0 else 'dense (IROW > 0)'} but those "
                                             f"before are not", *where)

    def string(self, icol, first, n, where):
        """``n`` values of consecutive rows from ``first`` (1-based) of column ``icol``."""
        if first < 1 or first + n - 1 > self.nrows:
            raise FileFormatError(self.path, f"matrix {self.name!r}: column {icol}: {n} value(s) from row {first} "
                                             f"fall outside rows 1..{self.nrows}", *where)
        self.starts.append(first - 1)
        self.lengths.append(n)
        self.cols.append(icol - 1)
        self.wheres.append(where)

    def strings_end(self, icol, where):
        """A sparse column's strings may come in any order, but never give a row twice."""
        strings = sorted(zip(self.starts[self.first:], self.lengths[self.first:]))
        for (a, n), (b, _) in zip(strings, strings[1:]):
            if b < a + n:
                raise FileFormatError(self.path, f"matrix {self.name!r}: column {icol} gives row {b + 1} twice",
                                      *where)

    def counts(self, icol, expected: dict, where):
        """Keep the counting conventions under which the record's counts are ``expected`` ones."""
        self.conventions &= {c for c, ok in expected.items() if ok}
        if not self.conventions:
            raise FileFormatError(self.path, f"matrix {self.name!r}: column {icol}: the record's word counts do not "
                                             f"match the values it holds (a value is missing or a count is damaged)",
                                  *where)

    def matrix(self, vals: np.ndarray):
        """The matrix from the values of every string, in their order (finite: the readers check them)."""
        lengths = np.array(self.lengths, dtype=np.int64)
        ends = np.cumsum(lengths)
        total = int(ends[-1]) if ends.size else 0
        rows = np.repeat(np.array(self.starts, dtype=np.int64) - (ends - lengths), lengths) + np.arange(total)
        cols = np.repeat(np.array(self.cols, dtype=np.int64), lengths)
        if self.dense is False:
            return sp.csr_matrix((vals, (rows, cols)), shape=(self.nrows, self.ncols))
        if self.nrows * self.ncols > MAX_ENTRIES:
            raise FileFormatError(self.path, f"matrix {self.name!r}: a dense {self.nrows} x {self.ncols} matrix has "
                                             f"more than {MAX_ENTRIES:.0e} entries")
        A = np.zeros((self.nrows, self.ncols), vals.dtype)
        A[rows, cols] = vals
        return A


def _add(path, found: dict, name: str, A):
    if name in found:
        raise FileFormatError(path, f"holds two matrices named {name!r}")
    found[name] = A


# -- text ------------------------------------------------------------------------------------------
class _Text:
    def __init__(self, path: Path, raw: bytes):
        try:
            text = raw.decode("ascii")
        except UnicodeDecodeError as err:
            raise FileFormatError(path, f"byte {err.start} is not ASCII text (a damaged file, or not OP4)",
                                  raw.count(b"\n", 0, err.start) + 1) from None
        self.path = path
        self.lines = text.replace("\r\n", "\n").split("\n")
        while self.lines and not self.lines[-1].strip():
            self.lines.pop()
        self.i = 0

    def read(self) -> dict:
        found = {}
        if not self.lines:
            raise FileFormatError(self.path, "an empty file")
        while self.i < len(self.lines):
            if not self.lines[self.i].strip():
                self.i += 1
                continue
            _add(self.path, found, *self._matrix())
        return found

    def _fail(self, what, line=None):
        raise FileFormatError(self.path, what, self.i + 1 if line is None else line)

    def _ints(self, count: int, what: str) -> list[int]:
        if self.i >= len(self.lines):
            self._fail(f"the file ends where {what} should be: truncated", len(self.lines))
        line = self.lines[self.i]
        items = line.split()
        if not _INTS.fullmatch(line) or len(items) != count:
            self._fail(f"expected {what}, got {line[:80]!r}")
        self.i += 1
        return [int(x) for x in items]

    def _matrix(self) -> tuple[str, object]:
        head, where = self.lines[self.i], (self.i + 1,)
        try:
            ncols, nrows, _form, kind = (int(head[k:k + 8]) for k in (0, 8, 16, 24))
        except ValueError:
            self._fail(f"expected a matrix header (NCOL, NROW, FORM, TYPE as 8-character integers, the name, the "
                       f"format), got {head[:80]!r}")
        name, fmt = head[32:40].strip(), head[40:].strip()
        m = _FORMAT.fullmatch(fmt)
        if not name or m is None or int(m.group(1)) < 1 or int(m.group(2)) < 2:
            self._fail(f"the matrix header must end with an 8-character name and a Fortran format such as "
                       f"1P,3E23.16; got {head[32:][:60]!r}")
        self.fmt, self.per_line, self.width = fmt, int(m.group(1)), int(m.group(2))
        self.cells, self.line_starts, self.line_numbers = [], [], []  # the matrix's values, and their lines
        matrix = _Matrix(self.path, name, ncols, nrows, kind, where)
        self.i += 1
        while True:
            where = (self.i + 1,)
            icol, irow, nw = self._ints(3, f"a column record 'ICOL IROW NW' of matrix {name!r}")
            if icol == matrix.ncols + 1:  # the end record and its value (one line: a matrix header may follow)
                held = len(self.cells)
                if not self._values(lines=1):
                    self._fail(f"matrix {name!r}: the end record has no value")
                vals = self._numbers()[:held]  # (the end record's value checked too)
                if matrix.complex:
                    vals = vals[0::2] + 1j * vals[1::2]
                return name, matrix.matrix(vals)
            matrix.column(icol, irow, where)
            if irow:
                f = self._string(matrix, icol, irow, where)
                matrix.counts(icol, {"words": nw == f * matrix.words // matrix.per_value, "values": nw == f}, where)
            else:
                self._sparse_column(matrix, icol, nw, where)

    def _string(self, matrix: _Matrix, icol: int, first: int, where) -> int:
        """Read the value lines of a string of rows from ``first``; returns the count of numbers."""
        f = self._values()
        if not f:
            self._fail(f"matrix {matrix.name!r}: column {icol}: expected a line of values")
        if f % matrix.per_value:
            self._fail(f"matrix {matrix.name!r}: column {icol}: a complex value needs two numbers, the record "
                       f"holds {f}", self.i)
        matrix.string(icol, first, f // matrix.per_value, where)
        return f

    def _sparse_column(self, matrix: _Matrix, icol: int, nw: int, where):
        h = 2 if matrix.big else 1
        strings = []
        while self.i < len(self.lines) and _INTS.fullmatch(self.lines[self.i]) \
                and len(self.lines[self.i].split()) == h:
            at = (self.i + 1,)
            ints = self._ints(h, "a string header")
            if matrix.big:
                words, first = ints[0] - 1, ints[1]
            else:
                words = ints[0] // 65536 - 1
                first = ints[0] - 65536 * (words + 1)
            strings.append((words, self._string(matrix, icol, first, at)))
        if not strings:
            self._fail(f"matrix {matrix.name!r}: column {icol} is sparse (IROW = 0) but no string of values follows")
        matrix.strings_end(icol, where)
        total = sum(f for _, f in strings)
        per_field = matrix.words // matrix.per_value
        words = all(w == f * per_field for w, f in strings) and nw == sum(h + f * per_field for _, f in strings)
        values = (nw == sum(h + f for _, f in strings)) if matrix.big else (
            nw == 2 * total + 1 and all(w == 2 * total for w, _ in strings))
        matrix.counts(icol, {"words": words, "values": values}, where)

    def _values(self, lines: int | None = None) -> int:
        """Gather the values on the lines from here to the next line of integers (at most ``lines`` lines),
        each line but the last full; returns their count."""
        start, full, w, k = len(self.cells), True, self.width, self.per_line
        first_line = self.i
        while self.i < len(self.lines) and not _INTS.fullmatch(self.lines[self.i]) \
                and (lines is None or self.i - first_line < lines):
            line = self.lines[self.i].rstrip()
            if not line:
                self._fail("an empty line among the values")
            n, rest = divmod(len(line), w)
            if rest:
                self._fail(f"{len(line)} characters are not a whole number of {w}-character values (format "
                           f"{self.fmt}): a value is damaged or cut short")
            if n > k:
                self._fail(f"{n} values on a line; the format {self.fmt} puts at most {k}")
            if not full:
                self._fail(f"{(len(self.cells) - start) % k} values on a line that is not the last of its record; "
                           f"the format {self.fmt} puts {k} (a value is missing)", self.i)
            full = n == k
            self.line_starts.append(len(self.cells))
            self.line_numbers.append(self.i + 1)
            self.cells.extend(line[j:j + w] for j in range(0, len(line), w))
            self.i += 1
        return len(self.cells) - start

    def _numbers(self) -> np.ndarray:
        """The matrix's values, each a number of the format: NumPy reads them all at once (strictly:
        '4.0E+0x' is no number); where it cannot, the first value that is not one is named with its line."""
        cells = self.cells
        try:
            out = np.array(cells).astype(np.float64)
            ok = bool(np.isfinite(out).all()) and not any("_" in c for c in cells)
        except ValueError:
            ok = False
        if ok:
            return out
        out = np.empty(len(cells))  # Fortran's forms (1.0D+00, 1.0-100) or a damaged value
        for j, cell in enumerate(cells):
            at = bisect.bisect_right(self.line_starts, j) - 1
            line, position = self.line_numbers[at], j - self.line_starts[at] + 1
            if not _NUMBER.fullmatch(cell):
                self._fail(f"value {position}, {cell.strip()!r}, is not a number of the format {self.fmt}", line)
            out[j] = _float(cell)
            if not math.isfinite(out[j]):
                self._fail(f"the value {out[j].item()!r} is not finite", line)
        return out


def _float(cell: str) -> float:
    s = cell.strip().upper().replace("D", "E")
    if "E" not in s:  # Fortran's three-digit exponent without its letter: 1.0-100
        s = s[:-4] + "E" + s[-4:]
    return float(s)


# -- binary ----------------------------------------------------------------------------------------
class _Binary:
    def __init__(self, path: Path, raw: bytes, endian: str):
        self.path, self.raw, self.pos = path, raw, 0
        self.i4 = np.dtype(endian + "i4")
        self.endian = endian

    def _fail(self, what, at):
        raise FileFormatError(self.path, f"at byte {at}: {what}")

    def _record(self, what: str) -> tuple[int, int, int]:
        """``(start, end, at)``: where the next record's bytes lie in the file, and where it starts."""
        at, raw = self.pos, self.raw
        if at + 4 > len(raw):
            self._fail(f"the file ends where {what} should be: truncated", at)
        n = int(np.frombuffer(raw, self.i4, 1, at)[0])
        if n < 0 or at + 8 + n > len(raw):
            self._fail(f"{what} of {n} bytes runs past the end of the file ({len(raw)} bytes): truncated or damaged",
                       at)
        if int(np.frombuffer(raw, self.i4, 1, at + 4 + n)[0]) != n:
            self._fail(f"{what}: the byte counts before and after the record differ (a damaged file)", at)
        self.pos = at + 8 + n
        return at + 4, at + 4 + n, at

    def read(self) -> dict:
        found = {}
        while self.pos < len(self.raw):
            _add(self.path, found, *self._matrix())
        return found

    def _matrix(self) -> tuple[str, object]:
        start, end, at = self._record("a matrix header record")
        if end - start != 24:
            self._fail(f"expected a matrix header record of 24 bytes, got {end - start}", at)
        ncols, nrows, _form, kind = (int(x) for x in np.frombuffer(self.raw, self.i4, 4, start))
        name = self.raw[start + 16:end].decode("ascii", errors="replace").strip()
        try:
            matrix = _Matrix(self.path, name, ncols, nrows, kind, ())
        except FileFormatError as err:
            self._fail(err.what, at)
        code, words, _ = KINDS[kind]
        dtype = np.dtype(self.endian + code)
        pieces, offsets = [], []  # the bytes of each string's values, and where the record starts
        while True:
            start, end, at = self._record(f"a column record of matrix {name!r}")
            if end - start < 12:
                self._fail(f"matrix {name!r}: a column record of {end - start} bytes (at least ICOL, IROW, NW: 12)", at)
            icol, irow, nw = (int(x) for x in np.frombuffer(self.raw, self.i4, 3, start))
            if icol == ncols + 1:
                break
            if nw < 0 or end - start - 12 != 4 * nw:
                self._fail(f"matrix {name!r}: column {icol} declares NW = {nw} words but its record holds "
                           f"{(end - start - 12) / 4:g}", at)
            try:
                matrix.column(icol, irow, ())
                if irow:
                    if nw % words:
                        self._fail(f"matrix {name!r}: column {icol}: {nw} words are not whole values of {words} words",
                                   at)
                    matrix.string(icol, irow, nw // words, ())
                    pieces.append(self.raw[start + 12:end])
                    offsets.append(at)
                else:
                    self._sparse_column(matrix, icol, start + 12, end, words, at, pieces, offsets)
            except FileFormatError as err:
                if err.line is None and not err.what.startswith("at byte"):
                    self._fail(err.what, at)
                raise
        vals = np.frombuffer(b"".join(pieces), dtype)
        if not np.isfinite(vals).all():
            k = int(np.flatnonzero(~np.isfinite(vals))[0])
            string = int(np.searchsorted(np.cumsum(matrix.lengths), k, side="right"))
            self._fail(f"matrix {name!r}: column {matrix.cols[string] + 1} holds {vals[k].item()!r}", offsets[string])
        return name, matrix.matrix(vals.astype(np.complex128 if matrix.complex else np.float64))

    def _sparse_column(self, matrix, icol, off, end, words, at, pieces, offsets):
        h = 8 if matrix.big else 4
        if off == end:
            self._fail(f"matrix {matrix.name!r}: column {icol} is sparse (IROW = 0) but holds no string", at)
        while off < end:
            if off + h > end:
                self._fail(f"matrix {matrix.name!r}: column {icol}: a string header runs past the record", at)
            ints = [int(x) for x in np.frombuffer(self.raw, self.i4, h // 4, off)]
            if matrix.big:
                n_words, first = ints[0] - 1, ints[1]
            else:
                n_words = ints[0] // 65536 - 1
                first = ints[0] - 65536 * (n_words + 1)
            off += h
            if n_words <= 0 or n_words % words or off + 4 * n_words > end:
                self._fail(f"matrix {matrix.name!r}: column {icol}: a string of {n_words} words does not fit the "
                           f"record or is not whole values of {words} words", at)
            matrix.string(icol, first, n_words // words, ())
            pieces.append(self.raw[off:off + 4 * n_words])
            offsets.append(at)
            off += 4 * n_words
        matrix.strings_end(icol, ())
