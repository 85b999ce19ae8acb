"""Test-suite settings: under CI the hypothesis examples are derandomised; figures are closed after each test.

Locally every run draws new examples (and keeps the failures it finds in
``.hypothesis/``); under CI (``CI`` set in the environment, as ``.ci/run``
runs) the same examples are drawn every time, so the gate is reproducible.

BLAS runs on one thread: the suite's dense problems are small, and on a
2-core machine OpenBLAS threads competing with other jobs made factorisations
and eigen-solves 10 times slower (a 711-point reduced curve: 135 s against
10 s); results differ only by rounding.
"""

import os

import numpy  # noqa: F401  (loaded first: a limit set before a BLAS library is loaded does not reach it)
import scipy.linalg  # noqa: F401
from hypothesis import settings
from threadpoolctl import threadpool_info, threadpool_limits

_ONE_BLAS_THREAD = threadpool_limits(limits=1, user_api="blas")
assert all(p["num_threads"] == 1 for p in threadpool_info() if p["user_api"] == "blas"), threadpool_info()

settings.register_profile("ci", derandomize=True, print_blob=True)
if os.environ.get("CI"):
    settings.load_profile("ci")


import pytest  # noqa: E402


@pytest.fixture(autouse=True)
def _close_figures():
    """Every figure a test draws is closed after it (pyplot keeps them open otherwise)."""
    yield
    import sys

    if "matplotlib.pyplot" in sys.modules:
        sys.modules["matplotlib.pyplot"].close("all")
