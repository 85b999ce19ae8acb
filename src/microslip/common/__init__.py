"""Small helpers shared by every package: input checks (``_checks``), atomic files and CSV
(``_io``), unit-labelled tables (``_table``), units (``units``), the HTML/Markdown report writer
(``report``), progress on standard error (``_progress``), plot colours (``_style``), numerical
inversion (``_numeric``) and binned means (``_binning``).

Nothing here imports from the rest of :mod:`microslip`.
"""
