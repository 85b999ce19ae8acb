"""The frames a cyclic sector's DOFs are given in: the turn from one sector to the next, the vectors it turns.

A sector of a disk of ``N`` sectors is given in one of two frames
(:class:`~.cyclic.CyclicStructure`'s ``frame``):

* ``"cylindrical"``: every DOF in a frame that turns with the sector, as the
  nodal cylindrical frames ``(r, theta, z)`` of ANSYS ``CECYC``/``CPCYC`` and
  Nastran ``CYAX`` are: the right boundary's DOFs equal the next sector's left
  ones without a rotation.
* ``"cartesian"``: every DOF in the global Cartesian frame of this sector, as a
  sector exported without cyclic coordinates is: the right boundary is the
  left one turned by ``2 pi / N`` about the axis, so each boundary node's
  translation (or rotation) ``(x, y(, z))`` is turned by that rotation ``R``,
  ``u_right = R u_left`` in the sector's own coordinates.

Here: the rotation (Rodrigues' formula), a boundary given as DOFs or as one
tuple per node, the vectors the rotation acts on (``(dofs, components)``,
components 0, 1, 2 for x, y, z; none for a DOF that does not turn), and the
check that the right boundary's nodes are the left ones turned.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ...common import _checks
from .structure import dof_indices

#: the frames a sector's DOFs may be given in (the first is the default: today's, boundaries already matching)
FRAMES = ("cylindrical", "cartesian")
#: a right boundary node may lie this far from its left node turned, relative to the largest boundary radius
GEOMETRY_TOLERANCE = 1e-6
#: the largest coordinate (m) of a node or of the axis' point: their squares stay finite
MAX_COORDINATE = 1e100
#: an entry of the rotation below this couples no components (cos(pi / 2) is 6e-17)
_ZERO = 1e-12
_LETTERS = "xyz"


def rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    """The rotation matrix (3, 3) by ``angle`` (rad) about the unit vector ``axis`` (right hand)."""
    a = np.asarray(axis, dtype=float)
    c, s = np.cos(angle), np.sin(angle)
    cross = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    return c * np.eye(3) + s * cross + (1.0 - c) * np.outer(a, a)


def unit_axis(axis) -> np.ndarray:
    """``axis`` checked (3 numbers, not zero) and scaled to unit length."""
    a = _checks.real_array("axis", axis, ndim=1)
    if a.size != 3:
        raise ValueError(f"axis must be the 3 components of the axis' direction, e.g. [0, 0, 1], got {a.tolist()}")
    big = float(np.max(np.abs(a)))
    if not big > 0:
        raise ValueError(f"axis must not be zero, got {a.tolist()}")
    a = a / big  # no overflow or underflow in the norm
    return a / np.linalg.norm(a)


def axis_point(point) -> np.ndarray:
    """``point`` checked: 2 or 3 coordinates (m, z = 0 for 2), below :data:`MAX_COORDINATE`; origin for None."""
    if point is None:
        return np.zeros(3)
    p = _checks.real_array("point", point, ndim=1)
    if p.size not in (2, 3):
        raise ValueError(f"point must be a point of the axis, 2 or 3 coordinates (m), got {p.tolist()}")
    if np.max(np.abs(p)) > MAX_COORDINATE:
        raise ValueError(f"point must have coordinates below {MAX_COORDINATE:g} m, got {p.tolist()}")
    return np.concatenate([p, np.zeros(3 - p.size)])


@dataclass(frozen=True)
class Vector:
    """DOFs that turn together: a node's translation or rotation, components ``0, 1(, 2)`` = x, y(, z).

    ``components`` empty: one DOF that does not turn (a scalar).
    """

    dofs: tuple[int, ...]
    components: tuple[int, ...]
    node: int = -1  # the boundary node it belongs to (an index into the boundary's nodes), -1 for none

    def turns_within(self, R: np.ndarray) -> bool:
        """True when ``R`` maps these components onto themselves (always for three, or for none)."""
        idx = list(self.components)
        other = [k for k in range(3) if k not in idx]
        return not (idx and other) or max(np.abs(R[np.ix_(idx, other)]).max(),
                                          np.abs(R[np.ix_(other, idx)]).max()) <= _ZERO

    def block(self, R: np.ndarray, where: str) -> np.ndarray:
        """``R`` on these components (``(c, c)``), refused when ``R`` turns them into components not given."""
        if not self.components:
            return np.eye(1)
        idx = list(self.components)
        if not self.turns_within(R):
            other = [k for k in range(3) if k not in idx]
            given = ", ".join(_LETTERS[k] for k in idx)
            raise ValueError(f"{where}: DOFs {list(self.dofs)} are the components {given} of a node, but the rotation "
                             f"about the axis turns {', '.join(_LETTERS[k] for k in other)} into them: give all three "
                             f"(x, y, z), or an axis along the missing one")
        return R[np.ix_(idx, idx)]


def boundary_elements(name: str, values, ndof: int, dof_map=None) -> list:
    """A boundary as given: ``[(dofs, grouped)]``, one per entry of ``values``.

    An entry is one DOF (an index, or a name with a DOF map: ``grouped`` False)
    or a tuple (list) of one node's DOFs (``grouped`` True). The DOFs are
    checked (in range, no repeats across the whole boundary).
    """
    if isinstance(values, np.ndarray) and values.ndim == 2:
        values = [list(row) for row in values]
    if isinstance(values, (list, tuple)) and any(isinstance(v, (list, tuple, np.ndarray)) for v in values):
        out = []
        for j, v in enumerate(values):
            grouped = isinstance(v, (list, tuple, np.ndarray))
            if grouped and not len(v):
                raise ValueError(f"{name}[{j}] must list a node's DOFs, got an empty {type(v).__name__}")
            dofs = dof_indices(f"{name}[{j}]", list(v) if grouped else [v], ndof, dof_map)
            out.append((tuple(int(d) for d in dofs), grouped))
        dof_indices(name, [d for dofs, _ in out for d in dofs], ndof)  # no DOF twice
        return out
    return [((int(d),), False) for d in dof_indices(name, values, ndof, dof_map)]


def _component(dof_map, dof: int) -> tuple[int, str, int]:
    """``(node id, kind, component)`` of a DOF in a DOF map: kind ``""`` for a translation, ``"r"`` a rotation."""
    letter = dof_map.components[dof]
    kind = "r" if letter.startswith("r") else ""
    return int(dof_map.nodes[dof]), kind, _LETTERS.index(letter[-1])


def _check_letters(name: str, dofs, dof_map) -> None:
    """A tuple's DOFs named in a DOF map must be x, y(, z) (or rx, ry(, rz)) in that order."""
    letters = [dof_map.components[d] for d in dofs]
    if letters not in (["x", "y"], ["x", "y", "z"], ["rx", "ry"], ["rx", "ry", "rz"]):
        raise ValueError(f"{name} must be a node's components in the order x, y(, z) (or rx, ry(, rz)), got "
                         f"{', '.join(dof_map.names[d] for d in dofs)}")


def _label(left, right, dof_map) -> str:
    """A boundary node for messages: its node ids with a DOF map (when its DOFs are one node's), else its DOFs."""
    if dof_map is not None:
        ids = [{int(dof_map.nodes[d]) for d in dofs} for dofs in (left, right)]
        if all(len(i) == 1 for i in ids):
            return f"left node {ids[0].pop()}, right node {ids[1].pop()}"
    return f"left DOFs {list(left)}, right DOFs {list(right)}"


def xyz_text(x) -> str:
    """A point or direction for a message: ``[0.1, 0, 0.3]`` (6 significant digits)."""
    return "[" + ", ".join(f"{float(v):.6g}" for v in x) + "]"


@dataclass
class Boundary:
    """The sector's boundaries, paired: ``left[j]`` of sector ``s + 1`` is ``right[j]`` of sector ``s``.

    ``nodes``: ``(left DOFs, right DOFs, label)`` of each boundary node (the
    unit of ``coordinates``); ``vectors``: ``(left, right)`` :class:`Vector` pairs
    (the Cartesian frame's rotation acts on them; empty in the cylindrical
    frame).
    """

    left: np.ndarray
    right: np.ndarray
    nodes: list
    vectors: list


def pair(left, right, frame: str, dof_map=None) -> Boundary:
    """Pair two boundaries of :func:`boundary_elements` into nodes and (in the Cartesian frame) vectors."""
    flat_l = np.array([d for dofs, _ in left for d in dofs], dtype=np.int64)
    flat_r = np.array([d for dofs, _ in right for d in dofs], dtype=np.int64)
    if flat_l.size != flat_r.size or len(left) != len(right):
        raise ValueError(f"left and right must pair the boundary DOFs one to one, got {flat_l.size} and "
                         f"{flat_r.size} DOFs")
    for j, ((dl, gl), (dr, gr)) in enumerate(zip(left, right)):
        if gl != gr or len(dl) != len(dr):
            raise ValueError(f"left[{j}] and right[{j}] must pair the boundary DOFs one to one: got "
                             f"{list(dl) if gl else dl[0]} and {list(dr) if gr else dr[0]}")
    nodes, vectors = [], []
    groups = [j for j, (_, g) in enumerate(left) if g]
    for j in groups:  # a tuple: one node, its DOFs one vector in the Cartesian frame
        dl, dr = left[j][0], right[j][0]
        if frame == "cartesian" and len(dl) > 3:
            raise ValueError(f"left[{j}] must be one node's (x, y) or (x, y, z) DOFs, or one DOF that does not turn "
                             f"as (j,), got {len(dl)} DOFs {list(dl)}")
        comps = tuple(range(len(dl))) if len(dl) > 1 else ()
        if frame == "cartesian" and dof_map is not None and comps:
            _check_letters(f"left[{j}]", dl, dof_map)
            _check_letters(f"right[{j}]", dr, dof_map)
        if frame == "cartesian":
            vectors.append((Vector(dl, comps, len(nodes)), Vector(dr, comps, len(nodes))))
        nodes.append((dl, dr, _label(dl, dr, dof_map)))
    lone = [j for j, (_, g) in enumerate(left) if not g]
    if dof_map is None:
        if frame == "cartesian" and lone:
            j = lone[0]
            raise ValueError(f"left[{j}]: DOF {left[j][0][0]} is not in a node's tuple: in the Cartesian frame each "
                             f"boundary node's DOFs turn together, give them as a tuple, left=[(0, 1), ...] (x, "
                             f"y(, z)); (j,) for a DOF that does not turn")
        nodes += [(left[j][0], right[j][0], _label(left[j][0], right[j][0], None)) for j in lone]
        return Boundary(flat_l, flat_r, nodes, vectors)
    by_node: dict = {}
    for j in lone:  # with a DOF map: a node's DOFs together, its translation and rotation each a vector
        by_node.setdefault(int(dof_map.nodes[left[j][0][0]]), []).append(j)
    for node, js in by_node.items():
        index = len(nodes)
        right_nodes = {int(dof_map.nodes[right[j][0][0]]) for j in js}
        if len(right_nodes) > 1:
            given = ", ".join(dof_map.names[left[j][0][0]] for j in js)
            raise ValueError(f"right: the DOFs paired with left node {node}'s ({given}) belong to several nodes, "
                             f"{sorted(right_nodes)}: a node's DOFs pair with one node's")
        dl, dr = tuple(left[j][0][0] for j in js), tuple(right[j][0][0] for j in js)
        nodes.append((dl, dr, _label(dl, dr, dof_map)))
        if frame != "cartesian":
            continue
        for kind in ("", "r"):
            mine = [j for j in js if _component(dof_map, left[j][0][0])[1] == kind]
            if not mine:
                continue
            comps_l = [_component(dof_map, left[j][0][0])[2] for j in mine]
            comps_r = [_component(dof_map, right[j][0][0])[2] for j in mine]
            kinds_r = {_component(dof_map, right[j][0][0])[1] for j in mine}
            if comps_l != comps_r or kinds_r != {kind}:
                pairs = ", ".join(f"{dof_map.names[left[j][0][0]]} with {dof_map.names[right[j][0][0]]}" for j in mine)
                raise ValueError(f"right: the DOFs pair {pairs}: in the Cartesian frame each component pairs with the "
                                 f"same component")
            if sorted(comps_l) not in ([0, 1], [0, 1, 2]):
                raise ValueError(f"left: node {node}'s DOFs {', '.join(dof_map.names[left[j][0][0]] for j in mine)} "
                                 f"turn together in the Cartesian frame: give its x and y (and z) components")
            order = np.argsort(comps_l)
            vectors.append((Vector(tuple(left[mine[k]][0][0] for k in order), tuple(sorted(comps_l)), index),
                            Vector(tuple(right[mine[k]][0][0] for k in order), tuple(sorted(comps_l)), index)))
    return Boundary(flat_l, flat_r, nodes, vectors)


def node_vectors(nodes, ndof: int, dof_map, taken: np.ndarray, R: np.ndarray) -> list:
    """The sector's other vectors (Cartesian frame): the tuples ``nodes``, or every node of a DOF map.

    From a DOF map: each node's x, y(, z) and rx, ry(, rz) that are not on a
    boundary (``taken``), when it has x and y (and z, unless ``R`` turns about z).
    """
    out = []
    if nodes is not None:
        for j, v in enumerate(boundary_elements("nodes", nodes, ndof, dof_map)):
            dofs, grouped = v
            if not grouped or len(dofs) > 3:
                raise ValueError(f"nodes[{j}] must be a node's (x, y) or (x, y, z) DOFs as a tuple, or (j,) for a DOF "
                                 f"that does not turn, got {list(dofs) if grouped else dofs[0]}")
            on = np.intersect1d(dofs, taken)
            if on.size:
                raise ValueError(f"nodes[{j}]: DOF {int(on[0])} is on a boundary, whose nodes left and right give")
            if dof_map is not None and len(dofs) > 1:
                _check_letters(f"nodes[{j}]", dofs, dof_map)
            out.append(Vector(dofs, tuple(range(len(dofs))) if len(dofs) > 1 else ()))
        return out
    if dof_map is None:
        return out
    rows: dict = {}
    for dof in range(ndof):
        node, kind, comp = _component(dof_map, dof)
        rows.setdefault((node, kind), {})[comp] = dof
    for comps in rows.values():
        have = sorted(comps)
        if have not in ([0, 1], [0, 1, 2]):
            continue
        v = Vector(tuple(comps[k] for k in have), tuple(have))
        if not np.isin(v.dofs, taken).any() and v.turns_within(R):
            out.append(v)
    return out


def boundary_coordinates(coordinates, boundary: Boundary, dof_map) -> np.ndarray:
    """The boundary nodes' positions ``(2, nodes, 3)`` (m): left, right (z = 0 for 2-D coordinates).

    ``coordinates`` is an array ``(2, nodes, 2 or 3)`` in the order of the
    boundary's nodes, or with a DOF map a mapping ``{node id: (x, y(, z))}``.
    """
    k = len(boundary.nodes)
    if isinstance(coordinates, dict):
        if dof_map is None:
            raise TypeError("coordinates as a mapping {node id: position} needs a DOF map (dof_map=...) for the node "
                            "ids; without one give an array (2, nodes, 2 or 3): the left nodes' and the right nodes'")
        where = {int(_checks.positive_int("coordinates (a node id as key)", key, minimum=0)): value
                 for key, value in coordinates.items()}
        rows = []
        for side in (0, 1):
            row = []
            for node in boundary.nodes:
                ids = {int(dof_map.nodes[d]) for d in node[side]}
                if len(ids) > 1 or next(iter(ids)) not in where:
                    raise ValueError(f"coordinates has no position for node {sorted(ids)[0]} of the "
                                     f"{('left', 'right')[side]} boundary")
                row.append(where[next(iter(ids))])
            rows.append(row)
        coordinates = rows
    x = _checks.real_array("coordinates", coordinates)
    if k == 0 and x.shape == (2, 0):  # no boundary (blades in a rigid disk), as a list [[], []] writes it
        x = np.zeros((2, 0, 3))
    if x.ndim != 3 or x.shape[:2] != (2, k) or x.shape[2] not in (2, 3):
        raise ValueError(f"coordinates must have shape (2, {k}, 2 or 3): the positions (m) of the {k} left boundary "
                         f"nodes and of the {k} right ones, got shape {x.shape}")
    if x.size and np.max(np.abs(x)) > MAX_COORDINATE:
        raise ValueError(f"coordinates must be below {MAX_COORDINATE:g} m, got {float(np.max(np.abs(x)))!r}")
    return np.concatenate([x, np.zeros((2, k, 3 - x.shape[2]))], axis=2) if x.shape[2] == 2 else x


def check_geometry(x: np.ndarray, boundary: Boundary, axis: np.ndarray, point: np.ndarray, sectors: int) -> None:
    """Refuse a right boundary node farther than the tolerance from its left node turned by ``2 pi / sectors``.

    The tolerance is :data:`GEOMETRY_TOLERANCE` times the largest distance of
    a boundary node from the axis.
    """
    if not len(boundary.nodes):
        return
    rel = x - point
    radius = np.linalg.norm(rel - (rel @ axis)[..., None] * axis, axis=-1)
    tol = GEOMETRY_TOLERANCE * max(float(radius.max()), float(np.abs(rel).max()) if not radius.max() else 0.0)
    turned = rel[0] @ rotation(axis, 2 * np.pi / sectors).T
    miss = np.linalg.norm(rel[1] - turned, axis=1)
    bad = np.flatnonzero(~(miss <= tol))
    if not bad.size:
        return
    j = int(bad[np.argmax(miss[bad])]) if np.isfinite(miss[bad]).all() else int(bad[0])
    back = np.linalg.norm(rel[1] - rel[0] @ rotation(axis, -2 * np.pi / sectors).T, axis=1)
    hint = (f"; it is the left one turned by -2 pi / sectors: give axis = {xyz_text(-axis)}"
            if np.all(back <= tol) else "")
    raise ValueError(f"coordinates: the right boundary's node {j} ({boundary.nodes[j][2]}) at {xyz_text(x[1, j])} m is "
                     f"{float(miss[j]):.3g} m from its left node at {xyz_text(x[0, j])} m turned by 2 pi / sectors "
                     f"({360 / sectors:.6g} deg, sectors = {sectors}) about axis = {xyz_text(axis)} through point = "
                     f"{xyz_text(point)} (tolerance {tol:.3g} m, {GEOMETRY_TOLERANCE:g} of the largest boundary "
                     f"radius){hint}")


def blocks(vectors, R: np.ndarray, where: str) -> list:
    """``[(dofs (n, c), block (c, c))]``: the vectors grouped by components, each with ``R`` on its components."""
    by: dict = {}
    for v in vectors:
        by.setdefault(v.components, []).append(v)
    out = []
    for comps, vs in by.items():
        B = vs[0].block(R, where) if comps else np.eye(1)
        out.append((np.array([v.dofs for v in vs], dtype=np.int64), B))
    return out


def turn_back(b: np.ndarray, parts) -> np.ndarray:
    """``Q^T b``: a vector on DOFs turned by :func:`blocks` ``parts`` (``Q`` the rotation), in the unturned frame."""
    out = b.copy()
    for dofs, B in parts:
        out[dofs] = b[dofs] @ B
    return out


def boundary_rotation(boundary: Boundary, R: np.ndarray) -> sp.csr_matrix:
    """``(k, k)`` sparse: ``u_right = rotation @ u_left`` in the boundaries' flat order (identity without vectors)."""
    k = boundary.left.size
    pos_l = {int(d): i for i, d in enumerate(boundary.left)}
    pos_r = {int(d): i for i, d in enumerate(boundary.right)}
    rows, cols, vals = [], [], []
    turned = np.zeros(k, dtype=bool)
    for vl, vr in boundary.vectors:
        B = vl.block(R, "left")
        for a, dr in enumerate(vr.dofs):
            for b, dl in enumerate(vl.dofs):
                if B[a, b]:
                    rows.append(pos_r[dr])
                    cols.append(pos_l[dl])
                    vals.append(B[a, b])
            turned[pos_r[dr]] = True
    rest = np.flatnonzero(~turned).tolist()  # right[i] pairs left[i]
    rows += rest
    cols += rest
    vals += [1.0] * len(rest)
    return sp.csr_matrix((np.array(vals, dtype=float), (rows, cols)), shape=(k, k))
