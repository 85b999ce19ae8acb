"""``microslip frf`` with the structure in FE files: an ambiguous or damaged file is refused by name (issue 24).

The command exits with status 2 and one line naming the file (and the line of a text file), never
a traceback, a crash, or a run on the wrong matrices.
"""

import shutil
import subprocess
import sys

import numpy as np
import pytest
import scipy.io
import scipy.sparse as sp

from _paths import EXAMPLES
from microslip.cli import main
from microslip.config import load_config

STRUCTURE = """M = [[0.1, 0.0], [0.0, 0.1]]          # kg
K = [[1e7, 0.0], [0.0, 1e7]]          # N/m
C = [[17.32, 0.0], [0.0, 17.32]]      # N s/m
dofs = ["x", "y"]"""
M = 0.1 * np.eye(2)
K = sp.csr_matrix(1e7 * np.eye(2))


@pytest.fixture
def block(tmp_path):
    shutil.copy(EXAMPLES / "sphere_4_elements.json", tmp_path / "sphere_4_elements.json")
    assert STRUCTURE in (EXAMPLES / "inclined_block.toml").read_text()
    return tmp_path


def _config(folder, structure: str):
    """The example's configuration with its [structure] matrices replaced by ``structure``."""
    cfg = folder / "block.toml"
    cfg.write_text((EXAMPLES / "inclined_block.toml").read_text().replace(STRUCTURE, structure))
    return cfg


def _frf(cfg, capsys) -> str:
    """The error line of ``microslip frf`` on ``cfg`` (which must exit with status 2)."""
    code = main(["frf", str(cfg), "--out", str(cfg.parent / "out"), "--quiet"])
    err = capsys.readouterr().err
    assert code == 2, err
    assert "Traceback" not in err and err.startswith("microslip frf: error: "), err
    return err


@pytest.mark.parametrize("damping", ["", "rayleigh = [0.0, 1e-5]"])
def test_1_a_single_matrix_file_is_not_the_whole_model(block, capsys, damping):
    scipy.io.mmwrite(block / "K.mtx", K)
    err = _frf(_config(block, f'file = "K.mtx"\n{damping}'), capsys)
    assert "[structure] file = 'K.mtx' is a Matrix Market file, which holds a single matrix: say which matrix each " \
           "file is, M = \"M.mtx\", K = \"K.mtx\"" in err
    assert "give either C or rayleigh" not in err
    scipy.io.mmwrite(block / "M.mtx", M)
    cfg = load_config(_config(block, f'M = "M.mtx"\nK = "K.mtx"\n{damping}'))  # each file says which matrix it is
    np.testing.assert_array_equal(cfg.structure.M, M)


def test_3_a_damaged_op4_value_is_named_with_its_file_and_line(block, capsys):
    from pyNastran.op4.op4 import OP4

    path = block / "model.op4"
    OP4().write_op4(str(path), {"M": (6, M), "K": (6, sp.coo_matrix(K))}, is_binary=False, precision="double")
    lines = path.read_text().split("\n")
    i = max(i for i, line in enumerate(lines) if line.startswith(" 1.0000000000000000E+07"))  # K[1, 1]
    lines[i] = lines[i][:-4] + "X+07"
    path.write_text("\n".join(lines))
    err = _frf(_config(block, 'file = "model.op4"'), capsys)
    assert f"model.op4: line {i + 1}: value 1, '1.0000000000000000X+07', is not a number" in err
    assert "no stiffness" not in err


@pytest.mark.parametrize("key", ["file", "matrices"])
@pytest.mark.parametrize("damage", ["empty", "truncated"])
def test_9_a_damaged_npz_file_is_named(block, capsys, key, damage):
    path = block / "model.npz"
    np.savez(path, M=M, K=K.toarray())
    raw = path.read_bytes()
    path.write_bytes(b"" if damage == "empty" else raw[:len(raw) // 2])
    err = _frf(_config(block, f'{key} = "model.npz"'), capsys)
    assert "model.npz: not a NumPy .npz (zip) file, or a truncated one" in err


def test_9_a_truncated_mat73_file_and_a_huge_matrix_market_size_are_named(block, capsys):
    import h5py

    path = block / "model.mat"
    with h5py.File(path, "w", userblock_size=512) as f:
        for name, A in (("M", M), ("K", K.toarray())):
            f.create_dataset(name, data=A).attrs["MATLAB_class"] = np.bytes_("double")
    raw = path.read_bytes()
    path.write_bytes(raw[:len(raw) // 2])
    err = _frf(_config(block, 'file = "model.mat"'), capsys)
    assert "model.mat: a damaged or truncated MATLAB v7.3 (HDF5) file" in err
    (block / "M.mtx").write_text("%%MatrixMarket matrix array real general\n100000000000 100000000000\n1\n")
    scipy.io.mmwrite(block / "K.mtx", K)
    err = _frf(_config(block, 'M = "M.mtx"\nK = "K.mtx"'), capsys)
    assert "M.mtx: line 2: declares a 100000000000 x 100000000000 matrix" in err


def test_2_a_large_mat73_sparse_index_is_named_not_a_crash(block):
    """``ir = [0, 3000000]`` crashed ``microslip frf`` (segmentation fault): run in a child process."""
    import h5py

    path = block / "model.mat"
    with h5py.File(path, "w", userblock_size=512) as f:
        f.create_dataset("M", data=M).attrs["MATLAB_class"] = np.bytes_("double")
        g = f.create_group("K")
        g.attrs["MATLAB_class"], g.attrs["MATLAB_sparse"] = np.bytes_("double"), np.uint64(2)
        g["data"], g["ir"], g["jc"] = [1e7, 1e7], np.array([0, 3000000], np.uint64), np.array([0, 1, 2], np.uint64)
    cfg = _config(block, 'file = "model.mat"')
    code = f"from microslip.cli import main; raise SystemExit(main(['frf', {str(cfg)!r}, '--quiet']))"
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert run.returncode == 2, run.stderr[-2000:]
    assert "model.mat: K: ir[1] = 3000000 is not a row of the 2 x 2 matrix (0..1)" in run.stderr
    assert "Traceback" not in run.stderr
