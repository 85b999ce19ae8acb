"""Running a study's cases on Dask: a local cluster of worker processes, or an existing scheduler.

The study (base configuration, the files it reads: matrices, contact models)
is scattered to every worker once; each case then travels as its few values.
Finished cases are written as they arrive (:mod:`~microslip.study.store`), so
an interrupted run loses only the cases in flight.
"""

from __future__ import annotations

import contextlib
import logging
import os
import sys
import time
from pathlib import Path

from ..common import _checks
from ..common._optional import require
from ..common._progress import TimeLeft
from .folder import LEFTOVER_AGE, FolderLock, notice, remove_leftovers
from .result import SweepResult
from .solve import solve_case
from .spec import Case, Study, load_study
from .store import case_file, read_case, save_case

#: environment of each local worker process: one thread for BLAS and numba (one process per core)
WORKER_ENV = {"OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1",
              "NUMBA_NUM_THREADS": "1", "MPLBACKEND": "Agg"}
#: Dask settings of a local cluster: the workers' periodic chores (a statistical profiler sampling the solving
#: thread every 10 ms, memory and system monitors, the event loop's tick) compete with the solve for the
#: interpreter and made a case measurably slower on a worker than in a plain loop
LOCAL_CONFIG = {"distributed.worker.profile.enabled": False, "distributed.worker.memory.monitor-interval": "10s",
                "distributed.admin.system-monitor.interval": "10s", "distributed.admin.tick.interval": "5s"}
#: seconds to wait for an existing scheduler to answer
CONNECT_TIMEOUT = 10.0


def sweep(study, client=None, *, out="microslip-sweep", workers: int | None = None, scheduler: str | None = None,
          progress: bool = False, retry_failed: bool = False, report: bool = True) -> SweepResult:
    """Solve every case of a design study on Dask and write its results.

    Parameters
    ----------
    study : Study or str or Path
        The study, or its file (:func:`~microslip.study.load_study`).
    client : dask.distributed.Client, optional
        Where to run; default: a local cluster of ``workers`` processes, or
        ``scheduler``'s cluster.
    out : str or Path, default "microslip-sweep"
        Results folder: ``cases/`` (one file per finished case),
        ``summary.csv``, ``summary.parquet``, ``curves.zarr`` and, with
        ``report``, ``report.html`` and its figures. One run at a time
        (:class:`~microslip.study.folder.FolderLock`): a case file that
        cannot be read, or holds values not those of its key, is solved again
        and what a killed run left is removed, each said in a
        :class:`~microslip.study.folder.StudyFolderWarning`.
    workers : int, optional
        Worker processes of the local cluster (default: one per core), each
        with one thread for BLAS and numba.
    scheduler : str, optional
        Address of a running Dask scheduler, ``"tcp://HOST:PORT"``.
    progress : bool, default False
        Report cases done, running and failed, and the time left, on standard
        error: estimated once 3 cases have finished, from their durations and
        the time the cases in flight have run (:class:`~microslip.common._progress.TimeLeft`),
        and repeated every :data:`REFRESH` seconds without a case finishing.
    retry_failed : bool, default False
        Solve again the cases recorded as failed by an earlier run (finished
        cases are never solved again).
    report : bool, default True
        Write the plots and the HTML report.

    Returns
    -------
    SweepResult
        Every case's summary row and curves; ``computed`` cases were solved by
        this run, the others read back from ``out``.

    Raises
    ------
    ConfigError
        An invalid study (before any case is solved).
    ConnectionError
        ``scheduler`` does not answer within :data:`CONNECT_TIMEOUT` seconds.
    FolderInUseError
        Another run is writing into ``out`` (its process id, host and start
        time are named); nothing is solved.
    """
    from ..common.report import plural
    from .report import write_report
    from .store import summary_rows, write_curves, write_summary

    if not isinstance(study, (Study, str, os.PathLike)):
        raise TypeError(f"study must be a Study or the study file's name (str or path), got {type(study).__name__}")
    study = study if isinstance(study, Study) else load_study(study)
    if client is not None and not (hasattr(client, "submit") and hasattr(client, "scatter")):
        raise TypeError(f"client must be a dask.distributed.Client, got {type(client).__name__}")
    if client is not None and (workers is not None or scheduler is not None):
        raise ValueError("give either client or workers/scheduler, not both (the client already names its cluster)")
    if workers is not None:
        workers = _checks.positive_int("workers", workers)
    if scheduler is not None:
        scheduler = _checks.text("scheduler", scheduler)
    progress = _checks.flag("progress", progress)
    retry_failed = _checks.flag("retry_failed", retry_failed)
    report = _checks.flag("report", report)
    if not isinstance(out, (str, os.PathLike)) or not str(out).strip():
        raise TypeError(f"out must be a folder name (str or path), got {out!r}")
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise ValueError(f"out: {str(out)!r} is a file; give a folder for the results")
    cases = study.cases()
    require("dask.distributed", "a design study", "sweep")
    cfg = study.configuration(Case({}, ""))  # the base configuration's output DOFs
    names = [cfg.dof_names[d] for d in cfg.plot_dofs]
    start = time.perf_counter()
    with _client(client, workers, scheduler) as running:
        out.mkdir(parents=True, exist_ok=True)
        with FolderLock(out) as lock:
            _clean(out, lock)
            found = _finished(out, study, cases, len(names))
            todo = [c for c in cases if found[c.key] is None or (retry_failed and found[c.key]["error"])]
            if progress:
                threads = _threads(running)
                print(f"{plural(len(cases), 'case')}: {len(cases) - len(todo)} finished by an earlier run, "
                      f"{len(todo)} to solve on {plural(threads, 'worker')}", file=sys.stderr, flush=True)
            if todo:
                for case, outcome in _solve(running, study, todo, progress):
                    found[case.key] = save_case(out, case, outcome)
            outcomes = [found[c.key] for c in cases]
            rows = summary_rows(study, cases, outcomes)
            write_summary(out, rows)
            write_curves(out, study, cases, outcomes, names)
            result = SweepResult(study, cases, outcomes, rows, names, out, computed=len(todo),
                                 elapsed=time.perf_counter() - start)
            if report:
                write_report(result)
    return result


def _clean(out: Path, lock: FolderLock) -> None:
    """Remove what an interrupted run left in ``out`` (holding its lock), and say so."""
    removed, kept = remove_leftovers(out, owner_gone=lock.previous is not None)
    if removed:
        notice(f"removed what an interrupted run left in {str(out)!r}: {_names(removed)}")
    if kept:
        notice(f"left alone in {str(out)!r}, written less than {LEFTOVER_AGE / 3600:g} h ago by a run not known to "
               f"have ended: {_names(kept)}")


def _names(names: list, most: int = 10) -> str:
    return ", ".join(names[:most]) + (f" and {len(names) - most} more" if len(names) > most else "")


def _finished(out: Path, study: Study, cases: list[Case], dofs: int) -> dict:
    """Each case's stored outcome by key (None: to solve); a case file that cannot be trusted is named, and why."""
    found = {}
    for case in cases:
        found[case.key], problem = read_case(out, case, study.solve, dofs)
        if problem:
            notice(f"{case_file(out, case)} {problem}: its case ({case.label}) is solved again")
    return found


#: seconds without a case finishing after which the progress line is repeated (its estimate counts the cases in
#: flight, so a case running long shows)
REFRESH = 60.0
#: seconds between looks for finished cases
POLL = 0.1


def _solve(client, study: Study, todo: list[Case], progress: bool):
    """``(case, outcome)`` as each case finishes; a worker lost while solving one is that case's error."""
    from dask.distributed import as_completed

    shared = client.scatter(study, broadcast=True, hash=False)  # sent once to every worker
    futures = {client.submit(solve_case, shared, case, key=f"microslip-case-{case.key}-{time.time_ns()}",
                             pure=False): case for case in todo}
    clock = TimeLeft(len(todo), _threads(client))
    failed = 0
    pending = as_completed(futures)
    said = time.perf_counter()
    try:
        while pending.count():
            batch = pending.next_batch(block=False)
            if not batch:
                time.sleep(POLL)
                if progress and time.perf_counter() - said >= REFRESH:
                    _report_progress(clock, failed)
                    said = time.perf_counter()
                continue
            for future in batch:
                case = futures[future]
                try:
                    outcome = future.result()
                except Exception as exc:  # noqa: BLE001 - a lost worker: the case failed, the others go on
                    outcome = {"row": {}, "curves": {}, "error": f"{type(exc).__name__}: {exc}", "warnings": "",
                               "time": 0.0}
                clock.finished(outcome["time"])
                failed += bool(outcome["error"])
                if progress:
                    _report_progress(clock, failed, case, outcome)
                    said = time.perf_counter()
                yield case, outcome
    finally:
        for future in futures:
            future.cancel()


def _report_progress(clock: TimeLeft, failed: int, case=None, outcome=None) -> None:
    """``[done/total] done, running, failed, time left``, and the case just finished with its time or error."""
    line = (f"[{clock.finished_count}/{clock.total}] done, {clock.running} running, {failed} failed, "
            f"{clock.text()}")
    if case is not None:
        state = "failed: " + outcome["error"] if outcome["error"] else f"{outcome['time']:.1f} s"
        line += f" ({case.label}: {state})"
    print(line, file=sys.stderr, flush=True)


def _threads(client) -> int:
    try:
        return max(1, sum(client.nthreads().values()))
    except Exception:  # noqa: BLE001 - only for the progress line
        return 1


@contextlib.contextmanager
def _client(client, workers, scheduler):
    """The client to run on: the one given, one on ``scheduler``, or a new local cluster's (closed after)."""
    if client is not None:
        yield client
        return
    from dask.distributed import Client

    if scheduler is not None:
        try:
            connected = Client(scheduler, timeout=CONNECT_TIMEOUT)
        except (OSError, TimeoutError, ValueError) as exc:
            raise ConnectionError(f"scheduler: no Dask scheduler answers at {scheduler!r} within "
                                  f"{CONNECT_TIMEOUT:g} s ({type(exc).__name__}: {exc})") from None
        with connected:
            yield connected
        return
    with local_cluster(workers or os.cpu_count() or 1) as cluster, Client(cluster) as local:
        yield local


def local_cluster(workers: int):
    """A ``dask.distributed.LocalCluster`` of ``workers`` processes of one thread each, set up for solving cases."""
    import dask
    from dask.distributed import LocalCluster

    with dask.config.set(LOCAL_CONFIG):
        return LocalCluster(n_workers=_checks.positive_int("workers", workers), threads_per_worker=1, processes=True,
                            dashboard_address=":0", silence_logs=logging.ERROR, env=WORKER_ENV)
