"""File writing that never leaves a half-written file behind (private)."""

from __future__ import annotations

import os
import re
import stat
import tempfile
from pathlib import Path

#: the end of the name of :func:`atomic_write`'s temporary files, ``.NAME.RANDOM.tmp`` beside ``NAME``
TEMPORARY_SUFFIX = ".tmp"


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
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=TEMPORARY_SUFFIX, dir=path.parent)
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


def temporary_names(names: str) -> re.Pattern:
    """The temporary files :func:`atomic_write` makes for the files whose names match the regular expression ``names``.

    ``.NAME.RANDOM.tmp`` (``RANDOM``: :mod:`tempfile`'s letters, digits and
    underscores): what a write interrupted by a kill leaves beside ``NAME``.
    """
    return re.compile(rf"\.(?:{names})\.[a-z0-9_]+{re.escape(TEMPORARY_SUFFIX)}")


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


#: characters a CSV name or text cell must not hold: the separator, the quote, the comment mark of
#: ``numpy.genfromtxt`` and line breaks (naive parsers split on them; quoting helps only some parsers)
_CSV_FORBIDDEN = (",", '"', "#", "\n", "\r")


def write_csv(path, columns: dict) -> Path:
    """Write equal-length columns (name -> 1-D sequence) as a plain CSV, atomically.

    The file holds one header row of names and then the data, nothing else
    (no comment lines), so ``csv.reader``, ``numpy.genfromtxt(names=True,
    delimiter=',')`` and ``pandas.read_csv`` read it without options. Floats
    are written with ``repr`` (they read back exactly). Columns shorter
    than the longest are padded with empty cells.

    Raises
    ------
    ValueError
        A name or a text cell holds a comma, a double quote, ``#`` or a line
        break (the column is named).
    """
    import csv
    import io

    import numpy as np

    names = list(columns)
    arrays = [np.asarray(columns[k]).ravel() for k in names]
    for name, a in zip(names, arrays):
        cells = [str(name)] + ([str(v) for v in a] if a.dtype.kind in "USO" else [])
        bad = next((c for c in cells if any(ch in c for ch in _CSV_FORBIDDEN)), None)
        if bad is not None:
            where = "the column name" if bad == str(name) else f"a cell {bad!r} of column"
            raise ValueError(f"write_csv: {where} {str(name)!r} holds one of , \" # or a line break; "
                             "CSV names and text cells must be free of them")
    rows = max((a.size for a in arrays), default=0)
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(names)
    for r in range(rows):
        cells = []
        for a in arrays:
            if r < a.size:
                v = a[r]
                cells.append(repr(float(v)) if isinstance(v, (float, np.floating)) else str(v))
            else:
                cells.append("")
        writer.writerow(cells)
    return atomic_write(path, buf.getvalue())
