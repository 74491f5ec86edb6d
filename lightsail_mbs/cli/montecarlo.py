"""`lightsail-mbs montecarlo`: failure probability over random multi-mode defects ."""

from __future__ import annotations

import dataclasses
import json

from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.cli.options import add_case_options, params_from_args, settings_from_args, writable_folder
from lightsail_mbs.solvers import SOLVERS

SWEEPABLE = ("youngs_modulus", "tension", "thickness", "intensity", "defect_amplitude")  # studies.montecarlo's


def register(sub) -> None:
    p = sub.add_parser("montecarlo", help="failure probability and failure times over N seeded multi-mode defects")
    add_case_options(p)
    p.add_argument(
        "--vary",
        choices=SWEEPABLE,
        default="youngs_modulus",
        help="the parameter swept [default youngs_modulus]",
    )
    p.add_argument("--values", required=True, help="comma-separated values of the swept parameter (SI)")
    p.add_argument("--seeds", type=int, default=50, help="defects per value (seeds 0…N−1) [50]")
    p.add_argument("--solver", choices=sorted(SOLVERS), default="exudyn")
    p.add_argument("--store", required=True, help="folder of the per-case store (resumable)")
    p.add_argument("--workers", type=int, default=None, help="local processes [all cores]")
    p.add_argument("--scheduler", default=None, help="Dask scheduler address, e.g. tcp://host:8786")
    p.add_argument("--json", action="store_true", help="print the table as JSON")
    p.add_argument("--quiet", action="store_true", help="no progress bar on stderr")
    p.set_defaults(func=run)


def run(args) -> int:
    from lightsail_mbs.studies import montecarlo

    base = params_from_args(args).replace(defect_seed=0)  # the seeds 0…N−1 replace any --defect-seed
    try:
        values = [float(v) for v in args.values.split(",") if v.strip()]
    except ValueError:
        values = []
    if not values:
        raise ParameterError(f"values={args.values!r} is invalid: allowed one or more comma-separated numbers")
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
    )
    if args.json:
        print(json.dumps([dataclasses.asdict(r) for r in rows]))
        return 0
    print(f"| {args.vary} | runs | failed | P(fail) | 95 % CI | median t_f (s) | IQR (s) | errors |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        iqr = "–" if r.failure_time_q25 is None else f"{r.failure_time_q25:.3g}–{r.failure_time_q75:.3g}"
        med = "–" if r.failure_time_median is None else f"{r.failure_time_median:.3g}"
        print(
            f"| {r.value:.3g} | {r.runs} | {r.failures} | {r.probability:.2f} | "
            f"{r.probability_low:.2f}–{r.probability_high:.2f} | {med} | {iqr} | {r.errors} |"
        )
    return 0
