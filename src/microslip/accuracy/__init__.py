"""The accuracy of a contact model against an exact reference, on load paths.

* :mod:`microslip.paths` (:mod:`.paths`) -- load paths: constant-load loops, variable-normal-load
  cycles, the paper's Fig. 4 path, paths from arrays, the default family;
* :func:`accuracy` (:mod:`.compare`) -- a model and a reference model along the same paths:
  energy per cycle, peak force, force and normal-force differences, as an
  :class:`AccuracyReport`.
"""

from . import paths
from .compare import AccuracyReport, PathBatch, ReferenceRun, accuracy, reference_run, restriction_mask

__all__ = ["AccuracyReport", "PathBatch", "ReferenceRun", "accuracy", "paths", "reference_run", "restriction_mask"]
