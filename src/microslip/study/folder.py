"""A study's results folder shared by its runs: what a run found there that a finished run does not leave."""

from __future__ import annotations

import warnings


class StudyFolderWarning(UserWarning):
    """The results folder was not as a finished run leaves it: a case file not trusted."""


def notice(message: str) -> None:
    """Say ``message`` about the results folder (a :class:`StudyFolderWarning`, shown on standard error)."""
    warnings.warn(message, StudyFolderWarning, stacklevel=3)
