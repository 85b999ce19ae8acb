"""``examples/bolted_lap_joint.py --quick``: the lap joint's first bending nonlinear mode, as users run it."""

import sys

import numpy as np
import pytest

from _paths import EXAMPLES

pytest.importorskip("skfem")
sys.path.insert(0, str(EXAMPLES))

import bolted_lap_joint  # noqa: E402


def test_the_quick_lap_joint_example(tmp_path):
    out = tmp_path / "joint.png"
    mode = bolted_lap_joint.main(out, quick=True)
    assert out.stat().st_size > 20_000
    lo, hi = bolted_lap_joint.SETTINGS[True][2]
    assert mode.modal_amplitude[0] == pytest.approx(lo, rel=1e-6)
    assert mode.modal_amplitude[-1] == pytest.approx(hi, rel=1e-6)
    # at the smallest amplitude the joint is stuck: the linear prestressed mode's frequency (C = beta K keeps the
    # modes: equal but for the Newton tolerance, measured 1.8e-8) and no energy lost in the contacts
    assert mode.omega[0] == pytest.approx(mode.linear_frequency, rel=1e-7)
    assert abs(mode.contact_damping_ratio[0]) < 1e-6 * mode.damping_ratio[0]
    # the energy balance of the harmonics kept: viscous and contact shares add up to the damping ratio
    assert np.allclose(mode.viscous_damping_ratio + mode.contact_damping_ratio, mode.damping_ratio, rtol=1e-6,
                       atol=0)
    # microslip: the frequency falls and the damping ratio rises several times above the viscous one
    assert mode.omega[-1] < mode.omega[0]
    assert mode.damping_ratio.max() > 5 * mode.damping_ratio[0]
