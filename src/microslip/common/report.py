"""Reports: one document written both as self-contained HTML and as Markdown.

A :class:`Report` collects headings, paragraphs, tables and figures. Figures
are saved as PNG next to the report (and embedded in the HTML as base64, so
``report.html`` can be mailed on its own). Every file is written atomically.
"""

from __future__ import annotations

import base64
import html
import io
from dataclasses import dataclass, field
from pathlib import Path

from ._io import atomic_write


@dataclass
class Report:
    """A document to be written as ``report.html`` and ``report.md``.

    Parameters
    ----------
    title : str
        Document title.
    """

    title: str
    _blocks: list = field(default_factory=list)

    def heading(self, text: str, level: int = 2) -> None:
        """Add a heading (level 2 = section)."""
        self._blocks.append(("heading", text, level))

    def text(self, text: str) -> None:
        """Add a paragraph of plain text (Markdown inline code with backticks is kept)."""
        self._blocks.append(("text", text))

    def table(self, headers, rows, caption: str | None = None) -> None:
        """Add a table; ``rows`` is a list of sequences of cells (str or numbers)."""
        self._blocks.append(("table", list(headers), [list(r) for r in rows], caption))

    def figure(self, fig, name: str, caption: str, out_dir) -> Path:
        """Save ``fig`` as ``out_dir/name.png`` (atomically) and add it to the report."""
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=150, bbox_inches="tight")
        png = buf.getvalue()
        path = atomic_write(Path(out_dir) / f"{name}.png", png)
        self._blocks.append(("figure", name, caption, png))
        return path

    # -- rendering ----------------------------------------------------------
    def to_markdown(self) -> str:
        out = [f"# {self.title}", ""]
        for block in self._blocks:
            kind = block[0]
            if kind == "heading":
                out += ["#" * block[2] + " " + block[1], ""]
            elif kind == "text":
                out += [block[1], ""]
            elif kind == "table":
                _, headers, rows, caption = block
                if caption:
                    out += [f"*{caption}*", ""]
                out.append("| " + " | ".join(headers) + " |")
                out.append("|" + "---|" * len(headers))
                out += ["| " + " | ".join(_cell(c) for c in r) + " |" for r in rows]
                out.append("")
            elif kind == "figure":
                _, name, caption, _png = block
                out += [f"![{caption}]({name}.png)", "", f"*{caption}*", ""]
        return "\n".join(out)

    def to_html(self) -> str:
        parts = [
            "<!DOCTYPE html><html><head><meta charset='utf-8'>",
            f"<title>{html.escape(self.title)}</title>",
            "<style>body{font-family:sans-serif;max-width:60em;margin:2em auto;line-height:1.4}"
            "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:.25em .6em;"
            "text-align:right}th{background:#eee}img{max-width:100%}figcaption{font-style:italic}"
            "code{background:#f4f4f4}</style></head><body>",
            f"<h1>{html.escape(self.title)}</h1>",
        ]
        for block in self._blocks:
            kind = block[0]
            if kind == "heading":
                parts.append(f"<h{block[2]}>{html.escape(block[1])}</h{block[2]}>")
            elif kind == "text":
                parts.append(f"<p>{_inline_code(html.escape(block[1]))}</p>")
            elif kind == "table":
                _, headers, rows, caption = block
                parts.append("<table>")
                if caption:
                    parts.append(f"<caption>{html.escape(caption)}</caption>")
                parts.append("<tr>" + "".join(f"<th>{html.escape(h)}</th>" for h in headers) + "</tr>")
                for r in rows:
                    parts.append("<tr>" + "".join(f"<td>{html.escape(_cell(c))}</td>" for c in r) + "</tr>")
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


def _cell(value) -> str:
    if isinstance(value, float):
        return f"{value:.4g}"
    return str(value)


def _inline_code(text: str) -> str:
    pieces = text.split("`")
    return "".join(p if i % 2 == 0 else f"<code>{p}</code>" for i, p in enumerate(pieces))
