"""What a default run's uncertainty costs: the CPU time of each twin run against the base run, per benchmark row,
and the wall time of the default run with its twins in worker processes.

For each row of validation/benchmark.py (both solvers) the base run (``solve(..., uncertainty=False)``) and
the default run (``lightsail_mbs.solve``: the uncertainty's twins, the film twin and the n-twins) are timed
by CPU time (time.process_time, with the worker processes' own: the machine is shared, and CPU time is what a
run costs whatever else runs beside it), the minimum over repeats after one warm-up run. The breakdown runs
every twin in this process (twin_workers.CONCURRENT_AFTER = inf), each solver run timed and named by what it
changes against the base run:

- ``base``: the base run's options (with its reruns that locate a failure between samples);
- ``loose`` / ``half`` / ``tight``: tolerances looser or tighter than the base run's (``half``: the first of
  two tighter ones, generalized-α's step / 2);
- ``probe``: a start perturbed by the seeded round-off roughness; ``film``: the case with a film;
- ``n/2``, ``n/4``: the twins of the n-error (lightsail_mbs.analysis.n_error);
- ``rest``: what is not a solver run (the resolvedness spectrum, bookkeeping).

The default run as it runs for a user (its twins in worker processes beside the base run where the base run
is long enough: lightsail_mbs.solvers.twin_workers) is timed by wall clock (time.perf_counter, minimum over
repeats) against the base run's, with its CPU time (this process and its workers). ``bound`` is the wall-time
ratio two idle cores allow at best, max(base, default CPU / 2) / base of the CPU times: no schedule of the same
runs on two cores can do better.

    nice -n 10 python validation/uncertainty_cost.py --markdown validation/uncertainty_cost.md
    python validation/uncertainty_cost.py --solvers reduced --cases torsion-soft --repeats 1
    python validation/uncertainty_cost.py --solvers exudyn --force-workers   # the workers' CPU on a busy machine

The script names the runs from their options alone, so it measures any version of the rule.
"""

from __future__ import annotations

import argparse
import math
import os
import resource
import sys
import time
from pathlib import Path

import lightsail_mbs
from lightsail_mbs import paper_case, paper_settings
from lightsail_mbs.result import with_uncertainty
from lightsail_mbs.solvers import SOLVERS, contract, twin_workers

CASES = {  # label -> paper case (validation/benchmark.py's rows)
    "torsion E=4.5e13, 6 s (stable)": "torsion-stable",
    "tnt T=3.34e-3 N, 6 s (stable)": "tnt-stable",
    "torsion E=4.5e9, to failure": "torsion-soft",
    "tnt T=3.34e-8 N, to failure": "tnt-soft",
    "rigid n=40 ν=1.5, 10 ms": "rigid",
}
KINDS = ("base", "loose", "half", "tight", "probe", "film", "n/2", "n/4", "rest")
TOLERANCES = ("rtol", "step_size")


class Recorder:
    """Times every solver run (contract.Solver.run) while installed: (case, options, its rtol or fixed step,
    CPU seconds)."""

    def __init__(self):
        self.calls = []
        self.original = contract.Solver.run

    def __enter__(self):
        recorder = self

        def run(solver, params, settings, *, progress=False, **options):
            start = time.process_time()
            result = recorder.original(solver, params, settings, progress=progress, **options)
            accuracy = result.info.get("rtol", result.info.get("step_size"))
            recorder.calls.append((params, options, accuracy, time.process_time() - start))
            return result

        contract.Solver.run = run
        return self

    def __exit__(self, *exc):
        contract.Solver.run = self.original


def kind(call, base) -> str:
    """What a run inside the default run is (module docstring), from its case, options and rtol (or fixed step)
    against the base run's (`base`: the first call)."""
    params, options, accuracy, _ = call
    base_params, _, base_accuracy, _ = base
    if params.n != base_params.n:
        return "n/2" if 2 * params.n >= base_params.n - 1 else "n/4"
    if params.film_rms != base_params.film_rms or params.film_seed != base_params.film_seed:
        return "film"
    if options.get("perturbation"):
        return "probe"
    if accuracy is not None and base_accuracy is not None and accuracy != base_accuracy:
        return "loose" if accuracy > base_accuracy else "tight"
    return "base"


def default_breakdown(calls) -> dict:
    """CPU seconds per kind of run (the first call is the base run); ``half``: the looser of two tighter runs."""
    out = dict.fromkeys(KINDS, 0.0)
    tighter = sorted({call[2] for call in calls if kind(call, calls[0]) == "tight"})
    for call in calls:
        name = kind(call, calls[0])
        if name == "tight" and len(tighter) > 1 and call[2] == tighter[-1]:
            name = "half"
        out[name] += call[3]
    return out


def measure(case: str, solver: str, repeats: int) -> dict:
    """The row's base and default CPU times (minimum over repeats), the default run's breakdown (of its fastest
    repeat, every twin in this process), and the wall times of the base run and of the default run with its
    twins in workers (minimum over repeats) with that run's CPU time."""
    params, settings = paper_case(case), paper_settings(case)
    lightsail_mbs.solve(params, solver, settings, uncertainty=False)  # warm-up: compiled kernels, caches
    bases = [timed(params, solver, settings, False) for _ in range(repeats)]
    best, after = None, twin_workers.CONCURRENT_AFTER
    twin_workers.CONCURRENT_AFTER = math.inf  # the breakdown: every twin in this process
    try:
        for _ in range(repeats):
            with Recorder() as recorder:
                cpu, _, result = timed(params, solver, settings, True)
            if best is None or cpu < best[0]:
                best = (cpu, recorder.calls, result)
    finally:
        twin_workers.CONCURRENT_AFTER = after
    concurrent = min((timed(params, solver, settings, True)[:2] for _ in range(repeats)), key=lambda run: run[1])
    cpu, calls, result = best
    parts = default_breakdown(calls)
    parts["rest"] = max(0.0, cpu - sum(parts.values()))
    u = result.uncertainty or {}
    what = "t_f" if u.get("quantity") == "failure_time" else "max ratio"
    text = f"{what} {with_uncertainty(u['value'], u['uncertainty'])}" if u.get("estimated") else "not estimated"
    return {
        "base": min(b[0] for b in bases),
        "default": cpu,
        "parts": parts,
        "answer": text,
        "base_wall": min(b[1] for b in bases),
        "concurrent_cpu": concurrent[0],
        "concurrent_wall": concurrent[1],
    }


def cpu_seconds() -> float:
    """CPU seconds of this process and of its children that have ended (the twins' workers)."""
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.process_time() + children.ru_utime + children.ru_stime


def timed(params, solver, settings, uncertainty: bool):
    """(CPU s, wall s, Result) of one solve."""
    start, start_wall = cpu_seconds(), time.perf_counter()
    result = lightsail_mbs.solve(params, solver, settings, uncertainty=uncertainty)
    return cpu_seconds() - start, time.perf_counter() - start_wall, result


def markdown(rows) -> str:
    head = (
        "| case | solver | base CPU (s) | default CPU (s) | default / base | "
        + " | ".join(KINDS)
        + " | answer | base wall (s) | default wall, twins in workers (s) | its CPU (s) | wall default / base | "
        "bound (2 cores) |"
    )
    lines = [head, "|" + "---|" * 2 + "---:|" * (3 + len(KINDS)) + "---|" + "---:|" * 5]
    for r in rows:
        parts = " | ".join(f"{r['parts'][k]:.3f}" if r["parts"][k] else "—" for k in KINDS)
        bound = max(r["base"], r["default"] / 2) / r["base"]
        lines.append(
            f"| {r['case']} | {r['solver']} | {r['base']:.3f} | {r['default']:.3f} | {r['default'] / r['base']:.2f} | "
            f"{parts} | {r['answer']} | {r['base_wall']:.3f} | {r['concurrent_wall']:.3f} | "
            f"{r['concurrent_cpu']:.3f} | {r['concurrent_wall'] / r['base_wall']:.2f} | {bound:.2f} |"
        )
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--solvers", nargs="+", default=list(SOLVERS), choices=list(SOLVERS))
    ap.add_argument("--cases", nargs="+", default=list(CASES.values()), choices=list(CASES.values()))
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--markdown", type=Path, help="write the report (header and table) to this Markdown file")
    ap.add_argument(
        "--force-workers",
        action="store_true",
        help="the default run's twins in workers even where no core stood idle (MIN_IDLE_CORES = 0): their CPU "
        "time, forks included, on a loaded machine (its wall times then mean nothing)",
    )
    args = ap.parse_args(argv)
    if args.repeats < 1:
        ap.error("--repeats must be ≥ 1")
    labels = {name: label for label, name in CASES.items()}
    if args.force_workers:
        twin_workers.MIN_IDLE_CORES = 0.0
    rows, load = [], os.getloadavg()
    for solver in args.solvers:
        for case in args.cases:
            row = {"case": labels[case], "solver": solver, **measure(case, solver, args.repeats)}
            rows.append(row)
            print(
                f"{case:15s} {solver:8s} base {row['base']:.3f} s  default {row['default']:.3f} s  "
                f"({row['default'] / row['base']:.2f}×)  {row['answer']}  wall: base {row['base_wall']:.3f} s, "
                f"default {row['concurrent_wall']:.3f} s ({row['concurrent_wall'] / row['base_wall']:.2f}×)",
                flush=True,
            )
    table = markdown(rows)
    print()
    print(table)
    if args.markdown:
        command = "nice -n 10 python validation/uncertainty_cost.py " + " ".join(argv or sys.argv[1:])
        args.markdown.write_text(
            "# What the uncertainty costs: CPU time per twin run, and wall time with the twins in workers\n\n"
            f"Generated by `{command.strip()}`: CPU time of the process and its worker processes, minimum of "
            f"{args.repeats} repeats after a warm-up, on a shared 2-core machine (load average {load[0]:.1f} when it "
            f"started, {os.getloadavg()[0]:.1f} at the end: with other processes running, the wall times are upper "
            "bounds). Columns after the ratio: the default run's CPU time per run it made, every twin in this process "
            "(module docstring of validation/uncertainty_cost.py); `rest` is what is not a solver run. The last "
            "five: the base run's wall time; the default run's, its twins in worker processes beside the base run "
            "(lightsail_mbs.solvers.twin_workers), and its CPU time; their ratio; and the ratio two idle cores allow "
            "at best, max(base, default CPU / 2) / base.\n\n" + table
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
