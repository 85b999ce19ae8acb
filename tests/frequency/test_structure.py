"""Structure and contacts: directions, preloads, input checks."""

import numpy as np
import pytest
import scipy.sparse as sp

from microslip import MicroslipModel
from microslip.frequency import Structure

MODEL = MicroslipModel(kt=[1e6], kn=[1e7], gaps=[0.0], mu=0.5)


def test_directions_from_index_mapping_and_vector():
    s = Structure(np.eye(3), None, np.eye(3))
    a = s.add_contact(MODEL, tangential=2, normal={0: 1.0, 1: -1.0}, preload=5.0)
    b = s.add_contact(MODEL, tangential=[0.0, 0.6, 0.8], approach=1e-6, name="wall")
    np.testing.assert_array_equal(a.tangential, [0, 0, 1])
    np.testing.assert_array_equal(a.normal, [1, -1, 0])
    assert (a.preload, a.approach, a.name) == (5.0, 0.0, "contact0")
    np.testing.assert_array_equal(b.normal, [0, 0, 0])
    assert b.approach == 1e-6 and b.name == "wall"
    assert repr(s) == "Structure(ndof=3, dense, contacts=2)"


def test_sparse_matrices_are_kept_sparse():
    s = Structure(sp.identity(4), sp.identity(4) * 0.1, sp.diags([2.0, 2.0, 2.0, 2.0]))
    assert s.sparse and s.ndof == 4
    assert np.allclose(s.force_vector([1, 2, 3, 4j]).imag, [0, 0, 0, 4])


@pytest.mark.parametrize("kwargs, message", [
    (dict(M=np.ones((2, 3)), C=None, K=np.eye(2)), "M must be a square matrix, got shape \\(2, 3\\)"),
    (dict(M=np.eye(2), C=None, K=np.eye(3)), "K must be 2 x 2 like M, got shape \\(3, 3\\)"),
    (dict(M=np.eye(2), C=[[np.inf, 0], [0, 0]], K=np.eye(2)), "C must be finite"),
    (dict(M=sp.csr_matrix(np.array([[np.nan]])), C=None, K=[[1.0]]), "M must be finite"),
])
def test_matrix_errors(kwargs, message):
    with pytest.raises((ValueError, TypeError), match=message):
        Structure(**kwargs)


@pytest.mark.parametrize("kwargs, message", [
    (dict(model="m", tangential=0, approach=1e-6), "model must be a microslip MicroslipModel, got str"),
    (dict(model=MODEL, tangential=5, approach=1e-6), "tangential: DOF 5 is out of range for a structure with 2 DOFs"),
    (dict(model=MODEL, tangential=[1.0], approach=1e-6), "tangential must have one coefficient per DOF \\(2\\), got 1"),
    (dict(model=MODEL, tangential=[0.0, 0.0], approach=1e-6), "tangential must not be all zeros"),
    (dict(model=MODEL, tangential=None, approach=1e-6), "tangential must name the DOF"),
    (dict(model=MODEL, tangential={"a": 1.0}, approach=1e-6), "tangential: DOF keys must be integers, got 'a'"),
    (dict(model=MODEL, tangential=0), "approach must be given \\(m\\) when normal is None"),
    (dict(model=MODEL, tangential=0, approach=1e-6, preload=3.0), "preload must be None when normal is None"),
    (dict(model=MODEL, tangential=0, normal=1, preload=-3.0), "preload must be non-negative, got -3.0"),
    (dict(model=MODEL, tangential=0, normal=1, approach="x"), "approach must be a real number, got 'x'"),
    (dict(model=MODEL, tangential=0, normal=1, name=""), "name must be a non-empty string"),
])
def test_contact_errors(kwargs, message):
    s = Structure(np.eye(2), None, np.eye(2))
    with pytest.raises((ValueError, TypeError), match=message):
        s.add_contact(**kwargs)


def test_duplicate_contact_name():
    s = Structure(np.eye(2), None, np.eye(2))
    s.add_contact(MODEL, tangential=0, normal=1, name="a")
    with pytest.raises(ValueError, match="name 'a' is already used"):
        s.add_contact(MODEL, tangential=1, normal=0, name="a")


def test_force_vector_errors():
    s = Structure(np.eye(2), None, np.eye(2))
    with pytest.raises(ValueError, match="force must have one entry per DOF \\(2\\), got 3"):
        s.force_vector([1, 2, 3])
    with pytest.raises(ValueError, match="force must be finite"):
        s.force_vector([1, np.nan])


@pytest.mark.parametrize("M, message", [
    (np.array([[-1.0]]), "M must be positive definite: its diagonal entry 0 is -1.0 \\(every DOF needs a positive"),
    (np.diag([1.0, 0.0]), "M must be positive definite: its diagonal entry 1 is 0.0"),
    (np.array([[1.0, 1.0], [1.0, 1.0]]), "M must be positive definite \\(a mass matrix\\); it is symmetric with a "
                                         "positive diagonal but singular or indefinite"),
    (np.array([[1.0, 2.0], [2.0, 1.0]]), "M must be positive definite \\(a mass matrix\\)"),
    (np.array([[1.0, 0.5], [0.0, 1.0]]), "M must be symmetric, got \\|M - M\\^T\\| up to 0.5"),
    (sp.csr_matrix(np.array([[1.0, 2.0], [2.0, 1.0]])), "M must be positive definite \\(a mass matrix\\)"),
    (sp.csr_matrix(np.array([[1.0, 1.0], [1.0, 1.0]])), "M must be positive definite \\(a mass matrix\\)"),
    (sp.diags([1.0, -2.0]), "M must be positive definite: its diagonal entry 1 is -2.0"),
])
def test_mass_matrix_must_be_symmetric_positive_definite(M, message):
    # before this check such an M was accepted and time integration failed later with a raw LinAlgError
    with pytest.raises(ValueError, match=message):
        Structure(M, None, np.eye(2) if M.shape[0] == 2 else [[1.0]])


def test_positive_definite_masses_are_accepted_dense_and_sparse():
    M = np.array([[2.0, 1.0, 0.0], [1.0, 2.0, 1.0], [0.0, 1.0, 2.0]])  # consistent-mass-like, eigenvalues > 0
    dense = Structure(M, None, np.eye(3))
    sparse = Structure(sp.csr_matrix(M), None, sp.identity(3))
    assert not dense.sparse and sparse.sparse and dense.ndof == sparse.ndof == 3
    np.testing.assert_array_equal(dense.M, M)
    np.testing.assert_array_equal(sparse.M.toarray(), M)
    # an indefinite one with the same (positive) diagonal is refused: the check is more than the diagonal
    with pytest.raises(ValueError, match="M must be positive definite"):
        Structure(np.array([[2.0, 3.0, 0.0], [3.0, 2.0, 0.0], [0.0, 0.0, 2.0]]), None, np.eye(3))


def test_assembled_contact_data():
    """``contact_directions``, ``preload_force``, ``packed_models`` and ``stuck_stiffness``, dense and sparse."""
    two = MicroslipModel(kt=[1e6, 2e6], kn=[1e7, 3e7], gaps=[0.0, 1e-6], mu=0.3)
    for sparse in (False, True):
        K = np.diag([1e5, 2e5, 3e5])
        s = Structure(sp.identity(3) if sparse else np.eye(3), None, sp.csr_matrix(K) if sparse else K)
        s.add_contact(MODEL, tangential=0, normal={1: 1.0, 2: -1.0}, preload=5.0)
        s.add_contact(two, tangential=[0.0, 0.6, 0.8], approach=2e-6)
        Bt, Bn, n0 = s.contact_directions()
        np.testing.assert_array_equal(Bt, [[1, 0], [0, 0.6], [0, 0.8]])
        np.testing.assert_array_equal(Bn, [[0, 0], [1, 0], [-1, 0]])
        np.testing.assert_array_equal(n0, [0.0, 2e-6])
        np.testing.assert_array_equal(s.preload_force(), [0.0, 5.0, -5.0])
        kt, kn, gaps, offsets, mu = s.packed_models()
        np.testing.assert_array_equal(kt, [1e6, 1e6, 2e6])
        np.testing.assert_array_equal(offsets, [0, 1, 3])
        np.testing.assert_array_equal(mu, [0.5, 0.3])
        expected = K + 1e6 * np.outer(Bt[:, 0], Bt[:, 0]) + 1e7 * np.outer(Bn[:, 0], Bn[:, 0]) \
            + 3e6 * np.outer(Bt[:, 1], Bt[:, 1])  # the second contact has no normal direction
        Ks = s.stuck_stiffness()
        assert sp.issparse(Ks) == sparse
        np.testing.assert_allclose(Ks.toarray() if sparse else Ks, expected, rtol=1e-15)
        np.testing.assert_array_equal(s.K.toarray() if sparse else s.K, K)  # K itself untouched
    empty = Structure(np.eye(2), None, np.eye(2))
    Bt, Bn, n0 = empty.contact_directions()
    assert Bt.shape == Bn.shape == (2, 0) and n0.shape == (0,)
    assert [a.size for a in empty.packed_models()] == [0, 0, 0, 1, 0]
