"""A study's results folder shared by its runs: one run at a time, and what an interrupted run left behind.

``OUT/.sweep.lock`` is held (``flock``) by the run writing into ``OUT`` and
holds its process id, host and start time; a second run on the same folder is
refused with them. The kernel releases the lock when its process ends, so a
lock file found still holding a record when the lock is taken was left by a
run that was killed: its record names it, and what it was writing (temporary
files of atomic writes, a Zarr store half written or moved aside) is removed.
"""

from __future__ import annotations

import datetime
import json
import os
import re
import shutil
import socket
import time
import warnings
from pathlib import Path

from ..common._io import temporary_names
from ..common.errors import FolderInUseError, StudyFolderWarning

#: the lock file in the results folder
LOCK = ".sweep.lock"
#: seconds after which a temporary file of the patterns below is a leftover even without a lock to prove whose
#: it is (another program writing it would have touched it since)
LEFTOVER_AGE = 3600.0

#: what a run killed while writing leaves, by folder (relative to OUT): temporary files of atomic writes (a case
#: file, the summary, the report and its figures), write_curves's temporary folder and the old store it moves aside
LEFTOVERS = {
    "cases": (temporary_names(r"[0-9a-f]{16}\.npz"),),
    ".": (temporary_names(r"summary\.csv|summary\.parquet|report\.html|report\.md|[A-Za-z0-9_]+\.png"),
          re.compile(r"\.curves\.[a-z0-9_]+\.tmp"), re.compile(r"\.curves\.zarr\.old\.\d+")),
}


def notice(message: str) -> None:
    """Say ``message`` about the results folder (a :class:`StudyFolderWarning`, shown on standard error)."""
    warnings.warn(message, StudyFolderWarning, stacklevel=3)


class FolderLock:
    """``OUT/.sweep.lock``, held while a run reads and writes ``OUT`` (a context manager).

    Attributes
    ----------
    previous : dict or None
        The record of a run that held the lock and ended without releasing it
        (killed): ``pid``, ``host``, ``started``.
    held : bool
        False where the file system refuses locks (the run goes on unguarded).

    Raises
    ------
    FolderInUseError
        Another run holds the lock (its pid, host and start time are named).
    """

    def __init__(self, folder):
        self.folder = Path(folder)
        self.path = self.folder / LOCK
        self.previous = None
        self.held = False
        self._fd = None

    def __enter__(self) -> FolderLock:
        try:
            import fcntl
        except ImportError:  # not POSIX
            notice(f"this system has no file locks: a second run on {str(self.folder)!r} would not be kept out")
            return self
        while True:
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o666)
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                holder = _record(fd)
                os.close(fd)
                raise FolderInUseError(f"{str(self.folder)!r} is in use by another microslip sweep "
                                       f"({describe(holder)}): wait for it to finish, or give another results "
                                       "folder") from None
            except OSError as exc:
                os.close(fd)
                notice(f"the file system of {str(self.folder)!r} refuses locks ({exc.strerror}): a second run on it "
                       "would not be kept out")
                return self
            try:  # the run that held it may have removed the file meanwhile: lock the one now there
                same = os.path.samestat(os.fstat(fd), os.stat(self.path))
            except FileNotFoundError:
                same = False
            if same:
                break
            os.close(fd)
        self._fd, self.held = fd, True
        self.previous = _record(fd)
        if self.previous is not None:
            notice(f"the run that last wrote into {str(self.folder)!r} ({describe(self.previous)}) ended without "
                   "releasing its lock (it was killed): lock taken over")
        record = {"pid": os.getpid(), "host": socket.gethostname(),
                  "started": datetime.datetime.now().astimezone().isoformat(timespec="seconds")}
        # written in place, not renamed over: the lock is this file's inode
        os.ftruncate(fd, 0)
        os.pwrite(fd, json.dumps(record).encode(), 0)
        return self

    def __exit__(self, *exc) -> None:
        if self._fd is not None:
            try:
                os.unlink(self.path)  # before the lock goes: a run waiting on this inode then sees it gone
            finally:
                os.close(self._fd)
                self._fd = None


def _record(fd: int) -> dict | None:
    """The record in an open lock file: a dict, ``{}`` when it is not one, None when the file is empty."""
    try:
        text = os.pread(fd, 4096, 0)
    except OSError:
        return {}
    if not text.strip():
        return None
    try:
        record = json.loads(text)
    except ValueError:
        return {}
    return record if isinstance(record, dict) else {}


def describe(record: dict | None) -> str:
    """A lock's record as ``pid 123 on host h, started 2025-...``."""
    if not record:
        return "which has not written its process id yet" if record is None else "whose lock file cannot be read"
    return (f"pid {record.get('pid', '?')} on host {record.get('host', '?')}, started "
            f"{record.get('started', 'at an unknown time')}")


def leftovers(out) -> list[Path]:
    """Every entry of ``out`` that a run killed while writing may have left (:data:`LEFTOVERS`)."""
    found = []
    for sub, patterns in LEFTOVERS.items():
        folder = Path(out) / sub
        try:
            names = sorted(os.listdir(folder))
        except (FileNotFoundError, NotADirectoryError):
            continue
        found += [folder / n for n in names if any(p.fullmatch(n) for p in patterns)]
    return found


def remove_leftovers(out, *, owner_gone: bool) -> tuple[list[str], list[str]]:
    """Remove what an interrupted run left in ``out``; the entries removed and those left alone, named from ``out``.

    To be called holding the folder's lock (no other run writes into it).
    An entry is removed when the run that held the lock before was killed
    (``owner_gone``: the lock file still held its record, so everything of
    these patterns is that run's or an earlier one's), else when nothing has
    touched it for :data:`LEFTOVER_AGE` seconds. Folders are named with a
    trailing ``/``.
    """
    removed, kept = [], []
    now = time.time()
    for path in leftovers(out):
        folder = path.is_dir() and not path.is_symlink()
        name = path.relative_to(out).as_posix() + ("/" if folder else "")
        if not owner_gone and now - _newest(path) < LEFTOVER_AGE:
            kept.append(name)
            continue
        try:
            if folder:
                shutil.rmtree(path)
            else:
                path.unlink()
        except FileNotFoundError:
            continue
        except OSError:
            kept.append(name)
            continue
        removed.append(name)
    return removed, kept


def _newest(path: Path) -> float:
    """The latest modification time in ``path`` (a file, or a folder and everything in it)."""
    try:
        newest = path.lstat().st_mtime
    except FileNotFoundError:
        return 0.0
    if path.is_dir() and not path.is_symlink():
        for root, dirs, files in os.walk(path):
            for name in dirs + files:
                try:
                    newest = max(newest, os.lstat(os.path.join(root, name)).st_mtime)
                except FileNotFoundError:
                    pass
    return newest
