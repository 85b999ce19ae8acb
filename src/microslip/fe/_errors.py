"""The error of a damaged or inconsistent file (private; defined in :mod:`microslip.common.errors`, exported as
:class:`microslip.fe.FileFormatError` and :class:`microslip.FileFormatError`)."""

from ..common.errors import FileFormatError

__all__ = ["FileFormatError"]
