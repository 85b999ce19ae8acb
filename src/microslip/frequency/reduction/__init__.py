"""Reductions of the linear structure onto the DOFs the contacts use: exact condensation
(:mod:`.condensation`), modes plus residual flexibility (:mod:`.modal`), a sector per nodal
diameter (:mod:`.cyclic_modal`), Craig-Bampton models (:mod:`.craig_bampton`) and the choice
among them (:mod:`.choice`)."""
