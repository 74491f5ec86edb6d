"""The in-house solver's steps on the spinning disc of validation/spin_benchmark.py: what sets them, and the
tolerance a ride needs (two tables of its report, measured by its `--only steps` and `--only tolerance`).

* **Steps** (STEP_RUNS): 193 and 1009 tiles, the benchmark's centred case, 3 ms at rtol 1e-7, 1e-5 and 1e-3,
  every accepted step traced (spin_benchmark's CHILD with trace: its time, size, error norm and the state
  component and tile of the largest scaled error ‖e_i‖/(atol_i + rtol |y_i|)). The table splits the steps
  at ONSET (the beam switched on at t = 0: the first steps are sub-microsecond) and counts, after it, the
  median step, the share of steps whose largest scaled error is a tile's angular rate about an in-plane axis
  (ω_x, ω_y in the tile's axes) and the share on the centre tile.
* **Tolerance** (TOLERANCES): 193 tiles, the benchmark's case with the beam's axis RIDE_OFFSET from the
  disc's centre (so that the ride's lateral position and tilt are not zero by symmetry), RIDE_SPAN s at each
  rtol; the ride's end values (lateral position, tilt, spin rate, shape amplitude: analysis.ride3d) and their
  differences from the tightest rtol's.
"""

from __future__ import annotations

import statistics

ONSET = 1e-4  # s: the steps before this are the beam's onset
TINY = 1e-6  # s: a step below this after the onset is counted apart (a collapse of the step size)
STEP_SPAN = 3e-3
STEP_RUNS = [(193, 1e-7), (193, 1e-5), (193, 1e-3), (1009, 1e-7), (1009, 1e-5), (1009, 1e-3)]
TOLERANCES = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7)
RIDE_SPAN = 0.1
RIDE_OFFSET = 0.02  # m: the beam's axis from the disc's centre, along x
IN_PLANE_RATES = (10, 11)  # the state's ω_x, ω_y of a tile (13 per body: u, q, v, ω_b)


def step_rows(measure) -> list:
    """(tiles, rtol, row) of STEP_RUNS, each traced."""
    return [(n, rtol, measure(n, "reduced", {"rtol": rtol}, STEP_SPAN, trace=True)) for n, rtol in STEP_RUNS]


def step_summary(row: dict) -> dict:
    """The counts of a traced run (module docstring): the onset's steps, and after it the steps below TINY (a
    collapse: when, and their median error norm) and the median step, error norm and largest error of the
    others."""
    history = row["history"]
    onset = [h for h in history if h[0] < ONSET]
    tiny = [h for h in history if h[0] >= ONSET and h[1] < TINY]
    after = [h for h in history if h[0] >= ONSET and h[1] >= TINY]
    return dict(
        onset=len(onset),
        onset_smallest=min((h[1] for h in onset), default=float("nan")),
        tiny=len(tiny),
        tiny_from=min((h[0] for h in tiny), default=float("nan")),
        tiny_to=max((h[0] for h in tiny), default=float("nan")),
        tiny_error=statistics.median(h[2] for h in tiny) if tiny else float("nan"),
        after=len(after),
        median=statistics.median(h[1] for h in after) if after else float("nan"),
        rates=sum(1 for h in after if h[3] in IN_PLANE_RATES) / max(len(after), 1),
        centre=sum(1 for h in after if h[4] == 0) / max(len(after), 1),
        error=statistics.median(h[2] for h in after) if after else float("nan"),
    )


def step_table(rows: list) -> list[str]:
    lines = [
        f"| tiles | rtol | steps < {1e3 * ONSET:g} ms (smallest) | steps < {1e6 * TINY:g} µs after it (when; median "
        f"error norm) | other steps to {1e3 * STEP_SPAN:g} ms | their median step | their median error norm "
        "| their largest error on ω_x, ω_y | on the centre tile | rejected | Jacobians | CPU per step (ms) |",
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for tiles, rtol, row in rows:
        s = step_summary(row)
        tiny = (
            f"{s['tiny']} ({1e3 * s['tiny_from']:.3g}–{1e3 * s['tiny_to']:.3g} ms; {s['tiny_error']:.2g})"
            if s["tiny"]
            else "0"
        )
        lines.append(
            f"| {tiles} | {rtol:g} | {s['onset']} ({1e9 * s['onset_smallest']:.3g} ns) | {tiny} | {s['after']} "
            f"| {1e6 * s['median']:.3g} µs | {s['error']:.2g} | {100 * s['rates']:.0f} % | {100 * s['centre']:.0f} % "
            f"| {row['rejected']} | {row['jacobians']} | {1e3 * row['cpu'] / row['steps']:.1f} |"
        )
    return lines


def tolerance_rows(measure) -> list:
    """(rtol, row) of the offset ride at each of TOLERANCES."""
    changes = dict(beam_centre=0.5 + RIDE_OFFSET)
    return [(rtol, measure(193, "reduced", {"rtol": rtol}, RIDE_SPAN, changes)) for rtol in TOLERANCES]


def end_values(row: dict) -> dict:
    """The ride's values at a run's last sample."""
    return {name: values[-1] for name, values in row["rides"].items()}


RIDE = (("lateral_x", "X (m)"), ("lateral_y", "Y (m)"), ("tilt_x", "α_x (rad)"), ("tilt_y", "α_y (rad)"))


def deviations(rows: list) -> list[dict]:
    """Per row: the relative differences of its end values from the tightest rtol's (the last row's): the lateral
    position and tilt as vectors, |Δ|/|reference|; the spin rate and shape amplitude each against its own."""
    ref = end_values(rows[-1][1])
    out = []
    for _, row in rows:
        end = end_values(row)

        def vector(a, b, end=end):
            size = (ref[a] ** 2 + ref[b] ** 2) ** 0.5
            return ((end[a] - ref[a]) ** 2 + (end[b] - ref[b]) ** 2) ** 0.5 / size

        out.append(
            dict(
                lateral=vector("lateral_x", "lateral_y"),
                tilt=vector("tilt_x", "tilt_y"),
                spin=abs(end["spin_rate"] - ref["spin_rate"]) / abs(ref["spin_rate"]),
                amplitude=abs(end["amplitude"] - ref["amplitude"]) / ref["amplitude"],
            )
        )
    return out


def tolerance_table(rows: list) -> list[str]:
    lines = [
        "| rtol | steps | rejected | Jacobians | mean step (µs) | CPU (s) | "
        + " | ".join(name for _, name in RIDE)
        + " | Ω (rad/s) | amplitude (m) | Δ lateral | Δ tilt | Δ Ω | Δ amplitude |",
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for (rtol, row), d in zip(rows, deviations(rows)):
        end = end_values(row)
        values = " | ".join(f"{end[key]:.7g}" for key, _ in RIDE)
        lines.append(
            f"| {rtol:g} | {row['steps']} | {row['rejected']} | {row['jacobians']} | "
            f"{1e6 * RIDE_SPAN / row['steps']:.3g} | {row['cpu']:.1f} | {values} | {end['spin_rate']:.9g} | "
            f"{end['amplitude']:.6g} | {d['lateral']:.1e} | {d['tilt']:.1e} | {d['spin']:.1e} | {d['amplitude']:.1e} |"
        )
    return lines


def needed_rtol(rows: list, bound: float = 1e-3) -> float | None:
    """The loosest rtol whose end values all lie within `bound` (relative) of the tightest rtol's, and every
    tighter one's too; None if only the tightest does."""
    good = None
    for (rtol, _), d in reversed(list(zip(rows, deviations(rows)))[:-1]):
        if max(d.values()) > bound:
            break
        good = rtol
    return good


COSTS = r"""
import json, math, os, sys, time
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
import numpy as np
from lightsail_mbs import SailParameters
from lightsail_mbs.model import materials
from lightsail_mbs.solvers.reduced import sheet_radau as radau
from lightsail_mbs.solvers.reduced.sheet import SheetModel
n, ny, h = json.loads(sys.argv[1])
fields = dict(model="sheet", planform="disc", n=n, ny=ny, length=1.0, width=1.0, material="silicon-nitride",
              thickness=2e-7, spin_rate=2 * math.pi * 120, intensity=1e9, beam_waist=0.4, defect_amplitude=0.0)
m = SheetModel(SailParameters(**materials.fill(fields)), frame="turning")
y = m.y0()
m.rhs(0.0, y)
def cpu(f, repeat):
    start = time.process_time()
    for _ in range(repeat):
        out = f()
    return (time.process_time() - start) / repeat, out
rhs, _ = cpu(lambda: m.rhs(1e-4, y), 50)
jacobian, J = cpu(lambda: m.jacobian(0.0, y), 2)
system, S = cpu(lambda: radau.ReducedSystem(J, m.kinematics(y), m.position_indices, m.velocity_indices), 2)
lu, pair = cpu(lambda: (radau.ReducedLU(S, radau.MU_REAL / h), radau.ReducedLU(S, radau.MU_COMPLEX / h)), 2)
b = np.random.default_rng(0).random(m.n)
real, _ = cpu(lambda: pair[0].solve(b), 20)
complex_, _ = cpu(lambda: pair[1].solve(b + 1j * b), 20)
print(json.dumps(dict(states=m.n, colours=len(m.groups), rhs=rhs, jacobian=jacobian, system=system, lu=lu,
                      real=real, complex=complex_)))
"""


def unit_costs(tiles: int, sizes: dict, h: float = 1e-4) -> dict:
    """CPU (s) of one right-hand side, one Jacobian (13 per colour of the tiles' distance-2 colouring), its
    reduced system, one LU pair (step h) and one real and one complex solve, on the benchmark's disc in the
    turning frame at its start, in a process of its own."""
    import json
    import subprocess
    import sys

    argument = json.dumps([*sizes[tiles], h])
    out = subprocess.run([sys.executable, "-c", COSTS, argument], capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def cost_table(costs: dict) -> list[str]:
    lines = [
        "| tiles | states | colours | RHS (ms) | Jacobian (ms) | reduced system (ms) | LU pair (ms) "
        "| real + complex solve (ms) | Newton iteration: 3 RHS + 2 solves (ms) |",
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for tiles, c in costs.items():
        iteration = 3 * c["rhs"] + c["real"] + c["complex"]
        lines.append(
            f"| {tiles} | {c['states']} | {c['colours']} | {1e3 * c['rhs']:.3g} | {1e3 * c['jacobian']:.0f} "
            f"| {1e3 * c['system']:.0f} | {1e3 * c['lu']:.0f} | {1e3 * (c['real'] + c['complex']):.2f} "
            f"| {1e3 * iteration:.2f} |"
        )
    return lines


def step_findings(rows: list) -> list[str]:
    """What the step table says, with its numbers."""
    import math

    out = []
    by = {(tiles, rtol): step_summary(row) for tiles, rtol, row in rows}
    raw = {(tiles, rtol): row for tiles, rtol, row in rows}
    for tiles in sorted({t for t, _ in by}):
        mine = sorted((rtol, s) for (t, rtol), s in by.items() if t == tiles)
        (r0, s0), (r1, s1) = mine[0], mine[-1]
        slope = math.log(s1["median"] / s0["median"]) / math.log(r1 / r0)
        onsets = ", ".join(f"{s['onset']}" for _, s in mine)
        rates = ", ".join(f"{100 * s['rates']:.0f} %" for _, s in mine)
        centre = ", ".join(f"{100 * s['centre']:.0f} %" for _, s in mine)
        out.append(
            f"* {tiles} tiles, rtol {r0:g} … {r1:g}: the beam's onset (t < {1e3 * ONSET:g} ms) takes {onsets} steps, "
            f"nothing against a 1 s ride; after it the median step is {1e6 * s0['median']:.3g} … "
            f"{1e6 * s1['median']:.3g} µs, ∝ rtol^{slope:.2f}, with the largest scaled error on a tile's rate "
            f"ω_x, ω_y about an in-plane axis in {rates} of those steps (on the centre tile in {centre}): the "
            "error estimate of the tiles' tilting sets the step."
        )
        for rtol, s in mine:
            if s["tiny"]:
                row = raw[(tiles, rtol)]
                out.append(
                    f"* {tiles} tiles, rtol {rtol:g}: {s['tiny']} of its {row['steps']} steps are below "
                    f"{1e6 * TINY:g} µs, between {1e3 * s['tiny_from']:.3g} and {1e3 * s['tiny_to']:.3g} ms, with a "
                    f"median error norm of {s['tiny_error']:.2g}: the error estimate does not set them; "
                    f"{row['rejected']} rejected steps and {row['jacobians']} Jacobians do (the signature of "
                    "simplified Newton not converging: a fresh Jacobian, then a halved step). The looser rtol pass "
                    "the same span with "
                    + ", ".join(f"{raw[(tiles, r)]['rejected']}" for r, _ in mine if r != rtol)
                    + " rejected steps; this is the step-size collapse that stopped the earlier run at 1.53 ms "
                    f"('step size below 9.31e-12 s'), here at {1e3 * row['cpu'] / row['steps']:.0f} ms CPU a step."
                )
    return out


def tolerance_findings(rows: list, bound: float = 1e-3) -> list[str]:
    """What the tolerance table says."""
    d = deviations(rows)
    worst = [max(x.values()) for x in d]
    good = needed_rtol(rows, bound)
    tight, loose = rows[-1][1], rows[0][1]
    out = [
        f"* The offset ride on 193 tiles over {RIDE_SPAN:g} s: the end values of rtol {rows[0][0]:g} … "
        f"{rows[-2][0]:g} differ from rtol {rows[-1][0]:g}'s by at most "
        + ", ".join(f"{w:.1e}" for w in worst[:-1])
        + " (relative; lateral position and tilt as vectors); "
        + (
            f"rtol {good:g} is the loosest within {bound:g} of it ({tight['steps']} steps at rtol "
            f"{rows[-1][0]:g}, {dict((r, row['steps']) for r, row in rows)[good]} at {good:g})"
            if good
            else f"no looser rtol is within {bound:g}"
        )
        + f"; the loosest, {rows[0][0]:g}, takes {loose['steps']} steps with {loose['jacobians']} Jacobians."
    ]
    return out
