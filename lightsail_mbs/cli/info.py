"""`lightsail-mbs info`: what a saved run is, what it found, and what made it."""

from __future__ import annotations

import json


def register(sub) -> None:
    p = sub.add_parser("info", help="summary and provenance of a saved run (.npz)")
    p.add_argument("run", help="a Result saved by `lightsail-mbs simulate --out RUN.npz`")
    p.add_argument("--json", action="store_true", help="print the summary (with provenance) as one JSON object")
    p.set_defaults(func=run)


def run(args) -> int:
    from lightsail_mbs.result import Result

    result = Result.load(args.run)
    summary = result.summary()
    if args.json:
        print(json.dumps(summary, default=str))
        return 0
    p = result.params
    size = f"{p.n} x {p.ny} tiles" if p.model == "sheet" else f"n = {p.n}"
    print(f"{args.run}: {summary['solver']} run of a {p.model} sail, {size}, t_end = {summary['t_end']:.6g} s")
    verdict = f"failed at t = {summary['failure_time']:.6g} s" if summary["failed"] else "did not fail"
    print(f"  {verdict}; max amplitude ratio {summary['max_amplitude_ratio']:.4g}")
    if summary["error"]:
        print(f"  solver error: {summary['error']}")
    for note in summary.get("warnings") or []:
        print(f"  warning: {note}")
    print("  parameters: " + ", ".join(f"{k}={v}" for k, v in summary["parameters"].items()))
    print("  settings:   " + ", ".join(f"{k}={v}" for k, v in summary["settings"].items()))
    print("  solver:     " + ", ".join(f"{k}={v}" for k, v in summary["info"].items()))
    made = summary["provenance"] or {}
    if not made:
        print("  provenance: not recorded (saved by an earlier version)")
    for key, value in made.items():
        print(f"  {key:12s} {value}")
    return 0
