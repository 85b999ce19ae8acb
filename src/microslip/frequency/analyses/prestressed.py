"""The state a prestress leaves a structure in: :class:`Prestress` (from :func:`~.prestress.prestress`).

It holds the static equilibrium under the static loads (bolt preloads,
centrifugal loads, static forces) with the friction state chosen, each
contact's normal load, tangential force and closed elements there, and the
structure the dynamic analyses then solve (:attr:`Prestress.prestressed`: the
same matrices and contacts, the static loads on it, each contact's sliders
reset at the static state when the friction was released). It gives the
linear modes of the prestressed structure (contacts stuck at the prestress:
their tangential stiffness at the closed elements, open elements absent) and
a viscous damping matrix fitted on them (:meth:`Prestress.modal_damping`,
:meth:`Prestress.rayleigh_damping`).
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field, replace
from typing import Mapping

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from ...common._numeric import eigsh_repeatable
from ...common import _checks
from ...common._io import write_csv
from ..equations.epmc import DENSE_EIGEN, stuck_matrices
from ..structures.cyclic import CyclicStructure
from ..structures.structure import Structure, check_symmetric, refuse_indefinite

#: the friction states of a prestress
FRICTION_STATES = ("released", "stuck")
#: DOFs up to which a damping matrix is built from modes (it is dense: every entry couples through the modes)
MODAL_DAMPING_LIMIT = 5000


@dataclass(frozen=True, eq=False)
class PrestressedModes:
    """Linear modes of a prestressed structure, contacts stuck at the prestress (from :meth:`Prestress.modes`).

    Attributes
    ----------
    omega : ndarray, shape (n,)
        Natural frequencies (rad/s), ascending.
    shapes : ndarray, shape (ndof, n)
        Mode shapes, mass-normalised (``shapes.T @ M @ shapes = I``, unit kg^-1/2),
        each with its largest entry real and positive (a sector's: complex, on its
        independent DOFs, in the nodal diameter asked for).
    """

    omega: np.ndarray
    shapes: np.ndarray

    @property
    def frequency(self) -> np.ndarray:
        """Natural frequencies (Hz), shape ``(n,)``."""
        return self.omega / (2 * np.pi)

    def __len__(self) -> int:
        return self.omega.size

    def __repr__(self) -> str:
        shown = ", ".join(f"{f:.6g}" for f in self.frequency[:6])
        return f"PrestressedModes({len(self)} modes: {shown}{', ...' if len(self) > 6 else ''} Hz)"


@dataclass(frozen=True, eq=False)
class Prestress:
    """A structure's static state under its static loads with a chosen friction state (from
    :func:`~microslip.frequency.prestress`); ``nc`` contacts.

    Attributes
    ----------
    structure : Structure
        The structure as given (its solvers take ``prestress=`` this object
        with this very structure).
    prestressed : Structure
        What the dynamic analyses solve: the same matrices and contacts with
        the static loads on it (``static_force`` plus ``load``) and, with the
        friction released, each contact's sliders reset at its static
        displacement (:attr:`Contact.reference
        <microslip.frequency.Contact>`), so the dynamic analysis begins stuck
        at the prestressed state with no tangential force.
    friction : {"released", "stuck"}
        The friction state of the static step.
    load : ndarray, shape (ndof,)
        The static load given to the prestress (N), besides the structure's
        own preloads and static forces.
    displacement : ndarray, shape (ndof,)
        The static displacement (m).
    normal_force, tangential_force, tangential_force2 : ndarray, shape (nc,)
        Each contact's normal load and tangential force (N) at the static
        state (zero tangential force with the friction released;
        ``tangential_force2`` the second component of a contact on its plane).
    closed_elements : ndarray of int, shape (nc,)
        Elements of each contact closed at the static state.
    tangential_displacement, tangential_displacement2, normal_approach : ndarray, shape (nc,)
        Each contact's tangential displacement (both components on its plane)
        and normal approach at the static state (m).
    reduction : str
        How the static problem was solved: ``"none"``, ``"exact"`` or ``"modal"``.
    """

    structure: Structure
    prestressed: Structure
    friction: str
    load: np.ndarray
    displacement: np.ndarray
    normal_force: np.ndarray
    tangential_force: np.ndarray
    tangential_force2: np.ndarray
    closed_elements: np.ndarray
    tangential_displacement: np.ndarray
    tangential_displacement2: np.ndarray
    normal_approach: np.ndarray
    reduction: str = "none"
    _modes: dict = field(default_factory=dict, repr=False)

    def __repr__(self) -> str:
        return (f"Prestress(friction={self.friction!r}, contacts={len(self.structure.contacts)}, normal force "
                f"{np.array2string(self.normal_force, precision=4)} N, closed elements "
                f"{self.closed_elements.tolist()})")

    # -- the static state ------------------------------------------------------------------
    def slip_share(self) -> np.ndarray:
        """``|T0| / (mu N0)`` of each contact, shape ``(nc,)``: 1 means gross slip statically, NaN an open contact."""
        mu = np.array([c.model.mu for c in self.structure.contacts])
        limit = mu * self.normal_force
        T = np.hypot(self.tangential_force, self.tangential_force2)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(limit > 0, T / np.where(limit > 0, limit, 1.0), np.nan)

    def summary(self) -> str:
        """The static state in words: one line for the prestress, one per contact."""
        lines = [f"Prestress with the friction {self.friction}: static load {np.abs(self.load).sum():.6g} N given "
                 f"(plus the structure's preloads and static forces), largest static displacement "
                 f"{np.max(np.abs(self.displacement), initial=0.0):.6g} m"
                 + ("; the contacts' sliders reset there" if self.friction == "released" else "") + "."]
        share = self.slip_share()
        for c, contact in enumerate(self.structure.contacts):
            T = float(np.hypot(self.tangential_force[c], self.tangential_force2[c]))
            state = "open" if np.isnan(share[c]) else f"{share[c]:.3g} of mu N0"
            lines.append(f"  {contact.name}: normal force N0 = {self.normal_force[c]:.6g} N, tangential force "
                         f"|T0| = {T:.6g} N ({state}), {self.closed_elements[c]} of {contact.model.elements} "
                         f"elements closed, t0 = {self.tangential_displacement[c]:.6g} m, n0 = "
                         f"{self.normal_approach[c]:.6g} m")
        return "\n".join(lines)

    def columns(self) -> dict:
        """One row per contact, named columns with units (for CSV)."""
        contacts = self.structure.contacts
        return {"contact": np.array([c.name for c in contacts], dtype=object),
                "N0 [N]": self.normal_force, "T0 [N]": self.tangential_force, "T0_2 [N]": self.tangential_force2,
                "|T0| / mu N0 [-]": self.slip_share(), "closed elements [-]": self.closed_elements,
                "elements [-]": np.array([c.model.elements for c in contacts]),
                "t0 [m]": self.tangential_displacement, "t0_2 [m]": self.tangential_displacement2,
                "n0 [m]": self.normal_approach}

    def to_csv(self, path):
        """Write :meth:`columns` to ``path`` as CSV (atomically). Returns the path."""
        path = _checks.file_path("path", path)
        return write_csv(path, self.columns())

    def plot(self, ax=None, **kwargs):
        """Bar chart of each contact's static normal load and tangential force (N).

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Where to draw (a new figure if omitted).
        **kwargs
            Passed to ``Axes.bar``.

        Returns
        -------
        matplotlib.axes.Axes
        """
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(6, 4))
        names = [c.name for c in self.structure.contacts]
        x = np.arange(len(names))
        ax.bar(x - 0.2, self.normal_force, 0.4, label="normal load N0", **kwargs)
        ax.bar(x + 0.2, np.hypot(self.tangential_force, self.tangential_force2), 0.4, label="tangential |T0|",
               **kwargs)
        ax.set_xticks(x, names)
        ax.set_ylabel("static force (N)")
        ax.set_title(f"prestress, friction {self.friction}")
        ax.grid(True, axis="y", alpha=0.3)
        ax.legend()
        return ax

    # -- the linear prestressed structure ---------------------------------------------------
    def stiffness(self):
        """Stiffness of the structure with its contacts stuck at the prestress (N/m), ``(ndof, ndof)``.

        ``K`` plus, for every element closed at the static state, ``kt`` along
        the contact's tangential direction(s) and ``kn`` along its normal; an
        open element adds nothing. Stored like ``K`` (dense or sparse). It is
        the stiffness the dynamic analysis sees at small amplitude.
        """
        self._refuse_sector("stiffness", "modes(n, nodal_diameter)")
        return stuck_matrices(self.prestressed, self.displacement)[2]

    def _refuse_sector(self, what: str, instead: str) -> None:
        if isinstance(self.structure, CyclicStructure):
            raise ValueError(f"{what} is for a structure that is not cyclic; a sector's prestressed stiffness depends "
                             f"on the nodal diameter: use {instead}")

    def modes(self, n: int = 6, nodal_diameter: int | None = None) -> PrestressedModes:
        """The ``n`` lowest linear modes of the structure with its contacts stuck at the prestress.

        Parameters
        ----------
        n : int, default 6
            Number of modes (at most ``ndof``; at most ``ndof - 1`` for a
            sparse structure above :data:`~microslip.frequency.equations.epmc.DENSE_EIGEN` DOFs).
        nodal_diameter : int, optional
            For a :class:`~microslip.frequency.CyclicStructure` sector (required
            there): the modes of that nodal diameter (0 to ``N - 1``), on the
            sector's independent DOFs (complex shapes, mass-normalised
            ``shapes^H M shapes = I``).

        Returns
        -------
        PrestressedModes

        Raises
        ------
        ValueError
            ``n`` out of range, or a mode without stiffness (a part moving freely).
        """
        cyclic = isinstance(self.structure, CyclicStructure)
        if cyclic:
            if nodal_diameter is None:
                raise ValueError(f"nodal_diameter must be given for a CyclicStructure sector (0 to "
                                 f"{self.structure.sectors - 1})")
            nd = _checks.positive_int("nodal_diameter", nodal_diameter, minimum=0)
            if nd >= self.structure.sectors:
                raise ValueError(f"nodal_diameter must be below the number of sectors {self.structure.sectors}, "
                                 f"got {nd}")
            ndof = self.structure.independent.size
        elif nodal_diameter is not None:
            raise ValueError(f"nodal_diameter is only for a CyclicStructure sector, got {nodal_diameter!r}")
        else:
            nd, ndof = None, self.structure.ndof
        dense = ndof <= DENSE_EIGEN
        n = _checks.positive_int("n", n)
        if n > (ndof if dense else ndof - 1):
            raise ValueError(f"n must be at most {ndof if dense else ndof - 1} (the structure has {ndof} DOFs), "
                             f"got {n}")
        if (n, nd) not in self._modes:
            self._modes[(n, nd)] = self._solve_modes(n, dense, nd)
        return self._modes[(n, nd)]

    def _solve_modes(self, n: int, dense: bool, nodal_diameter: int | None) -> PrestressedModes:
        M, _, K = stuck_matrices(self.prestressed, self.displacement, nodal_diameter)
        if dense:
            Kd = K.toarray() if sp.issparse(K) else np.asarray(K)
            Md = M.toarray() if sp.issparse(M) else np.asarray(M)
            lam, vec = sla.eigh(0.5 * (Kd + Kd.conj().T), 0.5 * (Md + Md.conj().T), subset_by_index=[0, n - 1])
            refuse_indefinite(lam, Kd, Md, "the structure with its contacts stuck at the prestress")
        else:
            Ks, Ms = sp.csc_matrix(K), sp.csc_matrix(M)
            scale = float(np.median(np.abs(Ks.diagonal())) / np.median(np.abs(Ms.diagonal())))
            lam, vec = eigsh_repeatable(Ks, k=n, M=Ms, sigma=-1e-6 * scale, which="LM")
            refuse_indefinite(lam, Ks, Ms, "the structure with its contacts stuck at the prestress")
            order = np.argsort(lam)
            lam, vec = lam[order], vec[:, order]
            vec = vec / np.sqrt(np.real(np.einsum("ik,ik->k", vec.conj(), Ms @ vec)))
        if not lam[0] > 0:
            raise ValueError(f"the structure with its contacts stuck at the prestress has a mode without stiffness "
                             f"(natural frequency {np.sqrt(max(lam[0], 0.0)):.3g} rad/s): a part of it moves freely")
        big = vec[np.argmax(np.abs(vec), axis=0), np.arange(n)]
        vec = vec * (np.abs(big) / big)  # largest entry real and positive
        omega, shapes = np.sqrt(lam), vec
        omega.setflags(write=False)
        shapes.setflags(write=False)
        return PrestressedModes(omega, shapes)

    def modal_damping(self, ratios, modes: int | None = None) -> np.ndarray:
        """A viscous damping matrix (N s/m) with the given damping ratio on each prestressed mode.

        ``C = M Phi diag(2 zeta_k omega_k) Phi^T M`` over the ``n`` lowest modes of
        :meth:`modes` (mass-normalised ``Phi``): mode ``k`` of the prestressed
        structure gets the damping ratio ``zeta_k``, the modes above ``n`` none.

        Parameters
        ----------
        ratios : float or array_like, shape (n,)
            Damping ratios (dimensionless, ``>= 0``; 0.01 is 1 %): one per mode,
            or one for all ``modes``.
        modes : int, optional
            Number of modes (default: as many as ``ratios``, which must then be a list).

        Returns
        -------
        ndarray, shape (ndof, ndof)
            Dense (the modes couple every DOF); :meth:`with_damping` puts it on the structure.
        """
        scalar = np.ndim(ratios) == 0 and not isinstance(ratios, (str, bytes))
        zeta = _checks.positive_array("ratios", [ratios] if scalar else ratios, ndim=1, min_size=1, allow_zero=True)
        if modes is None:
            if scalar:
                raise ValueError("modes must be given with a single damping ratio (how many modes it applies to)")
            n = zeta.size
        else:
            n = _checks.positive_int("modes", modes)
            if n > self.structure.ndof:
                raise ValueError(f"modes must be at most the {self.structure.ndof} DOFs of the structure, got {n}")
            if zeta.size not in (1, n):
                raise ValueError(f"ratios must be one value or one per mode ({n}), got {zeta.size}")
        self._refuse_sector("modal_damping", "the assembled disk (CyclicStructure.assembled())")
        ndof = self.structure.ndof
        if ndof > MODAL_DAMPING_LIMIT:
            raise ValueError(f"modal_damping builds a dense ndof x ndof matrix; this structure has {ndof} DOFs "
                             f"(more than {MODAL_DAMPING_LIMIT}): use rayleigh_damping, which stays sparse")
        m = self.modes(n)
        M = self.prestressed.M
        MPhi = np.asarray(M @ m.shapes)
        C = (MPhi * (2 * np.broadcast_to(zeta, (n,)) * m.omega)) @ MPhi.T
        return _checks.finite_result("ratios", zeta, 0.5 * (C + C.T))

    def rayleigh_damping(self, ratios, modes=(1, 2)):
        """``C = alpha M + beta K_p`` (N s/m) with the given damping ratios on two prestressed modes.

        ``K_p`` is :meth:`stiffness` (the contacts stuck at the prestress), so the
        modes of :meth:`modes` stay the damped structure's and mode ``k`` gets
        ``zeta_k = alpha / (2 omega_k) + beta omega_k / 2``: exactly ``ratios`` on
        the two ``modes``. ``beta K_p`` damps the contacts' stuck stiffness too,
        a viscous damping that stays when they slide.

        Parameters
        ----------
        ratios : (float, float)
            Damping ratios (dimensionless, ``>= 0``) of the two modes.
        modes : (int, int), default (1, 2)
            Which modes (1: the lowest), different.

        Returns
        -------
        ndarray or scipy.sparse matrix, shape (ndof, ndof)
            Stored like ``K`` (dense, or sparse CSR).
        """
        self._refuse_sector("rayleigh_damping", "the assembled disk (CyclicStructure.assembled())")
        z = _checks.positive_array("ratios", ratios, ndim=1, allow_zero=True)
        if z.size != 2:
            raise ValueError(f"ratios must be two damping ratios, got {z.size}")
        if isinstance(modes, (str, bytes)) or np.ndim(modes) != 1 or len(modes) != 2:
            raise ValueError(f"modes must be two mode numbers such as (1, 2), got {modes!r}")
        k1, k2 = (_checks.positive_int(f"modes[{i}]", k) for i, k in enumerate(modes))
        if k1 == k2:
            raise ValueError(f"modes must be two different modes, got {modes!r}")
        if max(k1, k2) > self.structure.ndof:
            raise ValueError(f"modes must be at most the {self.structure.ndof} DOFs of the structure, got {modes!r}")
        w = self.modes(max(k1, k2)).omega[[k1 - 1, k2 - 1]]
        # zeta_k = alpha / (2 w_k) + beta w_k / 2, two equations in alpha and beta
        alpha, beta = np.linalg.solve([[0.5 / w[0], 0.5 * w[0]], [0.5 / w[1], 0.5 * w[1]]], z)
        M, K = self.prestressed.M, self.stiffness()
        _checks.finite_result("ratios", z, (alpha, beta))
        if sp.issparse(M) or sp.issparse(K):
            C = (alpha * sp.csr_matrix(M) + beta * sp.csr_matrix(K)).tocsr()
            _checks.finite_result("ratios", z, C.data)
            return C
        return _checks.finite_result("ratios", z, alpha * np.asarray(M) + beta * np.asarray(K))

    def with_damping(self, C) -> Prestress:
        """This prestress with the viscous damping ``C`` (N s/m, ``(ndof, ndof)``, symmetric) on the structure solved.

        The static state does not depend on ``C``; the dynamic analyses given
        the returned object solve :attr:`prestressed` with this damping
        (e.g. from :meth:`modal_damping` or :meth:`rayleigh_damping`).
        """
        ndof = self.structure.ndof
        if sp.issparse(C):
            C = sp.csr_matrix(C, dtype=np.float64)
            if not np.all(np.isfinite(C.data)):
                raise ValueError("C must be finite")
        else:
            C = _checks.real_array("C", C, ndim=2)
        if C.shape != (ndof, ndof):
            raise ValueError(f"C must have shape ({ndof}, {ndof}), got {C.shape}")
        check_symmetric("C", C, self.structure.dof_map)
        damped = _copy_structure(self.prestressed)
        damped.C = C
        return replace(self, prestressed=damped, _modes=self._modes)


def _copy_structure(structure: Structure) -> Structure:
    """A shallow copy of ``structure`` (the matrices shared) whose lists can change without changing the original's."""
    out = copy.copy(structure)
    for name, value in vars(structure).items():
        if isinstance(value, list):
            setattr(out, name, list(value))
    return out


def prestressed_structure(structure: Structure, prestress, force=None) -> Structure:
    """The structure a solver solves: ``structure`` itself, or with ``prestress`` its :attr:`Prestress.prestressed`.

    Parameters
    ----------
    structure : Structure
        The structure given to the solver.
    prestress : Prestress or None
        A prestress of that same structure (from :func:`~microslip.frequency.prestress`).
    force : array_like or mapping, optional
        The solver's excitation: with a prestress it may not carry a static
        part (key 0): the static loads are the prestress's.

    Raises
    ------
    TypeError, ValueError
        ``prestress`` not a :class:`Prestress`, of another structure, or a static force given twice.
    """
    if prestress is None:
        return structure
    if not isinstance(prestress, Prestress):
        raise TypeError(f"prestress must be None or a Prestress (from microslip.frequency.prestress), got "
                        f"{type(prestress).__name__}")
    if prestress.structure is not structure:
        raise ValueError("prestress was computed for another structure: give the structure that prestress() was given")
    if len(structure.contacts) != len(prestress.prestressed.contacts):
        raise ValueError(f"prestress was computed before contacts were added to the structure (it has "
                         f"{len(prestress.prestressed.contacts)}, the structure now {len(structure.contacts)}): "
                         f"compute the prestress again")
    if isinstance(force, Mapping) and 0 in force:
        f0 = structure.force_vector(force[0], "force[0]")
        if np.any(f0):
            raise ValueError("force[0]: with a prestress the static loads are the prestress's (give them to "
                             "prestress(structure, load)); the force of the dynamic analysis holds harmonics >= 1")
    return prestress.prestressed
