"""The accuracy-sweep section's rows say what was measured, not fixed text."""

import numpy as np
import pytest

from microslip.figures import accuracy_sweep
from microslip.tuning.target import ElementSweep


def _sweep(first_meeting: dict, elements=(2, 4, 8, 11, 16, 32)):
    """A sweep whose spacing ``s`` first meets 2 % / 2 % at ``first_meeting[s]`` (None: never)."""
    Js = np.array(elements)
    energy = {s: np.where(Js >= (J or 10 ** 6), 0.01, 0.05) for s, J in first_meeting.items()}
    force = {s: np.full(Js.size, 0.01) for s in first_meeting}
    return ElementSweep(Js, energy, force, {}, 0.02, 0.02)


@pytest.mark.parametrize("found, notes", [
    ({"force": None, "displacement": 16, "optimal": 8}, ["none up to 32", "", ""]),
    ({"force": 32, "displacement": 11, "optimal": 11}, ["", "", ""]),
    ({"force": None, "displacement": None, "optimal": None}, ["none up to 32"] * 3),
])
def test_rows_follow_the_measured_smallest_j(found, notes):
    rows = accuracy_sweep.error_rows({"sweep": _sweep(found)})
    assert [r[1] for r in rows] == [found["force"], found["displacement"], found["optimal"]]
    assert [r[4] for r in rows] == notes
