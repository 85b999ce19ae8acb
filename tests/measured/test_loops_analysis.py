"""Loop analysis against closed forms (a Jenkins element), the kernels against their pure-Python twins,
and the analysis of the real damper data."""

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from microslip import MicroslipModel, Sphere, loops, tune
from microslip.loops import _kernels
from _paths import DAMPER

K, F, A = 2e7, 10.0, 2e-6  # a Jenkins element: stiffness (N/m), slip force (N); amplitude (m)


def _jenkins_record(cycles=5, per_cycle=400, noise_t=0.0, noise_T=0.0, seed=0, start=0.0):
    m = MicroslipModel(kt=[K], kn=[1e9], gaps=[0.0], mu=F / (1e9 * 1e-6))
    tau = np.arange(cycles * per_cycle + 1) / per_cycle
    t = A * np.sin(2 * np.pi * tau + start)
    T = m.simulate(t, 1e-6, per_element=False).T
    rng = np.random.default_rng(seed)
    return loops.Record(t=t + rng.normal(0, noise_t, t.size), T=T + rng.normal(0, noise_T, t.size),
                        time=tau / 10, normal_load=25.0, source="jenkins")


def test_jenkins_element_closed_forms():
    L = loops.analyse(_jenkins_record())
    # energy of a Jenkins loop: 4 F (A - F/K); the trapezoidal rule on 400 samples per cycle is
    # exact on the straight pieces and cuts the corners by < 0.1 % of the area
    assert L.cycles == 4 and L.is_steady  # 5 periods from rest: 9 reversals, 4 complete cycles
    np.testing.assert_allclose(L.energy, 4 * F * (A - F / K), rtol=1e-3)
    # stick is exactly linear; the noise correction reads the curvature of the clean sine as a
    # noise of ~0.3 nm, which raises the slope by < 1e-4
    np.testing.assert_allclose(L.stiffness_after_min, K, rtol=1e-4)
    np.testing.assert_allclose(L.stiffness_after_max, K, rtol=1e-4)
    np.testing.assert_allclose(L.slip_force_positive, F, rtol=1e-12)
    np.testing.assert_allclose(L.slip_force_negative, -F, rtol=1e-12)
    # reversal = mean over ±3 samples of a sine sampled 400 times per cycle: (2 pi / 400)^2 / 2 * 4 = 5e-4 low
    np.testing.assert_allclose(L.amplitude, A, rtol=1e-3)
    np.testing.assert_allclose(L.force_amplitude, F, rtol=1e-3)
    assert L.gross_slip.all()
    # bins of the branch and of the virgin curve sample the corner differently: < 1 %
    assert L.masing_error < 0.01 and L.masing_basis == "virgin curve"


def test_cycle_count_and_energy_survive_noise():
    clean = loops.analyse(_jenkins_record(cycles=8))
    noisy = loops.analyse(_jenkins_record(cycles=8, noise_t=0.01 * A, noise_T=0.01 * F, seed=3))
    # noise of 1 % never makes a reversal (threshold 10 % of the range)
    assert noisy.cycles == clean.cycles == 7 and noisy.reversal_index.size == clean.reversal_index.size
    # energy: noise averages out over 400 samples per loop; 2 % bound = 3 sigma of the area noise
    np.testing.assert_allclose(noisy.energy, clean.energy, rtol=0.02)
    s = noisy.summary()
    assert s["slip_force"] == pytest.approx(F, rel=0.01)
    # slope of ~20 samples with 20 nm of noise on a 100 nm stick window: without the noise
    # correction it would read 0.68 K (regression dilution); 10 % = about 3 sigma of what is left
    assert s["stick_stiffness"] == pytest.approx(K, rel=0.1)


def test_steady_part_excludes_ramps():
    rec = _jenkins_record(cycles=10, per_cycle=200)
    env = np.clip(np.minimum(rec.time * 10 / 2.0, (10 - rec.time * 10) / 2.0), 0.3, 1.0)  # ramp up and down
    m = MicroslipModel(kt=[K], kn=[1e9], gaps=[0.0], mu=F / 1e3)
    t = rec.t * env
    L = loops.analyse(loops.Record(t=t, T=m.simulate(t, 1e-6, per_element=False).T, normal_load=1.0))
    s = L.steady
    assert L.is_steady and s.stop - s.start >= 2
    np.testing.assert_allclose(L.amplitude[s], A, rtol=0.05)  # the steady tolerance
    assert np.all(L.amplitude[: s.start] < 0.95 * A) and np.all(L.amplitude[s.stop:] < 0.95 * A)


def test_never_steady_is_reported():
    tau = np.linspace(0, 6, 2401)
    t = A * (1 + 0.3 * tau) * np.sin(2 * np.pi * tau)  # amplitude grows 30 % per cycle
    m = MicroslipModel(kt=[K], kn=[1e9], gaps=[0.0], mu=F / 1e3)
    L = loops.analyse(loops.Record(t=t, T=m.simulate(t, 1e-6, per_element=False).T))
    assert not L.is_steady and L.steady.stop - L.steady.start == 1


def test_masing_number_flags_a_non_masing_record():
    rec = _jenkins_record(cycles=4)
    # a virgin curve twice as compliant as the branches imply: Masing's rule is broken
    soft = MicroslipModel(kt=[K / 2], kn=[1e9], gaps=[0.0], mu=F / 1e3)
    first = int(np.argmax(rec.t[:200]))
    T = rec.T.copy()
    T[:first + 1] = soft.simulate(rec.t[:first + 1], 1e-6, per_element=False).T
    L = loops.analyse(loops.Record(t=rec.t, T=T))
    assert L.masing_basis == "virgin curve" and L.masing_error > 0.1
    assert loops.analyse(rec).masing_error < 0.01


def test_masing_by_branch_symmetry_without_virgin_curve():
    sphere = Sphere.paper()
    model = tune(sphere, 37.5, elements=40)
    tau = np.linspace(0, 5, 4001)
    t = 1.5e-6 * np.cos(2 * np.pi * tau)  # starts at a reversal, not from rest
    L = loops.analyse(loops.Record(t=t, T=model.simulate(t, float(sphere.approach(37.5)), per_element=False).T))
    assert L.masing_basis == "branch symmetry" and L.masing_error < 0.01


def test_analysis_errors_name_the_parameter():
    rec = _jenkins_record()
    with pytest.raises(ValueError, match=r"threshold must lie in \(0.0, 0.5\], got 0.7"):
        loops.analyse(rec, threshold=0.7)
    with pytest.raises(TypeError, match="record must be a microslip.loops.Record"):
        loops.analyse({"t": [1, 2]})
    with pytest.raises(loops.LoopError, match="does not vary"):
        loops.analyse(loops.Record(t=np.zeros(40), T=np.zeros(40)))
    with pytest.raises(ValueError, match="T must have the same length as t"):
        loops.Record(t=np.zeros(40), T=np.zeros(39))
    L = loops.analyse(rec)
    with pytest.raises(ValueError, match=r"cycle must be < 4 \(the number of complete cycles\), got 5"):
        L.cycle_bounds(5)


def test_branch_number_is_checked():
    L = loops.analyse(_jenkins_record())
    # 5 periods from rest: 9 reversals, 8 branches; the last one ends at the last reversal
    assert L.branches == 8 and L.branch(7)[0][-1] == L.record.t[L.reversal_index[-1]]
    # before: 2.5 raised IndexError from numpy, 8 an IndexError, -1 silently gave the last branch
    with pytest.raises(TypeError, match=r"number must be an integer, got 2\.5"):
        L.branch(2.5)
    with pytest.raises(ValueError, match=r"number must be < 8 \(the number of branches, between the 9 reversals\), "
                                         r"got 8"):
        L.branch(8)
    with pytest.raises(ValueError, match=r"number must be an integer >= 0, got -1"):
        L.branch(-1)


def test_steady_mean_and_backbone_points_check_their_arguments():
    L = loops.analyse(_jenkins_record())
    assert L.steady_mean("slip_force") == pytest.approx(F, rel=1e-3)
    # before: AttributeError from getattr
    with pytest.raises(ValueError, match=r"name must be a per-cycle attribute, one of \['energy', .*got 'enrgy'"):
        L.steady_mean("enrgy")
    assert L.backbone_points([0, 1])[0].size == L.backbone_points(slice(0, 2))[0].size
    # before: "'int' object is not iterable", "need at least one array to concatenate"
    with pytest.raises(TypeError, match=r"cycles must be a slice or a sequence of cycle numbers, got 2"):
        L.backbone_points(2)
    with pytest.raises(ValueError, match=r"cycles must select at least one of the 4 cycles, got \[\]"):
        L.backbone_points([])
    with pytest.raises(TypeError, match=r"cycles: each cycle must be an integer, got 1\.5"):
        L.backbone_points([1.5])
    with pytest.raises(ValueError, match=r"cycles: cycle 4 does not exist \(0\.\.3\)"):
        L.backbone_points([4])
    with pytest.raises(TypeError, match=r"source must be a str \(a file name, for messages\), got 3"):
        loops.Record(t=np.zeros(20), T=np.zeros(20), source=3)


def test_reversed_force_sign_is_refused():
    rec = _jenkins_record()
    flipped = loops.Record(t=rec.t, T=-rec.T, source="flipped.csv")
    # the Jenkins loop area is 4 F (A - F/K) = 60 µJ and its stick stiffness K: both come out negative
    with pytest.raises(loops.LoopError, match=r"flipped.csv: force sign reversed: loop energy < 0 \(-6(\.\d+)?e-05 J "
                                              r"per steady cycle\) and stick stiffness < 0 \(-2e\+07 N/m\)\. "
                                              r".*negate the force"):
        loops.analyse(flipped)


def test_plot_returns_axes_with_labels():
    import matplotlib

    matplotlib.use("Agg")
    ax = loops.analyse(_jenkins_record()).plot()
    assert "µm" in ax.get_xlabel() and "(N)" in ax.get_ylabel()
    assert "µm" in _jenkins_record().plot().get_xlabel()


# -- kernels against their pure-Python twins ---------------------------------------------------

walks = st.lists(st.floats(-1.0, 1.0, allow_nan=False), min_size=2, max_size=300)


@settings(max_examples=150, deadline=None)
@given(steps=walks, h=st.floats(0.01, 2.0))
def test_reversals_kernel_matches_twin(steps, h):
    x = np.cumsum(steps)
    idx, kind = loops.find_reversals(x, h)
    ref_idx, ref_kind = _kernels.reversals_reference(x, h)
    assert idx.tolist() == ref_idx and kind.tolist() == ref_kind
    # invariants: kinds alternate; between two reversals x moves by more than h
    assert np.all(np.diff(kind) != 0)
    assert np.all(np.abs(np.diff(x[idx])) > h)


@settings(max_examples=100, deadline=None)
@given(values=st.lists(st.floats(-5, 5, allow_nan=False), min_size=3, max_size=60),
       data=st.data())
def test_window_ends_kernel_matches_twin(values, data):
    x = np.asarray(values)
    n = x.size
    starts = np.array(data.draw(st.lists(st.integers(0, n - 1), min_size=1, max_size=8)), dtype=np.int64)
    stops = np.array([data.draw(st.integers(0, n - 1)) for _ in starts], dtype=np.int64)
    lims = np.array([data.draw(st.floats(0.0, 6.0)) for _ in starts])
    out = np.empty(starts.size, dtype=np.int64)
    _kernels.window_ends(x, starts, stops, lims, out)
    assert out.tolist() == _kernels.window_ends_reference(x, starts, stops, lims)


# -- the real damper data -----------------------------------------------------------------------

@pytest.mark.parametrize("name", ["1Hz20lbtension.json", "1Hz80lbtension.json"])
def test_real_damper_loops(name):
    r = loops.read(DAMPER / name)
    L = loops.analyse(r)
    # about 10 s at 1 Hz with a ramp of amplitude at both ends: 6 full-size cycles, >= 2 steady
    assert L.cycles >= 5 and L.is_steady and L.steady.stop - L.steady.start >= 2
    # its sign convention is ours (T acts along t: positive loop energy and stick stiffness), so the
    # sign check lets it through
    assert np.all(L.energy > 0) and L.summary()["gross_slip"] and L.summary()["stick_stiffness"] > 0
    # independent check: tests/data/arts-friction-damper/README.md gives the mean loop area over the
    # 10 s record (|loop area| per cycle in in*kip, 10 cycles); the whole record's work ∮T dt must match it
    area = {"1Hz20lbtension.json": 1.823, "1Hz80lbtension.json": 4.715}[name] * 0.0254 * 4448.2216152605
    work = float(np.sum(0.5 * (r.T[1:] + r.T[:-1]) * np.diff(r.t)))
    assert work == pytest.approx(10 * area, rel=0.05)
    assert L.energy.sum() < work  # the cycles leave out the start and end
    # slip forces: that README's median force while sliding (|v| > 0.5 max) vs ours (mean over the
    # last 10 % of the stroke of steady branches): two definitions, agree within 12 %
    med = {"1Hz20lbtension.json": (0.945, -0.888), "1Hz80lbtension.json": (2.556, -2.693)}[name]
    s = L.summary()
    assert s["slip_force_positive"] / 4448.2216 == pytest.approx(med[0], rel=0.12)
    assert s["slip_force_negative"] / 4448.2216 == pytest.approx(med[1], rel=0.12)
    raw = np.asarray(json.loads((DAMPER / name).read_text())["data"])
    assert L.reversal_index.max() < raw.shape[0]
