"""The parts of microslip's documentation that are generated from the code and the benchmarks' output.

- the API reference: one page per package of ``conf.DOCUMENTED``, one autosummary entry per name of its
  ``__all__`` (a name exported by an earlier package too is listed there as an alias);
- ``{microslip-cli}``: the command line's reference, from the parsers of :mod:`microslip.cli`;
- ``{benchmark-results}``: the tables of ``benchmarks/results/*.json`` (written by
  ``benchmarks/_common.save_results``), so that no figure of the performance page is typed by hand;
- the gallery's command lines (:func:`gallery_argv`) and the scraper that shows the figures an example
  writes into its output folder (:func:`scrape_written_figures`).
"""

from __future__ import annotations

import importlib
import inspect
import json
import os
import shutil
import types
from pathlib import Path

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import nested_parse_with_titles

DOCS = Path(__file__).resolve().parent.parent
ROOT = DOCS.parent
GALLERY_OUTPUT = DOCS / "_build" / "gallery-output"

#: the options each example takes in the gallery beyond ``--out DIR``: a small size (MICROSLIP_GALLERY=full
#: runs every example at its own defaults)
QUICK_OPTIONS = {"bladed_disk": ["--quick"], "fe_blade": ["--dofs", "300"], "blade_sector_3d": ["--quick"],
                 "bolted_lap_joint": ["--quick"], "damper_sector": ["--quick", "--run"]}


# --------------------------------------------------------------------------------------------- API reference

def api_entries(documented: list[str]) -> dict[str, list[tuple[str, str | None]]]:
    """For each package, its ``__all__`` as ``(name, canonical)``: ``canonical`` is None for the name documented
    on this package's page, else the qualified name under which an earlier package documents the same object."""
    # a documented package exported as a name elsewhere (``microslip.loops``) is documented by its own page
    seen: dict[int, str] = {id(importlib.import_module(p)): p for p in documented}
    out = {}
    for package in documented:
        module = importlib.import_module(package)
        rows = []
        for name in module.__all__:
            obj = getattr(module, name)
            keyed = inspect.isclass(obj) or inspect.isroutine(obj) or isinstance(obj, types.ModuleType)
            if keyed and id(obj) in seen:
                rows.append((name, seen[id(obj)]))
                continue
            if keyed:
                seen[id(obj)] = f"{package}.{name}"
            rows.append((name, None))
        out[package] = rows
    return out


def write_api_pages(app, config) -> None:
    """Write ``api/index.rst`` and one ``api/<package>.rst`` per documented package (before Sphinx looks for
    its sources)."""
    documented = config.microslip_documented
    folder = Path(app.srcdir) / "api"
    folder.mkdir(exist_ok=True)
    pages = []
    entries = api_entries(documented)
    current = {f"{package}.{name}" for package, rows in entries.items() for name, canonical in rows if not canonical}
    for stale in (folder / "generated").glob("*.rst"):  # a name no longer public leaves no page behind
        if stale.stem not in current:
            stale.unlink()
    for package, rows in entries.items():
        pages.append(package)
        own = [name for name, canonical in rows if canonical is None]
        aliases = [(name, canonical) for name, canonical in rows if canonical is not None]
        lines = [f"``{package}``", "=" * (len(package) + 4), "",
                 f".. automodule:: {package}", "   :no-members:", "   :no-index:", "",
                 f".. currentmodule:: {package}", ""]
        if own:
            lines += [".. autosummary::", "   :toctree: generated", "   :nosignatures:", ""]
            lines += [f"   {name}" for name in own] + [""]
        if aliases:
            lines += ["Also exported here", "-" * 18, "", ".. list-table::", "   :header-rows: 1", "",
                      "   * - name", "     - documented as"]
            for name, canonical in aliases:
                target = (f":doc:`{canonical} <{canonical}>`" if canonical in documented
                          else f":obj:`{canonical}`")
                lines += [f"   * - ``{package}.{name}``", f"     - {target}"]
            lines.append("")
        _write_if_changed(folder / f"{package}.rst", "\n".join(lines))
    index = ["API reference", "=============", "",
             "Every public name: the ``__all__`` of each package below (``docs/conf.py`` lists them). A name "
             "exported by several packages is documented under the first.", "",
             ".. toctree::", "   :maxdepth: 1", ""] + [f"   {p}" for p in pages] + [""]
    _write_if_changed(folder / "index.rst", "\n".join(index))


def _write_if_changed(path: Path, text: str) -> None:
    """Rewrite ``path`` only when its text changes (an unchanged page is not rebuilt)."""
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


# ---------------------------------------------------------------------------------------------- command line

def subcommands(parser) -> dict:
    """The sub-command parsers of ``parser``, by name, in the order they were added."""
    import argparse

    for action in parser._actions:  # argparse keeps its sub-parsers only there
        if isinstance(action, argparse._SubParsersAction):
            return dict(action.choices)
    return {}


class CommandLine(SphinxDirective):
    """``{microslip-cli}``: a section per sub-command of ``microslip`` with its ``--help``."""

    def run(self):
        from microslip.cli import build_parser

        os.environ["COLUMNS"] = "100"  # the help's width, the same on every machine
        parser = build_parser()
        lines = ["``microslip``", "-" * 13, "", ".. code-block:: text", ""]
        lines += ["   " + line for line in parser.format_help().splitlines()] + [""]
        for name, sub in subcommands(parser).items():
            title = f"``microslip {name}``"
            lines += [title, "-" * len(title), "", ".. code-block:: text", ""]
            lines += ["   " + line for line in sub.format_help().splitlines()] + [""]
        return _parse(self, lines)


def _parse(directive, lines: list[str]) -> list:
    """``lines`` of reStructuredText, section titles included, as the directive's nodes."""
    node = nodes.section()
    node.document = directive.state.document
    nested_parse_with_titles(directive.state, StringList(lines, source="generated"), node)
    return node.children


# ----------------------------------------------------------------------------------------- benchmark results

def _text(value) -> str:
    """``value`` as literal reStructuredText on one line: every markup character escaped."""
    text = " ".join(str(value).split())
    return "".join("\\" + c if c in "\\*`|_<>[]:" else c for c in text)


def _number(value) -> str:
    """A figure with three significant digits (integers and text as they are), escaped for a table cell."""
    if isinstance(value, bool) or not isinstance(value, float):
        return _text(value)
    return f"{value:.3g}"


def _flatten(figures, prefix: str = "") -> list[tuple[str, str]]:
    """``(path, value)`` rows of a nested dict of figures: ``one direction / cold / first call``."""
    rows = []
    for key, value in figures.items():
        path = f"{prefix} / {key}" if prefix else str(key)
        if isinstance(value, dict):
            rows += _flatten(value, path)
        elif isinstance(value, list):
            rows.append((_text(path), ", ".join(_number(v) for v in value)))
        else:
            rows.append((_text(path), _number(value)))
    return rows


def _table(caption: str, header: list[str], rows: list[list[str]]) -> list[str]:
    lines = [f".. list-table:: {_text(caption)}", "   :header-rows: 1", ""]
    for row in [header] + rows:
        lines.append(f"   * - {row[0] if str(row[0]) else ' '}")
        lines += [f"     - {cell if str(cell) else ' '}" for cell in row[1:]]
    return lines + [""]


def benchmark_lines(path: Path) -> list[str]:
    """One benchmark's section: what it measures, the machine, its figures as tables."""
    data = json.loads(path.read_text(encoding="utf-8"))
    name, machine, figures = data["benchmark"], data["machine"], data["figures"]
    title = f"``{name}``"
    lines = [title, "-" * len(title), ""]
    if isinstance(figures, dict) and figures.get("description"):
        lines += [_text(figures["description"]), ""]
    command = figures.get("command") if isinstance(figures, dict) else None
    lines += [f"Command: ``{command or 'python benchmarks/' + name + '.py'}``; "
              f"output ``benchmarks/results/{path.name}``.", ""]
    load = machine.get("load_average")
    lines += [f"Run on {machine.get('date')}: {machine.get('cpu')} ({machine.get('cores')} cores, numba target "
              f"{machine.get('numba_target')}, load average {', '.join(f'{v:.2f}' for v in load or [])}), "
              f"{machine.get('system')}; Python {machine.get('python')}, NumPy {machine.get('numpy')}, SciPy "
              f"{machine.get('scipy')}, numba {machine.get('numba')}, microslip {machine.get('microslip')}.", ""]
    if isinstance(figures, dict) and figures.get("sizes"):
        lines += [f"Sizes: {_text(figures['sizes'])}.", ""]
    tables = figures.get("tables") if isinstance(figures, dict) else None
    if tables:
        for table in tables:
            lines += _table(table.get("caption", ""), [_text(c) for c in table["columns"]],
                            [[_number(v) for v in row] for row in table["rows"]])
    else:
        rest = {k: v for k, v in figures.items() if k not in ("description", "command", "sizes")}
        lines += _table("", ["figure", "value"], [list(r) for r in _flatten(rest)])
    return lines


class BenchmarkResults(SphinxDirective):
    """``{benchmark-results}``: a section per ``benchmarks/results/*.json``, sorted by name."""

    def run(self):
        folder = ROOT / "benchmarks" / "results"
        lines = []
        for path in sorted(folder.glob("*.json")):
            self.env.note_dependency(str(path))
            lines += benchmark_lines(path)
        if not lines:
            lines = ["No benchmark has saved its results yet."]
        return _parse(self, lines)


# --------------------------------------------------------------------------------------------------- gallery

def gallery_argv(gallery_conf, script_vars) -> list[str]:
    """The command line of an example in the gallery: ``--out`` a fresh folder of its own, at a small size."""
    stem = Path(script_vars["src_file"]).stem
    out = GALLERY_OUTPUT / stem
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    quick = [] if os.environ.get("MICROSLIP_GALLERY") == "full" else QUICK_OPTIONS.get(stem, [])
    return ["--out", str(out), *quick]


_shown: set = set()


def scrape_written_figures(block, block_vars, gallery_conf) -> str:
    """The PNG files an example wrote into its ``--out`` folder since the last block, as the block's images."""
    from sphinx_gallery.scrapers import figure_rst

    out = GALLERY_OUTPUT / Path(block_vars["src_file"]).stem
    images = []
    for png in sorted(out.rglob("*.png")) if out.is_dir() else []:
        key = (str(png), png.stat().st_mtime_ns)
        if key in _shown:
            continue
        _shown.add(key)
        target = Path(next(block_vars["image_path_iterator"]))
        shutil.copyfile(png, target)
        images.append(str(target))
    return figure_rst(images, gallery_conf["src_dir"])


def setup(app):
    app.add_config_value("microslip_documented", [], "env")
    app.connect("config-inited", write_api_pages)  # before Sphinx lists its sources and autosummary its stubs
    app.add_directive("microslip-cli", CommandLine)
    app.add_directive("benchmark-results", BenchmarkResults)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
