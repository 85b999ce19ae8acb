"""Compiled kernels (numba): internal, called only through the checked public functions.

One home for the loops that run per sample and per element: the element's
return mapping and its marches along one direction and on the contact plane
(:mod:`.element`), the AFT with exact Jacobians (:mod:`.aft`,
:mod:`.aft_plane`, the plane's march in time :mod:`.plane_march`), the friction
work per cycle (:mod:`.friction_work`), the dense harmonic balance
(:mod:`.harmonic_balance`), the products of a structure's matrices with every harmonic
(:mod:`.structure_products`) and the time integrators (:mod:`.transient`,
:mod:`.transient_plane`). Each keeps a slow, obviously correct pure-Python twin
that the tests compare it with. Nothing here checks its input: the public
wrappers (:class:`microslip.MicroslipModel`, :mod:`microslip.frequency`) do.
"""
