"""A strict reader of MATLAB v5 MAT-files, compressed (v7) or not (private; :mod:`._formats` calls it).

scipy's reader trusts the byte counts and the dimensions inside a variable: a flipped bit there
crashed the interpreter. Here every element is checked before it is used: the byte count of each
variable against the file, of each part (flags, dimensions, name, values, sparse indices) against
its variable, the count of values against the dimensions, a compressed variable's stream to its
end (zlib checks it there). The messages name the byte where the variable starts.

Only what a finite-element matrix can be is read: numeric arrays (double, single, integers) of two
dimensions, real or complex, and sparse matrices; text, cells, structures, logical arrays and N-D
arrays are named and refused.
"""

from __future__ import annotations

import struct
import zlib
from pathlib import Path
from typing import NamedTuple

import numpy as np
import scipy.sparse as sp

from ._errors import FileFormatError
from ._limits import MAX_ENTRIES, MAX_ROWS
from ._sparse import compressed

#: data types of the elements (miINT8 ... miUINT64) -> NumPy codes
_NUMBERS = {1: "i1", 2: "u1", 3: "i2", 4: "u2", 5: "i4", 6: "u4", 7: "f4", 9: "f8", 12: "i8", 13: "u8"}
_MATRIX, _COMPRESSED = 14, 15
_INTEGERS = (1, 2, 3, 4, 5, 6, 12, 13)
#: array classes: 6-15 numeric (double, single, int8 ... uint64), 5 sparse, the others refused by name
_NUMERIC = range(6, 16)
_SPARSE = 5
_CLASSES = {1: "cell", 2: "struct", 3: "object", 4: "char", 16: "function handle", 17: "opaque"}
#: the largest decompressed variable: a dense complex matrix of MAX_ENTRIES entries and its name
_LARGEST = 16 * MAX_ENTRIES + (1 << 20)


class _Variable(NamedTuple):
    name: str
    at: int  # byte of the file where its element starts
    body: bytes  # the miMATRIX element's data (decompressed)
    parts: int  # offset in body after the flags, dimensions and name
    cls: int
    flags: int
    nzmax: int
    dims: tuple


def read(path: Path, wanted: list[str], pick) -> dict:
    """``{name: matrix}`` of the ``wanted`` variables (``pick(found, wanted)`` refuses missing ones)."""
    raw = path.read_bytes()
    return _File(path, raw).read(wanted, pick)


class _File:
    def __init__(self, path: Path, raw: bytes):
        self.path, self.raw = path, raw
        if len(raw) < 128 or raw[126:128] not in (b"IM", b"MI"):
            raise FileFormatError(path, "not a MATLAB v5 file: no 128-byte header ending with 'IM' or 'MI'")
        self.e = "<" if raw[126:128] == b"IM" else ">"

    def fail(self, at: int, what: str):
        raise FileFormatError(self.path, f"at byte {at}: {what}")

    def read(self, wanted, pick) -> dict:
        found, twice = {}, set()
        for v in self._variables():
            if v.name in found:
                twice.add(v.name)
            found[v.name] = v
        pick(found, wanted)
        for w in wanted:
            if w in twice:
                raise FileFormatError(self.path, f"holds two variables named {w!r}")
        return {w: self._value(found[w]) for w in wanted}

    def _variables(self):
        raw, pos = self.raw, 128
        while pos < len(raw):
            if pos + 8 > len(raw):
                self.fail(pos, f"{len(raw) - pos} byte(s) after the last variable: truncated or damaged")
            kind, n = struct.unpack(self.e + "II", raw[pos:pos + 8])
            if kind not in (_MATRIX, _COMPRESSED) or n == 0:
                self.fail(pos, f"an element of type {kind} and {n} bytes is not a MATLAB variable: damaged")
            if pos + 8 + n > len(raw):
                self.fail(pos, f"a variable of {n} bytes runs past the end of the file ({len(raw)} bytes): truncated")
            body = raw[pos + 8:pos + 8 + n]
            if kind == _COMPRESSED:
                body = self._inflate(pos, body)
            yield self._header(pos, body)
            pos += 8 + n

    def _inflate(self, at: int, data: bytes) -> bytes:
        d = zlib.decompressobj()
        try:
            inner = d.decompress(data, _LARGEST)
        except zlib.error as err:
            self.fail(at, f"a compressed variable is damaged ({err})")
        if d.unconsumed_tail:
            self.fail(at, f"a compressed variable expands beyond {_LARGEST} bytes")
        if not d.eof:
            self.fail(at, "a compressed variable ends before its stream does: truncated or damaged")
        if len(inner) < 8:
            self.fail(at, "a compressed variable holds no element")
        kind, n = struct.unpack(self.e + "II", inner[:8])
        if kind != _MATRIX or 8 + n > len(inner):
            self.fail(at, f"a compressed variable holds an element of type {kind} and {n} bytes in {len(inner) - 8}")
        return inner[8:8 + n]

    def _part(self, at: int, body: bytes, o: int, what: str, who: str = "a variable") -> tuple[int, bytes, int]:
        """``(type, data, next offset)`` of the element at ``o`` of ``body`` (normal or small format)."""
        if o + 8 > len(body):
            self.fail(at, f"{who} ends before its {what}")
        w0, w1 = struct.unpack(self.e + "II", body[o:o + 8])
        if w0 >> 16:  # small element: type and byte count in one word, up to 4 bytes of data
            kind, n = w0 & 0xFFFF, w0 >> 16
            if n > 4:
                self.fail(at, f"{who}: its {what} declare {n} bytes in a 4-byte small element")
            return kind, body[o + 4:o + 4 + n], o + 8
        kind, n = w0, w1
        if o + 8 + n > len(body):
            self.fail(at, f"{who}: its {what} of {n} bytes run past the variable ({len(body)} bytes)")
        return kind, body[o + 8:o + 8 + n], o + 8 + n + (-n % 8)

    def _numbers(self, at: int, body: bytes, o: int, what: str, who: str = "a variable") -> tuple[np.ndarray, int]:
        kind, data, o = self._part(at, body, o, what, who)
        if kind not in _NUMBERS:
            self.fail(at, f"{who}: its {what} are of element type {kind}, not numbers")
        dtype = np.dtype(self.e + _NUMBERS[kind])
        if len(data) % dtype.itemsize:
            self.fail(at, f"{who}: its {what}: {len(data)} bytes are not whole {dtype.itemsize}-byte numbers")
        return np.frombuffer(data, dtype), o

    def _header(self, at: int, body: bytes) -> _Variable:
        kind, flags, o = self._part(at, body, 0, "array flags")
        if kind != 6 or len(flags) != 8:  # miUINT32, two words
            self.fail(at, f"a variable's array flags are an element of type {kind} and {len(flags)} bytes (type 6, "
                          f"8 bytes expected)")
        word, nzmax = struct.unpack(self.e + "II", flags)
        dims, o = self._numbers(at, body, o, "dimensions")
        if dims.size < 2 or dims.dtype.kind not in "iu" or (dims < 0).any():
            self.fail(at, f"a variable's dimensions {dims.tolist()} are not two or more counts")
        kind, name, o = self._part(at, body, o, "name")
        if kind not in (1, 2, 16):
            self.fail(at, f"a variable's name is an element of type {kind}, not text")
        try:
            text = name.decode("ascii")
        except UnicodeDecodeError:
            self.fail(at, f"a variable's name {name[:40]!r} is not ASCII text")
        return _Variable(text, at, body, o, word & 0xFF, word, nzmax, tuple(int(d) for d in dims))

    def _value(self, v: _Variable):
        at, body, o, dims = v.at, v.body, v.parts, v.dims
        where = f"variable {v.name!r}"
        if v.cls in _CLASSES or v.cls not in _NUMERIC and v.cls != _SPARSE:
            self.fail(at, f"{where} is a MATLAB {_CLASSES.get(v.cls, f'class {v.cls}')} array; expected a numeric "
                          f"matrix")
        if v.flags & 0x200:
            self.fail(at, f"{where} is a logical array; expected a numeric matrix")
        if len(dims) != 2:
            self.fail(at, f"{where} is a {len(dims)}-D array of shape {dims}; expected a matrix")
        complex_ = bool(v.flags & 0x800)
        if v.cls == _SPARSE:
            return self._sparse(v, where, complex_)
        count = dims[0] * dims[1]
        if count > MAX_ENTRIES:
            self.fail(at, f"{where} declares {dims[0]} x {dims[1]}: more than {MAX_ENTRIES:.0e} entries")
        real, o = self._numbers(at, body, o, "values", where)
        if real.size != count:
            self.fail(at, f"{where} declares {dims[0]} x {dims[1]} but holds {real.size} values")
        A = real.astype(np.float64)
        if complex_:
            imag, o = self._numbers(at, body, o, "imaginary parts", where)
            if imag.size != count:
                self.fail(at, f"{where} holds {imag.size} imaginary parts for {count} values")
            A = A + 1j * imag
        return A.reshape(dims, order="F")

    def _sparse(self, v: _Variable, where: str, complex_: bool):
        at, body, o, (nrows, ncols) = v.at, v.body, v.parts, v.dims
        if max(nrows, ncols) > MAX_ROWS:
            self.fail(at, f"{where} declares {nrows} x {ncols}: more than {MAX_ROWS} rows or columns")
        ir, o = self._numbers(at, body, o, "row indices", where)
        jc, o = self._numbers(at, body, o, "column pointers", where)
        pr, o = self._numbers(at, body, o, "values", where)
        for name, a in (("row indices", ir), ("column pointers", jc)):
            if a.dtype.kind not in "iu":
                self.fail(at, f"{where}: its {name} are {a.dtype}, not integers")
        nnz = int(jc[-1]) if jc.size else 0
        if not 0 <= nnz <= min(ir.size, pr.size):
            self.fail(at, f"{where}: its column pointers end at {nnz} but it holds {ir.size} row indices and "
                          f"{pr.size} values")
        data = pr[:nnz].astype(np.float64)
        if complex_:
            pi, o = self._numbers(at, body, o, "imaginary parts", where)
            if pi.size < nnz:
                self.fail(at, f"{where} holds {pi.size} imaginary parts for {nnz} values")
            data = data + 1j * pi[:nnz]
        try:
            compressed(self.path, v.name, data, ir[:nnz], jc, (nrows, ncols), by_row=False,
                       names=("values", "row indices", "column pointers"))
        except FileFormatError as err:
            self.fail(at, err.what)
        return sp.csc_matrix((data, ir[:nnz].astype(np.int64), jc.astype(np.int64)), shape=(nrows, ncols))
