"""Writers of the matrix file formats as the programs that produce them lay them out (test helpers)."""

import struct
import zipfile

import h5py
import numpy as np
import scipy.io
import scipy.sparse as sp


def chain(n=6, seed=0):
    """A symmetric positive definite tridiagonal matrix with distinct entries (sparse CSR)."""
    rng = np.random.default_rng(seed)
    k = rng.uniform(1e5, 1e6, n + 1)
    return sp.diags([-k[1:-1], k[:-1] + k[1:], -k[1:-1]], [-1, 0, 1], format="csr")


def dense(A):
    return A.toarray() if sp.issparse(A) else np.asarray(A)


# -- MATLAB v7.3 (HDF5) as MATLAB lays it out ----------------------------------------------------------
def write_mat73(path, variables):
    with h5py.File(path, "w", userblock_size=512) as f:
        for name, A in variables.items():
            if sp.issparse(A):
                csc = sp.csc_matrix(A)
                g = f.create_group(name)
                g.attrs["MATLAB_class"] = np.bytes_("double")
                g.attrs["MATLAB_sparse"] = np.uint64(csc.shape[0])
                g["data"], g["ir"], g["jc"] = csc.data, csc.indices.astype(np.uint64), csc.indptr.astype(np.uint64)
            elif np.asarray(A).dtype.kind == "U":  # MATLAB text: UTF-16 code units
                d = f.create_dataset(name, data=np.vectorize(ord)(A).astype(np.uint16).T)
                d.attrs["MATLAB_class"] = np.bytes_("char")
            else:
                d = f.create_dataset(name, data=np.asarray(A).T)  # MATLAB writes columns first
                d.attrs["MATLAB_class"] = np.bytes_("double")
    with open(path, "r+b") as fh:
        fh.write(b"MATLAB 7.3 MAT-file, created by a test".ljust(116) + bytes(8) + b"\x00\x02IM")


def write_mat73_sparse(path, name, nrows, data, ir, jc, *, M=None):
    """One sparse variable from raw ``data, ir, jc`` (as a damaged or hand-made file may hold them)."""
    with h5py.File(path, "w", userblock_size=512) as f:
        g = f.create_group(name)
        g.attrs["MATLAB_class"] = np.bytes_("double")
        g.attrs["MATLAB_sparse"] = np.uint64(nrows)
        g["data"], g["ir"], g["jc"] = np.asarray(data, float), np.asarray(ir), np.asarray(jc)
        if M is not None:
            d = f.create_dataset("M", data=np.asarray(M).T)
            d.attrs["MATLAB_class"] = np.bytes_("double")
    with open(path, "r+b") as fh:
        fh.write(b"MATLAB 7.3 MAT-file, created by a test".ljust(116) + bytes(8) + b"\x00\x02IM")


def write_mat5(path, variables, compress=False):
    scipy.io.savemat(path, variables, do_compression=compress)


# -- Nastran OP4 ----------------------------------------------------------------------------------------
def write_op4(path, variables):
    """Text OP4 as pyNastran writes it (NW counting values in dense records)."""
    from pyNastran.op4.op4 import OP4

    matrices = {k: (6, sp.coo_matrix(A) if sp.issparse(A) else np.asarray(A)) for k, A in variables.items()}
    OP4().write_op4(str(path), matrices, is_binary=False, precision="double")


def _runs(rows):
    """Consecutive row indices in runs: [[0, 1, 2], [5], ...]."""
    return np.split(rows, np.flatnonzero(np.diff(rows) != 1) + 1) if rows.size else []


def write_op4_text(path, variables, *, sparse=False, bigmat=False):
    """Text OP4 as Nastran writes it (``1P,3E23.16``, counts in 4-byte words: 2 per double)."""
    out = []
    for name, A in variables.items():
        A = dense(A)
        nrows, ncols = A.shape
        out.append(f"{ncols:8d}{-nrows if bigmat else nrows:8d}{6:8d}{2:8d}{name:<8s}1P,3E23.16")
        for j in range(ncols):
            nz = np.flatnonzero(A[:, j])
            if not nz.size:
                continue
            if not sparse:
                vals = A[nz[0]:nz[-1] + 1, j]
                out.append(f"{j + 1:8d}{nz[0] + 1:8d}{2 * vals.size:8d}")
                out += _lines(vals)
                continue
            runs = _runs(nz)
            nw = sum((2 if bigmat else 1) + 2 * r.size for r in runs)
            out.append(f"{j + 1:8d}{0:8d}{nw:8d}")
            for r in runs:
                L = 2 * r.size
                out.append(f"{L + 1:8d}{r[0] + 1:8d}" if bigmat else f"{r[0] + 1 + 65536 * (L + 1):8d}")
                out += _lines(A[r, j])
        out.append(f"{ncols + 1:8d}{1:8d}{1:8d}")
        out.append(f"{1.0:23.16E}")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def _lines(vals):
    return ["".join(f"{v:23.16E}" for v in vals[i:i + 3]) for i in range(0, vals.size, 3)]


def write_op4_binary(path, variables, *, sparse=False, bigmat=False, endian="<", kind=2):
    """Binary OP4 as Nastran writes it: Fortran records (byte count before and after each)."""
    vdt = np.dtype(endian + {1: "f4", 2: "f8"}[kind])
    words = {1: 1, 2: 2}[kind]
    out = bytearray()

    def record(payload):
        out.extend(struct.pack(endian + "i", len(payload)) + payload + struct.pack(endian + "i", len(payload)))

    def ints(*values):
        return struct.pack(endian + f"{len(values)}i", *values)

    for name, A in variables.items():
        A = dense(A)
        nrows, ncols = A.shape
        record(ints(ncols, -nrows if bigmat else nrows, 6, kind) + name.ljust(8).encode())
        for j in range(ncols):
            nz = np.flatnonzero(A[:, j])
            if not nz.size:
                continue
            if not sparse:
                vals = A[nz[0]:nz[-1] + 1, j].astype(vdt)
                record(ints(j + 1, nz[0] + 1, vals.size * words) + vals.tobytes())
                continue
            body = b""
            for r in _runs(nz):
                L = r.size * words
                body += (ints(L + 1, r[0] + 1) if bigmat else ints(r[0] + 1 + 65536 * (L + 1)))
                body += A[r, j].astype(vdt).tobytes()
            record(ints(j + 1, 0, len(body) // 4) + body)
        record(ints(ncols + 1, 1, words) + np.array([1.0], vdt).tobytes())
    with open(path, "wb") as f:
        f.write(bytes(out))


# -- NumPy .npz -------------------------------------------------------------------------------------------
def write_npz(path, variables):
    arrays = {}
    for name, A in variables.items():
        if sp.issparse(A):
            arrays |= {f"{name}_data": A.data, f"{name}_indices": A.indices, f"{name}_indptr": A.indptr,
                       f"{name}_shape": A.shape, f"{name}_format": A.format}
        else:
            arrays[name] = A
    np.savez(path, **arrays)


def data_offset(path, member: str) -> int:
    """Where the stored (maybe compressed) bytes of ``member`` start in the zip file ``path``."""
    with zipfile.ZipFile(path) as z:
        info = z.getinfo(member)
    with open(path, "rb") as f:
        f.seek(info.header_offset + 26)
        name_length, extra_length = struct.unpack("<HH", f.read(4))
    return info.header_offset + 30 + name_length + extra_length


def damage_npz(path, damage: str, member: str = "M.npy"):
    """Empty, truncate (half) or flip a bit in the middle of ``member``'s stored data (not a header)."""
    raw = bytearray(open(path, "rb").read())
    if damage == "empty":
        raw = b""
    elif damage == "truncated":
        raw = raw[:len(raw) // 2]
    else:
        with zipfile.ZipFile(path) as z:
            middle = z.getinfo(member).compress_size // 2
        raw[data_offset(path, member) + middle] ^= 0x10
    open(path, "wb").write(bytes(raw))
