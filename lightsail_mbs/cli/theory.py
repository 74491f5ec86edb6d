"""`lightsail-mbs theory`: the closed forms of Section II (Eqs 4, 7–10)."""

from __future__ import annotations

import json

from lightsail_mbs.cli.options import add_case_options, params_from_args


def register(sub) -> None:
    p = sub.add_parser("theory", help="g0, E_cr,max and T_cr,max for a case (paper Eqs 4, 8, 10)")
    add_case_options(p, run=False)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run)


def run(args) -> int:
    from lightsail_mbs.model import theory

    numbers = theory.summary(params_from_args(args))
    if args.json:
        print(json.dumps(numbers))
    else:
        for key, value in numbers.items():
            print(f"{key:22s} {value if value is None else f'{value:.6g}'}")
    return 0
