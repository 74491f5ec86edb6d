"""Speed of a spinning 1 m disc in the beam, both solvers: `nice -n 10 python validation/spin_benchmark.py`.

The case (issue #26's speed target): a free 1 m disc of Si₃N₄ film (the materials table's FlexSailSim values:
E = 270 GPa, ρ = 3100 kg/m³), 200 nm thick, spinning at 120 Hz (Ω = 2π · 120 rad/s, FlexSailSim's spin), flat
at the start, in a round Gaussian beam of 1 GW/m² and waist 0.4 m on its axis, switched on at t = 0, on 49,
193 and 1009 polar tiles (disc n × ny = 9 × 12, 17 × 24, 37 × 56). Output every 1 ms; the stop rule is off
(failure ratio 1e300: a flat start has no amplitude to grow, an offset or tilted one a round-off amplitude whose
'failure' would rerun the case at finer output intervals). Rows run each solver's defaults (in-house: rtol
1e-7, the turning frame for a spinning sheet; Exudyn: generalized-α, h = 0.026 √(L/g₀), at most a third of the
output interval) or the options they name (in-house rtol, Exudyn step_size, the in-house inertial frame) over
a span chosen to keep the table affordable; the CPU time of that span (time.process_time, after a warm-up run
that loads the compiled kernels) gives the cost per simulated second and the projected cost of 1 s (linear in
the span; the first 0.1 ms, the beam's onset, take sub-microsecond steps but few of them). Every run is a
Python process of its own and records the ride's histories (analysis.ride3d: lateral position, tilt, spin
rate, shape amplitude) at the output samples.

The options table (validation/spin_benchmark_options.py): the 1009-tile case and the offset ride with the in-house
solver's opt-in rate_scale and jacobian options. Further tables (validation/spin_benchmark_steps.py): every
in-house step traced on 193 and 1009 tiles (what sets its size), the end values of a 0.1 s offset ride on 193 tiles
against rtol (the tolerance a ride needs), and the CPU of the parts of an in-house step (right-hand side, Jacobian,
LU, solves) at 193 and 1009 tiles; and the same film unlit in both frames, flat and with the case's default 10 µm
defect (released in the flat sheet's centrifugal stress, which pulls it towards flat: docs: sheet, 'Spin against
tension').

Writes validation/spin_benchmark.md; the measured rows are kept in validation/spin_benchmark_rows.json (one
entry a table: speed, crumple, steps, tolerance, costs, options). `--only NAME` (repeatable) measures those tables and
keeps the others' rows; `--reuse` writes the report from the kept rows, nothing run; `--rows` names another
file for the kept rows.
"""

import argparse
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import spin_benchmark_options as opt_in
import spin_benchmark_steps as steps

HERE = Path(__file__).resolve().parent
SIZES = {49: (9, 12), 193: (17, 24), 1009: (37, 56)}
SPIN = 2 * math.pi * 120.0  # rad/s
TARGETS = {"reduced": 60.0, "exudyn": 180.0}  # CPU s for 1 s at ~1000 tiles (issue #26)
ROWS = [  # tiles, solver, options, span (s)
    (49, "reduced", {}, 0.05),
    (193, "reduced", {}, 0.02),
    (193, "reduced", {"rtol": 1e-3}, 0.1),
    (1009, "reduced", {"rtol": 1e-3}, 0.02),
    (1009, "reduced", {"rtol": 1e-2}, 0.02),
    (49, "exudyn", {}, 0.02),
    (193, "exudyn", {}, 0.01),
    (193, "exudyn", {"step_size": 1e-4}, 0.005),
    (1009, "exudyn", {}, 0.003),
    (49, "reduced", {"frame": "inertial"}, 0.002),
    (193, "reduced", {"frame": "inertial"}, 0.001),
]
CHILD = r"""
import json, math, os, sys, time
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
import numpy as np
from lightsail_mbs import RunSettings, SailParameters, solve
from lightsail_mbs.analysis.ride3d import sheet_ride
from lightsail_mbs.model import materials
from lightsail_mbs.solvers.reduced import sheet_radau
n, ny, solver, span, options, changes, interval, trace = json.loads(sys.argv[1])
def disc(n, ny, **changes):
    fields = dict(model="sheet", planform="disc", n=n, ny=ny, length=1.0, width=1.0, material="silicon-nitride",
                  thickness=2e-7, spin_rate=2 * math.pi * 120, intensity=1e9, beam_waist=0.4, defect_amplitude=0.0)
    return SailParameters(**materials.fill({**fields, **changes}))
def settings(span, interval=1e-3):
    return RunSettings(t_final=span, output_interval=min(span, interval), stop_at_failure=False, failure_ratio=1e300)
solve(disc(5, 6, **changes), solver, settings(1e-4), uncertainty=False, **options)  # loads the kernels
history = []
if trace:  # each accepted step: (t, h, error norm, state component (0-12) and tile of the largest scaled error)
    norm, step, scaled = sheet_radau.norm, sheet_radau.SheetRadau.step, []
    def spy(x):
        if x.ndim == 1:  # the error estimate / scale (the Newton increments are (3, n))
            scaled.append(np.abs(x))
        return norm(x)
    def traced(self):
        t, scaled[:] = self.t, []
        message = step(self)
        if scaled:
            worst = int(np.argmax(scaled[-1]))
            history.append((t, self.t - t, norm(scaled[-1]) / math.sqrt(scaled[-1].size), worst % 13, worst // 13))
        return message
    sheet_radau.norm, sheet_radau.SheetRadau.step = spy, traced
cpu, wall = time.process_time(), time.perf_counter()
r = solve(disc(n, ny, **changes), solver, settings(span, interval), uncertainty=False, **options)
cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
info, ride = r.info, sheet_ride(r)
rides = dict(lateral_x=ride.lateral[:, 0], lateral_y=ride.lateral[:, 1], tilt_x=ride.tilt[:, 0],
             tilt_y=ride.tilt[:, 1], spin_rate=ride.spin_rate, amplitude=ride.amplitude)
print(json.dumps(dict(cpu=cpu, wall=wall, error=r.error,
    steps=info["steps"], jacobians=info["njev"], rejected=info.get("rejected_steps"),
    newton=info.get("newton_iterations"), rhs=info.get("nfev"), frame=info.get("frame"),
    step=info.get("step_size"), rtol=info.get("rtol"), amplitude=[float(a) for a in r.amplitude],
    time=[float(t) for t in r.time],
    rides={k: [float(x) for x in v] for k, v in rides.items()}, history=history, load=os.getloadavg()[0])))
"""


def measure(tiles, solver, options, span, changes=None, interval=1e-3, trace=False) -> dict:
    """One run in its own process (CHILD): counts, CPU, the ride's end values; trace: each step's record."""
    n, ny = SIZES[tiles]
    argument = json.dumps([n, ny, solver, span, options, changes or {}, interval, trace])
    out = subprocess.run([sys.executable, "-c", CHILD, argument], capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def label(solver: str, row: dict) -> str:
    if solver == "reduced":
        return f"in-house, {row['frame']} frame, rtol {row.get('rtol') or 1e-7:g}"
    return f"Exudyn, h = {1e3 * row['step']:.3g} ms"


def speed_table(rows: list) -> list[str]:
    lines = [
        "| tiles | solver | simulated (s) | steps | rejected | Jacobians | Newton it. · RHS | CPU (s) | wall (s) "
        "| CPU per simulated s | projected 1 s (CPU) | target (~1000 tiles) |",
        "|---:|---|---:|---:|---:|---:|---|---:|---:|---:|---:|---|",
    ]
    for tiles, solver, _, span, row in rows:
        if row["error"]:
            lines.append(
                f"| {tiles} | {label(solver, row)} | {span:g} | {row['steps']} | "
                f"{row['rejected'] or 0} | {row['jacobians']} | – | {row['cpu']:.2f} | {row['wall']:.2f} | – | – "
                f"| stopped: {row['error']} |"
            )
            continue
        per_second = row["cpu"] / span
        target = TARGETS[solver]
        verdict = "–"
        if tiles == max(SIZES):
            verdict = f"≤ {target:g} s: {'met' if per_second <= target else 'not met'} (projected)"
        counts = f"{row['newton'] or '–'} · {row['rhs'] or '–'}"
        lines.append(
            f"| {tiles} | {label(solver, row)} | {span:g} | {row['steps']} | {row['rejected'] or 0} | "
            f"{row['jacobians']} | {counts} | {row['cpu']:.2f} | {row['wall']:.2f} | {per_second:,.0f} | "
            f"{per_second:,.0f} s = {per_second / 3600:.2f} h | {verdict} |"
        )
    return lines


FRAME_CASES = {  # the unlit film disc in both frames: label -> (changes, span (s), output interval (s))
    "flat, unlit": (dict(intensity=0.0, beam_waist=float("inf")), 0.05, 5e-3),
    "10 µm defect (ν = 1.5), unlit": (dict(intensity=0.0, defect_amplitude=1e-5, beam_waist=float("inf")), 1e-3, 1e-4),
}


def crumple_rows() -> list:
    """The unlit film disc on 49 tiles in both frames (FRAME_CASES): (case, frame, span, row)."""
    out = []
    for case, (changes, span, interval) in FRAME_CASES.items():
        for frame in ("inertial", "turning"):
            out.append((case, frame, span, measure(49, "reduced", {"frame": frame}, span, changes, interval)))
    return out


def crumple_table(crumple: list) -> list[str]:
    lines = [
        "| case | frame | simulated (s) | steps | rejected | Jacobians | CPU (s) "
        "| plane amplitude / a₀ at 0.2, 0.4, 0.5, 0.6, 0.8, 1.0 ms (defect) |",
        "|---|---|---:|---:|---:|---:|---:|---|",
    ]
    for case, frame, span, row in crumple:
        a0 = row["amplitude"][0]
        ratio = {round(t, 6): a / a0 for t, a in zip(row["time"], row["amplitude"]) if a0}
        picked = ", ".join(f"{ratio[t]:.4g}" for t in (2e-4, 4e-4, 5e-4, 6e-4, 8e-4, 1e-3) if t in ratio) or "–"
        lines.append(
            f"| {case} | {frame} | {span:g} | {row['steps']} | {row['rejected'] or 0} | {row['jacobians']} "
            f"| {row['cpu']:.2f} | {picked} |"
        )
    return lines


def row_of(rows: list, tiles: int, solver: str, options: dict | None = None) -> tuple[dict, float] | None:
    """(row, span) of the speed row with these tiles, solver and options (None if there is none)."""
    return next(((r, sp) for t, s, o, sp, r in rows if (t, s, o) == (tiles, solver, options or {})), None)


def at_time(row: dict, name: str, time: float) -> float:
    """A ride history's value at the output sample `time`."""
    k = min(range(len(row["time"])), key=lambda i: abs(row["time"][i] - time))
    return row["rides"][name][k]


def frame_findings(rows: list) -> list[str]:
    out = []
    for tiles in SIZES:
        slow, fast = row_of(rows, tiles, "reduced", {"frame": "inertial"}), row_of(rows, tiles, "reduced")
        if slow and fast:
            (r0, s0), (r1, s1) = slow, fast
            out.append(
                f"* {tiles} tiles, in-house, rtol 1e-7: the inertial frame takes {r0['steps'] / s0:,.0f} steps per "
                f"simulated second (mean step {1e6 * s0 / r0['steps']:.2g} µs), the turning frame "
                f"{r1['steps'] / s1:,.0f} ({1e6 * s1 / r1['steps']:.3g} µs)."
            )
    return out


def speed_findings(rows: list, costs: dict) -> list[str]:
    """The 1009-tile rows against the targets: steps needed × cost per step."""
    big, out = max(SIZES), []
    c = costs.get(str(big)) or costs.get(big)
    iteration = 3 * c["rhs"] + c["real"] + c["complex"]
    refresh = c["jacobian"] + c["system"] + c["lu"]
    best = None
    for t, s, o, span, r in rows:
        if t != big or s != "reduced" or r["error"]:
            continue
        per_s, per_step = r["steps"] / span, r["cpu"] / r["steps"]
        jac_share = r["jacobians"] * refresh / r["cpu"]
        out.append(
            f"* {big} tiles, in-house, rtol {o.get('rtol', 1e-7):g}, {1e3 * span:g} ms: {per_s:,.0f} steps per "
            f"simulated second (mean {1e6 / per_s:.3g} µs), {1e3 * per_step:.0f} ms CPU a step, "
            f"{r['jacobians']} Jacobians (~{100 * jac_share:.0f} % of the CPU at {1e3 * refresh:.0f} ms each with "
            f"its reduced system and one LU pair): projected {per_s * per_step:,.0f} s for 1 s."
        )
        if best is None or per_s * per_step < best[0] * best[1]:
            best = (per_s, per_step, o.get("rtol", 1e-7))
    if best:
        per_s, per_step, rtol = best
        out.append(
            f"* The floor, in-house at {big} tiles: the best row (rtol {rtol:g}) needs {per_s:,.0f} steps for 1 s "
            f"at {1e3 * per_step:.0f} ms a step = {per_s * per_step:,.0f} s, "
            f"{per_s * per_step / TARGETS['reduced']:.1f}× the {TARGETS['reduced']:g} s target. Even at one Newton "
            "iteration a step and no Jacobian "
            f"({1e3 * iteration:.1f} ms: 3 right-hand sides of {1e3 * c['rhs']:.2f} ms, a real and a complex "
            f"solve) those steps cost {per_s * iteration:,.0f} s; 60 s allows "
            f"{TARGETS['reduced'] / per_s * 1e3:.1f} ms a step. A Jacobian costs {13 * c['colours']} right-hand "
            "sides: the polar disc's centre tile touches "
            f"all {SIZES[big][1]} tiles of the first ring, so its distance-2 colouring needs {c['colours']} colours "
            "(a rectangular grid 5)."
        )
    for t, s, _, span, r in rows:
        if s == "exudyn" and not r["error"]:
            ref = row_of(rows, t, "reduced", {"rtol": 1e-3}) or row_of(rows, t, "reduced")
            drift = ""
            if ref and ref[1] >= span:
                mine, theirs = r["rides"]["spin_rate"][-1], at_time(ref[0], "spin_rate", span)
                drift = (
                    f"; spin rate at {1e3 * span:g} ms {mine:.6g} rad/s against the in-house {theirs:.6g}, "
                    f"{1 - mine / theirs:.2e} low ((Ωh)²/12 = {(SPIN * r['step']) ** 2 / 12:.2e}: the phase error of "
                    "a second-order step on the tiles' circular motion)"
                )
            out.append(
                f"* {t} tiles, Exudyn, h = {1e3 * r['step']:.3g} ms: {r['jacobians'] / r['steps']:.1f} Jacobians and "
                f"{r['newton'] / r['steps']:.1f} Newton iterations a step, {r['cpu'] / r['steps']:.2f} s CPU a step "
                f"(inertial frame: the disc turns {r['step'] * SPIN:.2f} rad a step){drift}."
            )
    exudyn = row_of(rows, big, "exudyn")
    if exudyn:
        r, _ = exudyn
        h_max = math.sqrt(12e-3) / SPIN  # (Ωh)²/12 ≤ 1e-3: issue #26's bound on the spin rate
        out.append(
            f"* The floor, Exudyn at {big} tiles: the spin rate within 1e-3 needs (Ωh)²/12 ≤ 1e-3, h ≤ "
            f"{1e3 * h_max:.3g} ms, {1 / h_max:,.0f} steps for 1 s; {TARGETS['exudyn']:g} s allows "
            f"{1e3 * TARGETS['exudyn'] * h_max:.0f} ms a step against {r['cpu'] / r['steps']:.2f} s measured "
            f"({r['newton'] / r['steps']:.1f} Newton iterations and {r['jacobians'] / r['steps']:.1f} Jacobians a "
            f"step): {r['cpu'] / r['steps'] / (TARGETS['exudyn'] * h_max):,.0f}× over, the Newton iterations "
            "alone (9–11 a step at h = 0.333 and 0.1 ms alike: the rows above) far over."
        )
    return out


TABLES = ("speed", "crumple", "steps", "tolerance", "costs", "options")


def measured(name: str):
    """The rows of one table, measured now."""
    if name == "speed":
        rows = []
        for tiles, solver, options, span in ROWS:
            row = measure(tiles, solver, options, span)
            rows.append((tiles, solver, options, span, row))
            print(tiles, solver, options, span, {k: row[k] for k in ("cpu", "steps", "jacobians", "error")}, flush=True)
        return rows
    if name == "crumple":
        return crumple_rows()
    if name == "costs":
        return {tiles: steps.unit_costs(tiles, SIZES) for tiles in (193, 1009)}
    if name == "options":
        return opt_in.option_rows(measure)
    return steps.step_rows(measure) if name == "steps" else steps.tolerance_rows(measure)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(HERE / "spin_benchmark.md"))
    parser.add_argument("--reuse", action="store_true", help="write the report from the kept rows")
    parser.add_argument("--only", choices=TABLES, action="append", help="measure only this table (repeatable)")
    parser.add_argument("--rows", default=str(HERE / "spin_benchmark_rows.json"), help="the kept rows (json)")
    args = parser.parse_args(argv)
    tables = {} if args.reuse else {name: measured(name) for name in (args.only or TABLES)}
    kept_file = Path(args.rows)  # read after measuring: runs of different tables may overlap
    kept = {**(json.loads(kept_file.read_text()) if kept_file.exists() else {}), **tables}
    kept_file.write_text(json.dumps(kept))
    rows, crumple = kept["speed"], kept["crumple"]
    loads = [row["load"] for *_, row in rows]
    text = [
        "# A spinning 1 m disc in the beam: speed of both solvers",
        "",
        "Generated by `nice -n 10 python validation/spin_benchmark.py` (module docstring: the case and the spans; "
        "`--only NAME` measures the tables named again (speed, crumple, steps, tolerance, costs, options), "
        "`--reuse` rewrites this page from the kept rows). "
        f"Load average {min(loads):.1f}–{max(loads):.1f} on {os.cpu_count()} cores during the speed rows: CPU times "
        "are those of the run's process, wall times include waiting for a core.",
        "",
        "Si₃N₄ film 200 nm, 1 m disc, 120 Hz, flat start, Gaussian beam 1 GW/m², w = 0.4 m on the disc's axis; "
        "each solver's defaults unless the row says; 'projected 1 s' = CPU of the span × (1 s / span).",
        "",
        *speed_table(rows),
        "",
        "## What sets the in-house step",
        "",
        f"Every accepted step traced over {1e3 * steps.STEP_SPAN:g} ms (module validation/spin_benchmark_steps.py): "
        "the largest scaled error ‖e_i‖/(atol_i + rtol |y_i|) of the step's error estimate, by state component.",
        "",
        *steps.step_table(kept["steps"]),
        "",
        "## The tolerance a ride needs",
        "",
        f"193 tiles, the beam's axis {100 * steps.RIDE_OFFSET:g} cm from the disc's centre (so that lateral position "
        f"and tilt are not zero by symmetry), {steps.RIDE_SPAN:g} s; end values and their relative differences "
        "from the tightest rtol's.",
        "",
        *steps.tolerance_table(kept["tolerance"]),
        "",
        "## Cost of the parts of a step (in-house, turning frame, at the start)",
        "",
        *steps.cost_table(kept["costs"]),
        "",
        "The same film unlit on 49 tiles, in-house solver, in both frames (the same tolerances): flat, the spun disc "
        "rests in the turning frame; the case's default 10 µm defect is released in the flat sheet's centrifugal "
        "stress, which pulls it towards flat.",
        "",
        *crumple_table(crumple),
        "",
        "## The in-house solver's opt-in options",
        "",
        "Measured by validation/spin_benchmark_options.py (`--only options`): solvers.reduced.sheet_options' "
        "rate_scale spin and jacobian split, each off by default; the offset ride's Δ against the "
        "tolerance table's tightest rtol.",
        "",
        *(opt_in.options_table(kept["options"], kept["tolerance"]) if "options" in kept else []),
        "",
        "## What the rows say",
        "",
        *steps.step_findings(kept["steps"]),
        *steps.tolerance_findings(kept["tolerance"]),
        *frame_findings(rows),
        *speed_findings(rows, kept["costs"]),
        *(opt_in.options_findings(kept["options"], kept["tolerance"], TARGETS["reduced"]) if "options" in kept else []),
    ]
    Path(args.out).write_text("\n".join(text) + "\n")
    print("\n".join(text))
    return 0


if __name__ == "__main__":
    sys.exit(main())
