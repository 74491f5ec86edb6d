"""`lightsail-mbs simulate`: run one case with one solver, save the Result, print its summary."""

from __future__ import annotations

import json
import sys

from lightsail_mbs.cli.options import add_case_options, params_from_args, settings_from_args, writable_file
from lightsail_mbs.solvers import SOLVERS


def register(sub) -> None:
    p = sub.add_parser("simulate", help="run one case (exudyn or reduced solver; a chain or, --model sheet, a sheet)")
    add_case_options(p)
    p.add_argument("--solver", choices=sorted(SOLVERS), default="exudyn")
    p.add_argument("--out", help="write the Result to this .npz (and its .json summary)")
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object on stdout")
    p.add_argument("--quiet", action="store_true", help="no progress bar on stderr")
    p.set_defaults(func=run)


def run(args) -> int:
    from lightsail_mbs.solvers import solve

    params, settings = params_from_args(args), settings_from_args(args)
    out = writable_file(args.out, "--out", ".npz") if args.out else None
    result = solve(params, args.solver, settings, progress=not args.quiet)
    if out:
        result.save(out)
    summary = result.summary()
    if args.json:
        print(json.dumps(summary))
    else:
        ft = summary["failure_time"]
        size = f"{summary['n']}x{summary['ny']} tiles" if "ny" in summary else f"n={summary['n']}"
        print(
            f"{summary['solver']} {summary['model']} {size}: "
            f"{f'FAILED at t = {ft:.6g} s' if summary['failed'] else 'not failed'} "
            f"(max amplitude ratio {summary['max_amplitude_ratio']:.4g}, t_end {summary['t_end']:.6g} s, "
            f"wall {summary['wall_time']:.3g} s)"
        )
        if summary["dissipated_energy"]:
            print(f"dissipated as heat: {summary['dissipated_energy']:.6g} J")
    for note in summary["warnings"]:
        print(f"warning: {note}", file=sys.stderr)
    if summary["error"]:
        print(f"solver error: {summary['error']}", file=sys.stderr)
        return 1
    return 0
