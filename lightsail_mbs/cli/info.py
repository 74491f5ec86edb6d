"""`lightsail-mbs info`: what a saved run is, what it found, and what made it."""

from __future__ import annotations

import json
from pathlib import Path

from lightsail_mbs.model.fields import number


def register(sub) -> None:
    p = sub.add_parser(
        "info", help="what a saved run (.npz) found, with its uncertainty and conditioning, and what made it"
    )
    p.add_argument("run", help="a Result saved by `lightsail-mbs simulate --out RUN.npz` (or its summary RUN.json)")
    p.add_argument("--json", action="store_true", help="print the summary (with provenance) as one JSON object")
    p.set_defaults(func=run)


def run(args) -> int:
    from lightsail_mbs.result import Result

    path = Path(args.run)
    if path.suffix == ".json" and path.with_suffix(".npz").exists():  # the summary beside its run
        path = path.with_suffix(".npz")
    result = Result.load(path)
    summary = result.summary()
    if args.json:
        print(json.dumps(summary, default=str))
        return 0
    p = result.params
    size = f"{p.n} x {p.ny} tiles" if p.model == "sheet" else f"n = {p.n}"
    print(f"{path}: {summary['solver']} run of a {p.model} sail, {size}, t_end = {summary['t_end']:.6g} s")
    print(f"  answer: {result.answer_text()}")
    print(f"  conditioning: {conditioning(summary['uncertainty'])}")
    film = result.film_text()
    if film:
        print(f"  {film}")
    if summary["failed"]:
        print(f"  max amplitude ratio {summary['max_amplitude_ratio']:.4g}")
    if summary["error"]:
        print(f"  solver error: {summary['error']}")
    for note in summary.get("warnings") or []:
        print(f"  warning: {note}")
    print("  parameters: " + ", ".join(f"{k}={number(v)}" for k, v in summary["parameters"].items()))
    print("  settings:   " + ", ".join(f"{k}={number(v)}" for k, v in summary["settings"].items()))
    print("  solver:     " + ", ".join(f"{k}={v}" for k, v in summary["info"].items()))
    made = summary["provenance"] or {}
    if not made:
        print("  provenance: not recorded (saved by an earlier version)")
    for key, value in made.items():
        print(f"  {key:12s} {value}")
    return 0


def conditioning(estimate: dict | None) -> str:
    """The conditioning verdict of a run's uncertainty estimate (solvers.uncertainty), in one line."""
    if estimate is None:
        return "not estimated (the run was made with --no-uncertainty)"
    if not estimate.get("estimated"):
        return estimate.get("explanation") or "not estimated"
    if estimate.get("well_conditioned"):
        from lightsail_mbs.solvers.uncertainty import CONDITION_TOL, PROBE_LEVEL

        return (
            f"well-conditioned (a roughness of {number(PROBE_LEVEL)} a₀ added to the defect moves the answer by at "
            f"most {number(CONDITION_TOL)} of it)"
        )
    return f"ILL-CONDITIONED: {estimate.get('explanation', '')}".rstrip(": ")
