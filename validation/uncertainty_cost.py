"""What a default run's uncertainty costs: the CPU time of each twin run against the base run, per benchmark row.

For each row of validation/benchmark.py (both solvers) the base run (``solve(..., uncertainty=False)``) and
the default run (``lightsail_mbs.solve``: the uncertainty's twins, the film twin and the n-twins) are timed
by the process's CPU time (time.process_time: the machine is shared, and CPU time is what a run costs
whatever else runs beside it), the minimum over repeats after one warm-up run. Each solver run inside the
default run is timed too and named by what it changes against the base run:

- ``base``: the base run's options (with its reruns that locate a failure between samples);
- ``loose`` / ``half`` / ``tight``: tolerances looser or tighter than the base run's (``half``: the first of
  two tighter ones, generalized-α's step / 2);
- ``probe``: a start perturbed by the seeded round-off roughness; ``film``: the case with a film;
- ``n/2``, ``n/4``: the twins of the n-error (lightsail_mbs.analysis.n_error);
- ``rest``: what is not a solver run (the resolvedness spectrum, bookkeeping).

    nice -n 10 python validation/uncertainty_cost.py --markdown validation/uncertainty_cost.md
    python validation/uncertainty_cost.py --solvers reduced --cases torsion-soft --repeats 1

The script names the runs from their options alone, so it measures any version of the rule.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import lightsail_mbs
from lightsail_mbs import paper_case, paper_settings
from lightsail_mbs.result import with_uncertainty
from lightsail_mbs.solvers import SOLVERS, contract

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
    """The row's base and default CPU times (minimum over repeats) and the default run's breakdown (of its
    fastest repeat)."""
    params, settings = paper_case(case), paper_settings(case)
    lightsail_mbs.solve(params, solver, settings, uncertainty=False)  # warm-up: compiled kernels, caches
    base = min(timed(params, solver, settings, False)[0] for _ in range(repeats))
    best = None
    for _ in range(repeats):
        with Recorder() as recorder:
            cpu, result = timed(params, solver, settings, True)
        if best is None or cpu < best[0]:
            best = (cpu, recorder.calls, result)
    cpu, calls, result = best
    parts = default_breakdown(calls)
    parts["rest"] = max(0.0, cpu - sum(parts.values()))
    u = result.uncertainty or {}
    what = "t_f" if u.get("quantity") == "failure_time" else "max ratio"
    text = f"{what} {with_uncertainty(u['value'], u['uncertainty'])}" if u.get("estimated") else "not estimated"
    return {"base": base, "default": cpu, "parts": parts, "answer": text}


def timed(params, solver, settings, uncertainty: bool):
    start = time.process_time()
    result = lightsail_mbs.solve(params, solver, settings, uncertainty=uncertainty)
    return time.process_time() - start, result


def markdown(rows) -> str:
    head = "| case | solver | base CPU (s) | default CPU (s) | default / base | " + " | ".join(KINDS) + " | answer |"
    lines = [head, "|" + "---|" * 2 + "---:|" * (3 + len(KINDS)) + "---|"]
    for r in rows:
        parts = " | ".join(f"{r['parts'][k]:.3f}" if r["parts"][k] else "—" for k in KINDS)
        ratio = r["default"] / r["base"]
        lines.append(
            f"| {r['case']} | {r['solver']} | {r['base']:.3f} | {r['default']:.3f} | {ratio:.2f} | {parts} | "
            f"{r['answer']} |"
        )
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--solvers", nargs="+", default=list(SOLVERS), choices=list(SOLVERS))
    ap.add_argument("--cases", nargs="+", default=list(CASES.values()), choices=list(CASES.values()))
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--markdown", type=Path, help="write the report (header and table) to this Markdown file")
    args = ap.parse_args(argv)
    if args.repeats < 1:
        ap.error("--repeats must be ≥ 1")
    labels = {name: label for label, name in CASES.items()}
    rows = []
    for solver in args.solvers:
        for case in args.cases:
            row = {"case": labels[case], "solver": solver, **measure(case, solver, args.repeats)}
            rows.append(row)
            print(
                f"{case:15s} {solver:8s} base {row['base']:.3f} s  default {row['default']:.3f} s  "
                f"({row['default'] / row['base']:.2f}×)  {row['answer']}",
                flush=True,
            )
    table = markdown(rows)
    print()
    print(table)
    if args.markdown:
        command = "nice -n 10 python validation/uncertainty_cost.py " + " ".join(argv or sys.argv[1:])
        args.markdown.write_text(
            "# What the uncertainty costs: CPU time per twin run\n\nGenerated by `"
            + command.strip()
            + f"`: CPU time (time.process_time) of the process, minimum of {args.repeats} repeats after a warm-up, "
            "on a shared 2-core machine. Columns after the ratio: the default run's CPU time per run it made "
            "(module docstring of validation/uncertainty_cost.py); `rest` is what is not a solver run.\n\n" + table
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
