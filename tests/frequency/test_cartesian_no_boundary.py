"""A Cartesian-frame sector without boundaries (blades clamped in a rigid disk) keeps its frame when reduced."""

import numpy as np

from microslip import MicroslipModel
from microslip.frequency import CyclicStructure, UnderPlatformDamper, craig_bampton


def test_a_cartesian_sector_without_boundaries_is_reduced_and_takes_a_damper():
    # two nodes (x, y) on springs to ground: no DOF shared with the neighbours
    K = np.kron(np.array([[2e6, -1e6], [-1e6, 2e6]]), np.eye(2))
    s = CyclicStructure(np.eye(4) * 0.1, None, K, sectors=8, left=[], right=[], frame="cartesian",
                        coordinates=np.zeros((2, 0, 3)), nodes=[(0, 1), (2, 3)])
    cb = craig_bampton(s, [0, 1, 2, 3], modes=0)  # the frame's arguments round-trip through lists
    reduced = cb.structure
    assert isinstance(reduced, CyclicStructure) and reduced.frame == "cartesian"
    assert reduced.coordinates.shape == (2, 0, 3)
    d = UnderPlatformDamper(0.005, 2e-8, centrifugal_load=10.0)
    law = MicroslipModel([1e4], [1e6], [0.0], 0.5)
    d.add_interface(law, points=[(1e-3, 0.0), (3e-3, 1e-3)], angle=np.pi / 2 - 0.7, platform={"x": 0, "y": 1})
    d.add_interface(law, points=[(-2e-3, 0.0)], angle=np.pi / 2 + 0.7, platform={"x": reduced.next(2),
                                                                                 "y": reduced.next(3)})
    attached = d.attach(reduced)
    assert attached.ndof == 7 and len(attached.contacts) == 3 and attached.frame == "cartesian"
