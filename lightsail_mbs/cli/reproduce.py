"""`lightsail-mbs reproduce`: recompute the paper's figures with the pipelines of lightsail_mbs.paper.

Each pipeline writes its PNG and CSV files into --out and prints the numbers it plotted; this command
prints the wall time of each. Cases go through the resumable sweep store (--store, default OUT/store): a
rerun recomputes nothing already finished.
"""
from __future__ import annotations

import time
from pathlib import Path

from lightsail_mbs.model.parameters import ParameterError
from lightsail_mbs.paper import PIPELINES, pipeline
from lightsail_mbs.solvers import SOLVERS


def register(sub) -> None:
    p = sub.add_parser("reproduce", help="recompute the paper's figures (PNG + CSV + printed tables)")
    which = p.add_mutually_exclusive_group(required=True)
    which.add_argument("--figure", type=int, action="append", choices=sorted(PIPELINES),
                       help="paper figure number (repeatable): " + ", ".join(map(str, sorted(PIPELINES))))
    which.add_argument("--all", action="store_true", help="every figure")
    p.add_argument("--out", default="results", help="output folder of PNG and CSV files [results]")
    p.add_argument("--store", default=None, help="folder of the resumable case store [OUT/store]")
    p.add_argument("--solver", choices=sorted(SOLVERS), default="exudyn", help="[exudyn]")
    p.add_argument("--workers", type=int, default=None, help="local processes [all cores]")
    p.add_argument("--scheduler", default=None, help="Dask scheduler address, e.g. tcp://host:8786")
    p.add_argument("--quick", action="store_true",
                   help="smoke test: fewer slices, modes and thicknesses, shorter runs (not the paper's numbers)")
    p.add_argument("--quiet", action="store_true", help="no progress bars")
    p.set_defaults(func=run)


def run(args) -> int:
    if args.workers is not None and args.workers < 1:
        raise ParameterError(f"workers={args.workers!r} is invalid: allowed an integer ≥ 1")
    numbers = sorted(PIPELINES) if args.all else sorted(set(args.figure))
    names = list(dict.fromkeys(PIPELINES[k] for k in numbers))
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    walls = []
    for name in names:
        module = pipeline(name)
        start = time.perf_counter()
        module.run(out, solver=args.solver, workers=args.workers, scheduler=args.scheduler, quick=args.quick,
                   store=args.store, progress=not args.quiet)
        wall = time.perf_counter() - start
        figs = ", ".join(str(k) for k in module.FIGURES)
        walls.append((figs, name, wall))
        print(f"\nFig. {figs} ({name}): wall time {wall:.1f} s", flush=True)
    print("\n| figures | pipeline | wall time (s) |\n|---|---|---|")
    for figs, name, wall in walls:
        print(f"| {figs} | {name} | {wall:.1f} |")
    print(f"| all | | {sum(w for *_, w in walls):.1f} |")
    return 0
