"""Design studies: parameter sweeps, random samples and mistuning Monte Carlo of a configuration, on Dask.

A study file names a base ``microslip frf`` configuration and the values to vary
by their key paths (:mod:`~microslip.study.spec`); :func:`sweep` solves every
case on a Dask cluster (local worker processes by default, or a running
scheduler) and writes a summary table, every curve in a Zarr store and a
report (:mod:`~microslip.study.store`, :mod:`~microslip.study.report`).
Needs the ``sweep`` extra: ``pip install microslip[sweep]``.
"""

from .engine import sweep
from .result import SweepResult
from .spec import Case, Mistuning, Study, load_study

__all__ = ["Case", "Mistuning", "Study", "SweepResult", "load_study", "sweep"]
