"""Benchmark: wall time (minimum of repeats), steps and failure time of the paper cases for every solver.

    python validation/benchmark.py                      # all solvers, all cases, 3 repeats
    python validation/benchmark.py --solvers exudyn --repeats 5 --markdown bench.md
    python validation/benchmark.py --convergence        # Exudyn step/tolerance study (soft cases)
    python validation/benchmark.py --no-default         # the base runs alone
    python validation/benchmark.py --roofline           # and each row's roofline (validation/roofline.py)

Each row is the base run (``solve(..., uncertainty=False)``: what sweeps run) and, beside it, the default
run (``solve(...)``: the base run with its uncertainty estimate, the answer with its ±, its twins in worker
processes beside the base run where it is long enough: lightsail_mbs.solvers.twin_workers) and the ratios of
the two, of wall times (what a user waits) and of CPU times (what the runs cost, the workers' included).
Timings on a shared machine are noisy: the minimum over repeats is reported, the CPU time (time.process_time
and the ended child processes', what the run costs whatever else runs beside it) next to the wall time.
"""

from __future__ import annotations

import argparse
import os
import resource
import sys
import time
from pathlib import Path

from lightsail_mbs import paper_case, paper_settings, solve
from lightsail_mbs.result import with_uncertainty
from lightsail_mbs.solvers import SOLVERS, twin_workers

# label -> paper case name
CASES = {
    "torsion E=4.5e13, 6 s (stable)": "torsion-stable",
    "torsion E=4.5e9, to failure": "torsion-soft",
    "tnt T=3.34e-3 N, 6 s (stable)": "tnt-stable",
    "tnt T=3.34e-8 N, to failure": "tnt-soft",
    "rigid n=40 ν=1.5, 10 ms": "rigid",
}


def measure(name: str, solver: str, repeats: int, default: bool = True) -> dict:
    params, settings = paper_case(name), paper_settings(name)
    best, cpu = None, float("inf")
    for _ in range(repeats):
        start, start_cpu = time.perf_counter(), time.process_time()
        result = solve(params, solver, settings, uncertainty=False)
        wall = time.perf_counter() - start
        cpu = min(cpu, time.process_time() - start_cpu)
        if best is None or wall < best[0]:
            best = (wall, result)
    wall, result = best
    steps = result.info.get("steps", result.info.get("n_steps", "—"))
    ft = result.failure_time
    row = {
        "wall": wall,
        "cpu": cpu,
        "steps": steps,
        "failure": "—" if ft is None else f"{ft:.4f} s",
        "t_end": float(result.time[-1]),
        "error": result.error,
    }
    return {**row, **measure_default(params, solver, settings, repeats)} if default else row


def measure_default(params, solver: str, settings, repeats: int) -> dict:
    """The default run of a row (the base run with its uncertainty estimate): wall and CPU time (minimum of
    repeats; CPU: this process's and its twin workers') and its answer with the ±."""
    wall, cpu, result = float("inf"), float("inf"), None
    for _ in range(repeats):
        start, start_cpu = time.perf_counter(), cpu_seconds()
        result = solve(params, solver, settings)
        cpu = min(cpu, cpu_seconds() - start_cpu)
        wall = min(wall, time.perf_counter() - start)
    u = result.uncertainty or {}
    what = "t_f" if u.get("quantity") == "failure_time" else "max ratio"
    answer = f"{what} {with_uncertainty(u['value'], u['uncertainty'])}" if u.get("estimated") else "not estimated"
    return {"default_wall": wall, "default_cpu": cpu, "default_answer": answer}


def cpu_seconds() -> float:
    """CPU seconds of this process and of its children that have ended (a default run's twin workers)."""
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.process_time() + children.ru_utime + children.ru_stime


def benchmark(solvers, cases, repeats, default: bool = True) -> list[dict]:
    rows = []
    for solver in solvers:
        for case in cases:
            row = {"case": case, "solver": solver, **measure(CASES[case], solver, repeats, default)}
            rows.append(row)
            print(
                f"{case:34s} {solver:8s} wall {row['wall']:7.3f} s  cpu {row['cpu']:7.3f} s  "
                f"steps {row['steps']!s:>7}  failure {row['failure']}"
                + (f"  ERROR {row['error']}" if row["error"] else "")
                + (
                    f"  default wall {row['default_wall']:.3f} s ({row['default_wall'] / row['wall']:.2f}×) "
                    f"cpu {row['default_cpu']:.3f} s ({row['default_cpu'] / row['cpu']:.2f}×) {row['default_answer']}"
                    if default
                    else ""
                ),
                flush=True,
            )
    return rows


def convergence(cases=("torsion-soft", "tnt-soft", "rigid"), factors=(1.0, 0.5, 0.25)) -> list[dict]:
    """Failure time of the soft paper cases with the step and both Newton tolerances scaled
    together (factor 1 = the defaults), plus tight tolerances (1e-10) at the default step."""
    from lightsail_mbs.solvers.exudyn import chain as ec

    rows = []
    for case in cases:
        p, settings = paper_case(case, defect_mode=1.5), paper_settings(case)
        h, rel, abs_ = ec.default_step_size(p, settings), ec.NEWTON_REL_TOL, ec.default_abs_tol(p)
        runs = [(h * f, rel * f, abs_ * f) for f in factors] + [(h, 1e-10, 1e-10 * p.flat_force)]
        reference = None
        for step, r_tol, a_tol in runs:
            result = solve(
                p, "exudyn", settings, step_size=step, newton_rel_tol=r_tol, newton_abs_tol=a_tol, uncertainty=False
            )
            ft = result.failure_time
            reference = reference if reference is not None else ft
            change = None if ft is None or reference is None else (ft - reference) / reference
            step = result.info.get("step_size", step)  # the step actually used (divides dt)
            rows.append(
                {
                    "case": case,
                    "step": step,
                    "rel_tol": r_tol,
                    "abs_tol": a_tol,
                    "failure_time": ft,
                    "change": change,
                    "wall": result.wall_time,
                }
            )
            print(
                f"{case}: h {step:.3g} s  relTol {r_tol:.3g}  absTol {a_tol:.3g} N  failure "
                f"{ft if ft is None else round(ft, 5)} s  change "
                f"{'—' if change is None else f'{change:+.3%}'}  wall {result.wall_time:.2f} s",
                flush=True,
            )
    return rows


def markdown(rows) -> str:
    default = "default_cpu" in rows[0] if rows else False
    head = "| case | solver | wall time (s, min) | CPU time (s, min) | steps | failure time |"
    rule = "|---|---|---:|---:|---:|---:|"
    if default:
        head += (
            " default run: answer | default wall (s, min) | default CPU (s, min) | wall default / base |"
            " CPU default / base |"
        )
        rule += "---|---:|---:|---:|---:|"
    lines = [head, rule]
    for r in rows:
        fail = r["failure"] + (f" (error: {r['error']})" if r["error"] else "")
        line = f"| {r['case']} | {r['solver']} | {r['wall']:.3f} | {r['cpu']:.3f} | {r['steps']} | {fail} |"
        if default:
            line += (
                f" {r['default_answer']} | {r['default_wall']:.3f} | {r['default_cpu']:.3f} | "
                f"{r['default_wall'] / r['wall']:.2f} | {r['default_cpu'] / r['cpu']:.2f} |"
            )
        lines.append(line)
    return "\n".join(lines) + "\n"


def convergence_markdown(rows) -> str:
    lines = ["| case | step (s) | relTol | absTol (N) | failure time (s) | change |", "|---|---:|---:|---:|---:|---:|"]
    for r in rows:
        ft = "—" if r["failure_time"] is None else f"{r['failure_time']:.5f}"
        ch = "—" if r["change"] is None else f"{r['change']:+.3%}"
        lines.append(f"| {r['case']} | {r['step']:.3g} | {r['rel_tol']:.3g} | {r['abs_tol']:.3g} | {ft} | {ch} |")
    return "\n".join(lines) + "\n"


def roofline_section(repeats: int) -> str:
    """The roofline of the chain rows (validation/roofline.py, its sheet rows in validation/roofline.md) as a
    Markdown section: the work each base run does against what one core allows."""
    sys.path.insert(0, str(Path(__file__).parent))
    import roofline

    roof = roofline.machine()
    table = roofline.markdown(roofline.chain_rows(roof, repeats), roof, "", (repeats, 0)).split("\n\n", 2)[2]
    return (
        "\n## Roofline\n\n"
        "Each row's base run against one core of this machine (validation/roofline.py; its docstring counts the "
        "work): "
        f"peak {roof['flops'] / 1e9:.1f} GFlop/s (1024² DGEMM), bandwidth {roof['bandwidth'] / 1e9:.1f} GB/s; CPU the "
        f"least of {repeats} runs; the sheets' rows are in roofline.md.\n\n" + table
    )


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--solvers", nargs="+", default=list(SOLVERS), choices=list(SOLVERS))
    ap.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES), metavar="CASE")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--markdown", type=Path, help="also write the table(s) as Markdown to this file")
    ap.add_argument("--no-default", action="store_true", help="time the base runs alone (no default-run columns)")
    ap.add_argument(
        "--roofline",
        action="store_true",
        help="append the chain rows' roofline (validation/roofline.py: each base run's work against one core's limit)",
    )
    ap.add_argument(
        "--convergence",
        action="store_true",
        help="run the Exudyn step/tolerance convergence study instead of the benchmark",
    )
    args = ap.parse_args(argv)
    if args.repeats < 1:
        ap.error("--repeats must be ≥ 1")
    load = os.getloadavg()[0]
    if args.convergence:
        text = convergence_markdown(convergence())
    else:
        text = markdown(benchmark(args.solvers, args.cases, args.repeats, default=not args.no_default))
        if args.roofline:
            text += roofline_section(args.repeats)
    print()
    print(text)
    if args.markdown:
        command = "python validation/benchmark.py " + " ".join(argv if argv is not None else sys.argv[1:])
        args.markdown.write_text(
            f"Generated by `{command.strip()}` on a shared 2-core machine (load average {load:.1f} when it started, "
            f"{os.getloadavg()[0]:.1f} at the end): the minimum of {args.repeats} repeats; the "
            f"default run's twins run in worker processes beside its base run where it takes "
            f"{twin_workers.CONCURRENT_AFTER:g} s or more "
            "(lightsail_mbs.solvers.twin_workers) when a core stood idle meanwhile, so its wall time is what a user "
            "waits and its CPU time (the workers' included) what it costs; other processes' load moves the wall times "
            "more than the CPU times, and on a machine with no idle core the twins run in process.\n\n" + text
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
