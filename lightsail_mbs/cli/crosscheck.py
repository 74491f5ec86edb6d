"""`lightsail-mbs crosscheck`: both solvers on the cross-validation cases; Markdown report and plots."""

from __future__ import annotations

from pathlib import Path

from lightsail_mbs.cli.options import writable_folder


def register(sub) -> None:
    from lightsail_mbs.studies import crosscheck  # the case names (numpy only)

    p = sub.add_parser("crosscheck", help="run the Exudyn and reduced solvers side by side (the cross-check report)")
    p.add_argument(
        "--cases",
        nargs="+",
        metavar="CASE",
        choices=sorted(crosscheck.CASES),
        help=f"subset of cases [default: all: {', '.join(crosscheck.CASES)}]",
    )
    p.add_argument(
        "--out", default="validation", help="directory for crosscheck.md and the plots [default: validation]"
    )
    p.add_argument(
        "--exudyn-step-scale",
        type=float,
        default=1.0,
        help="multiply Exudyn's default step by this factor ≤ 1 (convergence check) [default: 1]",
    )
    p.add_argument("--quiet", action="store_true", help="no progress on stderr/stdout")
    p.set_defaults(func=run)


def run(args) -> int:
    from lightsail_mbs.studies import crosscheck
    from lightsail_mbs.viz.plots import crosscheck_figure

    writable_folder(args.out, "--out")
    out = Path(args.out)

    def draw(case, exudyn, reduced):
        ie, ir = crosscheck.common_samples(exudyn.time, reduced.time, case.settings.sample_interval)
        title, path = f"{case.name}: {case.note}", out / f"crosscheck_{case.name}.png"
        crosscheck_figure(exudyn, reduced, ie, ir, title, crosscheck.ANGLE_LIMIT, path)

    rows = crosscheck.run(
        args.cases, out_dir=out, progress=not args.quiet, exudyn_step_scale=args.exudyn_step_scale, draw=draw
    )
    print(f"wrote {args.out}/crosscheck.md: {sum(r['passed'] for r in rows)}/{len(rows)} cases pass")
    return 0 if all(r["passed"] for r in rows) else 1
