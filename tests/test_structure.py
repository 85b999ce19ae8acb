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
