"""BLAS threads for small dense linear algebra (private).

OpenBLAS's threads wait busily for work after each call: on small dense
systems solved thousands of times, on a machine whose cores are busy, they
made a nonlinear mode of a 20-DOF chain take 37 s instead of 0.3 s with one
thread. The solvers of small dense problems run with one BLAS thread; so do the
solvers of interface-dominated structures (their products are small: harmonic
blocks of the structure, contacts' blocks), except for their rare factorisations
of the whole Jacobian, which get :data:`FACTOR_THREADS` (:func:`factor_threads`).
Solves with those factors keep one thread: a triangular solve reads each factor
entry once, so it is bound by the memory's bandwidth, which a second thread on the
same memory does not raise.
"""

from __future__ import annotations

import contextlib
from contextlib import contextmanager
from functools import cache

#: unknowns up to which the harmonic balance uses dense linear algebra (and one BLAS thread)
DENSE_LIMIT = 600
#: BLAS threads of a large dense factorisation inside a one-thread block (None: as many as outside it)
FACTOR_THREADS: int | None = None
#: unknowns from which a factorisation is large
LARGE_DENSE = 2000


@cache
def _controller():
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()


@contextmanager
def one_blas_thread():
    """Dense LAPACK with one BLAS thread inside the block (the previous limits restored after)."""
    with _controller().limit(limits=1, user_api="blas"):
        yield


@contextmanager
def factor_threads(n: int):
    """BLAS threads for a dense factorisation of ``n`` unknowns: from :data:`LARGE_DENSE` on, those in force outside
    any one-thread block (or :data:`FACTOR_THREADS`), else as they are."""
    if n < LARGE_DENSE or _outside[-1] is None:
        yield
        return
    with _controller().limit(limits=FACTOR_THREADS or _outside[-1], user_api="blas"):
        yield


_outside: list = [None]  # BLAS threads when the outermost one-thread block was entered


@contextmanager
def solver_threads():
    """One BLAS thread in the block, remembering the threads outside it for :func:`factor_threads`."""
    if _outside[-1] is None:
        outside = max([i["num_threads"] for i in _controller().info() if i["user_api"] == "blas"], default=1)
    else:
        outside = _outside[-1]
    _outside.append(outside)
    try:
        with one_blas_thread():
            yield
    finally:
        _outside.pop()


def small_dense(structure, harmonics: int):
    """:func:`one_blas_thread` when the harmonic balance of every DOF of ``structure`` is small and dense, else nothing.

    ``(2 harmonics + 1) ndof <=`` :data:`DENSE_LIMIT` unknowns: every linear
    system of the solve, reduced or not, is then that small.
    """
    if (2 * harmonics + 1) * structure.ndof <= DENSE_LIMIT:
        return one_blas_thread()
    return contextlib.nullcontext()
