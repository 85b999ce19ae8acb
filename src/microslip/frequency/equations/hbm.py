"""Harmonic balance equations of a :class:`~microslip.frequency.structures.structure.Structure`.

Unknowns: the Fourier coefficients of every DOF, ``X`` of shape
``(2H+1, ndof)`` (harmonic-major, layout ``[c0, a1, b1, ..., aH, bH]``),
flattened to ``x`` of length ``n = (2H+1) ndof``. With ``tau = omega time``
the equations are

``R(x, omega) = (Kx + omega Cx - omega^2 Mx) x + sum_c L_c F_c(L_c^T x + a_c) - f = 0``

where ``Kx = I (x) K``, ``Mx = diag(0, 1, 1, 4, 4, ...) (x) M``, ``Cx`` the
harmonic derivative (blocks ``[[0, h], [-h, 0]]``) ``(x) C``, ``L_c`` picks the
contact's ``t`` and ``n`` coefficients and ``F_c`` are its AFT forces. The
static part (``h = 0``) carries the preloads and the static contact forces, so
the static normal approach is solved together with the vibration. The
Jacobian is exact: the linear part is analytic and the contact part comes
from the AFT kernel.
"""

from __future__ import annotations

from functools import cached_property
from typing import Mapping

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ...common import _checks
from ...kernels import aft as _aft, aft_plane as _aft_plane, harmonic_balance as _hbm
from ..numerics.blas import DENSE_LIMIT
from ..aft import (MAX_PERIODS, check_harmonics, check_periodic, check_samples, cycle_work, friction_work,
                   friction_work_plane)
from ..structures.structure import Structure



def harmonic_operators(H: int):
    """``(D, W)``: harmonic derivative ``d/dtau`` and ``-d^2/dtau^2`` in coefficient space, ``(2H+1, 2H+1)``."""
    nb = 2 * H + 1
    D = np.zeros((nb, nb))
    W = np.zeros((nb, nb))
    for h in range(1, H + 1):
        c, s = 2 * h - 1, 2 * h
        # d/dtau (a cos + b sin) = h b cos - h a sin
        D[c, s] = h
        D[s, c] = -h
        W[c, c] = W[s, s] = h * h
    return D, W


def harmonic_columns(H: int, ndof: int) -> tuple[np.ndarray, np.ndarray]:
    """``(lo, hi)``, each ``(nb ndof,)``: row ``r`` of the harmonic form of a linear operator is zero outside ``lo[r]:hi[r]``.

    ``I (x) K``, ``D (x) C`` and ``W (x) M`` couple the cosine and the sine of the
    same harmonic only: the row of coefficient ``p`` (harmonic ``h = (p + 1) // 2``)
    spans the columns of the coefficients ``0`` (for ``h = 0``) or ``2h - 1, 2h``.
    """
    p = np.arange(2 * H + 1)
    h = (p + 1) // 2
    first = np.where(h == 0, 0, 2 * h - 1)
    last = np.where(h == 0, 1, 2 * h + 1)
    return np.repeat(first * ndof, ndof).astype(np.int64), np.repeat(last * ndof, ndof).astype(np.int64)


def excitation(structure: Structure, force, H: int) -> np.ndarray:
    """Excitation coefficients ``(2H+1, ndof)`` (N) from ``force``.

    ``force`` is one vector of ``ndof`` amplitudes (real or complex) at the
    first harmonic, or a mapping ``{h: vector}`` with ``0 <= h <= H`` (``h = 0``
    a static force, real). A complex amplitude ``F`` means
    ``Re(F exp(i h omega time)) = Re F cos - Im F sin``.
    """
    nb = 2 * H + 1
    out = np.zeros((nb, structure.ndof))
    items = force.items() if isinstance(force, Mapping) else [(1, force)]
    for h, vec in items:
        if isinstance(h, bool) or not isinstance(h, (int, np.integer)):
            raise TypeError(f"force: harmonic keys must be integers, got {h!r}")
        if not 0 <= h <= H:
            raise ValueError(f"force: harmonic {h} is outside 0..harmonics = {H}")
        f = structure.force_vector(vec, f"force[{h}]" if isinstance(force, Mapping) else "force")
        if h == 0:
            if np.iscomplexobj(f) and np.any(f.imag):
                raise ValueError("force[0] (the static force) must be real")
            out[0] += f.real
        else:
            out[2 * h - 1] += f.real
            out[2 * h] -= f.imag if np.iscomplexobj(f) else 0.0
    return out


class HarmonicBalance:
    """Residual and exact Jacobian of the harmonic balance equations.

    Parameters
    ----------
    structure : Structure
        The structure with its contacts.
    force : array_like or mapping
        Excitation (N), see :func:`excitation`.
    harmonics : int
        Number of harmonics ``H`` (0: static problem).
    samples : int, optional
        AFT time samples per period (default
        :func:`~microslip.frequency.aft.default_samples`).
    max_periods : int
        Periods allowed for each contact to become periodic.
    """

    def __init__(self, structure: Structure, force, harmonics: int, *, samples: int | None = None,
                 max_periods: int = MAX_PERIODS):
        self._setup(structure, force, harmonics, samples, max_periods, getattr(structure, "ndof", 0))
        nb = self.nb
        D, W = harmonic_operators(self.H)
        self.dense = self.n <= DENSE_LIMIT
        if self.dense:
            dense = [A.toarray() if sp.issparse(A) else np.asarray(A) for A in
                     (structure.K, structure.C, structure.M)]
            self.Kx = np.kron(np.eye(nb), dense[0])
            self.Cx = np.kron(D, dense[1])
            self.Mx = np.kron(W, dense[2])
            self._columns = harmonic_columns(self.H, self.ndof)
        else:
            self.Kx = sp.kron(sp.identity(nb), sp.csr_matrix(structure.K), format="csc")
            self.Cx = sp.kron(sp.csr_matrix(D), sp.csr_matrix(structure.C), format="csc")
            self.Mx = sp.kron(sp.csr_matrix(W), sp.csr_matrix(structure.M), format="csc")
        # contact directions, (ndof, nc), and offsets of the normal approach
        self.Bt, self.Bn, self.n0 = structure.contact_directions()
        self.Bt2 = structure.second_tangential_directions()

    def _setup(self, structure, force, harmonics, samples, max_periods, unknown_dofs: int) -> None:
        """What every form of the equations shares: sizes, AFT tables, excitation, the contacts' laws."""
        if not isinstance(structure, Structure):
            raise TypeError(f"structure must be a microslip Structure, got {type(structure).__name__}")
        H = check_harmonics(harmonics, minimum=0)
        self.structure = structure
        self.H = H
        self.nb = nb = 2 * H + 1
        self.ndof = unknown_dofs
        self.n = nb * unknown_dofs
        self.samples = check_samples(samples, H)
        self.max_periods = _checks.positive_int("max_periods", max_periods)
        self.tables = _aft.tables(H, self.samples)
        self.f_ext = excitation(structure, force, H)
        self.nc = nc = len(structure.contacts)
        self.f_ext[0] += structure.preload_force()
        self.f = self.f_ext.ravel()
        self.packed = structure.packed_models()
        # work arrays of the AFT
        self.FT = np.zeros((nc, nb))
        self.FN = np.zeros((nc, nb))
        self.JTt = np.zeros((nc, nb, nb))
        self.JTn = np.zeros((nc, nb, nb))
        self.JNn = np.zeros((nc, nb, nb))
        self.periods = np.zeros(nc, dtype=np.int64)
        # contacts on their planes: the second tangential force and the derivatives it adds (zero elsewhere)
        self.planar = np.array([c.planar for c in structure.contacts], dtype=bool)
        # where each contact's sliders were reset (m): its law sees t - reference (zero unless prestressed)
        self.t_ref, self.t2_ref = structure.tangential_references()
        self.Bt2 = np.zeros((unknown_dofs, nc))  # the second directions on the unknowns (set by each form)
        self.FT2 = np.zeros((nc, nb))
        self.JT12, self.JT21, self.JT22, self.JT2n = (np.zeros((nc, nb, nb)) for _ in range(4))
        self._J_dummy = np.empty((0, 0))
        self._Rw_dummy = np.empty(self.n)

    @property
    def compiled(self) -> bool:
        """True when the residual and Jacobian come from the compiled dense kernel (contacts along one direction)."""
        return self.dense and isinstance(self.Kx, np.ndarray) and not self.planar.any()

    # -- pieces ---------------------------------------------------------------
    def local(self, x) -> tuple[np.ndarray, np.ndarray]:
        """Coefficients of every contact's ``t`` and ``n`` (m), each ``(nc, 2H+1)``, at the unknowns ``x`` (n,)."""
        return self._local(self._unknowns(x))

    def _local(self, x) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`local` without the check of ``x`` (the solvers' own vectors)."""
        X = np.reshape(x, (self.nb, self.ndof))
        xt = np.ascontiguousarray((X @ self.Bt).T)
        xn = np.ascontiguousarray((X @ self.Bn).T)
        xn[:, 0] += self.n0
        xt[:, 0] -= self.t_ref
        return xt, xn

    def _local2(self, x) -> np.ndarray:
        """Coefficients of every contact's second tangential displacement (m), ``(nc, 2H+1)`` (zero on one direction)."""
        xt2 = np.ascontiguousarray((np.reshape(x, (self.nb, self.ndof)) @ self.Bt2).T)
        xt2[:, 0] -= self.t2_ref
        return xt2

    def _aft(self, x) -> None:
        if not self.nc:
            return
        xt, xn = self._local(x)
        if self.planar.any():
            _aft_plane.aft_mixed_batch(*self.packed, self.planar, xt, self._local2(x), xn, *self.tables,
                                       _aft_plane.sweep_tables(self.H, self.samples), self.max_periods,
                                       self.FT, self.FN, self.JTt, self.JTn, self.JNn, self.FT2, self.JT12, self.JT21,
                                       self.JT22, self.JT2n, self.periods)
        else:
            _aft.aft_batch(*self.packed, xt, xn, *self.tables, self.max_periods,
                           self.FT, self.FN, self.JTt, self.JTn, self.JNn, self.periods)
        check_periodic(self.periods, self.max_periods)

    def dynamic_stiffness(self, omega: float):
        """``Z(omega) = Kx + omega Cx - omega^2 Mx``, shape ``(n, n)`` (dense or sparse CSC)."""
        omega = self._omega(omega)
        return self.Kx + omega * self.Cx - (omega * omega) * self.Mx

    def _unknowns(self, x) -> np.ndarray:
        """``x`` checked: a finite vector of the ``n`` unknowns."""
        x = np.asarray(x)
        if x.shape != (self.n,):
            raise ValueError(f"x must be a vector of the n = (2H+1) ndof = {self.n} unknowns "
                             f"(harmonic-major Fourier coefficients, m), got shape {x.shape}")
        return np.ascontiguousarray(_checks.real_array("x", x), dtype=np.float64)

    def _point(self, x, omega) -> tuple[np.ndarray, float]:
        """``x`` and ``omega`` checked: a finite vector of the ``n`` unknowns and a positive frequency."""
        return self._unknowns(x), self._omega(omega)

    @staticmethod
    def _omega(omega) -> float:
        """A positive frequency (rad/s) whose square ``omega^2 M`` needs is still a float."""
        omega = _checks.positive_scalar("omega", omega)
        _checks.finite_result("omega", omega, omega * omega)
        return omega

    def evaluate(self, x, omega: float, *, jacobian: bool = True):
        """Residual of the harmonic balance equations and its derivatives.

        Parameters
        ----------
        x : array_like, shape (n,)
            The unknowns: Fourier coefficients of every DOF (m), harmonic-major
            ``[c0 (ndof), a1 (ndof), b1 (ndof), ..., bH (ndof)]``, ``n = (2H+1) ndof``.
        omega : float
            Excitation frequency (rad/s), positive.
        jacobian : bool, default True
            Also return the derivatives.

        Returns
        -------
        R : ndarray, shape (n,)
            Residual (N), same layout as ``x``.
        Jx : ndarray or scipy.sparse CSC matrix, shape (n, n)
            ``dR/dx`` (N/m); only with ``jacobian``.
        R_omega : ndarray, shape (n,)
            ``dR/domega`` (N s); only with ``jacobian``.

        ``R`` alone when ``jacobian`` is False, else ``(R, Jx, R_omega)`` (fresh
        arrays). Dense problems use the compiled kernel of
        :mod:`microslip.kernels.harmonic_balance`; sparse ones :meth:`evaluate_reference`.

        Raises
        ------
        ValueError, TypeError
            ``x`` of the wrong shape or not finite, ``omega`` not positive and finite.
        """
        x, omega = self._point(x, omega)
        return self._evaluate(x, omega, jacobian=_checks.flag("jacobian", jacobian))

    def _evaluate(self, x, omega: float, *, jacobian: bool = True):
        """:meth:`evaluate` without the input checks (for the solvers, which build ``x`` themselves)."""
        if not self.compiled:
            return self._evaluate_reference(x, omega, jacobian=jacobian)
        n = self.n
        R = np.empty(n)
        J = np.empty((n, n)) if jacobian else self._J_dummy
        Rw = np.empty(n) if jacobian else self._Rw_dummy
        MD, xi = self._extra_damping()
        worst = _hbm.evaluate_dense(np.ascontiguousarray(x, dtype=np.float64), float(omega), self.Kx, self.Cx,
                                    self.Mx, MD, float(xi), *self._columns, self.f, self.Bt, self.Bn, self.n0, self.t_ref,
                                    *self.packed, *self.tables, self.max_periods, jacobian, R, J, Rw, self.FT, self.FN, self.JTt, self.JTn,
                                    self.JNn, self.periods)
        if worst < 0:
            check_periodic(self.periods, self.max_periods)
        return (R, J, Rw) if jacobian else R

    def _extra_damping(self) -> tuple[np.ndarray, float]:
        """``(MD, xi)``: a damping ``-xi MD`` (dense, harmonic form) added to ``Cx``; none here (``xi = 0``)."""
        return self.Kx, 0.0

    def evaluate_reference(self, x, omega: float, *, jacobian: bool = True):
        """As :meth:`evaluate`, with NumPy/SciPy array operations (any storage; ``Jx`` sparse CSC when sparse)."""
        x, omega = self._point(x, omega)
        return self._evaluate_reference(x, omega, jacobian=_checks.flag("jacobian", jacobian))

    def _evaluate_reference(self, x, omega: float, *, jacobian: bool = True):
        Z = self.dynamic_stiffness(omega)
        R = Z @ x - self.f
        if self.nc:
            self._aft(x)
            R += self._contact_residual()
        if not jacobian:
            return R
        Jx = Z + self._contact_jacobian() if self.nc else Z
        return R, Jx, self._omega_derivative(x, omega)

    def _omega_derivative(self, x, omega: float) -> np.ndarray:
        """``dR/domega`` (N s), shape ``(n,)``: the linear part's, the contact forces not depending on omega."""
        return self.Cx @ x - 2.0 * omega * (self.Mx @ x)

    @cached_property
    def _pattern(self) -> tuple:
        """Where the contact Jacobian's entries go (sparse path), computed once.

        Every non-zero of every contact's outer products ``bt bt^T``, ``bt bn^T``,
        ``bn bn^T`` for every pair of harmonics ``(p, q)``: ``(rows, cols, which,
        contact, value, p, q)`` so that one vectorised product and one COO sum
        assemble the whole Jacobian, whatever the number of contacts.
        """
        rows, cols, which, contact, value = [], [], [], [], []
        for c in range(self.nc):
            bt, bn, bt2 = self.Bt[:, c], self.Bn[:, c], self.Bt2[:, c]
            pairs = ((bt, bt), (bt, bn), (bn, bn))
            if self.planar[c]:  # the blocks of JT12, JT21, JT22, JT2n (see _contact_jacobian)
                pairs += ((bt, bt2), (bt2, bt), (bt2, bt2), (bt2, bn))
            for k, (u, v) in enumerate(pairs):
                iu, iv = np.flatnonzero(u), np.flatnonzero(v)
                I, Jj = np.meshgrid(iu, iv, indexing="ij")
                rows.append(I.ravel())
                cols.append(Jj.ravel())
                value.append(np.outer(u[iu], v[iv]).ravel())
                which.append(np.full(I.size, k))
                contact.append(np.full(I.size, c))
        rows, cols, which, contact, value = (np.concatenate(a) for a in (rows, cols, which, contact, value))
        p, q = np.meshgrid(np.arange(self.nb), np.arange(self.nb), indexing="ij")
        p, q = p.ravel(), q.ravel()
        R = (p[:, None] * self.ndof + rows[None, :]).ravel()
        C = (q[:, None] * self.ndof + cols[None, :]).ravel()
        return R, C, which, contact, value, p, q

    def _contact_jacobian(self):
        # one pass: every non-zero of every contact's outer products times its harmonic block
        R, C, which, contact, value, p, q = self._pattern
        blocks = [self.JTt, self.JTn, self.JNn]
        if self.planar.any():
            blocks += [self.JT12, self.JT21, self.JT22, self.JT2n]
        blocks = np.stack(blocks)  # (3 or 7, nc, nb, nb)
        data = (blocks[which[None, :], contact[None, :], p[:, None], q[:, None]] * value[None, :]).ravel()
        if self.dense:  # summed into the dense matrix (contacts may share DOFs)
            return np.bincount(self._dense_pattern, weights=data, minlength=self.n * self.n).reshape(self.n, self.n)
        return sp.csc_matrix((data, (R, C)), shape=(self.n, self.n))

    @cached_property
    def _dense_pattern(self) -> np.ndarray:
        """Flat indices ``R n + C`` of :attr:`_pattern` into the dense Jacobian."""
        R, C = self._pattern[:2]
        return R.astype(np.int64) * self.n + C

    # -- linear algebra ---------------------------------------------------------
    def solve(self, A, b) -> np.ndarray:
        """Solve ``A z = b`` for the Newton and continuation steps.

        Parameters
        ----------
        A : ndarray or scipy.sparse matrix, shape (m, m)
            A Jacobian (``m = n``) or an :meth:`augmented` system (``m = n + 1``),
            in the units of its rows and columns (N/m, N s, ...).
        b : ndarray, shape (m,)
            Right-hand side.

        Returns
        -------
        ndarray, shape (m,)
            ``z``; all NaN when ``A`` is singular (the callers then shorten the step).
        """
        try:
            if sp.issparse(A):
                return spla.splu(A.tocsc()).solve(b)
            return np.linalg.solve(A, b)
        except (np.linalg.LinAlgError, RuntimeError):
            return np.full(np.shape(b), np.nan)

    def augmented(self, Jx, R_omega, row):
        """The bordered system of pseudo-arclength continuation, ``[[Jx, R_omega], [row]]``.

        Parameters
        ----------
        Jx : ndarray or scipy.sparse matrix, shape (n, n)
            ``dR/dx`` (N/m), possibly with scaled columns.
        R_omega : ndarray, shape (n,)
            ``dR/domega`` (N s), possibly scaled.
        row : ndarray, shape (n + 1,)
            The extra equation's coefficients (the arclength direction, in
            the continuation's scaled, dimensionless variables).

        Returns
        -------
        ndarray or scipy.sparse CSC matrix, shape (n + 1, n + 1)
            Dense when ``Jx`` is dense, sparse CSC when it is sparse.
        """
        if sp.issparse(Jx):
            return sp.vstack([sp.hstack([Jx, sp.csr_matrix(R_omega[:, None])]),
                              sp.csr_matrix(row[None, :])], format="csc")
        A = np.empty((self.n + 1, self.n + 1))
        A[:-1, :-1] = Jx
        A[:-1, -1] = R_omega
        A[-1] = row
        return A

    # -- quantities along a curve ------------------------------------------------------
    def _contact_residual(self) -> np.ndarray:
        """The contact forces' share of the residual (N), shape ``(n,)``, from the last AFT."""
        R = self.FT.T @ self.Bt.T + self.FN.T @ self.Bn.T
        if self.planar.any():
            R += self.FT2.T @ self.Bt2.T
        return R.ravel()

    def static_directions(self) -> tuple[np.ndarray, np.ndarray]:
        """Each contact's directions in the static problem ``(Bt, Bn)``, shape ``(ndof, nc)`` each."""
        return self.Bt, self.Bn

    def stuck_stiffness(self):
        """Stiffness of the unknowns with every contact element closed and stuck (N/m): see
        :meth:`Structure.stuck_stiffness <microslip.frequency.structures.structure.Structure.stuck_stiffness>`."""
        return self.structure.stuck_stiffness()

    def _full(self, x, omega: float) -> np.ndarray:
        """Coefficients of every DOF ``(2H+1, ndof)`` (m): here the unknowns themselves."""
        return np.reshape(x, (self.nb, self.ndof))

    def curve_quantities(self, xs, omegas, *, viscous: bool = True) -> dict:
        """Contact displacements and forces and the work per cycle at solutions ``xs`` ``(points, n)``.

        Returns a dict of arrays: ``t, n, T, N`` (m, N), shape ``(points, nc, 2H+1)``, and ``t2, T2``
        the second tangential displacement and force of the contacts on their planes (zero for the others);
        ``excitation``, ``viscous`` (J, ``(points,)``): work of the excitation and energy
        dissipated by ``C`` per cycle; ``contacts`` (J, ``(points, nc)``): energy dissipated by
        each contact, the friction work of its elements over the sampled period (never
        negative); ``contacts_harmonic``: the same from the force harmonics kept, which
        balances the other two exactly at a solution but carries the AFT's sampling error
        (of either sign where a contact opens); ``opens`` (bool, ``(points, nc)``): a contact
        opening and closing during the cycle.
        """
        xs = np.asarray(xs, dtype=float)
        P = xs.shape[0]
        X = xs.reshape(P, self.nb, self.ndof)
        excitation = cycle_work(self.f_ext.T, X.transpose(0, 2, 1)).sum(axis=-1)
        if viscous:
            # int q'^T C q' dtime = pi omega sum_h h^2 (a^T C a + b^T C b)
            V = X[:, 1:, :].reshape(-1, self.ndof)
            quad = np.einsum("ki,ki->k", V, np.asarray((self.structure.C @ V.T).T)).reshape(P, 2 * self.H)
            h2 = np.repeat(np.arange(1, self.H + 1) ** 2, 2)
            viscous = np.pi * np.asarray(omegas) * (quad @ h2)
        else:
            viscous = None
        out = {"t": np.zeros((P, self.nc, self.nb)), "n": np.zeros((P, self.nc, self.nb)),
               "T": np.zeros((P, self.nc, self.nb)), "N": np.zeros((P, self.nc, self.nb))}
        out["contacts"] = np.zeros((P, self.nc))
        out["opens"] = np.zeros((P, self.nc), dtype=bool)
        out["t2"], out["T2"] = np.zeros((P, self.nc, self.nb)), np.zeros((P, self.nc, self.nb))
        for k in range(P):
            if self.nc:
                out["t"][k], out["n"][k] = self._local(xs[k])
                self._aft(xs[k])
                out["T"][k], out["N"][k] = self.FT, self.FN
                out["contacts"][k], out["opens"][k] = friction_work(self.packed, out["t"][k], out["n"][k],
                                                                    self.tables[0], self.max_periods)
            if self.planar.any():
                out["t2"][k], out["T2"][k] = self._local2(xs[k]), self.FT2
                friction_work_plane(self.packed, self.planar, out["t"][k], out["t2"][k], out["n"][k],
                                    self.tables[0], self.max_periods, out["contacts"][k], out["opens"][k])
        out["contacts_harmonic"] = (cycle_work(out["T"], out["t"]) + cycle_work(out["N"], out["n"])
                                    + cycle_work(out["T2"], out["t2"]))
        out["excitation"], out["viscous"] = excitation, viscous
        return out
