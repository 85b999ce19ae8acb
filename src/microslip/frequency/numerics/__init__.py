"""Numerical machinery with no physics: pseudo-arclength continuation and Newton's method
(:mod:`.continuation`), BLAS threads for small dense problems (:mod:`.blas`), operators and GMRES
(:mod:`.krylov`), one LU factorisation reused over many solves (:mod:`.reuse`)."""
