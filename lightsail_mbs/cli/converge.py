"""`lightsail-mbs converge --vary n`: a case at increasing n, its answer against n with the fitted order and
the n needed for 1 % — or "not converging" when the answers are not monotone, the fit is unphysical or the
case is ill-posed in n (lightsail_mbs.studies.convergence)."""

from __future__ import annotations

import json
import sys

from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.cli.options import add_case_options, params_from_args, settings_from_args, writable_file
from lightsail_mbs.model.cases import PAPER_CASES


def register(sub) -> None:
    p = sub.add_parser(
        "converge",
        help="run a case at increasing n: failure time (or max amplitude ratio) vs n, fitted order, n for 1 %% "
        "(or 'not converging')",
    )
    p.add_argument("--vary", choices=["n"], default="n", help="what is refined: the number of slices n [default: n]")
    p.add_argument(
        "--case",
        choices=sorted(PAPER_CASES),
        help="start from the paper's named case and its run (the case options below change it)",
    )
    add_case_options(p)
    sizes = p.add_argument_group("sizes (instead of --n)")
    sizes.add_argument(
        "--sizes",
        help="comma-separated numbers of slices (a sheet: tiles along L, ny = n W/L across), increasing, "
        "e.g. 15,30,60,120",
    )
    sizes.add_argument("--n-start", type=int, default=15, help="first n of a geometric sequence [default: 15]")
    sizes.add_argument("--n-max", type=int, default=960, help="largest n of the sequence [default: 960]")
    sizes.add_argument("--factor", type=float, default=2.0, help="ratio of successive n [default: 2]")
    p.add_argument("--no-noise", dest="noise", action="store_false", help="skip the runs at rtol/10")
    p.add_argument("--budget", type=float, help="stop refining once one run takes over budget/4 CPU seconds")
    p.add_argument("--rtol", type=float, help="reduced solver's relative tolerance [default: the method's own]")
    p.add_argument(
        "--method",
        choices=["auto", "DOP853", "Radau"],
        default="auto",
        help="reduced solver's integrator [default: auto, from the stiffness]",
    )
    p.add_argument("--markdown", help="also write the table to this Markdown file")
    p.add_argument("--json", action="store_true", help="print the study as one JSON object")
    p.add_argument("--quiet", action="store_true", help="no progress lines on stderr")
    p.set_defaults(func=run)


def run(args) -> int:
    from lightsail_mbs.model.cases import paper_case
    from lightsail_mbs.solvers.settings import paper_settings
    from lightsail_mbs.studies import convergence

    if args.n is not None:
        raise ParameterError("--n is invalid with converge: n is varied (use --sizes or --n-start/--n-max/--factor)")
    if args.case:
        base = params_from_args(args, base=paper_case(args.case))
        settings = settings_from_args(args, base=paper_settings(args.case))
    else:
        base, settings = params_from_args(args), settings_from_args(args)
    if args.sizes:
        try:
            sizes = [int(v) for v in args.sizes.split(",") if v.strip()]
        except ValueError:
            raise ParameterError(f"sizes={args.sizes!r} is invalid: allowed comma-separated integers") from None
    else:
        sizes = convergence.geometric_sizes(args.n_start, args.n_max, args.factor)
    markdown = writable_file(args.markdown, "--markdown", ".md") if args.markdown else None
    options = {"method": args.method} if base.model != "sheet" or args.method != "auto" else {}
    if args.rtol is not None:
        options["rtol"] = args.rtol

    def report(row):
        if not args.quiet:
            noise = "—" if row.tolerance_noise is None else f"{row.tolerance_noise:.1e}"
            print(
                f"n = {row.size}: {row.kind} {row.value} (tolerance noise {noise}, {row.method}, "
                f"{row.cpu_time:.3g} s CPU; fastest-growing wave: {convergence.wave_text(row.resolvedness)})",
                file=sys.stderr,
                flush=True,
            )

    study = convergence.converge(
        base, settings, sizes, noise=args.noise, budget=args.budget, progress=report, **options
    )
    table = convergence.markdown_table(study)
    if markdown:
        markdown.write_text(table + "\n")
    if args.json:
        print(json.dumps(study.to_dict()))
    else:
        print(table)
    return 0
