"""Harmonic balance equations: on every DOF (:mod:`.hbm`), on the retained DOFs (:mod:`.reduced`),
for a cyclic sector (:mod:`.cyclic_balance`), on every DOF of an interface-dominated structure with
the Jacobian in parts (:mod:`.interface`), with the damping of a nonlinear mode (:mod:`.epmc`),
all built by one factory (:func:`.build.build_equations`)."""
