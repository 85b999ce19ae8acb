"""Reports: one document written both as self-contained HTML and as Markdown.

A :class:`Report` collects headings, paragraphs, tables and figures. Figures
are saved as PNG next to the report (and embedded in the HTML as base64, so
``report.html`` can be mailed on its own). Every file is written atomically.

What an engineer reads first is stated first: under the title, a table of the
package version, the date and every parameter of the run. Tables align text
left and numbers right (never broken across lines). Energies are given as
:class:`Energy` cells (J) and shown in one unit for the whole report, chosen
by their magnitude (mJ, µJ, ...); :data:`ENERGY_UNIT` in any text stands for
that unit.
"""

from __future__ import annotations

import base64
import datetime
import html
import io
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path

from ._io import atomic_write
from .units import display_unit
from ._version import __version__

#: written in headings, text, captions, headers or cells, stands for the report's energy unit
ENERGY_UNIT = "{energy unit}"

#: resolution of the report's figures (dpi) and the width (in) the HTML shows them at: 60em of 16 px
DPI = 150
REPORT_WIDTH = 960 / DPI

#: a cell read as a number: 12, -3.5, 1.2e-05, nan, or numbers joined by " / " (e.g. "167 / 30.1")
_NUMBER = r"[-+−]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?|nan|[-+]?inf"
_NUMERIC_CELL = re.compile(rf"^\s*(?:{_NUMBER})(?:\s*/\s*(?:{_NUMBER}))*\s*$")


class Energy(float):
    """An energy (J) in a report table: shown in the report's energy unit (:data:`ENERGY_UNIT`)."""


def plural(count: int, noun: str, plural_form: str | None = None) -> str:
    """``count`` and ``noun`` in the right number: ``plural(1, 'element')`` is ``'1 element'``."""
    return f"{count} {noun if count == 1 else (plural_form or noun + 's')}"


def energy_unit(values) -> tuple[str, float]:
    """The unit for energies ``values`` (J): the largest of J, mJ, µJ, nJ that their largest magnitude reaches.

    Returns
    -------
    unit : str
    factor : float
        The value of one unit in J (divide by it).
    """
    finite = [abs(float(v)) for v in values if v == v and abs(float(v)) != float("inf")]
    unit, per_joule = display_unit(finite, "energy")
    return unit, 1.0 / per_joule


def _now() -> str:
    return datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z")


def run_lines(parameters=None, date: str | None = None) -> list[str]:
    """The header of a plain-text report: package version, date, then ``name: value`` per parameter."""
    lines = [f"microslip version: {__version__}", f"date: {date or _now()}"]
    return lines + [f"{name}: {_cell(value, 1.0)}" for name, value in (parameters or {}).items()]


@dataclass
class Report:
    """A document to be written as ``report.html`` and ``report.md``.

    Parameters
    ----------
    title : str
        Document title.
    parameters : mapping of str to object, optional
        Every parameter of the run (name -> value, units in the value, e.g.
        ``{"tuning load N_tot": "37.5 N"}``), shown under the title with the
        package version and the date.
    """

    title: str
    parameters: dict | None = None
    _blocks: list = field(default_factory=list)
    _date: str = field(default_factory=_now)

    def heading(self, text: str, level: int = 2) -> None:
        """Add a heading (level 2 = section)."""
        self._blocks.append(("heading", text, level))

    def text(self, text: str) -> None:
        """Add a paragraph of plain text (Markdown inline code with backticks is kept)."""
        self._blocks.append(("text", text))

    def table(self, headers, rows, caption: str | None = None) -> None:
        """Add a table; ``rows`` is a list of sequences of cells (str, numbers, :class:`Energy` or None)."""
        self._blocks.append(("table", list(headers), [list(r) for r in rows], caption))

    def figure(self, fig, name: str, caption: str, out_dir) -> Path:
        """Save ``fig`` as ``out_dir/name.png`` (atomically), add it to the report and close it.

        Closed because the report holds the picture: a command run within Python (a script, a notebook,
        the docs' gallery) leaves no figure open to pile up or be shown again. A figure pyplot does not
        manage (``matplotlib.figure.Figure``) holds no window and is left to the garbage collector.
        """
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=DPI, bbox_inches="tight")
        pyplot = sys.modules.get("matplotlib.pyplot")  # imported by whoever made a pyplot figure; not imported here
        if pyplot is not None:
            pyplot.close(fig)
        png = buf.getvalue()
        path = atomic_write(Path(out_dir) / f"{name}.png", png)
        self._blocks.append(("figure", name, caption, png))
        return path

    # -- rendering ----------------------------------------------------------
    def run_table(self) -> list[list[str]]:
        """Rows ``[name, value]`` of the table under the title: version, date, then every parameter."""
        rows = [["microslip version", __version__], ["date", self._date]]
        for name, value in (self.parameters or {}).items():
            rows.append([str(name), _cell(value, 1.0)])
        return rows

    def energy_unit(self) -> tuple[str, float]:
        """The unit of every energy in the report (:func:`energy_unit` of all its :class:`Energy` cells)."""
        return energy_unit([c for b in self._blocks if b[0] == "table" for r in b[2] for c in r
                            if isinstance(c, Energy)])

    def _render_parts(self):
        """The blocks, run table first, with the energy unit put in and every cell as text."""
        unit, factor = self.energy_unit()

        def sub(s: str) -> str:
            return s.replace(ENERGY_UNIT, unit)

        blocks = [("table", ["run", "value"], self.run_table(), None)] + self._blocks
        for block in blocks:
            if block[0] == "table":
                _, headers, rows, caption = block
                cells = [[sub(_cell(c, factor)) for c in r] for r in rows]
                numeric = [_numeric_column([r[j] for r in cells if j < len(r)]) for j in range(len(headers))]
                yield ("table", [sub(h) for h in headers], cells, sub(caption) if caption else None, numeric)
            elif block[0] == "heading":
                yield ("heading", sub(block[1]), block[2])
            elif block[0] == "text":
                yield ("text", sub(block[1]))
            else:
                _, name, caption, png = block
                yield ("figure", name, sub(caption), png)

    def to_markdown(self) -> str:
        out = [f"# {self.title}", ""]
        for block in self._render_parts():
            kind = block[0]
            if kind == "heading":
                out += ["#" * block[2] + " " + block[1], ""]
            elif kind == "text":
                out += [block[1], ""]
            elif kind == "table":
                _, headers, rows, caption, numeric = block
                if caption:
                    out += [f"*{caption}*", ""]
                out.append("| " + " | ".join(headers) + " |")
                out.append("|" + "".join("---:|" if n else ":---|" for n in numeric))
                out += ["| " + " | ".join(r) + " |" for r in rows]
                out.append("")
            elif kind == "figure":
                _, name, caption, _png = block
                out += [f"![{caption}]({name}.png)", "", f"*{caption}*", ""]
        return "\n".join(out)

    def to_html(self) -> str:
        parts = [
            "<!DOCTYPE html><html><head><meta charset='utf-8'>",
            f"<title>{html.escape(self.title)}</title>",
            "<style>body{font-family:sans-serif;font-size:16px;max-width:60em;margin:2em auto;line-height:1.4}"
            "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:.25em .6em;"
            "text-align:left;vertical-align:top}th{background:#eee}.num{text-align:right;white-space:nowrap}"
            "img{max-width:100%}figcaption{font-style:italic}code{background:#f4f4f4}</style></head><body>",
            f"<h1>{html.escape(self.title)}</h1>",
        ]
        for block in self._render_parts():
            kind = block[0]
            if kind == "heading":
                parts.append(f"<h{block[2]}>{html.escape(block[1])}</h{block[2]}>")
            elif kind == "text":
                parts.append(f"<p>{_inline_code(html.escape(block[1]))}</p>")
            elif kind == "table":
                _, headers, rows, caption, numeric = block
                cls = ["<td class='num'>" if n else "<td>" for n in numeric]
                parts.append("<table>")
                if caption:
                    parts.append(f"<caption>{html.escape(caption)}</caption>")
                parts.append("<tr>" + "".join(f"<th{' class=num' if n else ''}>{html.escape(h)}</th>"
                                              for h, n in zip(headers, numeric)) + "</tr>")
                for r in rows:
                    parts.append("<tr>" + "".join(f"{cls[j] if j < len(cls) else '<td>'}{html.escape(c)}</td>"
                                                  for j, c in enumerate(r)) + "</tr>")
                parts.append("</table>")
            elif kind == "figure":
                _, name, caption, png = block
                data = base64.b64encode(png).decode("ascii")
                parts.append(f"<figure><img alt='{html.escape(name)}' src='data:image/png;base64,{data}'>"
                             f"<figcaption>{html.escape(caption)}</figcaption></figure>")
        parts.append("</body></html>")
        return "\n".join(parts)

    def write(self, out_dir, stem: str = "report") -> tuple[Path, Path]:
        """Write ``stem.html`` and ``stem.md`` into ``out_dir``; returns both paths."""
        out_dir = Path(out_dir)
        return (atomic_write(out_dir / f"{stem}.html", self.to_html()),
                atomic_write(out_dir / f"{stem}.md", self.to_markdown()))


def _cell(value, energy_factor: float) -> str:
    if value is None:
        return ""
    if isinstance(value, Energy):
        return f"{value / energy_factor:.4g}"
    if isinstance(value, float):
        return f"{value:.4g}"
    return str(value)


def _numeric_column(cells) -> bool:
    """A column is numeric when every non-empty cell reads as a number (and one at least is not empty)."""
    filled = [c for c in cells if c.strip()]
    return bool(filled) and all(_NUMERIC_CELL.match(c) for c in filled)


def _inline_code(text: str) -> str:
    pieces = text.split("`")
    return "".join(p if i % 2 == 0 else f"<code>{p}</code>" for i, p in enumerate(pieces))
