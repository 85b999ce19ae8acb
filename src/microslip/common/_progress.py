"""Progress shown on standard error for anything that takes more than a moment (private)."""

from __future__ import annotations

import sys
import time


class Progress:
    """Print ``[k/total] label ... (elapsed)`` lines on stderr.

    Parameters
    ----------
    total : int
        Number of steps announced.
    enabled : bool
        False silences it (``--quiet``).
    stream : file, optional
        Where to write (default ``sys.stderr``).
    """

    def __init__(self, total: int, *, enabled: bool = True, stream=None):
        self.total = total
        self.enabled = enabled
        self.stream = stream if stream is not None else sys.stderr
        self.count = 0
        self.start = time.perf_counter()

    def step(self, label: str) -> None:
        """Announce the next step."""
        self.count += 1
        now = time.perf_counter()
        self._noted = now  # a note comes ``every`` seconds after the last line, whichever it was
        if self.enabled:
            print(f"[{self.count}/{self.total}] {label} ({now - self.start:.1f} s)", file=self.stream, flush=True)

    def note(self, label: str, *, every: float = 5.0) -> None:
        """Within a long step: print ``label`` indented, at most once per ``every`` seconds (s)."""
        now = time.perf_counter()
        if self.enabled and now - getattr(self, "_noted", self.start) >= every:
            self._noted = now
            print(f"      {label} ({now - self.start:.1f} s)", file=self.stream, flush=True)

    def done(self, label: str = "done") -> float:
        """Announce the end; returns the elapsed time (s)."""
        elapsed = time.perf_counter() - self.start
        if self.enabled:
            print(f"{label} in {elapsed:.1f} s", file=self.stream, flush=True)
        return elapsed


def duration(seconds: float) -> str:
    """A time span as people say it: ``"40 s"``, ``"12 min"``, ``"3.5 h"``."""
    if seconds < 90:
        return f"{seconds:.0f} s"
    if seconds < 5400:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"


class TimeLeft:
    """The time left of ``total`` tasks run ``workers`` at a time, from the tasks finished and those in flight.

    A task's duration is estimated as the larger of the median of the
    finished tasks' durations and their time on test per finished task: the
    finished tasks' durations plus the time the tasks in flight have run so
    far, over the number finished (a task in flight that runs long raises the
    estimate before it ends). Tasks start as workers free up; the time left is
    the work left over the workers, or the longest task in flight if longer.
    Nothing is estimated before ``least`` tasks have finished: a first task
    that happens to be fast says little about the others.

    Parameters
    ----------
    total : int
        Tasks to run.
    workers : int
        Tasks run at a time.
    least : int, default 3
        Finished tasks an estimate needs (all of them when fewer).
    clock : callable, optional
        Time in s (default :func:`time.perf_counter`); the tasks start at its
        value when the object is made.
    """

    def __init__(self, total: int, workers: int, *, least: int = 3, clock=time.perf_counter):
        self.total = int(total)
        self.workers = max(1, int(workers))
        self.least = max(1, min(int(least), self.total))
        self.clock = clock
        self.durations: list[float] = []
        now = clock()
        self._starts = [now] * min(self.workers, self.total)  # of the tasks in flight
        self._started = len(self._starts)

    @property
    def finished_count(self) -> int:
        """Tasks finished so far."""
        return len(self.durations)

    @property
    def running(self) -> int:
        """Tasks in flight."""
        return len(self._starts)

    def finished(self, seconds: float) -> None:
        """A task ended after ``seconds`` of work; the next one waiting starts."""
        now = self.clock()
        seconds = max(float(seconds), 0.0)
        self.durations.append(seconds)
        if self._starts:  # the task in flight whose start best matches its duration
            k = min(range(len(self._starts)), key=lambda i: abs(now - self._starts[i] - seconds))
            self._starts.pop(k)
        if self._started < self.total:
            self._starts.append(now)
            self._started += 1

    def seconds(self) -> float | None:
        """The time left (s); None before :attr:`least` tasks have finished."""
        import statistics

        n = len(self.durations)
        if n >= self.total:
            return 0.0
        if n < self.least:
            return None
        ages = [self.clock() - s for s in self._starts]
        per_task = max(statistics.median(self.durations), (sum(self.durations) + sum(ages)) / n)
        waiting = self.total - n - len(ages)
        remaining = [max(per_task - a, 0.0) for a in ages]
        return max((per_task * waiting + sum(remaining)) / self.workers, max(remaining, default=0.0))

    def text(self, noun: str = "case") -> str:
        """``"about 3 min left (estimate after 4 cases)"``, or when there is no estimate yet, what it waits for."""
        left = self.seconds()
        n = len(self.durations)
        if left is None:
            return f"time left estimated after {self.least} {noun}{'s' if self.least != 1 else ''}"
        if n >= self.total:
            return "none left"
        return f"about {duration(left)} left (estimate after {n} {noun}{'s' if n != 1 else ''})"
