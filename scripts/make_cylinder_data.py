"""Write the SYNTHETIC cylinder-on-flat data set into src/microslip/data (reproducible: fixed seed).

Usage: python scripts/make_cylinder_data.py [OUT_DIR]

The physics and the test conditions are described in microslip.loops.synthetic.
"""

import sys
from pathlib import Path

from microslip.loops.synthetic import Specimen, write_dataset

if __name__ == "__main__":
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "src/microslip/data"
    for path in write_dataset(out, Specimen()):
        print(path)
