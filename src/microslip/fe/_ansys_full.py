"""ANSYS ``.full`` files (the assembled matrices of a modal or harmonic solution) through ansys-mapdl-reader (private).

ansys-mapdl-reader (``pip install ansys-mapdl-reader``, the ``fe`` extra) reads the stiffness and mass
matrices, one triangle in the order of its sorted DOF table (node, DOF), with the constrained DOFs
left as empty rows; this module makes them whole, removes the constrained DOFs and labels each row
from the file's node/DOF table (ANSYS's DOF numbers 1..6: UX, UY, UZ, ROTX, ROTY, ROTZ). A damping
matrix, when the file holds one, is read by the same routine of the library.

The library reads records at offsets the file declares with compiled code, which trusts them: the
file's structure is walked here first (every record's length and trailer, the header's sizes, the
matrices' offsets on record boundaries, each matrix row's terms, the node and DOF tables' lengths), so
that a truncated or damaged file is refused by name, with the word offset of the bad record, before
the library reads it. Records compressed by ANSYS (``/FCOMP``) are walked but their contents are not
checked before the library reads them.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from ._errors import FileFormatError
from ._labelled import Labelled
from ._limits import MAX_ENTRIES, MAX_ROWS
from ._optional import require

#: ANSYS DOF numbers read (1..6), as components 0..5
_DOF_NAMES = {1: "UX", 2: "UY", 3: "UZ", 4: "ROTX", 5: "ROTY", 6: "ROTZ"}
#: positions in the full-file header record of what the walk checks (ANSYS fdfull.inc, as the library reads it)
_NEQN, _NUMDOF, _LUMPM, _KEYUNS, _NNODES = 1, 7, 10, 13, 32


def _records(path: Path, words: np.ndarray, end: int) -> dict:
    """``{offset: (length, compressed)}`` of every record from the file's start up to word ``end``."""
    out, pos = {}, 0
    while pos < end:
        if pos + 3 > words.size:
            raise FileFormatError(path, f"the record at word {pos} is cut by the end of the file (truncated)")
        n, flags = int(words[pos]), int(words[pos + 1])
        if n < 0 or pos + n + 3 > words.size:
            raise FileFormatError(path, f"the record at word {pos} declares {n} words; the file holds "
                                        f"{words.size - pos - 3} after it (truncated or damaged)")
        if int(words[pos + n + 2]) != n:
            raise FileFormatError(path, f"the record at word {pos} of {n} words ends with {int(words[pos + n + 2])} "
                                        f"instead of its length: damaged")
        out[pos] = (n, bool((flags >> 24) & 0b1100))
        pos += n + 3
    if pos != end:
        raise FileFormatError(path, f"the records run to word {pos}, past the end the header declares ({end})")
    return out


def _data(words, records, pos) -> np.ndarray:
    n, _ = records[pos]
    return words[pos + 2:pos + 2 + n]


def _walk(path: Path) -> dict:
    """Check the file's records and tables; the header as the library parses it."""
    from ansys.mapdl.reader.common import parse_header, two_ints_to_long
    from ansys.mapdl.reader.full import SYMBOLIC_FULL_HEADER_KEYS

    size = path.stat().st_size
    if size < 4 * 206 or size % 4:
        raise FileFormatError(path, f"{size} bytes: not an ANSYS binary file (whole 4-byte words, two header records)")
    words = np.fromfile(path, dtype="<i4")
    if words[0] != 100:
        swapped = words.byteswap()
        if swapped[0] != 100:
            raise FileFormatError(path, f"the first record declares {int(words[0])} words; an ANSYS binary file "
                                        f"starts with its 100-word standard header")
        words = swapped
    first = _records(path, words, 206)
    if first[103][0] < 40:
        raise FileFormatError(path, f"the full-file header record holds {first[103][0]} words; at least 40 expected")
    header = parse_header(_data(words, first, 103), SYMBOLIC_FULL_HEADER_KEYS)
    raw = _data(words, first, 103)
    neqn, numdof, nnodes = int(raw[_NEQN]), int(raw[_NUMDOF]), int(raw[_NNODES])
    if not 1 <= neqn <= MAX_ROWS or not 1 <= numdof <= 64 or not 1 <= nnodes <= MAX_ROWS:
        raise FileFormatError(path, f"the header declares {neqn} equations, {numdof} DOFs a node and {nnodes} nodes "
                                    f"(from 1 to {MAX_ROWS}, DOFs a node up to 64): damaged")
    if raw[_LUMPM]:
        raise FileFormatError(path, "holds a lumped mass matrix, which ansys-mapdl-reader does not read")
    if raw[_KEYUNS]:
        raise FileFormatError(path, "holds unsymmetric matrices; microslip reads symmetric ones")
    end = int(header["ptrEND"])
    if not 206 <= end <= words.size:
        raise FileFormatError(path, f"the header declares its end at word {end}; the file holds {words.size} words "
                                    f"(truncated or damaged)")
    records = _records(path, words, end)
    terms = {}
    for label, ptr, lo, hi in (("stiffness", "ptrSTF", "ntermKl", "ntermKh"), ("mass", "ptrMAS", "ntermMl", "ntermMh"),
                               ("damping", "ptrDMP", "ntermDl", "ntermDh")):
        nterm = int(two_ints_to_long(header[lo], header[hi]))
        if nterm == 0:
            continue
        terms[label] = nterm
        if not 0 < nterm <= MAX_ENTRIES:
            raise FileFormatError(path, f"the header declares {nterm} {label} terms (at most {MAX_ENTRIES:.0e})")
        _matrix_records(path, words, records, int(header[ptr]), neqn, nterm, label)
    if "stiffness" not in terms or "mass" not in terms:
        raise FileFormatError(path, f"holds no {'stiffness' if 'stiffness' not in terms else 'mass'} matrix (a .full "
                                    f"file of a modal or harmonic analysis holds both)")
    dofs = _table(path, words, records, 206, numdof, "DOF numbers")
    neqv = _table(path, words, records, 206 + records.get(206, (0,))[0] + 3, nnodes, "nodal equivalence table")
    ptr = int(header["ptrDOF"])
    per_node = _table(path, words, records, ptr, nnodes, "DOFs of each node")
    const = _table(path, words, records, ptr + records.get(ptr, (0,))[0] + 3, neqn, "constraint table")
    if per_node is not None and (per_node.min() < 0 or per_node.max() > numdof or int(per_node.sum()) != neqn):
        raise FileFormatError(path, f"the DOFs of each node (record at word {ptr}) must be from 0 to {numdof} and sum "
                                    f"to the {neqn} equations; they sum to {int(per_node.sum())}")
    if neqv is not None and (neqv.min() < 1 or np.unique(neqv).size != neqv.size):
        raise FileFormatError(path, "the nodal equivalence table must list distinct positive node numbers")
    if dofs is not None:
        bad = [int(d) for d in dofs if int(d) not in _DOF_NAMES]
        if bad:
            raise FileFormatError(path, f"the model has DOF number {bad[0]} (only displacements and rotations, ANSYS "
                                        f"DOFs 1..6 {', '.join(_DOF_NAMES.values())}, make a structural model here)")
    return {"neqn": neqn, "dofs": dofs, "terms": terms, "header": header, "const": const}


def _table(path, words, records, pos, n, what):
    """An integer table of ``n`` entries at record ``pos`` (None when compressed: the library checks it)."""
    if pos not in records:
        raise FileFormatError(path, f"the {what} should start a record at word {pos}: damaged offsets")
    length, packed = records[pos]
    if packed:
        return None
    if length != n:
        raise FileFormatError(path, f"the {what} (record at word {pos}) holds {length} entries; {n} expected")
    return _data(words, records, pos)


def _matrix_records(path, words, records, pos, neqn, nterm, label):
    """Each of the ``neqn`` rows of a matrix: a record of column numbers, then one of as many float64 values."""
    if pos not in records:
        raise FileFormatError(path, f"the {label} matrix should start a record at word {pos}: damaged offsets")
    total = 0
    for row in range(neqn):
        if pos not in records:
            raise FileFormatError(path, f"{label} matrix, row {row + 1}: no record at word {pos} (truncated)")
        n, packed = records[pos]
        if packed:
            return
        cols = _data(words, records, pos)
        if n and (cols.min() < 1 or cols.max() > neqn):
            raise FileFormatError(path, f"{label} matrix, row {row + 1} (record at word {pos}): column "
                                        f"{int(cols[(cols < 1) | (cols > neqn)][0])} is outside 1..{neqn}")
        pos += n + 3
        if pos not in records or records[pos][0] != 2 * n:
            got = records[pos][0] if pos in records else None
            raise FileFormatError(path, f"{label} matrix, row {row + 1}: the values' record at word {pos} holds "
                                        f"{got} words; {2 * n} expected for {n} terms")
        values = _data(words, records, pos).view("<f8") if words.dtype.byteorder != ">" else None
        if values is not None and not np.isfinite(values).all():
            raise FileFormatError(path, f"{label} matrix, row {row + 1}: a value is not finite")
        total += n
        pos += 2 * n + 3
    if total != nterm:
        raise FileFormatError(path, f"the {label} matrix's rows hold {total} terms; the header declares {nterm}")


def read(path: Path) -> dict:
    """``{"K": Labelled, "M": Labelled, "C": Labelled (when held)}`` of an ANSYS ``.full`` file.

    Raises
    ------
    FileFormatError
        A truncated, damaged or unsupported file (the message names the record).
    ImportError
        ansys-mapdl-reader is not installed (``pip install microslip[fe]``).
    """
    require("ansys.mapdl.reader", "Reading ANSYS .full files")
    from ansys.mapdl.reader import _binary_reader
    from ansys.mapdl.reader.full import FullFile

    checked = _walk(path)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        full = FullFile(str(path))
        dof_ref, k, m = full.load_km(sort=True)
        const_pairs = full.const
    dof_ref = np.asarray(dof_ref, dtype=np.int64)
    dofs = checked["dofs"] if checked["dofs"] is not None else np.arange(1, int(dof_ref[:, 1].max()) + 2)
    if dof_ref.shape != (checked["neqn"], 2) or dof_ref[:, 1].min() < 0 or dof_ref[:, 1].max() >= len(dofs):
        raise FileFormatError(path, "the node/DOF table does not match the equations and DOF numbers: damaged")
    constrained = {tuple(p) for p in np.asarray(const_pairs, dtype=np.int64).tolist()}
    free = np.array([tuple(p) not in constrained for p in dof_ref.tolist()])
    if not free.any():
        raise FileFormatError(path, "every DOF is constrained: no matrix left")
    out = {"K": k, "M": m}
    if "damping" in checked["terms"]:
        out["C"] = _damping(path, full, _binary_reader, checked)
    nodes, components = dof_ref[free, 0], np.asarray(dofs, dtype=np.int64)[dof_ref[free, 1]] - 1
    labelled = {}
    for role, A in out.items():
        A = sp.csr_matrix(A)
        whole = A + sp.triu(A, 1).T if sp.tril(A, -1).nnz == 0 else A
        labelled[role] = Labelled(sp.csr_matrix(whole[free][:, free]), nodes, components)
    return labelled


def _damping(path, full, binary_reader, checked):
    """The damping matrix in the library's order of the stiffness and mass (one triangle)."""
    h = checked["header"]
    with open(path, "rb") as f:
        from ansys.mapdl.reader.common import read_table

        read_table(f, skip=True)
        read_table(f, skip=True)
        read_table(f, skip=True)
        neqv = read_table(f, cython=True)
        f.seek(int(h["ptrDOF"]) * 4)
        ndof = read_table(f, cython=True)
        const = read_table(f, cython=True)
    rows, cols, data = binary_reader.read_array(str(path), int(h["ptrDMP"]), checked["terms"]["damping"],
                                                checked["neqn"], const)
    _, index, _, _ = binary_reader.sort_nodal_eqlv(checked["neqn"], neqv, ndof)
    keep = ~(np.isin(rows, np.nonzero(const < 0)[0]) | np.isin(cols, np.nonzero(const < 0)[0]))
    r, c = np.sort(np.vstack((index[rows[keep]], index[cols[keep]])), 0)
    return sp.csr_matrix((data[keep], (r, c)), shape=(checked["neqn"],) * 2)
