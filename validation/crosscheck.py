"""Cross-validation report: `python validation/crosscheck.py [--cases ...]`.

Runs every case with Exudyn's chain and the reduced-Lagrangian chain and writes
validation/crosscheck.md plus one plot per case (lightsail_mbs.studies.crosscheck does the work).
"""

import os
import sys
from pathlib import Path

# small dense LU factorisations (Radau on the TnT chain) run 5-10x faster on one BLAS thread
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from lightsail_mbs.cli import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main(["crosscheck", "--out", str(Path(__file__).resolve().parent), *sys.argv[1:]]))
