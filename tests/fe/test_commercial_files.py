"""Readers of the files commercial FE codes write: ANSYS .full, Harwell-Boeing, Nastran DMIG, Abaqus.

Each is read on a file a maintained package ships or writes (ansys-mapdl-reader's example ``file.full``,
SciPy's Harwell-Boeing test matrix, DMIG entries written by pyNastran) to the same matrices as that
package's own reader, exactly; Abaqus files follow the data lines documented in the Abaqus Keywords
Reference (``*MATRIX INPUT``: "row node number, degree of freedom number for row node, column node
number, degree of freedom number for column node, matrix entry", which ``*MATRIX OUTPUT,
FORMAT=MATRIX INPUT`` writes; ``FORMAT=COORDINATE``: "row, column, value"). Damaged copies are refused
with a FileFormatError naming the file and the line (text) or the record (binary).
"""

import numpy as np
import pytest
import scipy.io
import scipy.sparse as sp

from microslip.fe import DofMap, FileFormatError, read_matrices, read_matrix
from microslip.frequency import Structure


def _refused(path, *fragments):
    """The FileFormatError of reading ``path``; its message names the file and each fragment."""
    with pytest.raises(FileFormatError) as err:
        read_matrices(path) if path.suffix in (".full",) else read_matrix(path)
    message = str(err.value)
    assert str(path) in message
    for f in fragments:
        assert f in message, message
    return err.value


# -- ANSYS .full ----------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def ansys_example():
    pytest.importorskip("ansys.mapdl.reader")
    from ansys.mapdl.reader import examples

    return examples.fullfile


def test_ansys_full_gives_the_librarys_matrices_without_the_constrained_dofs(ansys_example):
    from ansys.mapdl.reader.full import FullFile

    full = FullFile(ansys_example)
    dof_ref, k, m = full.load_km(sort=True)  # one triangle, constrained DOFs left as empty rows
    constrained = {tuple(p) for p in full.const.tolist()}
    free = np.array([tuple(p) not in constrained for p in dof_ref.tolist()])
    got = read_matrices(ansys_example)
    for mine, theirs in ((got.K, k), (got.M, m)):
        whole = (theirs + sp.triu(theirs, 1).T).tocsr()[free][:, free]
        assert (mine != whole).nnz == 0  # exactly
    assert got.C is None  # the example is undamped
    assert free.sum() == 900 and len(constrained) == 63  # the library's own counts of the example
    assert got.dof_map == DofMap(dof_ref[free, 0], dof_ref[free, 1] + 1)  # the file's DOFs 1, 2, 3 are UX, UY, UZ
    s = Structure.from_files(ansys_example)
    assert s.dof_map.names[:3] == ["22:x", "22:y", "22:z"]


def _damage(src, tmp_path, name, edit):
    path = tmp_path / name
    raw = bytearray(src.read_bytes() if hasattr(src, "read_bytes") else open(src, "rb").read())
    path.write_bytes(edit(raw))
    return path


def _word(raw, k, value):
    raw[4 * k:4 * k + 4] = np.array([value], "<i4").tobytes()
    return bytes(raw)


def test_ansys_full_damaged_copies_are_refused_naming_the_file_and_record(ansys_example, tmp_path):
    size = len(open(ansys_example, "rb").read())
    _refused(_damage(ansys_example, tmp_path, "cut.full", lambda r: bytes(r[:size // 2])), "word")
    _refused(_damage(ansys_example, tmp_path, "head.full", lambda r: bytes(r[:600])), "bytes")
    _refused(_damage(ansys_example, tmp_path, "length.full", lambda r: _word(r, 536, 7)), "record at word 536")
    _refused(_damage(ansys_example, tmp_path, "column.full", lambda r: _word(r, 538, 5000)),
             "stiffness matrix, row 1", "column 5000 is outside 1..963")
    _refused(_damage(ansys_example, tmp_path, "neqn.full", lambda r: _word(r, 106, 964)), "stiffness matrix, row")
    _refused(_damage(ansys_example, tmp_path, "magic.full", lambda r: _word(r, 0, 99)), "standard header")


# -- Harwell-Boeing -----------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def scipy_simple():
    """SciPy's own Harwell-Boeing test matrix (RUA, 100 x 100), as its test suite ships it."""
    test_hb = pytest.importorskip("scipy.io._harwell_boeing.tests.test_hb")
    return test_hb.SIMPLE


def test_harwell_boeing_rua_equals_scipys_reader(scipy_simple, tmp_path):
    from microslip.fe import _harwell_boeing

    path = tmp_path / "simple.rua"
    path.write_text(scipy_simple)
    mine, theirs = _harwell_boeing.read(path), scipy.io.hb_read(path)
    assert mine.shape == theirs.shape == (100, 100) and (mine != theirs).nnz == 0  # exactly
    with pytest.raises(ValueError, match="must be symmetric"):  # a general matrix is no mass or stiffness
        read_matrix(path)


def test_harwell_boeing_rsa_is_made_whole_and_read_by_format(tmp_path):
    from _writers import chain

    K = chain(7)
    rua = tmp_path / "lower.rua"
    scipy.io.hb_write(rua, sp.csc_matrix(sp.tril(K)))
    lower = scipy.io.hb_read(rua)  # SciPy reads the stored triangle as it is
    rsa = tmp_path / "K.MATRIX"  # HBMAT's default extension: the format must be named
    text = rua.read_text().split("\n")
    text[2] = "RSA" + text[2][3:]
    rsa.write_text("\n".join(text))
    A = read_matrix(rsa, format="harwell-boeing")
    assert (A != (lower + sp.triu(lower.T, 1))).nnz == 0 and (A != K).nnz == 0
    with pytest.raises(ValueError, match="unknown matrix file suffix"):
        read_matrix(rsa)


def test_harwell_boeing_damaged_copies_are_refused_naming_the_line(scipy_simple, tmp_path):
    lines = scipy_simple.split("\n")

    def copy(name, k, new):
        path = tmp_path / name
        path.write_text("\n".join(lines[:k] + [new] + lines[k + 1:]))
        return path

    assert "2.971243799687726e-01" in lines[9] and "37 71" in lines[8]
    _refused(copy("value.rua", 9, lines[9].replace("2.971243799687726e-01", "2.97124379968772xe-01")),
             "line 10", "is not a number")
    _refused(copy("header.rua", 1, lines[1].replace("9", "8", 1)), "line 2", "TOTCRD")
    _refused(copy("index.rua", 8, lines[8].replace("71", "101")), "row indices[1] = 100", "0..99")
    cut = tmp_path / "cut.rua"
    cut.write_text("\n".join(lines[:11]) + "\n")
    _refused(cut, "truncated")
    kind = tmp_path / "kind.rua"
    kind.write_text("\n".join(lines[:2] + ["CUA" + lines[2][3:]] + lines[3:]))
    _refused(kind, "line 3", "real assembled")


# -- Nastran DMIG ---------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def dmig_file(tmp_path_factory):
    """KAAX and MAAX written by pyNastran's own writer (large fields, double precision)."""
    bdf = pytest.importorskip("pyNastran.bdf.bdf")
    model = bdf.BDF(debug=None)
    cols, rows = [(10, 1), (10, 1), (10, 2), (10, 2), (11, 3)], [(10, 1), (10, 2), (10, 2), (11, 3), (11, 3)]
    model.add_dmig("KAAX", 6, 2, 0, 0, 0, cols, rows, Real=[4.0e6, -1.0e6, 3.0e6, -0.5e6, 2.0e6])
    model.add_dmig("MAAX", 6, 2, 0, 0, 0, [(10, 1), (10, 2), (11, 3)], [(10, 1), (10, 2), (11, 3)],
                   Real=[1.5, 1.5, 0.25])
    path = tmp_path_factory.mktemp("dmig") / "sector.pch"
    model.write_bdf(str(path), size=16, is_double=True, enddata=False)
    return path


def test_dmig_matrices_equal_pynastrans_with_the_grid_component_map(dmig_file):
    from pyNastran.bdf.bdf import read_bdf

    model = read_bdf(str(dmig_file), punch=True, debug=None)
    got = read_matrices(dmig_file, names={"M": "MAAX", "K": "KAAX"})
    for mine, name in ((got.K, "KAAX"), (got.M, "MAAX")):
        theirs, rows, _ = model.dmig[name].get_matrix(is_sparse=False)
        order = [got.dof_map.index((int(g), int(c))) for _, (g, c) in sorted(rows.items())]
        assert np.array_equal(mine.toarray()[np.ix_(order, order)], theirs)  # exactly
    assert got.dof_map.names == ["10:x", "10:y", "11:z"]
    s = Structure.from_files(dmig_file, names={"M": "MAAX", "K": "KAAX"})
    assert s.K[s.dof_index("10:y"), s.dof_index("11:z")] == -0.5e6


def test_dmig_damaged_entries_are_refused_naming_the_file_and_matrix(dmig_file, tmp_path):
    text = dmig_file.read_text()

    def copy(name, old, new):
        assert old in text
        path = tmp_path / name
        path.write_text(text.replace(old, new, 1))
        return path

    for path, fragments in (
            (copy("number.pch", "14.0000000000D+06", "14.00000x0000D+06"), ()),
            (copy("scalar.pch", "*                     11               32.0000000000D+06",
                  "*                     11               02.0000000000D+06"), ("DMIG 'KAAX'", "component 0")),
            (copy("twice.pch", "*                     10               23.0000000000D+06",
                  "*                     11               3-5.000000000D+05"), ("DMIG 'KAAX'", "stored twice")),
            (copy("complex.pch", "KAAX               0               6               2",
                  "KAAX               0               6               4"), ())):
        with pytest.raises(FileFormatError) as err:
            read_matrices(path, names={"M": "MAAX", "K": "KAAX"})
        assert str(path) in str(err.value) and all(f in str(err.value) for f in fragments), str(err.value)


# -- Abaqus ---------------------------------------------------------------------------------------------------
#: a beam's two nodes, 2 DOFs each, written as *MATRIX OUTPUT, FORMAT=MATRIX INPUT writes a symmetric matrix
#: (one triangle: row node, row DOF, column node, column DOF, value)
STIF = """** stiffness, lower triangle
1,1, 1,1, 2.0e6
1,2, 1,2, 3.0e6
2,1, 1,1, -1.0e6
2,1, 2,1, 2.0e6
2,2, 1,2, -1.5e6
2,2, 2,2, 3.0e6
"""
MASS = """1,1, 1,1, 0.5
1,2, 1,2, 0.5
2,1, 2,1, 0.5
2,2, 2,2, 0.5
"""
K_EXPECTED = np.array([[2.0e6, 0, -1.0e6, 0], [0, 3.0e6, 0, -1.5e6], [-1.0e6, 0, 2.0e6, 0], [0, -1.5e6, 0, 3.0e6]])


def test_abaqus_matrix_input_format_gives_the_documented_matrix_and_node_dof_map(tmp_path):
    (tmp_path / "job_STIF1.mtx").write_text(STIF)
    (tmp_path / "job_MASS1.mtx").write_text(MASS)
    got = read_matrices(M=tmp_path / "job_MASS1.mtx", K=tmp_path / "job_STIF1.mtx")
    assert np.array_equal(got.K.toarray(), K_EXPECTED) and np.array_equal(got.M.toarray(), 0.5 * np.eye(4))
    assert got.dof_map.names == ["1:x", "1:y", "2:x", "2:y"]
    square = tmp_path / "square.txt"  # the whole square (each entry with its mirror) reads the same
    rows = [f"{n},{d}, {m},{e}, {float(K_EXPECTED[2 * n + d - 3, 2 * m + e - 3])!r}" for n in (1, 2) for d in (1, 2)
            for m in (1, 2) for e in (1, 2) if K_EXPECTED[2 * n + d - 3, 2 * m + e - 3]]
    square.write_text("\n".join(rows) + "\n")
    assert np.array_equal(read_matrix(square, format="abaqus").toarray(), K_EXPECTED)
    coordinate = tmp_path / "coord_STIF1.mtx"  # FORMAT=COORDINATE: equation numbers, no labels
    coordinate.write_text("1,1,2.0e6\n2,2,3.0e6\n3,1,-1.0e6\n3,3,2.0e6\n4,2,-1.5e6\n4,4,3.0e6\n")
    assert np.array_equal(read_matrix(coordinate).toarray(), K_EXPECTED)


def test_abaqus_files_with_different_dofs_are_put_on_their_union(tmp_path):
    (tmp_path / "K.mtx").write_text(STIF)
    (tmp_path / "M.mtx").write_text(MASS.replace("2,2, 2,2, 0.5\n", "3,3, 3,3, 0.25\n"))
    got = read_matrices(M=tmp_path / "M.mtx", K=tmp_path / "K.mtx")
    assert got.dof_map.names == ["1:x", "1:y", "2:x", "2:y", "3:z"]
    assert got.K[4, 4] == 0 and got.M[3, 3] == 0 and got.M[4, 4] == 0.25
    order = DofMap.from_names(["3:z", "2:y", "2:x", "1:y", "1:x"])  # a map given sets the order
    again = read_matrices(M=tmp_path / "M.mtx", K=tmp_path / "K.mtx", dof_map=order)
    assert again.dof_map == order and np.array_equal(again.K.toarray(), got.K.toarray()[::-1, ::-1])
    with pytest.raises(ValueError, match="lacks DOF 3:z"):
        read_matrices(M=tmp_path / "M.mtx", K=tmp_path / "K.mtx", dof_map=DofMap.from_names(
            ["1:x", "1:y", "2:x", "2:y", "4:z"]))


@pytest.mark.parametrize("edit, fragments", [
    (lambda t: t.replace("3.0e6\n2,1", "3.0x6\n2,1"), ("line 3", "is not a number")),
    (lambda t: t.replace("2,1, 1,1, -1.0e6", "2,1, 1,1"), ("line 4", "5 items")),
    (lambda t: t.replace("2,2, 2,2,", "2,8, 2,8,"), ("line 7", "not a displacement or rotation DOF")),
    (lambda t: t + "2,1, 1,1, -1.0e6\n", ("line 8", "stored twice")),
    (lambda t: t + "1,1, 2,1, -1.0e6\n", ("line 6", "no mirror")),  # one mirrored pair: a square lacking others
    (lambda t: t[:-3], ("line 7", "truncated")),
    (lambda t: "", ("line 1",)),  # neither Abaqus (no commas) nor Matrix Market (no banner)
])
def test_abaqus_damaged_copies_are_refused_naming_the_line(tmp_path, edit, fragments):
    path = tmp_path / "job_STIF1.mtx"
    path.write_text(edit(STIF))
    _refused(path, *fragments)


def test_a_matrix_market_mtx_is_still_matrix_market(tmp_path):
    from _writers import chain

    K = chain(4)
    scipy.io.mmwrite(tmp_path / "K.mtx", sp.coo_matrix(K), symmetry="symmetric")
    assert (read_matrix(tmp_path / "K.mtx") != K).nnz == 0


def test_format_is_checked_and_offered_in_the_configuration(tmp_path):
    with pytest.raises(ValueError, match="format must be one of"):
        read_matrix(tmp_path / "K.mtx", format="ansys")
    (tmp_path / "K.txt").write_text(STIF)
    (tmp_path / "M.txt").write_text(MASS)
    s = Structure.from_files(M=tmp_path / "M.txt", K=tmp_path / "K.txt", format="abaqus")
    assert s.dof_index("2:y") == 3 and s.K[3, 1] == -1.5e6
    from microslip.config import load_config

    toml = tmp_path / "frf.toml"
    toml.write_text('[structure]\nM = "M.txt"\nK = "K.txt"\nformat = "abaqus"\nrayleigh = [0.0, 1e-5]\n'
                    '[[contact]]\nmodel = "c.json"\ntangential = "2:x"\napproach = "1um"\n'
                    '[excitation]\nh1 = {"1:x" = "1N"}\n[sweep]\nfrequency = [10, 20]\nharmonics = 3\n')
    from microslip import MicroslipModel

    MicroslipModel([1e4], [1e6], [0.0], 0.5).save(tmp_path / "c.json")
    cfg = load_config(toml)
    assert cfg.structure.dof_map.names == ["1:x", "1:y", "2:x", "2:y"]
    assert np.array_equal(cfg.structure.K.toarray(), K_EXPECTED)
