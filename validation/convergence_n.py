"""Convergence in n of the paper's cases: what the answers at the paper's n = 30/40 really are.

    python validation/convergence_n.py                       # all cases, writes validation/convergence_n.md
    python validation/convergence_n.py --cases rigid,torsion-soft --max-n 960 --out /tmp/conv.md

For each case the reduced solver runs at n doubling from the first size up to --max-n (and --max-n itself),
each run repeated at rtol/10 for the tolerance noise (studies.convergence.converge), and stops refining
once one run takes over a quarter of --budget CPU seconds. The report has one summary table and one table
per case (the same as `lightsail-mbs converge --case NAME --n-start N0 --n-max 3000`).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from lightsail_mbs import paper_case, paper_settings
from lightsail_mbs.studies import convergence

# key -> (label, paper case, changes, first n, the paper's n)
CASES = {
    "torsion-soft": ("soft torsion (paper Fig. 7; E = 4.5e9 Pa, r ≈ 0.01)", "torsion-soft", {}, 15, 30),
    "torsion-stable": ("stable torsion (paper Fig. 6; E = 4.5e13 Pa)", "torsion-stable", {}, 15, 30),
    "torsion-r1": ("torsion, E = 4.5e11 Pa (r ≈ 1)", "torsion-soft", dict(youngs_modulus=4.5e11), 15, 30),
    "tnt-soft": ("soft TnT (paper Fig. 11; T = 3.34e-8 N, no bending)", "tnt-soft", {}, 15, 30),
    "tnt-stable": ("stable TnT (paper Fig. 10; T = 3.34e-3 N, no bending)", "tnt-stable", {}, 15, 30),
    "rigid": ("rigid, ν = 3/2 (paper Fig. 5)", "rigid", {}, 10, 40),
}
UNITS = {"failure_time": "t_f", "max_amplitude_ratio": "max a/a₀"}


def fmt(value, spec=".6g"):
    return "—" if value is None else format(value, spec)


def summary_row(label, study, paper_n) -> str:
    rows = study.rows
    at_paper = next((r for r in rows if r.n == paper_n), None)
    finest = rows[-1]
    fit = study.fit
    paper_error = "—"  # against the limit; a study that gives none (not converging) is compared with nothing
    if at_paper is not None and at_paper.value is not None and fit.limit:
        paper_error = f"{(at_paper.value - fit.limit) / fit.limit:+.1%}"
    kind = UNITS[finest.kind]
    return (
        f"| {label} | {kind} | {rows[0].n}–{finest.n} | {fmt(at_paper.value if at_paper else None)} "
        f"| {fmt(finest.value)} | {fmt(fit.limit)} | {paper_error} | {fmt(fit.order, '.2f')} "
        f"| {fmt(fit.n_for_one_percent, '.0f')} | {fmt(study.empirical_n_for_one_percent)} "
        f"| {fmt(study.tolerance_noise, '.1e')} | {fit.verdict} |"
    )


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", default=",".join(CASES), help="comma-separated keys of CASES")
    parser.add_argument("--max-n", type=int, default=3000)
    parser.add_argument("--budget", type=float, default=240.0, help="CPU seconds per case, roughly")
    parser.add_argument("--out", default=str(Path(__file__).with_name("convergence_n.md")))
    args = parser.parse_args()
    summary, sections = [], []
    start = time.perf_counter()
    for key in args.cases.split(","):
        label, name, changes, n0, paper_n = CASES[key]
        print(f"\n{label}", flush=True)

        def report(row):
            noise = "—" if row.tolerance_noise is None else f"{row.tolerance_noise:.1e}"
            print(f"  n = {row.n}: {row.value} ({noise}; {row.method}, {row.cpu_time:.3g} s CPU)", flush=True)

        sizes = convergence.geometric_sizes(n0, args.max_n)
        study = convergence.converge(
            paper_case(name, **changes), paper_settings(name), sizes, budget=args.budget, progress=report
        )
        summary.append(summary_row(label, study, paper_n))
        sections.append(f"### {label}\n\n{convergence.markdown_table(study)}\n")
    text = [
        "| case | answer | n | at the paper's n | at the largest n | limit (fit) | paper's n vs limit "
        "| order p | n for 1 % (fit) | n for 1 % (direct) | tolerance noise | verdict |",
        "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|",
        *summary,
        "",
        f"Reduced solver, default tolerances; tolerance noise: the largest change of the answer when a run is "
        f"repeated at rtol/10. {time.perf_counter() - start:.0f} s wall for the whole report.",
        "",
        *sections,
    ]
    Path(args.out).write_text("\n".join(text))
    print("\n".join(text[: len(summary) + 2]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
