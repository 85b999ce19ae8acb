"""Nastran ``DMIG`` matrices from punch or bulk-data files, parsed by pyNastran (private).

A ``DMIG`` entry names a matrix (``KAAX``, ``MAAX``, ...), its form ``IFO`` (1 square, 6 symmetric:
one triangle or the whole square) and its type ``TIN`` (1, 2 real; 3, 4 complex), then one column
``(GJ, CJ)`` per entry with its terms ``(GI, CI, value)``. Rows are labelled by grid and component
(1..6); the matrix's rows are its DOFs sorted by grid then component. pyNastran parses the cards
(small, large and free fields, continuations); every matrix is then checked here: real, square or
symmetric, components 1..6 (a scalar point's component 0 is refused), no term written twice.
"""

from __future__ import annotations

import contextlib
import io
import logging
from pathlib import Path

import numpy as np

from ._errors import FileFormatError
from ._labelled import Labelled, from_entries, key, one_triangle_or_square
from ._optional import require

#: IFO values read: square and symmetric
_FORMS = {1: "square", 6: "symmetric"}


def _parse(path: Path):
    """pyNastran's model of the file (a punch file, or a deck with ``BEGIN BULK``)."""
    bdf = require("pyNastran.bdf.bdf", "Reading Nastran DMIG matrices")
    raw = path.read_bytes()
    try:
        text = raw.decode("latin-1")
    except UnicodeDecodeError:  # pragma: no cover - latin-1 decodes every byte
        raise FileFormatError(path, "not a text file") from None
    if "\0" in text:
        raise FileFormatError(path, f"byte {text.index(chr(0))} is a NUL: not a Nastran text file",
                              text.count("\n", 0, text.index("\0")) + 1)
    if text and not text.endswith("\n"):  # a cut inside the last line could leave a shorter number, still a number
        raise FileFormatError(path, "the file does not end with a line break: it may be truncated (if its last line "
                                    "is complete, end it with a line break)", text.count("\n") + 1)
    punch = "BEGIN BULK" not in text.upper()
    log = logging.getLogger("microslip.fe.dmig")
    log.addHandler(logging.NullHandler())
    log.propagate = False
    model = bdf.BDF(debug=None, log=log)
    try:
        with contextlib.redirect_stdout(io.StringIO()):  # pyNastran prints some complaints instead of raising
            model.read_bdf(str(path), xref=False, punch=punch, validate=True)
    except (FileNotFoundError, PermissionError, ImportError, MemoryError):
        raise
    except Exception as err:  # the parser's own errors: a damaged card
        first = str(err).strip().split("\n")
        raise FileFormatError(path, f"not a readable Nastran bulk-data file ({type(err).__name__}: "
                                    f"{' '.join(first)[:300]})") from None
    return model, text


def _line(text: str, name: str, grid: int | None = None) -> int | None:
    """The first line of a DMIG entry of matrix ``name`` (and of column ``grid``), for a message."""
    for no, line in enumerate(io.StringIO(text), start=1):
        fields = line.replace(",", " ").split()
        if len(fields) >= 2 and fields[0].upper().rstrip("*") == "DMIG" and fields[1].upper() == name.upper():
            if grid is None or (len(fields) > 2 and fields[2] == str(grid)):
                return no
    return None


def read(path: Path, wanted: list[str]) -> dict:
    """``{name: Labelled}`` for the ``wanted`` DMIG matrices, or a MissingVariable through ``pick``.

    Returns
    -------
    dict
        ``{"held": [...names...], name: Labelled, ...}``: the names the file holds, and those found.
    """
    model, text = _parse(path)
    held = dict(model.dmig)
    out = {"held": sorted(held)}
    for name in wanted:
        if name in held:
            out[name] = _matrix(path, text, name, held[name])
    return out


def _matrix(path: Path, text: str, name: str, card) -> Labelled:
    where = f"DMIG {name!r}"
    line = _line(text, name)
    form = int(card.matrix_form)
    if form not in _FORMS:
        raise FileFormatError(path, f"{where}: form IFO = {form} is not read (1 square or 6 symmetric; 2 and 9 are "
                                    f"rectangular)", line)
    if int(card.tin) not in (1, 2) or getattr(card, "is_complex", False):
        raise FileFormatError(path, f"{where}: type TIN = {card.tin} is complex; expected a real matrix (TIN 1 or 2)",
                              line)
    gi, gj = np.asarray(card.GCi, dtype=np.int64).reshape(-1, 2), np.asarray(card.GCj, dtype=np.int64).reshape(-1, 2)
    values = np.asarray(card.Real, dtype=np.float64).ravel()
    if not (gi.shape[0] == gj.shape[0] == values.size) or values.size == 0:
        raise FileFormatError(path, f"{where}: {gi.shape[0]} rows, {gj.shape[0]} columns and {values.size} values "
                                    f"(they must agree, at least one term)", line)
    for label, g in (("row", gi), ("column", gj)):
        bad = ~((g[:, 1] >= 1) & (g[:, 1] <= 6) & (g[:, 0] >= 0) & (g[:, 0] <= 2 ** 53))
        if bad.any():
            k = int(np.flatnonzero(bad)[0])
            raise FileFormatError(path, f"{where}: {label} (grid {g[k, 0]}, component {g[k, 1]}) of column (grid "
                                        f"{gj[k, 0]}, component {gj[k, 1]}): components 1..6 of grids only (a scalar "
                                        f"point's component 0 is not a displacement)", _line(text, name, int(gj[k, 0])))
    if not np.isfinite(values).all():
        k = int(np.flatnonzero(~np.isfinite(values))[0])
        raise FileFormatError(path, f"{where}: the value at row (grid {gi[k, 0]}, component {gi[k, 1]}), column "
                                    f"(grid {gj[k, 0]}, component {gj[k, 1]}) is {values[k]!r}",
                              _line(text, name, int(gj[k, 0])))
    rows, cols = key(gi[:, 0], gi[:, 1] - 1), key(gj[:, 0], gj[:, 1] - 1)

    def entry(k):
        return (f"{where}: row (grid {gi[k, 0]}, component {gi[k, 1]}) of column (grid {gj[k, 0]}, component "
                f"{gj[k, 1]})", _line(text, name, int(gj[k, 0])))

    if form == 6:
        rows, cols, values = one_triangle_or_square(path, rows, cols, values, entry, "term")
    else:
        _, first, counts = np.unique(np.stack([rows, cols], 1), axis=0, return_index=True, return_counts=True)
        if (counts > 1).any():
            k = int(np.setdiff1d(np.arange(rows.size), first)[0])
            what, no = entry(k)
            raise FileFormatError(path, f"{what}: this term is stored twice", no)
    if form == 1 and set(rows.tolist()) != set(cols.tolist()):
        raise FileFormatError(path, f"{where}: a square matrix (IFO = 1) whose rows and columns name different DOFs",
                              line)
    return from_entries(rows, cols, values)
