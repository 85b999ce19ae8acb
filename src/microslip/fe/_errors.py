"""The error of a damaged or inconsistent file (private; exported as :class:`microslip.fe.FileFormatError`)."""

from __future__ import annotations

from pathlib import Path


class FileFormatError(ValueError):
    """A file that cannot be what it claims to be: truncated, damaged or inconsistent.

    The message names the file and, for a text format, the line:
    ``"blade.op4: line 12: ..."``.

    Attributes
    ----------
    path : Path
        The file.
    line : int or None
        The line (from 1) of a text file, None when the format has no lines.
    """

    __module__ = "microslip.fe"

    def __init__(self, path, what: str, line: int | None = None):
        self.path, self.line, self.what = Path(path), line, what
        super().__init__(f"{path}: line {line}: {what}" if line is not None else f"{path}: {what}")

    def __reduce__(self):  # pickled whole (a worker's error reaches the caller intact)
        return type(self), (self.path, self.what, self.line)
