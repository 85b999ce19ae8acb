"""BLAS threads for small dense linear algebra (private).

OpenBLAS's threads wait busily for work after each call: on small dense
systems solved thousands of times, on a machine whose cores are busy, they
made a nonlinear mode of a 20-DOF chain take 37 s instead of 0.3 s with one
thread. The solvers of small dense problems run with one BLAS thread.
"""

from __future__ import annotations

import contextlib
from contextlib import contextmanager
from functools import cache

#: unknowns up to which the harmonic balance uses dense linear algebra (and one BLAS thread)
DENSE_LIMIT = 600


@cache
def _controller():
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()


@contextmanager
def one_blas_thread():
    """Dense LAPACK with one BLAS thread inside the block (the previous limits restored after)."""
    with _controller().limit(limits=1, user_api="blas"):
        yield


def small_dense(structure, harmonics: int):
    """:func:`one_blas_thread` when the harmonic balance of every DOF of ``structure`` is small and dense, else nothing.

    ``(2 harmonics + 1) ndof <=`` :data:`DENSE_LIMIT` unknowns: every linear
    system of the solve, reduced or not, is then that small.
    """
    if (2 * harmonics + 1) * structure.ndof <= DENSE_LIMIT:
        return one_blas_thread()
    return contextlib.nullcontext()
