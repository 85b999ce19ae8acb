"""``microslip sweep``: a design study (parameter grid, random samples, mistuning Monte Carlo) on Dask."""

from __future__ import annotations

from ._args import add_output_folder, positive_int


def add_parser(sub) -> None:
    p = sub.add_parser(
        "sweep", help="design study: many forced responses or nonlinear modes of one configuration, on Dask",
        description="Solve a design study: a base configuration of 'microslip frf' (or of 'microslip modes', with "
                    "solve = \"modes\") and the values to vary, named by their key paths (\"damper.mass\", "
                    "\"contact.sphere.preload\", \"excitation.h1\", \"sweep.engine_order\"), as a grid ([vary]), a "
                    "list ([[case]]), random samples with a seed ([random]) and, for a bladed disk sector, a "
                    "Monte Carlo of blade stiffness mistuning solved on the assembled disk ([mistuning]). Format: "
                    "microslip config-reference (its study file section). The study is checked against "
                    "the base configuration before any case is solved. Cases run on Dask: a local cluster of "
                    "--workers processes (one thread each), or a running cluster with --scheduler (e.g. started on "
                    "SLURM with dask-jobqueue; see the README). Writes OUT/cases/ (one file per finished case: a "
                    "rerun solves only the cases not finished yet, and again any whose file is damaged or not "
                    "that case's, naming it; what a killed run left half written is removed, saying so), "
                    "OUT/summary.csv and summary.parquet (one row "
                    "per case: its values, each output DOF's peak amplitude and frequency, the contacts' "
                    "dissipation at the peak and static state, complete, time, error), OUT/curves.zarr (every "
                    "curve; xarray.open_zarr) and OUT/report.html with the plots. A failed case is recorded with "
                    "its error and the others go on. Exit status: 0 when every case is solved and complete, 1 when "
                    "a case failed or stopped early (the rest is written, each failed case's error printed), 2 for an "
                    "invalid study, an unreachable scheduler or a results folder in use by another run (one run at "
                    "a time per folder: OUT/.sweep.lock names it). Needs the sweep extra: pip install "
                    "microslip[sweep].")
    p.add_argument("study", help="study file (TOML)")
    add_output_folder(p, "microslip-sweep", "-o")
    engine = p.add_mutually_exclusive_group()
    engine.add_argument("--workers", type=positive_int, default=None,
                        help="worker processes of the local Dask cluster, one thread each (default: one per core)")
    engine.add_argument("--scheduler", default=None, metavar="tcp://HOST:PORT",
                        help="address of a running Dask scheduler to run the cases on instead of a local cluster")
    p.add_argument("--retry-failed", action="store_true",
                   help="solve again the cases an earlier run recorded as failed (finished cases are never "
                        "solved again)")
    p.set_defaults(func=run)


def run(args) -> int:
    import sys

    from ..common.report import plural
    from ..study import sweep
    from ..study.spec import load_study

    study = load_study(args.study)
    result = sweep(study, out=args.out, workers=args.workers, scheduler=args.scheduler, progress=not args.quiet,
                   retry_failed=args.retry_failed)
    incomplete = sum(1 for r in result.rows if not r.get("complete") and not r.get("error"))
    failed = result.failed
    print(f"{plural(len(result.cases), 'case')} ({result.computed} solved now, {len(failed)} failed, {incomplete} "
          f"incomplete) in {result.elapsed:.1f} s: wrote {result.out / 'summary.csv'}, "
          f"{result.out / 'curves.zarr'} and {result.out / 'report.html'}")
    for case, error in failed:
        print(f"microslip sweep: case {case.key} ({case.label}) failed: {error}", file=sys.stderr)
    if failed and len(failed) == len(result.cases):
        print(f"microslip sweep: every case failed ({len(failed)} of {len(result.cases)}); the summary and the "
              "report list their errors", file=sys.stderr)
    return 1 if failed or incomplete else 0
