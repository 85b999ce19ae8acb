"""Damaged, ambiguous and inconsistent model files are refused by name (issue 24, its FE items).

Each test names the item of the issue it holds; every refusal is a ``FileFormatError`` (a
``ValueError``) naming the file, and the line where the format has lines.
"""

import re
import subprocess
import sys

import numpy as np
import pytest
import scipy.io
import scipy.sparse as sp

from _writers import chain, damage_npz, data_offset, write_mat73, write_mat73_sparse, write_npz, write_op4
from microslip.fe import FileFormatError, read_matrices, read_matrix
from microslip.fe.files import OneMatrixFile
from microslip.frequency import Structure

K = chain(4)
M = np.diag([1.0, 2.0, 3.0, 4.0])


def _refused(call, *patterns, error=FileFormatError):
    with pytest.raises(error) as err:
        call()
    for p in patterns:
        assert p in str(err.value), f"{p!r} not in {str(err.value)!r}"
    return err.value


# -- 1: one matrix taken for the whole model ----------------------------------------------------------------
def test_1_a_single_matrix_file_is_not_taken_for_the_whole_model(tmp_path):
    scipy.io.mmwrite(tmp_path / "K.mtx", K)
    sp.save_npz(tmp_path / "K.npz", K)
    for name, kind in (("K.mtx", "Matrix Market"), ("K.npz", "NumPy .npz")):
        path = tmp_path / name
        for call in (lambda: read_matrices(path), lambda: Structure.from_files(path),
                     lambda: read_matrices(path, names={"M": "K", "K": "K"})):
            err = _refused(call, str(path), f"a {kind} file holds a single matrix", "one file per matrix (M=..., K=...",
                           error=OneMatrixFile)
            assert isinstance(err, ValueError)
    scipy.io.mmwrite(tmp_path / "M.mtx", M)
    s = Structure.from_files(M=tmp_path / "M.mtx", K=tmp_path / "K.npz")  # each file says which matrix it is
    np.testing.assert_array_equal(s.K.toarray(), K.toarray())
    np.testing.assert_array_equal(s.M, M)
    assert not s.C.any()


# -- 2: MATLAB v7.3 sparse indices ----------------------------------------------------------------------------
@pytest.mark.parametrize("ir, jc, data, message", [
    ([0, 1, 2, 4], [0, 1, 2, 3, 4], [1.0] * 4, "K: ir[3] = 4 is not a row of the 4 x 4 matrix (0..3)"),
    ([0, 1, 2, -1], [0, 1, 2, 3, 4], [1.0] * 4, "K: ir[3] = -1 is not a row of the 4 x 4 matrix (0..3)"),
    ([0, 1, 2, 3000000], [0, 1, 2, 3, 4], [1.0] * 4, "K: ir[3] = 3000000 is not a row"),
    ([0, 1, 2, 3], [0, 1, 3, 2, 4], [1.0] * 4, "K: jc[3] = 2: the pointers must start at 0 and never decrease"),
    ([0, 1, 2, 3], [1, 1, 2, 3, 4], [1.0] * 4, "K: jc[0] = 1: the pointers must start at 0"),
    ([0, 1, 2, 3], [0, 1, 2, 3, 5], [1.0] * 4, "K: jc ends at 5 but ir has 4 entries and data 4: they must agree"),
    ([0, 1, 2, 3], [0, 1, 2, 3, 4], [1.0] * 3, "K: jc ends at 4 but ir has 4 entries and data 3"),
    ([0, 1, 3, 2], [0, 1, 2, 4, 4], [1.0] * 4, "K: ir[3] = 2 repeats or precedes the row before it in its column"),
    ([0, 1, 1, 3], [0, 1, 3, 3, 4], [1.0] * 4, "K: ir[2] = 1 repeats or precedes the row before it"),
])
def test_2_mat73_sparse_indices_are_checked_before_the_matrix_is_built(tmp_path, ir, jc, data, message):
    path = tmp_path / "k.mat"
    write_mat73_sparse(path, "K", 4, data, np.array(ir, dtype=np.int64), np.array(jc, dtype=np.int64), M=M)
    _refused(lambda: read_matrices(path), str(path), message, error=ValueError)


def test_2_a_large_index_no_longer_crashes_the_reader(tmp_path):
    """ir = [0, 1, 2, 3000000] crashed the interpreter (segmentation fault): run in a child process."""
    path = tmp_path / "k.mat"
    write_mat73_sparse(path, "K", 4, [1.0] * 4, np.array([0, 1, 2, 3000000], np.uint64), np.arange(5, dtype=np.uint64),
                       M=M)
    code = (f"from microslip.fe import read_matrices, FileFormatError\n"
            f"try:\n    read_matrices({str(path)!r})\nexcept FileFormatError as e:\n    print(e)\n")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr[-2000:]
    assert "k.mat: K: ir[3] = 3000000 is not a row of the 4 x 4 matrix (0..3)" in run.stdout


# -- 3: a damaged value at the end of a text OP4 line ---------------------------------------------------------
def _op4_lines(tmp_path):
    path = tmp_path / "model.op4"
    write_op4(path, {"M": M, "K": K})
    return path, path.read_text().split("\n")


def _last_value_line(lines, name):
    """The index of the line holding the matrix ``name``'s last stored value (K[3, 3], M[3, 3])."""
    start = next(i for i, line in enumerate(lines) if line[32:40].strip() == name)
    end = next(i for i in range(start + 1, len(lines)) if lines[i].split()[:1] == ["5"])  # column 5: the end record
    return end - 1


@pytest.mark.parametrize("damage, message", [
    (lambda line: line[:-4] + "X+06", "is not a number of the format 1P,3E23.16"),  # a corrupted exponent
    (lambda line: line[:-3] + "+6", "characters are not a whole number of 23-character values"),  # a field cut short
    (lambda line: line[:-23], "the record's word counts do not match the values it holds|an empty line among the "
                              "values"),  # the last value dropped (M's: the only one on its line)
    (lambda line: line[:-23] + "NaN".rjust(23), "'NaN', is not a number of the format 1P,3E23.16"),
    (lambda line: line[:-23] + " 1.000000000000000E+999", "the value inf is not finite"),
])
@pytest.mark.parametrize("name", ["K", "M"])
def test_3_a_damaged_value_at_the_end_of_an_op4_line_is_refused_with_the_line(tmp_path, damage, message, name):
    path, lines = _op4_lines(tmp_path)
    i = _last_value_line(lines, name)
    lines[i] = damage(lines[i])
    path.write_text("\n".join(lines))
    err = _refused(lambda: read_matrices(path), str(path))
    assert re.search(message, str(err)), str(err)
    assert i - 1 <= err.line <= i + 1 and f"line {err.line}: " in str(err)  # the value's line, or its record's


def test_3_a_value_dropped_inside_a_column_is_refused(tmp_path):
    path = tmp_path / "model.op4"
    write_op4(path, {"M": M, "K": K.toarray() + 1.0})  # dense columns of 4 values: lines of 3 and 1
    lines = path.read_text().split("\n")
    i = next(i for i, line in enumerate(lines) if line.count("E") == 3)
    lines[i] = lines[i][:-23]
    path.write_text("\n".join(lines))
    _refused(lambda: read_matrices(path), f"line {i + 1}: 2 values on a line that is not the last of its record")


# -- 9: truncated, empty, bit-flipped files; huge declared sizes ----------------------------------------------
@pytest.mark.parametrize("damage", ["empty", "truncated", "bit flip"])
def test_9_a_damaged_npz_file_is_refused_by_name(tmp_path, damage):
    path = tmp_path / "model.npz"
    write_npz(path, {"M": M, "K": K})
    damage_npz(path, damage)
    _refused(lambda: read_matrices(path), str(path))


def test_9_a_damaged_zip_directory_does_not_drop_the_damping_matrix(tmp_path):
    """A damaged length in the zip directory made zipfile stop listing members early, silently: C was gone."""
    import struct

    path = tmp_path / "model.npz"
    np.savez(path, M=M, K=K.toarray(), C=1e-4 * K.toarray())
    raw = bytearray(path.read_bytes())
    end = raw.rfind(b"PK\x05\x06")
    entry = struct.unpack("<I", raw[end + 16:end + 20])[0]  # the directory's first entry (M.npy)
    entry += 46 + sum(struct.unpack("<3H", raw[entry + 28:entry + 34]))  # the second (K.npy)
    raw[entry + 32:entry + 34] = struct.pack("<H", 0x4000)  # its comment's length: past the directory's end
    path.write_bytes(bytes(raw))
    _refused(lambda: read_matrices(path), f"{path}: its zip directory lists 2 of the 3 members its end record "
                                          f"declares: damaged")


def test_9_a_truncated_mat73_file_is_refused_by_name(tmp_path):
    path = tmp_path / "model.mat"
    write_mat73(path, {"M": M, "K": K})
    raw = path.read_bytes()
    path.write_bytes(raw[:len(raw) // 2])
    _refused(lambda: read_matrices(path), str(path), "a damaged or truncated MATLAB v7.3 (HDF5) file")


@pytest.mark.parametrize("text, message", ids=["array", "coordinates", "entries", "array entries"], argvalues=[
    ("%%MatrixMarket matrix array real general\n100000000000 100000000000\n1\n",
     "line 2: declares a 100000000000 x 100000000000 matrix; at most 10000000 rows and columns are read"),
    ("%%MatrixMarket matrix coordinate real general\n100000000000 100000000000 1\n1 1 1.0\n",
     "line 2: declares a 100000000000 x 100000000000 matrix"),
    ("%%MatrixMarket matrix coordinate real general\n3 3 100000000000\n1 1 1.0\n",
     "line 3: the size line (line 2) declares 100000000000 entries but the file holds 1: truncated"),
    ("%%MatrixMarket matrix array real general\n1000000 1000000\n1\n",
     "line 3: the size line (line 2) declares 1000000000000 entries but the file holds 1: truncated"),
])
def test_9_a_matrix_market_file_declaring_a_huge_size_is_refused_before_any_allocation(tmp_path, text, message):
    path = tmp_path / "huge.mtx"
    path.write_text(text)
    _refused(lambda: read_matrix(path), f"{path}: {message}")


@pytest.mark.parametrize("byte, bit, message", [
    (176, 0, "at byte 128: variable 'M': its values are of element type 8, not numbers"),
    (521, 6, "at byte 472: variable 'K': its row indices are of element type 16389, not numbers"),
    (596, 4, "at byte 472: variable 'K': its values are of element type 11, not numbers"),
    (817, 7, "at byte 768: variable 'C': its row indices are of element type 32773, not numbers"),
    (639, 6, "at byte 472: variable 'K': its values of 1073741952 bytes run past the variable (288 bytes)"),
])
def test_9_a_damaged_mat5_variable_is_named_not_a_crash(tmp_path, byte, bit, message):
    """These flipped bits crashed scipy's reader (segmentation fault) or made it allocate 8 GB: run in a child."""
    path = tmp_path / "model.mat"
    scipy.io.savemat(path, {"M": np.diag(np.linspace(0.5, 3.0, 6)), "K": chain(6), "C": 1e-4 * chain(6, seed=1)})
    raw = bytearray(path.read_bytes())
    raw[byte] ^= 1 << bit
    path.write_bytes(bytes(raw))
    code = (f"from microslip.fe import read_matrices, FileFormatError\n"
            f"try:\n    read_matrices({str(path)!r})\nexcept FileFormatError as e:\n    print(e)\n")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr[-2000:]
    assert f"{path}: {message}" in run.stdout


def test_9_a_damaged_mat4_size_is_refused_before_any_allocation(tmp_path):
    """A bit of K's column count flipped: scipy's reader tried to allocate 36 GB (MemoryError)."""
    path = tmp_path / "model.mat"
    scipy.io.savemat(path, {"M": np.diag(np.linspace(0.5, 3.0, 6)), "K": chain(6)}, format="4")
    raw = bytearray(path.read_bytes())
    raw[321] ^= 1 << 4  # K's header starts at byte 310: MOPT, rows, columns (318..321), ...
    path.write_bytes(bytes(raw))
    _refused(lambda: read_matrices(path), f"{path}: at byte 310: a variable of 17 x 268435459 values runs past the "
                                          f"end of the file")


def test_9_a_matrix_market_file_cut_inside_its_last_line_is_refused(tmp_path):
    """A cut inside the last line can leave a shorter number that is still a number: 1.2e+05 -> 1.2."""
    path = tmp_path / "K.mtx"
    scipy.io.mmwrite(path, K)
    text = path.read_text()
    path.write_text(text[:text.rindex("E")])  # 9.468180872559213E5 -> 9.468180872559213
    _refused(lambda: read_matrix(path), f"line {text.count(chr(10))}: the file does not end with a line break: it "
                                        f"may be truncated")


def test_9_a_binary_op4_row_outside_the_matrix_is_refused(tmp_path):
    """pyNastran placed a value of row -1 in the last row, silently."""
    from _writers import write_op4_binary

    path = tmp_path / "model.op4"
    write_op4_binary(path, {"M": M, "K": K})
    raw = bytearray(path.read_bytes())
    raw[40:44] = np.array([-1], "<i4").tobytes()  # IROW of the first column record (after the 32-byte header)
    path.write_bytes(bytes(raw))
    _refused(lambda: read_matrices(path), f"{path}: at byte 32: matrix 'M': column 1: 1 value(s) from row -1 fall "
                                          f"outside rows 1..4")


# -- 22: the messages of garbage and inconsistent files ------------------------------------------------------
def test_22_an_npz_of_python_objects_is_named(tmp_path):
    path = tmp_path / "model.npz"
    np.savez(path, M=M, K=np.array([{"a": 1}], dtype=object))
    _refused(lambda: read_matrices(path), str(path), "array 'K' holds Python objects (pickled data), which are never "
                                                     "loaded; expected numbers")


def test_22_a_truncated_mat5_file_is_said_truncated_not_short_of_a_variable(tmp_path):
    path = tmp_path / "model.mat"
    scipy.io.savemat(path, {"M": M, "K": K})
    raw = path.read_bytes()
    for cut in (400, len(raw) - 8, len(raw) - 1):
        path.write_bytes(raw[:cut])
        err = _refused(lambda: read_matrices(path), str(path), "truncated")
        assert "no variable" not in str(err)


@pytest.mark.parametrize("ir, jc, nrows, message", [
    (np.array([0.0, 1.0]), [0, 1, 2], 2, "K: ir must be a 1-D array of integers, got float64"),
    ([0, 1], [0, 1], 2, "K: jc ends at 1 but ir has 2 entries and data 2: they must agree"),
    ([0, 1], [0, 1, 2], 2**63, "K: the row count MATLAB_sparse = 9223372036854775808 is not a whole number"),
])
def test_22_inconsistent_mat73_sparse_data_is_named(tmp_path, ir, jc, nrows, message):
    path = tmp_path / "k.mat"
    write_mat73_sparse(path, "K", nrows, [1.0, 1.0], np.asarray(ir), np.asarray(jc, dtype=np.uint64))
    _refused(lambda: read_matrix(path, "K"), str(path), message)


@pytest.mark.parametrize("write", [
    lambda p: np.savez(p.with_suffix(".npz"), M=np.zeros((0, 0)), K=np.zeros((0, 0))),
    lambda p: scipy.io.savemat(p.with_suffix(".mat"), {"M": np.zeros((0, 0)), "K": np.zeros((0, 0))}),
    lambda p: p.with_suffix(".mtx").write_text("%%MatrixMarket matrix coordinate real general\n0 0 0\n"),
])
def test_22_an_empty_matrix_is_named(tmp_path, write):
    write(tmp_path / "empty")
    path = next(tmp_path.iterdir())
    call = (lambda: read_matrix(path)) if path.suffix == ".mtx" else (lambda: read_matrices(path))
    _refused(call, str(path), "is an empty 0 x 0 matrix; expected at least one row and column", error=ValueError)


# -- 23: silently accepted ------------------------------------------------------------------------------------
@pytest.mark.parametrize("shape", [[4.5, 4], [4, -4], [4], [4, 4, 1], [np.nan, 4], [1e12, 4]])
def test_23_an_npz_sparse_shape_must_be_two_whole_numbers(tmp_path, shape):
    path = tmp_path / "model.npz"
    csr = sp.csr_matrix(K)
    np.savez(path, M=M, K_data=csr.data, K_indices=csr.indices, K_indptr=csr.indptr, K_shape=np.array(shape))
    _refused(lambda: read_matrices(path), str(path), "K: shape", "must be two whole numbers of rows and columns")


def test_a_damaged_file_error_survives_pickling(tmp_path):
    import pickle

    err = FileFormatError(tmp_path / "a.op4", "a damaged value", 12)
    back = pickle.loads(pickle.dumps(err))
    assert str(back) == str(err) and back.line == 12 and back.path == err.path


def test_the_zip_checksum_is_verified(tmp_path):
    """A changed byte of an array's data (not of its header) is found by the member's CRC-32."""
    path = tmp_path / "model.npz"
    np.savez(path, M=M, K=K.toarray())
    raw = bytearray(path.read_bytes())
    raw[data_offset(path, "K.npy") + 128 + 8] ^= 0x01  # one bit of K[0, 1], after the 128-byte array header
    path.write_bytes(bytes(raw))
    _refused(lambda: read_matrices(path), str(path), "array 'K' is damaged (Bad CRC-32 for file 'K.npy')")
