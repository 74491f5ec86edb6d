"""Adversarial inputs through the command line and the API: writes validation/robustness.md.

    python validation/robustness.py [--out validation/robustness.md]

Each row tries one input a user could give (bad numbers, bad and unwritable paths, foreign, corrupt and
truncated files, truncated, corrupt and stale store records, a Dask scheduler that does not answer,
Ctrl-C, killed sweep workers, an unforeseen internal error, case files that are malformed, of a newer
format, name unknown keys or tables, put a key in the wrong table, values of the wrong type or out of range, or
fields or tables of another model family)
and records what happened: the exit status, the first line of stderr, whether a Python traceback reached
the user, and the time to fail (wall clock of the whole command, Python start-up and imports included; the
machine is shared, so these are upper bounds) with the command's CPU time, on which the row with a time
limit is judged. Every row must be one of:

* ``error``: exit status 2 and exactly one line on stderr naming the problem (API: ParameterError or
  RunFileError, whose message names the parameter or the file);
* ``result``: the correct result (what "correct" means is stated in the row: a file written, a record
  recomputed, counts that match);
* ``interrupted``: Ctrl-C ends the command with exit status 130, one line, no file half-written;
* ``internal``: an unforeseen error prints one line with the file holding its traceback (exit status 1).

No row may show a traceback, lose a finished case or serve a stale record. The script exits 1 if any
row misses its expectation. It takes about three minutes on two cores.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import traceback
import uuid
from dataclasses import dataclass
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
CLI = [sys.executable, "-m", "lightsail_mbs.cli"]
QUICK = ["--n", "12", "--t-final", "0.05", "--solver", "reduced", "--quiet"]  # a short real run
TIMINGS = ("wall_time", "case_wall_time")  # record fields that are measured times
HOLD_ENV = "LIGHTSAIL_ROBUSTNESS_HOLD"  # seconds a held case sleeps before solving (sweep kill rows)


@dataclass
class Row:
    through: str  # CLI or API
    input: str
    expected: str  # error | result | interrupted | internal
    outcome: str = ""
    status: str = ""
    first_line: str = ""
    traceback: bool = False
    seconds: float = 0.0
    cpu: float | None = None  # CPU seconds (user + system) of a command-line process
    ok: bool = False


ROWS: list[Row] = []


# ---- running commands ---------------------------------------------------------------------------
def run_cli(args, cwd, *, interrupt_after: float | None = None, interrupt_when=None, timeout: float = 300.0):
    """(exit status, stdout, stderr, wall seconds, CPU seconds) of one command line; SIGINT after
    interrupt_after seconds, or as soon as interrupt_when() is true (polled every 20 ms, for at most 120 s).
    CPU: user + system time of the process and the children it waited for."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    proc = subprocess.Popen(
        [*CLI, *map(str, args)],
        cwd=cwd,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),  # a shell's background job ignores it
    )
    if interrupt_after is not None:
        time.sleep(interrupt_after)
        os.killpg(proc.pid, signal.SIGINT)  # Ctrl-C reaches the whole foreground process group
    elif interrupt_when is not None:
        deadline = time.perf_counter() + 120.0
        while not interrupt_when() and proc.poll() is None and time.perf_counter() < deadline:
            time.sleep(0.02)
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGINT)
    out, err = proc.communicate(timeout=timeout)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return proc.returncode, out, err, wall, cpu


def stderr_lines(err: str) -> list[str]:
    return [line for line in err.splitlines() if line.strip()]


def cli_row(
    args,
    cwd,
    expected: str,
    *,
    names=(),
    limit: float | None = None,
    check=None,
    interrupt_after: float | None = None,
    interrupt_when=None,
    shown=None,
):
    """Run a command line and judge it: an ``error`` must exit 2 with one stderr line containing every
    word of ``names``, within ``limit`` CPU seconds if given (CPU, not wall clock: the machine is shared);
    a ``result`` must exit 0 and pass check(out, err)."""
    row = Row("CLI", "lightsail-mbs " + " ".join(map(str, shown or args)), expected)
    code, out, err, row.seconds, row.cpu = run_cli(
        args, cwd, interrupt_after=interrupt_after, interrupt_when=interrupt_when
    )
    lines = stderr_lines(err)
    row.status, row.first_line, row.traceback = str(code), (lines[0] if lines else ""), "Traceback" in err + out
    if expected == "error":
        row.ok = code == 2 and len(lines) == 1 and all(n in lines[0] for n in names)
        row.outcome = "one-line error" if row.ok else "NOT a one-line error"
        if limit is not None:
            row.ok &= row.cpu < limit
            row.outcome += f" after {row.cpu:.2f} s CPU, {row.seconds:.2f} s wall (limit {limit:g} s)"
    elif expected == "interrupted":
        row.ok = code == 130 and lines == ["lightsail-mbs: interrupted"]
        row.outcome = "interrupted, exit 130" if row.ok else "NOT a clean interrupt"
    elif expected == "internal":
        row.ok = code == 1 and len(lines) == 1 and "traceback in" in lines[0]
        row.outcome = "one line, traceback written to a file" if row.ok else "NOT one line"
    else:
        verdict = check(out, err) if check else (code == 0, "exit 0")
        row.ok, row.outcome = verdict
        row.ok = bool(row.ok) and code in (0,)
    row.ok &= not row.traceback
    ROWS.append(row)
    return row


def api_row(text: str, call, *, names=(), expected="error", check=None):
    """Call the API: an ``error`` must raise ParameterError or RunFileError naming ``names``; a
    ``result`` must return something check(value) accepts, as (ok, outcome)."""
    from lightsail_mbs import ParameterError
    from lightsail_mbs.result import RunFileError

    row = Row("API", text, expected, status="–")
    start = time.perf_counter()
    try:
        value = call()
    except (ParameterError, RunFileError) as exc:
        row.seconds = time.perf_counter() - start
        row.first_line = f"{type(exc).__name__}: {str(exc).splitlines()[0]}"
        row.ok = expected == "error" and all(n in str(exc) for n in names) and len(str(exc).splitlines()) == 1
        row.outcome = "one-line error" if row.ok else "unexpected error"
    except Exception as exc:  # noqa: BLE001 - what the user would see as a traceback
        row.seconds = time.perf_counter() - start
        row.first_line = f"{type(exc).__name__}: {exc}".splitlines()[0]
        row.traceback, row.outcome = True, "TRACEBACK: " + traceback.format_exc(limit=-1).splitlines()[-1]
    else:
        row.seconds = time.perf_counter() - start
        if expected == "error":
            row.outcome = "NO error raised"
        else:
            row.ok, row.outcome = check(value)
    ROWS.append(row)
    return row


# ---- files to feed the commands ----------------------------------------------------------------
def make_files(work: Path) -> None:
    """A good saved run and damaged variants of it, a foreign archive, a text file, a pickle."""
    code, _, err, _, _ = run_cli(["simulate", *QUICK, "--out", "good.npz"], work)
    assert code == 0, err
    (work / "text.npz").write_text("these are not the arrays you are looking for\n")
    np.savez(work / "foreign.npz", a=np.arange(3.0))
    np.save(work / "pickle.npy", np.array([{"a": 1}], dtype=object), allow_pickle=True)
    (work / "pickle.npy").rename(work / "pickle.npz")
    good = (work / "good.npz").read_bytes()
    (work / "truncated.npz").write_bytes(good[: len(good) // 2])
    with np.load(work / "good.npz") as data:
        arrays = {k: data[k] for k in data.files}
    summary = json.loads(str(arrays["summary_json"]))

    def variant(name, summary_text=None, **changes):
        np.savez(work / name, **{**arrays, "summary_json": np.array(summary_text or json.dumps(summary)), **changes})

    variant("badjson.npz", "{not json")
    variant("future.npz", json.dumps({**summary, "format_version": 99}))
    variant("badcase.npz", json.dumps({**summary, "parameters": {**summary["parameters"], "n": -3}}))
    variant("nosolver.npz", json.dumps({k: v for k, v in summary.items() if k != "solver"}))
    variant("shapes.npz", x=arrays["x"][:3])


# ---- case files ----------------------------------------------------------------------------------
BAD_CASE_FILES = (  # file name, content, words the one-line error must hold (the file, the key, what is allowed)
    ("syntax.toml", "n = = 3\n", ["syntax.toml", "not valid TOML", "line 1"]),
    ("unknown.toml", "thicknes = 1e-6\n", ["unknown.toml", "thicknes", "did you mean thickness", "allowed"]),
    ("type.toml", 'n = "ten"\n', ["type.toml", "n = ", "an integer"]),
    ("range.toml", "thickness = -1e-6\n", ["range.toml", "thickness=", "> 0"]),
    ("family.toml", 'model = "torsion"\nny = 3\n', ["family.toml", "ny=3", "unless model='sheet'"]),
    ("newer.toml", "version = 3\n", ["newer.toml", "version = 3", "up to version 2"]),
    ("top.toml", "version = 2\nn = 12\n", ["top.toml", "n at the top", "allowed in [sail]"]),
    ("wrongtable.toml", "[beam]\nny = 3\n", ["wrongtable.toml", "beam.ny", "allowed in [sheet]"]),
    ("table.toml", "[hull]\nn = 12\n", ["table.toml", "unknown table [hull]", "[sail]"]),
    ("sectionkey.toml", "[beam]\nbeam_wasit = 0.3\n", ["sectionkey.toml", "beam.beam_wasit", "allowed in [beam]"]),
    (
        "othertable.toml",
        '[sail]\nmodel = "torsion"\n[sheet]\nny = 3\n',
        ["othertable.toml", "ny=3", "unless model='sheet'"],
    ),
    ("runtable.toml", "[run]\nt_fnal = 1.0\n", ["runtable.toml", "run.t_fnal", "t_final"]),
    ("missing.toml", None, ["missing.toml", "no such file"]),
)


def case_file_rows(work: Path) -> None:
    """Case files: a good one runs and --save-case writes the case it ran (read back equal); each kind of
    bad file is one line naming the file, the key and what is allowed."""
    from lightsail_mbs import SailParameters
    from lightsail_mbs.cli import build_parser
    from lightsail_mbs.cli.options import params_from_args

    SailParameters(n=12, youngs_modulus=4.5e9).to_toml(work / "case.toml")
    run = ["--t-final", "0.05", "--solver", "reduced", "--quiet", "--no-uncertainty"]

    def saved(out, err):
        given = params_from_args(
            build_parser().parse_args(["simulate", str(work / "case.toml"), "--modulus", "4.5e10"])
        )
        ok = SailParameters.from_toml(work / "saved.toml") == given and "n=12" in out
        return ok, "the case file ran (n = 12); --save-case wrote it with --modulus applied, read back equal"

    cli_row(
        ["simulate", "case.toml", "--modulus", "4.5e10", *run, "--save-case", "saved.toml"], work, "result", check=saved
    )
    for name, text, words in BAD_CASE_FILES:
        if text is not None:
            (work / name).write_text(text)
        cli_row(["simulate", name, *run], work, "error", names=words)
    api_row(
        "SailParameters.from_toml(a file with an unknown key)",
        lambda: SailParameters.from_toml(work / "unknown.toml"),
        names=["unknown.toml", "thicknes"],
    )


# ---- the sweep rows ------------------------------------------------------------------------------
def sweep_cases():
    from lightsail_mbs import RunSettings, SailParameters
    from lightsail_mbs.studies.sweep import Case

    return [
        Case(SailParameters(n=12, youngs_modulus=e), "reduced", save_result=True, settings=RunSettings(t_final=0.05))
        for e in (4.5e9, 4.5e10, 4.5e11, 4.5e12, 4.5e13, 4.5e14)
    ]


def held_case(case):
    """The real reduced solver, after a marker naming this worker's pid and a pause of HOLD_ENV seconds
    (so that a worker can be killed mid-case)."""
    from lightsail_mbs.studies.sweep import solve_case

    markers = os.environ.get(HOLD_ENV + "_MARKERS")
    if markers:
        Path(markers, f"{case.key}.{os.getpid()}.{uuid.uuid4().hex}").touch()
    time.sleep(float(os.environ.get(HOLD_ENV, "0")))
    return solve_case(case)


def comparable(record: dict) -> dict:
    """A record without its measured times and the creation time of its provenance."""
    out = {k: v for k, v in record.items() if k not in TIMINGS}
    if "provenance" in out:
        out["provenance"] = {k: v for k, v in out["provenance"].items() if k != "created"}
    return json.loads(json.dumps(out, sort_keys=True, default=str))


def executions(markers: Path) -> dict:
    counts: dict = {}
    for name in os.listdir(markers):
        counts[name.split(".")[0]] = counts.get(name.split(".")[0], 0) + 1
    return counts


def sweep_script(store, workers=2, scheduler=None):
    """A command line running the held sweep in a fresh process (killed by the rows below)."""
    args = [sys.executable, str(Path(__file__).resolve()), "--sweep", str(store), "--workers", str(workers)]
    return args + (["--scheduler", scheduler] if scheduler else [])


def killed_worker_row(work: Path, reference: list, scheduler=None, markers: Path | None = None) -> None:
    """SIGKILL one worker in the middle of a case; the sweep must finish with every record equal to the
    reference (timings aside), recomputing only the killed case (and any innocent case beside it)."""
    from lightsail_mbs.studies.store import CaseStore

    label = "Dask cluster on 127.0.0.1" if scheduler else "local process pool"
    row = Row("API", f"SIGKILL of a sweep worker mid-case ({label}, 6 reduced cases)", "result")
    store = work / f"kill-{uuid.uuid4().hex[:6]}"
    if markers is None:
        markers = work / f"markers-{uuid.uuid4().hex[:6]}"
        markers.mkdir()
    env = {**os.environ, HOLD_ENV: "0.6", HOLD_ENV + "_MARKERS": str(markers)}
    start = time.perf_counter()
    proc = subprocess.Popen(sweep_script(store, scheduler=scheduler), env=env, stderr=subprocess.PIPE, text=True)
    victim, finished_before = None, set()
    deadline = time.monotonic() + 120
    while victim is None and time.monotonic() < deadline and proc.poll() is None:
        finished_before = set(CaseStore(store).keys()) if store.exists() else set()
        running = [name.split(".") for name in os.listdir(markers) if name.split(".")[0] not in finished_before]
        if finished_before and running:
            key, pid = running[0][0], int(running[0][1])
            os.kill(pid, signal.SIGKILL)
            victim = key
        time.sleep(0.05)
    _, err = proc.communicate(timeout=300)
    row.seconds = time.perf_counter() - start
    records = [json.loads(CaseStore(store).record_path(c.key).read_text()) for c in sweep_cases()]
    counts = executions(markers)
    lost = sum(r["status"] != "ok" for r in records)
    recomputed = sum(counts.get(k, 0) - 1 for k in finished_before)
    equal = [comparable(r) for r in records] == [comparable(r) for r in reference]
    row.status, row.first_line = str(proc.returncode), (stderr_lines(err) or [""])[0]
    row.traceback = "Traceback" in err
    row.ok = victim is not None and proc.returncode == 0 and lost == 0 and recomputed == 0 and equal
    row.outcome = (
        f"killed case rerun {counts.get(victim, 0) - 1}×; cases lost {lost}; finished cases recomputed "
        f"{recomputed}; records equal to an uninterrupted sweep's: {equal}"
    )
    ROWS.append(row)


def killed_sweep_row(work: Path, reference: list) -> None:
    """SIGKILL the whole sweep (process group) part-way, rerun it: nothing finished is recomputed."""
    from lightsail_mbs.studies.store import CaseStore
    from lightsail_mbs.studies.sweep import run_sweep

    text = "SIGKILL of a whole sweep (main process and workers) part-way, then the same sweep again"
    row = Row("API", text, "result")
    store, markers = work / "killed-sweep", work / "killed-sweep-markers"
    markers.mkdir()
    env = {**os.environ, HOLD_ENV: "0.4", HOLD_ENV + "_MARKERS": str(markers)}
    start = time.perf_counter()
    proc = subprocess.Popen(sweep_script(store), env=env, stderr=subprocess.DEVNULL, start_new_session=True)
    deadline = time.monotonic() + 120
    while not (store.exists() and len(list(store.glob("*.json"))) >= 2) and time.monotonic() < deadline:
        time.sleep(0.02)
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    finished = set(CaseStore(store).keys())
    os.environ[HOLD_ENV + "_MARKERS"] = str(markers)
    try:
        records = run_sweep(sweep_cases(), store, workers=2, progress=False, case_function=held_case)
    finally:
        del os.environ[HOLD_ENV + "_MARKERS"]
    row.seconds = time.perf_counter() - start
    counts = executions(markers)
    recomputed = sum(counts.get(k, 0) - 1 for k in finished)
    equal = [comparable(r) for r in records] == [comparable(r) for r in reference]
    row.status = "–"
    row.ok = 2 <= len(finished) < 6 and recomputed == 0 and equal and all(r["status"] == "ok" for r in records)
    row.outcome = (
        f"{len(finished)} of 6 finished before the kill; rerun recomputed {recomputed} of them; "
        f"records equal to an uninterrupted sweep's: {equal}"
    )
    ROWS.append(row)


def damaged_store_rows(work: Path, reference: list) -> None:
    """A store with a truncated, a corrupt, a stale and an incomplete record: `store` reports them, the
    next sweep recomputes exactly those four and serves none of them."""
    from lightsail_mbs.studies.store import CaseStore
    from lightsail_mbs.studies.sweep import run_sweep

    store = work / "damaged-store"
    cases = sweep_cases()
    run_sweep(cases, store, workers=1, progress=False)
    s = CaseStore(store)
    keys = [c.key for c in cases]
    truncated, corrupt, stale, incomplete = keys[:4]
    text = s.record_path(truncated).read_text()
    s.record_path(truncated).write_text(text[: len(text) // 3])
    s.record_path(corrupt).write_text(json.dumps({"key": corrupt, "status": "ok"}))  # no code_version
    record = json.loads(s.record_path(stale).read_text())
    record["code_version"] = "0" * 16  # made by other code
    record["failed"] = not record["failed"]  # and with another answer: serving it would show
    s.record_path(stale).write_text(json.dumps(record))
    data = s.result_path(incomplete).read_bytes()
    s.result_path(incomplete).write_bytes(data[: len(data) // 2])

    def counted(out, err):
        found = dict(line.split() for line in out.splitlines()[1:5])
        want = {"current": "2", "stale": "1", "corrupt": "2", "incomplete": "1"}
        return found == want, f"reported {found} (truncated and no-code-version records both count as corrupt)"

    cli_row(["store", store.name], work, "result", check=counted)
    markers = work / "damaged-markers"
    markers.mkdir()
    os.environ[HOLD_ENV + "_MARKERS"] = str(markers)
    row = Row("API", "run_sweep over that store (truncated, corrupt, stale and incomplete records)", "result")
    start = time.perf_counter()
    try:
        records = run_sweep(cases, store, workers=1, progress=False, case_function=held_case)
    finally:
        del os.environ[HOLD_ENV + "_MARKERS"]
    row.seconds, row.status = time.perf_counter() - start, "–"
    counts = executions(markers)
    served_stale = sum(comparable(r) != comparable(ref) for r, ref in zip(records, reference))
    row.ok = set(counts) == {truncated, corrupt, stale, incomplete} and served_stale == 0
    row.outcome = (
        f"recomputed {len(counts)} (the 4 damaged), served the 2 current ones; stale records served {served_stale}"
    )
    ROWS.append(row)


# ---- all rows -----------------------------------------------------------------------------------
def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(HERE / "robustness.md"))
    parser.add_argument("--sweep", help=argparse.SUPPRESS)  # internal: run the held sweep into this store
    parser.add_argument("--workers", type=int, default=2, help=argparse.SUPPRESS)
    parser.add_argument("--scheduler", default=None, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.sweep:
        from lightsail_mbs.studies.sweep import run_sweep

        run_sweep(
            sweep_cases(),
            args.sweep,
            workers=args.workers,
            scheduler=args.scheduler,
            progress=False,
            case_function=held_case,
        )
        return 0

    work = Path(tempfile.mkdtemp(prefix="lightsail-robustness-"))
    try:
        run_all(work)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    write_report(Path(args.out))
    failed = [r for r in ROWS if not r.ok]
    print(f"{len(ROWS)} inputs, {len(ROWS) - len(failed)} as expected; wrote {args.out}")
    for r in failed:
        print(f"  NOT AS EXPECTED: {r.through} {r.input}: {r.outcome} ({r.first_line})")
    return 1 if failed else 0


def run_all(work: Path) -> None:
    from lightsail_mbs import Result, RunSettings, SailParameters, solve
    from lightsail_mbs.studies.sweep import Case, run_sweep

    make_files(work)
    (work / "afile").write_text("x")
    (work / "folder.npz").mkdir()

    # bad and unwritable paths
    cli_row(["simulate", *QUICK, "--out", "/proc/x.npz"], work, "error", names=["--out", "/proc/x.npz"], limit=3.0)
    cli_row(["simulate", *QUICK, "--out", "afile/x.npz"], work, "error", names=["--out"])
    cli_row(["simulate", *QUICK, "--out", "folder.npz"], work, "error", names=["--out", "folder"])
    # bad numbers
    for option, value, name in (
        ("--n", "1", "n"),
        ("--modulus", "nan", "youngs_modulus"),
        ("--thickness", "-1e-6", "thickness"),
        ("--defect-amplitude", "1", "defect_amplitude"),
        ("--t-final", "1e300", "t_final"),
        ("--output-interval", "0", "output_interval"),
        ("--failure-ratio", "1", "failure_ratio"),
        ("--n", "abc", "--n"),
        ("--defect-seed", "-1", "defect_seed"),
        ("--defect-mode-count", "0", "defect_mode_count"),
        ("--defect-spectrum", "nan", "defect_spectrum"),
        ("--roughness", "-1e-9", "roughness"),
    ):
        cli_row(["simulate", *QUICK, option, value], work, "error", names=[name])
    cli_row(["simulate", *QUICK, "--model", "tnt", "--tension", "-1"], work, "error", names=["tension"])
    # the sheet's options (checked before any tile is built)
    sheet = ["simulate", "--model", "sheet", "--t-final", "0.05", "--solver", "reduced", "--quiet"]
    for option, value, name in (
        ("--nx", "1", "n"),
        ("--ny", "0", "ny"),
        ("--ny", "2.5", "--ny"),
        ("--mode-y", "-1", "defect_mode_y"),
        ("--membrane-modulus", "nan", "membrane_modulus"),
        ("--edge-tension", "-1", "edge_tension"),
        ("--beam-centre-y", "inf", "beam_centre_y"),
    ):
        cli_row([*sheet, option, value], work, "error", names=[name])
    cli_row(["simulate", *QUICK, "--ny", "3"], work, "error", names=["ny", "model='sheet'"])

    def sheet_saved(out, err):
        r = Result.load(work / "sheet.npz")
        ok = r.is_sheet and r.tile_centres.shape[1:] == (12, 3) and np.all(np.isfinite(r.tile_centres))
        return ok, "a 4 × 3 sheet run saved with its tile arrays (T, 12, 3)"

    cli_row([*sheet, "--nx", "4", "--ny", "3", "--out", "sheet.npz"], work, "result", check=sheet_saved)
    cli_row(["render", "sheet.npz", "--out", "frames", "--compare", "good.npz"], work, "error", names=["--compare"])
    cli_row(["frobnicate"], work, "error", names=["frobnicate"])

    def warned(out, err):
        saved = Result.load(work / "coarse.npz")
        ok = "slices per half wavelength" in err and any("slices per half wavelength" in w for w in saved.warnings)
        return ok, "run done, warning printed and recorded in the Result (n cannot resolve ν = 3/2)"

    cli_row(
        ["simulate", "--n", "3", "--t-final", "0.05", "--solver", "reduced", "--quiet", "--out", "coarse.npz"],
        work,
        "result",
        check=warned,
    )

    def flat_not_failed(out, err):
        return "not failed" in out, "a flat sail (a₀ = 0) runs and is not failed (no defect to double)"

    cli_row(["simulate", *QUICK, "--defect-amplitude", "0"], work, "result", check=flat_not_failed)

    def provenance_shown(out, err):
        ok = all(word in out for word in ("code_version", "git_commit", "exudyn", "numpy", "scipy", "numba", "python"))
        return ok, "summary and provenance printed (versions, code_version, git commit)"

    cli_row(["info", "good.npz"], work, "result", check=provenance_shown)
    # missing, foreign, corrupt and truncated files
    for name, words in (
        ("missing.npz", ["missing.npz", "no such file"]),
        ("text.npz", ["text.npz", "not a NumPy"]),
        ("foreign.npz", ["foreign.npz", "not a saved"]),
        ("pickle.npz", ["pickle.npz"]),
        ("truncated.npz", ["truncated.npz"]),
        ("badjson.npz", ["badjson.npz"]),
        ("future.npz", ["future.npz", "version 99"]),
        ("badcase.npz", ["badcase.npz", "n=-3"]),
        ("nosolver.npz", ["nosolver.npz", "solver"]),
        ("shapes.npz", ["shapes.npz", "x is"]),
    ):
        cli_row(["info", name], work, "error", names=words)
    cli_row(["render", "truncated.npz", "--out", "frames", "--quiet"], work, "error", names=["truncated.npz"])
    cli_row(["render", "good.npz", "--out", "/proc/frames", "--quiet"], work, "error", names=["--out"])
    cli_row(["render", "good.npz", "--out", "frames", "--movie", "gif", "--fps", "0"], work, "error", names=["fps"])
    cli_row(["render", "good.npz", "--out", "frames", "--compare", "text.npz"], work, "error", names=["text.npz"])
    # sweeps and studies
    mc = ["montecarlo", "--n", "12", "--t-final", "0.05", "--solver", "reduced", "--seeds", "2", "--quiet"]
    cli_row([*mc, "--values", "1e9,abc", "--store", "mc"], work, "error", names=["values"])
    cli_row([*mc, "--values", ",", "--store", "mc"], work, "error", names=["values"])
    cli_row([*mc, "--values", "1e9", "--store", "afile"], work, "error", names=["--store"])
    cli_row([*mc, "--values", "1e9", "--store", "mc", "--workers", "0"], work, "error", names=["workers"])
    cli_row(
        [*mc, "--values", "1e9", "--store", "mc", "--scheduler", "tcp://127.0.0.1:9"],
        work,
        "error",
        names=["scheduler", "127.0.0.1:9"],
        limit=20.0,
    )
    cli_row(["reproduce", "--figure", "5", "--quick", "--out", "/proc/figs"], work, "error", names=["--out"])
    cli_row(["crosscheck", "--cases", "rigid-0.5", "--out", "/proc/cc"], work, "error", names=["--out"])
    cli_row(["crosscheck", "--cases", "rigid-0.5", "--exudyn-step-scale", "0"], work, "error", names=["step_scale"])
    cli_row(["stability", "--factor", "1"], work, "error", names=["factor"])
    cli_row(["stability", "--tau-final", "-1"], work, "error", names=["tau_final"])
    cli_row(["store", "no-such-store"], work, "error", names=["no-such-store"])
    case_file_rows(work)
    # Ctrl-C
    long_run = ["simulate", "--n", "30", "--modulus", "4.5e13", "--t-final", "60", "--quiet", "--out", "long.npz"]
    for solver in ("exudyn", "reduced"):
        row = cli_row([*long_run, "--solver", solver], work, "interrupted", interrupt_after=4.0)
        row.input = f"Ctrl-C during: lightsail-mbs simulate --solver {solver} --t-final 60 --out long.npz"
        written = (work / "long.npz").exists()
        row.ok &= not written
        row.outcome += f"; long.npz written: {written}"
    mc_long = ["montecarlo", "--n", "12", "--t-final", "6", "--solver", "exudyn", "--seeds", "4"]
    mc_long += ["--values", "4.5e9,4.5e11", "--store", "mc-int", "--workers", "2", "--quiet"]
    # Ctrl-C as soon as the first case is on disk: some cases done, others not, on any machine
    row = cli_row(mc_long, work, "interrupted", interrupt_when=lambda: any((work / "mc-int").glob("*.json")))
    row.input = "Ctrl-C during: lightsail-mbs montecarlo --solver exudyn --seeds 4 --values 4.5e9,4.5e11 --workers 2"
    kept = {p.name: p.stat().st_mtime_ns for p in (work / "mc-int").glob("*.json")}

    def resumed(out, err):
        now = {p.name: p.stat().st_mtime_ns for p in (work / "mc-int").glob("*.json")}
        untouched = all(now.get(name) == stamp for name, stamp in kept.items())
        return len(now) == 8 and untouched and 0 < len(kept) < 8, (
            f"rerun finished the sweep: {len(kept)} records from before the Ctrl-C kept untouched "
            f"(not recomputed: {untouched}), 8 in all"
        )

    again = cli_row(mc_long, work, "result", check=resumed)
    again.input = "the same montecarlo command again, after the Ctrl-C (8 cases in all)"
    # an unforeseen error
    row = Row("CLI", "an unforeseen error inside a command (theory.summary patched to divide by zero)", "internal")
    code = (
        "import sys; from lightsail_mbs.model import theory; theory.summary = lambda p: 1 / 0; "
        "from lightsail_mbs.cli import main; sys.exit(main(['theory']))"
    )
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=work)
    row.seconds = time.perf_counter() - start
    lines = stderr_lines(proc.stderr)
    row.status, row.first_line = str(proc.returncode), lines[0] if lines else ""
    row.traceback = "Traceback" in proc.stderr
    log = lines[0].rsplit("traceback in ", 1)[-1].rstrip(")") if lines else ""
    row.ok = proc.returncode == 1 and len(lines) == 1 and Path(log).is_file() and not row.traceback
    row.outcome = f"one line; traceback file exists: {Path(log).is_file()}"
    Path(log).unlink(missing_ok=True)
    ROWS.append(row)

    # the API
    api_row("SailParameters(n=2.5)", lambda: SailParameters(n=2.5), names=["n="])
    api_row("SailParameters(intensity=-1)", lambda: SailParameters(intensity=-1.0), names=["intensity"])
    api_row("RunSettings(t_final=float('inf'))", lambda: RunSettings(t_final=float("inf")), names=["t_final"])
    api_row("solve(…, solver='nope')", lambda: solve(SailParameters(n=12), "nope"), names=["solver"])
    api_row(
        "solve(…, 'exudyn', step_size=-1)",
        lambda: solve(SailParameters(n=12), "exudyn", RunSettings(t_final=0.01), step_size=-1.0),
        names=["step_size"],
    )
    api_row("Result.load(a folder)", lambda: Result.load(work / "folder.npz"), names=["folder.npz"])
    api_row("Case(…, options={'f': object()})", lambda: Case(SailParameters(), "x", {"f": object()}), names=["options"])
    api_row(
        "run_sweep(…, workers=0)",
        lambda: run_sweep(sweep_cases()[:1], work / "w0", workers=0, progress=False),
        names=["workers"],
    )
    api_row(
        "run_sweep(…, scheduler='tcp://127.0.0.1:9')",
        lambda: run_sweep(sweep_cases()[:1], work / "dead", scheduler="tcp://127.0.0.1:9", progress=False),
        names=["scheduler"],
    )
    api_row(
        "run_sweep(…, store_dir=a file)",
        lambda: run_sweep(sweep_cases()[:1], work / "afile", workers=1, progress=False),
        names=["afile"],
    )

    # stores and killed workers
    from lightsail_mbs.studies.store import CaseStore

    reference = run_sweep(sweep_cases(), work / "reference", workers=1, progress=False)
    assert all(CaseStore(work / "reference").has(c.key) for c in sweep_cases()), "reference sweep incomplete"
    damaged_store_rows(work, reference)
    killed_sweep_row(work, reference)
    killed_worker_row(work, reference)
    from distributed import LocalCluster

    markers = work / "dask-markers"
    markers.mkdir()
    os.environ.update({HOLD_ENV: "0.6", HOLD_ENV + "_MARKERS": str(markers)})  # the cluster's workers inherit it
    try:
        with LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
        ) as cluster:
            killed_worker_row(work, reference, scheduler=cluster.scheduler_address, markers=markers)
    finally:
        del os.environ[HOLD_ENV], os.environ[HOLD_ENV + "_MARKERS"]


def write_report(path: Path) -> None:
    expected = {"error": "one-line error, exit 2", "result": "correct result", "interrupted": "exit 130, one line"}
    expected["internal"] = "one line + traceback file, exit 1"
    expected["API error"] = "ParameterError or RunFileError naming the problem"
    lines = [
        "# Robustness: adversarial inputs",
        "",
        "Generated by `python validation/robustness.py`. Each row is one input tried through the command line",
        "(a fresh `python -m lightsail_mbs.cli` process) or the Python API. *time* is the wall clock to the",
        "end of the command (Python start-up and imports included) on a shared two-core machine, *CPU* the",
        "command's own CPU time (user + system, its waited-for children included). A *traceback*",
        "is a Python traceback reaching the user. Store rows: timing fields (`wall_time`, `case_wall_time`) and",
        "the provenance's `created` are left out of the record comparison; every other field must be equal.",
        "",
        f"{sum(r.ok for r in ROWS)} of {len(ROWS)} inputs behave as expected; tracebacks shown: "
        f"{sum(r.traceback for r in ROWS)}.",
        "",
        "| # | through | input | expected | outcome | exit | first line of stderr | traceback | time (s) | CPU (s) "
        "| ok |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for i, r in enumerate(ROWS, 1):
        first = r.first_line.replace("|", "\\|")
        first = first if len(first) <= 160 else first[:157] + "…"
        text = r.input.replace("|", "\\|")
        want = expected["API error"] if (r.through, r.expected) == ("API", "error") else expected[r.expected]
        cpu = "–" if r.cpu is None else f"{r.cpu:.2f}"
        lines.append(
            f"| {i} | {r.through} | `{text}` | {want} | {r.outcome} | "
            f"{r.status} | {first} | {'yes' if r.traceback else 'no'} | {r.seconds:.2f} | {cpu} | "
            f"{'✅' if r.ok else '❌'} |"
        )
    path.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    sys.exit(main())
