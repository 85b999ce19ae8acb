"""Craig--Bampton reduction: a smaller :class:`Structure` on kept DOFs plus fixed-interface modes.

The reduced coordinates are the kept DOFs (physical, first, in the order of
``keep``) and ``modes`` modal coordinates of the structure with the kept DOFs
held fixed. The recovery matrix ``T`` (``ndof x (k + modes)``) gives every DOF,
``q = T u``; the reduced matrices are ``T^T M T``, ``T^T C T``, ``T^T K T``.
Contacts are carried over (they must use kept DOFs only), so the reduced
structure is solved like any other (harmonic balance, time integration) and
exchanged as a file (:meth:`CraigBampton.save`, :meth:`CraigBampton.load`).
"""

from __future__ import annotations

import json
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ...common._numeric import eigsh_repeatable
from ...common import _checks
from ...common._io import atomic_write
from ...fe.files import FileFormatError, NpzArrays
from ...model import MicroslipModel
from ..structures.cyclic import CyclicStructure, add_contact_terms, contact_terms
from ..structures.structure import Structure, dof_indices, refuse_indefinite

#: interior DOFs up to which the fixed-interface eigenproblem is solved densely
DENSE_EIGEN = 600


@dataclass(frozen=True, eq=False)
class CraigBampton:
    """A Craig--Bampton reduced structure and how to expand its solutions.

    Attributes
    ----------
    structure : Structure
        The reduced structure, ``k + modes`` DOFs (dense): the kept DOFs first
        (m), then the modal coordinates (m kg^1/2, mass-normalised modes), with
        the original contacts.
    recovery : ndarray, shape (ndof, k + modes)
        ``T``: every original DOF from the reduced coordinates.
    keep : ndarray of int, shape (k,)
        The kept DOFs, numbered as in the original structure.
    frequencies : ndarray, shape (modes,)
        Natural frequencies of the structure with the kept DOFs fixed (rad/s).
    """

    structure: Structure
    recovery: np.ndarray
    keep: np.ndarray
    frequencies: np.ndarray

    def expand(self, u) -> np.ndarray:
        """Original DOFs ``q = T u`` (m) from reduced coordinates ``u``, shape ``(..., k + modes)`` -> ``(..., ndof)``."""
        u = _checks.real_array("u", u)
        if u.shape[-1] != self.recovery.shape[1]:
            raise ValueError(f"u must have {self.recovery.shape[1]} reduced coordinates in its last axis, "
                             f"got shape {u.shape}")
        return u @ self.recovery.T

    def save(self, path) -> str:
        """Write the reduced model (matrices, recovery, kept DOFs, contacts) to a ``.npz`` file atomically."""
        path = str(_checks.file_path("path", path))
        if not path.endswith(".npz"):
            raise ValueError(f"path must end with .npz, got {path!r}")
        s = self.structure
        contacts = []
        for i, c in enumerate(s.contacts):
            tangential, normal = contact_terms(s, i)
            contacts.append({"model": c.model.to_dict(), "tangential": tangential, "normal": normal,
                             "preload": c.preload, "approach": c.approach, "name": c.name})
        cyclic = s._cyclic_arguments() if isinstance(s, CyclicStructure) else None
        import io

        buffer = io.BytesIO()
        np.savez_compressed(buffer, M=s.M, C=s.C, K=s.K, recovery=self.recovery, keep=self.keep,
                            frequencies=self.frequencies, contacts=np.array(json.dumps(contacts)),
                            static_force=s.static_force, cyclic=np.array(json.dumps(cyclic)))
        atomic_write(path, buffer.getvalue())
        return path

    @classmethod
    def load(cls, path) -> "CraigBampton":
        """Read a model written by :meth:`save`.

        Raises
        ------
        microslip.fe.FileFormatError
            Not such a model file, or a damaged one (truncated, altered, of
            inconsistent sizes): a ValueError naming the file.
        """
        path = _checks.file_path("path", path)
        if not path.is_file():
            raise ValueError(f"path: no Craig-Bampton model file at {str(path)!r}")
        with NpzArrays(path) as npz:
            missing = {"M", "C", "K", "recovery", "keep", "frequencies", "contacts"} - set(npz.names)
            if missing:
                raise FileFormatError(path, f"not a Craig-Bampton model file (missing {', '.join(sorted(missing))})")
            data = {k: npz.get(k) for k in npz.names}
        try:
            return cls._from_arrays(data)
        except (ValueError, TypeError, KeyError, IndexError, AttributeError) as err:
            raise FileFormatError(path, f"not a valid Craig-Bampton model file ({type(err).__name__}: {err})") \
                from None

    @classmethod
    def _from_arrays(cls, data: dict) -> "CraigBampton":
        def parsed(key):
            try:
                return json.loads(str(data[key]))
            except ValueError as err:
                raise ValueError(f"{key} is not valid JSON ({err})") from None

        cyclic = parsed("cyclic") if "cyclic" in data else None
        if cyclic:
            s = CyclicStructure(data["M"], data["C"], data["K"], **cyclic)
        else:
            s = Structure(data["M"], data["C"], data["K"])
        contacts = parsed("contacts")
        if not isinstance(contacts, list) or not all(isinstance(c, dict) for c in contacts):
            raise ValueError("contacts must be a list of tables")
        for c in contacts:
            add_contact_terms(s, MicroslipModel.from_dict(c["model"]), c["tangential"], c["normal"],
                              preload=c["preload"], approach=c["approach"], name=c["name"])
        n = s.ndof
        if "static_force" in data:
            s.static_force = _checks.real_array("static_force", data["static_force"], ndim=1)
            if s.static_force.size != n:
                raise ValueError(f"static_force has {s.static_force.size} entries; the structure has {n} DOFs")
        recovery = _checks.real_array("recovery", data["recovery"], ndim=2)
        keep, frequencies = np.asarray(data["keep"]), _checks.real_array("frequencies", data["frequencies"], ndim=1)
        if recovery.shape[1] != n or keep.ndim != 1 or keep.dtype.kind not in "iu" \
                or keep.size + frequencies.size != n or not np.all((keep >= 0) & (keep < recovery.shape[0])) \
                or np.unique(keep).size != keep.size:
            raise ValueError(f"recovery {recovery.shape}, keep {keep.shape} and frequencies {frequencies.shape} do "
                             f"not fit a reduced structure of {n} DOFs (keep: distinct rows of recovery)")
        return cls(s, recovery, keep, frequencies)


def _kept(structure: Structure, keep) -> np.ndarray:
    if np.size(keep) == 0 and not isinstance(keep, str):
        raise TypeError(f"keep must be a non-empty list of DOF indices, got {keep!r}")
    keep = dof_indices("keep", keep, structure.ndof, structure.dof_map)
    Bt, Bn, _ = structure.contact_directions()
    used = np.any(Bt != 0, axis=1) | np.any(Bn != 0, axis=1) | (structure.preload_force() != 0)
    used |= np.any(structure.second_tangential_directions() != 0, axis=1)
    if isinstance(structure, CyclicStructure):
        Btn, Bnn = structure.contact_directions_next()
        used |= np.any(Btn != 0, axis=1) | np.any(Bnn != 0, axis=1)
        boundary = np.setdiff1d(np.concatenate([structure.left, structure.right]), keep)
        if boundary.size:
            raise ValueError(f"keep must include the sector's left and right boundary DOFs; missing "
                             f"{boundary[:10].tolist()}")
    missing = np.setdiff1d(np.flatnonzero(used), keep)
    if missing.size:
        raise ValueError(f"keep must include every DOF a contact or a static force uses; missing "
                         f"{missing[:10].tolist()}")
    return keep


def craig_bampton(structure: Structure, keep, modes: int) -> CraigBampton:
    """Craig--Bampton reduction of ``structure`` onto the DOFs ``keep`` plus ``modes`` fixed-interface modes.

    Parameters
    ----------
    structure : Structure
        The full structure (dense or sparse) with its contacts.
    keep : array_like of int, shape (k,)
        DOFs kept physical: every DOF a contact uses, plus the excitation and
        output DOFs you need; indices, or names ``"node:component"`` when the
        structure has a DOF map.
    modes : int
        Fixed-interface normal modes kept (``0 <= modes < ndof - k``),
        computed by a sparse shift-invert eigensolver above 600 interior DOFs.

    Returns
    -------
    CraigBampton
        The reduced structure and the recovery matrix.

    Raises
    ------
    ValueError
        ``keep`` missing a contact's DOF, out of range or repeating a DOF; the
        structure moves freely with the kept DOFs fixed (keep more DOFs); an
        indefinite ``K`` (the negative eigenvalue named: of the structure with
        the kept DOFs fixed, or of the reduced structure).
    TypeError
        ``keep`` holds something other than DOF indices (or names, with a
        DOF map).
    """
    if not isinstance(structure, Structure):
        raise TypeError(f"structure must be a microslip Structure, got {type(structure).__name__}")
    b = _kept(structure, keep)
    ndof = structure.ndof
    mask = np.ones(ndof, dtype=bool)
    mask[b] = False
    i = np.flatnonzero(mask)
    modes = _checks.positive_int("modes", modes, minimum=0)
    limit = i.size if i.size <= DENSE_EIGEN else i.size - 1  # the sparse eigensolver finds fewer than all
    if modes > limit:
        raise ValueError(f"modes must be at most {limit} (the structure has {i.size} DOFs besides the kept ones), "
                         f"got {modes}")
    K = sp.csr_matrix(structure.K)
    M = sp.csr_matrix(structure.M)
    Kii, Kib = K[i][:, i].tocsc(), K[i][:, b].toarray()
    Mii = M[i][:, i].tocsc()
    T = np.zeros((ndof, b.size + modes))
    T[b, np.arange(b.size)] = 1.0
    frequencies = np.zeros(0)
    if i.size:
        try:
            lu = spla.splu(Kii)
            psi = -lu.solve(Kib)
        except RuntimeError:
            raise ValueError("the structure moves freely with the kept DOFs fixed: keep more DOFs") from None
        if not np.all(np.isfinite(psi)):
            raise ValueError("the structure moves freely with the kept DOFs fixed: keep more DOFs")
        T[i, :b.size] = psi
        fixed = "a Craig-Bampton reduction (the structure with the kept DOFs fixed)"
        if i.size <= DENSE_EIGEN:  # the lowest fixed-interface mode even when none is kept: is K indefinite there?
            lam, phi = sla.eigh(Kii.toarray(), Mii.toarray(), subset_by_index=[0, max(modes, 1) - 1])
            refuse_indefinite(lam, Kii, Mii, fixed)
            lam, phi = lam[:modes], phi[:, :modes]
        elif modes:
            op = spla.LinearOperator(Kii.shape, matvec=lu.solve, dtype=float)
            lam, phi = eigsh_repeatable(Kii, k=modes, M=Mii, sigma=0.0, which="LM", OPinv=op)
            refuse_indefinite(lam, Kii, Mii, fixed)
            order = np.argsort(lam)
            lam, phi = lam[order], phi[:, order]
        if modes:
            T[i, b.size:] = phi
            frequencies = np.sqrt(np.maximum(lam, 0.0))  # >= 0 but for rounding (checked above)
    reduced = [T.T @ (A @ T) for A in (structure.M, structure.C, structure.K)]
    reduced = [0.5 * (A + A.T) for A in reduced]  # symmetric to rounding already (Structure checks M, C, K)
    # T^T K T is congruent to K when every interior mode is kept (Sylvester): an indefinite K shows here, through
    # the boundary's static condensation if not through the interior
    Mr, _, Kr = reduced
    refuse_indefinite(sla.eigh(Kr, Mr, eigvals_only=True, subset_by_index=[0, 0]), Kr, Mr,
                      "a Craig-Bampton reduction (the reduced structure)")
    return CraigBampton(_carry_over(structure, reduced, b), T, b, frequencies)


def _carry_over(structure: Structure, reduced, keep) -> Structure:
    """The reduced structure (cyclic when ``structure`` is) with the contacts and static forces on the kept DOFs."""
    position = {int(d): k for k, d in enumerate(keep)}
    if isinstance(structure, CyclicStructure):
        out = CyclicStructure(*reduced, **structure._cyclic_arguments(position))
    else:
        out = Structure(*reduced)
    for i, c in enumerate(structure.contacts):
        add_contact_terms(out, c.model, *contact_terms(structure, i), position=position, preload=c.preload,
                          approach=c.approach, name=c.name)
    static = np.zeros(out.ndof)
    static[:keep.size] = structure.static_force[keep]
    out.static_force = static
    return out
