"""The n-error a single run prints, against the converged answers of `converge`, on well-posed seeded cases.

Writes validation/n_error.md. A run at n slices carries, when its case is well posed in n (the resolvedness
verdict, lightsail_mbs.analysis.resolvedness), an estimate E_n of the distance of its answer from the
continuum answer (lightsail_mbs.analysis.n_error). This script measures the candidates on cases whose
converged answer `converge` finds (studies.convergence.converge, reduced solver, n doubling up to N_MAX):

- **the package's rule** (lightsail_mbs.analysis.n_error: twins at n/2 and, where it draws the defect, n/4):
  2 |q(n) − q(n/2)| where the three answers shrink as a power law of order 1–8 or there is no twin at n/4, else
  twice the larger of the two changes; without the twin at n/4, for a failure time at the grid scale, at least
  the spectrum's estimate; for a largest amplitude ratio, at least the rise its recurrences may make above it
  (n_error.recurrence_rise, from the amplitude histories at n and n/2);
- **twin n/2, order 1**: E_n = |q(n) − q(n/2)| / (2^p − 1), p = 1 (Richardson's estimate alone);
- **twin 2n/3, order 1**: E_n = |q(n) − q(⌊2n/3⌋)| / ((n/⌊2n/3⌋)^p − 1), p = 1;
- **twin n/2, order 2**: the same at p = 2 (the order the soft sail reaches from n ≈ 120);
- **spectrum**: q · |σ(n) − σ(2n)|/σ(2n) (failure times only; the verdict's ``relative_n_error``).

The reference is converge's fitted limit where it accepts a power law, else its finest answer (the row says
which). A candidate covers a row when E_n ≥ |q(n) − reference|. Cases: the paper's well-posed chains (soft,
stable and stiff torsion, torsion at E = E_cr,max, the stable membrane) at n = 30–240, and the seeded random
cases of validation/accuracy.py whose verdict is well posed (the first RANDOM_CASES), at their own n. Every
answer is the reduced solver's base run at its default tolerances (no twins: the n-error is the subject).

    nice -n 10 python validation/n_error.py             # writes validation/n_error.md (rows: n_error_rows.jsonl)
    nice -n 10 python validation/n_error.py --resume    # reuses the finished cases of n_error_rows.jsonl
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

from lightsail_mbs import paper_case, paper_settings, solve
from lightsail_mbs.analysis import n_error, resolvedness
from lightsail_mbs.model import theory
from lightsail_mbs.studies import convergence

sys.path.insert(0, str(Path(__file__).parent))
from accuracy import describe, random_case  # noqa: E402

ROWS = Path(__file__).with_name("n_error_rows.jsonl")
N_MAX = 1920  # converge's largest n
BUDGET = 120.0  # CPU seconds per case, roughly (converge stops refining once one run takes a quarter)
RANDOM_CASES = 16  # the first this many well-posed seeded cases of accuracy.py


def soft(name: str, **changes):
    return paper_case(name, **changes), paper_settings(name)


def at_critical_modulus():
    p = paper_case("torsion-soft")
    return p.replace(youngs_modulus=theory.critical_modulus_max(p)), paper_settings("torsion-soft")


PAPER = {  # key -> (label, case, the n to estimate at)
    "torsion-soft": (
        "soft torsion (Fig. 7, E = 4.5e9 Pa ≈ 0.01 E_cr,max)",
        lambda: soft("torsion-soft"),
        (30, 60, 120, 240),
    ),
    "torsion-stable": ("stable torsion (Fig. 6)", lambda: soft("torsion-stable"), (30, 60, 120)),
    "torsion-r1": (
        "torsion, E = 4.5e11 Pa (≈ 0.99 E_cr,max)",
        lambda: soft("torsion-soft", youngs_modulus=4.5e11),
        (30, 60, 120),
    ),
    "torsion-critical": ("torsion, E = E_cr,max", at_critical_modulus, (30, 60, 120)),
    "tnt-stable": ("stable TnT (Fig. 10)", lambda: soft("tnt-stable"), (30, 60)),
}


def value_of(result) -> tuple[float | None, str]:
    return convergence.answer(result)


def run_value(p, settings) -> tuple[float | None, str]:
    return value_of(solve(p, "reduced", settings, uncertainty=False))


def recurrence_rise(p, settings, n: int) -> float:
    """The package rule's recurrences' rise (n_error.recurrence_rise) of the case at n, from base runs at n and n/2."""
    fine, coarse = (solve(p.replace(n=size), "reduced", settings, uncertainty=False) for size in (n, n // 2))
    return n_error.recurrence_rise(fine.time, fine.amplitude, coarse.time, coarse.amplitude)


def add_rises(case: dict, p, settings) -> bool:
    """Record the recurrences' rise in each row of `case` whose answer is a largest amplitude ratio and that lacks
    it (rows of an earlier version of this script); whether any was added."""
    missing = [
        row
        for row in case["rows"]
        if not row.get("skipped") and row["kind"] == "max_amplitude_ratio" and "rise" not in row
    ]
    for row in missing:
        row["rise"] = recurrence_rise(p, settings, row["n"])
    return bool(missing)


def candidates(row: dict, p) -> dict:
    """E_n of every candidate (module docstring) from a row's answer and its twins' ({size: (value, kind)}); `p`:
    the case (the package's rule runs the twin at n/4 only where it draws the defect)."""
    q, n, kind = row["value"], row["n"], row["kind"]
    out = {}
    for name, size, order in (("half_p1", n // 2, 1.0), ("two_thirds_p1", (2 * n) // 3, 1.0), ("half_p2", n // 2, 2.0)):
        value, twin_kind = row["twins"][str(size)]
        out[name] = math.inf if value is None or twin_kind != kind else abs(q - value) / ((n / size) ** order - 1.0)
    quarter, quarter_kind = row["twins"][str(n // 4)]
    half, half_kind = row["twins"][str(n // 2)]
    if half is None or half_kind != kind:
        out["package"] = math.inf
    else:
        usable = quarter_kind == kind and n // 4 in n_error.twin_sizes(p.replace(n=n))
        estimate = n_error.estimate(q, half, quarter if usable else None, ratio=kind == "max_amplitude_ratio")
        if "slices_per_wavelength" not in row:
            row["slices_per_wavelength"] = resolvedness.assess(p.replace(n=n)).slices_per_wavelength
        verdict = {"slices_per_wavelength": row["slices_per_wavelength"], "relative_n_error": row["spectrum"]}
        floor = 0.0 if usable else n_error.spectral_floor(verdict, q, kind == "failure_time")
        out["package"] = max(estimate, floor, row.get("rise") or 0.0)
    out["spectrum"] = q * row["spectrum"] if row["spectrum"] is not None and kind == "failure_time" else None
    return out


def run_case(key: str, label: str, p, settings, sizes_at) -> dict:
    """One case: converge's sequence from min(n)/2 to N_MAX, the twins at 2n/3, the candidates at each n."""
    start = time.process_time()
    first = min(sizes_at) // 2
    sizes = convergence.geometric_sizes(first, max(N_MAX, 16 * first))
    sizes = [s for s in sizes if s <= N_MAX] or sizes[:1]
    study = convergence.converge(p, settings, sizes, budget=BUDGET)
    answers = {row.n: (row.value, row.kind) for row in study.rows}
    fit = study.fit
    finest = study.rows[-1]
    accepted = fit.verdict in convergence.CONVERGED and fit.limit is not None
    reference = fit.limit if accepted else finest.value
    rows = []
    for n in sizes_at:
        for size in (n // 4, n // 2, (2 * n) // 3, n):
            if size not in answers:
                answers[size] = run_value(p.replace(n=size), settings)
        q, kind = answers[n]
        verdict = resolvedness.assess(p.replace(n=n))
        if q is None or kind != finest.kind:
            rows.append({"n": n, "value": q, "kind": kind, "well_posed": verdict.well_posed, "skipped": True})
            continue
        rows.append(
            {
                "n": n,
                "value": q,
                "kind": kind,
                "well_posed": verdict.well_posed,
                "error": q - reference,
                "spectrum": verdict.relative_n_error,
                "slices_per_wavelength": verdict.slices_per_wavelength,
                "twins": {str(size): answers[size] for size in (n // 4, n // 2, (2 * n) // 3)},
            }
        )
    case = {
        "key": key,
        "label": label,
        "sizes": [row.n for row in study.rows],
        "answers": [row.value for row in study.rows],
        "verdict": fit.verdict,
        "order": fit.order,
        "reference": reference,
        "reference_kind": "fit" if accepted else f"finest (n = {finest.n})",
        "rows": rows,
    }
    add_rises(case, p, settings)
    case["cpu"] = time.process_time() - start
    return case


def well_posed_seeds(count: int) -> list[int]:
    """The first `count` seeds of accuracy.py's random cases (rigid ones excluded: never well posed) whose
    verdict at their n is well posed."""
    seeds = []
    for seed in range(96):
        p, _ = random_case(seed)
        if p.model == "rigid":
            continue
        if resolvedness.assess(p).well_posed:
            seeds.append(seed)
        if len(seeds) == count:
            break
    return seeds


def covered(row: dict, name: str) -> bool | None:
    estimate = row["candidates"].get(name)
    return None if estimate is None else estimate >= abs(row["error"])


NAMES = {
    "package": "package rule",
    "half_p1": "twin n/2, p = 1",
    "two_thirds_p1": "twin 2n/3, p = 1",
    "half_p2": "twin n/2, p = 2",
    "spectrum": "spectrum",
}


def fmt(value, spec=".3g") -> str:
    if value is None:
        return "—"
    if isinstance(value, float) and math.isinf(value):
        return "∞"
    return format(value, spec)


def markdown(cases: list[dict], params: dict) -> str:
    """The report; `params`: each case's SailParameters by key."""
    for case in cases:
        for row in case["rows"]:
            if not row.get("skipped"):
                row["candidates"] = candidates(row, params[case["key"]])
    rows = [(case, row) for case in cases for row in case["rows"] if not row.get("skipped") and row["well_posed"]]
    lines = [
        "# The n-error of a single run against converged answers",
        "",
        "Generated by `nice -n 10 python validation/n_error.py` "
        f"({sum(c['cpu'] for c in cases) / 60:.0f} min of CPU time on the shared machine). Reduced solver at its "
        "default tolerances; the reference is `converge`'s fitted limit (n "
        f"doubling up to {N_MAX}) where it accepts a power law, else its finest answer. Covered: E_n ≥ "
        "|q(n) − reference|. Rows of runs whose verdict at n is ill-posed are left out (they print no n-error). "
        "The package's rule is applied here to twins at the default tolerances against the base run; a default run "
        "(solvers.uncertainty) runs them at its loose twin's options against the loose twin's answer. That moves the "
        "answer at n by the loose twin's change (on the paper's soft sail at n = 30 inside the numerical ± of 2e-5 s, "
        "against E_n = 0.16 s: validation/roughness.md) and each twin by its own, not measured here.",
        "",
        "## Coverage",
        "",
        "| candidate | covered | median E_n / error | smallest E_n / error | median E_n / q |",
        "|---|---:|---:|---:|---:|",
    ]
    for name, text in NAMES.items():
        judged = [(c, r) for c, r in rows if covered(r, name) is not None]
        hits = sum(covered(r, name) for _, r in judged)
        margins = sorted(
            r["candidates"][name] / abs(r["error"]) for _, r in judged if r["error"] and math.isfinite(r["error"])
        )
        relative = sorted(r["candidates"][name] / abs(r["value"]) for _, r in judged if r["value"])
        lines.append(
            f"| {text} | {hits} of {len(judged)} | {fmt(margins[len(margins) // 2]) if margins else '—'} "
            f"| {fmt(margins[0]) if margins else '—'} | {fmt(relative[len(relative) // 2]) if relative else '—'} |"
        )
    misses = [f"{c['label']} at n = {r['n']}" for c, r in rows if covered(r, "package") is False]
    lines += [
        "",
        f"Rows the package rule misses: {'; '.join(misses) or 'none'}.",
        "",
        "## Rows",
        "",
        "| case | n | answer q(n) | reference | q(n) − reference | " + " | ".join(NAMES.values()) + " |",
        "|---|---:|---:|---:|---:|" + "---:|" * len(NAMES),
    ]
    for case in cases:
        for row in case["rows"]:
            if row.get("skipped"):
                lines.append(
                    f"| {case['label']} | {row['n']} | {fmt(row['value'], '.6g')} | (another kind of answer) |"
                )
                continue
            if not row["well_posed"]:
                lines.append(
                    f"| {case['label']} | {row['n']} | {fmt(row['value'], '.6g')} | ill-posed at this n: no n-error |"
                )
                continue
            cells = []
            for name in NAMES:
                mark = {True: "", False: " **miss**", None: ""}[covered(row, name)]
                cells.append(fmt(row["candidates"][name], ".2g") + mark)
            lines.append(
                f"| {case['label']} | {row['n']} | {fmt(row['value'], '.6g')} | {fmt(case['reference'], '.6g')} "
                f"({case['reference_kind']}) | {fmt(row['error'], '+.2g')} | " + " | ".join(cells) + " |"
            )
    lines += ["", "## The sequences", ""]
    for case in cases:
        shown = ", ".join(f"{n}: {fmt(v, '.6g')}" for n, v in zip(case["sizes"], case["answers"]))
        lines.append(f"- {case['label']}: {shown}; converge: {case['verdict']} (order {fmt(case['order'], '.2f')}).")
    return "\n".join(lines) + "\n"


def all_cases() -> list[tuple]:
    out = [(key, label, *make(), sizes) for key, (label, make, sizes) in PAPER.items()]
    for seed in well_posed_seeds(RANDOM_CASES):
        p, settings = random_case(seed)
        out.append((f"seed-{seed}", f"case {seed}: {describe(p, settings)}", p, settings, (p.n,)))
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--resume", action="store_true", help=f"reuse the finished cases in {ROWS.name}")
    parser.add_argument("--only", help="comma-separated case keys (prints, writes no report)")
    args = parser.parse_args()
    done = {}
    if args.resume and ROWS.exists():
        done = {row["key"]: row for row in map(json.loads, ROWS.read_text().splitlines())}
    elif ROWS.exists() and not args.only:
        ROWS.unlink()
    cases = []
    for key, label, p, settings, sizes_at in all_cases():
        if args.only and key not in args.only.split(","):
            continue
        case = done.get(key) or run_case(key, label, p, settings, sizes_at)
        case["label"] = label  # the label of this version of the script
        start = time.process_time()
        if add_rises(case, p, settings):
            case["cpu"] += time.process_time() - start
        if not args.only:
            done[key] = case
            with ROWS.open("a") as out:
                out.write(json.dumps(case) + "\n")
        cases.append(case)
        for row in case["rows"]:
            print(key, row, flush=True)
    if not args.only:  # one line per case (the appended ones replace those they updated)
        ROWS.write_text("".join(json.dumps(case) + "\n" for case in done.values()))
    text = markdown(cases, {key: p for key, _, p, *_ in all_cases()})
    if args.only:
        print(text)
    else:
        path = Path(__file__).with_name("n_error.md")
        path.write_text(text)
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
