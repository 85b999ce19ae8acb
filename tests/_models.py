"""Small test models that more than one test file uses.

The plane contact (:data:`PLANE_CONTACT`): a three-element microslip array (kt = 3e4, 2e4, 1e4 N/m; kn = 2e6 N/m
each; gaps 0, 0.3, 0.6 µm; mu = 0.5) held at a normal approach of 1 µm (:data:`PLANE_APPROACH`), where all three
elements are closed: normal load N = 2 + 1.4 + 0.8 = 4.2 N, slip force mu N = 2.1 N. The excitation
:data:`PLANE_FORCE`, 1.6 N in phase at 30 degrees from x on the contact's plane, makes the contact's motion an
ellipse on a structure whose x and y modes differ (:func:`plane_chain`).
"""

import numpy as np

from microslip import MicroslipModel
from microslip.frequency import Structure

#: the three-element contact (see the module docstring)
PLANE_CONTACT = MicroslipModel(kt=[3e4, 2e4, 1e4], kn=[2e6, 2e6, 2e6], gaps=[0.0, 0.3e-6, 0.6e-6], mu=0.5)
#: m, its normal approach: N = 4.2 N, slip force 2.1 N
PLANE_APPROACH = 1e-6
#: N, the force on the contact's two tangential directions (x, y): 1.6 N in phase, 30 degrees from x
PLANE_FORCE = 1.6 * np.array([np.cos(np.radians(30)), np.sin(np.radians(30))])


def plane_chain(masses: int) -> tuple[Structure, np.ndarray]:
    """``(structure, force)``: a chain of ``masses`` masses of 0.2 kg moving in x and y, the first tied to the
    ground, neighbours joined by springs of 1e5 N/m in x and 1.2e5 N/m in y, damping ``C = 1e-4 K``; the plane
    contact on the last mass's x and y (DOFs ``2 masses - 2``, ``2 masses - 1``; DOF ``2 i`` is mass ``i``'s x);
    ``force`` (N, shape ``(2 masses,)``) is :data:`PLANE_FORCE` on the last mass."""
    n = 2 * masses
    K = np.zeros((n, n))
    for axis, k in ((0, 1e5), (1, 1.2e5)):
        idx = np.arange(axis, n, 2)
        for a, b in zip(idx[:-1], idx[1:]):
            K[np.ix_([a, b], [a, b])] += k * np.array([[1, -1], [-1, 1]])
        K[idx[0], idx[0]] += k
    s = Structure(np.eye(n) * 0.2, 1e-4 * K, K)
    s.add_contact(PLANE_CONTACT, tangential=[{n - 2: 1.0}, {n - 1: 1.0}], approach=PLANE_APPROACH)
    force = np.zeros(n)
    force[n - 2:] = PLANE_FORCE
    return s, force
