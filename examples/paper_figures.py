"""The paper's figures: ``microslip reproduce``
============================================

Gastaldi & Gola's benchmark (a steel sphere, d = 10 mm, E = 200 GPa, nu = 0.3, mu = 0.4, tuned at
N_tot = 37.5 N with J = 4 elements): Figs. 2a, 2b, 3a, 3b, 4a, 4b and 6 of the paper (Fig. 6 from the synthetic
cylinder data set shipped with the package), three sections beyond the paper (accuracy under a variable normal
load against the exact MDR reference, worst errors against J, energy error against amplitude), each as PNG and
CSV, and ``report.html``/``report.md`` with the tables of differences.

The same as ``microslip reproduce --out DIR``. Run ``python examples/paper_figures.py [--out DIR]`` (default
``./microslip-results``).
"""

import argparse
from pathlib import Path

from microslip.figures import reproduce

# sphinx_gallery_thumbnail_number = 4


def main(out=Path("microslip-results")) -> Path:
    """Write every section of the paper's reproduction into the folder ``out``; returns the HTML report."""
    report = reproduce(out, progress=False)
    print(f"report: {report}")
    print(Path(out, "report.md").read_text(encoding="utf-8"))
    return report


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description="The paper's figures and report (as microslip reproduce).")
    parser.add_argument("--out", default="microslip-results", help="folder to write into (created if needed; "
                                                                   "default ./microslip-results)")
    main(Path(parser.parse_args().out))
