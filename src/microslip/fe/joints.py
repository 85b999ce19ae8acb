"""A bolted lap joint: two plates meshed with scikit-fem, reduced to relative interface coordinates.

Geometry (SI units, origin at the clamped end of the lower plate): two plates of ``length``, ``width``
and ``thickness`` overlap over ``overlap`` in a half-lap (each plate is half as thick over the overlap,
as in the Brake--Reuss beam), so that the assembly is a prismatic beam of ``2 * length - overlap``
with the interface on its mid-plane ``z = thickness / 2``. The lower plate (side ``a``) is clamped at
``x = 0``, the upper plate (side ``b``) at ``x = 2 * length - overlap``. Three bolts cross the overlap
at a quarter, a half and three quarters of it, on the centre line ``y = width / 2``.

Mesh: 27-node hexahedra (``ElementHex2``: no shear locking in bending), one element through each half of
the thickness, a structured grid whose nodes on the interface are the ``P`` node pairs of
:func:`~microslip.fe.contact_patch` (each with its tributary area, normal ``+z`` from ``a`` to ``b`` and
tangents ``x``, ``y``). The size is chosen by the number of contact elements (:data:`PRESETS`).

Bolts: each bolt's clamping force pushes the outer faces towards the interface, spread over the nodes
of the outer faces above and below its washer (by tributary area); around each bolt a block of pairs is
tied (``tied_pairs``: the structure built by :func:`microslip.frequency.jointed_structure` holds them with
the interface's stiffness, stuck and closed: they never slip nor open); every other pair is a contact
element on its plane.

Reduction ("relative coordinates plus tied-interface modes"): the displacements of side ``b``'s
interface nodes are replaced by the relative displacements ``r = u_b - u_a`` of every pair, which are
kept physical; the rest of the structure is represented by its static response to ``r`` and the
lowest ``modes`` normal modes of the structure with the interface tied (``r = 0``: the monolithic
beam), a Craig--Bampton reduction of the structure in relative coordinates. The reduced model has
``3 P + modes`` DOFs: ``3 * 147 + 40 = 481`` for the default of 120 contact elements.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..common._numeric import eigsh_repeatable
from ..common import _checks
from ._optional import require
from .dof_map import DofMap
from .patches import ContactPatch, contact_patch

__all__ = ["LapJoint", "PRESETS", "lap_joint"]

#: structural steel, rounded: Young's modulus (Pa), Poisson's ratio, density (kg/m^3)
STEEL = {"E": 2.0e11, "nu": 0.3, "rho": 7850.0}

def _block(along: int, across: int) -> tuple:
    return tuple((i, j) for i in range(-(along // 2), along // 2 + 1) for j in range(-(across // 2), across // 2 + 1))


#: the meshes by number of contact elements: interface nodes along and across the overlap, and the pairs tied
#: around each bolt as offsets (along, across) in nodes from the bolt's node. Nodes along - 1 is a multiple of 4
#: so that every bolt (a quarter, a half, three quarters of the overlap) sits on a node; the tied pairs cover
#: about the same washer footprint at 120 and 480 contacts (12 x 10 mm and 13 x 9 mm with the default shape);
#: the coarsest mesh, whose bolts are two nodes apart, ties each bolt's line of nodes across the plate.
PRESETS = {30: {"along": 9, "across": 5, "tied": _block(1, 5)},
           120: {"along": 21, "across": 7, "tied": _block(3, 3)},
           480: {"along": 37, "across": 15, "tied": _block(5, 5)}}

#: the most tied-interface modes :func:`lap_joint` keeps
MAX_MODES = 500

#: points closer than this fraction of the plate's length are one point
_SAME_POINT = 1e-9


@dataclass(frozen=True, eq=False)
class LapJoint:
    """A bolted lap joint reduced to relative interface coordinates (from :func:`lap_joint`).

    Attributes
    ----------
    M, K : ndarray, shape (n, n)
        Reduced mass (kg) and stiffness (N/m), ``n = 3 P + modes``: first the relative displacements
        ``r = u_b - u_a`` of the ``P`` interface pairs (x, y, z of pair 0, then of pair 1, ...; m), then
        the tied-interface modal coordinates (kg^1/2 m). The pairs are free (no tie, no contact).
    patch : ContactPatch
        The ``P`` interface pairs (node ids of the full mesh, tributary areas, normal ``+z``); its
        ``nodes_a`` are the pairs' ids for :func:`~microslip.fe.add_patch` with ``relative=True``.
    contact_pairs, tied_pairs : ndarray of int
        Indices into ``patch`` of the pairs that are contact elements, and of those tied around the bolts.
    dofs : dict of int to tuple of 3 int
        ``{patch.nodes_a[p]: (x, y, z)}``: the reduced DOFs of each pair's relative displacement.
    bolt_force : ndarray, shape (n,)
        The reduced static load of the three bolts' clamping (N; ``T^T f``).
    full_bolt_force : ndarray, shape (N,)
        ``f``: that load on the free DOFs of the mesh (N), ``+z`` on the lower plate's bottom face, ``-z``
        on the upper plate's top face, ``bolt_load`` per bolt and face.
    bolt_pairs : list of 3 ndarray of int
        Indices into ``patch`` of each bolt's tied pairs (the first bolt nearest ``x = 0``).
    bolt_positions : ndarray, shape (3, 2)
        ``(x, y)`` of each bolt's axis (m).
    recovery : ndarray, shape (N, n)
        ``T``: every DOF of the full mesh (its ``dof_map``) from the reduced coordinates.
    tied_frequencies : ndarray, shape (modes,)
        Natural frequencies of the structure with the interface tied (rad/s): the monolithic beam's.
    full_M, full_K : scipy.sparse.csr_matrix, shape (N, N)
        The two plates' mass and stiffness on the free DOFs of the mesh (no ties, no contacts).
    dof_map : DofMap
        Node id and component of every row of the full matrices.
    points : ndarray, shape (nodes, 3)
        Coordinates (m) of every node of the mesh (row ``i`` is node id ``i``).
    mesh : tuple of two skfem.MeshHex
        The lower and the upper plate's meshes (their nodes are ids ``0..`` of the lower plate, then
        the upper plate's after them, each plate's nodes in scikit-fem's order of DOFs).
    geometry : dict
        ``length``, ``width``, ``thickness``, ``overlap`` (m), ``E`` (Pa), ``nu``, ``rho`` (kg/m^3),
        ``bolt_load`` (N per bolt).
    """

    M: np.ndarray
    K: np.ndarray
    patch: ContactPatch
    contact_pairs: np.ndarray
    tied_pairs: np.ndarray
    dofs: dict
    bolt_force: np.ndarray
    full_bolt_force: np.ndarray
    bolt_pairs: list
    bolt_positions: np.ndarray
    recovery: np.ndarray
    tied_frequencies: np.ndarray
    full_M: sp.csr_matrix
    full_K: sp.csr_matrix
    dof_map: DofMap
    points: np.ndarray
    mesh: tuple = ()
    geometry: dict = field(default_factory=dict)

    @property
    def ndof(self) -> int:
        """Reduced DOFs, ``3 P + modes``."""
        return self.M.shape[0]

    @property
    def contacts(self) -> int:
        """Number of contact elements (pairs that are not tied)."""
        return int(self.contact_pairs.size)

    @property
    def bolt_dofs(self) -> list:
        """Each bolt's reduced DOFs: the relative displacements (x, y, z) of its tied pairs, 3 arrays of int."""
        return [np.array([d for p in pairs for d in self.dofs[int(self.patch.nodes_a[p])]], dtype=np.int64)
                for pairs in self.bolt_pairs]

    def contact_patch(self) -> ContactPatch:
        """The sub-patch of the contact pairs (tied pairs left out), for :func:`~microslip.fe.add_patch`."""
        i = self.contact_pairs
        p = self.patch
        return ContactPatch(p.nodes_a[i], p.nodes_b[i], p.area[i], p.normal[i], p.tangent1[i], p.tangent2[i],
                            p.distance[i])

    def monolithic_frequency(self) -> float:
        """The first bending frequency (rad/s) of the monolithic clamped--clamped beam, Euler--Bernoulli.

        ``(4.7300)^2 sqrt(E I / (rho A)) / L^2`` with ``I / A = thickness^2 / 12`` and
        ``L = 2 length - overlap``: bending across the thickness (the interface's normal).
        """
        g = self.geometry
        L = 2 * g["length"] - g["overlap"]
        beta = 4.730040744862704  # the first root of cos(x) cosh(x) = 1
        return float(beta ** 2 * np.sqrt(g["E"] * g["thickness"] ** 2 / (12 * g["rho"])) / L ** 2)

    def __repr__(self) -> str:
        return (f"LapJoint(ndof={self.ndof}, pairs={len(self.patch)}, contacts={self.contacts}, "
                f"tied={self.tied_pairs.size}, full_ndof={self.full_M.shape[0]})")


def _plate(skfem, xs, ys, zs, keep_lower_over, x_over: tuple[float, float], material):
    """``(mesh, basis, M, K)`` of one plate: the grid ``xs x ys x zs`` without one half-layer over the overlap.

    The elements of a structured grid come in a few sizes: each size's element matrices are computed once
    (by scikit-fem, on a one-element mesh) and scattered into the plate's matrices.
    """
    mesh = skfem.MeshHex.init_tensor(xs, ys, zs)
    centre = mesh.p[:, mesh.t].mean(axis=1)
    zmid = 0.5 * (zs[0] + zs[-1])
    inside = (centre[0] > x_over[0]) & (centre[0] < x_over[1])
    drop = inside & ((centre[2] > zmid) if keep_lower_over else (centre[2] < zmid))
    mesh = mesh.remove_elements(np.flatnonzero(drop))
    basis = skfem.Basis(mesh, skfem.ElementVector(skfem.ElementHex2()))
    corners = mesh.p[:, mesh.t]  # (3, 8, elements)
    sizes = np.round(corners.max(axis=1) - corners.min(axis=1), 12).T  # (elements, 3)
    kinds, which = np.unique(sizes, axis=0, return_inverse=True)
    which = np.asarray(which).ravel()
    dofs = basis.element_dofs  # (81, elements)
    rows = np.broadcast_to(dofs[:, None, :], (dofs.shape[0],) + dofs.shape).ravel()
    cols = np.broadcast_to(dofs[None, :, :], (dofs.shape[0],) + dofs.shape).ravel()
    Me, Ke = np.empty((dofs.shape[0],) * 2 + (dofs.shape[1],)), np.empty((dofs.shape[0],) * 2 + (dofs.shape[1],))
    for k, (dx, dy, dz) in enumerate(kinds):
        one = skfem.Basis(skfem.MeshHex.init_tensor([0.0, dx], [0.0, dy], [0.0, dz]),
                          skfem.ElementVector(skfem.ElementHex2()))
        m1, k1 = _element_matrices(skfem, one, material)
        local = one.element_dofs[:, 0]
        Me[:, :, which == k] = m1[np.ix_(local, local)][:, :, None]
        Ke[:, :, which == k] = k1[np.ix_(local, local)][:, :, None]
    N = basis.N
    M = sp.coo_matrix((Me.ravel(), (rows, cols)), shape=(N, N)).tocsr()
    K = sp.coo_matrix((Ke.ravel(), (rows, cols)), shape=(N, N)).tocsr()
    return mesh, basis, M, K


def _element_matrices(skfem, basis, material) -> tuple[np.ndarray, np.ndarray]:
    """Dense mass (kg) and stiffness (N/m) of ``basis`` (one element): isotropic linear elasticity."""
    from skfem.helpers import ddot, dot, sym_grad, trace

    E, nu, rho = material
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))

    @skfem.BilinearForm
    def stiffness(u, v, w):
        eu, ev = sym_grad(u), sym_grad(v)
        return 2 * mu * ddot(eu, ev) + lam * trace(eu) * trace(ev)

    @skfem.BilinearForm
    def mass(u, v, w):
        return rho * dot(u, v)

    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is reported by the caller
        return mass.assemble(basis).toarray(), stiffness.assemble(basis).toarray()


def _node_table(basis) -> tuple[np.ndarray, np.ndarray]:
    """``(points, dofs)``: every node's coordinates ``(nodes, 3)`` and its x, y, z DOFs ``(nodes, 3)``."""
    groups = [basis.nodal_dofs, basis.edge_dofs, basis.facet_dofs, basis.interior_dofs]
    dofs = np.concatenate([g for g in groups if g.size], axis=1).T
    return basis.doflocs[:, dofs[:, 0]].T.copy(), dofs


def _grid(a: float, b: float, elements: int) -> np.ndarray:
    return np.linspace(a, b, elements + 1)


def _layout(contacts: int):
    try:
        return PRESETS[contacts]
    except KeyError:
        raise ValueError(f"contacts must be one of {sorted(PRESETS)} (the meshes of the lap joint), "
                         f"got {contacts!r}") from None


def lap_joint(contacts: int = 120, *, modes: int = 40, length: float = 0.24, width: float = 0.03,
              thickness: float = 0.012, overlap: float = 0.12, bolt_load: float = 10e3,
              washer: float = 3.0, E: float = STEEL["E"], nu: float = STEEL["nu"],
              rho: float = STEEL["rho"]) -> LapJoint:
    """A bolted lap joint of two clamped plates, reduced to relative interface coordinates (see the module).

    Parameters
    ----------
    contacts : {30, 120, 480}, default 120
        Contact elements: selects the mesh (:data:`PRESETS`); the interface has 45, 147 or 555 node pairs,
        of which 15, 27 or 75 are tied around the bolts.
    modes : int, default 40
        Tied-interface normal modes kept, 1 to :data:`MAX_MODES` (and fewer than the tied structure's DOFs).
    length, width, thickness : float
        Each plate's size (m); ``length`` along the beam, ``thickness`` across the interface.
    overlap : float
        Length of the overlap (m), below ``length`` and at least its 1/20.
    bolt_load : float
        Each bolt's clamping force (N), positive.
    washer : float, default 3.0
        The bolt's load is spread over the outer faces under a footprint ``washer`` times the tied
        block's (its nodes' tributary areas), at least 1.
    E, nu, rho : float
        Young's modulus (Pa), Poisson's ratio and density (kg/m^3); default structural steel.

    Returns
    -------
    LapJoint
        The reduced matrices (``3 P + modes`` DOFs), the patch, the bolts' static load and the mesh.

    Raises
    ------
    ValueError
        ``contacts`` not a preset, a size or material constant that is not positive and finite, ``nu``
        outside (-1, 0.5), an overlap not shorter than the plates, or ``modes`` above the tied structure's
        DOFs less one.
    ImportError
        scikit-fem is not installed (``pip install microslip[fe]``).

    Examples
    --------
    >>> from microslip.fe import lap_joint
    >>> joint = lap_joint(30, modes=10)  # doctest: +SKIP
    >>> joint.ndof, joint.contacts  # doctest: +SKIP
    (127, 30)
    """
    if isinstance(contacts, (bool, np.bool_)) or not isinstance(contacts, (int, np.integer)):
        raise TypeError(f"contacts must be an integer, one of {sorted(PRESETS)}, got {_checks._show(contacts)}")
    preset = _layout(int(contacts))
    modes = _checks.positive_int("modes", modes, minimum=1)
    if modes > MAX_MODES:
        raise ValueError(f"modes must be at most {MAX_MODES} (tied-interface modes of a beam; the first few matter), "
                         f"got {modes}")
    g = {name: _checks.positive_scalar(name, value) for name, value in (
        ("length", length), ("width", width), ("thickness", thickness), ("overlap", overlap),
        ("bolt_load", bolt_load), ("E", E), ("rho", rho))}
    nu = _checks.in_range("nu", nu, -1.0, 0.5, lo_open=True, hi_open=True)
    washer = _checks.positive_scalar("washer", washer)
    if not washer >= 1.0:
        raise ValueError(f"washer must be at least 1 (a footprint at least the tied block's), got {washer!r}")
    if not g["overlap"] < g["length"]:
        raise ValueError(f"overlap must be shorter than length ({g['length']!r} m), got {g['overlap']!r} m")
    if not g["overlap"] >= g["length"] / 20:
        raise ValueError(f"overlap must be at least length / 20 = {g['length'] / 20!r} m (the mesh's elements "
                         f"are as long outside the overlap as inside), got {g['overlap']!r} m")
    for name in ("width", "thickness"):
        if not g[name] <= g["length"]:
            raise ValueError(f"{name} must be at most length ({g['length']!r} m) for a plate, got {g[name]!r} m")
    skfem = require("skfem", "The lap joint (lap_joint)")

    Lp, W, t, Lo = g["length"], g["width"], g["thickness"], g["overlap"]
    ex, ey = (preset["along"] - 1) // 2, (preset["across"] - 1) // 2  # elements along and across the overlap
    hx = Lo / ex
    # outside the overlap no finer than the 120-contact mesh: the interface is what the presets refine
    outside = max(1, int(round((Lp - Lo) / max(hx, Lo / 10))))
    x_a = np.unique(np.concatenate([_grid(0.0, Lp - Lo, outside), _grid(Lp - Lo, Lp, ex)]))
    x_b = np.unique(np.concatenate([_grid(Lp - Lo, Lp, ex), _grid(Lp, 2 * Lp - Lo, outside)]))
    ys, zs = _grid(0.0, W, ey), _grid(0.0, t, 2)
    material = (g["E"], nu, g["rho"])
    over = (Lp - Lo, Lp)
    mesh_a, basis_a, Ma, Ka = _plate(skfem, x_a, ys, zs, True, over, material)
    mesh_b, basis_b, Mb, Kb = _plate(skfem, x_b, ys, zs, False, over, material)
    for A in (Ma, Ka, Mb, Kb):
        if not np.isfinite(A.data).all():
            raise ValueError(f"the matrices overflow: E = {g['E']!r} Pa and rho = {g['rho']!r} kg/m^3 are too large")
    pa, da = _node_table(basis_a)
    pb, db = _node_table(basis_b)
    na = pa.shape[0]
    points = np.vstack([pa, pb])
    node_dofs = np.vstack([da, db + basis_a.N])  # (nodes, 3), DOFs of the two plates side by side
    M = sp.block_diag([Ma, Mb], format="csr")
    K = sp.block_diag([Ka, Kb], format="csr")
    size = 2 * Lp - Lo
    close = _SAME_POINT * size

    # the interface: side a is the lower plate's top face over the overlap, side b the upper plate's bottom face
    def face_nodes(lo, hi):
        on = (np.abs(points[:, 2] - t / 2) <= close) & (points[:, 0] >= over[0] - close) \
            & (points[:, 0] <= over[1] + close)
        ids = np.flatnonzero(on)
        return ids[(ids >= lo) & (ids < hi)]

    ids_a, ids_b = face_nodes(0, na), face_nodes(na, points.shape[0])
    patch = contact_patch(points, _quads(points, ids_a, flip=False), _quads(points, ids_b, flip=True),
                          tolerance=close)
    P = len(patch)

    # the bolts: tied blocks and the washer footprints on the outer faces
    bolts = np.array([[Lp - Lo + f * Lo, W / 2] for f in (0.25, 0.5, 0.75)])
    hy = W / (preset["across"] - 1)
    h = np.array([hx / 2, hy])  # the interface's node spacing along and across (quadratic elements)
    xy = points[patch.nodes_a, :2]
    offsets = set(preset["tied"])
    steps = [np.round((xy - b) / h).astype(np.int64) for b in bolts]  # node offsets from each bolt's node
    bolt_pairs = [np.array([p for p in range(P) if tuple(d[p]) in offsets], dtype=np.int64) for d in steps]
    tied = np.concatenate(bolt_pairs)
    if tied.size != 3 * len(offsets):  # the presets put a node on every bolt
        raise AssertionError(f"tied pairs: {tied.size}")
    half = np.abs(np.array(preset["tied"])).max(axis=0) * h  # the tied pairs' half-extent along and across (m)
    contact_pairs = np.setdiff1d(np.arange(P), tied)

    f = np.zeros(M.shape[0])
    footprint = np.maximum(washer * (half + h / 2), h / 2) - h / 2  # half-size of the washer's node block
    for b in bolts:
        share = np.all(np.abs(xy - b) <= footprint + close, axis=1)
        weights = patch.area[share] / patch.area[share].sum()
        for sign, z in ((+1.0, 0.0), (-1.0, t)):  # the nut under the lower plate, the head on the upper one
            for (x, y), w in zip(xy[share], weights):
                d = np.hypot(points[:, 0] - x, points[:, 1] - y) + np.abs(points[:, 2] - z)
                node = int(np.argmin(d))
                f[node_dofs[node, 2]] += sign * g["bolt_load"] * w

    # clamp the far ends
    clamped = np.flatnonzero((np.abs(points[:, 0]) <= close) | (np.abs(points[:, 0] - size) <= close))
    free = np.ones(M.shape[0], dtype=bool)
    free[node_dofs[clamped].ravel()] = False
    keep = np.flatnonzero(free)
    new = -np.ones(M.shape[0], dtype=np.int64)
    new[keep] = np.arange(keep.size)
    M, K = (A[keep][:, keep] for A in (M, K))
    M, K = ((A + A.T) / 2 for A in (M, K))  # exactly symmetric (the assembly leaves round-off)
    M, K = M.tocsr(), K.tocsr()
    f = f[keep]
    node_of = np.empty(new.size, dtype=np.int64)
    comp_of = np.empty(new.size, dtype=object)
    for c, name in enumerate("xyz"):
        node_of[node_dofs[:, c]] = np.arange(points.shape[0])
        comp_of[node_dofs[:, c]] = name
    dof_map = DofMap(node_of[keep], list(comp_of[keep]))

    # relative coordinates: u_b = u_a + r on every pair; r kept, the rest condensed onto r plus tied modes
    ia = new[node_dofs[patch.nodes_a]]  # (P, 3)
    ib = new[node_dofs[patch.nodes_b]]
    if (ia < 0).any() or (ib < 0).any():
        raise AssertionError("an interface node is clamped")
    n = keep.size
    S = sp.identity(n, format="lil")
    S[ib.ravel(), ia.ravel()] = 1.0
    S = S.tocsr()
    Kr, Mr = (S.T @ A @ S for A in (K, M))
    b = ib.ravel()  # the relative DOFs take the rows of side b's interface DOFs
    mask = np.ones(n, dtype=bool)
    mask[b] = False
    i = np.flatnonzero(mask)
    if modes > i.size - 1:
        raise ValueError(f"modes must be at most {i.size - 1} (the tied structure's DOFs less one), got {modes}")
    Kii, Kib = Kr[i][:, i].tocsc(), Kr[i][:, b].toarray()
    Mii = Mr[i][:, i].tocsc()
    lu = spla.splu(Kii)
    psi = -lu.solve(Kib)
    op = spla.LinearOperator(Kii.shape, matvec=lu.solve, dtype=float)
    lam, phi = eigsh_repeatable(Kii, k=modes, M=Mii, sigma=0.0, which="LM", OPinv=op)
    order = np.argsort(lam)
    lam, phi = lam[order], phi[:, order]
    Tp = np.zeros((n, b.size + modes))
    Tp[b, np.arange(b.size)] = 1.0
    Tp[i, :b.size] = psi
    Tp[i, b.size:] = phi
    T = S @ Tp
    Mred = T.T @ (M @ T)
    Kred = T.T @ (K @ T)
    Mred, Kred = 0.5 * (Mred + Mred.T), 0.5 * (Kred + Kred.T)
    # the relative coordinates of a pair are rows 3p..3p+2 of the reduced model (b is ib.ravel(), pair-major)
    fred = T.T @ f
    dofs = {int(patch.nodes_a[p]): (3 * p, 3 * p + 1, 3 * p + 2) for p in range(P)}
    geometry = {**{k: g[k] for k in ("length", "width", "thickness", "overlap", "E", "rho", "bolt_load")},
                "nu": nu}
    return LapJoint(Mred, Kred, patch, contact_pairs, tied, dofs, fred, f, bolt_pairs, bolts, T,
                    np.sqrt(np.maximum(lam, 0.0)), M, K, dof_map, points, (mesh_a, mesh_b), geometry)


def _quads(points: np.ndarray, ids: np.ndarray, *, flip: bool) -> list:
    """The quad faces of a structured grid of nodes ``ids`` on a plane ``z = const``, counter-clockwise seen
    from ``+z`` (or clockwise with ``flip``): each cell of the node grid (the sub-quads of the 9-node faces)."""
    xy = points[ids, :2]
    xs, ys = np.unique(np.round(xy[:, 0], 12)), np.unique(np.round(xy[:, 1], 12))
    ix = np.searchsorted(xs, np.round(xy[:, 0], 12))
    iy = np.searchsorted(ys, np.round(xy[:, 1], 12))
    grid = -np.ones((xs.size, ys.size), dtype=np.int64)
    grid[ix, iy] = ids
    if (grid < 0).any():
        raise AssertionError("the interface nodes are not a full grid")
    faces = []
    for a in range(xs.size - 1):
        for c in range(ys.size - 1):
            q = [grid[a, c], grid[a + 1, c], grid[a + 1, c + 1], grid[a, c + 1]]
            faces.append(tuple(int(v) for v in (q[::-1] if flip else q)))
    return faces
