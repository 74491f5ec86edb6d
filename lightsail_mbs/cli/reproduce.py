"""`lightsail-mbs reproduce`: recompute the paper's figures, or the studies beyond it, with the pipelines
of lightsail_mbs.paper.

--figure N (repeatable) and --all run the paper's figure pipelines (PIPELINES); --scenario NAME
(repeatable) runs the studies beyond the paper (SCENARIOS) with their default options — their scripts
scenarios/NAME.py expose those options. --all is the paper's figures only. Each pipeline writes its
PNG/GIF and CSV files into --out and prints the numbers it plotted; this command prints the wall time of
each. Cases go through the resumable sweep store (--store, default OUT/store): a rerun recomputes
nothing already finished.
"""

from __future__ import annotations

import time

from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.cli.options import SOLVER_HELP, writable_folder
from lightsail_mbs.paper import PIPELINES, SCENARIOS, pipeline
from lightsail_mbs.solvers import SOLVERS


def register(sub) -> None:
    p = sub.add_parser(
        "reproduce", help="recompute the paper's figures or the studies beyond it (PNG + CSV + printed tables)"
    )
    which = p.add_mutually_exclusive_group(required=True)
    which.add_argument(
        "--figure",
        type=int,
        action="append",
        choices=sorted(PIPELINES),
        help="paper figure number (repeatable): " + ", ".join(map(str, sorted(PIPELINES))),
    )
    which.add_argument("--all", action="store_true", help="every paper figure (not the scenarios)")
    which.add_argument(
        "--scenario",
        action="append",
        choices=list(SCENARIOS),
        metavar="NAME",
        help="study beyond the paper (repeatable): " + ", ".join(SCENARIOS),
    )
    p.add_argument("--out", default="results", help="output folder of PNG and CSV files [default: results]")
    p.add_argument("--store", default=None, help="folder of the resumable case store [default: OUT/store]")
    p.add_argument(
        "--solver",
        choices=sorted(SOLVERS),
        default=None,
        help=f"{SOLVER_HELP} [default: exudyn for the figures and the animations, reduced for the other scenarios]",
    )
    p.add_argument("--workers", type=int, default=None, help="local processes [default: all cores]")
    p.add_argument("--scheduler", default=None, help="Dask scheduler address, e.g. tcp://host:8786")
    p.add_argument(
        "--quick",
        action="store_true",
        help="smoke test: fewer slices, modes and thicknesses, shorter runs (not the published numbers)",
    )
    p.add_argument("--quiet", action="store_true", help="no progress bars")
    p.set_defaults(func=run)


def selected(args) -> list[tuple[str, str]]:
    """(label, pipeline module name) of the chosen figures or scenarios, each module once."""
    if args.scenario:
        return [(name, SCENARIOS[name]) for name in dict.fromkeys(args.scenario)]
    numbers = sorted(PIPELINES) if args.all else sorted(set(args.figure))
    names = dict.fromkeys(PIPELINES[k] for k in numbers)
    return [("Fig. " + ", ".join(str(k) for k in pipeline(name).FIGURES), name) for name in names]


def run(args) -> int:
    if args.workers is not None and args.workers < 1:
        raise ParameterError(f"workers={args.workers!r} is invalid: allowed an integer ≥ 1")
    out = writable_folder(args.out, "--out")
    if args.store:
        writable_folder(args.store, "--store")
    solver = {} if args.solver is None else {"solver": args.solver}
    walls = []
    for label, name in selected(args):
        module = pipeline(name)
        start = time.perf_counter()
        module.run(
            out,
            workers=args.workers,
            scheduler=args.scheduler,
            quick=args.quick,
            store=args.store,
            progress=not args.quiet,
            **solver,
        )
        wall = time.perf_counter() - start
        walls.append((label, name, wall))
        print(f"\n{label} ({name}): wall time {wall:.1f} s", flush=True)
    what = "scenario" if args.scenario else "figures"
    print(f"\n| {what} | pipeline | wall time (s) |\n|---|---|---|")
    for label, name, wall in walls:
        print(f"| {label.removeprefix('Fig. ')} | {name} | {wall:.1f} |")
    print(f"| all | | {sum(w for *_, w in walls):.1f} |")
    return 0
