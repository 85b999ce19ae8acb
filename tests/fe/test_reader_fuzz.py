"""The FE readers under damage: truncation, bit flips, edited text, index corruption, huge declared sizes.

Valid files of every format (Matrix Market, MATLAB v4, v5 plain and compressed, v7.3, ``.npz`` with
named arrays and as ``save_npz`` writes one matrix, Nastran OP4 as text -- pyNastran's and Nastran's
layouts -- and binary, a DOF map CSV, a saved Craig-Bampton model, ansys-mapdl-reader's example ANSYS
``.full`` file, Harwell-Boeing ``RSA``, Nastran DMIG written by pyNastran, Abaqus matrix output in both
of its text layouts) are damaged in seeded ways, and
each damaged file is read in a child process: a reader that crashed the interpreter would take
the test run with it, and the child runs with a memory limit so that an allocation from a damaged
size cannot hurt the machine.

Every read must either give the undamaged file's matrices or raise a ``ValueError`` naming the file;
never another exception, a crash, a hang, a NaN, or an allocation the file does not back. Damage
that changes structure (truncation, indices, sizes) and any damage of a file with a checksum
(``.npz``) must be found. A changed value of a format without a checksum (a digit of a text file,
a byte of a double in a binary one) cannot be found: such a read need only give finite matrices.
Nor can a MATLAB v5 or OP4 file cut exactly between two variables (neither format marks its end), a
DMIG or Abaqus file cut exactly at the end of a line (a punch file needs no ``ENDDATA``, Abaqus writes no
count: the entries after the cut are lost),
or one whose byte changed the name of the optional damping matrix C: it reads as a file without
that matrix, the others unchanged.
"""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest
import scipy.io
import scipy.sparse as sp

from _writers import (chain, write_mat73, write_mat73_sparse, write_npz, write_op4, write_op4_binary,
                      write_op4_text)

M = np.diag(np.linspace(0.5, 3.0, 6))
K = chain(6)
C = 1e-4 * chain(6, seed=1)
NODES = [11, 11, 12, 12, 13, 13]
COMPONENTS = ["x", "y", "x", "y", "x", "rz"]
SEED = int(os.environ.get("FE_FUZZ_SEED", 24))  # other seeds damage other bytes: FE_FUZZ_SEED=7 pytest ...

#: file name -> (how to read it, whether a changed value could go unnoticed: no checksum)
FILES = {
    "K.mtx": ("matrix", True),
    "M_array.mtx": ("matrix", True),
    "model4.mat": ("matrices", True),
    "model5.mat": ("matrices", True),
    "model5z.mat": ("matrices", False),  # each variable compressed: zlib's checksum
    "model73.mat": ("matrices", True),
    "model.npz": ("matrices", False),
    "K_one.npz": ("matrix", False),
    "pynastran.op4": ("matrices", True),
    "nastran.op4": ("matrices", True),
    "nastran_big.op4": ("matrices", True),
    "binary.op4": ("matrices", True),
    "binary_big.op4": ("matrices", True),
    "dofs.csv": ("dof_map", True),
    "reduced.npz": ("craig_bampton", False),
    "example.full": ("matrices", True),
    "K.rsa": ("matrix", True),
    "sector.pch": ("dmig", True),
    "job_STIF1.mtx": ("matrix", True),
    "coord_MASS1.mtx": ("matrix", True),
}
#: files without an end marker or a count: a cut at the end of a line drops the entries after it, unseen
CUT_AT_LINES = {"sector.pch", "job_STIF1.mtx", "coord_MASS1.mtx"}
#: files of formats whose text is damaged character by character too
_TEXT = (".mtx", ".op4", ".csv", ".rsa", ".pch")


def _write_files(folder: Path):
    scipy.io.mmwrite(folder / "K.mtx", sp.coo_matrix(K), symmetry="symmetric")
    scipy.io.mmwrite(folder / "M_array.mtx", M)
    scipy.io.savemat(folder / "model4.mat", {"M": M, "K": K, "C": C}, format="4")
    scipy.io.savemat(folder / "model5.mat", {"M": M, "K": K, "C": C})
    scipy.io.savemat(folder / "model5z.mat", {"M": M, "K": K, "C": C}, do_compression=True)
    write_mat73(folder / "model73.mat", {"M": M, "K": K, "C": C})
    write_npz(folder / "model.npz", {"M": M, "K": sp.csr_matrix(K), "C": sp.csc_matrix(C)})
    sp.save_npz(folder / "K_one.npz", sp.csc_matrix(K))
    write_op4(folder / "pynastran.op4", {"M": M, "K": K, "C": C})
    write_op4_text(folder / "nastran.op4", {"M": M, "K": K}, sparse=True)
    write_op4_text(folder / "nastran_big.op4", {"M": M, "K": K}, sparse=True, bigmat=True)
    write_op4_binary(folder / "binary.op4", {"M": M, "K": K})
    write_op4_binary(folder / "binary_big.op4", {"M": M, "K": K, "C": C}, sparse=True, bigmat=True, endian=">")
    (folder / "dofs.csv").write_text("node,component\n" + "".join(f"{n},{c}\n" for n, c in zip(NODES, COMPONENTS)))
    np.savez(folder / "base.npz", M=M, K=K.toarray())  # the matrices the DOF map goes with
    from microslip import MicroslipModel
    from microslip.frequency import Structure, craig_bampton

    s = Structure(M, None, K)
    s.add_contact(MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0), tangential={0: 1.0, 2: -1.0},
                  approach=1e-6)
    craig_bampton(s, [0, 2], 2).save(folder / "reduced.npz")
    from ansys.mapdl.reader import examples

    shutil.copyfile(examples.fullfile, folder / "example.full")
    scipy.io.hb_write(folder / "lower.rua", sp.csc_matrix(sp.tril(K)))
    lines = (folder / "lower.rua").read_text().split("\n")
    (folder / "K.rsa").write_text("\n".join(lines[:2] + ["RSA" + lines[2][3:]] + lines[3:]))
    from pyNastran.bdf.bdf import BDF

    nastran = BDF(debug=None)
    coo = sp.coo_matrix(sp.tril(K))
    grid = [(n, {"x": 1, "y": 2, "rz": 6}[c]) for n, c in zip(NODES, COMPONENTS)]
    nastran.add_dmig("KAAX", 6, 2, 0, 0, 0, [grid[j] for j in coo.col], [grid[i] for i in coo.row], Real=coo.data)
    nastran.add_dmig("MAAX", 6, 2, 0, 0, 0, grid, grid, Real=np.diag(M))
    nastran.write_bdf(str(folder / "sector.pch"), size=16, is_double=True, enddata=False)
    (folder / "job_STIF1.mtx").write_text("".join(
        f"{grid[i][0]}, {grid[i][1]}, {grid[j][0]}, {grid[j][1]}, {v!r}\n" for i, j, v in
        zip(coo.row.tolist(), coo.col.tolist(), coo.data.tolist())))
    (folder / "coord_MASS1.mtx").write_text("".join(f"{i + 1},{i + 1},{v!r}\n"
                                                    for i, v in enumerate(np.diag(M).tolist())))


# -- damage ---------------------------------------------------------------------------------------------------
def _damaged_copies(folder: Path, name: str, rng) -> list[tuple[str, str, bytes]]:
    """``(label, kind, content)``: kind ``structure`` (must be found) or ``value`` (may change a value)."""
    raw = (folder / name).read_bytes()
    n = len(raw)
    out = []
    cuts = {0, 1, 7, n // 4, n // 2, 3 * n // 4, n - 1, n - 2, n - 9, n - 30} | set(rng.integers(1, n, 12).tolist())
    for cut in sorted(c for c in cuts if 0 <= c < n):
        out.append((f"truncated to {cut} of {n} bytes", "structure", raw[:cut]))
    for pos, bit in zip(rng.integers(0, n, 40), rng.integers(0, 8, 40)):
        b = bytearray(raw)
        b[pos] ^= 1 << bit
        out.append((f"bit {bit} of byte {pos} flipped", "value", bytes(b)))
    if name.endswith(_TEXT) and raw[:1] != b"\x18" and raw[:4] != b"\0\0\0\x18":
        text = raw.decode()
        junk = "x.-+eE 9\t#,;N"
        for pos in rng.integers(0, len(text), 15):
            out.append((f"character {pos} deleted", "value", (text[:pos] + text[pos + 1:]).encode()))
            ch = junk[rng.integers(len(junk))]
            out.append((f"{ch!r} inserted at {pos}", "value", (text[:pos] + ch + text[pos:]).encode()))
            out.append((f"character {pos} replaced by {ch!r}", "value", (text[:pos] + ch + text[pos + 1:]).encode()))
        lines = text.split("\n")
        for i in rng.integers(0, len(lines), 6):
            out.append((f"line {i + 1} deleted", "value", "\n".join(lines[:i] + lines[i + 1:]).encode()))
            out.append((f"line {i + 1} doubled", "value", "\n".join(lines[:i + 1] + lines[i:]).encode()))
    return out


def _text_edits(folder: Path) -> list[tuple[str, str, str, bytes]]:
    """Sizes and indices of the text formats set out of range: ``(file, label, kind, content)``."""
    out = []
    mtx = (folder / "K.mtx").read_text().split("\n")
    size = next(i for i, line in enumerate(mtx) if line and not line.startswith("%"))
    for value in ("100000000000 100000000000 16", "6 6 100000000000", "6 6 15", "6 6 17", "7 6 16", "6 0 16",
                  "99999999 99999999 16"):
        out.append(("K.mtx", f"size line {value!r}", "structure", "\n".join(
            mtx[:size] + [value] + mtx[size + 1:]).encode()))
    for k, bad in enumerate(("0", "7", "-1", "100000000000", "1.5", "3.0e0")):
        i = size + 1 + k
        items = mtx[i].split()
        out.append(("K.mtx", f"row of line {i + 1} = {bad}", "structure",
                    "\n".join(mtx[:i] + [" ".join([bad] + items[1:])] + mtx[i + 1:]).encode()))
    for name in ("pynastran.op4", "nastran.op4"):
        lines = (folder / name).read_text().split("\n")
        for field, value in ((0, 99999999), (8, 99999999), (0, 0), (8, 0), (8, -99999999), (24, 7)):
            head = lines[0]
            edited = head[:field] + f"{value:8d}" + head[field + 8:]
            out.append((name, f"header field {field // 8 + 1} = {value}", "structure",
                        "\n".join([edited] + lines[1:]).encode()))
        records = [i for i, line in enumerate(lines) if len(line.split()) == 3 and "E" not in line]
        for i in records[1:4]:
            icol, irow, nw = (int(x) for x in lines[i].split())
            for values in ((icol, 7, nw), (icol, -1, nw), (99, irow, nw), (icol - 1 or 3, irow, nw),
                           (icol, irow, nw + 2), (icol, irow, 10**7)):
                out.append((name, f"record line {i + 1} = {values}", "structure", "\n".join(
                    lines[:i] + ["".join(f"{v:8d}" for v in values)] + lines[i + 1:]).encode()))
        headers = [i for i, line in enumerate(lines) if len(line.split()) == 1 and "E" not in line]
        for i in headers[:2]:
            for value in (65536 * 5 + 7, 65536 * 5, 65536 * 99 + 1, 1):
                out.append((name, f"string header line {i + 1} = {value}", "structure", "\n".join(
                    lines[:i] + [f"{value:8d}"] + lines[i + 1:]).encode()))
    return out


def _binary_edits(folder: Path) -> list[tuple[str, str, str, bytes]]:
    """Sizes and indices of the binary OP4 files set out of range."""
    out = []
    for name, endian in (("binary.op4", "<"), ("binary_big.op4", ">")):
        raw = (folder / name).read_bytes()
        i4 = np.dtype(endian + "i4")
        for word, value in ((1, 2**30), (2, 2**30), (2, -(2**30)), (1, 0), (4, 9), (1, -1)):
            b = bytearray(raw)
            b[4 * word:4 * word + 4] = np.array([value], i4).tobytes()
            out.append((name, f"header word {word} = {value}", "structure", bytes(b)))
        pos = 32  # the first column record: count, ICOL, IROW, NW, then (sparse BIGMAT) a string's L + 1 and row
        edits = [(1, 0), (1, 99), (2, -1), (2, 99), (3, 10**6), (3, -3), (0, 10**9), (0, 3)]
        if name == "binary_big.op4":
            edits += [(4, 99), (4, 0), (5, 0), (5, 99), (2, 1)]
        for k, value in edits:
            b = bytearray(raw)
            b[pos + 4 * k:pos + 4 * k + 4] = np.array([value], i4).tobytes()
            out.append((name, f"first column record word {k} = {value}", "structure", bytes(b)))
    return out


def _array_edits(folder: Path) -> list[tuple[str, str, str, bytes]]:
    """Sparse indices and declared shapes of the .npz and v7.3 files set out of range (rewritten files)."""
    out = []
    csr = sp.csr_matrix(K)
    tmp = folder / "edit.npz"

    def npz(label, **arrays):
        base = {"M": M, "K_data": csr.data, "K_indices": csr.indices, "K_indptr": csr.indptr, "K_shape": csr.shape}
        np.savez(tmp, **(base | arrays))
        out.append(("model.npz", label, "structure", tmp.read_bytes()))

    for k, value in ((0, -1), (3, 6), (5, 2**40), (15, 7)):
        npz(f"indices[{k}] = {value}", K_indices=np.where(np.arange(csr.nnz) == k, value, csr.indices))
    for k, value in ((0, 1), (3, 1), (6, 17), (6, 2**40), (2, -5)):
        npz(f"indptr[{k}] = {value}", K_indptr=np.where(np.arange(7) == k, value, csr.indptr))
    for shape in ([6, 7], [10**8, 6], [6.5, 6], [-6, 6], [6]):
        npz(f"shape = {shape}", K_shape=np.array(shape))
    npz("indices of floats", K_indices=csr.indices.astype(float))
    npz("data of objects", K_data=np.array([None] * csr.nnz, dtype=object))
    import io
    import zipfile

    header = io.BytesIO()
    np.lib.format.write_array_header_1_0(header, {"descr": "<f8", "fortran_order": False,
                                                  "shape": (10**6, 10**6)})
    member = header.getvalue() + np.zeros(4).tobytes()
    with zipfile.ZipFile(tmp, "w") as z:
        z.writestr("M.npy", member)
        z.writestr("K.npy", member)
    out.append(("model.npz", "an array header declaring 10**12 entries (a valid zip)", "structure", tmp.read_bytes()))

    h5 = folder / "edit.mat"
    csc = sp.csc_matrix(K)
    for k, value in ((0, 6), (4, 2**62), (7, 2**64 - 1), (15, 10**7)):
        ir = csc.indices.astype(np.uint64)
        ir[k] = value
        write_mat73_sparse(h5, "K", 6, csc.data, ir, csc.indptr.astype(np.uint64), M=M)
        out.append(("model73.mat", f"ir[{k}] = {value}", "structure", h5.read_bytes()))
    for k, value in ((1, 0), (3, 9), (6, 15), (6, 2**63)):
        jc = csc.indptr.astype(np.uint64)
        jc[k] = value
        write_mat73_sparse(h5, "K", 6, csc.data, csc.indices.astype(np.uint64), jc, M=M)
        out.append(("model73.mat", f"jc[{k}] = {value}", "structure", h5.read_bytes()))
    for nrows in (10**12, 0, 5):
        write_mat73_sparse(h5, "K", nrows, csc.data, csc.indices.astype(np.uint64), csc.indptr.astype(np.uint64), M=M)
        out.append(("model73.mat", f"MATLAB_sparse = {nrows}", "structure", h5.read_bytes()))
    write_mat73(h5, {"K": K})
    with h5py.File(h5, "a") as f:
        d = f.create_dataset("M", shape=(10**6, 10**6), dtype="f8", chunks=(100, 100))
        d.attrs["MATLAB_class"] = np.bytes_("double")
    out.append(("model73.mat", "M declared 10**6 x 10**6 (unwritten chunks)", "structure", h5.read_bytes()))

    v5 = bytearray((folder / "model5.mat").read_bytes())
    for value in (2**30, 0, 7):  # M's first dimension: tag 8 + flags 16 + dims tag 8 bytes into the variable
        b = bytearray(v5)
        b[128 + 32:128 + 36] = np.array([value], "<i4").tobytes()
        out.append(("model5.mat", f"M's first dimension = {value}", "structure", bytes(b)))
    return out


def _commercial_edits(folder: Path) -> list[tuple[str, str, str, bytes]]:
    """Sizes, offsets and indices of the ANSYS .full and Harwell-Boeing files set out of range."""
    out = []
    raw = (folder / "example.full").read_bytes()
    header = 105  # the full-file header record's first data word
    for word, value in ((0, 99), (header + 1, 10**8), (header + 1, 964), (header + 1, 962), (header + 7, 2),
                        (header + 8, 10**6), (header + 18, 537), (header + 22, 10**9), (header + 22, 200000),
                        (header + 35, 130137), (header + 32, 320), (536, 7), (538, 5000), (538, 0), (541, 3),
                        (214, 0)):
        b = bytearray(raw)
        b[4 * word:4 * word + 4] = np.array([value], "<i4").tobytes()
        out.append(("example.full", f"word {word} = {value}", "structure", bytes(b)))
    lines = (folder / "K.rsa").read_text().split("\n")
    for no, start, value in ((1, 0, 99), (1, 14, 0), (2, 14, 10**9), (2, 14, 5), (2, 28, 7), (2, 42, 3),
                             (2, 56, 3)):
        line = lines[no]
        edited = line[:start] + f"{value:14d}" + line[start + 14:]
        out.append(("K.rsa", f"line {no + 1} field at {start} = {value}", "structure",
                    "\n".join(lines[:no] + [edited] + lines[no + 1:]).encode()))
    return out


# -- the child that reads ----------------------------------------------------------------------------------------
CHILD = r"""
import json, resource, sys, warnings
from pathlib import Path
import numpy as np, scipy.sparse as sp
with open("/proc/self/statm") as f:
    used = int(f.read().split()[0]) * resource.getpagesize()
resource.setrlimit(resource.RLIMIT_AS, (used + (1 << 30), resource.RLIM_INFINITY))  # 1 GB more at most
warnings.simplefilter("ignore")
from microslip.fe import read_matrices, read_matrix
from microslip.frequency import CraigBampton

def read(kind, path, base):
    if kind == "matrix":
        return {"A": read_matrix(path)}
    if kind == "matrices":
        m = read_matrices(path)
        return {"M": m.M, "K": m.K, **({"C": m.C} if m.C is not None else {})}
    if kind == "dof_map":
        return {"names": read_matrices(base, dof_map=path).dof_map.names}
    if kind == "dmig":
        m = read_matrices(path, names={"M": "MAAX", "K": "KAAX"})
        return {"M": m.M, "K": m.K, "names": m.dof_map.names}
    cb = CraigBampton.load(path)
    s = cb.structure
    return {"M": s.M, "C": s.C, "K": s.K, "recovery": cb.recovery, "keep": cb.keep, "frequencies": cb.frequencies,
            "static": s.static_force, "contacts": [np.concatenate([c.tangential, c.normal]) for c in s.contacts]}

def plain(x):
    if isinstance(x, list) and x and isinstance(x[0], str):
        return x
    if isinstance(x, list):
        return [plain(v) for v in x]
    a = x.toarray() if sp.issparse(x) else np.asarray(x)
    return a

def same(a, b):
    if isinstance(a, list) and a and isinstance(a[0], str) or isinstance(b, list) and b and isinstance(b[0], str):
        return a == b
    if isinstance(a, list) or isinstance(b, list):
        return (isinstance(a, list) and isinstance(b, list) and len(a) == len(b)
                and all(same(x, y) for x, y in zip(a, b)))
    return a.shape == b.shape and np.array_equal(a, b)

def finite(x):
    if isinstance(x, list) and x and isinstance(x[0], str):
        return True
    if isinstance(x, list):
        return all(finite(v) for v in x)
    return x.dtype.kind not in "fc" or bool(np.isfinite(x).all())

jobs = json.loads(Path(sys.argv[1]).read_text())
start = int(sys.argv[2])
refs = {}
for k in range(start, len(jobs)):
    job = jobs[k]
    print(json.dumps({"k": k, "status": "started"}), flush=True)
    key = job["original"]
    if key not in refs:
        refs[key] = {n: plain(v) for n, v in read(job["kind"], Path(job["original"]), Path(job["base"])).items()}
    path = Path(job["path"])
    try:
        got = {n: plain(v) for n, v in read(job["kind"], path, Path(job["base"])).items()}
    except BaseException as err:  # every kind is reported: the parent decides
        out = {"outcome": "error", "type": type(err).__name__, "classes": [c.__name__ for c in type(err).__mro__],
               "message": str(err)[:300]}
    else:
        ref = refs[key]
        equal = all(n in ref and same(got[n], ref[n]) for n in got)
        outcome = "changed" if not equal else "same" if got.keys() == ref.keys() else "fewer"
        out = {"outcome": outcome, "finite": all(finite(v) for v in got.values())}
    print(json.dumps({"k": k, **out}), flush=True)
"""


def _run(jobs_file: Path, count: int) -> dict:
    """Read every job in children (a new child after a crash); ``{k: result}``."""
    results, start = {}, 0
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
    while start < count:
        run = subprocess.run([sys.executable, "-c", CHILD, str(jobs_file), str(start)], capture_output=True,
                             text=True, timeout=300, env=env)
        last = start - 1
        for line in run.stdout.splitlines():
            r = json.loads(line)
            if r.get("status") == "started":
                last = r["k"]
            else:
                results[r["k"]] = r
        if run.returncode != 0 or last not in results:
            results[max(last, start)] = {"outcome": "crash", "returncode": run.returncode,
                                         "stderr": run.stderr[-1500:]}
            start = max(last, start) + 1
        else:
            start = count
    return results


@pytest.fixture(scope="module")
def fuzzed(tmp_path_factory):
    folder = tmp_path_factory.mktemp("valid")
    _write_files(folder)
    damaged = tmp_path_factory.mktemp("damaged")
    rng = np.random.default_rng(SEED)
    edits = [(name, label, kind, content) for name in FILES
             for label, kind, content in _damaged_copies(folder, name, rng)]
    edits += _text_edits(folder) + _binary_edits(folder) + _array_edits(folder) + _commercial_edits(folder)
    jobs = []
    for k, (name, label, kind, content) in enumerate(edits):
        path = damaged / f"{k:04d}_{name}"
        path.write_bytes(content)
        jobs.append({"name": name, "label": label, "damage": kind, "path": str(path), "original": str(folder / name),
                     "line_end": content.endswith(b"\n"),
                     "kind": FILES[name][0], "base": str(folder / "base.npz")})
    jobs_file = damaged / "jobs.json"
    jobs_file.write_text(json.dumps(jobs))
    return jobs, _run(jobs_file, len(jobs))


def _verdict(job, r) -> str | None:
    """What is wrong with the result ``r`` of reading ``job``'s file, or None."""
    if r is None:
        return "no result"
    if r["outcome"] == "crash":
        return f"the reader crashed (exit {r['returncode']}): {r['stderr'][-600:]}"
    if r["outcome"] == "error":
        if "ValueError" not in r["classes"]:
            return f"raised {r['type']}: {r['message']}"
        if job["path"] not in r["message"]:
            return f"raised {r['type']} without naming the file: {r['message']}"
        if "more data than the memory holds" in r["message"]:
            return f"an allocation from a damaged size reached the memory limit: {r['message']}"
        return None
    if not r["finite"]:
        return "returned a non-finite value"
    if job["label"].startswith("truncated") and job["name"] in CUT_AT_LINES and job["line_end"]:
        return None
    if r["outcome"] == "changed" and (job["damage"] == "structure" or not FILES[job["name"]][1]):
        return "returned other matrices than the undamaged file's, without an error"
    if r["outcome"] == "fewer" and not (job["label"].startswith("truncated") or job["damage"] == "value"
                                        and FILES[job["name"]][1]):
        return "returned fewer matrices than the undamaged file, without an error"
    return None


@pytest.mark.parametrize("name", FILES)
def test_a_damaged_file_gives_its_matrices_or_an_error_naming_it(fuzzed, name):
    jobs, results = fuzzed
    mine = [(job, results.get(k)) for k, job in enumerate(jobs) if job["name"] == name]
    assert len(mine) > 30
    problems = [f"{job['label']} ({job['damage']}): {why}" for job, r in mine if (why := _verdict(job, r))]
    assert not problems, f"{name}: {len(problems)} of {len(mine)} damaged copies:\n" + "\n".join(problems[:15])
    errors = sum(r is not None and r["outcome"] == "error" for _, r in mine)
    assert errors > len(mine) // 3  # the damage is found, not merely survived
