"""Cross-validation report (issue 4): `python validation/crosscheck.py [--cases ...]`.

Runs every case with Exudyn's chain and the reduced-Lagrangian chain and writes
validation/crosscheck.md plus one plot per case (lightsail_mbs.crosscheck does the work).
"""
import sys
from pathlib import Path

from lightsail_mbs.cli import main

if __name__ == "__main__":
    sys.exit(main(["crosscheck", "--out", str(Path(__file__).resolve().parent), *sys.argv[1:]]))
