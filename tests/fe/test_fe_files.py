"""Matrix files: a round trip through every format, and every message of the readers."""

import sys

import h5py
import numpy as np
import pytest
import scipy.io
import scipy.sparse as sp

from _writers import chain, dense, write_mat73, write_npz, write_op4, write_op4_binary, write_op4_text
from microslip.fe import DofMap, read_matrices, read_matrix

N = 6
M_DENSE = np.diag(np.linspace(0.1, 0.6, N))
K_SPARSE = chain(N)
C_SPARSE = 1e-4 * chain(N, seed=1)


def _equal(read, expected, sparse):
    assert sp.issparse(read) == sparse
    if sparse:
        assert read.format == "csr"
    np.testing.assert_array_equal(dense(read), dense(expected))  # exact: every format stores doubles


WRITERS = {
    "mat4": (".mat", lambda p, v: scipy.io.savemat(p, v, format="4")),
    "mat5": (".mat", lambda p, v: scipy.io.savemat(p, v)),
    "mat7": (".mat", lambda p, v: scipy.io.savemat(p, v, do_compression=True)),
    "mat73": (".mat", write_mat73),
    "npz": (".npz", write_npz),
    "op4": (".op4", write_op4),
}


@pytest.mark.parametrize("kind", WRITERS)
def test_one_file_round_trip(tmp_path, kind):
    suffix, write = WRITERS[kind]
    path = tmp_path / f"model{suffix}"
    write(path, {"M": M_DENSE, "K": K_SPARSE, "C": C_SPARSE})
    M, K, C, dofs = read_matrices(path)
    _equal(M, M_DENSE, sparse=False)
    _equal(K, K_SPARSE, sparse=True)
    _equal(C, C_SPARSE, sparse=True)
    assert dofs is None


@pytest.mark.parametrize("kind", WRITERS)
def test_other_names_and_no_damping(tmp_path, kind):
    suffix, write = WRITERS[kind]
    path = tmp_path / f"model{suffix}"
    write(path, {"MGG": K_SPARSE / 1e6, "KGG": K_SPARSE, "B": M_DENSE})
    M, K, C, _ = read_matrices(path, names={"M": "MGG", "K": "KGG"})
    _equal(M, K_SPARSE / 1e6, sparse=True)
    _equal(K, K_SPARSE, sparse=True)
    assert C is None
    _equal(read_matrices(path, names={"M": "MGG", "K": "KGG", "C": "B"}).C, M_DENSE, sparse=False)


def test_matrix_market_one_file_per_matrix_dense_and_sparse(tmp_path):
    scipy.io.mmwrite(tmp_path / "m.mtx", M_DENSE)  # array format: dense
    scipy.io.mmwrite(tmp_path / "k.mtx", sp.coo_matrix(K_SPARSE), symmetry="symmetric")
    scipy.io.mmwrite(tmp_path / "c.mtx", sp.coo_matrix(C_SPARSE))
    (tmp_path / "c.mtx").rename(tmp_path / "c.mm")
    M, K, C, _ = read_matrices(M=tmp_path / "m.mtx", K=str(tmp_path / "k.mtx"), C=tmp_path / "c.mm")
    _equal(M, M_DENSE, sparse=False)
    _equal(K, K_SPARSE, sparse=True)
    _equal(C, C_SPARSE, sparse=True)


def test_one_file_per_matrix_in_any_format(tmp_path):
    sp.save_npz(tmp_path / "k.npz", sp.csc_matrix(K_SPARSE))  # one matrix, as scipy writes it
    sp.save_npz(tmp_path / "c.npz", sp.coo_matrix(C_SPARSE))
    scipy.io.savemat(tmp_path / "m.mat", {"mass_matrix": M_DENSE})  # the only variable, whatever its name
    M, K, C, _ = read_matrices(M=tmp_path / "m.mat", K=tmp_path / "k.npz", C=tmp_path / "c.npz")
    _equal(M, M_DENSE, sparse=False)
    _equal(K, K_SPARSE, sparse=True)
    _equal(C, C_SPARSE, sparse=True)
    _equal(read_matrix(tmp_path / "m.mat"), M_DENSE, sparse=False)
    _equal(read_matrix(tmp_path / "k.npz"), K_SPARSE, sparse=True)


def test_npz_sparse_as_compressed_columns_and_coordinates(tmp_path):
    csc, coo = sp.csc_matrix(K_SPARSE), sp.coo_matrix(K_SPARSE)
    np.savez(tmp_path / "a.npz", M=M_DENSE, K_data=csc.data, K_indices=csc.indices, K_indptr=csc.indptr,
             K_shape=csc.shape, K_format="csc", C_row=coo.row, C_col=coo.col, C_data=coo.data, C_shape=coo.shape)
    _, K, C, _ = read_matrices(tmp_path / "a.npz")
    _equal(K, K_SPARSE, sparse=True)
    _equal(C, K_SPARSE, sparse=True)


def test_a_dof_map_from_csv_or_object(tmp_path):
    scipy.io.savemat(tmp_path / "m.mat", {"M": M_DENSE, "K": K_SPARSE})
    dofs = DofMap(np.repeat([11, 12, 13], 2), ["x", "y"] * 3)
    assert read_matrices(tmp_path / "m.mat", dof_map=dofs.to_csv(tmp_path / "d.csv")).dof_map == dofs
    assert read_matrices(tmp_path / "m.mat", dof_map=dofs).dof_map is dofs


def test_round_off_asymmetry_is_accepted_and_removed(tmp_path):
    K = K_SPARSE.toarray()
    K[0, 1] *= 1 + 1e-9  # as a program printing 10 digits could leave it
    np.savez(tmp_path / "a.npz", M=M_DENSE, K=K)
    K_read = read_matrices(tmp_path / "a.npz").K
    np.testing.assert_array_equal(K_read, K_read.T)
    assert K_read[0, 1] == pytest.approx(K[0, 1], rel=1e-9)


# -- messages --------------------------------------------------------------------------------------
def _npz(tmp_path, **arrays):
    path = tmp_path / "bad.npz"
    np.savez(path, **arrays)
    return path


@pytest.mark.parametrize("arrays, message", [
    (dict(M=np.ones((2, 3)), K=np.eye(2)), r"bad.npz: M must be square, got shape \(2, 3\)"),
    (dict(M=np.ones(3), K=np.eye(3)), r"bad.npz: M must be a 2-D matrix, got an array of shape \(3,\)"),
    (dict(M=np.eye(2), K=[[1.0, 2.0], [3.0, 1.0]]),
     r"bad.npz: K must be symmetric: max\|A - A\^T\| = 1 exceeds 1e-06 x max\|A\| = 3e-06"),
    (dict(M=np.eye(2), K=[[1.0, np.nan], [np.nan, 1.0]]),
     r"bad.npz: K must be finite; it holds nan at row 0, column 1"),
    (dict(M=np.eye(2), K=np.eye(2), C=[[np.inf, 0], [0, 1]]),
     r"bad.npz: C must be finite; it holds inf at row 0, column 0"),
    (dict(M=np.eye(2), K=np.eye(3)),
     r"bad.npz: K is 3 x 3 but .*bad.npz: M is 2 x 2: M, K and C must have the same size"),
    (dict(M=np.eye(2) * 1j, K=np.eye(2)), r"bad.npz: M is complex; expected a real matrix"),
    (dict(M=np.array([["a", "b"], ["c", "d"]]), K=np.eye(2)), r"bad.npz: M holds <U1 values; expected real numbers"),
    (dict(M=np.eye(2)), r"bad.npz: no variable 'K'; the file holds M \(choose others with names="),
    (dict(M=np.eye(2), K_data=[1.0], K_indices=[0], K_indptr=[0, 1, 1], K_shape=[2, 2], K_format="dia"),
     r"bad.npz: K is stored as sparse format 'dia'; expected csr, csc or coo"),
    (dict(M=np.eye(2), K_data=[1.0], K_indptr=[0, 1, 1], K_shape=[2, 2]),
     r"bad.npz: K in csr format needs the arrays data, indices, indptr, shape; missing indices"),
    (dict(M=np.eye(2), K_data=[1.0], K_indices=[5], K_indptr=[0, 1, 1], K_shape=[2, 2]),
     r"bad.npz: K: indices\[0\] = 5 is not a column of the 2 x 2 matrix \(0..1\)"),
])
def test_messages_name_the_file_and_the_variable(tmp_path, arrays, message):
    with pytest.raises(ValueError, match=message):
        read_matrices(_npz(tmp_path, **arrays))


def test_a_sparse_non_finite_entry_is_located(tmp_path):
    K = K_SPARSE.copy()
    K[2, 3] = K[3, 2] = np.nan
    scipy.io.savemat(tmp_path / "m.mat", {"M": M_DENSE, "K": K})
    with pytest.raises(ValueError, match=r"m.mat: K must be finite; it holds nan at row 2, column 3"):
        read_matrices(tmp_path / "m.mat")


def test_the_tolerance_is_relative_to_the_largest_entry(tmp_path):
    K = np.array([[1e6, 1.0], [0.0, 1e6]])  # |K - K^T| = 1 = 1e-6 x 1e6: accepted; 1.01 is not
    read_matrices(_npz(tmp_path, M=np.eye(2), K=K))
    K[0, 1] = 1.01
    with pytest.raises(ValueError, match=r"K must be symmetric"):
        read_matrices(_npz(tmp_path, M=np.eye(2), K=K))
    read_matrices(_npz(tmp_path, M=np.eye(2), K=K), symmetry_tolerance=2e-6)


@pytest.mark.parametrize("kind", WRITERS)
def test_a_missing_variable_lists_those_present(tmp_path, kind):
    suffix, write = WRITERS[kind]
    path = tmp_path / f"model{suffix}"
    write(path, {"MGG": M_DENSE, "KAA": K_SPARSE})
    with pytest.raises(ValueError, match=r"model\.\w+: no variable 'M', 'K'; the file holds KAA, MGG"):
        read_matrices(path)
    with pytest.raises(ValueError, match=r"no variable 'CGG'; the file holds KAA, MGG"):
        read_matrices(path, names={"M": "MGG", "K": "KAA", "C": "CGG"})
    with pytest.raises(ValueError, match=r"model\.\w+: holds KAA, MGG; name the variable to read"):
        read_matrix(path)


def test_mat73_is_read_columns_first(tmp_path):
    """MATLAB stores a 2 x 3 matrix as a 3 x 2 HDF5 dataset; the reader must transpose it back."""
    write_mat73(tmp_path / "a.mat", {"M": np.ones((2, 3)), "K": sp.csr_matrix(np.ones((2, 3)))})
    with pytest.raises(ValueError, match=r"a.mat: M must be square, got shape \(2, 3\)"):
        read_matrix(tmp_path / "a.mat", "M")
    with pytest.raises(ValueError, match=r"a.mat: K must be square, got shape \(2, 3\)"):
        read_matrix(tmp_path / "a.mat", "K")


def test_mat73_text_and_groups_are_refused(tmp_path):
    write_mat73(tmp_path / "a.mat", {"M": np.array([["a"]])})
    with h5py.File(tmp_path / "a.mat", "a") as f:
        f.create_group("S").attrs["MATLAB_class"] = np.bytes_("struct")
    with pytest.raises(ValueError, match=r"a.mat: M is a MATLAB char array; expected a numeric matrix"):
        read_matrix(tmp_path / "a.mat", "M")
    with pytest.raises(ValueError, match=r"a.mat: S is a MATLAB struct \(e.g. a struct or cell\); expected a numeric"):
        read_matrix(tmp_path / "a.mat", "S")


@pytest.mark.parametrize("call, error, message", [
    (lambda p: read_matrices(p / "m.txt"), ValueError,
     r"m.txt: unknown matrix file suffix '.txt'; expected one of .mtx \(Matrix Market\), .mm \(Matrix Market\), "
     r".mat \(MATLAB\), .npz \(NumPy .npz\), .op4 \(Nastran OP4\)"),
    (lambda p: read_matrices(p / "none.mat"), FileNotFoundError, r"none.mat: no such file"),
    (lambda p: DofMap.from_csv(p / "none.csv"), FileNotFoundError, r"none.csv: no such file$"),
    (lambda p: read_matrices(p / "m.npz", M=p / "m.npz"), ValueError,
     r"give either one file \(path\) or one file per matrix \(M=, K=, C=\), not both"),
    (lambda p: read_matrices(M=p / "m.npz"), ValueError, r"give the matrices' file: one file holding M and K"),
    (lambda p: read_matrices(), ValueError, r"give the matrices' file"),
    (lambda p: read_matrices(3), TypeError, r"path must be a file path, got int"),
    (lambda p: read_matrices(p / "m.npz", names={"Mass": "M"}), ValueError,
     r"names: unknown key\(s\) 'Mass'; the keys are M, K, C \(mass, stiffness, damping\)"),
    (lambda p: read_matrices(p / "m.npz", names=["M"]), TypeError, r"names must be a mapping such as"),
    (lambda p: read_matrices(p / "m.npz", names={"M": 3}), TypeError,
     r"names\['M'\] must be a non-empty variable name"),
    (lambda p: read_matrices(p / "m.npz", dof_map=DofMap([1], ["x"])), ValueError,
     r"dof_map has 1 rows but the matrices have 2: one row per DOF, in the order of the matrix rows"),
    (lambda p: read_matrices(p / "m.npz", dof_map=[1, 2]), TypeError,
     r"dof_map must be a DofMap or the path of a node,component CSV file, got list"),
    (lambda p: read_matrices(p / "m.npz", symmetry_tolerance=-1), ValueError,
     r"symmetry_tolerance must be positive, got -1.0"),
    (lambda p: read_matrix(p / "junk.mtx"), ValueError, r"junk.mtx: line 1: not a Matrix Market matrix: the first "
                                                        r"line must be '%%MatrixMarket matrix FORMAT FIELD SYMMETRY'"),
    (lambda p: read_matrix(p / "junk.op4"), ValueError, r"junk.op4: line 1: expected a matrix header \(NCOL, NROW, "
                                                        r"FORM, TYPE as 8-character integers, the name, the format\)"),
    (lambda p: read_matrix(p / "junk.mat"), ValueError, r"junk.mat: neither a MATLAB v5 nor a v7.3 \(HDF5\) file"),
])
def test_call_errors(tmp_path, call, error, message):
    np.savez(tmp_path / "m.npz", M=np.eye(2), K=np.eye(2))
    for name in ("m.txt", "junk.mtx", "junk.op4", "junk.mat"):
        (tmp_path / name).write_text("these are not matrices\n")
    with pytest.raises(error, match=message):
        call(tmp_path)


def test_a_missing_optional_package_names_the_extra(tmp_path, monkeypatch):
    path = tmp_path / "model.mat"
    write_mat73(path, {"M": M_DENSE, "K": K_SPARSE})
    monkeypatch.setitem(sys.modules, "h5py", None)  # makes `import h5py` raise ImportError
    with pytest.raises(ImportError, match=r"needs the package h5py, which is not installed: "
                                          r"pip install microslip\[fe\]"):
        read_matrices(path)


def test_op4_files_are_read_without_pynastran(tmp_path, monkeypatch):
    write_op4(tmp_path / "model.op4", {"M": M_DENSE, "K": K_SPARSE})
    for module in ("pyNastran", "pyNastran.op4", "pyNastran.op4.op4"):
        monkeypatch.setitem(sys.modules, module, None)
    _equal(read_matrices(tmp_path / "model.op4").K, K_SPARSE, sparse=True)


def _scattered(n=9):
    """A symmetric matrix whose columns hold several strings of rows (pyNastran writes its columns out of order)."""
    rng = np.random.default_rng(3)
    A = np.zeros((n, n))
    A[np.triu_indices(n)] = rng.normal(size=n * (n + 1) // 2)
    A = A + A.T
    A[2, 5] = A[5, 2] = A[0, 6] = A[6, 0] = A[1, 4] = A[4, 1] = 0.0
    A[:, 8] = A[8, :] = 0.0
    A[8, 8] = 3.0
    return A


@pytest.mark.parametrize("layout", ["pyNastran sparse", "pyNastran dense", "text dense", "text sparse",
                                    "text sparse bigmat", "binary dense", "binary sparse big-endian",
                                    "binary sparse bigmat", "binary dense bigmat big-endian"])
def test_op4_layouts_read_exactly_and_as_pynastran_reads_them(tmp_path, layout):
    from pyNastran.op4.op4 import read_op4

    path, A = tmp_path / "a.op4", _scattered()
    variables = {"A": A, "M": M_DENSE}
    if layout.startswith("pyNastran"):
        write_op4(path, {"A": sp.coo_matrix(A) if "sparse" in layout else A, "M": M_DENSE})
    else:
        write = write_op4_text if layout.startswith("text") else write_op4_binary
        kwargs = {"sparse": "sparse" in layout, "bigmat": "bigmat" in layout}
        if "big-endian" in layout:
            kwargs["endian"] = ">"
        write(path, variables, **kwargs)
    for name, expected in variables.items():
        got = read_matrix(path, name, symmetry_tolerance=1e-12)
        np.testing.assert_array_equal(dense(got), expected)
        np.testing.assert_array_equal(dense(got), dense(read_op4(str(path), debug=None)[name][1]))
