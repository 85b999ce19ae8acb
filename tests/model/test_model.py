"""MicroslipModel: validation, immutability, marching, trial/commit, static curves, JSON."""

from __future__ import annotations

import dataclasses
import json
import os
import re

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from _strategies import UM, models, paths, plane_paths
from microslip import MicroslipModel, Response, Sphere, State, Step, tune
from microslip.model import OPEN, SLIP, STICK, BeyondTuningWarning, _fresh


@pytest.fixture(scope="module")
def paper_model():
    return tune(Sphere.paper(), 37.5, elements=4)


def small_model():
    """Two elements with binary-exact numbers, so a path can be followed by hand."""
    return MicroslipModel(kt=[1.0, 2.0], kn=[10.0, 10.0], gaps=[0.0, 1.0], mu=0.5)


# -- validation ------------------------------------------------------------
GOOD = dict(kt=[1e7, 2e7], kn=[1e8, 1e8], gaps=[0.0, 1e-7], mu=0.4)


@pytest.mark.parametrize("change, error, message", [
    (dict(kt=[1e7, -2e7]), ValueError, "kt must be positive, got -20000000.0 at flat index 1"),
    (dict(kt=[0.0, 2e7]), ValueError, "kt must be positive, got 0.0 at flat index 0"),
    (dict(kt=[np.inf, 2e7]), ValueError, "kt must be finite, got inf at flat index 0"),
    (dict(kn=[1e8, 0.0]), ValueError, "kn must be positive, got 0.0 at flat index 1"),
    (dict(kn=[np.nan, 1e8]), ValueError, "kn must be finite, got nan at flat index 0"),
    (dict(gaps=[0.0, np.nan]), ValueError, "gaps must be finite, got nan at flat index 1"),
    (dict(gaps=[-np.inf, 0.0]), ValueError, "gaps must be finite, got -inf at flat index 0"),
    (dict(mu=0.0), ValueError, "mu must be positive, got 0.0"),
    (dict(mu=-0.3), ValueError, "mu must be positive, got -0.3"),
    (dict(mu=np.nan), ValueError, "mu must be finite, got nan"),
    (dict(mu="high"), TypeError, "mu must be a real number, got 'high'"),
    (dict(kn=[1e8, 1e8, 1e8]), ValueError, "kn must have the same length as kt (2), got 3"),
    (dict(gaps=[0.0]), ValueError, "gaps must have the same length as kt (2), got 1"),
    (dict(kt=[], kn=[], gaps=[]), ValueError, "kt must have at least 1 value(s), got 0"),
    (dict(kt=[[1e7, 2e7]]), ValueError, "kt must be 1-D, got shape (1, 2)"),
    (dict(kt=["a", "b"]), TypeError, "kt must be an array of real numbers, got ['a', 'b']"),
])
def test_invalid_parameters_are_named_with_their_value(change, error, message):
    with pytest.raises(error, match=re.escape(message)):
        MicroslipModel(**{**GOOD, **change})


def test_single_element_is_allowed():
    m = MicroslipModel(kt=[1e7], kn=[1e8], gaps=[0.0], mu=0.4)
    assert m.elements == 1


# -- immutability -------------------------------------------------------------
def test_parameters_are_read_only_copies():
    kt = np.array([1e7, 2e7])
    m = MicroslipModel(kt=kt, kn=[1e8, 1e8], gaps=[0.0, 1e-7], mu=0.4)
    kt[0] = 5.0  # the caller's array is copied
    assert m.kt[0] == 1e7
    for name in ("kt", "kn", "gaps"):
        with pytest.raises(ValueError, match="read-only"):
            getattr(m, name)[0] = 1.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        m.mu = 1.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        m.kt = np.ones(2)


def test_state_is_read_only():
    r = small_model().simulate([1.0, 3.0], 2.0)
    with pytest.raises(ValueError, match="read-only"):
        r.state.sliders[0] = 1.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        r.state.sliders = np.zeros(2)


def test_equality_and_unhashable():
    assert MicroslipModel(**GOOD) == MicroslipModel(**GOOD)
    assert MicroslipModel(**GOOD) != MicroslipModel(**{**GOOD, "mu": 0.5})
    assert MicroslipModel(**GOOD) != "model"
    with pytest.raises(TypeError):
        hash(MicroslipModel(**GOOD))


# -- simulate -----------------------------------------------------------------
def test_hand_built_path_conditions_and_forces():
    """Two elements (kt 1, 2 N/m; kn 10 N/m; gaps 0, 1 m; mu 0.5) followed by hand.

    At n = 2 the friction limits are 10 N and 5 N; at n = 0.5 element 1 carries
    a limit of 2.5 N and element 2 is open.
    """
    m = small_model()
    t = [1.0, 3.0, 12.0, 12.0, 12.0, 11.0]
    n = [2.0, 2.0, 2.0, 0.5, 2.0, 2.0]
    r = m.simulate(t, n)
    expected_Ti = [
        [1.0, 2.0],    # both stick
        [3.0, 5.0],    # element 2 slips at its limit, slider to 3 - 5/2 = 0.5
        [10.0, 5.0],   # both slip: sliders at 2 and 9.5
        [2.5, 0.0],    # n drops: element 1 slips at 2.5 N (slider 9.5), element 2 opens (slider 12)
        [2.5, 0.0],    # n back up: element 1 sticks, element 2 re-enters contact unloaded
        [1.5, -2.0],   # reversal: both stick
    ]
    expected_cond = [
        [STICK, STICK], [STICK, SLIP], [SLIP, SLIP], [SLIP, OPEN], [STICK, STICK], [STICK, STICK],
    ]
    np.testing.assert_array_equal(r.Ti, expected_Ti)
    np.testing.assert_array_equal(r.condition, expected_cond)
    np.testing.assert_array_equal(r.T, np.sum(expected_Ti, axis=1))
    np.testing.assert_array_equal(r.N, [30.0, 30.0, 30.0, 5.0, 30.0, 30.0])
    np.testing.assert_array_equal(r.state.sliders, [9.5, 12.0])
    assert r.condition.dtype == np.int8
    assert (OPEN, STICK, SLIP) == (0, 1, 2)


def test_default_state_starts_every_slider_at_zero(paper_model):
    """An element in contact at the first sample carries kt_i * t[0], capped by friction."""
    m = paper_model
    n0 = 1.2e-6  # elements 1..2 closed, 3..4 open (gaps ~0, 0.94, 1.49, 1.95 µm)
    for t0 in (0.05 * UM, -0.05 * UM, 2 * UM, -2 * UM):
        r = m.simulate([t0], [n0])
        Ni = m.element_normal_forces(n0)
        expected = np.sign(t0) * np.minimum(m.kt * abs(t0), m.mu * Ni)
        np.testing.assert_allclose(r.Ti[0], expected, rtol=1e-15, atol=0)
        assert list(r.condition[0, 2:]) == [OPEN, OPEN]
    assert m.simulate([0.05 * UM], [n0]).condition[0, 0] == STICK
    assert m.simulate([2 * UM], [n0]).condition[0, 0] == SLIP
    np.testing.assert_array_equal(m.initial_state().sliders, np.zeros(4))
    # an explicit initial state at t0 starts unloaded at t0
    r = m.simulate([1 * UM], [n0], state=m.initial_state(1 * UM))
    np.testing.assert_array_equal(r.Ti[0], np.zeros(4))


@settings(max_examples=80, deadline=None)
@given(model=models(), path=st.one_of(paths(min_size=2), plane_paths(min_size=2)), data=st.data())
def test_two_calls_continue_one_call_bit_for_bit(model, path, data):
    """Along one direction and on the contact plane (t of shape (steps, 2))."""
    t, n = path
    k = data.draw(st.integers(1, t.shape[0] - 1))
    whole = model.simulate(t, n)
    first = model.simulate(t[:k], n[:k])
    second = model.simulate(t[k:], n[k:], state=first.state)
    np.testing.assert_array_equal(np.concatenate([first.T, second.T]), whole.T)
    np.testing.assert_array_equal(np.concatenate([first.Ti, second.Ti]), whole.Ti)
    np.testing.assert_array_equal(np.concatenate([first.condition, second.condition]), whole.condition)
    np.testing.assert_array_equal(np.concatenate([first.friction_work, second.friction_work]), whole.friction_work)
    np.testing.assert_array_equal(second.state.sliders, whole.state.sliders)
    for work in (True, False):
        totals = model.simulate(t[k:], n[k:], state=first.state, per_element=False, work=work)
        np.testing.assert_array_equal(totals.T, second.T)
        np.testing.assert_array_equal(totals.N, second.N)
        np.testing.assert_array_equal(totals.state.sliders, second.state.sliders)


@settings(max_examples=60, deadline=None)
@given(model=models(), path=paths())
def test_totals_only_march_equals_per_element_march(model, path):
    t, n = path
    full = model.simulate(t, n)
    fast = model.simulate(t, n, per_element=False)
    np.testing.assert_array_equal(fast.T, full.T)
    np.testing.assert_array_equal(fast.N, full.N)
    np.testing.assert_array_equal(fast.state.sliders, full.state.sliders)
    assert fast.Ti is None and fast.condition is None
    # totals are the sums of the element forces (up to the order of summation)
    np.testing.assert_allclose(full.Ti.sum(axis=1), full.T, rtol=1e-13, atol=1e-13 * np.abs(full.Ti).max())
    np.testing.assert_allclose(full.Ni.sum(axis=1), full.N, rtol=1e-13, atol=0)


def test_Ni_property(paper_model):
    m = paper_model
    n = np.linspace(-0.5, 2.5, 13) * UM
    with pytest.warns(BeyondTuningWarning):  # 2.5 um is beyond the 2.36 um of the tuning load
        r = m.simulate(np.zeros_like(n), n)
    assert r.Ni.shape == (13, 4)
    np.testing.assert_array_equal(r.Ni, m.kn * np.maximum(n[:, None] - m.gaps, 0.0))
    np.testing.assert_array_equal(r.Ni[0], np.zeros(4))  # n < 0: all open


def test_scalar_n_is_held_constant(paper_model):
    t = np.linspace(0, 2, 50) * UM
    n = 1.5 * UM
    a = paper_model.simulate(t, n)
    b = paper_model.simulate(t, np.full(t.size, n))
    np.testing.assert_array_equal(a.T, b.T)
    np.testing.assert_array_equal(a.n, b.n)
    assert isinstance(a, Response) and a.model is paper_model


@pytest.mark.parametrize("kwargs, error, message", [
    (dict(t=[[0.0, 1e-6, 2e-6]], n=1e-6), ValueError, "t must have shape (steps,) (one tangential direction) or "
     "(steps, 2) (its two components on the contact plane), got shape (1, 3)"),
    (dict(t=[], n=1e-6), ValueError, "t must have at least 1 value(s), got 0"),
    (dict(t=[0.0, np.nan], n=1e-6), ValueError, "t must be finite, got nan at flat index 1"),
    (dict(t=[0.0, 1e-6], n=[1e-6, 1e-6, 1e-6]), ValueError,
     "n must be a scalar or have the same shape as t (2,), got (3,)"),
    (dict(t=[0.0, 1e-6], n=[1e-6, np.inf]), ValueError, "n must be finite, got inf at flat index 1"),
    (dict(t=[0.0], n=1e-6, state=np.zeros(4)), TypeError,
     "state must be a microslip State (from a Response or Step), got ndarray"),
    (dict(t=[0.0], n=1e-6, state=State(np.zeros(3))), ValueError,
     "state has 3 sliders, this model has J = 4"),
    (dict(t=[0.0], n=1e-6, per_element="no"), TypeError, "per_element must be True or False, got 'no'"),
    (dict(t=[0.0], n=1e-6, work=1), TypeError, "work must be True or False, got 1"),
    (dict(t=[0.0], n=1e-6, work=0), TypeError, "work must be True or False, got 0"),
    (dict(t=[0.0], n=1e-6, work=None), TypeError, "work must be True or False, got None"),
])
def test_simulate_rejects_bad_input(paper_model, kwargs, error, message):
    with pytest.raises(error, match=re.escape(message)):
        paper_model.simulate(**kwargs)


def test_backbone_and_files_name_their_arguments(paper_model):
    with pytest.raises(ValueError, match=re.escape("t (shape (3,)) and n (shape (2,)) must have shapes that")):
        paper_model.backbone([0.0, 1e-7, 2e-7], [1e-6, 2e-6])
    with pytest.raises(TypeError, match=re.escape("path must be a file name (str or os.PathLike), got 1.0")):
        paper_model.save(1.0)
    with pytest.raises(TypeError, match=re.escape("path must be a file name (str or os.PathLike), got None")):
        MicroslipModel.load(None)


def test_initial_state_rejects_bad_t0(paper_model):
    with pytest.raises(ValueError, match=re.escape("t0 must be finite, got nan")):
        paper_model.initial_state(np.nan)


def test_response_dissipation_and_plot(paper_model):
    import matplotlib

    matplotlib.use("Agg")
    n = Sphere.paper().approach(37.5)
    t = 1.0 * UM * np.sin(np.linspace(0, 4 * np.pi, 401))
    r = paper_model.simulate(t, n)
    assert r.dissipation > 0
    assert paper_model.simulate([1e-7], n).dissipation == 0.0
    ax = r.plot(label="4 elements")
    assert "µm" in ax.get_xlabel() and "(N)" in ax.get_ylabel()
    assert ax.get_legend() is not None
    import matplotlib.pyplot as plt

    plt.close(ax.figure)


# -- trial / commit -------------------------------------------------------------
@settings(max_examples=80, deadline=None)
@given(model=models(), path=st.one_of(paths(), plane_paths()))
def test_committed_trials_reproduce_simulate(model, path):
    """Along one direction and on the contact plane (a pair t, a 2x2 tangent)."""
    t, n = path
    r = model.simulate(t, n)
    state = None
    for k in range(t.shape[0]):
        before = None if state is None else state.sliders.copy()
        step = model.trial(state, t[k], n[k])
        if state is not None:  # a trial never mutates the committed state
            np.testing.assert_array_equal(state.sliders, before)
        assert isinstance(step, Step)
        np.testing.assert_array_equal(step.T, r.T[k])
        assert step.N == r.N[k] and np.shape(step.dT_dt) == t.shape[1:] * 2 and np.shape(step.dT_dn) == t.shape[1:]
        np.testing.assert_array_equal(step.Ti, r.Ti[k])
        np.testing.assert_array_equal(step.condition, r.condition[k])
        state = step.state  # commit
    np.testing.assert_array_equal(state.sliders, r.state.sliders)


def test_trial_discarded_leaves_state_usable(paper_model):
    n = 1.5 * UM
    r = paper_model.simulate([0.5 * UM], n)
    paper_model.trial(r.state, 3 * UM, n)  # big slipping trial, discarded
    again = paper_model.simulate([0.6 * UM], n, state=r.state)
    direct = paper_model.simulate([0.5 * UM, 0.6 * UM], n)
    assert again.T[0] == direct.T[1]


@settings(max_examples=80, deadline=None)
@given(model=models(), path=paths(), t=st.floats(-3 * UM, 3 * UM), n=st.floats(-0.5 * UM, 3 * UM))
def test_consistent_tangent_matches_finite_differences(model, path, t, n):
    """Away from a switch of condition the step is linear in (t, n): central differences are exact
    up to rounding. h = 1e-12 m is 1e-6 of the path scale; the relative error of a difference of
    forces of order kt*3e-6 m is then ~ eps * 3e-6 / 1e-12 ~ 1e-9, so rtol = 1e-6 has a margin."""
    state = model.simulate(*path).state
    h = 1e-12
    step = model.trial(state, t, n)
    probes = [model.trial(state, t + dt, n + dn) for dt, dn in ((h, 0), (-h, 0), (0, h), (0, -h))]
    assume(all(np.array_equal(p.condition, step.condition) for p in probes))
    scale = float(model.kt.sum() + model.kn.sum())
    dT_dt = (probes[0].T - probes[1].T) / (2 * h)
    dT_dn = (probes[2].T - probes[3].T) / (2 * h)
    dN_dn = (probes[2].N - probes[3].N) / (2 * h)
    assert dT_dt == pytest.approx(step.dT_dt, rel=1e-6, abs=1e-6 * scale)
    assert dT_dn == pytest.approx(step.dT_dn, rel=1e-6, abs=1e-6 * scale)
    assert dN_dn == pytest.approx(step.dN_dn, rel=1e-6, abs=1e-6 * scale)


def test_consistent_tangent_by_hand():
    m = small_model()
    # state after the hand path's third sample: sliders at 2 and 9.5
    state = m.simulate([1.0, 3.0, 12.0], 2.0).state
    stick = m.trial(state, 11.0, 2.0)      # both stick
    assert (stick.dT_dt, stick.dT_dn, stick.dN_dn) == (3.0, 0.0, 20.0)
    slip = m.trial(state, 13.0, 2.0)       # both slip forward
    assert (slip.dT_dt, slip.dT_dn, slip.dN_dn) == (0.0, 0.5 * 10 + 0.5 * 10, 20.0)
    half = m.trial(state, 12.0, 0.5)       # element 1 slips, element 2 open
    assert (half.dT_dt, half.dT_dn, half.dN_dn) == (0.0, 5.0, 10.0)
    back = m.trial(state, -20.0, 2.0)      # both slip backward
    assert back.dT_dn == -10.0


@pytest.mark.parametrize("t, n, message", [
    (np.nan, 1e-6, "t must be finite, got nan"),
    (0.0, "deep", "n must be a real number, got 'deep'"),
    (True, 1e-6, "t must be a real number, got True"),
])
def test_trial_rejects_bad_input(paper_model, t, n, message):
    with pytest.raises((ValueError, TypeError), match=re.escape(message)):
        paper_model.trial(None, t, n)


# -- static curves --------------------------------------------------------------
def test_approach_inverts_normal_force(paper_model):
    m = paper_model
    n = np.linspace(m.gaps.min(), 4 * UM, 41)
    np.testing.assert_allclose(m.approach(m.normal_force(n)), n, rtol=1e-12, atol=1e-12 * UM)
    N = np.array([0.0, 1.0, 10.0, 37.5, 80.0])
    np.testing.assert_allclose(m.normal_force(m.approach(N)), N, rtol=1e-12, atol=1e-12)
    assert m.approach(0.0) == m.gaps.min()
    # the tuned array carries N_tot at the reference approach
    assert float(m.approach(37.5)) == pytest.approx(float(Sphere.paper().approach(37.5)), rel=1e-12)


def test_approach_with_equal_gaps():
    m = MicroslipModel(kt=[1.0, 1.0, 1.0], kn=[1.0, 2.0, 3.0], gaps=[0.0, 0.0, 1.0], mu=0.5)
    # slope 3 up to n = 1 (N = 3), then slope 6
    np.testing.assert_allclose(m.approach([0.0, 1.5, 3.0, 9.0]), [0.0, 0.5, 1.0, 2.0], rtol=1e-15)


def test_approach_rejects_negative_load(paper_model):
    with pytest.raises(ValueError, match=re.escape("N must be non-negative, got -1.0 at flat index 0")):
        paper_model.approach(-1.0)


def test_backbone_is_the_virgin_monotone_march(paper_model):
    m = paper_model
    n = 1.7 * UM
    for t_end in (0.1 * UM, 0.7 * UM, 3 * UM):
        marched = m.simulate(np.linspace(0, t_end, 50), n).T[-1]
        assert float(m.backbone(t_end, n)) == pytest.approx(marched, rel=1e-13)
        assert float(m.backbone(-t_end, n)) == -float(m.backbone(t_end, n))
    assert float(m.backbone(10 * UM, n)) == pytest.approx(float(m.slip_force(n)), rel=1e-14)
    # broadcasting: t of shape (3, 1) against n of shape (2,)
    assert m.backbone(np.ones((3, 1)) * UM, [1 * UM, 2 * UM]).shape == (3, 2)
    with pytest.raises(ValueError, match=re.escape("t must be finite, got nan")):
        m.backbone(np.nan, n)


# -- persistence --------------------------------------------------------------------
def test_dict_and_json_round_trip(paper_model, tmp_path):
    d = paper_model.to_dict()
    assert d["format"] == "microslip.MicroslipModel" and d["version"] == 1
    assert d["units"] == {"kt": "N/m", "kn": "N/m", "gaps": "m", "mu": "-"}
    assert MicroslipModel.from_dict(json.loads(json.dumps(d))) == paper_model
    path = paper_model.save(tmp_path / "sub" / "model.json")
    assert path.is_file()
    assert MicroslipModel.load(path) == paper_model
    assert MicroslipModel.load(str(path)) == paper_model


def test_from_dict_rejects_non_dict():
    with pytest.raises(TypeError, match=re.escape("data must be a dict from MicroslipModel.to_dict(), got list")):
        MicroslipModel.from_dict([1, 2])


def test_load_errors(tmp_path):
    missing = tmp_path / "nope.json"
    with pytest.raises(FileNotFoundError, match=re.escape(f"model file {str(missing)!r} does not exist")):
        MicroslipModel.load(missing)
    bad = tmp_path / "bad.json"
    bad.write_text("{kt: [1, 2]")
    with pytest.raises(ValueError, match=re.escape(f"model file {str(bad)!r} is not valid JSON")):
        MicroslipModel.load(bad)


def test_save_is_atomic(paper_model, tmp_path, monkeypatch):
    path = tmp_path / "model.json"
    old = MicroslipModel(**GOOD)
    old.save(path)
    before = path.read_bytes()

    def failing_replace(src, dst):
        raise OSError("disk full (simulated)")

    monkeypatch.setattr(os, "replace", failing_replace)
    with pytest.raises(OSError, match="simulated"):
        paper_model.save(path)
    monkeypatch.undo()
    assert path.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["model.json"]
    assert MicroslipModel.load(path) == old


def test_state_refuses_non_finite_or_non_vector_sliders():
    from microslip import State

    with pytest.raises(ValueError, match=r"sliders must be finite, got nan at flat index 0"):
        State([np.nan, 0.0])
    with pytest.raises(ValueError, match=r"sliders must have shape \(J,\) \(one tangential direction\) or \(J, 2\) "
                                         r"\(the contact plane\), got shape \(2, 1\)"):
        State([[0.0], [1.0]])
    with pytest.raises(TypeError, match=r"sliders must be an array of real numbers, got 'ab'"):
        State("ab")


@pytest.mark.parametrize("bad", ["0.3", True, 0.3 + 0.1j])
def test_numeric_strings_booleans_and_complex_are_not_real_numbers(bad):
    with pytest.raises(TypeError, match=r"mu must be a real number"):
        MicroslipModel(kt=[1.0], kn=[1.0], gaps=[0.0], mu=bad)


def test_arrays_of_strings_are_refused_not_converted():
    with pytest.raises(TypeError, match=r"kt must be an array of real numbers, got \['1', '2'\]"):
        MicroslipModel(kt=["1", "2"], kn=[1.0, 1.0], gaps=[0.0, 0.0], mu=0.3)


def test_friction_work_can_be_left_out_and_then_dissipation_says_so(paper_model):
    t = np.linspace(0.0, 2e-6, 50)
    n = 1.9e-6
    full = paper_model.simulate(t, n, per_element=False)
    fast = paper_model.simulate(t, n, per_element=False, work=False)
    np.testing.assert_array_equal(full.T, fast.T)
    assert fast.friction_work is None
    with pytest.raises(ValueError, match=r"computed with work=False: run simulate\(\.\.\., work=True\)"):
        fast.dissipation
    np.testing.assert_array_equal(full.friction_work, paper_model.simulate(t, n).friction_work)


@pytest.mark.parametrize("shape, dtype", [((300_000, 16, 2), np.float64), ((300_000, 16), np.int8),
                                          ((524_289,), np.float64)])
def test_large_records_start_on_a_huge_page_boundary(shape, dtype):
    """So that every page of the fresh records is a huge page (one fault per 2 MiB, not per 4 KiB)."""
    a = _fresh(shape, dtype)
    assert a.shape == shape and a.dtype == dtype and a.flags.c_contiguous and a.flags.writeable
    assert a.ctypes.data % 2**21 == 0
    a[...] = 1  # the whole view lies inside its allocation
    assert a.base.ctypes.data <= a.ctypes.data and a.ctypes.data + a.nbytes <= a.base.ctypes.data + a.base.nbytes


def test_small_records_are_plain_arrays():
    a = _fresh((100, 16), np.int8)
    assert a.shape == (100, 16) and a.dtype == np.int8 and a.flags.owndata
