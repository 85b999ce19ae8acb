"""A tuned model driven beyond the load it was tuned for says so, once, naming the loads."""

from __future__ import annotations

import re
import warnings

import numpy as np
import pytest

from microslip import MicroslipModel, Sphere, tune
from microslip.model import BeyondTuningWarning

SPHERE = Sphere.paper()


@pytest.fixture
def model():
    return tune(SPHERE, 37.5, elements=4)  # a new object per test: trial warns once per object


def test_the_warning_is_a_user_warning():
    assert issubclass(BeyondTuningWarning, UserWarning)


def test_simulate_warns_once_per_call_naming_the_loads(model):
    n_tot = float(SPHERE.approach(37.5))
    t = np.linspace(0.0, 1e-6, 50)
    n = np.linspace(0.5, 1.5, 50) * n_tot  # half of the path beyond the tuning approach
    with pytest.warns(BeyondTuningWarning) as record:
        model.simulate(t, n)
    assert len(record) == 1
    top = float(model.normal_force(n.max()))
    message = str(record[0].message)
    assert f"carries {top:.4g} N" in message and "tuned for (37.5 N, approach 2.357e-06 m)" in message
    assert record[0].filename == __file__  # points at the caller's line, not at the package


def test_up_to_the_tuning_load_there_is_no_warning(model):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        model.simulate([0.0, 1e-6], SPHERE.approach(37.5))  # exactly the tuning approach
        model.simulate([0.0, 1e-6], model.approach(37.5))  # the model's own inverse, a few ulps away
        model.trial(None, 1e-6, float(SPHERE.approach(37.5)))


def test_trial_warns_once_per_model_object(model):
    n = 1.2 * float(SPHERE.approach(37.5))
    state = None
    with pytest.warns(BeyondTuningWarning) as record:
        for k in range(20):  # a solver steps many times
            state = model.trial(state, 1e-8 * k, n).state
    assert len(record) == 1
    fresh = tune(SPHERE, 37.5, elements=4)
    with pytest.warns(BeyondTuningWarning, match=re.escape("beyond the load it was tuned for (37.5 N")):
        fresh.trial(None, 0.0, n)


def test_a_model_without_provenance_has_no_load_to_compare_with():
    m = MicroslipModel([1e7], [1e8], [0.0], 0.4)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        m.simulate([0.0, 1e-6], 1.0)  # 1 m of approach: nothing known says it is too much
