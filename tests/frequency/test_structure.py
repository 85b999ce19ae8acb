"""Structure and contacts: directions, preloads, input checks."""

import re

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
    (np.array([[1.0, 0.5], [0.0, 1.0]]), "M must be symmetric \\(\\|M - M\\^T\\| at most 1e-06 x max\\|M\\| = "
                                         "1e-06\\): M\\[0, 1\\] = 0.5 but M\\[1, 0\\] = 0.0, a difference of 0.5"),
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


# -- issue 24 item 4: non-symmetric matrices refused by name; an indefinite K where a path needs it -----------------

def _chain(n: int = 6) -> np.ndarray:
    K = np.diag([2e6] * n) - np.diag([1e6] * (n - 1), 1) - np.diag([1e6] * (n - 1), -1)
    K[-1, -1] = 1e6
    return K


@pytest.mark.parametrize("sparse", [False, True])
@pytest.mark.parametrize("which", ["K", "C"])
def test_a_non_symmetric_stiffness_or_damping_is_refused_naming_the_worst_entry(which, sparse):
    # before, Structure took it: craig_bampton then symmetrised it silently (7 % off the full solve here), the
    # modal reduction and nonlinear_modes' linear mode used half of it
    K = _chain()
    C = 1e-5 * K + 0.5 * np.eye(6)
    A = (K if which == "K" else C).copy()
    A[1, 2] *= 1.3
    A[0, 1] *= 1.0001  # a smaller asymmetry: the message names the worst pair
    mats = {"K": K, "C": C, which: sp.csr_matrix(A) if sparse else A}
    with pytest.raises(ValueError) as info:
        Structure(np.eye(6), mats["C"], mats["K"])
    worst = float(A[1, 2])
    assert str(info.value).startswith(f"{which} must be symmetric (|{which} - {which}^T| at most 1e-06 x "
                                      f"max|{which}| = ")
    assert f"{which}[1, 2] = {worst!r} but {which}[2, 1] = {float(A[2, 1])!r}" in str(info.value)
    assert "non-symmetric (gyroscopic) structures are not supported" in str(info.value)


def test_asymmetry_within_the_tolerance_is_accepted_and_names_come_from_the_dof_map():
    from microslip.fe import DofMap

    K = _chain()
    K[1, 2] *= 1 + 1e-7  # rounding of a printed file: accepted (the FE readers' tolerance, 1e-6 of max |K|)
    Structure(np.eye(6), None, K)
    K[1, 2] = -1000010.0
    names = DofMap([10, 10, 11, 11, 12, 12], ["x", "y"] * 3)
    with pytest.raises(ValueError, match=r"K\[1, 2\] \('10:y', '11:x'\) = -1000010.0 but K\[2, 1\] = -1000000.0"):
        Structure(np.eye(6), None, K, dof_map=names)


def _indefinite() -> Structure:
    K = _chain()
    K[3, 3] = -5e6  # indefinite: a negative eigenvalue
    s = Structure(np.eye(6), 0.5 * np.eye(6), K)
    s.add_contact(MODEL, tangential=0, normal=5, preload=1.0)
    return s


@pytest.mark.parametrize("keep, modes", [([0, 5], 4), ([0, 5], 1), ([0, 5], 0), ([0, 1, 2, 3, 4, 5], 0)])
def test_craig_bampton_refuses_an_indefinite_stiffness_naming_its_negative_eigenvalue(keep, modes):
    # before: the negative eigenvalue was reported as a 0 rad/s fixed-interface mode
    from microslip.frequency import craig_bampton

    with pytest.raises(ValueError, match=r"K must be positive semi-definite for a Craig-Bampton reduction \(the "
                                         r"(structure with the kept DOFs fixed|reduced structure)\): K phi = lambda M "
                                         r"phi has the negative eigenvalue -\d"):
        craig_bampton(_indefinite(), keep, modes)


def test_the_modal_reduction_and_the_stuck_mode_refuse_an_indefinite_stiffness():
    # (on up to 2000 DOFs frequency_response and nonlinear_modes stop before, at their static check)
    from microslip.frequency.equations.epmc import stuck_mode
    from microslip.frequency.reduction.choice import linear_part

    for sparse in (False, True):
        s = _indefinite()
        if sparse:
            s = Structure(sp.csr_matrix(s.M), sp.csr_matrix(s.C), sp.csr_matrix(s.K))
        lowest = float(np.linalg.eigvalsh(_indefinite().K)[0])
        negative = re.escape(f"{lowest:.6g}")
        with pytest.raises(ValueError, match=f"K must be positive semi-definite for a modal reduction: K phi = "
                                             f"lambda M phi has the negative eigenvalue {negative} rad\\^2/s\\^2"):
            linear_part(s, [0, 5], "modal", 3)
        with pytest.raises(ValueError, match="K must be positive semi-definite for the linear mode of the structure "
                                             "with its contacts stuck: K phi = lambda M phi has the negative "
                                             "eigenvalue -"):
            stuck_mode(s, np.zeros(6), 2)
