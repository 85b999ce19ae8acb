"""Linear structures carrying microslip contacts.

A :class:`Structure` is ``M q'' + C q' + K q + sum_c (b_t T_c + b_n N_c) = f(time)``
with ``ndof`` degrees of freedom ``q`` (m, or any consistent unit per DOF),
mass, damping and stiffness matrices in kg, N s/m and N/m (dense arrays or
``scipy.sparse``), and contacts :class:`Contact` whose tangential
displacement ``t = b_t . q`` and normal approach ``n = b_n . q + n_0`` are
linear combinations of the degrees of freedom. A contact force acts on the
structure along the same combinations (virtual work ``T dt + N dn``), so a
single DOF ``i`` means a contact between that DOF and the ground, and
``{i: 1, j: -1}`` a contact between DOFs ``i`` and ``j``.

Static normal load. A contact is closed either by a ``preload`` -- an
external static force ``P b_n`` on the structure, which the structure's own
stiffness along ``b_n`` shares with the contact, so that the contact carries
``N0 <= P`` (found with the static equilibrium, reported as
``FrequencyResponse.static_normal_force``) -- or by an imposed ``approach``
(with ``normal=None`` the normal load is then fixed, e.g. at
``model.approach(N)`` it is ``N`` whatever the structure does).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ...common import _checks
from ...fe.dof_map import DofMap
from ...fe.files import SYMMETRY_TOLERANCE, read_matrices
from ...model import MicroslipModel
from ..aft import pack_models


#: contacts from which a dense structure's stuck stiffness adds their rank-one terms in one matrix product (one
#: update of the whole matrix per term costs ndof^2 each)
MANY_CONTACTS = 32

def add_rank_one_terms(K, terms, *, many: bool):
    """``K + sum_j k_j conj(h_j) h_j^T``: the stiffness (N/m) of contact elements stuck along directions ``h_j``.

    ``K`` is dense (``(n, n)``) or sparse; ``terms`` holds ``(h_j, k_j)`` with ``h_j`` of shape ``(n,)`` and
    ``k_j`` the stuck stiffness along it (N/m; zero terms are skipped). With ``many`` contacts a dense ``K``
    takes the terms in one product ``H diag(k) H^H`` instead of one outer product each.
    """
    columns, weights = [], []
    for h, k in terms:
        if not k:
            continue
        if sp.issparse(K):
            col = sp.csr_matrix(h[:, None])
            K = K + k * (col.conj() @ col.T)
        elif not many:
            K = K + k * np.outer(h.conj(), h)
        else:
            columns.append(h)
            weights.append(k)
    if columns:
        H = np.stack(columns, axis=1)
        K = K + (H.conj() * np.asarray(weights)) @ H.T
    return K


def _matrix(name: str, value, ndof: int | None):
    if sp.issparse(value):
        A = sp.csr_matrix(value, dtype=np.float64)
        if not np.isfinite(A.data).all():
            raise ValueError(f"{name} must be finite; it holds {A.data[~np.isfinite(A.data)][0]!r}")
    else:
        A = _checks.real_array(name, value)
        if A.ndim == 0 and ndof is None:
            A = A.reshape(1, 1)
    if A.ndim != 2 or A.shape[0] != A.shape[1]:
        raise ValueError(f"{name} must be a square matrix, got shape {A.shape}")
    if ndof is not None and A.shape[0] != ndof:
        raise ValueError(f"{name} must be {ndof} x {ndof} like M, got shape {A.shape}")
    return A


def _entry(name: str, i: int, j: int, dof_map) -> str:
    """``M[3, 5]``, with the DOFs' names when a DOF map is known: ``M[3, 5] ('12:x', '14:y')``."""
    return f"{name}[{i}, {j}]" + (f" ({dof_map.names[i]!r}, {dof_map.names[j]!r})" if dof_map is not None else "")


def check_symmetric(name: str, A, dof_map=None) -> None:
    """Raise unless ``A`` (dense or sparse, square) is symmetric to :data:`SYMMETRY_TOLERANCE`, relative.

    ``max |A - A^T| <= SYMMETRY_TOLERANCE max |A|`` (the tolerance of the
    finite-element file readers); the message names the worst pair of entries.
    Non-symmetric structures (gyroscopic, follower forces) are not supported:
    the reductions and the linear modes assume symmetric matrices.
    """
    if sp.issparse(A):
        D = sp.coo_matrix(A - A.T)
        if not D.nnz:
            return
        k = int(np.argmax(np.abs(D.data)))
        i, j, worst = int(D.row[k]), int(D.col[k]), float(abs(D.data[k]))
        scale = float(abs(A).max())
    else:
        D = np.abs(A - A.T)
        i, j = (int(x) for x in np.unravel_index(np.argmax(D), D.shape)) if D.size else (0, 0)
        worst, scale = (float(D[i, j]), float(np.max(np.abs(A)))) if D.size else (0.0, 0.0)
    if worst > SYMMETRY_TOLERANCE * scale:
        i, j = min(i, j), max(i, j)
        raise ValueError(f"{name} must be symmetric (|{name} - {name}^T| at most {SYMMETRY_TOLERANCE:g} x "
                         f"max|{name}| = {SYMMETRY_TOLERANCE * scale:.3g}): {_entry(name, i, j, dof_map)} = "
                         f"{float(A[i, j])!r} but {name}[{j}, {i}] = {float(A[j, i])!r}, a difference of "
                         f"{worst:.3g}; non-symmetric (gyroscopic) structures are not supported")


def _positive_definite(name: str, A) -> None:
    """Raise unless ``A`` (dense or sparse, square, symmetric) is positive definite."""
    diag = A.diagonal()
    if np.any(diag <= 0):
        i = int(np.argmax(diag <= 0))
        raise ValueError(f"{name} must be positive definite: its diagonal entry {i} is {float(diag[i])!r} "
                         f"(every DOF needs a positive mass)")
    if sp.issparse(A):
        # symmetric ordering without pivoting: A = L U with positive pivots iff A is positive definite
        try:
            lu = spla.splu(A.tocsc(), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                           options={"SymmetricMode": True})
            ok = np.array_equal(lu.perm_r, lu.perm_c) and bool(np.all(lu.U.diagonal() > 0))
        except RuntimeError:  # exactly singular
            ok = False
    else:
        try:
            np.linalg.cholesky(A)
            ok = True
        except np.linalg.LinAlgError:
            ok = False
    if not ok:
        raise ValueError(f"{name} must be positive definite (a mass matrix); it is symmetric with a positive "
                         f"diagonal but singular or indefinite")


#: an eigenvalue of ``K phi = lambda M phi`` below ``-INDEFINITE_TOLERANCE max K_ii / min M_ii`` is negative (beyond
#: the round-off of a rigid-body mode's zero): ``K`` is then indefinite
INDEFINITE_TOLERANCE = 1e-9


def refuse_indefinite(lam, K, M, where: str) -> None:
    """Raise when the smallest of the eigenvalues ``lam`` (rad^2/s^2) of ``K phi = lambda M phi`` is negative.

    ``where`` names the path that needs a positive semi-definite ``K`` (modal
    reduction, Craig--Bampton, the stuck linear mode): a negative eigenvalue
    has no real natural frequency (a buckled structure, a negative geometric
    stiffness larger than the elastic one).
    """
    lam = np.real(np.asarray(lam, dtype=complex if np.iscomplexobj(lam) else float))
    if not lam.size:
        return
    low = float(np.min(lam))
    diag_k, diag_m = np.abs(np.real(K.diagonal())), np.abs(np.real(M.diagonal()))
    limit = INDEFINITE_TOLERANCE * float(np.max(diag_k, initial=0.0)) / float(np.min(diag_m))
    if low < -limit:
        raise ValueError(f"K must be positive semi-definite for {where}: K phi = lambda M phi has the negative "
                         f"eigenvalue {low:.6g} rad^2/s^2 (below -{INDEFINITE_TOLERANCE:g} x max K_ii / min M_ii = "
                         f"{-limit:.3g}), which has no real natural frequency: K is indefinite (a buckled "
                         f"structure, or a negative geometric stiffness larger than the elastic one)")


def dof_index(name: str, key, ndof: int, dof_map=None) -> int:
    """The row of one DOF: an integer index, or a name such as ``"1204:x"`` looked up in ``dof_map``.

    Every DOF given by name (contacts, forces, outputs) goes through here.
    """
    if isinstance(key, str):
        if dof_map is None:
            raise TypeError(f"{name}: DOF keys must be integers, got {key!r} (names such as '1204:x' need a "
                            f"DOF map: Structure(..., dof_map=...) or Structure.from_files(..., dof_map=...))")
        try:
            return dof_map.index(key)
        except ValueError as err:
            raise ValueError(f"{name}: {err}") from None
    if isinstance(key, (bool, np.bool_)) or not isinstance(key, (int, np.integer)):
        raise TypeError(f"{name}: DOF keys must be integers, got {key!r}")
    i = int(key)
    if not 0 <= i < ndof:
        raise ValueError(f"{name}: DOF {i} is out of range for a structure with {ndof} DOFs")
    return i


def dof_indices(name: str, values, ndof: int, dof_map=None) -> np.ndarray:
    """The rows of a list of DOFs, integer indices or (with ``dof_map``) names such as ``"1204:x"``; no repeats.

    Every list of DOFs of the API (a sector's boundaries, the DOFs a
    Craig--Bampton reduction keeps, a mistuned blade's DOFs) goes through here.
    A single DOF is a list of one.
    """
    given = values
    if isinstance(values, (str, int, np.integer)) and not isinstance(values, (bool, np.bool_)):
        values = [values]
    if isinstance(values, (list, tuple)) and any(isinstance(v, str) for v in values):
        if dof_map is None:
            raise TypeError(f"{name} must be a list of DOF indices, got {given!r} (DOF names such as '1204:x' need "
                            f"a DOF map: dof_map=... when the structure is made)")
        arr = np.array([dof_index(f"{name}[{k}]", v, ndof, dof_map) for k, v in enumerate(values)], dtype=np.int64)
    else:
        arr = np.atleast_1d(np.asarray(values))
        if arr.ndim != 1 or not (np.issubdtype(arr.dtype, np.integer) or arr.size == 0):
            names = " or names" if dof_map is not None else ""
            raise TypeError(f"{name} must be a list of DOF indices{names}, got {given!r}")
        if arr.size and (arr.min() < 0 or arr.max() >= ndof):
            raise ValueError(f"{name}: DOF indices must lie in 0..{ndof - 1}, got {arr.min()}..{arr.max()}")
    unique, counts = np.unique(arr, return_counts=True)
    if np.any(counts > 1):
        raise ValueError(f"{name} must not repeat a DOF: DOF {int(unique[np.argmax(counts > 1)])} appears "
                         f"{int(counts.max())} times")
    return arr.astype(np.int64)


def dof_label(structure, dof) -> str | None:
    """The name of one DOF for a plot: its DOF map's ``"node:component"``, the name given, or ``"DOF i"``;
    None for a combination of DOFs."""
    dof_map = getattr(structure, "dof_map", None)
    if isinstance(dof, str):
        return dof
    if isinstance(dof, (int, np.integer)) and not isinstance(dof, (bool, np.bool_)) and 0 <= dof < structure.ndof:
        return dof_map.names[int(dof)] if dof_map is not None else f"DOF {int(dof)}"
    return None


def direction(name: str, spec, ndof: int, *, allow_none: bool = False, dof_map=None) -> np.ndarray:
    """A contact direction as a dense vector of length ``ndof``.

    ``spec`` is a DOF index (relative to ground), a mapping ``{dof: coefficient}``,
    a sequence of ``ndof`` coefficients, or (with ``allow_none``) ``None`` for
    "not coupled to the structure" (the zero vector). With a ``dof_map``
    (:class:`microslip.fe.DofMap`), a DOF may also be a name ``"node:component"``.
    """
    if spec is None:
        if allow_none:
            return np.zeros(ndof)
        raise ValueError(f"{name} must name the DOF(s) of the contact, got None")
    if isinstance(spec, (int, np.integer, str)) and not isinstance(spec, bool):
        spec = {spec: 1.0}
    if isinstance(spec, Mapping):
        b = np.zeros(ndof)
        for dof, coef in spec.items():
            i = dof_index(name, dof, ndof, dof_map)
            b[i] += _checks.real_scalar(f"{name}[{dof!r}]" if isinstance(dof, str) else f"{name}[{i}]", coef)
    else:
        b = _checks.real_array(name, spec, ndim=1)
        if b.size != ndof:
            raise ValueError(f"{name} must have one coefficient per DOF ({ndof}), got {b.size}")
    if not b.any() and not allow_none:
        raise ValueError(f"{name} must not be all zeros")
    return b


def _is_number(x) -> bool:
    return isinstance(x, (int, float, np.integer, np.floating)) and not isinstance(x, (bool, np.bool_))


def lists_two_directions(spec, ndof: int) -> bool:
    """Whether a contact's ``tangential`` gives two directions (the contact plane) or one.

    Two directions: a list or tuple of exactly two items of which at least one
    is a direction that is not a bare number (a DOF name, a mapping, a
    sequence of ``ndof`` coefficients), e.g. ``["12:x", "12:y"]`` or
    ``[{0: 1, 2: -1}, {1: 1, 3: -1}]``; a 2-D array of shape ``(2, ndof)``;
    or two integers ``[i, j]``, two DOF indices. Anything else is one
    direction (a flat list of ``ndof`` numbers is one direction's
    coefficients). Two integers on a structure of two DOFs could be either,
    and are refused.
    """
    if isinstance(spec, np.ndarray):
        return spec.ndim == 2
    if not isinstance(spec, (list, tuple)) or len(spec) != 2:
        return False
    if not all(_is_number(x) for x in spec):
        return True
    if all(isinstance(x, (int, np.integer)) for x in spec):
        if ndof == 2:
            raise ValueError(f"tangential = {list(spec)!r} is ambiguous on a structure of 2 DOFs: two DOF indices "
                             f"(two tangential directions) or the 2 coefficients of one direction; write "
                             f"[{{{spec[0]}: 1.0}}, {{{spec[1]}: 1.0}}] for two directions, or floats "
                             f"[{float(spec[0])!r}, {float(spec[1])!r}] for one")
        return True
    return False


def tangential_directions(spec, ndof: int, dof_map=None) -> tuple[np.ndarray, np.ndarray | None]:
    """A contact's tangential direction(s): ``(b_t, None)``, or ``(b_t1, b_t2)`` for two (:func:`lists_two_directions`).

    Two directions must be independent (they span the contact plane).
    """
    if not lists_two_directions(spec, ndof):
        return direction("tangential", spec, ndof, dof_map=dof_map), None
    b1, b2 = (direction(f"tangential[{k}]", spec[k], ndof, dof_map=dof_map) for k in range(2))
    if abs(b1 @ b2) >= (1.0 - 1e-12) * np.linalg.norm(b1) * np.linalg.norm(b2):
        raise ValueError("tangential[1] must not be parallel to tangential[0]: the two directions span the contact "
                         "plane")
    return b1, b2


@dataclass(frozen=True, eq=False)
class Contact:
    """A microslip contact attached to a structure (made by :meth:`Structure.add_contact`).

    Attributes
    ----------
    model : MicroslipModel
        The contact law.
    tangential, normal : ndarray, shape (ndof,)
        ``t = tangential . q``, ``n = normal . q + approach`` (``normal`` is
        zero for a contact whose approach is imposed). For a contact moving on
        its plane, ``tangential`` is the first of its two directions.
    preload : float
        External static force (N) applied to the structure along ``normal``
        (the force vector ``preload * normal``); not the contact's normal
        load, see :meth:`Structure.add_contact`.
    approach : float
        Imposed normal approach (interference) at ``q = 0`` (m).
    name : str
        Label used in results and files.
    tangential2 : ndarray, shape (ndof,), or None
        The second tangential direction of a contact moving on its plane
        (``t2 = tangential2 . q``); None for a contact along one direction.
    reference, reference2 : float
        Where the contact's sliders were reset (m): its elements carry no
        tangential force at ``t = reference`` (and ``t2 = reference2`` on its
        plane), the contact marched from there as from its unloaded state.
        Zero (the unloaded structure) unless a prestress with the friction
        released set them at its static displacement
        (:func:`~microslip.frequency.prestress`).
    """

    model: MicroslipModel
    tangential: np.ndarray
    normal: np.ndarray
    preload: float
    approach: float
    name: str
    tangential2: np.ndarray | None = None
    reference: float = 0.0
    reference2: float = 0.0

    @property
    def planar(self) -> bool:
        """True for a contact with two tangential directions (moving on its plane)."""
        return self.tangential2 is not None


class Structure:
    """A linear structure ``M q'' + C q' + K q = f`` to which contacts are added.

    Parameters
    ----------
    M, C, K : array_like or scipy.sparse matrix, shape (ndof, ndof)
        Mass (kg), viscous damping (N s/m) and stiffness (N/m) matrices,
        finite and symmetric to the relative tolerance
        :data:`~microslip.fe.files.SYMMETRY_TOLERANCE` (``max |A - A^T| <=
        1e-6 max |A|``; non-symmetric, e.g. gyroscopic, structures are not
        supported). ``M`` must be positive definite (every DOF carries mass:
        time integration factorises it). ``K`` may be indefinite here, but the
        modal and Craig--Bampton reductions and nonlinear modes refuse an
        indefinite ``K``, naming its negative eigenvalue. ``C`` may be
        ``None`` (no viscous damping).
    dof_map : microslip.fe.DofMap, optional
        Names of the DOFs (``"node:component"``): wherever a DOF index is
        taken, its name may be given instead.

    Raises
    ------
    ValueError
        A matrix that is not square and finite, of another size than ``M``,
        not symmetric (the message names the worst pair of entries), or an
        ``M`` that is not positive definite.

    Examples
    --------
    >>> import numpy as np
    >>> from microslip import MicroslipModel, Structure
    >>> s = Structure(M=np.eye(2), C=0.01 * np.eye(2), K=[[2e4, -1e4], [-1e4, 1e4]])
    >>> c = s.add_contact(MicroslipModel([1e4], [1e6], [0.0], 0.5), tangential=0, approach=2e-6)
    >>> s.ndof, len(s.contacts)
    (2, 1)
    """

    def __init__(self, M, C, K, *, dof_map=None):
        self.M = _matrix("M", M, None)
        ndof = self.M.shape[0]
        if dof_map is not None and not isinstance(dof_map, DofMap):
            raise TypeError(f"dof_map must be a microslip.fe.DofMap, got {type(dof_map).__name__}")
        if dof_map is not None and len(dof_map) != ndof:
            raise ValueError(f"dof_map must have one row per DOF ({ndof}), got {len(dof_map)}")
        check_symmetric("M", self.M, dof_map)
        _positive_definite("M", self.M)
        self.K = _matrix("K", K, ndof)
        check_symmetric("K", self.K, dof_map)
        self.C = sp.csr_matrix((ndof, ndof)) if C is None and sp.issparse(self.M) else (
            np.zeros((ndof, ndof)) if C is None else _matrix("C", C, ndof))
        check_symmetric("C", self.C, dof_map)
        self.dof_map = dof_map
        self.contacts: list[Contact] = []
        #: external static forces on the structure (N), ``(ndof,)``, e.g. a damper's centrifugal load
        self.static_force = np.zeros(ndof)

    @classmethod
    def from_files(cls, path=None, *, M=None, K=None, C=None, dof_map=None, names=None, format=None) -> Structure:
        """A structure from finite-element matrix files (see :func:`microslip.fe.read_matrices`).

        Parameters
        ----------
        path : str or Path, optional
            One file holding ``M``, ``K`` and optionally ``C``: ``.mat``,
            ``.npz``, ``.op4``, an ANSYS ``.full`` file, or Nastran DMIG
            entries (``.pch``, ``.bdf``; name the matrices with ``names``).
        M, K, C : str or Path, optional
            One file per matrix instead (``.mtx``, ``.mat``, ``.npz``,
            ``.op4``); ``C`` may be omitted (no viscous damping).
        dof_map : str, Path or microslip.fe.DofMap, optional
            A ``node,component`` CSV file or a map: DOFs may then be named
            ``"node:component"`` in contacts and forces.
        names : mapping, optional
            Variable names when they are not ``M``, ``K``, ``C``, e.g.
            ``{"M": "MGG", "K": "KGG"}``.
        format : str, optional
            The files' format when their suffix does not say it
            (``"harwell-boeing"``, ``"abaqus"``, ``"nastran-dmig"``, ...; see
            :mod:`microslip.fe.files`). ANSYS, DMIG and Abaqus files label
            their rows: the DOF map then comes from the files.

        Returns
        -------
        Structure

        Examples
        --------
        >>> s = Structure.from_files("blade.mat", dof_map="blade_dofs.csv")  # doctest: +SKIP
        >>> s.add_contact(model, tangential={"1204:x": 1.0}, normal={"1204:y": -1.0}, preload=40.0)  # doctest: +SKIP
        """
        m = read_matrices(path, M=M, K=K, C=C, dof_map=dof_map, names=names, format=format)
        return cls(m.M, m.C, m.K, dof_map=m.dof_map)

    def dof_index(self, dof) -> int:
        """The row of a DOF given as an index or, with a DOF map, as ``"node:component"``."""
        return dof_index("dof", dof, self.ndof, self.dof_map)

    @property
    def ndof(self) -> int:
        """Number of degrees of freedom."""
        return self.M.shape[0]

    @property
    def sparse(self) -> bool:
        """True when any of ``M``, ``C``, ``K`` is a ``scipy.sparse`` matrix."""
        return any(sp.issparse(A) for A in (self.M, self.C, self.K))

    def __repr__(self) -> str:
        kind = "sparse" if self.sparse else "dense"
        return f"Structure(ndof={self.ndof}, {kind}, contacts={len(self.contacts)})"

    def add_contact(self, model: MicroslipModel, *, tangential, normal=None, preload: float | None = None,
                    approach: float | None = None, name: str | None = None) -> Contact:
        """Attach a microslip contact.

        Parameters
        ----------
        model : MicroslipModel
            The contact law (e.g. from :func:`microslip.tune`).
        tangential : int, str, mapping, array_like, or a list of two of these
            ``t = b_t . q``: a DOF index (relative to ground), ``{dof: coef}``
            or ``ndof`` coefficients; with a DOF map a DOF may be named
            ``"node:component"``. Two directions ``[b_t1, b_t2]`` make a
            contact that moves on its plane (each element an isotropic
            Jenkins slider there, :func:`~microslip.frequency.aft_plane`),
            e.g. ``[0, 1]`` (DOFs 0 and 1), ``["12:x", "12:y"]``,
            ``[{0: 1, 2: -1}, {1: 1, 3: -1}]`` or a ``(2, ndof)`` array; they
            are the plane's orthonormal coordinates (two perpendicular unit
            displacements). A list of two items is two directions when one of
            them is not a bare number, or when both are integers (DOF indices);
            a flat list of ``ndof`` numbers is one direction. Two integers on a
            structure of two DOFs could be either and are refused: write
            ``[{0: 1.0}, {1: 1.0}]`` or ``[0.0, 1.0]``.
        normal : int, str, mapping, array_like or None
            ``n = b_n . q + approach``, same forms; ``None``: the normal
            approach is not coupled to the structure (it is ``approach``).
        preload : float, optional
            An external static force (N) on the structure, ``preload * normal``
            (e.g. the centrifugal load of a damper body). It is *not* the
            contact's normal load: the static normal approach is an unknown,
            and the structure's own stiffness along ``normal`` carries part of
            the preload, so the contact carries ``N0 <= preload``
            (:attr:`FrequencyResponse.static_normal_force
            <microslip.frequency.FrequencyResponse.static_normal_force>` reports
            it). The contact carries the whole preload only when nothing else
            resists the motion along ``normal`` (e.g. ``normal`` is a DOF of a
            damper body with no spring). To impose a normal load ``N``
            regardless of the structure, give ``approach=model.approach(N)``
            with ``normal=None``.
        approach : float, optional
            Imposed normal approach at ``q = 0`` (m), an interference fit.
            Needed when ``normal`` is None.
        name : str, optional
            Label (default ``contact<i>``).

        Returns
        -------
        Contact
        """
        if not isinstance(model, MicroslipModel):
            raise TypeError(f"model must be a microslip MicroslipModel, got {type(model).__name__}")
        bt, bt2 = tangential_directions(tangential, self.ndof, self.dof_map)
        bn = direction("normal", normal, self.ndof, allow_none=True, dof_map=self.dof_map)
        P = 0.0 if preload is None else _checks.positive_scalar("preload", preload, allow_zero=True)
        n0 = 0.0 if approach is None else _checks.real_scalar("approach", approach)
        if normal is None:
            if approach is None:
                raise ValueError("approach must be given (m) when normal is None: "
                                 "the normal approach is then imposed, not solved for")
            if P:
                raise ValueError("preload must be None when normal is None: a preload force needs a "
                                 "normal direction on the structure to act along")
        if name is None:
            name = f"contact{len(self.contacts)}"
        elif not isinstance(name, str) or not name:
            raise TypeError(f"name must be a non-empty string, got {name!r}")
        if any(c.name == name for c in self.contacts):
            raise ValueError(f"name {name!r} is already used by another contact")
        contact = Contact(model, bt, bn, P, n0, name, bt2)
        self.contacts.append(contact)
        return contact

    # -- assembled contact data (shared by harmonic balance and time integration) -----------
    def contact_directions(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Every contact's directions and imposed approach.

        Returns
        -------
        Bt, Bn : ndarray, shape (ndof, nc)
            Tangential and normal directions of the ``nc`` contacts, as columns.
        n0 : ndarray, shape (nc,)
            Imposed normal approach of each contact at ``q = 0`` (m).
        """
        nc = len(self.contacts)
        Bt = np.array([c.tangential for c in self.contacts]).T.reshape(self.ndof, nc)
        Bn = np.array([c.normal for c in self.contacts]).T.reshape(self.ndof, nc)
        return Bt, Bn, np.array([c.approach for c in self.contacts])

    def second_tangential_directions(self) -> np.ndarray:
        """Every contact's second tangential direction as columns, shape ``(ndof, nc)`` (zero for one direction)."""
        nc = len(self.contacts)
        return np.array([np.zeros(self.ndof) if c.tangential2 is None else c.tangential2
                         for c in self.contacts]).T.reshape(self.ndof, nc)

    def tangential_references(self) -> tuple[np.ndarray, np.ndarray]:
        """Where each contact's sliders were reset (m), ``(reference, reference2)``, shape ``(nc,)`` each.

        A contact's tangential displacement enters its law relative to these
        (:attr:`Contact.reference`); zero unless a prestress set them.
        """
        return (np.array([c.reference for c in self.contacts], dtype=float),
                np.array([c.reference2 for c in self.contacts], dtype=float))

    def add_static_force(self, force) -> None:
        """Add an external static force (N), ``(ndof,)`` (e.g. a centrifugal load), acting in every solution."""
        self.static_force = self.static_force + self.force_vector(force, "force").real

    def preload_force(self) -> np.ndarray:
        """Static force on the structure (N), shape ``(ndof,)``: the contacts' preloads ``sum_c P_c b_n,c`` and
        the static forces of :meth:`add_static_force`."""
        f = self.static_force.copy()
        for c in self.contacts:
            f += c.preload * c.normal
        return f

    def packed_models(self) -> tuple[np.ndarray, ...]:
        """The contacts' laws packed for the compiled kernels (see :func:`~microslip.frequency.aft.pack_models`)."""
        return pack_models([c.model for c in self.contacts])

    def stuck_stiffness(self):
        """Stiffness with every contact element closed and stuck (N/m), shape ``(ndof, ndof)``.

        ``K + sum_c (sum kt) b_t b_t^T + (sum kn) b_n b_n^T`` (and ``(sum kt) b_t2 b_t2^T``
        for a contact on its plane), stored like ``K`` (dense array or sparse
        CSR): the largest stiffness the contacts can add.
        """
        terms = []
        for c in self.contacts:
            terms += [(c.tangential, c.model.kt.sum()), (c.normal, c.model.kn.sum())]
            if c.planar:
                terms.append((c.tangential2, c.model.kt.sum()))
        return add_rank_one_terms(self.K.copy(), terms, many=len(self.contacts) >= MANY_CONTACTS)

    def force_vector(self, force, name: str = "force") -> np.ndarray:
        """A real or complex force vector of length ``ndof`` (N), checked; ``name`` names it in messages.

        ``force`` is ``ndof`` amplitudes or a mapping ``{dof: amplitude}``
        (DOF indices, or names ``"node:component"`` with a DOF map).
        """
        name = _checks.text("name", name)
        if isinstance(force, Mapping):
            f = np.zeros(self.ndof, dtype=complex)
            for dof, value in force.items():
                i = dof_index(name, dof, self.ndof, self.dof_map)
                part = f"{name}[{dof!r}]"
                if isinstance(value, (complex, np.complexfloating)):
                    f[i] += _checks.real_scalar(part, value.real) + 1j * _checks.real_scalar(part, value.imag)
                else:
                    f[i] += _checks.real_scalar(part, value)
            return f if f.imag.any() else f.real
        f = None if isinstance(force, (str, bytes)) else np.asarray(force)
        if f is not None and np.iscomplexobj(f):
            re = _checks.real_array(name, f.real, ndim=1)
            im = _checks.real_array(name, f.imag, ndim=1)
            f = re + 1j * im
        else:
            f = _checks.real_array(name, force, ndim=1)  # the value as given, in the message
        if f.size != self.ndof:
            raise ValueError(f"{name} must have one entry per DOF ({self.ndof}), got {f.size}")
        return f
