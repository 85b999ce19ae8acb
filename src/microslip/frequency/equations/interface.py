"""Harmonic balance of interface-dominated structures: every DOF an unknown, the Jacobian kept in its parts.

When the contacts use most of a structure's DOFs (a jointed structure reduced to relative interface
coordinates) a condensation keeps almost every DOF and costs more than it saves. These equations keep
every DOF, as :class:`~.hbm.HarmonicBalance` does, and hold the linear structure as its dense ``M``,
``C``, ``K``: harmonic ``h`` at ``omega`` acts on ``(a_h, b_h)`` through ``[[A, B], [-B, A]]`` with
``A = K - (h omega)^2 M`` and ``B = h omega C`` (``C - xi M`` for a nonlinear mode), never formed to
be applied: ``K``, ``M`` and ``C`` each multiply every harmonic's coefficients at once. The Jacobian is
returned to the solvers as a :class:`HarmonicOperator` -- those blocks plus each contact's small block
(its DOFs x harmonics), applied in ``O(ndof^2 H + contacts H^2)`` -- and assembled into a dense matrix
(only the entries asked for) when the solver factorises it (:mod:`~microslip.frequency.numerics.reuse`).
Other callers of ``_evaluate`` receive the dense Jacobian, as from :class:`~.hbm.HarmonicBalance`.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ...kernels.structure_products import structure_products
from ..aft import MAX_PERIODS
from ..numerics.blas import solver_threads
from ..numerics.krylov import block_index
from ..structures.structure import Structure
from .hbm import HarmonicBalance


def _dense(A) -> np.ndarray:
    return A.toarray() if sp.issparse(A) else np.asarray(A, dtype=float)


#: entries of a static state's contact Jacobian across harmonics up to this fraction of its largest entry in the
#: harmonic's own block are the AFT's rounding (a constant state couples no two harmonics), not a coupling
COUPLING_ROUNDING = 1e-12


class HarmonicOperator:
    """The harmonic balance Jacobian ``c (Z(omega) + J_contacts)`` as an operator, shape ``(n, n)`` (N/m).

    Parameters
    ----------
    static : ndarray, shape (ndof, ndof)
        The static block (N/m).
    A, B : ndarray, shape (H, ndof, ndof)
        Harmonic ``h``'s blocks: rows ``a_h`` get ``A a_h + B b_h``, rows ``b_h`` get ``A b_h - B a_h``.
    contacts : scipy.sparse matrix or None, shape (n, n)
        The contacts' Jacobian.
    factor : float, default 1
        ``c``.
    interior : ndarray of int, optional
        DOFs no contact touches (the contacts' Jacobian has no entry in their rows or columns): their
        unknowns are coupled by the linear structure alone, harmonic by harmonic (:meth:`groups`).
    """

    def __init__(self, static, A, B, contacts, factor: float = 1.0, interior=None, parts=None):
        self.static, self._A, self._B, self.contacts, self.factor = static, A, B, contacts, factor
        self.parts = parts  # (K, M, C, xi, W) of :meth:`of_structure`, else None
        self.ndof = static.shape[0]
        self.H = A.shape[0] if A is not None else parts[-1].size
        self.n = (2 * self.H + 1) * self.ndof
        self.shape = (self.n, self.n)
        self.interior = np.zeros(0, dtype=int) if interior is None else np.asarray(interior, dtype=int)

    @classmethod
    def of_structure(cls, K, M, C, omega: float, harmonics: int, contacts, factor: float = 1.0,
                     interior=None, xi: float = 0.0) -> "HarmonicOperator":
        """The operator of a structure ``K``, ``M``, ``C`` (each ``(ndof, ndof)``: N/m, kg, N s/m) at ``omega``
        (rad/s): ``A = K - (h omega)^2 M``, ``B = h omega (C - xi M)`` for ``h = 1..harmonics`` (``xi``, 1/s:
        a nonlinear mode's negative damping).

        Applied as three products of ``K``, ``M`` and ``C`` with every harmonic's coefficients at once, so the
        matrices are read once per product instead of once per harmonic and block; ``A`` and ``B`` are formed
        only when asked for (a dense block or the whole matrix).
        """
        W = omega * np.arange(1, harmonics + 1, dtype=float)
        return cls(K, None, None, contacts, factor, interior, parts=(K, M, C, float(xi), W))

    @property
    def A(self) -> np.ndarray:
        """Harmonic ``h``'s diagonal blocks ``A``, shape ``(H, ndof, ndof)`` (N/m)."""
        if self._A is None:
            K, M, _, _, W = self.parts
            self._A = K[None] - (W * W)[:, None, None] * M[None]
        return self._A

    @property
    def B(self) -> np.ndarray:
        """Harmonic ``h``'s coupling blocks ``B``, shape ``(H, ndof, ndof)`` (N/m)."""
        if self._B is None:
            _, M, C, xi, W = self.parts
            self._B = W[:, None, None] * (C - xi * M if xi else C)[None]
        return self._B

    def scaled(self, factor: float) -> "HarmonicOperator":
        """This operator times ``factor`` (the arrays shared)."""
        return HarmonicOperator(self.static, self._A, self._B, self.contacts, self.factor * factor, self.interior,
                                self.parts)

    def groups(self) -> list | None:
        """The interior DOFs' unknowns, harmonic by harmonic, and the unknowns each group is coupled to.

        Returns ``[(interior, coupled), ...]`` (index arrays; the static part first, then each harmonic's
        ``(a_h, b_h)``): the operator's entries in an interior group's rows and columns lie in the group or in
        its coupled unknowns, the contact DOFs of the same harmonic. None without interior DOFs. The factors
        of :mod:`~microslip.frequency.numerics.reuse` eliminate these groups before factorising the rest.
        """
        if self.interior.size == 0:
            return None
        m = self.ndof
        touched = np.setdiff1d(np.arange(m), self.interior)
        out = [(self.interior.copy(), touched.copy())]
        for h in range(1, self.H + 1):
            a, b = (2 * h - 1) * m, 2 * h * m
            out.append((np.concatenate([a + self.interior, b + self.interior]),
                        np.concatenate([a + touched, b + touched])))
        return out

    def _slot_block(self, row: int, col: int, rows: np.ndarray, cols: np.ndarray):
        """The linear part's block of harmonic slots ``(row, col)`` (slot 0 static, ``2h - 1`` and ``2h`` harmonic
        ``h``'s ``a_h`` and ``b_h``) at the DOFs ``rows`` x ``cols``, None where it is zero."""
        if row == col == 0:
            return self.static[np.ix_(rows, cols)]
        if row == 0 or col == 0 or (row + 1) // 2 != (col + 1) // 2:
            return None
        h = (row + 1) // 2 - 1
        ix = np.ix_(rows, cols)
        if self.parts is not None and self._A is None:  # the entries only, formed as A and B form them
            K, M, C, xi, W = self.parts
            if row == col:
                return K[ix] - (W[h] * W[h]) * M[ix]
            return (W[h] if row % 2 else -W[h]) * (C[ix] - xi * M[ix] if xi else C[ix])
        if row == col:
            return self.A[h][ix]
        return self.B[h][ix] if row % 2 else -self.B[h][ix]

    def submatrix(self, rows: np.ndarray, cols: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
        """The dense block ``J[rows][:, cols]`` (index arrays), built from the parts without the whole matrix
        (into ``out``, shape ``(rows.size, cols.size)``, when given)."""
        m = self.ndof
        r_slot, r_dof = np.divmod(rows, m)
        c_slot, c_dof = np.divmod(cols, m)
        if out is None:
            out = np.zeros((rows.size, cols.size))
        else:
            out[...] = 0.0
        c_sets = {int(c): np.flatnonzero(c_slot == c) for c in np.unique(c_slot)}
        for r in np.unique(r_slot):
            ri = np.flatnonzero(r_slot == r)
            for c, ci in c_sets.items():
                block = self._slot_block(int(r), c, r_dof[ri], c_dof[ci])
                if block is not None:
                    out[block_index(ri, ci)] = block
        if self.contacts is not None:
            if not sp.isspmatrix_csr(self.contacts):
                self.contacts = self.contacts.tocsr()  # rows picked once per block
                self.contacts.sum_duplicates()
            picked = self.contacts[rows][:, cols].tocoo()  # no two entries at one place: summed above
            out[picked.row, picked.col] += picked.data
        if self.factor != 1.0:
            out *= self.factor
        return out

    def linear(self, v: np.ndarray) -> np.ndarray:
        """The linear structure's part applied to ``v`` (without ``factor``), shape ``(n,)``."""
        if self.parts is not None:
            return structure_apply(*self.parts, v)
        return linear_apply(self.static, self.A, self.B, v)

    def matvec(self, v: np.ndarray) -> np.ndarray:
        out = self.linear(v)
        if self.contacts is not None:
            out += self.contacts @ v
        if self.factor != 1.0:
            out *= self.factor
        return out

    __matmul__ = matvec

    def toarray(self) -> np.ndarray:
        m, n = self.ndof, self.n
        out = np.zeros((n, n))
        out[:m, :m] = self.static
        for h in range(1, self.H + 1):
            a, b = slice((2 * h - 1) * m, 2 * h * m), slice(2 * h * m, (2 * h + 1) * m)
            out[a, a] = out[b, b] = self.A[h - 1]
            out[a, b] = self.B[h - 1]
            out[b, a] = -self.B[h - 1]
        if self.contacts is not None:
            C = self.contacts.tocoo()
            np.add.at(out, (C.row, C.col), C.data)  # summed where contacts share DOFs
        if self.factor != 1.0:
            out *= self.factor
        return out


def structure_apply(K, M, C, xi, W, v) -> np.ndarray:
    """``linear_apply`` of ``A = K - W^2 M``, ``B = W (C - xi M)`` (``W``, shape ``(H,)``: each harmonic's
    frequency, rad/s) without forming them: ``K``, ``M`` and ``C`` each multiply every harmonic's coefficients
    at once."""
    return structure_combine(*products(K, M, C, v), xi, W)


def products(K, M, C, v) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(V K^T, V M^T, V C^T)`` of the coefficients ``V = v.reshape(-1, ndof)`` (one row per harmonic slot)."""
    m = K.shape[0]
    V = np.ascontiguousarray(np.reshape(v, (-1, m)), dtype=float)
    KV, MV, CV = np.empty_like(V), np.empty_like(V), np.empty_like(V)
    structure_products(*(np.ascontiguousarray(A, dtype=float) for A in (K, M, C)), V, KV, MV, CV)
    return KV, MV, CV


def structure_combine(KV, MV, CV, xi, W) -> np.ndarray:
    """:func:`structure_apply` from the :func:`products` (not modified), shape ``(n,)``."""
    DV = CV - xi * MV if xi else CV
    w = np.repeat(W, 2)[:, None]
    out = KV.copy()
    out[1:] -= (w * w) * MV[1:]
    out[1::2] += W[:, None] * DV[2::2]
    out[2::2] -= W[:, None] * DV[1::2]
    return out.ravel()


def linear_apply(static, A, B, v) -> np.ndarray:
    """``[[static], [[A, B], [-B, A]] per harmonic] v``, ``v`` of shape ``(n,)`` harmonic-major."""
    m = static.shape[0]
    V = np.reshape(v, (-1, m))
    out = np.empty_like(V)
    out[0] = static @ V[0]
    a, b = V[1::2], V[2::2]
    out[1::2] = np.matmul(A, a[:, :, None])[:, :, 0] + np.matmul(B, b[:, :, None])[:, :, 0]
    out[2::2] = np.matmul(A, b[:, :, None])[:, :, 0] - np.matmul(B, a[:, :, None])[:, :, 0]
    return out.ravel()


class InterfaceBalance(HarmonicBalance):
    """Harmonic balance on every DOF of a dense structure, its Jacobian as a :class:`HarmonicOperator`.

    Parameters
    ----------
    structure : Structure
        The structure with its contacts (its matrices are held dense).
    force : array_like or mapping
        Excitation (N), see :func:`~.hbm.excitation`.
    harmonics : int
        ``H``.
    samples, max_periods
        As for :class:`~.hbm.HarmonicBalance`.

    Notes
    -----
    The unknowns and the residual are those of :class:`~.hbm.HarmonicBalance` on every DOF: the same
    equations, stored and solved differently.
    """

    xi = 0.0  # the damping is C - xi M (nonzero only for a nonlinear mode)
    #: the solvers ask :meth:`_evaluate_operator` for the Jacobian as an operator
    operator_jacobian = True

    def __init__(self, structure: Structure, force, harmonics: int, *, samples: int | None = None,
                 max_periods: int = MAX_PERIODS):
        self._setup(structure, force, harmonics, samples, max_periods, getattr(structure, "ndof", 0))
        self.dense = False  # the contacts' Jacobian sparse (HarmonicBalance._contact_jacobian)
        self.K, self.C, self.M = (np.ascontiguousarray(_dense(A)) for A in (structure.K, structure.C, structure.M))
        self.Bt, self.Bn, self.n0 = structure.contact_directions()
        self.Bt2 = structure.second_tangential_directions()
        touched = np.any(self.Bt != 0, axis=1) | np.any(self.Bn != 0, axis=1) | np.any(self.Bt2 != 0, axis=1)
        self.interior = np.flatnonzero(~touched)  # DOFs of no contact: coupled by the linear structure alone
        self._products_of = self._products_at = None

    @property
    def compiled(self) -> bool:
        return False

    def operator(self, omega: float, contacts: bool = False) -> HarmonicOperator:
        """``Z(omega)`` (with the contacts' Jacobian of the last AFT when ``contacts``) as an operator."""
        return HarmonicOperator.of_structure(self.K, self.M, self.C, omega, self.H,
                                             self._contact_jacobian() if contacts and self.nc else None,
                                             interior=self.interior, xi=self.xi)

    def dynamic_stiffness(self, omega: float):
        """``Z(omega)``, dense ``(n, n)`` (N/m)."""
        return self.operator(self._omega(omega)).toarray()

    def _residual(self, x, omega: float) -> np.ndarray:
        """``R`` (N), shape ``(n,)``; the AFT's forces and Jacobians are left for :meth:`_contact_jacobian`."""
        R = structure_combine(*self._products(x), self.xi, omega * np.arange(1, self.H + 1, dtype=float)) - self.f
        if self.nc:
            self._aft(x)
            R += self._contact_residual()
        return R

    def _evaluate_operator(self, x, omega: float):
        """``(R, Jx, R_omega)`` with ``Jx`` a :class:`HarmonicOperator` (for the solvers)."""
        R = self._residual(x, omega)
        return R, self.operator(omega, contacts=True), self._omega_derivative(x, omega)

    def _evaluate(self, x, omega: float, *, jacobian: bool = True):
        if not jacobian:
            return self._residual(x, omega)
        R, J, Rw = self._evaluate_operator(x, omega)
        return R, J.toarray(), Rw

    def response_scale(self, x_static, omegas) -> float:
        """Largest harmonic amplitude (m) of the response with the contacts linearised at the static state ``x_static``
        (``(n,)``, no harmonics) over the frequencies ``omegas`` (rad/s): ``max |dx|`` of ``J(omega) dx = -R``.

        At a state without harmonics the contacts' Jacobian couples no two harmonics, so each harmonic the
        residual (the excitation) has is solved alone (``2 ndof`` unknowns); a Jacobian that does couple them is
        solved whole.
        """
        with solver_threads():  # small dense solves: one BLAS thread
            return self._response_scale(np.asarray(x_static, dtype=float), omegas)

    def _response_scale(self, x_static, omegas) -> float:
        R, J, _ = self._evaluate_operator(x_static, float(omegas[0]))
        m, n = self.ndof, self.n
        contacts = J.contacts.tocsr() if J.contacts is not None else sp.csr_matrix((n, n))
        best = 0.0
        for h in range(1, self.H + 1):
            rows = slice((2 * h - 1) * m, (2 * h + 1) * m)
            if np.max(np.abs(R[rows])) <= 1e-13 * np.max(np.abs(R)):  # not excited: the AFT's rounding at most
                continue
            block = contacts[rows].toarray()
            # the AFT of a constant state leaves its rounding in other harmonics' columns, not a coupling
            across = max(np.max(np.abs(block[:, :rows.start]), initial=0.0),
                         np.max(np.abs(block[:, rows.stop:]), initial=0.0))
            coupled = across > COUPLING_ROUNDING * np.max(np.abs(block[:, rows]), initial=0.0)
            for w in omegas:
                if coupled:
                    dx = np.linalg.solve(self.operator(w, contacts=False).toarray() + contacts.toarray(), -R)[m:]
                else:
                    linear = self.operator(float(w))
                    A, B = linear.A, linear.B
                    try:
                        dx = _harmonic_solve(A[h - 1], B[h - 1], block[:, rows], -R[rows])
                    except np.linalg.LinAlgError:
                        continue
                if np.all(np.isfinite(dx)):
                    best = max(best, float(np.max(np.abs(dx))))
        return best if best > 0 else max(float(np.max(np.abs(x_static))), 1e-12)

    def _products(self, x):
        """``(V K^T, V M^T, V C^T)`` of ``x``'s coefficients ``V`` ``(2H+1, ndof)``, kept for the last ``x``: the
        residual and its derivatives in ``omega`` and ``xi`` at one point take them once."""
        if self._products_of is None or not np.array_equal(self._products_of, x):
            self._products_at = products(self.K, self.M, self.C, x)
            self._products_of = np.array(x, dtype=float)
        return self._products_at

    def _harmonic_products(self, x):
        """``(M v, (C - xi M) v, h)`` for the harmonics' coefficients ``v`` of ``x``, each ``(2H, ndof)``, and the
        harmonic of each row ``(2H, 1)``."""
        _, MV, CV = self._products(x)
        Mv = MV[1:]
        Cv = CV[1:] - self.xi * Mv if self.xi else CV[1:]
        return Mv, Cv, np.repeat(np.arange(1, self.H + 1, dtype=float), 2)[:, None]

    #: the same operations: the one compiled loop, the structure's products, is tested against its own twin
    _evaluate_reference = _evaluate

    def _omega_derivative(self, x, omega: float) -> np.ndarray:
        """``dR/domega`` (N s), shape ``(n,)``: ``dA/domega = -2 h^2 omega M``, ``dB/domega = h (C - xi M)``."""
        Mv, Cv, h = self._harmonic_products(x)
        out = np.zeros((self.nb, self.ndof))
        out[1:] = -2.0 * omega * h * h * Mv
        out[1::2] += h[0::2] * Cv[1::2]  # rows a_h: + B' b_h
        out[2::2] -= h[1::2] * Cv[0::2]  # rows b_h: - B' a_h
        return out.ravel()

    def xi_derivative(self, x, omega: float) -> np.ndarray:
        """``dR/dxi`` (N s), shape ``(n,)``: ``dB/dxi = -h omega M``."""
        Mv, _, h = self._harmonic_products(x)
        out = np.zeros((self.nb, self.ndof))
        out[1::2] = -omega * h[0::2] * Mv[1::2]
        out[2::2] = omega * h[1::2] * Mv[0::2]
        return out.ravel()

    def functional(self, w, omega: float):
        """``(w, 0, 0)``: a functional of every DOF is one of the unknowns (nothing condensed)."""
        zero = np.zeros(self.ndof, dtype=complex)
        return np.asarray(w).astype(complex), zero, zero.copy()


def _harmonic_solve(A, B, contacts, r) -> np.ndarray:
    """``([[A, B], [-B, A]] + contacts)^-1 r`` for one harmonic's ``(a_h, b_h)`` (``r`` and the result ``(2 m,)``).

    When ``contacts`` has the same form ``[[P, Q], [-Q, P]]`` (time-invariant, as at a state without harmonics)
    the system is ``(A + P + i (B + Q)) (a - i b) = r_a - i r_b``: ``m`` complex unknowns, half the work.
    """
    m = A.shape[0]
    P, Q = contacts[:m, :m], contacts[:m, m:]
    if np.array_equal(contacts[m:, m:], P) and np.array_equal(contacts[m:, :m], -Q):
        z = np.linalg.solve(A + P + 1j * (B + Q), r[:m] - 1j * r[m:])
        return np.concatenate([z.real, -z.imag])
    return np.linalg.solve(np.block([[A, B], [-B, A]]) + contacts, r)

