"""Harmonic balance equations: on every DOF (:mod:`.hbm`), on the retained DOFs (:mod:`.reduced`),
for a cyclic sector (:mod:`.cyclic_balance`), with the damping of a nonlinear mode (:mod:`.epmc`),
all built by one factory (:func:`.build.build_equations`)."""
