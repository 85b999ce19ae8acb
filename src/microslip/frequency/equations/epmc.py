"""The equations of the extended periodic motion concept (EPMC, Krack 2015) for nonlinear modes.

The unforced structure with an added mass-proportional damping ``-xi M q'``,

``M q'' + (C - xi M) q' + K q + sum_c L_c F_c = f_static``,

has periodic solutions of frequency ``omega``; ``xi`` (1/s) is the negative
damping that makes up for what the viscous damping and the contacts dissipate,
so ``omega`` is the mode's natural frequency and ``xi / (2 omega)`` its
damping ratio at that amplitude. Harmonic balance as in
:class:`~microslip.frequency.equations.hbm.HarmonicBalance` (the contacts by AFT, the
static term an unknown), on every DOF or on the contact DOFs with the rest of
the structure condensed with the damping ``C - xi M``
(:class:`~microslip.frequency.reduction.condensation.Condensation`,
:class:`~microslip.frequency.reduction.modal.ModalCondensation`).

Normalisation: the modal amplitude ``a`` is the first harmonic of the
coordinate of the linear mode ``phi`` (the structure with its contacts stuck
at the static state, mass-normalised): with ``z_1 = a_1 - i b_1`` the complex
amplitude of every DOF's first harmonic,

``phi^T M z_1 = a``   (real: the phase condition ``phi^T M b_1 = 0``).

Unknowns, scaled so that every one is of order one along the curve: the
vibration relative to the amplitude, ``x = [x0_static + a chi, a psi]``
(``chi`` the shift of the static term, ``psi`` the harmonics), and ``omega``,
``xi``; the parameter of the continuation is ``s = ln a``. The residual is the
harmonic balance residual divided by ``a rho`` (``rho`` the stiffness force of
the linear mode), so the tolerance is relative to the amplitude at every
amplitude, plus the two normalisation equations.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from ...common._numeric import eigsh_repeatable
from ..numerics.krylov import Bordered
from .cyclic_balance import CyclicHarmonicBalance
from .hbm import HarmonicBalance, harmonic_operators
from .reduced import ReducedHarmonicBalance
from ..structures.structure import MANY_CONTACTS, Structure, add_rank_one_terms, refuse_indefinite

#: DOFs up to which the linear mode is found by a dense eigensolution (sparse matrices: a sparse one above
#: :data:`SPARSE_EIGEN`)
DENSE_EIGEN = 2000
SPARSE_EIGEN = 500
#: the normalisation equations are divided by this: on the contact DOFs the modal coordinate goes through the
#: held structure's dynamic stiffness, whose poles near the mode's frequency (a natural frequency of the structure
#: with its contact DOFs held) make it sensitive to omega and leave a rounding floor of about 1e-10 in it, above
#: which Newton's method could not converge at a tolerance of 1e-9. The modal amplitude reported is the
#: solution's own (:meth:`EpmcEquations.modal_amplitude`), whatever the residual of these equations.
NORMALISATION = 100.0


class _MassDamped:
    """The damping ``C - xi M`` in equations on the contact DOFs: the condensation carries ``xi`` (1/s), set before
    each evaluation; :meth:`xi_derivative` gives ``dR/dxi``."""

    xi = 0.0

    def dynamic_stiffness(self, omega: float):
        """The condensed ``Z(omega)`` with the damping ``C - xi M``, dense ``(n, n)`` (N/m)."""
        return self.linear.operator(omega, self.H, self.xi)[0]

    def _omega_derivative(self, x, omega: float) -> np.ndarray:
        return self.linear.operator(omega, self.H, self.xi)[1] @ x

    def xi_derivative(self, x, omega: float) -> np.ndarray:
        """``dR/dxi`` (N s), shape ``(n,)``."""
        return self.linear.operator(omega, self.H, self.xi)[2] @ x

    def functional(self, w, omega: float):
        """``(g, g_omega, g_xi)``: ``w . z_1 = g . z_1r`` over every DOF (see :meth:`.Condensation.projection`)."""
        return self.linear.projection(w, omega, self.xi)

    def _recovered(self, x, omega: float) -> np.ndarray:
        """Coefficients of every DOF the condensation holds, from the unknowns ``x``, with the damping ``C - xi M``."""
        return self.linear.recover(np.reshape(x, (self.nb, self.ndof)), omega, self.H, self.xi)


class DampedReducedBalance(_MassDamped, ReducedHarmonicBalance):
    """:class:`~.reduced.ReducedHarmonicBalance` with the damping ``C - xi M`` condensed with the structure."""

    def _full(self, x, omega: float) -> np.ndarray:
        return self._recovered(x, omega)


class DampedCyclicBalance(_MassDamped, CyclicHarmonicBalance):
    """:class:`~.cyclic_balance.CyclicHarmonicBalance` with the damping ``C - xi M`` condensed with the sector in
    each harmonic's nodal diameter (``engine_order`` is the mode's nodal diameter)."""

    def _independent(self, x, omega: float) -> np.ndarray:
        return self._recovered(x, omega)


class DampedBalance(HarmonicBalance):
    """:class:`~.hbm.HarmonicBalance` on every DOF with the damping ``C - xi M`` (``xi`` set before evaluating)."""

    xi = 0.0

    def __init__(self, structure: Structure, harmonics: int, **kwargs):
        super().__init__(structure, {}, harmonics, **kwargs)
        D = harmonic_operators(self.H)[0]
        M = structure.M
        self.MD = np.kron(D, M.toarray() if sp.issparse(M) else M) if self.dense else \
            sp.kron(sp.csr_matrix(D), sp.csr_matrix(M), format="csc")

    def _extra_damping(self) -> tuple[np.ndarray, float]:
        return self.MD, self.xi

    def _evaluate(self, x, omega: float, *, jacobian: bool = True):
        out = super()._evaluate(x, omega, jacobian=jacobian)
        if not self.xi or self.compiled:  # the compiled evaluation has the damping already
            return out
        MDx = self.MD @ x
        if not jacobian:
            return out - omega * self.xi * MDx
        R, J, Rw = out
        return R - omega * self.xi * MDx, J - (omega * self.xi) * self.MD, Rw - self.xi * MDx

    def xi_derivative(self, x, omega: float) -> np.ndarray:
        return -omega * (self.MD @ x)

    def functional(self, w, omega: float):
        zero = np.zeros(self.ndof, dtype=complex)
        return w.astype(complex), zero, zero


def stuck_matrices(structure: Structure, q0, nodal_diameter: int | None = None):
    """``(M, C, K)``: the linear structure with its contacts stuck at the static state ``q0`` (m, ``(ndof,)``).

    ``K`` adds to the structure's stiffness the elements closed at ``q0``:
    ``sum kt`` along ``b_t`` (and along the second tangential direction of a
    contact on its plane), ``sum kn`` along ``b_n`` (N/m); an open element adds
    nothing. Stored like the structure's ``K`` (dense or sparse). For a
    :class:`~.cyclic.CyclicStructure` the matrices of ``nodal_diameter``
    (:meth:`~.cyclic.CyclicStructure.matrices`, on the independent DOFs), a
    contact to the next sector acting along ``b_own + exp(-i phi) b_next``.
    """
    Bt, Bn, n0 = structure.contact_directions()
    if nodal_diameter is None:
        M, C, K, T, shift = structure.M, structure.C, structure.K.copy(), None, 0.0
        Bt_next = Bn_next = np.zeros_like(Bt)
    else:
        phase = structure.phase(1, nodal_diameter)
        M, C, K = structure.matrices(phase)
        T = structure.constraint(phase)
        shift = np.exp(-1j * phase) if phase else 1.0
        Bt_next, Bn_next = structure.contact_directions_next()
    Bt2 = structure.second_tangential_directions()  # zero for a contact along one direction
    terms = []
    for c, contact in enumerate(structure.contacts):
        closed = (Bn[:, c] + Bn_next[:, c]) @ q0 + n0[c] > contact.model.gaps
        pairs = [(Bt[:, c] + shift * Bt_next[:, c], contact.model.kt[closed].sum()),
                 (Bn[:, c] + shift * Bn_next[:, c], contact.model.kn[closed].sum())]
        if contact.tangential2 is not None:  # a contact on its plane sticks along both directions
            pairs.append((Bt2[:, c], contact.model.kt[closed].sum()))
        # t = h . z on the DOFs the matrices act on
        terms += [(b if T is None else np.asarray(T.T @ b), k) for b, k in pairs]
    K = add_rank_one_terms(K, terms, many=len(structure.contacts) >= MANY_CONTACTS)
    return M, C, K


def stuck_mode(structure: Structure, q0, mode: int, nodal_diameter: int | None = None):
    """``(lambda, phi, M, C)``: linear mode ``mode`` (1: the lowest) of the structure with its contacts stuck at ``q0``.

    The contacts add the stiffness of the elements closed at the static state
    ``q0`` (m, ``(ndof,)``): ``sum kt`` along ``b_t`` (and along the second
    tangential direction of a contact on its plane), ``sum kn`` along ``b_n``.
    ``phi`` is mass-normalised (``phi^H M phi = 1``, unit ``kg^-1/2``), its
    largest entry real and positive; ``lambda`` is its squared natural frequency
    (rad^2/s^2); ``M`` and ``C`` the mass and damping matrices it goes with. For a
    :class:`~.cyclic.CyclicStructure` the mode is that of ``nodal_diameter``, on
    the sector's independent DOFs (complex unless the diameter is 0 or ``N/2``),
    with that diameter's matrices (:meth:`~.cyclic.CyclicStructure.matrices`):
    a contact to the next sector acts along ``b_own + exp(-i phi) b_next``.
    An indefinite stiffness (a negative eigenvalue among the ``mode`` lowest) is
    refused by name.
    """
    M, C, K = stuck_matrices(structure, q0, nodal_diameter)
    n = K.shape[0]
    if n <= (SPARSE_EIGEN if sp.issparse(K) else DENSE_EIGEN):
        Kd = K.toarray() if sp.issparse(K) else np.asarray(K)
        Md = M.toarray() if sp.issparse(M) else np.asarray(M)
        lam, vec = sla.eigh(0.5 * (Kd + Kd.conj().T), Md, subset_by_index=[0, mode - 1])
        refuse_indefinite(lam, Kd, Md, "the linear mode of the structure with its contacts stuck")
        lam, phi = float(lam[-1]), vec[:, -1]
    else:
        Ms = sp.csc_matrix(M)
        scale = float(np.median(np.abs(K.diagonal())) / np.median(np.abs(Ms.diagonal())))
        lam, vec = eigsh_repeatable(sp.csc_matrix(K), k=mode, M=Ms, sigma=-1e-6 * scale, which="LM")
        refuse_indefinite(lam, K, Ms, "the linear mode of the structure with its contacts stuck")
        order = np.argsort(lam)
        lam, phi = float(lam[order[-1]]), vec[:, order[-1]]
        phi = phi / np.sqrt(np.real(phi.conj() @ (Ms @ phi)))
    if not lam > 0:
        raise ValueError(f"mode {mode} of the structure with its contacts stuck has no stiffness (natural frequency "
                         f"{np.sqrt(max(lam, 0.0)):.3g} rad/s): a part of it moves freely")
    big = phi[np.argmax(np.abs(phi))]
    phi = phi * (abs(big) / big)  # largest entry real and positive
    return lam, (phi.real if not np.iscomplexobj(K) and not np.iscomplexobj(M) else phi), M, C


class EpmcEquations:
    """Residual and exact Jacobian of the EPMC equations in the scaled unknowns of the module docstring.

    Parameters
    ----------
    hb : DampedBalance or DampedReducedBalance
        The harmonic balance equations with the damping ``C - xi M``, unforced.
    x_static : ndarray, shape (hb.ndof,)
        The static solution (m) on the unknown DOFs.
    weight : ndarray, shape (ndof,)
        ``M phi`` over every DOF of the structure (kg^1/2).
    shape_scale : float
        The largest entry of the linear mode over every DOF (kg^-1/2): the scale of
        ``psi`` (the contact DOFs may move far more, relative to the modal
        amplitude, once the contacts slide than while they stick).
    omega_scale : float
        The linear mode's natural frequency (rad/s).
    force_scale : float
        ``rho`` (N / (kg^1/2 m)): the stiffness force of the mode, per unit modal amplitude.

    Notes
    -----
    The problem interface of :func:`~microslip.frequency.numerics.continuation.continuation`:
    ``_evaluate(y, s)`` returns the residual, ``dr/dy`` and ``dr/ds`` (``s = ln a``).
    """

    solve = HarmonicBalance.solve
    augmented = HarmonicBalance.augmented

    def __init__(self, hb, x_static, weight, shape_scale: float, omega_scale: float, force_scale: float):
        self.hb = hb
        self.m = hb.ndof
        self.n = hb.n + 2
        self.x_static = np.zeros(hb.n)
        self.x_static[:self.m] = x_static
        self.weight = weight
        self.psi_scale = shape_scale
        self.omega_scale = omega_scale
        self.rho = force_scale

    # -- between the scaled unknowns and the physical ones ---------------------------------------------
    #: the unknowns whose interpolation error against the log amplitude sets the chord rule's steps (see
    #: ``StepControl.chord_error``): the frequency and ``xi``, what a backbone plots
    watched = (-2, -1)

    def unpack(self, y, s: float) -> tuple[np.ndarray, float, float]:
        """``(x, omega, xi)``: the harmonic balance unknowns (m), the frequency (rad/s) and ``xi`` (1/s)."""
        a = np.exp(s)
        return self.x_static + a * self.psi_scale * y[:-2], y[-2] * self.omega_scale, y[-1] * self.omega_scale

    def pack(self, x, omega: float, xi: float, s: float) -> np.ndarray:
        """The scaled unknowns of ``(x, omega, xi)`` at ``s = ln a``."""
        a = np.exp(s)
        return np.concatenate([(x - self.x_static) / (a * self.psi_scale),
                               [omega / self.omega_scale, xi / self.omega_scale]])

    def _first(self, y) -> np.ndarray:
        """``psi_a1 - i psi_b1`` (scaled by :attr:`psi_scale`): the first harmonic's complex amplitude per unit ``a``."""
        m = self.m
        return (y[m:2 * m] - 1j * y[2 * m:3 * m]) * self.psi_scale

    def modal_amplitude(self, x, omega: float, xi: float) -> complex:
        """``phi^T M z_1`` (kg^1/2 m) of the unknowns ``x`` at ``(omega, xi)``."""
        self.hb.xi = xi
        g = self.hb.functional(self.weight, omega)[0]
        m = self.m
        return complex(g @ (x[m:2 * m] - 1j * x[2 * m:3 * m]))

    # -- the problem interface of the continuation ---------------------------------------------------
    @property
    def operator_jacobian(self) -> bool:
        """True when the harmonic balance equations give their Jacobian as an operator (:meth:`_evaluate_operator`)."""
        return bool(getattr(self.hb, "operator_jacobian", False))

    def _evaluate(self, y, s: float, *, jacobian: bool = True):
        return self._residual(y, s, jacobian, operator=False)

    def _evaluate_operator(self, y, s: float):
        """As :meth:`_evaluate`, ``dr/dy`` a :class:`~microslip.frequency.numerics.krylov.Bordered` operator."""
        return self._residual(y, s, True, operator=True)

    def _residual(self, y, s: float, jacobian: bool, operator: bool):
        hb = self.hb
        a = np.exp(s)
        x, omega, xi = self.unpack(y, s)
        hb.xi = xi
        scale = a * self.rho  # the residual's scale at this amplitude
        g, g_omega, g_xi = hb.functional(self.weight, omega)
        p = self._first(y)
        eta = g @ p
        normal = np.array([eta.real - 1.0, eta.imag]) / NORMALISATION
        if not jacobian:
            return np.concatenate([hb._evaluate(x, omega, jacobian=False) / scale, normal])
        R, J, R_omega = hb._evaluate_operator(x, omega) if operator else hb._evaluate(x, omega)
        R_xi = hb.xi_derivative(x, omega)
        r = np.concatenate([R / scale, normal])
        m, c = self.m, self.psi_scale
        # d(g . p)/d(y_a1) = g c, d/d(y_b1) = -i g c; rows [Re, Im]
        rows = np.zeros((2, self.n))
        rows[:, m:2 * m] = np.stack([g.real, g.imag]) * c
        rows[:, 2 * m:3 * m] = np.stack([g.imag, -g.real]) * c
        e_omega, e_xi = (gp @ p * self.omega_scale for gp in (g_omega, g_xi))
        rows[:, -2] = e_omega.real, e_omega.imag
        rows[:, -1] = e_xi.real, e_xi.imag
        rows /= NORMALISATION
        columns = np.stack([R_omega, R_xi], axis=1) * (self.omega_scale / scale)
        r_s = np.zeros(self.n)
        if operator:
            Jy = Bordered(J.scaled(a * c / scale), columns, rows[:, :-2], rows[:, -2:])
            r_s[:-2] = J.matvec(x - self.x_static) / scale - r[:-2]  # dx/ds = x - x_static
            return r, Jy, r_s
        if sp.issparse(J):
            Jy = sp.vstack([sp.hstack([J * (a * c / scale), sp.csr_matrix(columns)]), sp.csr_matrix(rows)],
                           format="csc")
        else:  # filled in place: one pass over the matrix
            Jy = np.empty((self.n, self.n))
            np.multiply(J, a * c / scale, out=Jy[:-2, :-2])  # dx/dy = a c
            Jy[:-2, -2:] = columns
            Jy[-2:] = rows
        r_s[:-2] = J @ (x - self.x_static) / scale - r[:-2]  # dx/ds = x - x_static
        return r, Jy, r_s
