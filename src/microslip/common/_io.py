"""File writing that never leaves a half-written file behind (private)."""

from __future__ import annotations

import os
import stat
import tempfile
from pathlib import Path


def atomic_write(path, data: str | bytes) -> Path:
    """Write ``data`` to ``path`` through a temporary file and a rename.

    The temporary file lives in the destination folder so the final
    ``os.replace`` is atomic; on any error it is removed and ``path`` is
    left as it was. A new file gets the permissions any program would give
    it (``0666`` less the umask); a file replaced keeps its own.
    """
    path = Path(path)
    if path.is_dir():
        raise IsADirectoryError(f"{str(path)!r} is a folder: give the name of a file to write")
    path.parent.mkdir(parents=True, exist_ok=True)
    mode = "wb" if isinstance(data, bytes) else "w"
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        os.chmod(tmp, _file_mode(path))  # mkstemp makes it 0600
        with os.fdopen(fd, mode, **({} if mode == "wb" else {"encoding": "utf-8"})) as fh:
            fh.write(data)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise
    return path


def _file_mode(path: Path) -> int:
    """Permission bits for ``path``: those of the file it replaces, else ``0666`` less the umask."""
    try:
        return stat.S_IMODE(os.stat(path).st_mode)
    except FileNotFoundError:
        return 0o666 & ~_umask()


def _umask() -> int:
    """The process's umask, read without changing it where the system allows (Linux), else set and restored."""
    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError):
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def save_figure(fig, path, **kwargs) -> Path:
    """Save a Matplotlib figure atomically (format from the suffix of ``path``)."""
    import io

    path = Path(path)
    buf = io.BytesIO()
    fig.savefig(buf, format=path.suffix.lstrip(".") or "png", **kwargs)
    return atomic_write(path, buf.getvalue())


def write_csv(path, columns: dict, *, header_comment: str | None = None) -> Path:
    """Write equal-length columns (name -> 1-D sequence) as CSV, atomically.

    Columns shorter than the longest are padded with empty cells.
    """
    import numpy as np

    names = list(columns)
    arrays = [np.asarray(columns[k]).ravel() for k in names]
    rows = max((a.size for a in arrays), default=0)
    lines = []
    if header_comment:
        lines += [f"# {line}" for line in header_comment.splitlines()]
    lines.append(",".join(names))
    for r in range(rows):
        cells = []
        for a in arrays:
            if r < a.size:
                v = a[r]
                cells.append(repr(float(v)) if isinstance(v, (float, np.floating)) else str(v))
            else:
                cells.append("")
        lines.append(",".join(cells))
    return atomic_write(path, "\n".join(lines) + "\n")
