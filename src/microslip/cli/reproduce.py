"""``microslip reproduce``: the paper's figures, their data as CSV, and a report with an error table."""

from __future__ import annotations

from pathlib import Path

from ._args import add_output_folder


def add_parser(sub) -> None:
    p = sub.add_parser(
        "reproduce", help="reproduce the paper's figures and write a report",
        description="Reproduce the figures of Gastaldi & Gola for the sphere benchmark (d = 10 mm, "
                    "steel E = 200 GPa, nu = 0.3, mu = 0.4, tuned at 37.5 N with 4 elements): each as PNG "
                    "plus a CSV of the plotted data, then report.html (self-contained) and report.md with "
                    "a table of the differences between the discrete model and the continuous reference.")
    add_output_folder(p, "microslip-results")
    p.set_defaults(func=run)


def run(args) -> int:
    from ..figures import reproduce

    report_path = reproduce(Path(args.out), progress=not args.quiet)
    print(f"report: {report_path}")
    return 0
