"""`lightsail-mbs simulate`: run one case with one solver, save the Result, print its summary."""

from __future__ import annotations

import json
import sys

from lightsail_mbs.cli.options import SOLVER_HELP, add_case_options, params_from_args, settings_from_args, writable_file
from lightsail_mbs.solvers import SOLVERS


def register(sub) -> None:
    p = sub.add_parser("simulate", help="run one case (exudyn or reduced solver; a chain or, --model sheet, a sheet)")
    add_case_options(p)
    p.add_argument("--solver", choices=sorted(SOLVERS), default="exudyn", help=f"{SOLVER_HELP} [default: exudyn]")
    p.add_argument(
        "--rtol",
        type=float,
        default=None,
        help="the solver's relative tolerance [default: exudyn 1e-7 (sets DOPRI5's tolerance or the generalized-α "
        "step), reduced 1e-8 (DOP853) or 1e-6 (Radau)]",
    )
    p.add_argument(
        "--no-uncertainty",
        dest="uncertainty",
        action="store_false",
        help="skip the twin runs that give the answer's uncertainty, conditioning and n-error (the base run is "
        "reported)",
    )
    p.add_argument("--out", help="write the Result to this .npz (and its .json summary)")
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object on stdout")
    p.add_argument("--quiet", action="store_true", help="no progress bar on stderr")
    p.set_defaults(func=run)


def run(args) -> int:
    from lightsail_mbs.analysis.runs import solve

    params, settings = params_from_args(args), settings_from_args(args)
    out = writable_file(args.out, "--out", ".npz") if args.out else None
    options = {} if args.rtol is None else {"rtol": args.rtol}
    result = solve(params, args.solver, settings, progress=not args.quiet, uncertainty=args.uncertainty, **options)
    if out:
        result.save(out)
    summary = result.summary()
    if args.json:
        print(json.dumps(summary))
    else:
        ratio = f"max amplitude ratio {summary['max_amplitude_ratio']:.4g}, " if summary["failed"] else ""
        size = f"{summary['n']}x{summary['ny']} tiles" if "ny" in summary else f"n={summary['n']}"
        wall = (summary["uncertainty"] or {}).get("elapsed", summary["wall_time"])  # twins run beside the base run
        print(
            f"{summary['solver']} {summary['model']} {size}: {result.answer_text()} "
            f"({ratio}t_end {summary['t_end']:.6g} s, wall {wall:.3g} s)"
        )
        estimate = summary["uncertainty"]
        if estimate is None:
            print("uncertainty: not estimated (--no-uncertainty)")
        elif not estimate["estimated"] or not estimate["well_conditioned"]:
            print(estimate["explanation"])
        film = result.film_text()
        if film:
            print(film)
        if summary["dissipated_energy"]:
            print(f"dissipated as heat: {summary['dissipated_energy']:.6g} J")
    for note in summary["warnings"]:
        print(f"warning: {note}", file=sys.stderr)
    if summary["error"]:
        print(f"solver error: {summary['error']}", file=sys.stderr)
        return 1
    return 0
