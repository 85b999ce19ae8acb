"""Reading named matrices from each file format, unchecked (private; :mod:`.files` checks them).

Every reader takes a path and the variable names wanted and returns ``{name: matrix}`` with
dense ``ndarray`` or ``scipy.sparse`` values; a wanted name the file does not hold raises a
ValueError listing the variables it does hold. A format that holds a single matrix (Matrix
Market, a ``scipy.sparse.save_npz`` file) returns it under every name asked for.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import scipy.io
import scipy.sparse as sp

from ._optional import require

#: suffix -> format name, as the messages say it
SUFFIXES = {".mtx": "Matrix Market", ".mm": "Matrix Market", ".mat": "MATLAB", ".npz": "NumPy .npz",
            ".op4": "Nastran OP4"}

#: keys of a file written by scipy.sparse.save_npz (compressed rows/columns, or coordinates)
_COMPRESSED = ("data", "indices", "indptr", "shape")
_COORDINATES = ("row", "col", "data", "shape")
_PARTS = set(_COMPRESSED + _COORDINATES + ("format",))


class MissingVariable(ValueError):
    """A file lacks variables that were asked for; ``missing`` and ``held`` list the names.

    ``advice`` ends the message: how the caller chooses other variables.
    """

    def __init__(self, path: Path, missing: list[str], held,
                 advice: str = "choose others with names={'M': ..., 'K': ...}"):
        self.path, self.missing, self.held = path, list(missing), sorted(held)
        listed = ", ".join(self.held) if self.held else "no variables"
        super().__init__(f"{path}: no variable {', '.join(repr(m) for m in missing)}; the file holds {listed} "
                         f"({advice})")


def _pick(path: Path, found: dict, wanted: list[str]) -> dict:
    missing = [w for w in wanted if w not in found]
    if missing:
        raise MissingVariable(path, missing, found)
    return {w: found[w] for w in wanted}


#: a name no variable has: asks a single-matrix file for its matrix
_ONLY = "\0"


def only(path: Path) -> tuple[str | None, object]:
    """``(name, matrix)`` of a file holding one matrix (name None for a single-matrix format).

    Raises
    ------
    ValueError
        The file holds several variables (the message lists them) or none.
    """
    try:
        return None, read(path, [_ONLY])[_ONLY]
    except MissingVariable as err:
        if len(err.held) != 1:
            listed = ", ".join(err.held) if err.held else "no variables"
            raise ValueError(f"{path}: holds {listed}; name the variable to read") from None
        name = err.held[0]
    return name, read(path, [name])[name]


def read(path: Path, wanted: list[str]) -> dict:
    """``{name: matrix}`` for the ``wanted`` names of the file at ``path`` (format from the suffix)."""
    suffix = path.suffix.lower()
    if suffix not in SUFFIXES:
        kinds = ", ".join(f"{s} ({k})" for s, k in SUFFIXES.items())
        raise ValueError(f"{path}: unknown matrix file suffix {path.suffix!r}; expected one of {kinds}")
    if not path.is_file():
        raise FileNotFoundError(f"{path}: no such file")
    return {".mtx": _matrix_market, ".mm": _matrix_market, ".mat": _mat, ".npz": _npz, ".op4": _op4}[suffix](
        path, wanted)


# -- Matrix Market -------------------------------------------------------------------------------
def _matrix_market(path: Path, wanted: list[str]) -> dict:
    try:
        A = scipy.io.mmread(path)
    except (ValueError, TypeError, IndexError) as err:
        raise ValueError(f"{path}: not a readable Matrix Market file ({err})") from None
    A = sp.csr_matrix(A) if sp.issparse(A) else np.asarray(A)
    return {w: A for w in wanted}


# -- MATLAB ----------------------------------------------------------------------------------------
def _mat(path: Path, wanted: list[str]) -> dict:
    try:
        major, _ = scipy.io.matlab.matfile_version(str(path))
    except (ValueError, IndexError, scipy.io.matlab.MatReadError):  # no v4/v5 header: HDF5 (v7.3) or not MATLAB
        major = 2
    if major == 2:
        return _mat73(path, wanted)
    present = [name for name, _, _ in scipy.io.whosmat(str(path))]
    _pick(path, dict.fromkeys(present), wanted)
    data = scipy.io.loadmat(str(path), variable_names=wanted)
    return {w: data[w] for w in wanted}


def _mat73(path: Path, wanted: list[str]) -> dict:
    h5py = require("h5py", "Reading a MATLAB v7.3 (HDF5) file")
    if not h5py.is_hdf5(path):
        raise ValueError(f"{path}: neither a MATLAB v5 nor a v7.3 (HDF5) file")
    with h5py.File(path, "r") as f:
        present = [k for k in f.keys() if not k.startswith("#")]
        _pick(path, dict.fromkeys(present), wanted)
        return {w: _mat73_variable(path, w, f[w]) for w in wanted}


def _mat73_variable(path: Path, name: str, node):
    """A MATLAB v7.3 variable: a dataset (stored transposed) or a sparse group ``data, ir, jc``."""
    kind = node.attrs.get("MATLAB_class", b"")
    kind = kind.decode() if isinstance(kind, bytes) else str(kind)
    if "MATLAB_sparse" in node.attrs:
        nrows = int(node.attrs["MATLAB_sparse"])
        jc = np.asarray(node["jc"], dtype=np.int64)
        ir = np.asarray(node["ir"], dtype=np.int64) if "ir" in node else np.zeros(0, np.int64)
        data = np.asarray(node["data"]) if "data" in node else np.zeros(0)
        if data.dtype.names:
            raise ValueError(f"{path}: {name} is a complex sparse matrix; expected a real one")
        if kind == "logical" or data.dtype.kind not in "iuf":
            raise ValueError(f"{path}: {name} is a sparse {kind or data.dtype} matrix; expected real numbers")
        return sp.csc_matrix((data.astype(np.float64), ir, jc), shape=(nrows, jc.size - 1)).tocsr()
    if not hasattr(node, "shape"):
        raise ValueError(f"{path}: {name} is a MATLAB {kind or 'group'} (e.g. a struct or cell); expected a "
                         f"numeric matrix")
    A = np.asarray(node)
    if A.dtype.names:
        raise ValueError(f"{path}: {name} is a complex matrix; expected a real one")
    if kind in ("char", "logical", "cell", "struct") or A.dtype.kind not in "iuf":
        raise ValueError(f"{path}: {name} is a MATLAB {kind or A.dtype} array; expected a numeric matrix")
    return A.T  # MATLAB stores columns first, HDF5 reads rows first


# -- NumPy .npz ------------------------------------------------------------------------------------
def _sparse(path: Path, label: str, get, parts: set) -> sp.csr_matrix:
    """A sparse matrix from the arrays that ``scipy.sparse.save_npz`` writes (``get(part)`` reads one)."""
    shape = tuple(int(n) for n in get("shape"))
    fmt = str(np.asarray(get("format")).astype(str)) if "format" in parts else ("coo" if "row" in parts else "csr")
    needed = _COORDINATES if fmt == "coo" else _COMPRESSED
    if fmt not in ("csr", "csc", "coo"):
        raise ValueError(f"{path}: {label} is stored as sparse format {fmt!r}; expected csr, csc or coo")
    if not set(needed) <= parts:
        raise ValueError(f"{path}: {label} in {fmt} format needs the arrays {', '.join(needed)}; "
                         f"missing {', '.join(sorted(set(needed) - parts))}")
    try:
        if fmt == "coo":
            return sp.coo_matrix((get("data"), (get("row"), get("col"))), shape=shape).tocsr()
        cls = sp.csr_matrix if fmt == "csr" else sp.csc_matrix
        A = cls((get("data"), get("indices"), get("indptr")), shape=shape)
        A.check_format(full_check=True)  # indices within the shape, pointers ascending
        return A.tocsr()
    except ValueError as err:
        raise ValueError(f"{path}: {label} is not a consistent {fmt} matrix ({err})") from None


def _npz(path: Path, wanted: list[str]) -> dict:
    """Dense arrays by name; sparse matrices as ``NAME_data, NAME_indices, NAME_indptr, NAME_shape``
    (``NAME_format`` csr/csc, default csr) or ``NAME_row, NAME_col, NAME_data, NAME_shape``; or a
    whole file written by ``scipy.sparse.save_npz`` (one matrix)."""
    with np.load(path, allow_pickle=False) as data:
        keys = set(data.files)
        if "shape" in keys:  # one matrix, as save_npz writes it
            A = _sparse(path, "the sparse matrix", lambda k: data[k], keys & _PARTS)
            return {w: A for w in wanted}
        sparse = {k[:-len("_shape")] for k in keys if k.endswith("_shape") and len(k) > len("_shape")}
        parts = {p: {k[len(p) + 1:] for k in keys if k[len(p) + 1:] in _PARTS and k.startswith(p + "_")}
                 for p in sparse}
        dense = keys - {f"{p}_{part}" for p in sparse for part in parts[p]}
        _pick(path, dict.fromkeys(dense | sparse), wanted)
        return {w: _sparse(path, w, lambda k, w=w: data[f"{w}_{k}"], parts[w]) if w in sparse
                else np.asarray(data[w]) for w in wanted}


# -- Nastran OP4 -----------------------------------------------------------------------------------
def _op4(path: Path, wanted: list[str]) -> dict:
    op4 = require("pyNastran.op4.op4", "Reading a Nastran OP4 file")
    try:
        found = {k.strip(): v for k, v in op4.read_op4(str(path), matrix_names=wanted, debug=None).items()}
        if any(w not in found for w in wanted):
            found = {k.strip(): v for k, v in op4.read_op4(str(path), debug=None).items()}
    except (ValueError, TypeError, IndexError, AssertionError, OSError) as err:
        raise ValueError(f"{path}: not a readable Nastran OP4 file ({type(err).__name__}: {err})") from None
    out = _pick(path, found, wanted)
    return {w: (sp.csr_matrix(m) if sp.issparse(m) else np.asarray(m)) for w, (_form, m) in out.items()}
