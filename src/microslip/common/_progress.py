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
