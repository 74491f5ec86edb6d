"""Speed of the two sheet solvers: `python validation/sheet_benchmark.py [--grids 5 10 20 50 100] [--repeats 3]`.

The paper's soft sail (E = 4.5e9 Pa, 1-D sine ν = 1.5, a₀ = 10 µm) on nx × nx tiles, run to failure
(~2 s of simulated time) by each solver with its defaults (Exudyn: 1 ms step; in-house: rtol 1e-7).
Every run happens in its own fresh Python process (run twice there; the second, warm run is timed,
so numba's compilation and cache loading are left out and reported apart; grids above --once-above
tiles a side run once, that run timed, cache loading included); the table gives the CPU time of the run
(time.process_time, the least of the repeats: the machine is shared and wall times are noisy), its wall
time and CPU per step, and fits CPU ∝ N^p over the grids (N = nx² tiles). At --fast-grids Exudyn runs a
third time with its own fast module (the environment variable EXUDYN_MODULE=fast loads exudynCPPfast: no range
checks, AVX2; the same model and settings, round-off apart). The large grids take long:
run them niced (`nice -n 10 python validation/sheet_benchmark.py`); every measured row is kept in
validation/sheet_benchmark_rows.jsonl and reused by a later call (delete it to measure again). Writes
validation/sheet_benchmark.md.
"""

import argparse
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
CHILD = r"""
import json, os, sys, time
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
from lightsail_mbs import RunSettings, SailParameters, solve
grid, solver, runs = int(sys.argv[1]), sys.argv[2], int(sys.argv[3])
p = SailParameters(model="sheet", n=grid, ny=grid, youngs_modulus=4.5e9)
out = []
for k in range(runs):
    cpu, wall = time.process_time(), time.perf_counter()
    r = solve(p, solver, RunSettings(t_final=3.0), uncertainty=False)
    out.append(dict(cpu=time.process_time() - cpu, wall=time.perf_counter() - wall, failure_time=r.failure_time,
                    steps=r.info["steps"], error=r.error))
print(json.dumps(dict(first=out[0], warm=out[-1], load=os.getloadavg()[0])))
"""


FAST = "exudyn-fast"  # Exudyn with its fast module (module docstring)
LABELS = {"exudyn": "Exudyn", FAST: "Exudyn, fast module", "reduced": "in-house"}


def measure(grid: int, solver: str, runs: int = 2) -> dict:
    """The child's record of `runs` runs in one fresh process: the first, the last (warm) and the load; a
    child that dies (a signal, an exception) gives {"crashed": its exit status, "stderr": its last lines}.
    solver FAST: Exudyn in a child whose environment selects Exudyn's fast module."""
    env = dict(os.environ, EXUDYN_MODULE="fast") if solver == FAST else None
    solver = "exudyn" if solver == FAST else solver
    command = [sys.executable, "-c", CHILD, str(grid), solver, str(runs)]
    done = subprocess.run(command, capture_output=True, text=True, env=env)
    if done.returncode:
        return {"crashed": done.returncode, "stderr": done.stderr[-500:], "load": os.getloadavg()[0]}
    return json.loads(done.stdout.strip().splitlines()[-1])


def measured(path: Path, grid: int, solver: str, runs: int, processes: int) -> list[dict]:
    """The records of (grid, solver) kept in the rows file (JSON lines) from an earlier call, else measured
    now (processes fresh processes of `runs` runs each) and appended to it: the large grids take long, and
    a call that stops keeps what it measured. Delete the file to measure everything again."""
    key = {"grid": grid, "solver": solver, "runs": runs}
    if path.exists():
        for line in path.read_text().splitlines():
            row = json.loads(line)
            if {k: row[k] for k in key} == key and len(row["records"]) >= processes:
                return row["records"][:processes]
    records = [measure(grid, solver, runs) for _ in range(processes)]
    with path.open("a") as out:
        out.write(json.dumps({**key, "records": records}) + "\n")
    return records


def table_row(grid: int, solver: str, records: list[dict], once: bool) -> tuple[str, float | None]:
    """(Markdown row, least warm CPU or None when the child crashed) of one grid and solver."""
    name = LABELS[solver]
    done = [r for r in records if "crashed" not in r]
    if not done:
        status, last = records[0]["crashed"], records[0]["stderr"].strip().splitlines()[-1:]
        why = f"crashed (signal {-status})" if status < 0 else f"crashed (exit status {status})"
        if last and last[0].startswith("lightsail_mbs.base.validation.ParameterError: "):
            why = "refused: " + last[0].split(": ", 1)[1]
        return f"| {grid}×{grid} | {grid * grid} | {name} | {why} | | | | | | {len(records)} | " + (
            f"{records[0]['load']:.1f} |"
        ), None
    warm = min(done, key=lambda r: r["warm"]["cpu"])
    run = warm["warm"]
    row = (
        f"| {grid}×{grid} | {grid * grid} | {name} | {run['cpu']:.2f} | {run['wall']:.2f} | "
        f"{1e3 * run['cpu'] / max(run['steps'], 1):.2f} | "
        f"{'(run once)' if once else format(warm['first']['cpu'] - run['cpu'], '+.2f')} | "
        f"{'–' if run['failure_time'] is None else format(run['failure_time'], '.6g')} | "
        f"{run['steps']} | {len(records)} | {warm['load']:.1f} |"
    )
    return row, run["cpu"]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grids", nargs="*", type=int, default=[5, 10, 14, 20, 28, 50, 100])
    parser.add_argument("--repeats", type=int, default=3, help="processes per grid of --repeat-grids")
    parser.add_argument("--repeat-grids", nargs="*", type=int, help="grids run in --repeats processes (default: ≤ 20)")
    parser.add_argument("--fast-grids", nargs="*", type=int, default=[20, 50], help="grids with Exudyn's fast module")
    parser.add_argument("--once-above", type=int, default=28, help="grids above this run once, in one process")
    parser.add_argument("--out", default=str(HERE / "sheet_benchmark.md"))
    parser.add_argument("--rows", default=str(HERE / "sheet_benchmark_rows.jsonl"), help="measured rows (resumed)")
    args = parser.parse_args(argv)
    rows, best = [], {}
    for grid in args.grids:
        for solver in ("exudyn", FAST, "reduced") if grid in args.fast_grids else ("exudyn", "reduced"):
            once = grid > args.once_above
            repeated = grid <= 20 if args.repeat_grids is None else grid in args.repeat_grids
            processes = args.repeats if repeated else 1
            records = measured(Path(args.rows), grid, solver, 1 if once else 2, processes)
            row, cpu = table_row(grid, solver, records, once)
            rows.append(row)
            if cpu is not None:
                best[(grid, solver)] = cpu
            print(row, flush=True)
    fits = []
    for solver, label in (("exudyn", "Exudyn"), ("reduced", "in-house")):
        grids = [g for g in args.grids if (g, solver) in best]
        n = np.array([g * g for g in grids], float)
        cpu = np.array([best[(g, solver)] for g in grids])
        slope = np.polyfit(np.log(n), np.log(cpu), 1)[0] if len(n) > 1 else math.nan
        fits.append(f"* {label}: CPU ∝ N^{slope:.2f} over N = {int(n[0])}…{int(n[-1])} tiles")
    targets = [
        f"* {nx} × {nx}: {LABELS[solver]} / in-house = {best[(nx, solver)] / best[(nx, 'reduced')]:.2f} (target ≤ 2)"
        for nx in (20, 50)
        for solver in ("exudyn", FAST)
        if (nx, solver) in best and (nx, "reduced") in best
    ]
    if (100, "reduced") in best:
        targets.append(f"* 100 × 100: in-house {best[(100, 'reduced')]:.1f} s CPU to failure (target ≤ 120 s)")
    twenty = {s: best.get((20, s)) for s in ("exudyn", "reduced")}
    repeat = [g for g in args.grids if (g <= 20 if args.repeat_grids is None else g in args.repeat_grids)]
    repeated_text = "grids " + ", ".join(f"{g} × {g}" for g in repeat) if repeat else "no grid"
    command = "".join(" " + a for a in (argv if argv is not None else sys.argv[1:]))
    text = "\n".join(
        [
            "# Speed of the sheet solvers",
            "",
            f"Generated by `nice -n 10 python validation/sheet_benchmark.py{command}`. The paper's soft sail "
            "(E = 4.5e9 Pa, 1-D sine ν = 1.5) on nx × nx tiles, to failure, each solver with its defaults (Exudyn: "
            "generalized-α, 1 ms, modified Newton, sparse LU; in-house: Radau IIA, rtol 1e-7). Each run in a fresh "
            f"process, run twice, the second timed (grids above {args.once_above} a side: run once, that run "
            f"timed); {repeated_text} in {args.repeats} processes, the other grids in one; "
            "CPU = time.process_time of that run, the least of the repeats; 'first − warm' is the extra "
            "CPU of the first run in a process (numba's cache loading, Exudyn's first assembly). "
            "The machine is a shared 2-core one (load average in the last column): wall times are noisy. Every "
            "measured row is kept in validation/sheet_benchmark_rows.jsonl and reused by a later call (delete it "
            "to measure again); a child process that dies is a row that says so. 'Exudyn, fast module': the "
            "same Exudyn runs with Exudyn's fast module (EXUDYN_MODULE=fast: no range checks, AVX2), an opt-in "
            "for the whole process, not the default.",
            "",
            "| grid | tiles N | solver | CPU (s) | wall (s) | CPU per step (ms) | first − warm CPU (s) "
            "| failure time (s) | steps | repeats | load avg |",
            "|---|---|---|---|---|---|---|---|---|---|---|",
            *rows,
            "",
            *fits,
            "",
            *targets,
            "",
            f"Target (20 × 20 soft sail to failure, 2 cores): Exudyn ≤ 60 s — measured "
            f"{twenty['exudyn'] if twenty['exudyn'] is not None else float('nan'):.2f} s CPU; second solver ≤ 10 s — "
            f"measured {twenty['reduced'] if twenty['reduced'] is not None else float('nan'):.2f} s CPU.",
            "",
        ]
    )
    Path(args.out).write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
