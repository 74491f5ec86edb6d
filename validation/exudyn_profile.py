"""Where Exudyn's chain spends its time, against the in-house solver: `python validation/exudyn_profile.py`.

    python validation/exudyn_profile.py                         # the benchmark's chain rows, 5 repeats
    python validation/exudyn_profile.py --cases torsion-stable --repeats 3 --markdown /tmp/profile.md

For every chain row of validation/benchmark.py: the base run (`solve(..., uncertainty=False)`, the event
location included) of each solver, CPU time of this process (time.process_time, the least of the repeats
after one untimed run: the machine is shared and wall times are noisy). Then instrumented Exudyn runs (the
one of least CPU of as many as the repeats):
Exudyn's own timers (SimulationSettings.show.computationTime; they read the wall clock), the force user
function's calls and the CPU spent inside it, the CPU of the post-step sampler (solvers.exudyn.sampler), and
the CPU of the whole solver call; Exudyn's own CPU (that call less the Python it calls) is apportioned by its
timers.

Exudyn's own work is the C++ part of its steps: the tree's mass matrix, its right-hand side (the tree's
forces and the call of the Python force function, less the CPU inside that function), the linear solves
and the integration formula. That part over the in-house solver's whole run is the floor of the ratio that
this formulation (the KinematicTree in minimal coordinates, the steps the integrator takes) can reach when
every line of Python around Exudyn costs nothing. Writes validation/exudyn_profile.md with --markdown.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

from lightsail_mbs import paper_case, paper_settings, solve
from lightsail_mbs.solvers.exudyn import chain

HERE = Path(__file__).resolve().parent
CASES = {  # paper case -> label (validation/benchmark.py's rows)
    "torsion-stable": "torsion E=4.5e13, 6 s (stable)",
    "torsion-soft": "torsion E=4.5e9, to failure",
    "tnt-stable": "tnt T=3.34e-3 N, 6 s (stable)",
    "tnt-soft": "tnt T=3.34e-8 N, to failure",
    "rigid": "rigid n=40 ν=1.5, 10 ms",
}
TIMERS = ("massMatrix", "ODE2RHS", "factorization", "newtonIncrement", "integrationFormula", "totalJacobian")


class Instruments:
    """Counters the instrumented run fills: Exudyn's solvers (their timers), the force function's calls
    and CPU, the post-step sampler's CPU."""

    def __init__(self):
        self.solvers, self.force_calls, self.force_cpu, self.sampler_cpu, self.solve_cpu = [], 0, 0.0, 0.0, 0.0

    def install(self):
        """Wrap chain's force function, solver call and sampler; returns the undo function."""
        originals = (chain.generalized_force, chain._solve, chain.Sampler)
        counters = self

        def generalized_force(p, layout, *beam_factor_of):
            force = originals[0](p, layout, *beam_factor_of)

            def timed(q, q_t=None, t=0.0):
                counters.force_calls += 1
                start = time.process_time()
                out = force(q, q_t, t)
                counters.force_cpu += time.process_time() - start
                return out

            return timed

        def solve_timed(mbs, s, method, sample, bar):
            s.show.computationTime = True
            start = time.process_time()
            made = originals[1](mbs, s, method, sample, bar)
            counters.solve_cpu += time.process_time() - start
            counters.solvers.append(made[0])
            return made

        class Sampler(originals[2]):
            def __call__(self, mbs, t):
                start = time.process_time()
                go_on = super().__call__(mbs, t)
                counters.sampler_cpu += time.process_time() - start
                return go_on

        chain.generalized_force, chain._solve, chain.Sampler = generalized_force, solve_timed, Sampler

        def undo():
            chain.generalized_force, chain._solve, chain.Sampler = originals

        return undo

    def timer(self, name: str) -> float:
        return sum(getattr(s.timer, name) for s in self.solvers)


def base_cpu(case: str, solver: str, repeats: int):
    """(least CPU s, Result) of the base run of a paper case, after one untimed run."""
    params, settings = paper_case(case), paper_settings(case)
    result = solve(params, solver, settings, uncertainty=False)
    best = float("inf")
    for _ in range(repeats):
        start = time.process_time()
        result = solve(params, solver, settings, uncertainty=False)
        best = min(best, time.process_time() - start)
    return best, result


def profile(case: str, repeats: int) -> dict:
    """The row of one case: both solvers' CPU and the instrumented Exudyn run's breakdown."""
    inhouse, reduced = base_cpu(case, "reduced", repeats)
    exudyn, result = base_cpu(case, "exudyn", repeats)
    counters, instrumented = None, float("inf")
    for _ in range(repeats):  # the instrumented run of least CPU
        trial = Instruments()
        undo = trial.install()
        try:
            start = time.process_time()
            solve(paper_case(case), "exudyn", paper_settings(case), uncertainty=False)
            cpu = time.process_time() - start
        finally:
            undo()
        if cpu < instrumented:
            counters, instrumented = trial, cpu
    timers = {name: counters.timer(name) for name in TIMERS}
    parts = {  # Exudyn's timers (wall clock) of its C++ work
        "mass": timers["massMatrix"],
        "rhs": max(timers["ODE2RHS"] - counters.force_cpu, 0.0),
        "linear": timers["factorization"] + timers["newtonIncrement"] + timers["totalJacobian"],
        "formula": timers["integrationFormula"],
    }
    # the CPU inside Exudyn's solver less the Python it calls, apportioned by those timers
    own = counters.solve_cpu - counters.force_cpu - counters.sampler_cpu
    total = sum(parts.values()) or 1.0
    runs = len(counters.solvers)
    return {
        "case": case,
        "inhouse": inhouse,
        "inhouse_info": reduced.info,
        "exudyn": exudyn,
        "info": result.info,
        "runs": runs,
        "instrumented": instrumented,
        **{name: own * value / total for name, value in parts.items()},
        "own": own,
        "force_calls": counters.force_calls,
        "force_cpu": counters.force_cpu,
        "sampler": counters.sampler_cpu,
        "rest": instrumented - own - counters.force_cpu - counters.sampler_cpu,
    }


def markdown(rows: list[dict], repeats: int) -> str:
    head = [
        "# Where Exudyn's chain spends its time",
        "",
        "Generated by `python validation/exudyn_profile.py --markdown validation/exudyn_profile.md`. Base runs "
        "(no uncertainty; the event location included) of the benchmark's chain rows, CPU time of the process "
        f"(time.process_time, the least of {repeats} repeats after one untimed run; load average "
        f"{os.getloadavg()[0]:.1f} on {os.cpu_count()} cores at the end). The breakdown is the instrumented "
        "Exudyn run of least CPU of as many: the CPU inside Exudyn's solver less the Python it calls (the "
        "force function's and the post-step sampler's CPU, measured around them), apportioned by Exudyn's "
        "own timers (wall clock) to the tree's mass matrix, its right-hand side (less the force function), "
        "the linear algebra (factorisation, Newton increment, Jacobian) and the integration formula; the rest "
        "(building the system, assembling the Result, the failure check) is the remainder. 'Floor' is Exudyn's own C++ "
        "work over the in-house run: the ratio left if every line of Python around Exudyn cost nothing.",
        "",
        "| case | in-house CPU (s) | Exudyn CPU (s) | ratio | Exudyn runs · steps · Newton it. · Jacobians "
        "| mass matrix (s) | C++ RHS (s) | linear algebra (s) | force calls · CPU (s) | sampler (s) | rest (s) "
        "| floor |",
        "|---|---:|---:|---:|---|---:|---:|---:|---|---:|---:|---:|",
    ]
    lines = []
    for r in rows:
        info = r["info"]
        counts = f"{r['runs']} · {info['steps']} · {info['newton_iterations']} · {info['njev']}"
        lines.append(
            f"| {CASES[r['case']]} | {r['inhouse']:.4f} | {r['exudyn']:.4f} | {r['exudyn'] / r['inhouse']:.1f}× "
            f"| {counts} | {r['mass']:.4f} | {r['rhs']:.4f} | {r['linear']:.4f} "
            f"| {r['force_calls']} · {r['force_cpu']:.4f} | {r['sampler']:.4f} | {r['rest']:.4f} "
            f"| {r['own'] / r['inhouse']:.1f}× |"
        )
    notes = [
        "",
        "Steps, Newton iterations and Jacobians are those of the reported run (the last, when the event location "
        "reran it); the timers and counts sum over every run.",
    ]
    return "\n".join(head + lines + notes) + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--markdown", type=Path, help="write the table to this file (validation/exudyn_profile.md)")
    args = parser.parse_args(argv)
    if args.repeats < 1:
        parser.error("--repeats must be ≥ 1")
    rows = []
    for case in args.cases:
        rows.append(profile(case, args.repeats))
        r = rows[-1]
        print(
            f"{case:15s} in-house {r['inhouse']:.4f} s  exudyn {r['exudyn']:.4f} s  "
            f"({r['exudyn'] / r['inhouse']:.1f}x, floor {r['own'] / r['inhouse']:.1f}x)",
            flush=True,
        )
    text = markdown(rows, args.repeats)
    print(text)
    if args.markdown:
        args.markdown.write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
