"""Benchmarks of the reduced solver at large n, its start-up, and the tolerances behind its defaults.

    python validation/benchmark_reduced.py                     # in-process table (the targets)
    python validation/benchmark_reduced.py --startup           # end-to-end command times (processes)
    python validation/benchmark_reduced.py --first-run         # fresh clone + venv + pip install, first run
    python validation/benchmark_reduced.py --tolerances        # answer vs rtol (the default tolerances)
    python validation/benchmark_reduced.py --choice            # both integrators vs the stiffness ratio
    python validation/benchmark_reduced.py --all --markdown validation/benchmark_reduced.md

In-process times are the CPU time of this process (time.process_time) around `solve(...)`, minimum over
the repeats, after one untimed run that loads the compiled code: robust to other load on a shared
machine, where wall times are inflated. Process times are wall and CPU (user + sys of the child) of whole
commands, minimum over the repeats. Every table states the load average it was measured under.
"""

from __future__ import annotations

import argparse
import functools
import math
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from lightsail_mbs import paper_case, paper_settings
from lightsail_mbs import solve as solve_with_estimate

solve = functools.partial(solve_with_estimate, uncertainty=False)  # single runs: no error bars in this report


ROOT = Path(__file__).resolve().parent.parent
SOFT_SIZES = (100, 300, 1000, 3000)
# the paper's soft torsion case on the command line (SailParameters' defaults are the stable case)
SOFT_SIMULATE = ["simulate", "--solver", "reduced", "--modulus", "4.5e9", "--quiet"]


def load() -> str:
    one, five, _ = os.getloadavg()
    return f"load average {one:.1f} (1 min), {five:.1f} (5 min) on {os.cpu_count()} cores"


def cpu_time(params, settings, repeats: int, **options):
    """(min CPU s, min wall s, last Result) of solve() over repeats, after one untimed run."""
    result = solve(params, "reduced", settings, **options)
    cpu = wall = math.inf
    for _ in range(repeats):
        start_cpu, start = time.process_time(), time.perf_counter()
        result = solve(params, "reduced", settings, **options)
        cpu = min(cpu, time.process_time() - start_cpu)
        wall = min(wall, time.perf_counter() - start)
    return cpu, wall, result


def in_process(repeats: int) -> list[str]:
    lines = [
        f"In-process, CPU time of `solve(...)` (minimum of {repeats} repeats, 2 for n ≥ 1000; {load()}).",
        "",
        "| case | n | method | steps | CPU (s) | wall (s) | answer | target |",
        "|---|---:|---|---:|---:|---:|---|---|",
    ]
    cpus = []
    for n in SOFT_SIZES:
        cpu, wall, r = cpu_time(
            paper_case("torsion-soft", n=n), paper_settings("torsion-soft", t_final=0.5), 2 if n >= 1000 else repeats
        )
        cpus.append(cpu)
        lines.append(
            f"| soft torsion, 0.5 s | {n} | {r.info['method']} | {r.info['steps']} | {cpu:.4f} | {wall:.4f} "
            f"| max a/a₀ {r.max_amplitude_ratio:.4f} | ∝ n^≤1.1 |"
        )
        print(lines[-1], flush=True)
    exponent = np.polyfit(np.log(SOFT_SIZES), np.log(cpus), 1)[0]
    steps_note = f"fitted CPU ∝ n^{exponent:.2f} over n = {SOFT_SIZES[0]}–{SOFT_SIZES[-1]}"
    rows = [
        ("stable torsion, 6 s", "torsion-stable", {}, repeats, "≤ 0.05 s"),
        ("extensible TnT (T = 3.34e-3 N), 6 s", "tnt-stable", {}, repeats, "≤ 0.15 s"),
        ("soft torsion, to failure", "torsion-soft", dict(n=1000), 2, "≤ 0.5 s"),
        ("soft torsion, to failure", "torsion-soft", {}, repeats, "—"),
        ("soft TnT (T = 3.34e-8 N), to failure", "tnt-soft", {}, repeats, "—"),
        ("rigid ν = 3/2, 10 ms", "rigid", {}, repeats, "—"),
    ]
    for label, case, changes, reps, target in rows:
        params = paper_case(case, **changes)
        cpu, wall, r = cpu_time(params, paper_settings(case), reps)
        answer = f"t_f = {r.failure_time:.6g} s" if r.failed else f"max a/a₀ {r.max_amplitude_ratio:.4f}"
        lines.append(
            f"| {label} | {params.n} | {r.info['method']} | {r.info['steps']} | {cpu:.4f} | {wall:.4f} "
            f"| {answer} | {target} |"
        )
        print(lines[-1], flush=True)
    lines += ["", f"Soft torsion 0.5 s: {steps_note}."]
    print(lines[-1])
    return lines


def process_times(command: list[str], repeats: int, env=None) -> tuple[float, float]:
    """(min wall s, min CPU s of the child) of a command over repeats."""
    wall = cpu = math.inf
    for _ in range(repeats):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True, env=env)
        elapsed = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        wall = min(wall, elapsed)
        cpu = min(cpu, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime))
    return wall, cpu


def startup(repeats: int) -> list[str]:
    exe = shutil.which("lightsail-mbs") or "lightsail-mbs"
    python = sys.executable
    subprocess.run([exe, *SOFT_SIMULATE], check=True, capture_output=True)  # compiled code cached
    commands = [
        ("`python -c pass`", [python, "-c", "pass"], "—"),
        ("`python -c 'import numpy'`", [python, "-c", "import numpy"], "—"),
        ("`python -c 'import numba'`", [python, "-c", "import numba"], "—"),
        ("`lightsail-mbs --help`", [exe, "--help"], "—"),
        ("`lightsail-mbs theory`", [exe, "theory"], "≤ 0.4 s"),
        (
            "`lightsail-mbs simulate --solver reduced --modulus 4.5e9` (paper's soft case)",
            [exe, *SOFT_SIMULATE],
            "≤ 1.0 s",
        ),
    ]
    lines = [
        f"Whole processes on a warm install (compiled code cached; minimum of {repeats} runs; {load()}).",
        "",
        "| command | wall (s) | CPU (s) | target (wall) |",
        "|---|---:|---:|---|",
    ]
    for label, command, target in commands:
        wall, cpu = process_times(command, repeats)
        lines.append(f"| {label} | {wall:.3f} | {cpu:.3f} | {target} |")
        print(lines[-1], flush=True)
    lines += ["", f"Measured under {load()} (after the runs)."]
    return lines


def first_run(editable: bool) -> list[str]:
    """Clone this checkout, make a venv, pip install it, and time the first reduced run after pip ends."""
    kind = 'editable, `pip install -e ".[dev]"`' if editable else "regular, `pip install .`"
    with tempfile.TemporaryDirectory(prefix="lightsail-first-run-") as tmp:
        clone, venv = Path(tmp) / "clone", Path(tmp) / "venv"
        subprocess.run(["git", "clone", "-q", str(ROOT), str(clone)], check=True)
        subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
        pip = [str(venv / "bin" / "python"), "-m", "pip", "install", "-q"]
        target = ["-e", f"{clone}[dev]"] if editable else [str(clone)]
        start = time.perf_counter()
        subprocess.run(pip + target, check=True, cwd=tmp)
        install = time.perf_counter() - start
        command = [str(venv / "bin" / "lightsail-mbs"), *SOFT_SIMULATE]
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        first = subprocess.run(command, check=True, capture_output=True, text=True, cwd=tmp)
        first_wall = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        first_cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        second, second_cpu = process_times(command, 3)
    compiled = "compiling" in first.stderr
    lines = [
        f"Fresh install ({kind}) of a clean clone into a new venv: pip took {install:.0f} s (wall, including "
        f"compiling the kernels); the first `lightsail-mbs simulate --solver reduced` after it took "
        f"{first_wall:.2f} s wall and {first_cpu:.2f} s CPU "
        f"({'compiled, with the message' if compiled else 'loaded the cached kernels'}), later ones {second:.2f} s "
        f"wall and {second_cpu:.2f} s CPU (minimum of 3; {load()}).",
    ]
    if first.stderr.strip():
        lines.append(f"stderr of the first run: `{first.stderr.strip()}`")
    print("\n".join(lines), flush=True)
    return lines


def tolerances() -> list[str]:
    """The answers of the paper's DOP853 cases against rtol (reference: rtol 1e-10)."""
    lines = [
        "Answer against DOP853's rtol, relative to rtol 1e-10 (t_f, or the largest amplitude ratio for the "
        "stable sail).",
        "",
        "| case | n | rtol 1e-9 | rtol 1e-8 | rtol 1e-7 | CPU 1e-9 / 1e-8 (s) |",
        "|---|---:|---:|---:|---:|---|",
    ]
    for case, sizes in [("torsion-soft", (30, 60, 120)), ("torsion-stable", (30, 60)), ("rigid", (40,))]:
        for n in sizes:
            values, cpus = {}, {}
            for rtol in (1e-10, 1e-9, 1e-8, 1e-7):
                cpu, _, r = cpu_time(paper_case(case, n=n), paper_settings(case), 2, method="DOP853", rtol=rtol)
                values[rtol] = r.failure_time if r.failed else r.max_amplitude_ratio
                cpus[rtol] = cpu
            ref = values[1e-10]
            cells = " | ".join(f"{(values[t] - ref) / ref:+.1e}" for t in (1e-9, 1e-8, 1e-7))
            lines.append(f"| {case} | {n} | {cells} | {cpus[1e-9]:.4f} / {cpus[1e-8]:.4f} |")
            print(lines[-1], flush=True)
    return lines


def method_choice() -> list[str]:
    """CPU of both integrators on the paper's torsion runs (6 s, stop at failure) against the stiffness ratio."""
    from lightsail_mbs.solvers.reduced.solver import choose_method

    lines = [
        "Both integrators on the paper's torsion run (6 s, stopped at failure), CPU s (minimum of 2), "
        f"against the stiffness ratio ω_max/ω_slow ({load()}).",
        "",
        "| E (Pa) | n | ω_max/ω_slow | DOP853 (s) | Radau (s) | cheaper | auto |",
        "|---:|---:|---:|---:|---:|---|---|",
    ]
    for modulus in (4.5e9, 4.5e11, 4.5e13):
        for n in (30, 60, 120, 240):
            params = paper_case("torsion-soft", youngs_modulus=modulus, n=n)
            auto, figures = choose_method(params)
            cpu = {m: cpu_time(params, paper_settings("torsion-soft"), 2, method=m)[0] for m in ("DOP853", "Radau")}
            cheaper = min(cpu, key=cpu.get)
            lines.append(
                f"| {modulus:.1e} | {n} | {figures['stiffness_ratio']:.3g} | {cpu['DOP853']:.4f} | {cpu['Radau']:.4f} "
                f"| {cheaper} | {auto} |"
            )
            print(lines[-1], flush=True)
    return lines


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--startup", action="store_true", help="end-to-end command times")
    parser.add_argument("--first-run", action="store_true", help="fresh clone, venv, pip install, first run")
    parser.add_argument("--tolerances", action="store_true", help="answers against DOP853's rtol")
    parser.add_argument("--choice", action="store_true", help="both integrators against the stiffness ratio")
    parser.add_argument("--install", choices=["editable", "regular", "both"], default="both", help="for --first-run")
    parser.add_argument("--all", action="store_true", help="everything above and the in-process table")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--markdown", help="also write the tables to this Markdown file")
    args = parser.parse_args()
    sections = []
    if args.all or not (args.startup or args.first_run or args.tolerances or args.choice):
        sections.append(("In-process", in_process(args.repeats)))
    if args.all or args.startup:
        sections.append(("Start-up", startup(max(args.repeats, 5))))
    if args.all or args.first_run:
        kinds = {"editable": [True], "regular": [False], "both": [True, False]}[args.install]
        runs = [line for editable in kinds for line in [*first_run(editable), ""]]
        sections.append(("First run on a fresh install", runs[:-1]))
    if args.all or args.tolerances:
        sections.append(("Tolerances", tolerances()))
    if args.all or args.choice:
        sections.append(("Method choice", method_choice()))
    if args.markdown:
        text = "\n\n".join(f"### {title}\n\n" + "\n".join(lines) for title, lines in sections)
        Path(args.markdown).write_text(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
