"""A strict reader of the matrices Abaqus writes with ``*MATRIX GENERATE`` / ``*MATRIX OUTPUT`` (private).

The layouts are those of the Abaqus Keywords Reference (``*MATRIX OUTPUT``, ``*MATRIX INPUT``) and
the Analysis User's Guide ("Generating matrices"); files ``jobname_STIF1.mtx``, ``_MASS1``, ``_DMPV1``:

* ``FORMAT=MATRIX INPUT`` (the default): one entry per line, ``row node, row DOF, column node,
  column DOF, value`` -- the format ``*MATRIX INPUT`` reads back. The rows are labelled by node and
  DOF (1..6: x, y, z, rx, ry, rz); the matrix's rows are its DOFs sorted by node then DOF.
* ``FORMAT=COORDINATE``: ``row, column, value`` with 1-based equation numbers and no labels; the
  size is the largest equation number written.

A symmetric matrix is written as one triangle or as the whole square (then each entry must have
its mirror). Lines starting with ``**`` are comments. Every line is checked before a number is taken
from it: a value that is not a number, a line with a value missing or an extra one, an entry written
twice, a DOF that is not a displacement or a rotation, or a file cut in its last line is refused with
the line.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from ._errors import FileFormatError
from ._labelled import Labelled, from_entries, key, one_triangle_or_square
from ._limits import MAX_ENTRIES, MAX_ROWS

_INT = re.compile(r"[+-]?[0-9]+")
_REAL = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eEdD][+-]?[0-9]+)?")
#: the largest node id (DofMap's limit)
_MAX_NODE = 2 ** 53


def _text(path: Path) -> list[str]:
    raw = path.read_bytes()
    try:
        text = raw.decode("ascii")
    except UnicodeDecodeError as err:
        raise FileFormatError(path, f"byte {err.start} is not text (ASCII): a damaged file, or not Abaqus matrix "
                                    f"output", raw.count(b"\n", 0, err.start) + 1) from None
    if not text.strip():
        raise FileFormatError(path, "the file is empty: no matrix entries")
    if not text.endswith("\n"):
        raise FileFormatError(path, "the file does not end with a line break: it may be truncated (if its last line "
                                    "is complete, end it with a line break)", text.count("\n") + 1)
    return text.replace("\r\n", "\n").split("\n")[:-1]


def read(path: Path) -> Labelled | sp.csr_matrix:
    """The matrix of an Abaqus matrix file: labelled (``MATRIX INPUT``) or plain CSR (``COORDINATE``).

    Raises
    ------
    FileFormatError
        A damaged or inconsistent file; the message names the line.
    """
    lines = _text(path)
    data = [(no, line) for no, line in enumerate(lines, start=1) if line.strip() and not line.startswith("**")]
    if not data:
        raise FileFormatError(path, "holds only comments: no matrix entries")
    if len(data) > MAX_ENTRIES:
        raise FileFormatError(path, f"holds {len(data)} entries, more than {MAX_ENTRIES:.0e}")
    width = len(data[0][1].split(","))
    if width not in (3, 5):
        raise FileFormatError(path, f"not Abaqus matrix output: a line must be 'row node, row DOF, column node, "
                                    f"column DOF, value' (FORMAT=MATRIX INPUT) or 'row, column, value' "
                                    f"(FORMAT=COORDINATE), got {data[0][1][:80]!r}", data[0][0])
    spelled = ("row node, row DOF, column node, column DOF, value" if width == 5 else "row, column, value")
    ints = np.zeros((len(data), width - 1), dtype=np.int64)
    values = np.zeros(len(data))
    for k, (no, line) in enumerate(data):
        items = [s.strip() for s in line.split(",")]
        if len(items) != width:
            raise FileFormatError(path, f"expected '{spelled}' ({width} items separated by commas), got {len(items)}: "
                                        f"{line[:80]!r}", no)
        for j, (item, name) in enumerate(zip(items[:-1], spelled.split(", "))):
            if not _INT.fullmatch(item):
                raise FileFormatError(path, f"the {name} {item[:40]!r} is not an integer: {line[:80]!r}", no)
            ints[k, j] = v = int(item) if len(item) < 20 else -1
            if name.endswith("DOF"):
                if not 1 <= v <= 6:
                    raise FileFormatError(path, f"the {name} {item[:40]!r} is not a displacement or rotation DOF "
                                                f"(1..6 for x, y, z, rx, ry, rz): {line[:80]!r}", no)
            elif name.endswith("node") and not 0 <= v <= _MAX_NODE:
                raise FileFormatError(path, f"the {name} {item[:40]!r} is not a node number from 0 to 2**53", no)
            elif not name.endswith(("node", "DOF")) and not 1 <= v <= MAX_ROWS:
                raise FileFormatError(path, f"the {name} {item[:40]!r} is not an equation number from 1 to "
                                            f"{MAX_ROWS}", no)
        if not _REAL.fullmatch(items[-1]):
            raise FileFormatError(path, f"the value {items[-1][:40]!r} is not a number: {line[:80]!r}", no)
        values[k] = v = float(items[-1].replace("d", "e").replace("D", "e"))
        if not np.isfinite(v):
            raise FileFormatError(path, f"the value {items[-1][:40]!r} is not finite", no)
    if width == 5:
        rows, cols = key(ints[:, 0], ints[:, 1] - 1), key(ints[:, 2], ints[:, 3] - 1)
        what = "node and DOF pair"
    else:
        rows, cols = ints[:, 0] - 1, ints[:, 1] - 1
        what = "row and column"
    rows, cols, values = one_triangle_or_square(path, rows, cols, values, lambda k: (data[k][1][:80], data[k][0]),
                                                what)
    if width == 5:
        return from_entries(rows, cols, values)
    n = int(max(rows.max(), cols.max())) + 1
    return sp.csr_matrix((values, (rows, cols)), shape=(n, n))
