"""Deliberate breakages that the test suite must catch: writes validation/mutations.md.

    python validation/mutations.py [--only ID ...] [--out validation/mutations.md]

For each test that could not fail before (the weak tests named in the issue that led to this script: wide
windows on the paper's cases, a critical ratio accepted anywhere in 1–30, a rigid linear case with an
all-zero spectrum, failure times passing without interpolation, velocities, info and error never compared
after a save/load, the store's key and code version, a failure ratio other than 2 never reaching a solver,
commands never run end to end), this script makes one small, plausible breakage of the code in a copy of
the repository and shows

* the test as it is now passes on the intact copy and fails on the broken one (the breakage is caught);
* the test as it was before (commit BEFORE), where there was one, passes on the broken copy (it was weak).

The copy holds the repository's tracked files and the package's compiled numba caches (so only a broken
compiled module is recompiled); every breakage is undone before the next. About ten minutes on two cores.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BEFORE = "eddcd23"  # the repository before the weak tests were strengthened


@dataclass(frozen=True)
class Mutation:
    id: str
    weak: str  # the weak test of the issue it demonstrates
    file: str
    old: str  # the exact text replaced (must occur once)
    new: str
    how: str
    tests: tuple  # node ids that must now catch it
    before: tuple = ()  # node ids of the tests as they were at BEFORE (same paths), expected to pass


MUTATIONS = [
    Mutation(
        "exudyn-load",
        "paper-case tests' wide windows (1.5–2.3 s)",
        "lightsail_mbs/solvers/exudyn/tree.py",
        "c, s, fx, fy = bodies[COS], bodies[SIN], forces[0], forces[1]",
        "c, s, fx, fy = bodies[COS], bodies[SIN], 0.95 * forces[0], 0.95 * forces[1]",
        "Exudyn's net slice forces enter its generalized forces 5 % low (for the mirror in a uniform beam, "
        "a reflectivity 5 % low: a wrong constant in its load)",
        (
            "tests/solvers/exudyn/test_chain.py::test_soft_torsion_fails_near_two_seconds",
            "tests/test_references.py::test_soft_torsion_failure_time_exudyn",
        ),
        ("tests/solvers/exudyn/test_chain.py::test_soft_torsion_fails_near_two_seconds",),
    ),
    Mutation(
        "reduced-rtol",
        "paper-case tests' wide windows (1.5–2.3 s)",
        "lightsail_mbs/solvers/reduced/solver.py",
        'DEFAULT_RTOL = {"DOP853": 1e-8, "Radau": 1e-6}',
        'DEFAULT_RTOL = {"DOP853": 1e-5, "Radau": 1e-6}',
        "the reduced solver's default DOP853 tolerance loosened 1000× (a tempting speed-up)",
        ("tests/solvers/reduced/test_solver.py::test_soft_torsion_fails_like_the_paper_and_converges",),
        ("tests/solvers/reduced/test_solver.py::test_soft_torsion_fails_like_the_paper_and_converges",),
    ),
    Mutation(
        "radau-rtol",
        "paper-case tests' wide windows (1.5–2.5 s, membrane)",
        "lightsail_mbs/solvers/reduced/solver.py",
        'DEFAULT_RTOL = {"DOP853": 1e-8, "Radau": 1e-6}',
        'DEFAULT_RTOL = {"DOP853": 1e-8, "Radau": 1e-5}',
        "the reduced solver's default Radau tolerance (the extensible membrane) loosened 10×",
        ("tests/solvers/reduced/test_solver.py::test_tnt_soft_fails_like_the_paper_and_converges",),
        ("tests/solvers/reduced/test_solver.py::test_tnt_soft_fails_like_the_paper_and_converges",),
    ),
    Mutation(
        "critical-scale",
        "the critical-ratio test accepting anything in 1 < r < 30",
        "lightsail_mbs/analysis/finite_amplitude.py",
        "return p.replace(**{name: float(ratio) * critical(p)})",
        "return p.replace(**{name: 1.05 * float(ratio) * critical(p)})",
        "with_ratio sets E 5 % above r·E_cr,max (a wrong constant in the scaled problem)",
        (
            "tests/analysis/test_finite_amplitude.py::test_critical_ratio_brackets_the_dated_reference",
            "tests/test_references.py::test_torsion_critical_ratio",
        ),
        ("tests/analysis/test_finite_amplitude.py::test_critical_ratio_independent_of_amplitude",),
    ),
    Mutation(
        "linear-load-sign",
        "test_stability's rigid case (every ω² exactly zero)",
        "lightsail_mbs/solvers/exudyn/capabilities.py",
        "return np.asarray(mass), np.asarray(stiffness) - jac",
        "return np.asarray(mass), np.asarray(stiffness) + jac",
        "Exudyn's linearisation adds the load stiffness with the wrong sign",
        ("tests/analysis/test_linear_stability.py::test_exudyn_load_stiffness_is_the_axial_first_order_load[rigid]",),
        ("tests/analysis/test_linear_stability.py::test_exudyn_linear_spectrum_with_load_equals_unloaded_and_reduced",),
    ),
    Mutation(
        "linear-load-dropped",
        "test_stability's rigid case (every ω² exactly zero)",
        "lightsail_mbs/solvers/exudyn/capabilities.py",
        "return beam(q).copy() - tension_only(q)",
        "return 0.0 * (beam(q).copy() - tension_only(q))",
        "Exudyn's linearisation loses the net load (radiation and frame force)",
        ("tests/analysis/test_linear_stability.py::test_exudyn_load_stiffness_is_the_axial_first_order_load[rigid]",),
        (
            "tests/analysis/test_linear_stability.py::"
            "test_exudyn_linear_spectrum_with_load_equals_unloaded_and_reduced[rigid]",
        ),
    ),
    Mutation(
        "no-interpolation",
        "analysis and result tests passing without failure-time interpolation",
        "lightsail_mbs/model/failure.py",
        "return float(time[k - 1] + (limit - a0) / (a1 - a0) * (time[k] - time[k - 1]))",
        "return float(time[k])",
        "failure_time returns the first sample at the limit instead of interpolating",
        (
            "tests/model/test_failure.py::test_failure_time_interpolated",
            "tests/test_result.py::test_summary_and_failure",
        ),
        (
            "tests/model/test_failure.py::test_failure_time_interpolated",
            "tests/test_result.py::test_summary_and_failure",
        ),
    ),
    Mutation(
        "lost-velocities",
        "velocities, info and error not compared after save/load",
        "lightsail_mbs/result.py",
        "arrays = {k: getattr(self, k) for k in ARRAYS}",
        'arrays = {k: getattr(self, k) * (k != "vx") for k in ARRAYS}',
        "Result.save writes zeros for vx",
        (
            "tests/test_result.py::test_save_load_keeps_every_field",
            "tests/test_result.py::test_any_saved_run_round_trips_bit_exactly_through_npz_and_json[fast]",
        ),
        ("tests/test_result.py::test_save_load_roundtrip",),
    ),
    Mutation(
        "lost-error",
        "velocities, info and error not compared after save/load",
        "lightsail_mbs/result.py",
        'error=summary["error"],',
        "error=None,",
        "Result.load drops the recorded solver error",
        ("tests/test_result.py::test_save_load_keeps_every_field",),
        ("tests/test_result.py::test_save_load_roundtrip",),
    ),
    Mutation(
        "lost-info",
        "velocities, info and error not compared after save/load",
        "lightsail_mbs/result.py",
        'info=summary["info"],',
        "info={},",
        "Result.load drops the solver's info",
        ("tests/test_result.py::test_save_load_keeps_every_field",),
        ("tests/test_result.py::test_save_load_roundtrip",),
    ),
    Mutation(
        "key-without-settings",
        "the sweep store's case key (fixed-value test)",
        "lightsail_mbs/studies/sweep.py",
        "        parameters.update(self.settings.to_dict())\n",
        "",
        "the case key forgets the run settings (runs of different length would share a record)",
        ("tests/studies/test_sweep.py::test_keys_of_stores_written_before_run_settings_are_unchanged",),
        ("tests/studies/test_sweep.py::test_keys_of_stores_written_before_run_settings_are_unchanged",),
    ),
    Mutation(
        "stale-served",
        "a record made by other code served (no test before)",
        "lightsail_mbs/studies/store.py",
        'if record["code_version"] != code_version():',
        "if False:",
        "the store ignores the code version of its records",
        ("tests/studies/test_store.py::test_a_record_made_by_other_code_is_not_served",),
    ),
    Mutation(
        "exudyn-ratio",
        "failure_ratio ≠ 2 never reaching a solver",
        "lightsail_mbs/solvers/exudyn/chain.py",
        "monitor = FailureMonitor(failure.amplitude(initial.x, initial.y), settings)",
        "monitor = FailureMonitor(failure.amplitude(initial.x, initial.y), settings.replace(failure_ratio=2.0))",
        "Exudyn's stop rule uses the paper's ratio 2 whatever the settings say",
        ("tests/cli/test_commands.py::test_failure_ratio_option_reaches_the_solver[exudyn]",),
        ("tests/solvers/exudyn/test_chain.py",),
    ),
    Mutation(
        "simulate-no-save",
        "simulate --json/--out untested end to end",
        "lightsail_mbs/cli/simulate.py",
        "        result.save(out)\n",
        "        pass\n",
        "simulate --out checks the path but never saves the run",
        ("tests/cli/test_commands.py::test_simulate_json_out_and_info_end_to_end",),
        ("tests/cli/test_commands.py",),
    ),
    Mutation(
        "info-no-provenance",
        "info shows provenance (new command)",
        "lightsail_mbs/cli/info.py",
        "    for key, value in made.items():\n",
        "    for key, value in list(made.items())[:0]:\n",
        "info prints no provenance",
        ("tests/cli/test_commands.py::test_simulate_json_out_and_info_end_to_end",),
    ),
    Mutation(
        "montecarlo-seeds",
        "montecarlo untested end to end",
        "lightsail_mbs/cli/montecarlo.py",
        "        args.seeds,\n",
        "        max(1, args.seeds - 1),\n",
        "montecarlo runs one seed fewer than asked",
        ("tests/cli/test_commands.py::test_montecarlo_end_to_end_and_resumed",),
        ("tests/cli/test_commands.py",),
    ),
    Mutation(
        "crosscheck-count",
        "crosscheck untested end to end",
        "lightsail_mbs/cli/crosscheck.py",
        "{sum(r['passed'] for r in rows)}/{len(rows)} cases pass",
        "{sum(not r['passed'] for r in rows)}/{len(rows)} cases pass",
        "crosscheck reports the failing cases as the passing count",
        ("tests/cli/test_commands.py::test_crosscheck_end_to_end_on_a_short_case",),
        ("tests/cli/test_commands.py",),
    ),
    Mutation(
        "fig5-csv",
        "reproduce untested end to end",
        "lightsail_mbs/paper/fig5.py",
        '"failure_time_ms": _ms(record.get("failure_time")),',
        '"failure_time_ms": _ms(record.get("t_end")),',
        "Fig. 5's CSV gives the run's end (the sample after failure) as its failure time",
        ("tests/cli/test_commands.py::test_reproduce_quick_end_to_end",),
        (
            "tests/cli/test_commands.py",
            "tests/paper/test_pipelines.py::test_figure_5_quick_writes_files_and_fails_at_troughs",
        ),
    ),
    Mutation(
        "store-count",
        "store command (new)",
        "lightsail_mbs/cli/store.py",
        'stale = sum(len(found[s]) for s in ("stale", "corrupt", "incomplete"))',
        'stale = sum(len(found[s]) for s in ("stale", "incomplete"))',
        "the store command leaves corrupt records out of those to recompute",
        ("tests/studies/test_store.py::test_store_command_reports_each_state",),
    ),
]


def copy_repository(target: Path) -> None:
    """Tracked files (with their modification times), the package's numba caches and the record of the kernel
    sources they were compiled from (lightsail_mbs.base.kernels.drop_stale_kernels)."""
    files = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True).stdout
    for name in files.decode().split("\0"):
        if name and (ROOT / name).is_file():
            (target / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / name, target / name)
    caches = [
        *(ROOT / "lightsail_mbs").rglob("__pycache__/*.nb[ic]"),
        ROOT / "lightsail_mbs/__pycache__/numba-kernel-sources",
    ]
    for cache in filter(Path.is_file, caches):
        destination = target / cache.relative_to(ROOT)
        destination.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(cache, destination)


def write_before_tests(copy: Path, mutation: Mutation) -> list[str]:
    """The test files of BEFORE as tests/.../before_<name>.py in the copy; their node ids."""
    ids = []
    for node in mutation.before:
        path, _, name = node.partition("::")
        text = subprocess.run(["git", "show", f"{BEFORE}:{path}"], cwd=ROOT, capture_output=True, text=True)
        if text.returncode:
            continue
        before = Path(path).with_name("test_before_" + Path(path).name.removeprefix("test_"))
        (copy / before).write_text(text.stdout)
        ids.append(str(before) + (f"::{name}" if name else ""))
    return ids


def pytest(copy: Path, ids) -> tuple[str, str, float]:
    """('passed' | 'FAILED' | 'error <status>', first failure line, seconds) of the tests in the copy."""
    env = {**os.environ, "PYTHONPATH": str(copy)}
    markers = ["-m", "slow or not slow"] if all("::" in i for i in ids) else []  # whole files: default suite
    start = time.perf_counter()
    run = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", *markers, *ids],
        cwd=copy,
        env=env,
        capture_output=True,
        text=True,
    )
    seconds = time.perf_counter() - start
    first = next((line[1:].strip() for line in run.stdout.splitlines() if line.startswith("E ")), "")
    state = {0: "passed", 1: "FAILED"}.get(run.returncode, f"error {run.returncode}")
    return state, first, seconds


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", nargs="+", metavar="ID", help="run only these mutations")
    parser.add_argument("--out", default=str(Path(__file__).resolve().with_suffix(".md")))
    parser.add_argument("--keep", action="store_true", help="keep the copy (its path is printed)")
    args = parser.parse_args(argv)
    chosen = [m for m in MUTATIONS if not args.only or m.id in args.only]
    copy = Path(tempfile.mkdtemp(prefix="lightsail-mutations-"))
    rows = []
    try:
        copy_repository(copy)
        where = subprocess.run(
            [sys.executable, "-c", "import lightsail_mbs; print(lightsail_mbs.__file__)"],
            cwd=copy,
            env={**os.environ, "PYTHONPATH": str(copy)},
            capture_output=True,
            text=True,
        ).stdout.strip()
        assert where.startswith(str(copy)), f"the copy's package is not the one imported: {where}"
        for m in chosen:
            path = copy / m.file
            original = path.read_text()
            stat = path.stat()
            assert original.count(m.old) == 1, f"{m.id}: the text to break is not in {m.file} exactly once"
            line = original[: original.index(m.old)].count("\n") + 1
            intact = pytest(copy, m.tests)
            path.write_text(original.replace(m.old, m.new))
            try:
                broken = pytest(copy, m.tests)
                before_ids = write_before_tests(copy, m)
                before = pytest(copy, before_ids) if before_ids else ("no test", "", 0.0)
            finally:
                path.write_text(original)
                os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns))  # the numba caches stay valid
                for node in before_ids if "before_ids" in locals() else []:
                    (copy / node.partition("::")[0]).unlink(missing_ok=True)
            ok = intact[0] == "passed" and broken[0] == "FAILED"
            rows.append((m, line, intact, broken, before, ok))
            print(f"{m.id}: intact {intact[0]}, broken {broken[0]}, before {before[0]} ({broken[1][:100]})", flush=True)
    finally:
        if args.keep:
            print(f"copy kept in {copy}")
        else:
            shutil.rmtree(copy, ignore_errors=True)
    write_report(Path(args.out), rows)
    missed = [r[0].id for r in rows if not r[-1]]
    print(f"{len(rows) - len(missed)} of {len(rows)} breakages caught; wrote {args.out}")
    return 1 if missed else 0


def write_report(path: Path, rows) -> None:
    def cell(text):
        return str(text).replace("|", "\\|").replace("\n", " ")

    lines = [
        "# Deliberate breakages and the tests that catch them",
        "",
        "Generated by `python validation/mutations.py`. Each row breaks one line of a copy of the repository;",
        "*now* is the test suite as it is (run on the intact copy, then on the broken one), *before* the same",
        f"test file as it was at commit {BEFORE}, run on the broken copy (“no test”: nothing covered it).",
        "",
        "| weak test (issue) | breakage | file:line | test that catches it | intact | broken | first failure |"
        " before, on the broken copy | caught |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for m, line, intact, broken, before, ok in rows:
        tests = "<br>".join(f"`{t.split('/')[-1]}`" for t in m.tests)
        first = broken[1] if len(broken[1]) <= 140 else broken[1][:137] + "…"
        lines.append(
            f"| {cell(m.weak)} | {cell(m.how)}: `{cell(m.old.strip())}` → `{cell(m.new.strip()) or '(deleted)'}` | "
            f"`{m.file}:{line}` | {tests} | {intact[0]} | {broken[0]} | {cell(first)} | {before[0]} | "
            f"{'✅' if ok else '❌'} |"
        )
    lines.append("")
    caught = sum(r[-1] for r in rows)
    lines.append(f"{caught} of {len(rows)} breakages caught by the tests as they are now.")
    path.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    sys.exit(main())
