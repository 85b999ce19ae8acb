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
is eliminated, ``q_R = exp(-i phi_h) q_L``, and the sector's matrices become the
complex Hermitian ``T_h^H A T_h`` on the sector's independent DOFs (all but the
right boundary). Contacts may join a sector to the next one
(:meth:`CyclicStructure.next`): their displacement takes the next sector's DOFs
through the same phase, and their force acts back on this sector's DOFs through
the previous sector's contact (the transpose of that map).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ...common import _checks
from ...model import MicroslipModel
from ...fe.files import read_matrices
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
    left, right : array_like of int or of str, shape (k,)
        The boundary DOFs: ``right[j]`` of sector ``s`` is ``left[j]`` of
        sector ``s + 1`` (same direction in the sector's own frame); indices,
        or names ``"node:component"`` with a ``dof_map``.
    dof_map : microslip.fe.DofMap, optional
        Names of the sector's DOFs (``"node:component"``), as for :class:`Structure`.

    Notes
    -----
    The sector's matrices must not couple its left and right boundary
    directly to each other beyond what one sector's elements do (the
    usual FE sector). Solve with :func:`~microslip.frequency.frequency_response`
    and ``engine_order=EO``; the result reports this sector's DOFs, numbered
    as in ``M``, ``C``, ``K`` (:meth:`FrequencyResponse.sector` expands to
    any other sector).

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
    """

    def __init__(self, M, C, K, *, sectors: int, left, right, dof_map=None):
        super().__init__(M, C, K, dof_map=dof_map)
        self.sectors = _checks.positive_int("sectors", sectors, minimum=3)
        self.left = _dof_list("left", left, self.ndof, self.dof_map)
        self.right = _dof_list("right", right, self.ndof, self.dof_map)
        if self.left.size != self.right.size:
            raise ValueError(f"left and right must pair the boundary DOFs one to one, got {self.left.size} and "
                             f"{self.right.size} DOFs")
        both = np.intersect1d(self.left, self.right)
        if both.size:
            raise ValueError(f"a DOF cannot be on both boundaries: DOF {int(both[0])} is in left and right")
        mask = np.ones(self.ndof, dtype=bool)
        mask[self.right] = False
        self.independent = np.flatnonzero(mask)
        #: each contact's direction on the next sector's DOFs, ``(tangential, normal)``, shape (ndof,) each
        self.next_directions: list[tuple[np.ndarray, np.ndarray]] = []

    @classmethod
    def from_files(cls, path=None, *, sectors: int, left, right, M=None, K=None, C=None, dof_map=None,
                   names=None) -> CyclicStructure:
        """One sector from finite-element matrix files, as :meth:`Structure.from_files
        <microslip.frequency.Structure.from_files>`; ``sectors``, ``left`` and ``right`` as in the class (the
        boundaries may be named ``"node:component"`` with a ``dof_map``).

        Examples
        --------
        >>> disk = CyclicStructure.from_files("sector.mat", sectors=24, dof_map="sector_dofs.csv",
        ...                                   left=["1014:x", "1014:y"], right=["2014:x", "2014:y"])  # doctest: +SKIP
        """
        m = read_matrices(path, M=M, K=K, C=C, dof_map=dof_map, names=names)
        return cls(m.M, m.C, m.K, sectors=sectors, left=left, right=right, dof_map=m.dof_map)

    def __repr__(self) -> str:
        return (f"CyclicStructure(ndof={self.ndof}, sectors={self.sectors}, boundary={self.left.size}, "
                f"contacts={len(self.contacts)})")

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
            f += c.preload * (c.normal + bn_next)
        return f

    def contact_directions_next(self) -> tuple[np.ndarray, np.ndarray]:
        """The contacts' next-sector directions ``(Bt_next, Bn_next)``, shape ``(ndof, nc)`` each."""
        nc = len(self.contacts)
        Bt = np.array([t for t, _ in self.next_directions]).T.reshape(self.ndof, nc)
        Bn = np.array([n for _, n in self.next_directions]).T.reshape(self.ndof, nc)
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
        """``T`` (sparse, ``(ndof, len(independent))``): every DOF from the independent ones, ``q_R = e^{-i phi} q_L``."""
        phi = _checks.real_scalar("phi", phi)
        col = {int(d): k for k, d in enumerate(self.independent)}
        rows = list(self.independent) + list(self.right)
        cols = [col[int(d)] for d in self.independent] + [col[int(d)] for d in self.left]
        shift = np.exp(-1j * phi) if phi else 1.0
        vals = [1.0] * self.independent.size + [shift] * self.right.size
        return sp.csr_matrix((np.array(vals, dtype=complex if phi else float), (rows, cols)),
                             shape=(self.ndof, self.independent.size))

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
        """DOF numbers in :meth:`assembled` of this sector's ``dofs`` placed in sector ``sector``."""
        ni = self.independent.size
        local = np.empty(self.ndof, dtype=np.int64)
        local[self.independent] = np.arange(ni)
        local[self.right] = local[self.left]
        owner = np.zeros(self.ndof, dtype=np.int64)
        owner[self.right] = 1  # the right boundary is the next sector's left one
        dofs = np.asarray(dofs, dtype=np.int64)
        return ((sector + owner[dofs]) % self.sectors) * ni + local[dofs]

    def assembled(self, stiffness_scale=None, *, scaled_dofs=None) -> Structure:
        """The whole disk as one :class:`Structure`: every sector's matrices, contacts and static forces.

        Sector ``s``'s independent DOFs (:attr:`independent`, in order) are
        DOFs ``s * n + k`` (``n = len(independent)``); its right boundary is
        sector ``s + 1``'s left one. Contact ``c`` of sector ``s`` is named
        ``"<name>@<s>"``. Sparse when the sector's matrices are, else dense.
        Solved with the force of :meth:`travelling_wave`, it gives the response
        a sector solution with ``engine_order`` stands for, at ``N`` times the
        cost (a check, or a baseline).

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
        N, ni = self.sectors, self.independent.size
        scale = self._stiffness_scale(stiffness_scale, scaled_dofs)
        mats = []
        for which, A in enumerate((self.M, self.C, self.K)):
            A = sp.coo_matrix(A)
            rows = np.concatenate([self._whole_index(s, A.row) for s in range(N)])
            cols = np.concatenate([self._whole_index(s, A.col) for s in range(N)])
            if which == 2 and scale is not None:
                factors, inside = scale
                scaled = inside[A.row] & inside[A.col]
                data = np.concatenate([np.where(scaled, A.data * f, A.data) for f in factors])
            else:
                data = np.tile(A.data, N)
            whole = sp.csr_matrix((data, (rows, cols)), shape=(N * ni, N * ni))
            mats.append(whole if self.sparse else whole.toarray())
        out = Structure(*mats)
        everything = np.arange(self.ndof)
        for s in range(N):
            np.add.at(out.static_force, self._whole_index(s, everything), self.static_force)
            for i, c in enumerate(self.contacts):
                tangential, normal = contact_terms(self, i)
                out.add_contact(c.model, tangential=self._whole_terms(s, tangential),
                                normal=self._whole_terms(s, normal) or None, preload=c.preload or None,
                                approach=c.approach, name=f"{c.name}@{s}")
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

    def _whole_terms(self, sector: int, terms) -> dict:
        """``{whole-disk DOF: coefficient}`` of :func:`contact_terms` ``terms`` of a contact of sector ``sector``."""
        out: dict = {}
        for dof, coef, nxt in terms:
            key = int(self._whole_index(sector + 1 if nxt else sector, [dof])[0])
            out[key] = out.get(key, 0.0) + coef
        return out

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
        everything = np.arange(self.ndof)
        for h, f in spec.items():
            h = _checks.positive_int("force (a harmonic as key)", h, minimum=0)
            f = self.force_vector(f, f"force[{h}]")
            whole = np.zeros(self.sectors * self.independent.size, dtype=complex)
            phi = self.phase(h, eo)
            for s in range(self.sectors):
                np.add.at(whole, self._whole_index(s, everything), f * np.exp(-1j * s * phi))
            out[h] = whole
        return out


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
