"""Contact patches from a mesh: node-to-node contacts with tributary areas, normals and tangents.

Two surfaces of a mesh (side ``a`` and side ``b``, each given by its triangle or quad faces) become
``P`` node pairs matched by position; each pair carries its tributary area (m²), the unit normal of
side ``a`` pointing from ``a`` to ``b`` and two unit tangents. :func:`add_patch` attaches one contact per
pair to a :class:`microslip.frequency.Structure`, with a contact law given per unit area and scaled by
each pair's area.

Conventions
-----------
* Tributary area of a node: the sum over its faces of the face's area divided by the face's number of
  nodes (exact for triangles and flat quads: the areas of a surface sum to its area).
* A face's vector area: ``(p1 - p0) x (p2 - p0) / 2`` for a triangle, ``(p2 - p0) x (p3 - p1) / 2`` for a
  quad (its area when flat); a node's normal is the sum of its faces' vector areas, normalised. The faces
  of side ``a`` are ordered so that this normal points from ``a`` to ``b`` (counter-clockwise seen from
  ``b``); the faces of side ``b`` only give its nodes.
* Tangents: ``tangent1`` is the global axis (x, y or z, the first of those) least aligned with the
  normal, projected onto the tangent plane and normalised; ``tangent2 = normal x tangent1``. The frame
  ``(tangent1, tangent2, normal)`` is right-handed and orthonormal, and it depends only on the normal.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ..common import _checks
from ..model import MicroslipModel
from ._optional import require

__all__ = ["ContactPatch", "PressureLaw", "add_patch", "contact_patch", "patch_from_mesh", "patch_from_tables"]


@dataclass(frozen=True)
class ContactPatch:
    """``P`` node pairs of a contact patch (made by :func:`contact_patch` or :func:`patch_from_mesh`).

    Attributes
    ----------
    nodes_a, nodes_b : ndarray of int, shape (P,)
        Node id of each pair on side ``a`` and on side ``b`` (sorted by ``nodes_a``).
    area : ndarray, shape (P,)
        Tributary area of each pair (m²), side ``a``'s.
    normal : ndarray, shape (P, 3)
        Unit normal of side ``a`` at each pair, pointing from ``a`` to ``b``.
    tangent1, tangent2 : ndarray, shape (P, 3)
        Unit tangents; ``(tangent1, tangent2, normal)`` is right-handed and orthonormal.
    distance : ndarray, shape (P,)
        Distance between the two nodes of each pair (m); zero for a patch read from tables
        (:func:`patch_from_tables`).
    """

    nodes_a: np.ndarray
    nodes_b: np.ndarray
    area: np.ndarray
    normal: np.ndarray
    tangent1: np.ndarray
    tangent2: np.ndarray
    distance: np.ndarray

    @property
    def total_area(self) -> float:
        """The patch's area (m²): the sum of the tributary areas."""
        return float(self.area.sum())

    def __len__(self) -> int:
        return int(self.area.size)


@dataclass(frozen=True)
class PressureLaw:
    """A pressure-overclosure and traction law per unit area: one Jenkins element per m².

    Parameters
    ----------
    kn_per_area : float
        Normal stiffness per unit area (Pa/m = N/m per m²): the contact pressure is
        ``kn_per_area * (overclosure - gap)`` when positive.
    kt_per_area : float
        Tangential stiffness per unit area (Pa/m).
    mu : float
        Friction coefficient.
    gap : float
        Overclosure at which the surfaces touch (m).
    """

    kn_per_area: float
    kt_per_area: float
    mu: float
    gap: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "kn_per_area", _checks.positive_scalar("kn_per_area", self.kn_per_area))
        object.__setattr__(self, "kt_per_area", _checks.positive_scalar("kt_per_area", self.kt_per_area))
        object.__setattr__(self, "mu", _checks.positive_scalar("mu", self.mu))
        object.__setattr__(self, "gap", _checks.real_scalar("gap", self.gap))

    def model(self, area: float) -> MicroslipModel:
        """The one-element :class:`~microslip.MicroslipModel` of a pair of tributary area ``area`` (m²)."""
        a = _checks.positive_scalar("area", area)
        kt, kn = self.kt_per_area * a, self.kn_per_area * a
        if not (0.0 < kt < np.inf and 0.0 < kn < np.inf):
            raise ValueError(f"area = {a!r} m² gives stiffnesses kt = {kt!r}, kn = {kn!r} N/m outside the "
                             "positive floating-point range")
        return MicroslipModel(kt=[kt], kn=[kn], gaps=[self.gap], mu=self.mu)


# -- geometry --------------------------------------------------------------------------------------------


def _points(mesh_or_points) -> dict:
    """``{node id: (x, y, z)}`` from a mapping, an ``(N, 2|3)`` array (ids = rows) or a mesh with ``points``."""
    if hasattr(mesh_or_points, "points") and not isinstance(mesh_or_points, (Mapping, np.ndarray)):
        mesh_or_points = mesh_or_points.points
    if isinstance(mesh_or_points, Mapping):
        if not mesh_or_points:
            raise ValueError("mesh_or_points must hold at least one node, got an empty mapping")
        out = {}
        for key, xyz in mesh_or_points.items():
            if isinstance(key, (bool, np.bool_)) or not isinstance(key, (int, np.integer)):
                raise TypeError(f"mesh_or_points: node ids must be integers, got {key!r}")
            p = _checks.real_array(f"mesh_or_points[{key}]", xyz, ndim=1)
            if p.size not in (2, 3):
                raise ValueError(f"mesh_or_points[{key}] must be (x, y) or (x, y, z) in m, got {p.size} values")
            out[int(key)] = np.pad(p, (0, 3 - p.size))
        return out
    p = _checks.real_array("mesh_or_points", mesh_or_points, ndim=2, min_size=1)
    if p.shape[1] not in (2, 3):
        raise ValueError(f"mesh_or_points must have shape (N, 2) or (N, 3) (m), got {p.shape}")
    if p.shape[0] > _checks.MAX_SIZE:
        raise ValueError(f"mesh_or_points must have at most {_checks.MAX_SIZE} nodes, got {p.shape[0]}")
    p = np.pad(p, ((0, 0), (0, 3 - p.shape[1])))
    return dict(enumerate(p))


def _faces(name: str, faces) -> list[tuple[int, ...]]:
    """The faces of a surface: sequences of 3 (triangle) or 4 (quad) node ids."""
    if isinstance(faces, (str, bytes, Mapping)) or not hasattr(faces, "__len__") or (
            isinstance(faces, np.ndarray) and faces.ndim != 2):
        raise TypeError(f"{name} must be a sequence of faces (3 or 4 node ids each), got {_checks._show(faces)}")
    out = []
    for k, face in enumerate(faces):
        if isinstance(face, (str, bytes, Mapping)) or np.ndim(face) != 1 or len(face) not in (3, 4):
            raise ValueError(f"{name}[{k}] must be a triangle or a quad (3 or 4 node ids), got {_checks._show(face)}")
        ids = []
        for v in face:
            if isinstance(v, (bool, np.bool_)) or not isinstance(v, (int, np.integer)):
                raise TypeError(f"{name}[{k}] must hold integer node ids, got {_checks._show(face)}")
            ids.append(int(v))
        if len(set(ids)) != len(ids):
            raise ValueError(f"{name}[{k}] repeats a node: {ids}")
        out.append(tuple(ids))
    if not out:
        raise ValueError(f"{name} must hold at least one face, got none")
    if len(out) > _checks.MAX_SIZE:
        raise ValueError(f"{name} must hold at most {_checks.MAX_SIZE} faces, got {len(out)}")
    return out


def _surface(name: str, faces, points: dict):
    """``(ids, area, vector)``: the surface's node ids (sorted), tributary areas (m²) and summed vector areas."""
    ids = sorted({v for f in faces for v in f})
    missing = [v for v in ids if v not in points]
    if missing:
        raise ValueError(f"{name} names nodes that mesh_or_points does not hold: {missing[:10]}")
    row = {v: i for i, v in enumerate(ids)}
    area, vector = np.zeros(len(ids)), np.zeros((len(ids), 3))
    for k, f in enumerate(faces):
        p = [points[v] for v in f]
        if len(f) == 3:
            va = 0.5 * np.cross(p[1] - p[0], p[2] - p[0])
        else:
            va = 0.5 * np.cross(p[2] - p[0], p[3] - p[1])
        a = float(np.linalg.norm(va))
        if not a > 0.0 or not np.isfinite(a):
            raise ValueError(f"{name}[{k}] (nodes {list(f)}) has zero or non-finite area at the positions of "
                             f"mesh_or_points, got {a!r} m²")
        for v in f:
            area[row[v]] += a / len(f)
            vector[row[v]] += va
    return np.array(ids, dtype=np.int64), area, vector


def _frames(vector: np.ndarray, ids) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    norm = np.linalg.norm(vector, axis=1)
    flat = np.flatnonzero(~(norm > 0.0))
    if flat.size:
        raise ValueError(f"surface_a: the faces around node {int(ids[flat[0]])} cancel (opposite orientations): "
                         f"no normal; order every face of surface_a the same way")
    n = vector / norm[:, None]
    axis = np.argmin(np.abs(n), axis=1)  # the global axis least aligned with the normal (first on ties)
    e = np.eye(3)[axis]
    t1 = e - np.sum(e * n, axis=1)[:, None] * n
    t1 /= np.linalg.norm(t1, axis=1)[:, None]
    t2 = np.cross(n, t1)
    return n, t1, t2


def contact_patch(mesh_or_points, surface_a, surface_b, *, tolerance: float) -> ContactPatch:
    """The node pairs of a contact patch between two surfaces of a mesh.

    Parameters
    ----------
    mesh_or_points : mapping, array_like or mesh
        Node positions (m): ``{node id: (x, y, z)}``, an array of shape ``(N, 3)`` or ``(N, 2)`` whose
        row ``i`` is node ``i``, or a mesh with such ``points`` (e.g. a ``meshio.Mesh``).
    surface_a, surface_b : sequence of faces
        The faces of each side: sequences of 3 (triangle) or 4 (quad) node ids. Side ``a``'s faces are
        ordered counter-clockwise seen from ``b`` (their normals point from ``a`` to ``b``).
    tolerance : float
        The largest distance (m) between the two nodes of a pair.

    Returns
    -------
    ContactPatch
        One pair per node of side ``a``, matched to the nearest node of side ``b``.

    Raises
    ------
    ValueError
        A node of either side has no partner within ``tolerance`` or two nodes of ``a`` share the
        nearest node of ``b`` (the node ids and the distances are named); a face is degenerate.
    """
    tol = _checks.positive_scalar("tolerance", tolerance, allow_zero=True)
    points = _points(mesh_or_points)
    fa, fb = _faces("surface_a", surface_a), _faces("surface_b", surface_b)
    ids_a, area, vector = _surface("surface_a", fa, points)
    ids_b = np.array(sorted({v for f in fb for v in f}), dtype=np.int64)
    missing = [int(v) for v in ids_b if int(v) not in points]
    if missing:
        raise ValueError(f"surface_b names nodes that mesh_or_points does not hold: {missing[:10]}")
    xa = np.array([points[int(v)] for v in ids_a])
    xb = np.array([points[int(v)] for v in ids_b])
    from scipy.spatial import cKDTree

    dist, j = cKDTree(xb).query(xa)
    far = np.flatnonzero(~(dist <= tol))
    if far.size:
        i = far[np.argmax(dist[far])]
        raise ValueError(f"tolerance = {tol!r} m: node {int(ids_a[i])} of surface_a has no node of surface_b within "
                         f"it (the nearest, node {int(ids_b[j[i]])}, is {float(dist[i]):.6g} m away); "
                         f"{far.size} node(s) of surface_a unmatched: {[int(v) for v in ids_a[far][:10]]}")
    taken = {}
    for i, jj in enumerate(j.tolist()):
        if jj in taken:
            k = taken[jj]
            raise ValueError(f"tolerance = {tol!r} m: nodes {int(ids_a[k])} and {int(ids_a[i])} of surface_a both match "
                             f"node {int(ids_b[jj])} of surface_b ({float(dist[k]):.6g} m and {float(dist[i]):.6g} m "
                             f"away): each node must have one partner")
        taken[jj] = i
    if len(taken) != ids_b.size:
        lone = np.setdiff1d(np.arange(ids_b.size), list(taken))
        back, _ = cKDTree(xa).query(xb[lone])
        raise ValueError(f"tolerance = {tol!r} m: node {int(ids_b[lone[0]])} of surface_b has no partner on "
                         f"surface_a (the nearest node of surface_a is {float(back[0]):.6g} m away); "
                         f"{lone.size} node(s) of surface_b unmatched: {[int(v) for v in ids_b[lone][:10]]}")
    n, t1, t2 = _frames(vector, ids_a)
    return ContactPatch(ids_a, ids_b[j], area, n, t1, t2, dist)


def _unit_rows(name: str, value, P: int) -> np.ndarray:
    v = _checks.real_array(name, value, ndim=2)
    if v.shape != (P, 3):
        raise ValueError(f"{name} must have shape (P, 3) = ({P}, 3), one unit vector per pair, got {v.shape}")
    norm = np.linalg.norm(v, axis=1)
    bad = np.flatnonzero(~(np.abs(norm - 1.0) <= 1e-6))
    if bad.size:
        raise ValueError(f"{name}[{int(bad[0])}] must be a unit vector (within 1e-6), got length {float(norm[bad[0]])!r}")
    return v / norm[:, None]


def patch_from_tables(nodes_a, area, normal, *, nodes_b=None, tangent1=None, tangent2=None) -> ContactPatch:
    """A :class:`ContactPatch` from the tables a reduced model's interface carries.

    Parameters
    ----------
    nodes_a : array_like of int, shape (P,)
        Node (or interface point) id of each pair.
    area : array_like, shape (P,)
        Tributary area of each pair (m²), positive.
    normal : array_like, shape (P, 3)
        Unit normal of each pair, from side ``a`` to side ``b`` (unit within 1e-6; normalised).
    nodes_b : array_like of int, shape (P,), optional
        The partner of each pair; default ``nodes_a`` (relative-displacement coordinates: use
        ``add_patch(..., relative=True)``).
    tangent1, tangent2 : array_like, shape (P, 3), optional
        Unit tangents, perpendicular to ``normal`` (within 1e-6); ``tangent2`` defaults to
        ``normal x tangent1`` and both default to the rule of :func:`contact_patch`.

    Returns
    -------
    ContactPatch
        With ``distance`` zero.
    """
    ids = _checks.real_array("nodes_a", nodes_a, ndim=1, min_size=1)
    if ids.size > _checks.MAX_SIZE:
        raise ValueError(f"nodes_a must have at most {_checks.MAX_SIZE} pairs, got {ids.size}")
    P = ids.size
    tables = {"nodes_a": nodes_a, "nodes_b": nodes_a if nodes_b is None else nodes_b}
    out = {}
    for name, value in tables.items():
        arr = np.asarray(value)
        if arr.dtype.kind not in "iu" or arr.shape != (P,) or (arr < 0).any():
            raise ValueError(f"{name} must be {P} non-negative integer node ids, got {_checks._show(value)}")
        out[name] = arr.astype(np.int64)
    a = _checks.positive_array("area", area, ndim=1)
    if a.size != P:
        raise ValueError(f"area must have one value per pair ({P}), got {a.size}")
    n = _unit_rows("normal", normal, P)
    if tangent1 is None:
        if tangent2 is not None:
            raise ValueError("tangent2 must be None when tangent1 is: give tangent1 (tangent2 = normal x tangent1)")
        n, t1, t2 = _frames(n, out["nodes_a"])
    else:
        t1 = _unit_rows("tangent1", tangent1, P)
        t2 = np.cross(n, t1) if tangent2 is None else _unit_rows("tangent2", tangent2, P)
        for name, t in (("tangent1", t1), ("tangent2", t2)):
            off = np.abs(np.sum(t * n, axis=1))
            if not (off <= 1e-6).all():
                k = int(np.argmax(off))
                raise ValueError(f"{name}[{k}] must be perpendicular to normal[{k}] (within 1e-6), got a cosine "
                                 f"{float(off[k])!r}")
        off = np.abs(np.sum(t1 * t2, axis=1))
        if not (off <= 1e-6).all():
            k = int(np.argmax(off))
            raise ValueError(f"tangent2[{k}] must be perpendicular to tangent1[{k}] (within 1e-6), got a cosine "
                             f"{float(off[k])!r}")
    return ContactPatch(out["nodes_a"], out["nodes_b"], a, n, t1, t2, np.zeros(P))


# -- from a mesh file ------------------------------------------------------------------------------------

#: meshio's names of the surface cells and their corner counts
_SURFACE_CELLS = {"triangle": 3, "quad": 4}


def _set_faces(path, mesh, name: str, where: str) -> list:
    """The triangle and quad faces (point indices) a named set of the mesh covers."""
    if not isinstance(name, str) or not name:
        raise TypeError(f"{where} must be the name of a set of the mesh, got {_checks._show(name)}")
    blocks = [(b.type, np.asarray(b.data)) for b in mesh.cells]
    if name in mesh.cell_sets:
        faces = []
        for (kind, data), rows in zip(blocks, mesh.cell_sets[name]):
            rows = np.asarray(rows, dtype=np.int64)
            if rows.size and kind in _SURFACE_CELLS:
                faces += [tuple(int(v) for v in c) for c in data[rows]]
        if not faces:
            raise ValueError(f"{where} = {name!r}: the cell set of {path} holds no triangle or quad")
        return faces
    physical = mesh.cell_data.get("gmsh:physical")
    if name in mesh.field_data and physical is not None:
        tag = int(mesh.field_data[name][0])
        faces = [tuple(int(v) for v in c) for (kind, data), tags in zip(blocks, physical)
                 if kind in _SURFACE_CELLS for c in data[np.asarray(tags) == tag]]
        if not faces:
            raise ValueError(f"{where} = {name!r}: the physical group of {path} holds no triangle or quad")
        return faces
    if name in mesh.point_sets:
        nodes = set(np.asarray(mesh.point_sets[name], dtype=np.int64).tolist())
        faces = [tuple(int(v) for v in c) for kind, data in blocks if kind in _SURFACE_CELLS
                 for c in data if nodes.issuperset(c.tolist())]
        if not faces:
            raise ValueError(f"{where} = {name!r}: no triangle or quad of {path} has all its nodes in the node set")
        return faces
    available = sorted(set(mesh.cell_sets) | set(mesh.point_sets) | set(mesh.field_data))
    raise ValueError(f"{where} = {name!r} is not a node set, cell set or physical group of {path}"
                     f"{_checks.close_spelling(name, available)}; the sets are: {', '.join(map(repr, available)) or 'none'}")


def patch_from_mesh(path, set_a: str, set_b: str, *, tolerance: float) -> ContactPatch:
    """:func:`contact_patch` between two named surfaces of a mesh file read with meshio.

    Parameters
    ----------
    path : str or os.PathLike
        A mesh meshio reads (Gmsh ``.msh``, Abaqus ``.inp``, VTK ``.vtk``/``.vtu``, ...). Node ids are
        meshio's point indices (0-based, in the file's order of nodes).
    set_a, set_b : str
        The name of each side: a cell set (Abaqus ``*ELSET``), a Gmsh physical group, or a node set
        (``*NSET``: the mesh's triangles and quads whose nodes all lie in it). Side ``a``'s faces are
        ordered counter-clockwise seen from ``b``.
    tolerance : float
        The largest distance (m) between the two nodes of a pair.

    Returns
    -------
    ContactPatch

    Raises
    ------
    ValueError
        The file cannot be read (named), a set is missing (the sets available are listed), or the
        pairs do not match (:func:`contact_patch`).
    """
    path = _checks.file_path("path", path)
    tol = _checks.positive_scalar("tolerance", tolerance, allow_zero=True)
    for where, name in (("set_a", set_a), ("set_b", set_b)):
        _checks.text(where, name)
    meshio = require("meshio", "reading a mesh (patch_from_mesh)")
    if not path.is_file():
        raise ValueError(f"path = {str(path)!r}: no such file")
    try:
        mesh = meshio.read(path)
    except Exception as exc:  # noqa: BLE001 - meshio raises many kinds on a damaged file
        raise ValueError(f"path = {str(path)!r} is not a mesh meshio can read: {type(exc).__name__}: {exc}") from None
    fa, fb = _set_faces(path, mesh, set_a, "set_a"), _set_faces(path, mesh, set_b, "set_b")
    return contact_patch(np.asarray(mesh.points, dtype=float), fa, fb, tolerance=tol)


# -- onto a structure ------------------------------------------------------------------------------------


def _pair_model(law, area: float) -> MicroslipModel:
    if isinstance(law, PressureLaw):
        return law.model(area)
    return MicroslipModel(kt=law.kt * area, kn=law.kn * area, gaps=law.gaps, mu=law.mu)


def _node_dofs(node: int, dofs, structure) -> list:
    """The (x, y, z) DOFs of ``node``: from ``dofs`` (a mapping) or the structure's DOF map."""
    if dofs is None:
        if getattr(structure, "dof_map", None) is None:
            raise ValueError("dofs must map each node id to its (x, y, z) DOFs when the structure has no dof_map")
        return [f"{node}:{c}" for c in "xyz"]
    if node not in dofs:
        raise ValueError(f"dofs has no entry for node {node} of the patch")
    triple = dofs[node]
    if isinstance(triple, (str, bytes)) or np.ndim(triple) != 1 or len(triple) != 3:
        raise ValueError(f"dofs[{node}] must be the node's 3 DOFs (x, y, z), indices or names, got "
                         f"{_checks._show(triple)}")
    out = []
    for v in triple:
        if isinstance(v, (bool, np.bool_)) or not isinstance(v, (int, np.integer, str)):
            raise TypeError(f"dofs[{node}] must hold DOF indices or names, got {_checks._show(triple)}")
        out.append(v if isinstance(v, str) else int(v))
    return out


def add_patch(structure, patch: ContactPatch, law, *, dofs=None, name: str = "patch", relative: bool = False) -> list:
    """Attach one contact per node pair of ``patch`` to ``structure``.

    Parameters
    ----------
    structure : microslip.frequency.Structure
        The structure (its :meth:`~microslip.frequency.Structure.add_contact` is called ``P`` times).
    patch : ContactPatch
        The node pairs, areas, normals and tangents.
    law : MicroslipModel or PressureLaw
        The contact law per unit area: a :class:`~microslip.MicroslipModel` whose ``kt`` and ``kn`` are
        per m² (N/m per m²; scaled by each pair's area, gaps and ``mu`` kept, its provenance dropped), or
        a :class:`PressureLaw`.
    dofs : mapping, optional
        ``{node id: (x_dof, y_dof, z_dof)}``, DOF indices or names, for the nodes of both sides; default:
        the structure's DOF map (``"node:x"``, ``"node:y"``, ``"node:z"``).
    name : str
        Contact ``p`` is named ``f"{name}{p}"``.
    relative : bool
        True: the structure's DOFs of ``nodes_a[p]`` are the pair's relative displacement
        ``r = u_b - u_a`` (x, y, z; the interface coordinates of a reduced model), and ``nodes_b`` is
        not used: ``t_k = tangent_k . r``, ``n = -normal . r``.

    Returns
    -------
    list of Contact, length P
        Contact ``p`` moves on its plane: ``t_k = tangent_k . (u_b - u_a)`` (k = 1, 2) and
        ``n = normal . (u_a - u_b)`` (m), an approach growing as ``a`` moves towards ``b``.
    """
    if not hasattr(structure, "add_contact") or not hasattr(structure, "ndof"):
        raise TypeError(f"structure must be a microslip Structure, got {type(structure).__name__}")
    if not isinstance(patch, ContactPatch):
        raise TypeError(f"patch must be a microslip.fe.ContactPatch, got {type(patch).__name__}")
    if not isinstance(law, (MicroslipModel, PressureLaw)):
        raise TypeError(f"law must be a MicroslipModel or a PressureLaw (per unit area), got {type(law).__name__}")
    if dofs is not None:
        dofs = _checks.mapping("dofs", dofs)
    _checks.text("name", name)
    relative = _checks.flag("relative", relative)
    contacts = []
    for p in range(len(patch)):
        a, b = int(patch.nodes_a[p]), int(patch.nodes_b[p])
        da = _node_dofs(a, dofs, structure)
        db = None if relative else _node_dofs(b, dofs, structure)
        directions = []
        for vec, sign in ((patch.tangent1[p], -1.0), (patch.tangent2[p], -1.0), (patch.normal[p], 1.0)):
            d = {}
            for k, c in enumerate(vec.tolist()):
                if c == 0.0:
                    continue
                if relative:  # r = u_b - u_a
                    d[da[k]] = d.get(da[k], 0.0) - sign * c
                else:
                    d[da[k]] = d.get(da[k], 0.0) + sign * c
                    d[db[k]] = d.get(db[k], 0.0) - sign * c
            directions.append(d)
        contacts.append(structure.add_contact(_pair_model(law, float(patch.area[p])),
                                              tangential=directions[:2], normal=directions[2], name=f"{name}{p}"))
    return contacts
