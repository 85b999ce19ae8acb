"""The exact condensation's shortcuts against a dense reference: one solve when the matrices are symmetric
(``V = W``), the general path (a second, transposed solve) when they are not, real arithmetic without damping."""

import numpy as np
import pytest
import scipy.sparse as sp

from microslip.frequency.reduction.condensation import Condensation, _rayleigh

NDOF = 520  # interior above DENSE_INTERIOR: the sparse factorisation on the aligned pattern
RETAINED = np.array([3, 50, 51, 200, 333, 517])
OMEGA = 1.3e3  # rad/s, between natural frequencies of the held structure (checked by the conditioning below)


def chain(ndof: int, seed: int = 0):
    """Symmetric sparse M, C, K of a chain with second-neighbour springs and random properties."""
    rng = np.random.default_rng(seed)
    k1, k2 = rng.uniform(1e6, 3e6, ndof - 1), rng.uniform(1e5, 3e5, ndof - 2)
    K = sp.diags([k1, k2], [1, 2], shape=(ndof, ndof))
    K = -(K + K.T)
    K = K + sp.diags(-np.asarray(K.sum(axis=1)).ravel() + 1e5)  # grounded: positive definite
    M = sp.diags(rng.uniform(0.01, 0.03, ndof))
    C = 1e-6 * K + 3.0 * M
    return sp.csr_matrix(M), sp.csr_matrix(C), sp.csr_matrix(K)


def dense_reference(M, C, K, retained, h: int, omega: float):
    """``S`` by a dense Schur complement and ``dS/domega`` by a central difference (independent of the code)."""
    M, C, K = (A.toarray() if sp.issparse(A) else np.asarray(A) for A in (M, C, K))
    interior = np.setdiff1d(np.arange(M.shape[0]), retained)

    def schur(w):
        Z = K - (h * w) ** 2 * M + 1j * h * w * C
        r, i = retained, interior
        return Z[np.ix_(r, r)] - Z[np.ix_(r, i)] @ np.linalg.solve(Z[np.ix_(i, i)], Z[np.ix_(i, r)])

    step = 1e-6 * omega
    return schur(omega), (schur(omega + step) - schur(omega - step)) / (2 * step)


def relative(a, b) -> float:
    return float(np.linalg.norm(a - b) / np.linalg.norm(b))


@pytest.mark.parametrize("h", [1, 3])
def test_symmetric_shortcut_equals_the_general_path_to_rounding(h):
    M, C, K = chain(NDOF)
    shortcut = Condensation(M, C, K, RETAINED)
    assert shortcut.sparse and shortcut._symmetric
    general = Condensation(M, C, K, RETAINED)
    general._symmetric = False  # the transposed solve for V, as for non-symmetric matrices
    S1, dS1 = shortcut.harmonic(h, OMEGA)
    S2, dS2 = general.harmonic(h, OMEGA)
    # the same factorisation: V from the transposed solve differs from W by rounding only
    # (1e-12: a thousand times double precision, far below any physical difference)
    assert relative(S1, S2) < 1e-12 and relative(dS1, dS2) < 1e-12
    S_ref, dS_ref = dense_reference(M, C, K, RETAINED, h, OMEGA)
    assert relative(S1, S_ref) < 1e-10  # dense LU against sparse LU: rounding times the conditioning
    assert relative(dS1, dS_ref) < 1e-6  # central difference: measured 2e-9 to 4e-8 (truncation and rounding)


def test_non_symmetric_damping_takes_the_general_path_and_the_shortcut_would_be_wrong():
    M, C, K = chain(NDOF, seed=1)
    rng = np.random.default_rng(2)
    G = sp.random(NDOF, NDOF, density=4 / NDOF, random_state=rng) * 50.0
    C = sp.csr_matrix(C + G - G.T)  # a gyroscopic (skew) part: C is no longer symmetric
    cond = Condensation(M, C, K, RETAINED)
    assert not cond._symmetric
    S, dS = cond.harmonic(1, OMEGA)
    S_ref, dS_ref = dense_reference(M, C, K, RETAINED, 1, OMEGA)
    assert relative(S, S_ref) < 1e-10 and relative(dS, dS_ref) < 1e-6
    wrong = Condensation(M, C, K, RETAINED)
    wrong._symmetric = True  # V = W although Z is not symmetric: the derivative is then wrong
    _, dS_wrong = wrong.harmonic(1, OMEGA)
    assert relative(dS_wrong, dS_ref) > 1e-4  # so the tolerance above tells the two paths apart


def test_an_undamped_structure_is_condensed_in_real_arithmetic():
    M, _, K = chain(NDOF, seed=3)
    C = sp.csr_matrix((NDOF, NDOF))
    cond = Condensation(M, C, K, RETAINED)
    S, dS = cond.harmonic(2, OMEGA)
    assert not np.any(S.imag) and not np.any(dS.imag)  # exactly real: no complex factorisation
    S_ref, dS_ref = dense_reference(M, C, K, RETAINED, 2, OMEGA)
    assert relative(S, S_ref) < 1e-10 and relative(dS, dS_ref) < 1e-6


def test_dense_damping_with_sparse_mass_and_stiffness_gives_the_same_condensation():
    M, C, K = chain(NDOF, seed=4)
    S1, dS1 = Condensation(M, C, K, RETAINED).harmonic(1, OMEGA)
    S2, dS2 = Condensation(M, C.toarray(), K, RETAINED).harmonic(1, OMEGA)
    assert relative(S2, S1) < 1e-12 and relative(dS2, dS1) < 1e-12


def test_small_dense_interior_takes_the_same_shortcuts():
    M, C, K = chain(60, seed=5)
    retained = np.array([0, 17, 59])
    cond = Condensation(M.toarray(), C.toarray(), K.toarray(), retained)
    assert not cond.sparse and cond._symmetric
    S, dS = cond.harmonic(1, OMEGA)
    S_ref, dS_ref = dense_reference(M, C, K, retained, 1, OMEGA)
    assert relative(S, S_ref) < 1e-10 and relative(dS, dS_ref) < 1e-6


def test_the_interior_is_recovered_exactly():
    M, C, K = chain(NDOF, seed=6)
    cond = Condensation(M, C, K, RETAINED)
    q_r = np.linspace(1.0, 2.0, RETAINED.size) * 1e-6 * (1 - 0.5j)
    q_i = cond.interior_response(1, OMEGA, q_r)
    # the interior rows of the full dynamic equations carry no force
    Z = (K - OMEGA ** 2 * M + 1j * OMEGA * C).tocsr()
    q = np.zeros(NDOF, dtype=complex)
    q[RETAINED], q[cond.interior] = q_r, q_i
    residual = (Z @ q)[cond.interior]
    assert np.linalg.norm(residual) < 1e-10 * np.linalg.norm(abs(Z) @ np.abs(q))


def damping(kind: str, M, C, K, retained):
    """Damping matrices whose interior block the held structure's modes diagonalise."""
    if kind == "rayleigh":
        return C
    if kind == "undamped":
        return sp.csr_matrix(M.shape)
    if kind == "coupling":  # Rayleigh plus a dashpot from a retained DOF to an interior one, not on the diagonal:
        E = sp.lil_matrix(M.shape)  # C_ii stays classical, C_ri is no multiple of M_ri
        E[50, 52] = E[52, 50] = 0.5
        return sp.csr_matrix(C + E)
    if kind == "modal":  # damping of each mode of the held structure, no multiple of M_ii and K_ii
        interior = np.setdiff1d(np.arange(M.shape[0]), retained)
        Mi = M.toarray()[np.ix_(interior, interior)]
        lam, phi = np.linalg.eigh(np.linalg.solve(np.linalg.cholesky(Mi), np.linalg.solve(
            np.linalg.cholesky(Mi), K.toarray()[np.ix_(interior, interior)]).T))
        phi = np.linalg.solve(np.linalg.cholesky(Mi).T, phi)  # mass-normalised modes of the held structure
        Cd = np.zeros(M.shape)
        Cd[np.ix_(interior, interior)] = Mi @ phi @ np.diag(0.02 * np.sqrt(lam)) @ phi.T @ Mi
        return sp.csr_matrix((Cd + Cd.T) / 2)  # exactly symmetric
    raise ValueError(kind)


@pytest.mark.parametrize("kind", ["rayleigh", "undamped", "coupling", "modal"])
@pytest.mark.parametrize("ndof", [NDOF, 60])
def test_the_spectral_interior_equals_the_factorised_one(kind, ndof):
    M, C, K = chain(ndof, seed=7)
    retained = RETAINED if ndof == NDOF else np.array([3, 50, 51, 59])
    C = damping(kind, M, C, K, retained)
    if ndof < NDOF:
        M, C, K = M.toarray(), C.toarray(), K.toarray()
    curve, point = Condensation(M, C, K, retained), Condensation(M, C, K, retained)
    # a curve: the first frequencies are factorised (a sparse interior: one, a dense one: three), then the
    # modes are computed; this chain's spectrum is dense (a few modes cannot reach 3 x 1200 rad/s), so
    # every mode is, as for modal damping (not Rayleigh) and for a dense interior
    first = 1 if ndof == NDOF else 3
    for omega in np.linspace(900.0, 1100.0, first):
        curve.operator(omega, 3)
    assert curve._spectral == {}
    curve.operator(1200.0, 3)
    assert curve._spectral[0] is not None and curve._spectral[0].tail is None
    assert curve._spectral[0].lam.size == ndof - retained.size
    if kind in ("coupling", "modal"):
        assert curve._spectral[0].gamma is None  # the coupling's damping is not a multiple of its mass
    bM, bC, bK = curve._blocks(0)
    # C_ii = a M_ii + b K_ii is recognised (no n^3 modal damping product); modal damping is checked in the modes
    assert (_rayleigh(bM[3], bC[3], bK[3]) is None) == (kind == "modal")
    Z1, dZ1 = curve.operator(OMEGA, 4)
    Z2, dZ2 = point.operator(OMEGA, 4)
    # the same Schur complement by two routes: rounding times the conditioning of the held structure, which
    # is largest undamped near its resonances (measured 4e-11 there, 1e-13 to 3e-13 otherwise); a wrong term
    # in either route would show at 1e-3 or more
    assert relative(Z1, Z2) < 1e-9 and relative(dZ1, dZ2) < 1e-9
    q_r = np.linspace(1.0, 2.0, retained.size) * 1e-6 * (1 - 0.5j)
    assert relative(curve.interior_response(2, OMEGA, q_r), point.interior_response(2, OMEGA, q_r)) < 1e-9
    S_ref, dS_ref = dense_reference(M, C, K, retained, 1, OMEGA)
    S, dS = curve.harmonic(1, OMEGA)
    assert relative(S, S_ref) < 1e-10 and relative(dS, dS_ref) < 1e-6


def test_non_classical_damping_keeps_the_factorisation():
    M, C, K = chain(NDOF, seed=8)
    E = sp.lil_matrix(M.shape)
    E[100, 101] = E[101, 100] = 0.5  # a dashpot between two interior DOFs: the modes no longer diagonalise C_ii
    C = sp.csr_matrix(C + E)
    cond = Condensation(M, C, K, RETAINED)
    for omega in (900.0, 1000.0, 1100.0, 1200.0, 1300.0):
        cond.operator(omega, 2)
    assert cond._spectral == {0: None}
    S_ref, dS_ref = dense_reference(M, C, K, RETAINED, 1, OMEGA)
    S, dS = cond.harmonic(1, OMEGA)
    assert relative(S, S_ref) < 1e-10 and relative(dS, dS_ref) < 1e-6


def test_the_modal_condensation_with_diagonal_damping_equals_its_general_path():
    from microslip.frequency.reduction.modal import ModalCondensation

    M, C, K = chain(NDOF, seed=9)
    fast = ModalCondensation(M, C, K, RETAINED, 30)
    assert fast._damping is not None  # Rayleigh damping: diagonal in the modes
    general = ModalCondensation(M, C, K, RETAINED, 30)
    general._damping = None  # the full modal damping matrix, one harmonic at a time
    Z1, dZ1 = fast.operator(OMEGA, 4)
    Z2, dZ2 = general.operator(OMEGA, 4)
    assert relative(Z1, Z2) < 1e-11 and relative(dZ1, dZ2) < 1e-11  # the same algebra: rounding only
    E = sp.lil_matrix(M.shape)
    E[100, 101] = E[101, 100] = 0.5  # a dashpot between interior DOFs: no longer diagonal in the modes
    assert ModalCondensation(M, sp.csr_matrix(C + E), K, RETAINED, 30)._damping is None


@pytest.mark.parametrize("coupling", [False, True])
def test_the_series_of_the_omitted_modes_on_a_blade_equals_the_factorised_condensation(coupling):
    """A finite-element blade's held structure: its spectrum spreads far (16 modes reach about 100 kHz), so a
    few modes and the exact series of the others replace a factorisation per frequency and harmonic."""
    from microslip.fe import blade

    b = blade(1000, contact_nodes=5)
    retained = np.sort([b.dof_map.index(f"{n}:x") for n in b.platform_nodes] + [b.dof_map.index(f"{b.tip_node}:x")])
    C = 2e-7 * b.K
    if coupling:  # a dashpot from a retained DOF to an interior one: C_ri no multiple of M_ri
        j = int(retained[0])
        i = int(np.flatnonzero(b.K[j].toarray()[0])[0 if b.K[j].indices[0] != j else 1])
        E = sp.lil_matrix(b.K.shape)
        E[i, j] = E[j, i] = 0.3
        C = sp.csr_matrix(C + E)
    curve, point = Condensation(b.M, C, b.K, retained), Condensation(b.M, C, b.K, retained)
    curve.operator(8000.0, 7)
    assert curve._spectral == {}
    W = 2 * np.pi * np.array([1200.0, 1800.0])
    for omega in W:  # from the second frequency on: 16 modes and the series
        Z1, dZ1 = curve.operator(omega, 7)
        Z2, dZ2 = point.operator(omega, 7)
        # rounding times the conditioning (measured up to 1.3e-11); a missing or wrong term shows at 1e-3 or more
        assert relative(Z1, Z2) < 1e-10 and relative(dZ1, dZ2) < 1e-10
    spectral = curve._spectral[0]
    assert spectral.tail is not None and spectral.lam.size == 16 and (spectral.gamma is None) == coupling
    # far above: the series would converge too slowly with 16 modes, so more are computed
    Z1, dZ1 = curve.operator(2 * np.pi * 9000.0, 7)
    Z2, dZ2 = point.operator(2 * np.pi * 9000.0, 7)
    assert curve._spectral[0].lam.size > 16
    assert relative(Z1, Z2) < 1e-10 and relative(dZ1, dZ2) < 1e-10
