"""A turbine-blade-like elastic body in plane stress, meshed and assembled with scikit-fem.

The body lies in the chord-span plane (``x`` along the chord, ``y`` along the span, origin at
the middle of the root) and has the out-of-plane ``thickness``; from the root up:

* a shank, ``shank_width`` wide and ``shank_height`` high, clamped along its bottom edge
  (``y = 0``, the root);
* a platform, ``platform_width`` wide and ``platform_height`` high, overhanging the shank on
  both sides: dampers press on the underside of the overhangs (``platform_nodes``);
* the airfoil, ``chord`` wide and ``span`` high, whose top middle node is ``tip_node``.

The mesh is a structured grid of 9-node quadrilaterals (biquadratic, ``ElementQuad2``: no shear
locking in bending), refined uniformly to come close to a requested number of DOFs. Node ids
count from 1: the element corners first, then the mid-edge nodes, then the element centres.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from ..common import _checks
from ..common.errors import MicroslipError
from ._optional import require
from .dof_map import DofMap

#: Inconel 718 at room temperature, rounded: Young's modulus (Pa), Poisson's ratio, density (kg/m^3)
NICKEL_ALLOY = {"E": 2.0e11, "nu": 0.3, "rho": 8190.0}

#: the largest number of DOFs :func:`blade` builds (10^5 take about 5 s)
MAX_DOFS = 1_000_000

#: DOFs per element of a large grid of 9-node quadrilaterals: 1 corner, 2 edges, 1 centre, 2 components
_DOFS_PER_ELEMENT = 8

#: points closer than this fraction of the body's size are one point (node look-ups, the clamped edge)
_SAME_POINT = 1e-9


class _Unmeshable(MicroslipError, ValueError):
    """No grid of about the requested DOFs fits the shape (:func:`blade` says which part is to blame)."""


@dataclass(frozen=True, eq=False)
class FEBlade:
    """A clamped blade model (from :func:`blade`).

    Attributes
    ----------
    M, K : scipy.sparse.csr_matrix, shape (ndof, ndof)
        Mass (kg) and stiffness (N/m) of the free DOFs (the root is clamped
        and its DOFs removed).
    dof_map : DofMap
        Node id and component (``x`` or ``y``) of every row.
    platform_nodes : ndarray of int, shape (2 * contact_nodes,)
        Nodes on the underside of the platform where dampers touch: the left
        overhang's from its outer edge inwards, then the right one's.
    tip_node : int
        The node at the middle of the airfoil's top edge (excitation, output).
    xy : ndarray, shape (nodes, 2)
        Coordinates (m) of every node, clamped ones included: row ``i`` is
        node id ``i + 1``.
    node_sets : dict of str to ndarray of int
        Named node sets: ``"platform_left"``, ``"platform_right"``,
        ``"tip"`` and ``"root"`` (the clamped nodes, not in ``dof_map``).
    mesh : skfem.MeshQuad
        The mesh (corner nodes ``mesh.p`` are node ids ``1..mesh.nvertices``).
    """

    M: sp.csr_matrix
    K: sp.csr_matrix
    dof_map: DofMap
    platform_nodes: np.ndarray
    tip_node: int
    xy: np.ndarray
    node_sets: dict = field(default_factory=dict)
    mesh: object = None

    @property
    def ndof(self) -> int:
        """Number of free DOFs."""
        return self.M.shape[0]

    def position(self, node: int) -> np.ndarray:
        """Coordinates ``(x, y)`` (m) of a node id, shape ``(2,)``."""
        node = _checks.positive_int("node", node)
        if node > self.xy.shape[0]:
            raise ValueError(f"node must be a node id in 1..{self.xy.shape[0]}, got {node}")
        return self.xy[node - 1].copy()

    def __repr__(self) -> str:
        return f"FEBlade(ndof={self.ndof}, nodes={self.xy.shape[0]}, tip_node={self.tip_node})"


# -- mesh ------------------------------------------------------------------------------------------
def _divisions(keys, h: float) -> tuple[np.ndarray, np.ndarray]:
    """The sorted key coordinates and how many divisions of at most ``h`` each gap between them gets (floats)."""
    keys = np.unique(np.asarray(keys, dtype=float))
    return keys, np.maximum(1.0, np.ceil(np.diff(keys) / h - 1e-9))


def _lines(keys, h: float) -> np.ndarray:
    """Grid lines through every key coordinate, spaced at most ``h`` apart."""
    keys, n = _divisions(keys, h)
    parts = [np.linspace(a, b, int(k) + 1)[:-1] for a, b, k in zip(keys, keys[1:], n)]
    return np.concatenate(parts + [keys[-1:]])


def _line_count(keys, h: float) -> float:
    """How many grid lines :func:`_lines` would draw (a float: it may be astronomically large)."""
    return float(_divisions(keys, h)[1].sum()) + 1.0


def _cells(rectangles, xkeys, ykeys, h):
    """``(xs, ys, i, j)``: grid lines of spacing about ``h = (hx, hy)`` and the cells ``(i, j)`` inside a rectangle."""
    xs, ys = _lines(xkeys, h[0]), _lines(ykeys, h[1])
    xc, yc = np.meshgrid((xs[:-1] + xs[1:]) / 2, (ys[:-1] + ys[1:]) / 2, indexing="ij")
    inside = np.zeros(xc.shape, dtype=bool)
    for x0, x1, y0, y1 in rectangles:
        inside |= (xc > x0) & (xc < x1) & (yc > y0) & (yc < y1)
    i, j = np.nonzero(inside)
    return xs, ys, i, j


def _dof_count(rectangles, xkeys, ykeys, h) -> int:
    """DOFs (before clamping) of the grid of spacing ``h``: 2 per corner, edge and cell of 9-node quadrilaterals."""
    xs, ys, i, j = _cells(rectangles, xkeys, ykeys, h)
    ny = ys.size
    corners = np.unique(np.concatenate([(i + a) * ny + j + b for a in (0, 1) for b in (0, 1)])).size
    horizontal = np.unique(np.concatenate([i * ny + j, i * ny + j + 1])).size  # edges along x, by left end
    vertical = np.unique(np.concatenate([i * ny + j, (i + 1) * ny + j])).size  # edges along y, by lower end
    return 2 * (corners + horizontal + vertical + i.size)


def _mesh(skfem, rectangles, xkeys, ykeys, dofs: int):
    """The grid whose DOF count (before clamping) is the closest to ``dofs``.

    Spacings ``hx, hy`` near the estimate from the area are tried (aspect ratios up to 1.5): one
    spacing for both directions makes the count jump whenever many intervals of one length gain a
    division together.
    """
    area = sum((x1 - x0) * (y1 - y0) for x0, x1, y0, y1 in rectangles)
    h0 = np.sqrt(_DOFS_PER_ELEMENT * area / dofs)
    factors = np.geomspace(0.7, 1.4, 9)
    trials = [(h0 * a, h0 * b) for a in factors for b in factors if 1 / 1.5 <= a / b <= 1.5]
    # a grid over the bounding box far larger than the body: proportions too extreme to mesh
    trials = [h for h in trials if _line_count(xkeys, h[0]) * _line_count(ykeys, h[1]) <= 20 * dofs]
    counts = [_dof_count(rectangles, xkeys, ykeys, h) for h in trials]
    if not trials or min(counts) > 2 * dofs:
        raise _Unmeshable(f"the shape's proportions need far more than dofs = {dofs} DOFs (a part much longer or "
                          f"thinner than the others); make them less extreme or ask for more dofs")
    h = trials[int(np.argmin([abs(np.log(n / dofs)) for n in counts]))]
    xs, ys, i, j = _cells(rectangles, xkeys, ykeys, h)
    ny = ys.size
    t = np.array([i * ny + j, (i + 1) * ny + j, (i + 1) * ny + j + 1, i * ny + j + 1])
    used, t = np.unique(t, return_inverse=True)
    return skfem.MeshQuad(np.array([xs[used // ny], ys[used % ny]]), t.reshape(4, -1))


# -- assembly --------------------------------------------------------------------------------------
def _assemble(skfem, mesh, E: float, nu: float, rho: float, thickness: float):
    """``(basis, M, K)`` of the whole mesh in plane stress (kg, N/m)."""
    from skfem.helpers import ddot, dot, sym_grad, trace

    basis = skfem.Basis(mesh, skfem.ElementVector(skfem.ElementQuad2()))
    mu = E / (2 * (1 + nu))
    lam = E * nu / (1 - nu ** 2)  # plane stress: the out-of-plane stress is zero

    @skfem.BilinearForm
    def stiffness(u, v, w):
        eu, ev = sym_grad(u), sym_grad(v)
        return thickness * (2 * mu * ddot(eu, ev) + lam * trace(eu) * trace(ev))

    @skfem.BilinearForm
    def mass(u, v, w):
        return rho * thickness * dot(u, v)

    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is reported by the caller
        return basis, mass.assemble(basis).tocsr(), stiffness.assemble(basis).tocsr()


def _nodes(basis) -> tuple[np.ndarray, np.ndarray]:
    """``(xy, dofs)``: coordinates of every node (ids 1..) and its x and y DOF, shape ``(nodes, 2)`` each."""
    groups = [basis.nodal_dofs, basis.facet_dofs]
    if basis.interior_dofs.size:
        groups.append(basis.interior_dofs)
    dofs = np.concatenate(groups, axis=1).T
    return basis.doflocs[:, dofs[:, 0]].T.copy(), dofs


def _elastic_body(rectangles, xkeys, ykeys, dofs: int, *, E: float, nu: float, rho: float, thickness: float,
                  clamp_y: float):
    """Mesh, assemble and clamp the union of ``rectangles`` ``(x0, x1, y0, y1)`` along ``y = clamp_y``.

    Returns ``(M, K, dof_map, xy, root, mesh)``: the free DOFs' sparse matrices, their
    :class:`DofMap`, every node's coordinates (row ``i``: node ``i + 1``) and the clamped node ids.
    """
    skfem = require("skfem", "The finite-element blade")
    mesh = _mesh(skfem, rectangles, xkeys, ykeys, dofs)
    basis, M, K = _assemble(skfem, mesh, E, nu, rho, thickness)
    if not (np.isfinite(M.data).all() and np.isfinite(K.data).all()):
        raise ValueError(f"the matrices overflow: E = {E!r} Pa, rho = {rho!r} kg/m^3 and thickness = "
                         f"{thickness!r} m are too large")
    xy, node_dofs = _nodes(basis)
    size = max(x1 - x0 for x0, x1, _, _ in rectangles) + max(y1 - y0 for _, _, y0, y1 in rectangles)
    root = np.flatnonzero(np.abs(xy[:, 1] - clamp_y) <= _SAME_POINT * size)
    free = np.ones(basis.N, dtype=bool)
    free[node_dofs[root].ravel()] = False
    node_of = np.empty(basis.N, dtype=np.int64)
    comp_of = np.empty(basis.N, dtype=object)
    for c, name in enumerate(("x", "y")):
        node_of[node_dofs[:, c]] = np.arange(1, xy.shape[0] + 1)
        comp_of[node_dofs[:, c]] = name
    keep = np.flatnonzero(free)
    dof_map = DofMap(node_of[keep], list(comp_of[keep]))
    M, K = (A[keep][:, keep] for A in (M, K))
    # exactly symmetric (the assembly leaves round-off of 1e-16 relative), as a file reader returns it
    return ((M + M.T) / 2).tocsr(), ((K + K.T) / 2).tocsr(), dof_map, xy, root + 1, mesh


def _node_at(xy, x: float, y: float, size: float) -> int:
    """The id of the node at ``(x, y)`` (the grid puts one there)."""
    d = np.hypot(xy[:, 0] - x, xy[:, 1] - y)
    k = int(np.argmin(d))
    assert d[k] <= _SAME_POINT * size, (x, y, d[k])
    return k + 1


#: the parameters that are the sizes (m) of the blade's parts
_PARTS = ("span", "chord", "platform_width", "platform_height", "shank_width", "shank_height")


def _dimensions(g: dict, n_contact: int, size: float) -> dict[str, float]:
    """``{label: length}`` (m) of every part and of every distance between grid lines across the chord."""
    out = {name: g[name] for name in _PARTS}
    if n_contact > 1:
        out["contact_width / (contact_nodes - 1)"] = g["contact_width"] / (n_contact - 1)
    W = g["platform_width"]
    keys = sorted([(0.0, "0"), (g["shank_width"] / 2, "shank_width / 2"), (g["chord"] / 2, "chord / 2"),
                   (W / 2, "platform_width / 2"), (W / 2 - g["contact_width"], "platform_width / 2 - contact_width")])
    for (a, name_a), (b, name_b) in zip(keys, keys[1:]):
        if b - a > _SAME_POINT * size:  # closer ones are one grid line
            out[f"the distance from x = {name_a} to x = {name_b}"] = b - a
    return out


def _extreme(dofs: int, W: float, H: float, label: str, value: float, advice: str) -> ValueError:
    return ValueError(f"the shape's proportions need far more than dofs = {dofs} DOFs: the blade is {W:.3g} m wide "
                      f"(platform_width) and {H:.3g} m high (shank_height + platform_height + span), and its "
                      f"smallest dimension, {label}, is {value:.3g} m; {advice}")


def blade(dofs: int = 2000, *, span: float = 0.06, chord: float = 0.02, platform_width: float = 0.04,
          platform_height: float = 0.004, shank_width: float = 0.012, shank_height: float = 0.015,
          thickness: float = 0.003, contact_width: float = 0.004, contact_nodes: int = 3,
          E: float = NICKEL_ALLOY["E"], nu: float = NICKEL_ALLOY["nu"], rho: float = NICKEL_ALLOY["rho"]) -> FEBlade:
    """A blade with a platform in plane stress, clamped at its root (see the module for the shape).

    Parameters
    ----------
    dofs : int
        Number of DOFs to come close to (before clamping), 300 to 10^6:
        within 6 % from 10^3 to 10^5 with the default shape (10^5 take
        about 5 s to build). The grid needs a line through every corner and
        contact node, so coarse requests may give more (at most twice).
    span, chord : float
        Airfoil height and width (m).
    platform_width, platform_height : float
        Platform size (m); wider than the airfoil and the shank.
    shank_width, shank_height : float
        Shank size (m) below the platform; its bottom edge is clamped.
    thickness : float
        Out-of-plane thickness (m) of the whole body.
    contact_width : float
        Width (m) of the contact patch on the underside of each platform
        overhang, from its outer edge; at most the overhang.
    contact_nodes : int
        Nodes per patch, evenly spaced across it, outer edge included; at
        most ``dofs / 6``.
    E, nu, rho : float
        Young's modulus (Pa), Poisson's ratio and density (kg/m^3); default
        a nickel alloy (Inconel 718 at room temperature).

    Returns
    -------
    FEBlade

    Raises
    ------
    ValueError
        A size that is not positive, a platform not wider than the airfoil
        and the shank, a contact patch wider than the overhang or too
        narrow for its nodes, proportions too extreme to mesh with ``dofs``
        (a part thinner than 1e-9 of the blade's width plus height, with
        any ``dofs``; the message names the smallest dimension), a material
        so stiff or heavy that the matrices overflow, ``nu`` outside
        (-1, 0.5), ``dofs`` outside 300..1e6 or ``contact_nodes`` above
        ``dofs / 6``.
    ImportError
        scikit-fem is not installed (``pip install microslip[fe]``).

    Examples
    --------
    >>> from microslip.fe import blade, natural_frequencies
    >>> b = blade(2000)  # doctest: +SKIP
    >>> natural_frequencies(b.M, b.K, 3)  # doctest: +SKIP
    """
    dofs = _checks.positive_int("dofs", dofs, minimum=300)
    if dofs > MAX_DOFS:
        raise ValueError(f"dofs must be at most {MAX_DOFS} (a plane model needs no more), got {dofs}")
    g = {name: _checks.positive_scalar(name, value) for name, value in (
        ("span", span), ("chord", chord), ("platform_width", platform_width), ("platform_height", platform_height),
        ("shank_width", shank_width), ("shank_height", shank_height), ("thickness", thickness),
        ("contact_width", contact_width), ("E", E), ("rho", rho))}
    nu = _checks.in_range("nu", nu, -1.0, 0.5, lo_open=True, hi_open=True)
    n_contact = _checks.positive_int("contact_nodes", contact_nodes, minimum=1)
    if n_contact > dofs // 6:
        raise ValueError(f"contact_nodes must be at most dofs / 6 = {dofs // 6}, got {n_contact}: each contact node "
                         f"puts a grid line of at least 3 nodes (6 DOFs) across each overhang, and the grid has at "
                         f"most 2 x dofs DOFs")
    W = g["platform_width"]
    for name in ("chord", "shank_width"):
        if g[name] >= W:
            raise ValueError(f"platform_width ({W!r} m) must exceed {name} ({g[name]!r} m): the platform "
                             f"overhangs the airfoil and the shank")
    overhang = (W - g["shank_width"]) / 2
    if g["contact_width"] > overhang:
        raise ValueError(f"contact_width must be at most the platform's overhang beyond the shank "
                         f"({overhang!r} m), got {g['contact_width']!r}")
    y1 = g["shank_height"]
    y2 = y1 + g["platform_height"]
    y3 = y2 + g["span"]
    size = W + y3
    parts = {name: g[name] for name in _PARTS}
    thinnest = min(parts, key=parts.get)
    if parts[thinnest] <= _SAME_POINT * size:  # so thin that its edges would be one grid line
        raise _extreme(dofs, W, y3, thinnest, parts[thinnest], "make them less extreme")
    if n_contact > 1 and g["contact_width"] / (n_contact - 1) <= _SAME_POINT * size:
        raise ValueError(f"contact_width ({g['contact_width']!r} m) is too narrow for contact_nodes = {n_contact} "
                         f"distinct nodes")
    rects = [(-g["shank_width"] / 2, g["shank_width"] / 2, 0.0, y1), (-W / 2, W / 2, y1, y2),
             (-g["chord"] / 2, g["chord"] / 2, y2, y3)]
    right = np.linspace(W / 2, W / 2 - g["contact_width"], n_contact) if n_contact > 1 else np.array([W / 2])
    xkeys = np.concatenate([[r[0] for r in rects], [r[1] for r in rects], [0.0], right, -right])
    try:
        M, K, dof_map, xy, root, mesh = _elastic_body(rects, xkeys, [0.0, y1, y2, y3], dofs, E=g["E"], nu=nu,
                                                      rho=g["rho"], thickness=g["thickness"], clamp_y=0.0)
    except _Unmeshable:
        label, value = min(_dimensions(g, n_contact, size).items(), key=lambda item: item[1])
        raise _extreme(dofs, W, y3, label, value, "make them less extreme or ask for more dofs") from None
    left_ids = np.array([_node_at(xy, -x, y1, size) for x in right])
    right_ids = np.array([_node_at(xy, x, y1, size) for x in right])
    tip = _node_at(xy, 0.0, y3, size)
    sets = {"platform_left": left_ids, "platform_right": right_ids, "tip": np.array([tip]), "root": root}
    return FEBlade(M, K, dof_map, np.concatenate([left_ids, right_ids]), tip, xy, sets, mesh)
