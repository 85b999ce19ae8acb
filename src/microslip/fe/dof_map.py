"""Which node and which displacement component each row of a finite-element matrix belongs to.

A degree of freedom is named ``"node:component"``, e.g. ``"1204:x"``: ``node`` is a
node (grid) id (an integer from 0 to 2**53), ``component`` one of ``x, y, z, rx, ry, rz``
(translations in m, rotations in rad), or its Nastran number ``1..6``
(``"1204:1"`` is ``"1204:x"``).
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from ..common import _checks
from ..common._io import atomic_write
from ._errors import FileFormatError

#: displacement components in Nastran's order (component ``k`` is ``COMPONENTS[k - 1]``)
COMPONENTS = ("x", "y", "z", "rx", "ry", "rz")

#: the largest node id: 2**53, so that an id read as a float (MATLAB stores numbers as doubles) is exact
MAX_NODE = 2 ** 53


def _component(value, where: str | None) -> str:
    """A component letter from a letter or a Nastran number 1..6 (``where`` starts the message, if given)."""
    text = str(value).strip().lower()
    if text in COMPONENTS:
        return text
    if text.isdigit() and 1 <= int(text) <= 6:
        return COMPONENTS[int(text) - 1]
    where = f"{where}: " if where else ""
    raise ValueError(f"{where}component {value!r} is not one of {', '.join(COMPONENTS)} "
                     f"(or their numbers 1..6)")


def _node(value, where: str | None) -> int:
    """A node id: an integer in ``0..MAX_NODE`` (also from text such as ``"1204"``)."""
    if isinstance(value, np.floating):
        value = float(value)  # shown as 1.5, not np.float64(1.5)
    where = f"{where}: " if where else ""
    if isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{where}node id must be an integer, got {value!r}")
    if isinstance(value, (int, np.integer)):
        node = int(value)
    elif isinstance(value, str) and value.strip().lstrip("+").isdigit():
        node = int(value)
    elif isinstance(value, (float, np.floating)) and float(value).is_integer():
        node = int(value)
    else:
        raise ValueError(f"{where}node id must be a non-negative integer, got {value!r}")
    if node < 0:
        raise ValueError(f"{where}node id must be a non-negative integer, got {node}")
    if node > MAX_NODE:
        raise ValueError(f"{where}node id must be at most 2**53 = {MAX_NODE}, got {value!r}")
    return node


def _sequence(name: str, value) -> list:
    if isinstance(value, (str, bytes)) or np.ndim(value) != 1:
        raise TypeError(f"{name} must be a 1-D sequence, one entry per matrix row, got {value!r:.80}")
    return list(value)


def split_name(name) -> tuple[int, str]:
    """``(node, component)`` of a DOF name such as ``"1204:x"`` or ``"1204:1"``.

    Raises
    ------
    TypeError
        ``name`` is not a string.
    ValueError
        ``name`` is not ``"node:component"`` with a non-negative integer node
        and a component ``x, y, z, rx, ry, rz`` or ``1..6``.
    """
    if not isinstance(name, str):
        raise TypeError(f"a DOF name must be a string such as '1204:x', got {name!r}")
    node, sep, comp = name.partition(":")
    if not sep or not node.strip() or not comp.strip():
        raise ValueError(f"DOF name {name!r} must be 'node:component', e.g. '1204:x' or '1204:1'")
    return _node(node.strip(), f"DOF name {name!r}"), _component(comp, f"DOF name {name!r}")


class DofMap:
    """The node id and component of every row of a finite-element matrix.

    Parameters
    ----------
    nodes : array_like of int, shape (ndof,)
        Node (grid) id of each row, integers from 0 to 2**53.
    components : sequence, shape (ndof,)
        Component of each row: ``"x", "y", "z", "rx", "ry", "rz"`` or
        Nastran's numbers ``1..6`` (stored as letters).

    Raises
    ------
    ValueError
        Lengths differ, an id or component is not valid, or two rows name
        the same node and component.

    Examples
    --------
    >>> from microslip.fe import DofMap
    >>> d = DofMap([1204, 1204, 1300], ["x", "y", 1])
    >>> d.index("1300:x"), d.names
    (2, ['1204:x', '1204:y', '1300:x'])
    """

    def __init__(self, nodes, components):
        nodes, components = _sequence("nodes", nodes), _sequence("components", components)
        if len(nodes) != len(components):
            raise ValueError(f"nodes and components must have the same length, got {len(nodes)} and "
                             f"{len(components)}")
        self._nodes = np.array([_node(n, f"nodes, row {i}") for i, n in enumerate(nodes)], dtype=np.int64)
        self._components = tuple(_component(c, f"components, row {i}") for i, c in enumerate(components))
        self._rows: dict[tuple[int, str], int] = {}
        for i, key in enumerate(zip(self._nodes.tolist(), self._components)):
            if key in self._rows:
                raise ValueError(f"rows {self._rows[key]} and {i} both name DOF '{key[0]}:{key[1]}': "
                                 f"each node and component must appear once")
            self._rows[key] = i

    # -- construction -------------------------------------------------------------------------
    @classmethod
    def from_names(cls, names) -> DofMap:
        """A map from DOF names, one per row (e.g. ``["1204:x", "1204:y"]``)."""
        pairs = []
        for i, name in enumerate(_sequence("names", names)):
            try:
                pairs.append(split_name(name))
            except (TypeError, ValueError) as err:
                raise type(err)(f"names, row {i}: {err}") from None
        return cls([p[0] for p in pairs], [p[1] for p in pairs])

    @classmethod
    def from_csv(cls, path) -> DofMap:
        """Read a CSV file with a header naming the columns ``node`` and ``component``.

        One data row per matrix row, in the order of the matrix rows, each
        with as many cells as the header; other columns are ignored, lines
        starting with ``#`` are comments, the last line ends with a line
        break. A UTF-8 byte-order mark is accepted.

        Raises
        ------
        FileNotFoundError
            No such file.
        FileFormatError
            (a ValueError naming the file and the line) No header with
            ``node`` and ``component``, a column named twice, a row with
            more or fewer cells than the header, an invalid node id or
            component, duplicate rows, no data row, a last line without its
            line break (a truncated file), or a file that is not UTF-8.
        TypeError
            ``path`` is not a file name.
        """
        path = _checks.file_path("path", path)
        try:
            with open(path, newline="", encoding="utf-8-sig") as fh:
                every = list(enumerate(fh, start=1))
            lines = [(no, line) for no, line in every if line.strip() and not line.lstrip().startswith("#")]
        except UnicodeDecodeError as err:
            raise FileFormatError(path, f"not a UTF-8 text file ({err.reason} at byte {err.start}); save the DOF "
                                        f"map as UTF-8 CSV") from None
        except FileNotFoundError:  # named as the matrix files are, not by the operating system's errno
            raise FileNotFoundError(f"{path}: no such file") from None
        if not lines:
            raise FileFormatError(path, "no header; the first line must name the columns 'node,component'")
        if not every[-1][1].endswith(("\n", "\r")):  # a cut inside the last row could leave a shorter node id
            raise FileFormatError(path, "the file does not end with a line break: it may be truncated (if its last "
                                        "row is complete, end it with a line break)", every[-1][0])
        try:
            rows = list(csv.reader(line for _, line in lines))
        except csv.Error as err:
            raise FileFormatError(path, f"not a CSV file ({err})") from None
        header = [h.strip().lower() for h in rows[0]]
        missing = [c for c in ("node", "component") if c not in header]
        if missing:
            raise FileFormatError(path, f"must be a header naming the columns 'node' and 'component' (missing "
                                        f"{', '.join(missing)}), got {rows[0]}", lines[0][0])
        twice = sorted({h for h in header if h and header.count(h) > 1})
        if twice:
            raise FileFormatError(path, f"the header names the column(s) {', '.join(map(repr, twice))} more than "
                                        f"once, got {rows[0]}", lines[0][0])
        ci, cc = header.index("node"), header.index("component")
        nodes, comps = [], []
        for (no, _), cells in zip(lines[1:], rows[1:]):
            if len(cells) != len(header):
                raise FileFormatError(path, f"has {len(cells)} cell(s), the header has {len(header)}", no)
            try:
                nodes.append(_node(cells[ci].strip(), None))
                comps.append(_component(cells[cc], None))
            except (TypeError, ValueError) as err:
                raise FileFormatError(path, str(err), no) from None
        if not nodes:
            raise FileFormatError(path, "no data row after the header")
        try:
            return cls(nodes, comps)
        except ValueError as err:
            raise FileFormatError(path, f"{err} (data rows counted from 0)") from None

    def to_csv(self, path) -> Path:
        """Write the map as a ``node,component`` CSV (readable by :meth:`from_csv`), atomically."""
        path = _checks.file_path("path", path)
        body = "".join(f"{n},{c}\n" for n, c in zip(self._nodes.tolist(), self._components))
        return atomic_write(path, "node,component\n" + body)

    # -- look-ups -------------------------------------------------------------------------------
    def __len__(self) -> int:
        return self._nodes.size

    def __repr__(self) -> str:
        return f"DofMap({len(self)} rows, {np.unique(self._nodes).size} nodes)"

    def __eq__(self, other) -> bool:
        if not isinstance(other, DofMap):
            return NotImplemented
        return np.array_equal(self._nodes, other._nodes) and self._components == other._components

    __hash__ = None

    @property
    def nodes(self) -> np.ndarray:
        """Node id of each row, shape ``(ndof,)`` (a copy)."""
        return self._nodes.copy()

    @property
    def components(self) -> tuple[str, ...]:
        """Component letter of each row."""
        return self._components

    @property
    def names(self) -> list[str]:
        """``"node:component"`` of each row."""
        return [f"{n}:{c}" for n, c in zip(self._nodes.tolist(), self._components)]

    def index(self, name) -> int:
        """The row of a DOF given as ``"node:component"`` (or a pair ``(node, component)``).

        Raises
        ------
        ValueError
            The name is malformed, the node has no rows (the message lists
            the nearest node ids present), or the node has no row for that
            component (the message lists the components it has).
        """
        if isinstance(name, tuple) and len(name) == 2:
            node, comp = _node(name[0], f"DOF {name!r}"), _component(name[1], f"DOF {name!r}")
        else:
            node, comp = split_name(name)
        row = self._rows.get((node, comp))
        if row is not None:
            return row
        have = [c for c in COMPONENTS if (node, c) in self._rows]
        if have:
            raise ValueError(f"DOF {name!r}: node {node} has no component {comp!r}; it has "
                             f"{', '.join(f'{node}:{c}' for c in have)}")
        ids = np.unique(self._nodes)
        close = ids[np.argsort(np.abs(ids - node), kind="stable")[:5]]
        raise ValueError(f"DOF {name!r}: node {node} is not in the DOF map ({ids.size} nodes, ids "
                         f"{ids[0]}..{ids[-1]}); the nearest ids are {', '.join(map(str, sorted(close)))}")

    def rows(self, node) -> dict[str, int]:
        """``{component: row}`` of one node (empty when the node has no rows)."""
        node = _node(node, "node")
        return {c: self._rows[(node, c)] for c in COMPONENTS if (node, c) in self._rows}
