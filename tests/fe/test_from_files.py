"""Structure.from_files: a finite-element model from files, contacts and forces named by node."""

import numpy as np
import pytest
import scipy.io
import scipy.sparse as sp

from microslip import MicroslipModel
from microslip.fe import DofMap, blade
from microslip.frequency import Structure, frequency_point

JENKINS = MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0)  # slips at 1 N with an approach of 1 µm


@pytest.fixture
def chain_files(tmp_path):
    """A three-mass chain (nodes 11, 12, 13 along x) saved as one .mat file and a DOF map CSV."""
    K = sp.csr_matrix(np.array([[2.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.0]]) * 1e4)
    M, C = np.eye(3), 0.5 * np.eye(3)
    scipy.io.savemat(tmp_path / "chain.mat", {"M": M, "K": K, "C": C})
    DofMap([11, 12, 13], ["x", "x", "x"]).to_csv(tmp_path / "dofs.csv")
    return tmp_path, M, K, C


def test_one_file_with_a_dof_map(chain_files):
    folder, M, K, C = chain_files
    s = Structure.from_files(folder / "chain.mat", dof_map=folder / "dofs.csv")
    assert s.ndof == 3 and s.sparse
    np.testing.assert_array_equal(s.K.toarray(), K.toarray())
    np.testing.assert_array_equal(s.C, C)
    assert s.dof_map.names == ["11:x", "12:x", "13:x"]
    assert s.dof_index("13:x") == 2 and s.dof_index(1) == 1


def test_contacts_and_forces_named_by_node_equal_those_given_by_index(chain_files):
    folder, M, K, C = chain_files
    named = Structure.from_files(folder / "chain.mat", dof_map=folder / "dofs.csv")
    indexed = Structure(M, C, K)
    a = named.add_contact(JENKINS, tangential={"13:x": 1.0, "12:1": -1.0}, approach=1e-6)
    b = indexed.add_contact(JENKINS, tangential={2: 1.0, 1: -1.0}, approach=1e-6)
    np.testing.assert_array_equal(a.tangential, b.tangential)
    np.testing.assert_array_equal(named.add_contact(JENKINS, tangential="11:x", approach=1e-6).tangential,
                                  [1.0, 0.0, 0.0])
    same_row = named.add_contact(JENKINS, tangential={"11:x": 1.0, "11:1": 0.5}, approach=1e-6)
    np.testing.assert_array_equal(same_row.tangential, [1.5, 0.0, 0.0])  # coefficients of one DOF add up
    indexed.add_contact(JENKINS, tangential=0, approach=1e-6)
    indexed.add_contact(JENKINS, tangential=[1.5, 0.0, 0.0], approach=1e-6)
    np.testing.assert_array_equal(named.force_vector({"13:x": 2.0, 0: 1.0}), [1.0, 0.0, 2.0])
    np.testing.assert_array_equal(named.force_vector({"13:x": 2j}), [0.0, 0.0, 2j])
    # the whole harmonic balance sees the same model: identical solutions
    w = 150.0
    p_named = frequency_point(named, {1: {"13:x": 0.8}}, w, harmonics=3)
    p_indexed = frequency_point(indexed, [0.0, 0.0, 0.8], w, harmonics=3)
    np.testing.assert_array_equal(p_named.coefficients, p_indexed.coefficients)


def test_one_file_per_matrix(tmp_path):
    scipy.io.mmwrite(tmp_path / "m.mtx", np.eye(2))
    scipy.io.mmwrite(tmp_path / "k.mtx", sp.coo_matrix(np.array([[2.0, -1.0], [-1.0, 1.0]])))
    s = Structure.from_files(M=tmp_path / "m.mtx", K=tmp_path / "k.mtx")
    assert s.ndof == 2 and s.dof_map is None and not s.C.any()


def test_a_blade_written_to_files_and_read_back(tmp_path):
    """The FE blade through files: a damper contact on its platform named by node."""
    b = blade(300)
    sp.save_npz(tmp_path / "m.npz", b.M)
    sp.save_npz(tmp_path / "k.npz", b.K)
    b.dof_map.to_csv(tmp_path / "dofs.csv")
    s = Structure.from_files(M=tmp_path / "m.npz", K=tmp_path / "k.npz", dof_map=tmp_path / "dofs.csv")
    node = b.node_sets["platform_right"][0]
    c = s.add_contact(JENKINS, tangential={f"{node}:x": 1.0}, normal={f"{node}:y": -1.0}, preload=10.0)
    assert c.tangential[b.dof_map.index(f"{node}:x")] == 1.0 and c.tangential.sum() == 1.0
    assert c.normal[b.dof_map.index(f"{node}:y")] == -1.0 and c.normal.sum() == -1.0
    assert abs(s.K - b.K).max() == 0.0


@pytest.mark.parametrize("kwargs, error, message", [
    (dict(tangential={"14:x": 1.0}), ValueError,
     r"tangential: DOF '14:x': node 14 is not in the DOF map \(3 nodes, ids 11..13\); the nearest ids are 11, 12, 13"),
    (dict(tangential="12:y"), ValueError, r"tangential: DOF '12:y': node 12 has no component 'y'; it has 12:x"),
    (dict(tangential={"12": 1.0}), ValueError, r"tangential: DOF name '12' must be 'node:component'"),
    (dict(tangential={1.5: 1.0}), TypeError, r"tangential: DOF keys must be integers, got 1.5"),
    (dict(tangential={"12:x": "a"}), TypeError, r"tangential\['12:x'\] must be a real number, got 'a'"),
    (dict(tangential={"11:x": 1.0, "11:1": -1.0}), ValueError, r"tangential must not be all zeros"),
])
def test_name_errors(chain_files, kwargs, error, message):
    folder, *_ = chain_files
    s = Structure.from_files(folder / "chain.mat", dof_map=folder / "dofs.csv")
    with pytest.raises(error, match=message):
        s.add_contact(JENKINS, approach=1e-6, **kwargs)


def test_names_need_a_dof_map():
    s = Structure(np.eye(2), None, np.eye(2))
    with pytest.raises(TypeError, match=r"tangential: DOF keys must be integers, got '1:x' \(names such as "
                                        r"'1204:x' need a DOF map: Structure\(..., dof_map=...\)"):
        s.add_contact(JENKINS, tangential="1:x", approach=1e-6)
    with pytest.raises(TypeError, match=r"force: DOF keys must be integers, got '1:x'"):
        s.force_vector({"1:x": 1.0})


@pytest.mark.parametrize("call, error, message", [
    (lambda: Structure(np.eye(2), None, np.eye(2), dof_map=DofMap([1], ["x"])), ValueError,
     r"dof_map must have one row per DOF \(2\), got 1"),
    (lambda: Structure(np.eye(2), None, np.eye(2), dof_map=["1:x", "2:x"]), TypeError,
     r"dof_map must be a microslip.fe.DofMap, got list"),
    (lambda: Structure(np.eye(2), None, np.eye(2), dof_map=DofMap([1, 2], "xy")), TypeError,
     r"components must be a 1-D sequence"),
    (lambda: Structure(np.eye(2), None, np.eye(2)).force_vector({5: 1.0}), ValueError,
     r"force: DOF 5 is out of range for a structure with 2 DOFs"),
    (lambda: Structure(np.eye(2), None, np.eye(2)).force_vector({0: np.nan}), ValueError,
     r"force\[0\] must be finite, got nan"),
])
def test_structure_dof_map_errors(call, error, message):
    with pytest.raises(error, match=message):
        call()
