"""The largest matrices the readers accept, checked before anything is allocated (private).

A damaged size field (a flipped bit, a truncated header) must be refused by name, not turned
into an allocation of terabytes.
"""

from ..common._checks import MAX_SIZE

#: the most rows or columns of a matrix (the package's limit on sizes, 1e7)
MAX_ROWS = MAX_SIZE

#: the most entries of a dense matrix or of one stored array: 1e8 (800 MB of float64)
MAX_ENTRIES = 10 ** 8
