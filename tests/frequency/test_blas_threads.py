"""Small dense problems are solved with one BLAS thread (busy-waiting BLAS threads slowed them 100-fold)."""

import importlib

import numpy as np
from threadpoolctl import threadpool_info, threadpool_limits

from microslip import MicroslipModel
from microslip.frequency import Structure, frequency_response, nonlinear_modes

# forced responses and nonlinear modes follow their curves through the response module's continuation
response_module = importlib.import_module("microslip.frequency.analyses.response")


def _blas_threads() -> list[int]:
    return [i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"]


def _jenkins_pair() -> Structure:
    s = Structure(np.eye(2), 0.1 * np.eye(2), [[2e4, -1e4], [-1e4, 1e4]])
    s.add_contact(MicroslipModel([1e4], [1e6], [0.0], 0.5), tangential=1, approach=2e-6)
    return s


def test_forced_responses_and_modes_of_small_structures_run_with_one_blas_thread(monkeypatch):
    seen = []

    def recording(module):
        original = module.continuation

        def continuation(*args, **kwargs):
            seen.append(_blas_threads())
            return original(*args, **kwargs)

        monkeypatch.setattr(module, "continuation", continuation)

    recording(response_module)
    with threadpool_limits(limits=2, user_api="blas"):  # as on a 2-core machine by default
        before = _blas_threads()
        assert max(before) == 2
        frequency_response(_jenkins_pair(), [0.0, 1.0], (60.0, 200.0), harmonics=3, stability=False)
        nonlinear_modes(_jenkins_pair(), 1, (1e-7, 1e-5), harmonics=1)
        assert _blas_threads() == before  # the limit is lifted after
    assert len(seen) == 2 and all(threads and max(threads) == 1 for threads in seen)
