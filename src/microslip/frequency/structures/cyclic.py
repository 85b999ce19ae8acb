"""Cyclic symmetry: one sector of a bladed disk solved for a travelling-wave (engine-order) excitation.

A disk of ``N`` identical sectors, each with the matrices of one sector including
its left and right boundary DOFs; the right boundary of sector ``s`` is the left
boundary of sector ``s + 1``. Under an engine-order ``EO`` excitation every sector
sees the same forcing, sector ``s + 1`` a fraction ``EO / N`` of a period later:

``q_{s+1}(time) = q_s(time - 2 pi EO / (N omega))``,

so harmonic ``h`` of the response lives in nodal diameter ``h EO mod N``: its
complex amplitude (``z = a - i b`` of ``a cos + b sin``) on sector ``s + 1`` is
``z_s exp(-i phi_h)`` with ``phi_h = 2 pi h EO / N``. The static term is the
zero-diameter one (centrifugal preloads). For each harmonic the right boundary
is eliminated, ``q_R = exp(-i phi_h) R q_L``, and the sector's matrices become the
complex Hermitian ``T_h^H A T_h`` on the sector's independent DOFs (all but the
right boundary). ``R`` is the identity when the DOFs are in frames that turn
with the sector (``frame="cylindrical"``, the default) and the rotation by
``2 pi / N`` about the disk's axis on each boundary node's ``(x, y(, z))`` when
they are in the global Cartesian frame (``frame="cartesian"``, :mod:`.frames`).
Contacts may join a sector to the next one (:meth:`CyclicStructure.next`):
their displacement takes the next sector's DOFs through the same phase (and
``R^T`` in the Cartesian frame), and their force acts back on this sector's
DOFs through the previous sector's contact (the transpose of that map).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ...common import _checks
from ...model import MicroslipModel
from ...fe.files import read_matrices
from . import frames
from .structure import Contact, Structure, direction, dof_index, dof_indices, lists_two_directions


@dataclass(frozen=True)
class NextDof:
    """DOF ``dof`` of the next sector, a key of a contact's direction (from :meth:`CyclicStructure.next`)."""

    dof: int


def _dof_list(name: str, values, ndof: int, dof_map=None) -> np.ndarray:
    return dof_indices(name, values, ndof, dof_map)


class CyclicStructure(Structure):
    """One sector of a cyclically symmetric structure (a bladed disk) with its contacts.

    Parameters
    ----------
    M, C, K : array_like or scipy.sparse matrix, shape (ndof, ndof)
        Mass (kg), damping (N s/m) and stiffness (N/m) of one sector,
        including its left and right boundary DOFs; ``C`` may be None.
    sectors : int
        Number of sectors ``N`` of the whole disk (at least 3).
    left, right : sequence, length k
        The boundaries: ``right[j]`` of sector ``s`` is ``left[j]`` of sector
        ``s + 1``. Each entry is a DOF (an index, or a name ``"node:component"``
        with a ``dof_map``) or a tuple of one node's DOFs: in the Cartesian
        frame its translation (or rotation) ``(x, y)`` or ``(x, y, z)``, which
        the rotation turns together, or ``(j,)`` for a DOF that does not turn.
        With a DOF map, DOFs given one by one are grouped by node.
    dof_map : microslip.fe.DofMap, optional
        Names of the sector's DOFs (``"node:component"``), as for :class:`Structure`.
    frame : {"cylindrical", "cartesian"}, default "cylindrical"
        The frame of the sector's DOFs. ``"cylindrical"``: every DOF in a
        frame that turns with the sector (the nodal cylindrical frames
        ``(r, theta, z)`` of ANSYS ``CECYC``/``CPCYC`` or Nastran ``CYAX``), so
        ``right[j]`` equals the next sector's ``left[j]`` as it is.
        ``"cartesian"``: every DOF in the global Cartesian frame (a sector
        exported without cyclic coordinates): the right boundary is the left
        one turned by ``R``, the rotation by ``2 pi / N`` about the axis, and
        each boundary node's tuple turns with it, ``u_right = R u_left``.
    axis : array_like, shape (3,), default (0, 0, 1)
        The disk's axis of rotation (any length), through ``point``; the
        next sector is this one turned by ``+2 pi / N`` about it (right hand).
        With 2-D nodes (tuples ``(x, y)``) it must lie along z.
    point : array_like, shape (2,) or (3,), optional
        A point of the axis (m); default the origin.
    coordinates : array_like or mapping, optional
        The boundary nodes' positions (m), to check that each right node is
        its left node turned by ``R``: an array ``(2, nodes, 2 or 3)``
        (``[0]`` the left nodes', ``[1]`` the right nodes', one node per tuple
        of ``left``, or per DOF given alone) or, with a ``dof_map``,
        ``{node id: (x, y(, z))}``. A right node farther than
        :data:`~.frames.GEOMETRY_TOLERANCE` (1e-6) times the largest boundary
        radius from its left node turned is refused, naming the node and the
        distance. Required with ``frame="cartesian"``.
    nodes : sequence of tuples, optional
        Cartesian frame only: the sector's other nodes' tuples ``(x, y(, z))``
        (or ``(j,)``), which turn with the sector. A contact naming a DOF of
        the next sector (:meth:`next`) needs that DOF in a tuple of ``left``
        or of ``nodes``; :meth:`assembled` turns them into the global frame.
        Default: with a ``dof_map``, every node's x, y(, z) and rx, ry(, rz)
        off the boundaries; else none.

    Notes
    -----
    The sector's matrices must not couple its left and right boundary directly
    beyond what one sector's elements do (the usual FE sector). Solve with
    :func:`~microslip.frequency.frequency_response` and ``engine_order=EO``; the
    result reports this sector's DOFs, numbered as in ``M``, ``C``, ``K``. Which
    quantity is in which frame: the user guide's page "Bladed disks, dampers and
    design curves".

    Examples
    --------
    >>> import numpy as np
    >>> from microslip import MicroslipModel
    >>> from microslip.frequency import CyclicStructure
    >>> K = np.array([[2e6, -1e6, 0], [-1e6, 2e6, -1e6], [0, -1e6, 1e6]])
    >>> disk = CyclicStructure(np.eye(3) * 0.1, None, K, sectors=8, left=[0], right=[2])
    >>> c = disk.add_contact(MicroslipModel([1e4], [1e6], [0.0], 0.5), tangential={1: 1.0, disk.next(1): -1.0},
    ...                      approach=1e-6)
    >>> disk.independent.size
    2

    In the global Cartesian frame, two nodes (x, y) per sector, the right one
    the left one turned by 45 degrees about z:

    >>> r = 0.1 * np.array([[1.0, 0.0], [np.cos(np.pi / 4), np.sin(np.pi / 4)]])
    >>> K4 = np.kron(np.array([[2e6, -1e6], [-1e6, 2e6]]), np.eye(2))
    >>> disk = CyclicStructure(np.eye(4) * 0.1, None, K4, sectors=8, left=[(0, 1)], right=[(2, 3)],
    ...                        frame="cartesian", coordinates=[r[:1], r[1:]])
    >>> disk.boundary_rotation.toarray().round(3)
    array([[ 0.707, -0.707],
           [ 0.707,  0.707]])
    """

    def __init__(self, M, C, K, *, sectors: int, left, right, dof_map=None, frame: str = "cylindrical",
                 axis=(0.0, 0.0, 1.0), point=None, coordinates=None, nodes=None):
        super().__init__(M, C, K, dof_map=dof_map)
        self.sectors = _checks.positive_int("sectors", sectors, minimum=3)
        self.frame = _checks.one_of("frame", frame, frames.FRAMES)
        self.axis = frames.unit_axis(axis)
        self.point = frames.axis_point(point)
        boundary = frames.pair(frames.boundary_elements("left", left, self.ndof, self.dof_map),
                               frames.boundary_elements("right", right, self.ndof, self.dof_map), self.frame,
                               self.dof_map)
        self.left, self.right = boundary.left, boundary.right
        both = np.intersect1d(self.left, self.right)
        if both.size:
            raise ValueError(f"a DOF cannot be on both boundaries: DOF {int(both[0])} is in left and right")
        self._boundary = boundary
        if self.frame == "cartesian" and self._planar() and abs(self.axis[2]) < 1.0 - 1e-12:
            raise ValueError(f"axis must lie along z for 2-D nodes (x, y), got axis = {frames.xyz_text(self.axis)}")
        #: the boundary nodes' positions (m), ``(2, nodes, 3)``: left, right; None when not given
        self.coordinates = (None if coordinates is None
                            else frames.boundary_coordinates(coordinates, boundary, self.dof_map))
        if self.coordinates is None and self.frame == "cartesian":
            raise ValueError("coordinates must be given with frame='cartesian' (the boundary nodes' positions, "
                             "(2, nodes, 2 or 3) m), to check that the right boundary is the left one turned by "
                             f"2 pi / {self.sectors} about the axis")
        if self.coordinates is not None:
            if (self.coordinates[..., 2].any() or self.point[2]) and self._planar():
                raise ValueError("coordinates: 2-D nodes (x, y) turn about an axis along z, in the plane z = 0")
            frames.check_geometry(self.coordinates, boundary, self.axis, self.point, self.sectors)
        if nodes is not None and self.frame != "cartesian":
            raise ValueError("nodes is for frame='cartesian' (the nodes whose DOFs turn with the sector); in the "
                             "cylindrical frame every DOF already turns with its sector")
        #: the rotation ``R`` (3, 3) from this sector to the next (identity in the cylindrical frame)
        self.rotation = (frames.rotation(self.axis, 2 * np.pi / self.sectors) if self.frame == "cartesian"
                         else np.eye(3))
        self._vectors = [] if self.frame != "cartesian" else (
            [v for pair in boundary.vectors for v in pair]
            + frames.node_vectors(nodes, self.ndof, self.dof_map, np.concatenate([self.left, self.right]),
                                  self.rotation))
        self._next_parts = frames.blocks(self._vectors, self.rotation, "nodes")
        #: ``(k, k)`` sparse: the right boundary from the left one, ``u_right = boundary_rotation @ u_left``
        #: in the order of :attr:`left` and :attr:`right` (identity in the cylindrical frame)
        self.boundary_rotation = frames.boundary_rotation(boundary, self.rotation)
        mask = np.ones(self.ndof, dtype=bool)
        mask[self.right] = False
        self.independent = np.flatnonzero(mask)
        #: each contact's direction on the next sector's DOFs as given (in its frame), ``(tangential, normal)``
        self.next_directions: list[tuple[np.ndarray, np.ndarray]] = []

    def _planar(self) -> bool:
        """Nodes given as 2-D tuples ``(x, y)`` (the Cartesian frame's vectors all of two components)."""
        comps = {len(v.components) for pair in self._boundary.vectors for v in pair} - {0}
        return comps == {2}

    def _cyclic_arguments(self, position=None) -> dict:
        """The keyword arguments (plain lists) that give another sector this one's symmetry and frame.

        ``position`` maps this sector's DOFs to the other's (a Craig--Bampton
        model's kept DOFs); None keeps the numbers (a damper's DOFs appended).
        A tuple of ``nodes`` the other lacks is left out (its z only: kept as
        ``(x, y)``).
        """
        where = (lambda d: int(d)) if position is None else (lambda d: int(position[int(d)]))
        b = self._boundary
        if self.frame == "cartesian":
            pairs = [(vl.dofs, vr.dofs, vl.node) for vl, vr in b.vectors]
        else:
            pairs = [(dl, dr, j) for j, (dl, dr, _) in enumerate(b.nodes)]
        out = {"sectors": self.sectors, "frame": self.frame, "axis": self.axis.tolist(), "point": self.point.tolist(),
               "left": [[where(d) for d in dl] for dl, _, _ in pairs],
               "right": [[where(d) for d in dr] for _, dr, _ in pairs]}
        if self.coordinates is not None:
            out["coordinates"] = self.coordinates[:, [j for _, _, j in pairs]].tolist()
        if self.frame == "cartesian":
            out["nodes"] = []
            taken = set(np.concatenate([self.left, self.right]).tolist())
            for v in self._vectors:
                if set(v.dofs) & taken:
                    continue
                kept = [d for d in v.dofs if position is None or int(d) in position]
                if len(kept) == len(v.dofs) or (len(v.dofs) == 3 and kept == list(v.dofs[:2])):
                    out["nodes"].append([where(d) for d in kept])
        return out

    @classmethod
    def from_files(cls, path=None, *, sectors: int, left, right, M=None, K=None, C=None, dof_map=None,
                   names=None, frame: str = "cylindrical", axis=(0.0, 0.0, 1.0), point=None, coordinates=None,
                   nodes=None, format=None) -> CyclicStructure:
        """One sector from finite-element matrix files, as :meth:`Structure.from_files
        <microslip.frequency.Structure.from_files>` (``format`` too); ``sectors``, ``left``, ``right``, ``frame``, ``axis``,
        ``point``, ``coordinates`` and ``nodes`` as in the class (the boundaries may be named ``"node:component"``
        with a ``dof_map``).

        Examples
        --------
        >>> disk = CyclicStructure.from_files("sector.mat", sectors=24, dof_map="sector_dofs.csv",
        ...                                   left=["1014:x", "1014:y"], right=["2014:x", "2014:y"])  # doctest: +SKIP
        """
        m = read_matrices(path, M=M, K=K, C=C, dof_map=dof_map, names=names, format=format)
        return cls(m.M, m.C, m.K, sectors=sectors, left=left, right=right, dof_map=m.dof_map, frame=frame, axis=axis,
                   point=point, coordinates=coordinates, nodes=nodes)

    def __repr__(self) -> str:
        return (f"CyclicStructure(ndof={self.ndof}, sectors={self.sectors}, boundary={self.left.size}, "
                f"frame={self.frame!r}, contacts={len(self.contacts)})")

    def next(self, dof) -> NextDof:
        """DOF ``dof`` (an index, or a name ``"node:component"`` with a DOF map) of the next sector, for a contact's
        ``tangential`` or ``normal`` mapping."""
        if isinstance(dof, str):
            return NextDof(dof_index("dof", dof, self.ndof, self.dof_map))
        i = _checks.positive_int("dof", dof, minimum=0)
        if i >= self.ndof:
            raise ValueError(f"dof: DOF {i} is out of range for a sector with {self.ndof} DOFs")
        return NextDof(i)

    def _split(self, name: str, spec):
        """``(own, next)`` direction vectors of a contact direction that may name next-sector DOFs."""
        own, nxt = {}, {}
        if isinstance(spec, Mapping):
            for key, coef in spec.items():
                (nxt if isinstance(key, NextDof) else own)[key.dof if isinstance(key, NextDof) else key] = coef
            b_own = direction(name, own, self.ndof, allow_none=True, dof_map=self.dof_map)
            b_next = direction(name, nxt, self.ndof, allow_none=True, dof_map=self.dof_map)
        else:
            b_own = direction(name, spec, self.ndof, allow_none=True, dof_map=self.dof_map)
            b_next = np.zeros(self.ndof)
        for b, where in ((b_own, ""), (b_next, " of the next sector")):
            on_right = np.intersect1d(np.flatnonzero(b), self.right)
            if on_right.size:
                j = int(np.flatnonzero(self.right == on_right[0])[0])
                raise ValueError(f"{name}: DOF {int(on_right[0])}{where} is on the right boundary, which is the next "
                                 f"sector's left boundary: name it as left DOF {int(self.left[j])} of the sector after")
        if self.frame == "cartesian":
            known = np.concatenate([v.dofs for v in self._vectors]) if self._vectors else np.zeros(0, np.int64)
            loose = np.setdiff1d(np.flatnonzero(b_next), known)
            if loose.size:
                raise ValueError(f"{name}: DOF {int(loose[0])} of the next sector is in no node's tuple: in the "
                                 f"Cartesian frame the next sector's DOFs are turned by 2 pi / {self.sectors}, so "
                                 f"its node must be known: a tuple of left, or of nodes=[(x, y(, z)), ...] (or a DOF "
                                 f"map); (j,) for a DOF that does not turn")
        return b_own, b_next

    def add_contact(self, model: MicroslipModel, *, tangential, normal=None, preload: float | None = None,
                    approach: float | None = None, name: str | None = None) -> Contact:
        """Attach a contact; its directions may mix this sector's DOFs and the next sector's (``disk.next(j)``).

        Parameters are those of :meth:`Structure.add_contact
        <microslip.frequency.Structure.add_contact>`; a key ``disk.next(j)`` in
        ``tangential`` or ``normal`` names DOF ``j`` of the next sector.
        ``preload`` acts along the whole normal direction (on this sector's
        DOFs and, through the previous sector's contact, on the next's).
        """
        if not isinstance(model, MicroslipModel):
            raise TypeError(f"model must be a microslip MicroslipModel, got {type(model).__name__}")
        if lists_two_directions(tangential, self.ndof):
            raise ValueError("tangential: a contact of a cyclic sector moves along one direction; two tangential "
                             "directions (a contact on its plane) are for a Structure")
        bt, bt_next = self._split("tangential", tangential)
        if not (bt.any() or bt_next.any()):
            raise ValueError("tangential must not be all zeros")
        bn, bn_next = self._split("normal", normal) if normal is not None else (np.zeros(self.ndof),) * 2
        # the checks of a plain contact, on the own part (the next part is checked above)
        proxy = super().add_contact(model, tangential=bt if bt.any() else bt_next, normal=normal if normal is None
                                    else (bn if bn.any() else bn_next), preload=preload, approach=approach, name=name)
        contact = Contact(model, bt, bn, proxy.preload, proxy.approach, proxy.name)
        self.contacts[-1] = contact
        self.next_directions.append((bt_next, bn_next))
        return contact

    def preload_force(self) -> np.ndarray:
        """Static force on the sector (N), ``(ndof,)``: preloads along own and next-sector normals, static forces."""
        f = self.static_force.copy()
        for c, (_, bn_next) in zip(self.contacts, self.next_directions):
            f += c.preload * (c.normal + frames.turn_back(bn_next, self._next_parts))
        return f

    def contact_directions_next(self) -> tuple[np.ndarray, np.ndarray]:
        """The contacts' next-sector directions ``(Bt_next, Bn_next)``, shape ``(ndof, nc)`` each, on the next
        sector's DOFs in its own frame (the frame of this sector's: the given ones turned back by ``R^T`` in the
        Cartesian frame)."""
        nc = len(self.contacts)
        turned = [[frames.turn_back(b, self._next_parts) for b in pair] for pair in self.next_directions]
        Bt = np.array([t for t, _ in turned]).T.reshape(self.ndof, nc)
        Bn = np.array([n for _, n in turned]).T.reshape(self.ndof, nc)
        return Bt, Bn

    def stuck_stiffness(self):
        """Not defined for a sector alone: it depends on the nodal diameter (see :meth:`matrices`)."""
        raise ValueError("a cyclic sector's stiffness depends on the nodal diameter: use "
                         "CyclicStructure.matrices(phase) for the sector's matrices in one diameter")

    # -- the sector's matrices in a nodal diameter ------------------------------------------
    def phase(self, harmonic: int, engine_order: int) -> float:
        """``phi_h = 2 pi h EO / N`` (rad): the phase lag of harmonic ``h`` from one sector to the next."""
        h = _checks.positive_int("harmonic", harmonic, minimum=0)
        eo = _checks.positive_int("engine_order", engine_order, minimum=0)
        return 2.0 * np.pi * ((h * eo) % self.sectors) / self.sectors

    def constraint(self, phi: float):
        """``T`` (sparse, ``(ndof, len(independent))``): every DOF from the independent ones,
        ``q_R = e^{-i phi} R q_L`` (``R`` :attr:`boundary_rotation`, the identity in the cylindrical frame)."""
        phi = _checks.real_scalar("phi", phi)
        col = np.empty(self.ndof, dtype=np.int64)
        col[self.independent] = np.arange(self.independent.size)
        Rb = self.boundary_rotation.tocoo()
        rows = np.concatenate([self.independent, self.right[Rb.row]])
        cols = np.concatenate([col[self.independent], col[self.left[Rb.col]]])
        shift = np.exp(-1j * phi) if phi else 1.0
        vals = np.concatenate([np.ones(self.independent.size), Rb.data * shift])
        return sp.csr_matrix((vals, (rows, cols)), shape=(self.ndof, self.independent.size))

    def matrices(self, phi: float):
        """``(M, C, K)`` on the independent DOFs for the phase ``phi`` (complex Hermitian; real for 0)."""
        T = self.constraint(phi)  # checks phi
        out = []
        for A in (self.M, self.C, self.K):
            A = sp.csr_matrix(A)
            out.append((T.conj().T @ A @ T).tocsr())
        if not phi:
            out = [A.real.tocsr() if np.iscomplexobj(A.data) else A for A in out]
        return tuple(out)

    # -- the whole disk, assembled (to check a sector solution against) -----------------------
    def _whole_index(self, sector: int, dofs) -> np.ndarray:
        """DOF numbers in :meth:`assembled` of this sector's ``dofs`` placed in sector ``sector`` (in the Cartesian
        frame a node's tuple there is turned: :meth:`_sector_map`)."""
        ni = self.independent.size
        local = np.empty(self.ndof, dtype=np.int64)
        local[self.independent] = np.arange(ni)
        local[self.right] = local[self.left]
        owner = np.zeros(self.ndof, dtype=np.int64)
        owner[self.right] = 1  # the right boundary is the next sector's left one
        dofs = np.asarray(dofs, dtype=np.int64)
        return ((sector + owner[dofs]) % self.sectors) * ni + local[dofs]

    def _sector_map(self, sector: int) -> sp.csr_matrix:
        """``A_s`` (sparse, ``(ndof, sectors * len(independent))``): sector ``sector``'s DOFs, in its own frame,
        from the whole disk's of :meth:`assembled` (``u_s = A_s w``).

        Sector ``s``'s independent DOFs are ``s * n + k`` (``n = len(independent)``), its right boundary is sector
        ``s + 1``'s left one; in the Cartesian frame every node's tuple is turned by ``s 2 pi / N`` into the global
        frame (``w = R^s u``), so ``u_s = (R^s)^T w`` on it.
        """
        N, ni = self.sectors, self.independent.size
        col = self._whole_index(sector, np.arange(self.ndof))
        turned = np.zeros(self.ndof, dtype=bool)
        rows, cols, vals = [], [], []
        if self.frame == "cartesian" and sector % N:
            R = frames.rotation(self.axis, 2 * np.pi * (sector % N) / N)
            for dofs, B in frames.blocks(self._vectors, R, "nodes"):
                c = B.shape[0]
                for a in range(c):  # u[dofs[:, a]] = sum_b B[b, a] w[col[dofs[:, b]]]
                    for b in range(c):
                        if B[b, a]:
                            rows.append(dofs[:, a])
                            cols.append(col[dofs[:, b]])
                            vals.append(np.full(dofs.shape[0], B[b, a]))
                turned[dofs] = True
        rest = np.flatnonzero(~turned)
        rows, cols = np.concatenate(rows + [rest]), np.concatenate(cols + [col[rest]])
        vals = np.concatenate(vals + [np.ones(rest.size)])
        return sp.csr_matrix((vals, (rows, cols)), shape=(self.ndof, N * ni))

    def assembled(self, stiffness_scale=None, *, scaled_dofs=None) -> Structure:
        """The whole disk as one :class:`Structure`: every sector's matrices, contacts and static forces.

        Sector ``s``'s independent DOFs (:attr:`independent`, in order) are
        DOFs ``s * n + k`` (``n = len(independent)``); its right boundary is
        sector ``s + 1``'s left one. In the Cartesian frame the disk is in the
        global frame: sector ``s`` turned by ``s 2 pi / N`` about the axis,
        every node's tuple (of ``left``, ``right`` and ``nodes``) turned with
        it (a DOF in no tuple stays in its sector's frame); in the
        cylindrical frame each sector's DOFs stay in their own frames.
        Contact ``c`` of sector ``s`` is named ``"<name>@<s>"``. Sparse when
        the sector's matrices are, else dense. Solved with the force of
        :meth:`travelling_wave`, it gives the response a sector solution with
        ``engine_order`` stands for, at ``N`` times the cost (a check, or a
        baseline).

        Parameters
        ----------
        stiffness_scale : array_like, shape (sectors,), optional
            A factor ``> 0`` on sector ``s``'s stiffness entries ``K[i, j]``
            with ``i`` and ``j`` both in ``scaled_dofs`` (a mistuned disk,
            :func:`~microslip.frequency.structures.mistuning.mistuned_disk`); None: every
            sector as given (the tuned disk).
        scaled_dofs : array_like of int, optional
            The sector's DOFs (indices into its ``ndof``) whose stiffness
            ``stiffness_scale`` scales; default every DOF.
        """
        N = self.sectors
        scale = self._stiffness_scale(stiffness_scale, scaled_dofs)
        maps = [self._sector_map(s) for s in range(N)]
        mats = []
        for which, A in enumerate((self.M, self.C, self.K)):
            A = sp.csr_matrix(A)
            whole = None
            for s, As in enumerate(maps):
                if which == 2 and scale is not None:
                    factors, inside = scale
                    Ac = A.tocoo()
                    scaled = inside[Ac.row] & inside[Ac.col]
                    A_s = sp.csr_matrix((np.where(scaled, Ac.data * factors[s], Ac.data), (Ac.row, Ac.col)),
                                        shape=A.shape)
                else:
                    A_s = A
                part = As.T @ A_s @ As
                whole = part if whole is None else whole + part
            whole = whole.tocsr()
            mats.append(whole if self.sparse else whole.toarray())
        out = Structure(*mats)
        for s, As in enumerate(maps):
            out.static_force += As.T @ self.static_force
            for c, (t_next, n_next) in zip(self.contacts, self.next_directions):
                nxt = maps[(s + 1) % N].T
                tangential = As.T @ c.tangential + nxt @ frames.turn_back(t_next, self._next_parts)
                normal = As.T @ c.normal + nxt @ frames.turn_back(n_next, self._next_parts)
                out.add_contact(c.model, tangential=_terms(tangential), normal=_terms(normal) or None,
                                preload=c.preload or None, approach=c.approach, name=f"{c.name}@{s}")
        return out

    def _stiffness_scale(self, stiffness_scale, scaled_dofs):
        """``(factors (sectors,), mask (ndof,))`` of :meth:`assembled`'s arguments, checked; None when not scaled."""
        if stiffness_scale is None:
            if scaled_dofs is not None:
                raise ValueError("scaled_dofs is only used with stiffness_scale, which is None")
            return None
        factors = _checks.positive_array("stiffness_scale", stiffness_scale, ndim=1)
        if factors.size != self.sectors:
            raise ValueError(f"stiffness_scale must have one factor per sector ({self.sectors}), got {factors.size}")
        inside = np.ones(self.ndof, dtype=bool)
        if scaled_dofs is not None:
            inside[:] = False
            inside[_dof_list("scaled_dofs", scaled_dofs, self.ndof, self.dof_map)] = True
        return factors, inside

    def travelling_wave(self, force, engine_order: int) -> dict:
        """The force on every sector of :meth:`assembled` for this sector's ``force`` and an engine order.

        Parameters
        ----------
        force : array_like or mapping
            This sector's excitation (N), as :func:`~microslip.frequency.frequency_response`
            takes it: ``ndof`` amplitudes at the first harmonic, or ``{h: vector}``.
        engine_order : int
            ``EO >= 0``: sector ``s`` lags sector 0 by ``s phi_h`` in harmonic ``h``.

        Returns
        -------
        dict of int to ndarray
            ``{h: amplitudes}`` (complex, N), shape ``(sectors * len(independent),)`` each.
        """
        eo = _checks.positive_int("engine_order", engine_order, minimum=0)
        spec = force if isinstance(force, Mapping) else {1: force}
        out = {}
        maps = [self._sector_map(s) for s in range(self.sectors)]
        for h, f in spec.items():
            h = _checks.positive_int("force (a harmonic as key)", h, minimum=0)
            f = self.force_vector(f, f"force[{h}]")
            whole = np.zeros(self.sectors * self.independent.size, dtype=complex)
            phi = self.phase(h, eo)
            for s, As in enumerate(maps):
                whole += As.T @ (f * np.exp(-1j * s * phi))
            out[h] = whole
        return out


def _terms(b: np.ndarray) -> dict:
    """``{DOF: coefficient}`` of a direction's non-zero entries."""
    return {int(i): float(b[i]) for i in np.flatnonzero(b)}


def contact_terms(structure: Structure, index: int) -> tuple[list, list]:
    """Contact ``index``'s directions as terms ``(dof, coefficient, next_sector)``: ``(tangential, normal)``.

    The plain form of a contact's directions, to copy it onto another structure
    (more DOFs, kept DOFs) or to write it to a file. A contact on its plane has
    two lists of terms in ``tangential``, one per direction.
    """
    c = structure.contacts[index]
    t_next, n_next = (structure.next_directions[index] if isinstance(structure, CyclicStructure)
                      else (np.zeros(structure.ndof), np.zeros(structure.ndof)))

    def terms(own, nxt):
        return ([(int(i), float(own[i]), False) for i in np.flatnonzero(own)]
                + [(int(j), float(nxt[j]), True) for j in np.flatnonzero(nxt)])

    if c.planar:
        return [terms(c.tangential, t_next), terms(c.tangential2, np.zeros(structure.ndof))], terms(c.normal, n_next)
    return terms(c.tangential, t_next), terms(c.normal, n_next)


def add_contact_terms(target: Structure, model, tangential, normal, *, position=None, preload=0.0, approach=0.0,
                      name=None):
    """Add a contact given by :func:`contact_terms` to ``target``, each DOF mapped through ``position``."""
    where = (lambda d: d) if position is None else position.__getitem__

    def spec(terms):
        out = {}
        for dof, coef, nxt in terms:
            key = target.next(where(dof)) if nxt else where(dof)
            out[key] = out.get(key, 0.0) + coef
        return out

    normal_spec = spec(normal)
    planar = isinstance(tangential[0], (list, tuple)) and isinstance(tangential[0][0], (list, tuple))
    return target.add_contact(model, tangential=[spec(t) for t in tangential] if planar else spec(tangential),
                              normal=normal_spec or None,
                              preload=preload or None, approach=approach, name=name)
