"""`lightsail-mbs journey`: the whole acceleration of a case to a target speed under constant beam power, with the
temperature, thermal strain, tension left and margin at snapshots along it, and the verdict (docs/journey.md)."""

from __future__ import annotations

import json
import math
import sys

from lightsail_mbs.cli.options import add_case_options, params_from_args, writable_folder

# option -> (JourneySettings field, type, help); the defaults are the settings class's
JOURNEY_OPTIONS = {
    "--power": ("power", float, "the beam power the sail intercepts (W, lab frame), constant (required)"),
    "--target-speed": ("target_speed", float, "the speed to reach, as a fraction β of c [default: 0.2]"),
    "--wavelength": ("wavelength", float, "the laser's wavelength (m) [default: 1.064e-6]"),
    "--absorptance": (
        "absorptance",
        float,
        "the film's absorptance at the laser's wavelength [default: the material's; with an optical table that has "
        "a wavelength axis and records absorption, the table's at each sail-frame wavelength]",
    ),
    "--emissivity-front": ("emissivity_front", float, "the laser-facing face's emissivity [default: the material's]"),
    "--emissivity-back": ("emissivity_back", float, "the back face's emissivity [default: the material's]"),
    "--environment-temperature": (
        "environment",
        float,
        "temperature of the surroundings the film radiates to (K) [default: 2.725, deep space; 293 in a lab]",
    ),
    "--reference-temperature": (
        "reference_temperature",
        float,
        "temperature at which the film was tensioned (K): the thermal strain is counted from it [default: 293.15]",
    ),
    "--step": ("step", float, "the fractional change of g₀ between snapshots [default: 0.05]"),
    "--shape-time": (
        "shape_time",
        float,
        "with --shape-runs: each run's duration in finite-amplitude times t_c [default: 20]",
    ),
}


def register(sub) -> None:
    p = sub.add_parser(
        "journey",
        help="the whole acceleration to a target speed: Doppler-shifted beam, temperature, thermal strain, tension "
        "left and margin along it, and the verdict (the case needs --material)",
    )
    add_case_options(p, run=False)
    g = p.add_argument_group("journey")
    for option, (name, kind, text) in JOURNEY_OPTIONS.items():
        g.add_argument(option, dest=f"journey_{name}", type=kind, default=None, help=text, required=name == "power")
    g.add_argument(
        "--shape-runs",
        action="store_true",
        help="solve each snapshot's case for its shape (reduced solver, the intensity and tension of the moment)",
    )
    g.add_argument(
        "--time-domain",
        action="store_true",
        help="a chain's whole journey as one run: its world line, the Doppler dimming and (TnT with axial springs) "
        "the heated film's tension inside the run, to the target speed or to failure; rows from the run's record",
    )
    g.add_argument(
        "--solver",
        choices=("reduced", "exudyn"),
        default="reduced",
        help="with --time-domain: the solver of the run [default: reduced]",
    )
    g.add_argument(
        "--samples", type=int, default=500, help="with --time-domain: the run's output samples [default: 500]"
    )
    p.add_argument(
        "--out",
        required=True,
        help="output folder: journey.csv, journey.json, journey.png; the snapshots' rows are kept in "
        "journey_rows.jsonl as they are made, and a rerun with the same case and settings resumes from them",
    )
    p.add_argument("--quiet", action="store_true", help="no progress bar on stderr")
    p.set_defaults(func=run)


def run(args) -> int:
    from lightsail_mbs.studies.journey import JourneySettings, run_journey
    from lightsail_mbs.studies.tables import write_csv
    from lightsail_mbs.viz.journey import journey_figure

    params = params_from_args(args)
    given = {name: getattr(args, f"journey_{name}") for name, _, _ in JOURNEY_OPTIONS.values()}
    given["carried_mass"] = params.carried_mass  # the case's (--carried-mass): the craft's mass beyond its bodies
    settings = JourneySettings(**{k: v for k, v in given.items() if v is not None}, shape_runs=args.shape_runs)
    out = writable_folder(args.out, "--out")
    if args.time_domain:
        from lightsail_mbs.base.validation import check
        from lightsail_mbs.studies.journey_run import run_time_domain

        check("--shape-runs", args.shape_runs, not args.shape_runs, "off with --time-domain (the run is the shape's)")
        report = run_time_domain(params, settings, args.solver, args.samples, progress=not args.quiet)
    else:
        report = run_journey(params, settings, progress=not args.quiet, folder=out)
    write_csv(out / "journey.csv", report["snapshots"])
    (out / "journey.json").write_text(json.dumps(_plain(report), indent=1), encoding="utf-8")
    journey_figure(report, out / "journey.png")
    verdict = report["verdict"]
    first = report["snapshots"][0]
    print(
        f"{verdict['text']}; at the start T max {first['temperature_max']:.4g} K "
        f"(limit {report['film']['limit_temperature']:.4g} K), margin {first['margin']:.4g}; "
        f"T lags its steady field by ≤ {report['thermal_lag']:.2g} of T; wrote {out}/journey.{{csv,json,png}}"
    )
    if args.time_domain:
        print(f"time domain: {args.solver} solver, {report['wall_time']:.3g} s of wall time")
    else:
        resume = report["resume"]
        if resume["discarded"]:
            print(f"note: {resume['discarded']}", file=sys.stderr)
        elif resume["resumed"]:
            print(f"resumed: {resume['resumed']} of {len(report['snapshots'])} snapshots read from {resume['file']}")
        if report["optics"]["wavelength_axis"]:
            print(f"optics: {report['optics']['text']}")
    for note in report["notes"]:
        print(f"note: {note}", file=sys.stderr)
    return 0


def _plain(value):
    """The report with NaN and inf as None (strict JSON)."""
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value
