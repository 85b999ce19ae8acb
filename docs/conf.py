"""Sphinx configuration of microslip's documentation.

Build (warnings are errors): ``python -m sphinx -W --keep-going -b html docs docs/_build/html``.
The gallery runs every script of ``examples/`` at a small size; ``MICROSLIP_GALLERY=full`` runs them at
the sizes their own command lines default to.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT / "src"))  # the tree being documented, ahead of any installed copy
sys.path.insert(0, str(HERE / "_ext"))
os.environ.setdefault("MPLBACKEND", "Agg")

import microslip  # noqa: E402

#: The packages whose ``__all__`` the API reference documents, in the order of its pages: the one list,
#: ``microslip.common.surface.DOCUMENTED_PACKAGES``. A name exported by several of them is documented once,
#: under the first; tests/test_docs.py checks the reference against the union of their ``__all__``.
from microslip.common.surface import DOCUMENTED_PACKAGES  # noqa: E402

DOCUMENTED = list(DOCUMENTED_PACKAGES)

# The configuration-file reference is rendered from the schema the readers check files against, at every build.
from microslip.config import reference_markdown  # noqa: E402

(HERE / "configuration.md").write_text(reference_markdown(), encoding="utf-8")

project = "microslip"
author = "the microslip developers"
copyright = "2026, the microslip developers"
version = release = microslip.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "microslip_docs",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "README.md", "auto_examples/*.ipynb", "auto_examples/*.py",
                    "auto_examples/*.zip", "auto_examples/*.md5", "auto_examples/*.json"]
templates_path = ["_templates"]
myst_enable_extensions = ["dollarmath", "colon_fence"]
myst_heading_anchors = 3

html_theme = "furo"
html_title = f"microslip {release}"
html_static_path: list = []

# API reference: autosummary writes one page per public name (api/generated/), numpydoc renders the docstrings
autosummary_generate = True
autodoc_default_options = {"members": True, "member-order": "bysource"}
autodoc_typehints = "none"  # the numpydoc sections carry the types and units
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_validation_checks: set = set()

sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples"),
    "gallery_dirs": "auto_examples",
    "filename_pattern": r".*\.py$",  # every example runs: the gallery shows what it produces
    "reset_argv": "microslip_docs.gallery_argv",
    "image_scrapers": ("matplotlib", "microslip_docs.scrape_written_figures"),
    "within_subsection_order": "FileNameSortKey",
    "download_all_examples": False,
    "remove_config_comments": True,
    "show_memory": False,
    "abort_on_example_error": True,
}

microslip_documented = DOCUMENTED  # read by the _ext/microslip_docs extension, which writes the api/ pages
