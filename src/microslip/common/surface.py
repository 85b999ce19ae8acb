"""The public surface: the packages the API reference documents and the names each one exports.

A name is public when it is listed in the ``__all__`` of one of :data:`DOCUMENTED_PACKAGES`; every
other name, wherever it can be imported from, is internal (it may change without notice). Every
public name is a class, a function or a module with its own docstring (``tests/test_public_surface.py``).
The documentation's API reference is generated from :func:`public_names`, so that it covers exactly
these names.

This module only names the packages; it imports them when :func:`public_names` is called (by name,
so :mod:`microslip.common` still imports nothing from the rest of the package).
"""

from __future__ import annotations

import importlib

#: the packages the API reference documents, in the order it shows them: the top level (what most users
#: need), then one package per job. ``microslip.loops`` and ``microslip.paths`` are the import paths
#: users know of ``microslip.measured.loops`` and ``microslip.accuracy.paths``.
DOCUMENTED_PACKAGES = (
    "microslip",
    "microslip.reference",
    "microslip.tuning",
    "microslip.accuracy",
    "microslip.paths",
    "microslip.measured",
    "microslip.loops",
    "microslip.frequency",
    "microslip.fe",
    "microslip.config",
    "microslip.study",
    "microslip.figures",
)


def public_names() -> dict[str, list[str]]:
    """The public names of each documented package.

    Returns
    -------
    dict of str to list of str
        For each of :data:`DOCUMENTED_PACKAGES`, in that order, its ``__all__`` sorted.
    """
    names = {}
    for package in DOCUMENTED_PACKAGES:
        module = importlib.import_module(package)
        names[package] = sorted(module.__all__)
    return names
