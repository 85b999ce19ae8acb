"""Mass, stiffness and damping matrices from the files finite-element programs write.

Formats, chosen by the file's suffix:

======================  ===============================================================================
``.mtx``, ``.mm``       Matrix Market (``scipy.io.mmread``): one matrix per file, dense or coordinate
``.mat``                MATLAB v5 (``scipy.io.loadmat``) or v7.3 (HDF5, read with h5py): dense or sparse
                        variables; several per file
``.npz``                NumPy: dense 2-D arrays by name; a sparse matrix ``NAME`` as the arrays
                        ``NAME_data, NAME_indices, NAME_indptr, NAME_shape`` (``NAME_format`` ``"csr"``
                        or ``"csc"``, default ``"csr"``) or ``NAME_row, NAME_col, NAME_data,
                        NAME_shape``; or a whole file written by ``scipy.sparse.save_npz`` (one matrix)
``.op4``                Nastran OUTPUT4, text or binary (32-bit), dense or sparse, BIGMAT or not
``.full``               ANSYS full file (ansys-mapdl-reader): stiffness ``K``, mass ``M``, damping ``C``
                        when held, rows labelled by node and DOF, constrained DOFs removed
``.rua``, ``.rsa``,     Harwell-Boeing (ANSYS ``HBMAT``, ``Form = ASCII``): one real assembled matrix,
``.hb``                 unsymmetric or symmetric (one triangle)
``.pch``, ``.bdf``,     Nastran ``DMIG`` entries (pyNastran): matrices by name (``KAAX``, ``MAAX``, ...), rows
``.dat``, ``.nas``      labelled by grid and component
``.mtx`` (no ``%``      Abaqus ``*MATRIX OUTPUT`` (``FORMAT=MATRIX INPUT``: rows labelled by node and DOF;
banner)                 ``FORMAT=COORDINATE``: equation numbers): one matrix per file
======================  ===============================================================================

``format=`` names the format whatever the suffix (ANSYS writes ``HBMAT`` files as ``.MATRIX``):
``matrix-market``, ``matlab``, ``npz``, ``op4``, ``ansys-full``, ``harwell-boeing``, ``nastran-dmig``,
``abaqus``.

Where the file labels its rows by node and DOF (ANSYS ``.full``, Nastran ``DMIG``, Abaqus), the
matrices are put on the union of their DOFs, sorted by node then component, and that is the DOF
map (:class:`DofMap`); a ``dof_map`` given as well must name the same DOFs and sets their order.

A Matrix Market file, or a ``save_npz`` file, holds one matrix: it is read as the matrix its
role names (``M=``, ``K=``, ``C=``), never as the whole model. h5py (MATLAB v7.3), ansys-mapdl-reader
(ANSYS) and pyNastran (DMIG) are optional (``pip install microslip[fe]``); the other formats need only
NumPy and SciPy. Matrices come
back as ``scipy.sparse`` CSR when the file stores them sparse and as dense arrays otherwise, in
the file's units (the rest of microslip expects kg, N s/m, N/m).

The files are checked as they are read: a truncated, damaged or inconsistent file (a value that
is not a number, a line with a value missing, sparse indices outside the matrix, sizes the file
does not hold, a failed checksum) raises :class:`FileFormatError`, a ``ValueError`` naming the
file and, for a text format, the line. Nothing is allocated from a size the file does not back.
"""

from __future__ import annotations

from pathlib import Path
from typing import Mapping, NamedTuple

import numpy as np
import scipy.sparse as sp

from ..common import _checks
from . import _formats
from ._errors import FileFormatError
from ._formats import NpzArrays, OneMatrixFile
from ._labelled import Labelled, key
from ._limits import MAX_ROWS
from .dof_map import COMPONENTS, DofMap

__all__ = ["FEMatrices", "FileFormatError", "NpzArrays", "OneMatrixFile", "check_matrix", "read_matrices",
           "read_matrix"]

#: the matrices of a model and their meaning
ROLES = {"M": "mass", "K": "stiffness", "C": "damping"}

#: default relative symmetry tolerance: loose enough for matrices printed with 8 significant
#: digits, tight enough to refuse a non-symmetric (gyroscopic, half-assembled, mixed-up) matrix
SYMMETRY_TOLERANCE = 1e-6


class FEMatrices(NamedTuple):
    """Matrices of a finite-element model, as read by :func:`read_matrices`.

    Attributes
    ----------
    M, K : ndarray or scipy.sparse.csr_matrix, shape (ndof, ndof)
        Mass and stiffness, symmetric.
    C : ndarray, scipy.sparse.csr_matrix or None
        Viscous damping, symmetric, or ``None`` when none was read.
    dof_map : DofMap or None
        Node and component of each row, when given.
    """

    M: object
    K: object
    C: object
    dof_map: DofMap | None


def _where(path: Path, name: str) -> str:
    return f"{path}: {name}"


def check_matrix(A, where: str, *, symmetry_tolerance: float = SYMMETRY_TOLERANCE):
    """``A`` as a square, finite, symmetric float matrix (CSR or dense), symmetrised.

    Parameters
    ----------
    A : array_like or scipy.sparse matrix
        The matrix read from a file.
    where : str
        ``"file: variable"``, the start of every message.
    symmetry_tolerance : float
        Largest accepted ``max|A - A^T| / max|A|``. ``A`` is returned as
        ``(A + A^T) / 2``, so no entry moves by more than this fraction of
        the largest entry.

    Raises
    ------
    ValueError
        ``A`` is not 2-D, not square, empty, larger than 1e7 rows, complex
        or not numeric, holds a non-finite entry (its row and column are
        named) or is not symmetric within the tolerance.
    """
    if sp.issparse(A):
        A = sp.csr_matrix(A)
    else:
        A = np.asarray(A)
        if A.ndim != 2:
            raise ValueError(f"{where} must be a 2-D matrix, got an array of shape {A.shape}")
    if A.dtype.kind == "c":
        raise ValueError(f"{where} is complex; expected a real matrix")
    if A.dtype.kind not in "iuf":
        raise ValueError(f"{where} holds {A.dtype} values; expected real numbers")
    if A.shape[0] != A.shape[1]:
        raise ValueError(f"{where} must be square, got shape {A.shape}")
    if A.shape[0] == 0:
        raise ValueError(f"{where} is an empty 0 x 0 matrix; expected at least one row and column")
    if A.shape[0] > MAX_ROWS:
        raise ValueError(f"{where} has {A.shape[0]} rows; at most {MAX_ROWS} are accepted")
    A = A.astype(np.float64)
    values = A.data if sp.issparse(A) else A
    if not np.isfinite(values).all():
        if sp.issparse(A):
            coo = A.tocoo()
            k = int(np.flatnonzero(~np.isfinite(coo.data))[0])
            i, j, v = int(coo.row[k]), int(coo.col[k]), float(coo.data[k])
        else:
            i, j = (int(x) for x in np.argwhere(~np.isfinite(A))[0])
            v = float(A[i, j])
        raise ValueError(f"{where} must be finite; it holds {v!r} at row {i}, column {j}")
    scale = abs(A).max() if A.size else 0.0
    asym = abs(A - A.T).max() if A.size else 0.0
    if asym > symmetry_tolerance * scale:
        raise ValueError(f"{where} must be symmetric: max|A - A^T| = {asym:.3g} exceeds {symmetry_tolerance:g} "
                         f"x max|A| = {symmetry_tolerance * scale:.3g}")
    return (A + A.T) / 2 if asym else A


def _names(names) -> dict:
    if names is None:
        return {}
    if not isinstance(names, Mapping):
        raise TypeError(f"names must be a mapping such as {{'M': 'MGG', 'K': 'KGG'}}, got {names!r}")
    unknown = [k for k in names if k not in ROLES]
    if unknown:
        raise ValueError(f"names: unknown key(s) {', '.join(map(repr, unknown))}; the keys are "
                         f"{', '.join(ROLES)} ({', '.join(ROLES.values())})")
    for k, v in names.items():
        if not isinstance(v, str) or not v:
            raise TypeError(f"names[{k!r}] must be a non-empty variable name, got {v!r}")
    return dict(names)


def _path(name: str, value) -> Path:
    if not isinstance(value, (str, Path)):
        raise TypeError(f"{name} must be a file path, got {type(value).__name__}")
    return Path(value)


def read_matrix(path, name: str | None = None, *, format: str | None = None,
                symmetry_tolerance: float = SYMMETRY_TOLERANCE):
    """One checked matrix from a file.

    Parameters
    ----------
    path : str or Path
        A matrix file of a format in the module's table.
    name : str, optional
        The variable to read from a file holding several; ignored for a
        single-matrix file. Default: the file's only variable.
    format : str, optional
        The file's format (``"harwell-boeing"``, ``"abaqus"``, ...; see the
        module) when its suffix does not say it.
    symmetry_tolerance : float
        See :func:`check_matrix`.

    Returns
    -------
    ndarray or scipy.sparse.csr_matrix, shape (n, n)
        Square, finite and symmetric.

    Raises
    ------
    FileFormatError
        A truncated, damaged or inconsistent file (a ``ValueError``).
    ValueError
        Unknown suffix, a missing variable (the message lists those the
        file holds), or a matrix that fails :func:`check_matrix`.
    TypeError
        ``path`` is not a file path or ``name`` not a string.
    ImportError
        A v7.3 ``.mat`` without h5py, an ANSYS file without ansys-mapdl-reader
        or a DMIG file without pyNastran.
    """
    path = _path("path", path)
    if name is not None:
        name = _checks.text("name", name)
    tol = _checks.positive_scalar("symmetry_tolerance", symmetry_tolerance)
    format = _formats.format_of(path, format)
    if name is None:
        name, A = _formats.only(path, format)
    else:
        try:
            A = _formats.read(path, [name], format)[name]
        except _formats.MissingVariable as err:
            raise _formats.MissingVariable(path, err.missing, err.held, advice="choose one with name=...") from None
    if isinstance(A, Labelled):
        A = A.matrix
    return check_matrix(A, _where(path, name) if name else str(path), symmetry_tolerance=tol)


def read_matrices(path=None, *, M=None, K=None, C=None, dof_map=None, names: Mapping | None = None,
                  format: str | None = None, symmetry_tolerance: float = SYMMETRY_TOLERANCE) -> FEMatrices:
    """Mass, stiffness and (optionally) damping matrices of a finite-element model.

    Either one file holding the variables ``M``, ``K`` and optionally ``C``
    (``path``; a ``.mat``, ``.npz`` or ``.op4`` file), or one file per
    matrix (``M=``, ``K=``, ``C=``; any format). A file that holds a single
    matrix (Matrix Market, ``scipy.sparse.save_npz``) says nothing of which
    matrix it is: it is read only as one of ``M=``, ``K=``, ``C=``.

    Parameters
    ----------
    path : str or Path, optional
        The file holding every matrix.
    M, K, C : str or Path, optional
        One file per matrix (instead of ``path``); ``C`` may be omitted.
    dof_map : str, Path or DofMap, optional
        Node and component of each row: a :class:`DofMap` or a CSV file
        with ``node,component`` columns (:meth:`DofMap.from_csv`). A file
        that labels its rows (ANSYS ``.full``, Nastran DMIG, Abaqus) gives
        the map itself; a map given as well must name the same DOFs, and
        the matrices then follow its order.
    names : mapping, optional
        Variable names in the file(s) when they are not ``M``, ``K``,
        ``C``, e.g. ``{"M": "MGG", "K": "KGG"}``. With one file, ``C`` is
        read when the file holds it (or when ``names`` names it, then it
        must be there). With one file per matrix, a file holding a single
        variable is read whatever its name.
    symmetry_tolerance : float
        Largest accepted ``max|A - A^T| / max|A|`` of each matrix (default
        1e-6); the matrices are returned symmetrised, ``(A + A^T) / 2``.
    format : str, optional
        The format of every file when the suffixes do not say it (see the
        module): ``"matrix-market"``, ``"matlab"``, ``"npz"``, ``"op4"``,
        ``"ansys-full"``, ``"harwell-boeing"``, ``"nastran-dmig"``,
        ``"abaqus"``.

    Returns
    -------
    FEMatrices
        ``(M, K, C, dof_map)``: CSR when the file stores a matrix sparse,
        dense arrays otherwise; ``C`` and ``dof_map`` may be None.

    Raises
    ------
    FileFormatError
        A truncated, damaged or inconsistent file (a ``ValueError``): the
        message names the file and, for a text format, the line.
    OneMatrixFile
        ``path`` holds a single matrix (a ``ValueError``).
    ValueError
        Both or neither of ``path`` and ``M``/``K`` given, an unknown
        suffix, a missing variable (the message lists the variables in the
        file), a matrix that is not square, finite or symmetric, matrices
        of different sizes, or a DOF map of another length. Every message
        names the file and the variable.
    ImportError
        A v7.3 ``.mat`` without h5py.

    Examples
    --------
    >>> from microslip.fe import read_matrices
    >>> M, K, C, dofs = read_matrices("blade.mat", dof_map="blade_dofs.csv")  # doctest: +SKIP
    >>> M, K, C, dofs = read_matrices(M="m.mtx", K="k.mtx")  # doctest: +SKIP
    >>> M, K, C, dofs = read_matrices("rotor.full")  # doctest: +SKIP
    >>> M, K, C, dofs = read_matrices("sector.pch", names={"M": "MAAX", "K": "KAAX"})  # doctest: +SKIP
    """
    chosen = _names(names)
    tol = _checks.positive_scalar("symmetry_tolerance", symmetry_tolerance)
    per_matrix = {r: v for r, v in (("M", M), ("K", K), ("C", C)) if v is not None}
    if path is not None and per_matrix:
        raise ValueError("give either one file (path) or one file per matrix (M=, K=, C=), not both")
    if path is not None:
        path = _path("path", path)
        wanted = {r: chosen.get(r, r) for r in ROLES}
        found = _read_with_optional_c(path, wanted, "C" in chosen, _formats.format_of(path, format))
        where = {r: _where(path, wanted[r]) for r in found}
    else:
        if "M" not in per_matrix or "K" not in per_matrix:
            raise ValueError("give the matrices' file: one file holding M and K (path), or M= and K= "
                             "(one file each)")
        found, where = {}, {}
        for role, value in per_matrix.items():
            p = _path(role, value)
            var = chosen.get(role, role)
            found[role] = _one(p, var, role in chosen, _formats.format_of(p, format))
            where[role] = _where(p, var)
    labelled = [r for r, A in found.items() if isinstance(A, Labelled)]
    for role, A in found.items():  # the labels' checks need square, finite matrices
        if isinstance(A, Labelled):
            found[role] = A._replace(matrix=check_matrix(A.matrix, where[role], symmetry_tolerance=tol))
    labels = None
    if labelled:
        found, labels = _on_common_dofs(found, where, dof_map)
    matrices = {r: check_matrix(A, where[r], symmetry_tolerance=tol) for r, A in found.items()}
    n = matrices["M"].shape[0]
    for role, A in matrices.items():
        if A.shape[0] != n:
            raise ValueError(f"{where[role]} is {A.shape[0]} x {A.shape[0]} but {where['M']} is {n} x {n}: "
                             f"M, K and C must have the same size")
    dofs = labels if labels is not None else _dof_map(dof_map, n)
    return FEMatrices(matrices["M"], matrices["K"], matrices.get("C"), dofs)


def _on_common_dofs(found: dict, where: dict, dof_map) -> tuple[dict, DofMap]:
    """Matrices whose files label their rows, put on the union of their DOFs (or ``dof_map``'s order)."""
    plain = [r for r, A in found.items() if not isinstance(A, Labelled)]
    if plain:
        named = next(r for r, A in found.items() if isinstance(A, Labelled))
        raise ValueError(f"{where[named]} labels its rows by node and DOF but {where[plain[0]]} does not: the "
                         f"matrices cannot be matched row by row (give files of the same kind)")
    keys = {r: key(A.nodes, A.components) for r, A in found.items()}
    union = np.unique(np.concatenate(list(keys.values())))
    if dof_map is not None:
        given = _dof_map(dof_map, union.size)
        order = key(given.nodes, [COMPONENTS.index(c) for c in given.components])
        extra = np.setdiff1d(union, order)
        if extra.size:
            raise ValueError(f"dof_map lacks DOF {extra[0] // 8}:{COMPONENTS[extra[0] % 8]}, which the matrix files "
                             f"label: the map given must name the files' DOFs")
        labels = given
    else:
        order = union
        labels = DofMap(union // 8, [COMPONENTS[c] for c in (union % 8).tolist()])
    sort = np.argsort(order, kind="stable")
    out = {}
    for role, A in found.items():
        at = sort[np.searchsorted(order[sort], keys[role])]  # each labelled row's place in `order`
        coo = sp.coo_matrix(A.matrix)
        out[role] = sp.csr_matrix((coo.data, (at[coo.row], at[coo.col])), shape=(order.size, order.size))
    return out, labels


def _read_with_optional_c(path: Path, wanted: dict, c_required: bool, format: str) -> dict:
    """``{role: matrix}`` from one file: M and K must be there, C when it is (or when required)."""
    try:
        raw = _formats.read(path, list(wanted.values()), format)
        return {r: raw[v] for r, v in wanted.items()}
    except _formats.MissingVariable as err:
        if c_required or wanted["C"] not in err.missing:
            raise
    raw = _formats.read(path, [wanted["M"], wanted["K"]], format)
    return {"M": raw[wanted["M"]], "K": raw[wanted["K"]]}


def _one(path: Path, var: str, named: bool, format: str):
    """The matrix ``var`` of a per-matrix file, or its only variable when ``var`` was not chosen."""
    try:
        return _formats.read(path, [var], format)[var]
    except _formats.MissingVariable as err:
        if named or len(err.held) != 1:
            raise
    return _formats.only(path, format)[1]


def _dof_map(value, n: int) -> DofMap | None:
    if value is None:
        return None
    where = "dof_map"
    if isinstance(value, (str, Path)):
        where = f"dof_map {str(value)!r}"
        value = DofMap.from_csv(value)
    elif not isinstance(value, DofMap):
        raise TypeError(f"dof_map must be a DofMap or the path of a node,component CSV file, got "
                        f"{type(value).__name__}")
    if len(value) != n:
        raise ValueError(f"{where} has {len(value)} rows but the matrices have {n}: one row per DOF, in the "
                         f"order of the matrix rows")
    return value
