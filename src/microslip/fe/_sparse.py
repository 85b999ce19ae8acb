"""Checks of the arrays that make a sparse matrix, before scipy builds it (private).

scipy trusts the indices it is given: an index outside the matrix was dropped, or crashed the
interpreter when the matrix was converted. Every reader of a sparse format checks its arrays here.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ._errors import FileFormatError


def entries(shape) -> int:
    """The number of entries of an array of ``shape`` (a Python int: no overflow)."""
    return math.prod(int(n) for n in shape)


def compressed(path: Path, label: str, data, indices, indptr, shape: tuple[int, int], *, by_row: bool,
               ordered: bool = False, names=("data", "indices", "indptr")) -> None:
    """Check the arrays of a compressed sparse matrix before scipy builds it (scipy trusts its indices).

    ``by_row``: CSR (``indptr`` over rows) or CSC; ``ordered``: the indices of each row (column)
    must be strictly increasing (MATLAB's rule). ``names`` are the arrays as the file calls them.

    Raises
    ------
    FileFormatError
        Non-integer indices, lengths that disagree, pointers not starting at 0 or decreasing,
        indices outside the matrix or (``ordered``) repeated or out of order.
    """
    nd, ni, np_ = names
    major, minor = (shape[0], shape[1]) if by_row else (shape[1], shape[0])
    what_major, what_minor = ("row", "column") if by_row else ("column", "row")
    data, indices, indptr = np.asarray(data), np.asarray(indices), np.asarray(indptr)

    def fail(what):
        raise FileFormatError(path, f"{label}: {what}")

    for name, a in ((ni, indices), (np_, indptr)):
        if a.ndim != 1 or a.dtype.kind not in "iu":
            fail(f"{name} must be a 1-D array of integers, got {a.dtype} of shape {a.shape}")
    if data.ndim != 1:
        fail(f"{nd} must be a 1-D array, got shape {data.shape}")
    if indptr.size != major + 1:
        fail(f"{np_} has {indptr.size} entries; a matrix of {major} {what_major}s needs {major + 1}")
    ptr = indptr.astype(np.int64)  # a uint64 beyond 2**63 becomes negative: refused below
    if ptr[0] != 0 or (np.diff(ptr) < 0).any():
        k = 0 if ptr[0] != 0 else int(np.flatnonzero(np.diff(ptr) < 0)[0]) + 1
        fail(f"{np_}[{k}] = {ptr[k]}: the pointers must start at 0 and never decrease")
    if not ptr[-1] == indices.size == data.size:
        fail(f"{np_} ends at {ptr[-1]} but {ni} has {indices.size} entries and {nd} {data.size}: they must agree")
    idx = indices.astype(np.int64)
    out = (idx < 0) | (idx >= minor)
    if out.any():
        k = int(np.flatnonzero(out)[0])
        fail(f"{ni}[{k}] = {indices[k]} is not a {what_minor} of the {shape[0]} x {shape[1]} matrix "
             f"(0..{minor - 1})")
    if ordered and idx.size > 1:
        rising = np.diff(idx) > 0
        rising[ptr[1:-1][(ptr[1:-1] > 0) & (ptr[1:-1] < idx.size)] - 1] = True  # a new row (column) may start lower
        if not rising.all():
            k = int(np.flatnonzero(~rising)[0]) + 1
            fail(f"{ni}[{k}] = {idx[k]} repeats or precedes the {what_minor} before it in its {what_major}: "
                 f"the indices of each {what_major} must increase")
