"""A strict reader of MATLAB v4 MAT-files (private; :mod:`._formats` calls it).

A v4 file is a sequence of variables, each a header of five integers (``MOPT``, rows, columns, an
imaginary flag, the length of the name), the name, and the values column after column (real, then
imaginary). ``MOPT`` gives the byte order (``0`` little- or ``1`` big-endian IEEE, thousands digit),
the type of the values (tens digit: double, single, int32, int16, uint16, uint8) and the kind (ones
digit: ``0`` a matrix, ``1`` text, ``2`` sparse: rows ``(i, j, value)``, 1-based, the last
``(rows, columns, 0)``). scipy's reader allocated what a damaged header declared; here every size is
checked against the bytes left before anything is read. The messages name the byte where the
variable starts.
"""

from __future__ import annotations

import struct
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from ._errors import FileFormatError
from ._limits import MAX_ENTRIES, MAX_ROWS

_TYPES = {0: "f8", 1: "f4", 2: "i4", 3: "i2", 4: "u2", 5: "u1"}


def read(path: Path, wanted: list[str], pick) -> dict:
    """``{name: matrix}`` of the ``wanted`` variables (``pick(found, wanted)`` refuses missing ones)."""
    raw = path.read_bytes()
    found, twice, pos = {}, set(), 0
    while pos < len(raw):
        name, value, end = _variable(path, raw, pos)
        if name in found:
            twice.add(name)
        found[name] = value
        pos = end
    pick(found, wanted)
    for w in wanted:
        if w in twice:
            raise FileFormatError(path, f"holds two variables named {w!r}")
        if isinstance(found[w], str):
            raise FileFormatError(path, f"variable {w!r} is {found[w]}; expected a numeric matrix")
    return {w: found[w] for w in wanted}


def _variable(path: Path, raw: bytes, at: int):
    """``(name, value, next position)``; value is a message for what is not a numeric matrix."""
    def fail(what):
        raise FileFormatError(path, f"at byte {at}: {what}")

    if at + 20 > len(raw):
        fail(f"{len(raw) - at} byte(s) where a variable's 20-byte header should be: truncated or damaged")
    for endian in "<>":
        mopt, rows, cols, imag, namelen = struct.unpack(endian + "5i", raw[at:at + 20])
        if 0 <= mopt < 2000 and (mopt // 1000 == (0 if endian == "<" else 1)):
            break
    else:
        fail("not a MATLAB v4 variable header (its type code MOPT is not a little- or big-endian IEEE one)")
    if (mopt // 100) % 10 or (mopt // 10) % 10 not in _TYPES or mopt % 10 > 2 or imag not in (0, 1):
        fail(f"the type code MOPT = {mopt} or the imaginary flag {imag} is not a v4 one")
    if rows < 0 or cols < 0 or not 1 <= namelen <= 4096:
        fail(f"a variable of {rows} x {cols} with a name of {namelen} bytes")
    start = at + 20 + namelen
    dtype = np.dtype(endian + _TYPES[(mopt // 10) % 10])
    count = rows * cols
    size = count * dtype.itemsize * (2 if imag else 1)
    if count > MAX_ENTRIES or start + size > len(raw):
        fail(f"a variable of {rows} x {cols} values runs past the end of the file ({len(raw)} bytes): truncated "
             f"or damaged")
    name = raw[at + 20:start].rstrip(b"\0")
    try:
        name = name.decode("ascii")
    except UnicodeDecodeError:
        fail(f"the name {name[:40]!r} is not ASCII text")
    values = np.frombuffer(raw, dtype, count, start).astype(np.float64)
    if imag:
        values = values + 1j * np.frombuffer(raw, dtype, count, start + count * dtype.itemsize)
    values = values.reshape((rows, cols), order="F")
    kind = mopt % 10
    if kind == 1:
        return name, "MATLAB text", start + size
    if kind == 2:
        return name, _sparse(fail, name, values), start + size
    return name, values, start + size


def _sparse(fail, name: str, rows_ijv: np.ndarray):
    """A sparse matrix from its ``(i, j, value)`` rows, the last ``(rows, columns, 0)``."""
    if rows_ijv.shape[0] < 1 or rows_ijv.shape[1] not in (3, 4):
        fail(f"sparse variable {name!r} has shape {rows_ijv.shape}; expected rows of (i, j, value)")
    ij = rows_ijv[:, :2].real
    if not (np.isfinite(ij).all() and (ij == np.round(ij)).all()):
        fail(f"sparse variable {name!r} has indices that are not whole numbers")
    n, m = (int(x) for x in ij[-1])
    if not (0 <= n <= MAX_ROWS and 0 <= m <= MAX_ROWS):
        fail(f"sparse variable {name!r} declares {n} x {m}")
    i, j = ij[:-1, 0].astype(np.int64) - 1, ij[:-1, 1].astype(np.int64) - 1
    if ((i < 0) | (i >= n) | (j < 0) | (j >= m)).any():
        k = int(np.flatnonzero((i < 0) | (i >= n) | (j < 0) | (j >= m))[0])
        fail(f"sparse variable {name!r}: entry {k} at ({i[k] + 1}, {j[k] + 1}) is outside its {n} x {m}")
    v = rows_ijv[:-1, 2] if rows_ijv.shape[1] == 3 else rows_ijv[:-1, 2].real + 1j * rows_ijv[:-1, 3].real
    return sp.csc_matrix((v, (i, j)), shape=(n, m))
