"""A matrix whose rows carry their node and DOF, as the commercial codes write them (private).

Abaqus, Nastran DMIG and ANSYS ``.full`` files label every row by a node (grid) and a DOF number;
:mod:`.files` puts the matrices of a model on the union of their labels, in the order of node
then component.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import scipy.sparse as sp


class Labelled(NamedTuple):
    """A square matrix and the node and component (0..5: x, y, z, rx, ry, rz) of each row."""

    matrix: sp.csr_matrix
    nodes: np.ndarray
    components: np.ndarray


def key(nodes, components) -> np.ndarray:
    """One sortable integer per DOF: node then component (node ids up to 2**53 fit with 8 components)."""
    return np.asarray(nodes, dtype=np.int64) * 8 + np.asarray(components, dtype=np.int64)


def from_entries(rows: np.ndarray, cols: np.ndarray, values: np.ndarray) -> Labelled:
    """A labelled matrix from entries whose rows and columns are DOF keys (:func:`key`), sorted by key."""
    dofs = np.unique(np.concatenate([rows, cols]))
    n = dofs.size
    A = sp.csr_matrix((values, (np.searchsorted(dofs, rows), np.searchsorted(dofs, cols))), shape=(n, n))
    return Labelled(A, dofs // 8, dofs % 8)


def one_triangle_or_square(path, rows, cols, values, where, what: str = "entry"):
    """The entries of a symmetric matrix stored as one triangle, or as the whole square, made whole.

    ``rows``, ``cols`` (integer keys or indices) and ``values`` are the stored entries; ``where(k)``
    gives ``(text, line)`` naming entry ``k`` for a message. A pair stored twice is refused; entries
    on both sides of the diagonal make a square storage, in which every entry needs its mirror.

    Raises
    ------
    FileFormatError
        An entry stored twice, or a square storage with an entry whose mirror is missing.
    """
    from ._errors import FileFormatError

    rows, cols, values = (np.asarray(a) for a in (rows, cols, values))
    pairs = np.stack([rows, cols], axis=1)
    _, first, counts = np.unique(pairs, axis=0, return_index=True, return_counts=True)
    if (counts > 1).any():
        twice = set(map(tuple, pairs[first[counts > 1]].tolist()))
        k = next(k for k in range(rows.size) if (rows[k], cols[k]) in twice and k not in set(first.tolist()))
        text, line = where(k)
        raise FileFormatError(path, f"{text}: this {what} is stored twice", line)
    lower, upper = rows > cols, rows < cols
    if lower.any() and upper.any():  # the whole square: each entry with its mirror
        held = set(map(tuple, pairs.tolist()))
        stray = upper if lower.sum() >= upper.sum() else lower  # the fewer side holds the stray entry, if one
        off = np.flatnonzero(stray)
        missing = [k for k in off.tolist() if (cols[k], rows[k]) not in held]
        if not missing:
            off = np.flatnonzero(rows != cols)
            missing = [k for k in off.tolist() if (cols[k], rows[k]) not in held]
        if missing:
            text, line = where(missing[0])
            raise FileFormatError(path, f"{text}: entries on both sides of the diagonal (a whole symmetric matrix) "
                                        f"but this {what} has no mirror entry (a damaged file, or a triangle with a "
                                        f"stray entry)", line)
        return rows, cols, values
    off = rows != cols
    return (np.concatenate([rows, cols[off]]), np.concatenate([cols, rows[off]]),
            np.concatenate([values, values[off]]))
