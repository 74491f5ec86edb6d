"""`lightsail-mbs montecarlo`: failure probability and failure times over random multi-mode defects, or over
the seeds of the case's film (``--over film``, the film from --film-rms, --film-correlation-length, --film-hurst)."""

from __future__ import annotations

import dataclasses
import json

from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.cli.options import (
    SOLVER_HELP,
    add_case_options,
    params_from_args,
    settings_from_args,
    writable_folder,
)
from lightsail_mbs.solvers import SOLVERS

SWEEPABLE = ("youngs_modulus", "tension", "thickness", "intensity", "defect_amplitude")  # studies.montecarlo's


def register(sub) -> None:
    p = sub.add_parser(
        "montecarlo", help="failure probability and failure times over N seeded multi-mode defects or films"
    )
    add_case_options(p)
    p.add_argument(
        "--vary",
        choices=SWEEPABLE,
        default="youngs_modulus",
        help="the parameter swept [default: youngs_modulus]",
    )
    p.add_argument(
        "--values",
        default=None,
        help="comma-separated values of the swept parameter (SI) [default: the case's own value]",
    )
    p.add_argument("--seeds", type=int, default=50, help="defects or films per value (seeds 0…N−1) [default: 50]")
    p.add_argument(
        "--over",
        choices=("defect", "film"),
        default="defect",
        help="what the seeds draw: the multi-mode defect (defect_seed), or the case's film (film_seed; needs "
        "--film-rms > 0, the defect kept as the case states it) [default: defect]",
    )
    p.add_argument("--solver", choices=sorted(SOLVERS), default="exudyn", help=f"{SOLVER_HELP} [default: exudyn]")
    p.add_argument("--store", required=True, help="folder of the per-case store (resumable)")
    p.add_argument("--workers", type=int, default=None, help="local processes [default: all cores]")
    p.add_argument("--scheduler", default=None, help="Dask scheduler address, e.g. tcp://host:8786")
    p.add_argument("--json", action="store_true", help="print the table as JSON")
    p.add_argument("--quiet", action="store_true", help="no progress bar on stderr")
    p.set_defaults(func=run)


def run(args) -> int:
    from lightsail_mbs.model import film
    from lightsail_mbs.studies import montecarlo

    base = params_from_args(args)
    if args.over == "defect":
        base = base.replace(defect_seed=0)  # the seeds 0…N−1 replace any --defect-seed
    try:
        text = str(getattr(base, args.vary)) if args.values is None else args.values
        values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        values = []
    if not values:
        raise ParameterError(f"values={args.values!r} is invalid: allowed one or more comma-separated numbers")
    montecarlo.cases(base, args.vary, values[:1], args.seeds, over=args.over)  # the inputs checked before any work
    writable_folder(args.store, "--store")
    rows = montecarlo.run(
        base,
        args.vary,
        values,
        args.seeds,
        args.store,
        solver=args.solver,
        settings=settings_from_args(args),
        workers=args.workers,
        scheduler=args.scheduler,
        progress=not args.quiet,
        over=args.over,
    )
    if args.json:
        print(json.dumps([dataclasses.asdict(r) for r in rows]))
        return 0
    seeded = "multi-mode defects" if args.over == "defect" else f"films ({film.of_case(base).describe()})"
    print(f"{args.seeds} {seeded} per value, seeds 0…{args.seeds - 1}")
    print(f"| {args.vary} | runs | failed | P(fail) | 95 % CI | median t_f (s) | IQR (s) | 5–95 % (s) | errors |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        iqr = "–" if r.failure_time_q25 is None else f"{r.failure_time_q25:.4g}–{r.failure_time_q75:.4g}"
        wide = "–" if r.failure_time_q05 is None else f"{r.failure_time_q05:.4g}–{r.failure_time_q95:.4g}"
        med = "–" if r.failure_time_median is None else f"{r.failure_time_median:.4g}"
        print(
            f"| {r.value:.3g} | {r.runs} | {r.failures} | {r.probability:.2f} | "
            f"{r.probability_low:.2f}–{r.probability_high:.2f} | {med} | {iqr} | {wide} | {r.errors} |"
        )
    return 0
