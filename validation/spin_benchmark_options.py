"""The in-house solver's opt-in options on the spinning disc of validation/spin_benchmark.py (its `--only options`
table): solvers.reduced.sheet_options' rate_scale "spin" (the tiles' rates scaled by the spin rate) and jacobian
"split" (the polar disc's centre tile's rows apart from the colouring).

* **Speed** (SPEED_RUNS): 1009 tiles, the benchmark's centred case over SPAN at rtol 1e-3 without the options
  (the speed table's row, measured again beside the others), then one option added at a time, and both at rtol
  1e-2; CPU per simulated second projected as in the speed table.
* **What sets the step** with both options: the 1009-tile case at rtol 1e-3 over spin_benchmark_steps.STEP_SPAN,
  every step traced as in the steps table; the share of the steps after the onset whose largest scaled error is
  on each kind of state component (COMPONENTS), and on the centre tile.
* **Accuracy** (RIDE_RUNS): the offset ride of the tolerance table (193 tiles, spin_benchmark_steps.RIDE_OFFSET,
  RIDE_SPAN) with the options, its end values against the tolerance table's tightest rtol.
"""

from __future__ import annotations

import spin_benchmark_steps as steps

SPAN = 0.02
LONG_SPAN = 0.1  # s: the fastest options again over a span in which the beam's onset is a small share
ALL = {"rate_scale": "spin", "jacobian": "split"}
SPEED_RUNS = [{"rtol": 1e-3}, {"rtol": 1e-3, "jacobian": "split"}, {"rtol": 1e-3, **ALL}, {"rtol": 1e-2, **ALL}]
RIDE_RUNS = [{"rtol": 1e-3, **ALL}, {"rtol": 1e-2, **ALL}]
COMPONENTS = {"u_x, u_y": (0, 1), "u_z": (2,), "q": (3, 4, 5, 6), "v_x, v_y": (7, 8), "v_z": (9,), "ω": (10, 11, 12)}


def option_rows(measure) -> dict:
    """{"speed": [(options, row)], "ride": [(options, row)]} of SPEED_RUNS and RIDE_RUNS."""
    changes = dict(beam_centre=0.5 + steps.RIDE_OFFSET)
    return {
        "speed": [(o, measure(1009, "reduced", o, SPAN)) for o in SPEED_RUNS],
        "long": [(SPEED_RUNS[2], measure(1009, "reduced", SPEED_RUNS[2], LONG_SPAN))],
        "ride": [(o, measure(193, "reduced", o, steps.RIDE_SPAN, changes)) for o in RIDE_RUNS],
        "traced": measure(1009, "reduced", {"rtol": 1e-3, **ALL}, steps.STEP_SPAN, trace=True),
    }


def traced_finding(row: dict) -> str:
    """The traced run's steps after the onset: median step and where the largest scaled error sits."""
    after = [h for h in row["history"] if h[0] >= steps.ONSET]
    s = steps.step_summary(row)
    shares = ", ".join(
        f"{name} {100 * sum(1 for h in after if h[3] in parts) / max(len(after), 1):.0f} %"
        for name, parts in COMPONENTS.items()
    )
    return (
        f"* What sets the step with both options (1009 tiles, rtol 1e-3, {1e3 * steps.STEP_SPAN:g} ms traced): "
        f"{s['after']} steps after the onset, median {1e6 * s['median']:.3g} µs; the largest scaled error on {shares} "
        f"of them, on the centre tile in {100 * s['centre']:.0f} %: the tiles' out-of-plane motion (the film's "
        "shape), no longer the centre tile's tilt rates."
    )


def named(options: dict) -> str:
    return ", ".join(f"{k} {v:g}" if isinstance(v, float) else f"{k} {v}" for k, v in options.items())


def ride_deviations(rows: dict, tolerance: list) -> list[tuple]:
    """(options, row, deviations) of each offset-ride row: its end values against the tightest tolerance's run."""
    reference = tuple(tolerance[-1])
    return [(o, row, steps.deviations([(o["rtol"], row), reference])[0]) for o, row in rows["ride"]]


def options_table(rows: dict, tolerance: list) -> list[str]:
    lines = [
        "| tiles | options | simulated (s) | steps | rejected | Jacobians | CPU (s) | CPU per simulated s "
        "| Δ lateral | Δ tilt | Δ Ω | Δ amplitude |",
        "|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    spans = [(SPAN, options, row) for options, row in rows["speed"]]
    for span, options, row in spans + [(LONG_SPAN, options, row) for options, row in rows.get("long", [])]:
        lines.append(
            f"| 1009 | {named(options)} | {span:g} | {row['steps']} | {row['rejected']} | {row['jacobians']} "
            f"| {row['cpu']:.2f} | {row['cpu'] / span:,.0f} | – | – | – | – |"
        )
    for options, row, d in ride_deviations(rows, tolerance):
        lines.append(
            f"| 193, offset | {named(options)} | {steps.RIDE_SPAN:g} | {row['steps']} | {row['rejected']} "
            f"| {row['jacobians']} | {row['cpu']:.2f} | {row['cpu'] / steps.RIDE_SPAN:,.0f} | {d['lateral']:.1e} "
            f"| {d['tilt']:.1e} | {d['spin']:.1e} | {d['amplitude']:.1e} |"
        )
    return lines


def options_findings(rows: dict, tolerance: list, target: float) -> list[str]:
    """What the options' table says: the 1009-tile rows against the row without options measured beside them (the
    machine's load moves the CPU of every row alike), the best projected second against the target, and the ride's
    accuracy with the options against rtol 1e-7's."""
    (_, plain), *others = rows["speed"]
    best_options, best = min(others, key=lambda item: item[1]["cpu"])
    per_s = best["cpu"] / SPAN
    loads = [r["load"] for _, r in rows["speed"]]
    out = [
        f"* 1009 tiles, {1e3 * SPAN:g} ms, each row against rtol 1e-3 without the options measured beside it "
        f"({plain['steps']} steps, {plain['jacobians']} Jacobians, {plain['cpu']:.1f} s CPU): "
        + "; ".join(
            f"{named(o)}: {r['steps'] / plain['steps']:.2f}× the steps, {plain['cpu'] / r['cpu']:.2f}× faster"
            for o, r in others
        )
        + f" (load average {min(loads):.1f}–{max(loads):.1f})."
        f" The fastest ({named(best_options)}) takes {best['steps'] / SPAN:,.0f} steps per simulated second at "
        f"{1e3 * best['cpu'] / best['steps']:.0f} ms CPU a step: projected {per_s:,.0f} s for 1 s, "
        f"{per_s / target:.1f}× the {target:g} s target."
    ]
    for options, row in rows.get("long", []):
        per_s = row["cpu"] / LONG_SPAN
        out.append(
            f"* The same ({named(options)}) over {LONG_SPAN:g} s, where the beam's onset is a smaller share: "
            f"{row['steps'] / LONG_SPAN:,.0f} steps per simulated second, {row['jacobians']} Jacobians, "
            f"{1e3 * row['cpu'] / row['steps']:.0f} ms CPU a step (load average {row['load']:.1f}): projected "
            f"{per_s:,.0f} s for 1 s, {per_s / target:.1f}× the {target:g} s target."
        )
    if "traced" in rows:
        out.append(traced_finding(rows["traced"]))
    reference = tolerance[-1]
    for options, row, d in ride_deviations(rows, tolerance):
        out.append(
            f"* The offset ride with {named(options)}: end values within {max(d.values()):.1e} of rtol "
            f"{reference[0]:g}'s ({row['steps']} steps, against {tolerance[0][1]['steps']} at rtol "
            f"{tolerance[0][0]:g} with the component scales)."
        )
    return out
