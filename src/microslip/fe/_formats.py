"""Reading named matrices from each file format, unchecked as matrices (private; :mod:`.files` checks them).

Every reader takes a path and the variable names wanted and returns ``{name: matrix}`` with
dense ``ndarray`` or ``scipy.sparse`` values; a wanted name the file does not hold raises a
ValueError listing the variables it does hold. A format that holds a single matrix (Matrix
Market, a ``scipy.sparse.save_npz`` file) gives it under one name asked for, never as several
matrices (:class:`OneMatrixFile`).

The files themselves are checked: a truncated, damaged or inconsistent file (sizes beyond what it
holds, sparse indices outside the matrix, a value that is not a number) raises
:class:`~._errors.FileFormatError` naming the file (and the line, for a text format), whatever
library reads it underneath; nothing is allocated from a size the file does not back.
"""

from __future__ import annotations

import struct
import zipfile
import zlib
from pathlib import Path
from typing import NamedTuple

import numpy as np
import scipy.io
import scipy.sparse as sp

from . import _abaqus, _ansys_full, _dmig, _harwell_boeing, _mat4, _mat5, _matrix_market, _op4
from ._errors import FileFormatError
from ..common.errors import MissingVariable, OneMatrixFile
from ._limits import MAX_ENTRIES, MAX_ROWS
from ._optional import require
from ._sparse import compressed, entries

#: format= name -> the format as the messages say it
FORMATS = {"matrix-market": "Matrix Market", "matlab": "MATLAB", "npz": "NumPy .npz", "op4": "Nastran OP4",
           "ansys-full": "ANSYS .full", "harwell-boeing": "Harwell-Boeing", "nastran-dmig": "Nastran DMIG",
           "abaqus": "Abaqus matrix output"}

#: suffix -> format= name (``.mtx`` is Matrix Market when the file starts with ``%``, Abaqus output otherwise)
SUFFIXES = {".mtx": "matrix-market", ".mm": "matrix-market", ".mat": "matlab", ".npz": "npz", ".op4": "op4",
            ".full": "ansys-full", ".rua": "harwell-boeing", ".rsa": "harwell-boeing", ".hb": "harwell-boeing",
            ".pch": "nastran-dmig", ".bdf": "nastran-dmig", ".dat": "nastran-dmig", ".nas": "nastran-dmig"}

#: keys of a file written by scipy.sparse.save_npz (compressed rows/columns, or coordinates)
_COMPRESSED = ("data", "indices", "indptr", "shape")
_COORDINATES = ("row", "col", "data", "shape")
_PARTS = set(_COMPRESSED + _COORDINATES + ("format",))

#: what the libraries underneath raise on a damaged file (each becomes a FileFormatError naming it)
_DAMAGE = (ValueError, TypeError, KeyError, IndexError, EOFError, OSError, OverflowError, RuntimeError,
           AssertionError, zipfile.BadZipFile, zlib.error, struct.error, scipy.io.matlab.MatReadError)
#: what passes through unchanged: not the file's fault, or already said
_PASSED = (FileFormatError, ImportError, FileNotFoundError, PermissionError, IsADirectoryError)


class _One(NamedTuple):
    """The matrix of a single-matrix file."""

    matrix: object


def _pick(path: Path, found: dict, wanted: list[str]) -> dict:
    missing = [w for w in wanted if w not in found]
    if missing:
        raise MissingVariable(path, missing, found)
    return {w: found[w] for w in wanted}


#: a name no variable has: asks a single-matrix file for its matrix
_ONLY = "\0"


def format_of(path: Path, format: str | None = None) -> str:
    """The ``format=`` name of ``path``: ``format`` when given (checked), else from the suffix.

    Raises
    ------
    ValueError
        An unknown ``format`` or suffix (the message lists those known).
    """
    if format is not None:
        if not isinstance(format, str) or format not in FORMATS:
            raise ValueError(f"format must be one of {', '.join(map(repr, FORMATS))}, got {format!r}")
        return format
    suffix = path.suffix.lower()
    if suffix not in SUFFIXES:
        kinds = ", ".join(f"{s} ({FORMATS[k]})" for s, k in SUFFIXES.items())
        raise ValueError(f"{path}: unknown matrix file suffix {path.suffix!r}; expected one of {kinds}, or say the "
                         f"format: format={'|'.join(FORMATS)}")
    if suffix == ".mtx" and path.is_file():  # Abaqus writes jobname_STIF1.mtx too: commas, no Matrix Market banner
        with open(path, "rb") as f:
            head = f.read(4096)
        first = next((line for line in head.split(b"\n") if line.strip() and not line.startswith(b"**")), b"")
        if not head.startswith(b"%") and (b"," in first or head.startswith(b"**")):
            return "abaqus"
    return SUFFIXES[suffix]


def only(path: Path, format: str | None = None) -> tuple[str | None, object]:
    """``(name, matrix)`` of a file holding one matrix (name None for a single-matrix format).

    Raises
    ------
    ValueError
        The file holds several variables (the message lists them) or none.
    """
    try:
        return None, read(path, [_ONLY], format)[_ONLY]
    except MissingVariable as err:
        if len(err.held) != 1:
            listed = ", ".join(err.held) if err.held else "no variables"
            raise ValueError(f"{path}: holds {listed}; name the variable to read") from None
        name = err.held[0]
    return name, read(path, [name], format)[name]


def read(path: Path, wanted: list[str], format: str | None = None) -> dict:
    """``{name: matrix}`` for the ``wanted`` names of the file at ``path`` (format from the suffix, or
    ``format``). A matrix whose rows the file labels by node and DOF comes as a :class:`._labelled.Labelled`.

    Raises
    ------
    FileFormatError
        The file is truncated, damaged or inconsistent (the message names it).
    MissingVariable
        A wanted name is not in the file.
    OneMatrixFile
        Several names wanted from a single-matrix file.
    """
    kind = format_of(path, format)
    if not path.is_file():
        raise FileNotFoundError(f"{path}: no such file")
    reader = {"matrix-market": _matrix_market_file, "matlab": _mat, "npz": _npz, "op4": _op4_file,
              "ansys-full": _ansys_full_file, "harwell-boeing": _harwell_boeing_file, "nastran-dmig": _dmig_file,
              "abaqus": _abaqus_file}
    try:
        found = reader[kind](path, wanted)
    except (*_PASSED, MissingVariable):
        raise
    except MemoryError:
        raise FileFormatError(path, "declares more data than the memory holds (a damaged size field?)") from None
    except _DAMAGE as err:
        raise FileFormatError(path, f"not a readable {FORMATS[kind]} file ({type(err).__name__}: {err})") from None
    if isinstance(found, _One):
        if len(wanted) != 1:
            raise OneMatrixFile(path, FORMATS[kind], wanted)
        return {wanted[0]: found.matrix}
    return found


def _shape(path: Path, label: str, value) -> tuple[int, int]:
    """A stored ``(rows, columns)``: two whole numbers from 0 to MAX_ROWS."""
    a = np.asarray(value)
    ok = a.shape == (2,) and a.dtype.kind in "iuf"
    if ok:
        f = a.astype(np.float64)
        ok = bool(np.all(np.isfinite(f)) and np.all(f == np.round(f)) and np.all(f >= 0) and np.all(f <= MAX_ROWS))
    if not ok:
        raise FileFormatError(path, f"{label}: shape {a.tolist() if a.size < 10 else a.shape} must be two whole "
                                    f"numbers of rows and columns from 0 to {MAX_ROWS}")
    return int(a[0]), int(a[1])


# -- Matrix Market -------------------------------------------------------------------------------
def _matrix_market_file(path: Path, wanted: list[str]) -> _One:
    return _One(_matrix_market.read(path))


# -- MATLAB ----------------------------------------------------------------------------------------
def _mat(path: Path, wanted: list[str]) -> dict:
    try:
        major, _ = scipy.io.matlab.matfile_version(str(path))
    except (ValueError, IndexError, scipy.io.matlab.MatReadError):  # no v4/v5 header: HDF5 (v7.3) or not MATLAB
        major = 2
    if major == 2:
        return _mat73(path, wanted)
    return (_mat5 if major == 1 else _mat4).read(path, wanted, lambda found, w: _pick(path, found, w))


def _mat73(path: Path, wanted: list[str]) -> dict:
    h5py = require("h5py", "Reading a MATLAB v7.3 (HDF5) file")
    if not h5py.is_hdf5(path):
        raise FileFormatError(path, "neither a MATLAB v5 nor a v7.3 (HDF5) file")
    try:
        f = h5py.File(path, "r")
    except OSError as err:
        raise FileFormatError(path, f"a damaged or truncated MATLAB v7.3 (HDF5) file ({err})") from None
    with f:
        present = [k for k in f.keys() if not k.startswith("#")]
        _pick(path, dict.fromkeys(present), wanted)
        return {w: _mat73_variable(path, w, f[w]) for w in wanted}


def _dataset(path: Path, label: str, node, limit: int = MAX_ENTRIES) -> np.ndarray:
    """A dataset's values, its declared size checked against ``limit`` and the bytes the file holds."""
    if not hasattr(node, "shape"):
        raise FileFormatError(path, f"{label} is a group; expected an array")
    n = entries(node.shape)
    if n > limit:
        raise FileFormatError(path, f"{label} declares {n} entries (shape {node.shape}), more than {limit:.0e} "
                                    f"(a damaged size?)")
    if node.chunks is None and node.compression is None and node.id.get_storage_size() < n * node.dtype.itemsize:
        raise FileFormatError(path, f"{label} declares {n} entries but the file stores "
                                    f"{node.id.get_storage_size()} bytes of them: truncated or damaged")
    return np.asarray(node)


def _mat73_variable(path: Path, name: str, node):
    """A MATLAB v7.3 variable: a dataset (stored transposed) or a sparse group ``data, ir, jc``."""
    kind = node.attrs.get("MATLAB_class", b"")
    kind = kind.decode() if isinstance(kind, bytes) else str(kind)
    if "MATLAB_sparse" in node.attrs:
        nrows = np.asarray(node.attrs["MATLAB_sparse"])
        if nrows.size != 1 or nrows.dtype.kind not in "iu" or not 0 <= int(nrows.ravel()[0]) <= MAX_ROWS:
            raise FileFormatError(path, f"{name}: the row count MATLAB_sparse = {nrows.tolist()} is not a whole "
                                        f"number from 0 to {MAX_ROWS}")
        if "jc" not in node:
            raise FileFormatError(path, f"{name}: a MATLAB sparse matrix without its column pointers jc")
        jc = _dataset(path, f"{name}/jc", node["jc"], MAX_ROWS + 1)
        ir = _dataset(path, f"{name}/ir", node["ir"]) if "ir" in node else np.zeros(0, np.int64)
        data = _dataset(path, f"{name}/data", node["data"]) if "data" in node else np.zeros(0)
        if data.dtype.names:
            raise FileFormatError(path, f"{name} is a complex sparse matrix; expected a real one")
        if kind == "logical" or data.dtype.kind not in "iuf":
            raise FileFormatError(path, f"{name} is a sparse {kind or data.dtype} matrix; expected real numbers")
        shape = (int(nrows.ravel()[0]), max(jc.size - 1, 0))
        compressed(path, name, data, ir, jc, shape, by_row=False, ordered=True, names=("data", "ir", "jc"))
        return sp.csc_matrix((data.astype(np.float64), ir.astype(np.int64), jc.astype(np.int64)), shape=shape).tocsr()
    if not hasattr(node, "shape"):
        raise FileFormatError(path, f"{name} is a MATLAB {kind or 'group'} (e.g. a struct or cell); expected a "
                                    f"numeric matrix")
    if node.attrs.get("MATLAB_empty", 0):
        raise FileFormatError(path, f"{name} is an empty MATLAB matrix")
    A = _dataset(path, name, node)
    if A.dtype.names:
        raise FileFormatError(path, f"{name} is a complex matrix; expected a real one")
    if kind in ("char", "logical", "cell", "struct") or A.dtype.kind not in "iuf":
        raise FileFormatError(path, f"{name} is a MATLAB {kind or A.dtype} array; expected a numeric matrix")
    return A.T  # MATLAB stores columns first, HDF5 reads rows first


# -- NumPy .npz ------------------------------------------------------------------------------------
class NpzArrays:
    """The arrays of an ``.npz`` file, each member's header checked before its data is read.

    Use as a context manager; :attr:`names` lists the arrays, :meth:`get` reads one. An array of
    Python objects (pickled data) is refused, never loaded; a header declaring more data than its
    member holds, or a member whose checksum fails, is a damaged file.

    Raises
    ------
    FileFormatError
        Not a zip file, a damaged member or header, or an array of objects.
    """

    def __init__(self, path):
        self.path = Path(path)
        try:
            self._zip = zipfile.ZipFile(self.path)
        except _PASSED:
            raise
        except _DAMAGE as err:
            raise FileFormatError(self.path, f"not a NumPy .npz (zip) file, or a truncated one ({err})") from None
        self.names, self.shapes = [], {}
        try:
            self._count()
            for info in self._zip.infolist():
                if info.filename.endswith(".npy"):
                    self.shapes[info.filename[:-4]] = self._check(info)
                    self.names.append(info.filename[:-4])
                else:  # opened all the same: zipfile checks its name against the member's own header
                    self._open(info).close()
        except BaseException:
            self._zip.close()
            raise

    def __enter__(self):
        return self

    def _count(self):
        """The members zipfile found must be all those the end record declares (it stops early, silently,
        where a damaged length makes it skip the rest of the directory)."""
        with open(self.path, "rb") as f:
            f.seek(max(f.seek(0, 2) - (1 << 16) - 22, 0))
            tail = f.read()
        end = tail.rfind(b"PK\x05\x06")
        declared = struct.unpack("<H", tail[end + 10:end + 12])[0] if 0 <= end <= len(tail) - 22 else None
        found = len(self._zip.infolist())
        if declared is not None and declared != 0xFFFF and declared != found:  # 0xFFFF: counted in a ZIP64 record
            raise FileFormatError(self.path, f"its zip directory lists {found} of the {declared} members its end "
                                             f"record declares: damaged")

    def _open(self, info):
        try:
            return self._zip.open(info)
        except _PASSED:
            raise
        except _DAMAGE as err:
            raise FileFormatError(self.path, f"member {info.filename!r} is damaged ({err})") from None

    def __exit__(self, *exc):
        self._zip.close()

    def _check(self, info: zipfile.ZipInfo):
        name = info.filename[:-4]
        fmt = np.lib.format
        try:
            with self._zip.open(info) as fp:
                version = fmt.read_magic(fp)
                if version not in ((1, 0), (2, 0)):
                    raise ValueError(f"NumPy format version {version} (1.0 or 2.0 expected)")
                read_header = fmt.read_array_header_1_0 if version == (1, 0) else fmt.read_array_header_2_0
                shape, _, dtype = read_header(fp)
                offset = fp.tell()
        except _PASSED:
            raise
        except _DAMAGE as err:
            raise FileFormatError(self.path, f"array {name!r} is damaged ({err})") from None
        if dtype.hasobject:
            raise FileFormatError(self.path, f"array {name!r} holds Python objects (pickled data), which are never "
                                             f"loaded; expected numbers")
        held = info.file_size - offset
        if entries(shape) * dtype.itemsize != held:
            raise FileFormatError(self.path, f"array {name!r}: its header declares shape {shape} of {dtype} "
                                             f"({entries(shape) * dtype.itemsize} bytes) but the file holds {held}: "
                                             f"damaged")
        return shape

    def get(self, name: str) -> np.ndarray:
        """The array ``name`` (its checksum verified)."""
        try:
            with self._zip.open(name + ".npy") as fp:
                a = np.lib.format.read_array(fp, allow_pickle=False)
                fp.read()  # to the end: the zip checksum is verified there
            return a
        except _PASSED:
            raise
        except _DAMAGE as err:
            raise FileFormatError(self.path, f"array {name!r} is damaged ({err})") from None


def _sparse(path: Path, label: str, get, parts: set) -> sp.csr_matrix:
    """A sparse matrix from the arrays that ``scipy.sparse.save_npz`` writes (``get(part)`` reads one)."""
    fmt = str(np.asarray(get("format")).astype(str)) if "format" in parts else ("coo" if "row" in parts else "csr")
    needed = _COORDINATES if fmt == "coo" else _COMPRESSED
    if fmt not in ("csr", "csc", "coo"):
        raise FileFormatError(path, f"{label} is stored as sparse format {fmt!r}; expected csr, csc or coo")
    if not set(needed) <= parts:
        raise FileFormatError(path, f"{label} in {fmt} format needs the arrays {', '.join(needed)}; "
                                    f"missing {', '.join(sorted(set(needed) - parts))}")
    shape = _shape(path, label, get("shape"))
    data = get("data")
    if data.ndim != 1 or data.dtype.kind not in "iufc":
        raise FileFormatError(path, f"{label}: data must be a 1-D array of numbers, got {data.dtype} of shape "
                                    f"{data.shape}")
    if fmt == "coo":
        row, col = get("row"), get("col")
        for name, idx, n in (("row", row, shape[0]), ("col", col, shape[1])):
            if idx.ndim != 1 or idx.dtype.kind not in "iu" or idx.size != data.size:
                raise FileFormatError(path, f"{label}: {name} must be a 1-D array of integers as long as data "
                                            f"({data.size}), got {idx.dtype} of shape {idx.shape}")
            bad = (idx.astype(np.int64) < 0) | (idx.astype(np.int64) >= n)
            if bad.any():
                k = int(np.flatnonzero(bad)[0])
                raise FileFormatError(path, f"{label}: {name}[{k}] = {idx[k]} is outside the {shape[0]} x {shape[1]} "
                                            f"matrix (0..{n - 1})")
        return sp.coo_matrix((data, (row.astype(np.int64), col.astype(np.int64))), shape=shape).tocsr()
    indices, indptr = get("indices"), get("indptr")
    compressed(path, label, data, indices, indptr, shape, by_row=fmt == "csr")
    cls = sp.csr_matrix if fmt == "csr" else sp.csc_matrix
    return cls((data, indices.astype(np.int64), indptr.astype(np.int64)), shape=shape).tocsr()


def _npz(path: Path, wanted: list[str]):
    """Dense arrays by name; sparse matrices as ``NAME_data, NAME_indices, NAME_indptr, NAME_shape``
    (``NAME_format`` csr/csc, default csr) or ``NAME_row, NAME_col, NAME_data, NAME_shape``; or a
    whole file written by ``scipy.sparse.save_npz`` (one matrix)."""
    with NpzArrays(path) as data:
        keys = set(data.names)
        if "shape" in keys:  # one matrix, as save_npz writes it
            return _One(_sparse(path, "the sparse matrix", data.get, keys & _PARTS))
        sparse = {k[:-len("_shape")] for k in keys if k.endswith("_shape") and len(k) > len("_shape")}
        parts = {p: {k[len(p) + 1:] for k in keys if k[len(p) + 1:] in _PARTS and k.startswith(p + "_")}
                 for p in sparse}
        dense = keys - {f"{p}_{part}" for p in sparse for part in parts[p]}
        _pick(path, dict.fromkeys(dense | sparse), wanted)
        out = {}
        for w in wanted:
            if w in sparse:
                out[w] = _sparse(path, w, lambda k, w=w: data.get(f"{w}_{k}"), parts[w])
            elif entries(data.shapes[w]) > MAX_ENTRIES:
                raise FileFormatError(path, f"{w} has shape {data.shapes[w]}: more than {MAX_ENTRIES:.0e} entries")
            else:
                out[w] = data.get(w)
        return out


# -- Nastran OP4 -----------------------------------------------------------------------------------
def _op4_file(path: Path, wanted: list[str]) -> dict:
    return _pick(path, _op4.read(path), wanted)


# -- the commercial codes' files -------------------------------------------------------------------
def _ansys_full_file(path: Path, wanted: list[str]) -> dict:
    return _pick(path, _ansys_full.read(path), wanted)


def _harwell_boeing_file(path: Path, wanted: list[str]) -> _One:
    return _One(_harwell_boeing.read(path))


def _abaqus_file(path: Path, wanted: list[str]) -> _One:
    return _One(_abaqus.read(path))


def _dmig_file(path: Path, wanted: list[str]) -> dict:
    found = _dmig.read(path, [w for w in wanted if w != _ONLY])
    held = found.pop("held")
    missing = [w for w in wanted if w not in found]
    if missing:
        raise MissingVariable(path, missing, held)
    return found
