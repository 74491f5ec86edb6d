"""The command line (lightsail_mbs.cli): as a user runs it (JSON output, clear one-line errors, no traceback),
and each subcommand in-process (options, stability, render, reproduce, crosscheck)."""

import json
import subprocess
import sys

import numpy as np
import pytest

from lightsail_mbs import Result, RunSettings, SailParameters, analysis, paper_case, paper_settings, solve
from lightsail_mbs.cli import build_parser, main
from lightsail_mbs.cli.options import params_from_args, settings_from_args
from lightsail_mbs.result import code_version
from lightsail_mbs.studies.store import CaseStore
from tests.helpers import growing_sine, read_csv, read_image


def cli(*args):
    return subprocess.run([sys.executable, "-m", "lightsail_mbs.cli", *map(str, args)], capture_output=True, text=True)


def clis(*commands):
    """Several command lines at once (each is mostly the interpreter's start-up); their CompletedProcess."""
    procs = [
        subprocess.Popen(
            [sys.executable, "-m", "lightsail_mbs.cli", *args],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        for args in commands
    ]
    done = []
    for proc in procs:
        out, err = proc.communicate()  # sets the return code
        done.append(subprocess.CompletedProcess(proc.args, proc.returncode, out, err))
    return done


def test_theory_json_paper_numbers():
    out = cli(
        "theory",
        "--thickness",
        "1e-6",
        "--density",
        "1000",
        "--intensity",
        "1e8",
        "--amplitude",
        "1e-5",
        "--mode",
        "1.5",
        "--json",
    )
    assert out.returncode == 0, out.stderr
    numbers = json.loads(out.stdout)
    assert numbers["e_cr_max"] == pytest.approx(4.5e11, rel=0.01)
    assert numbers["t_cr_max"] == pytest.approx(3.34e-6, rel=0.01)
    assert numbers["g0"] == pytest.approx(2e8 / (299_792_458.0 * 1e-3))


def test_theory_of_a_sheet_gives_its_tiles(capsys):
    """For a sheet: tile size and mass, D = E h³/12 (ν_p = 0), E_m, and T_cr,max per metre of edge."""
    args = ["theory", "--model", "sheet", "--nx", "10", "--ny", "5", "--width", "0.5", "--modulus", "4.5e9"]
    assert main([*args, "--membrane-modulus", "1e9", "--json"]) == 0
    numbers = json.loads(capsys.readouterr().out)
    assert numbers["tile_length"] == pytest.approx(0.1) and numbers["tile_width"] == pytest.approx(0.1)
    assert numbers["tile_mass"] == pytest.approx(1000.0 * 1e-6 * 0.01)  # ρ h a b, the default ρ and h
    assert numbers["bending_rigidity"] == pytest.approx(4.5e9 * 1e-18 / 12)
    assert numbers["membrane_modulus"] == 1e9 and "slice_length" not in numbers
    assert numbers["t_cr_max_per_metre"] == pytest.approx(numbers["t_cr_max"] / 0.5)


@pytest.mark.parametrize(
    "args, name",
    [
        (["--thickness", "0"], "thickness"),
        (["--n", "1"], "n"),
        (["--modulus", "nan"], "youngs_modulus"),
        (["--model", "tnt", "--tension", "-1"], "tension"),
        (["--mode", "-2"], "mode"),
    ],
)
def test_bad_input_one_line_error(args, name):
    for out in clis(["theory", *args], ["simulate", *args]):
        assert out.returncode == 2
        lines = out.stderr.strip().splitlines()
        assert len(lines) == 1 and name in lines[0] and "Traceback" not in out.stderr


def test_simulate_reports_heat_of_material_damping():
    out = cli(
        "simulate",
        "--model",
        "torsion",
        "--n",
        "6",
        "--modulus",
        "4.5e15",
        "--intensity",
        "0",
        "--stiffness-damping",
        "3e-3",
        "--t-final",
        "0.2",
        "--solver",
        "reduced",
        "--quiet",
    )
    assert out.returncode == 0, out.stderr
    heat = float(out.stdout.split("dissipated as heat:")[1].split()[0])
    assert heat > 0


def test_case_and_run_options_and_their_aliases():
    """--defect-amplitude/--amplitude and --defect-mode/--mode name the same fields; the run options make the
    RunSettings (defaults: RunSettings())."""
    parser = build_parser()
    long = parser.parse_args(["simulate", "--defect-amplitude", "2e-5", "--defect-mode", "2.5", "--n", "8"])
    short = parser.parse_args(["simulate", "--amplitude", "2e-5", "--mode", "2.5", "--n", "8"])
    assert (
        params_from_args(long) == params_from_args(short) == SailParameters(n=8, defect_amplitude=2e-5, defect_mode=2.5)
    )
    assert settings_from_args(long) == RunSettings()
    run = parser.parse_args(
        ["simulate", "--t-final", "0.5", "--output-interval", "1e-3", "--failure-ratio", "3", "--run-past-failure"]
    )
    assert settings_from_args(run) == RunSettings(
        t_final=0.5, output_interval=1e-3, failure_ratio=3.0, stop_at_failure=False
    )


def test_montecarlo_defect_options(tmp_path):
    parser = build_parser()
    common = ["montecarlo", "--values", "1e9", "--store", str(tmp_path)]
    assert parser.parse_args(common + ["--defect-modes", "7"]).defect_mode_count == 7
    assert parser.parse_args(common + ["--defect-mode-count", "7"]).defect_mode_count == 7
    assert parser.parse_args(common + ["--vary", "defect_amplitude"]).vary == "defect_amplitude"


def test_random_defect_and_roughness_options_reach_the_case(capsys):
    """The options an ill-conditioned run's explanation names (--roughness) and the seeded multi-mode
    defects of the Monte Carlo study are case options of every command."""
    parser = build_parser()
    args = ["--defect-seed", "3", "--defect-modes", "6", "--defect-spectrum", "2", "--roughness", "1e-12"]
    for command in (["simulate"], ["stability"], ["converge"]):
        params = params_from_args(parser.parse_args([*command, *args, "--roughness-seed", "5"]))
        assert params == SailParameters(
            defect_seed=3, defect_mode_count=6, defect_spectrum=2.0, roughness=1e-12, roughness_seed=5
        )
    assert main(["simulate", "--solver", "reduced", "--n", "12", "--t-final", "0.05", "--quiet", "--json", *args]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert printed["parameters"]["defect_seed"] == 3 and printed["parameters"]["roughness"] == 1e-12
    assert main(["simulate", "--defect-seed", "-1"]) == 2
    assert "defect_seed" in capsys.readouterr().err


def test_reproduce_prints_the_wall_time_of_each_pipeline(tmp_path, capsys, monkeypatch):
    """The command runs the chosen pipelines (a stand-in here) with its options and tabulates their wall times."""
    import types

    from lightsail_mbs.cli import reproduce

    calls = []

    def fake_run(out, **kwargs):
        calls.append((out, kwargs))
        print("Fig. 5 — stand-in")
        return {}

    monkeypatch.setattr(reproduce, "pipeline", lambda name: types.SimpleNamespace(FIGURES=(5,), run=fake_run))
    assert (
        main(
            [
                "reproduce",
                "--figure",
                "5",
                "--quick",
                "--solver",
                "reduced",
                "--workers",
                "1",
                "--quiet",
                "--out",
                str(tmp_path),
            ]
        )
        == 0
    )
    printed = capsys.readouterr().out
    assert "Fig. 5" in printed and "wall time" in printed and "| all |" in printed
    [(out, kwargs)] = calls
    assert str(out) == str(tmp_path) and kwargs["quick"] and kwargs["workers"] == 1 and not kwargs["progress"]
    assert kwargs["solver"] == "reduced"


@pytest.mark.parametrize("model", ["torsion", "sheet"])
def test_stability_refuses_a_receding_sail_before_any_run(model, capsys):
    """The scaled problem (E/E_cr,max, runs in t_c) is a sail at rest under a constant beam; a run with
    initial_beta has neither, so the command names the intensity the sail meets instead (I₀ · 9/11 at 0.1)."""
    assert main(["stability", "--model", model, "--n", "6", "--initial-beta", "0.1"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "initial_beta=0.1 is invalid: allowed 0 with stability" in err
    assert "--intensity 8.18182e+07 --initial-beta 0" in err


@pytest.mark.parametrize("model, key", [("torsion", "critical_modulus"), ("tnt", "critical_tension")])
def test_stability_command_json(model, key, capsys):
    code = main(
        ["stability", "--model", model, "--n", "10", "--tau-final", "6", "--factor", "1.2", "--linear", "--json"]
        + (["--tension", "1e-8"] if model == "tnt" else [])
    )
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    lo, hi = out[f"{key}_bracket"]
    assert lo <= out[key] <= hi <= 1.2 * lo * (1 + 1e-12)
    assert out["ratio_to_analytic"] == pytest.approx(out[key] / out["analytic"])
    assert out["linear_relative_shift"] < 1e-9
    # as text: the value with its bracket on one line, as many digits as tell the bracket's ends apart
    assert (
        main(
            ["stability", "--model", model, "--n", "10", "--tau-final", "6", "--factor", "1.2"]
            + (["--tension", "1e-8"] if model == "tnt" else [])
        )
        == 0
    )
    lines = {line.split()[0]: line.split(None, 1)[1] for line in capsys.readouterr().out.splitlines()}
    assert f"{key}_bracket" not in lines
    value, bracket = lines[key].split(" (bracket ")
    low, high = (float(v) for v in bracket.rstrip(")").split("–"))
    assert float(value) == pytest.approx(out[key], rel=0.05) and low <= lo and high >= hi
    assert low == pytest.approx(lo, rel=0.05) and high == pytest.approx(hi, rel=0.05)


def test_bracketed_values_show_the_digits_the_bracket_needs():
    from lightsail_mbs.cli.stability import bracketed

    assert bracketed(3.44056e12, 3.39515e12, 3.48658e12) == "3.44e+12 (bracket 3.39e+12–3.49e+12)"
    assert bracketed(7.63503, 7.5342, 7.7378) == "7.64 (bracket 7.53–7.74)"
    assert bracketed(7.63503, 7.63421, 7.63785) == "7.6350 (bracket 7.6342–7.6379)"
    assert bracketed(2.0, 1.0, 4.0) == "2.0 (bracket 1.0–4.0)"
    assert bracketed(9.97, 9.951, 9.991) == "9.970 (bracket 9.951–9.991)"


def test_cli_render_writes_frames_and_movie(run, tmp_path, capsys):
    path = run.save(tmp_path / "soft")
    out = tmp_path / "frames"
    code = main(
        [
            "render",
            str(path),
            "--out",
            str(out),
            "--frames",
            "3",
            "--size",
            "320x160",
            "--renderer",
            "matplotlib",
            "--movie",
            "gif",
        ]
    )
    assert code == 0
    assert len(list(out.glob("frame_*.png"))) == 3 and (out / "soft.gif").exists()
    assert read_image(out / "frame_0002.png").shape == (160, 320, 3)
    assert main(["render", str(path), "--out", str(out), "--frames", "0"]) == 2
    assert "frames=0" in capsys.readouterr().err


def test_reproduce_rejects_an_unknown_figure(capsys):
    with pytest.raises(SystemExit):
        main(["reproduce", "--figure", "4"])
    assert "invalid choice" in capsys.readouterr().err


def test_crosscheck_cli_rejects_unknown_case(tmp_path):
    with pytest.raises(SystemExit):
        main(["crosscheck", "--cases", "nonsense", "--out", str(tmp_path)])


def test_simulate_and_render_a_sheet(tmp_path, capsys):
    """`simulate --model sheet --nx --ny --mode-y`, then `info` and `render` of the saved run."""
    run = tmp_path / "sheet.npz"
    code = main(
        [
            "simulate",
            "--model",
            "sheet",
            "--nx",
            "6",
            "--ny",
            "4",
            "--mode-y",
            "1",
            "--modulus",
            "4.5e9",
            "--t-final",
            "0.3",
            "--solver",
            "reduced",
            "--out",
            str(run),
            "--quiet",
            "--json",
        ]
    )
    assert code == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["model"] == "sheet" and summary["n"] == 6 and summary["ny"] == 4 and summary["tiles"] == 24
    assert summary["parameters"]["defect_mode_y"] == 1.0 and summary["dissipated_energy"] is None
    assert main(["info", str(run)]) == 0
    assert "6 x 4 tiles" in capsys.readouterr().out
    out = tmp_path / "frames"
    assert main(["render", str(run), "--out", str(out), "--frames", "2", "--movie", "gif", "--quiet"]) == 0
    assert len(list(out.glob("frame_*.png"))) == 2 and (out / "sheet.gif").exists()
    assert main(["render", str(run), "--out", str(out), "--compare", str(run)]) == 2
    assert "--compare" in capsys.readouterr().err


def test_sheet_options_are_checked_before_solving(capsys):
    assert main(["simulate", "--ny", "3"]) == 2
    assert "ny=3 is invalid" in capsys.readouterr().err
    assert main(["simulate", "--model", "sheet", "--edge-tension", "-1"]) == 2
    assert "edge_tension" in capsys.readouterr().err


def test_stability_of_a_small_sheet_json(tmp_path, capsys):
    code = main(
        [
            "stability",
            "--model",
            "sheet",
            "--nx",
            "8",
            "--ny",
            "3",
            "--modulus",
            "4.5e9",
            "--quantity",
            "edge-tension",
            "--run-time",
            "3",
            "--factor",
            "2",
            "--store",
            str(tmp_path),
            "--json",
        ]
    )
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    lo, hi = out["ratio_bracket"]
    assert out["status"] == "converged" and hi / lo <= 2.0 and lo <= out["ratio_to_analytic"] <= hi
    assert out["analytic"] == pytest.approx(3.336e-6, rel=1e-3) and list(tmp_path.glob("*.json"))
    # as text, from the store: the value and the ratio each with its bracket
    args = ["stability", "--model", "sheet", "--nx", "8", "--ny", "3", "--modulus", "4.5e9", "--quantity"]
    assert main([*args, "edge-tension", "--run-time", "3", "--factor", "2", "--store", str(tmp_path)]) == 0
    printed = capsys.readouterr().out
    assert "ratio_bracket" not in printed
    assert (
        sum(line.split()[0] in ("value", "ratio_to_analytic") and "(bracket " in line for line in printed.splitlines())
        == 2
    )


HEAVY = ("matplotlib", "scipy", "exudyn", "numba", "dask", "PIL", "tqdm")


def loaded_after(code: str) -> set[str]:
    """The heavy libraries (HEAVY, and scipy's submodules) in sys.modules after running code in a fresh
    interpreter."""
    probe = f"import sys\n{code}\nprint(' '.join(sorted(sys.modules)))"
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True)
    modules = out.stdout.split()
    return {m for m in modules if m.split(".")[0] in HEAVY and (m.count(".") == 0 or m.startswith("scipy."))}


def test_building_the_parser_imports_no_heavy_library():
    """A command pays only for what it uses: registering every subcommand imports none of them."""
    assert loaded_after("from lightsail_mbs.cli import build_parser\nbuild_parser()") == set()
    assert loaded_after("from lightsail_mbs.cli import main\nmain(['theory'])") == set()


def test_reduced_simulate_imports_numba_and_not_the_rest():
    """The reduced solver's command loads numba (which imports scipy's top level) but not scipy.integrate,
    scipy.optimize, scipy.linalg (numba's BLAS probe is answered), matplotlib or exudyn."""
    args = ["simulate", "--solver", "reduced", "--n", "6", "--t-final", "0.01", "--quiet"]
    code = f"from lightsail_mbs.cli import main\nmain({args!r})"
    loaded = loaded_after(code)
    assert "numba" in loaded
    assert not {"matplotlib", "exudyn", "dask", "PIL", "scipy.integrate", "scipy.optimize", "scipy.linalg"} & loaded


def test_simulate_json_out_and_info_end_to_end(tmp_path, capsys):
    """simulate --json --out prints the summary it saves (.npz and .json); info prints that run's summary
    and its provenance (package and code versions, git commit, libraries)."""
    run = tmp_path / "run"
    out = cli("simulate", "--n", "12", "--t-final", "0.05", "--solver", "reduced", "--quiet", "--json", "--out", run)
    assert out.returncode == 0 and out.stderr == "", out.stderr
    printed = json.loads(out.stdout)
    saved = Result.load(tmp_path / "run.npz")
    assert printed == json.loads(json.dumps(saved.summary())) == json.loads((tmp_path / "run.json").read_text())
    assert printed["settings"]["t_final"] == 0.05 and printed["n"] == 12 and printed["solver"] == "reduced"
    info = cli("info", tmp_path / "run.npz")
    assert info.returncode == 0 and info.stderr == ""
    made = saved.provenance
    assert made["code_version"] == code_version() and made["numpy"] == np.__version__
    for key in ("version", "code_version", "git_commit", "exudyn", "numpy", "scipy", "numba", "python", "platform"):
        line = next(line for line in info.stdout.splitlines() if line.split()[:1] == [key])
        assert line.split(None, 1)[1] == str(made[key])
    assert main(["info", str(tmp_path / "run.npz"), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["provenance"] == made


def test_info_says_when_a_run_has_no_provenance(tmp_path, capsys):
    """Runs saved before provenance existed load and say so."""
    path = growing_sine().save(tmp_path / "old")
    with np.load(path) as data:
        arrays = {k: data[k] for k in data.files}
    summary = json.loads(str(arrays["summary_json"]))
    del summary["provenance"], summary["format"], summary["format_version"]
    np.savez(path, **{**arrays, "summary_json": np.array(json.dumps(summary))})
    assert main(["info", str(path)]) == 0
    assert "provenance: not recorded" in capsys.readouterr().out


@pytest.mark.parametrize("solver", ["reduced", "exudyn"])
def test_failure_ratio_option_reaches_the_solver(solver, tmp_path, capsys):
    """--failure-ratio 3 moves the stop to the first sample at 3 a₀ and the failure time with it."""
    args = ["simulate", "--modulus", "4.5e9", "--n", "12", "--t-final", "6", "--solver", solver, "--quiet", "--json"]
    assert main([*args, "--out", str(tmp_path / "two")]) == 0
    two = json.loads(capsys.readouterr().out)
    assert main([*args, "--failure-ratio", "3", "--out", str(tmp_path / "three")]) == 0
    three = json.loads(capsys.readouterr().out)
    assert (two["settings"]["failure_ratio"], three["settings"]["failure_ratio"]) == (2.0, 3.0)
    r = Result.load(tmp_path / "three.npz")
    assert r.amplitude[-1] >= 3 * r.amplitude[0] > r.amplitude[-2]  # stopped at the first sample at 3 a₀
    assert three["failure_time"] == analysis.failure_time(r.time, r.amplitude, 3.0)
    assert r.time[-2] < three["failure_time"] <= r.time[-1] and three["failure_time"] > two["t_end"]


def test_montecarlo_end_to_end_and_resumed(tmp_path, capsys):
    """The table counts the store's records; a rerun reads them back without recomputing any."""
    store = tmp_path / "store"
    args = ["montecarlo", "--n", "12", "--solver", "reduced", "--seeds", "3", "--values", "4.5e8,4.5e13"]
    args += ["--store", str(store), "--workers", "1", "--json", "--quiet"]
    assert main(args) == 0
    rows = json.loads(capsys.readouterr().out)
    records = CaseStore(store).records()
    assert len(records) == 6 and all(r["status"] == "ok" for r in records)
    for row in rows:
        mine = [r for r in records if r["parameters"]["youngs_modulus"] == row["value"]]
        assert row["runs"] == len(mine) == 3 and row["failures"] == sum(r["failed"] for r in mine)
        assert row["probability"] == row["failures"] / 3
    assert [row["failures"] for row in rows] == [3, 0]  # 1/1000 and 100 × E_cr,max of the sine
    stamps = {p: p.stat().st_mtime_ns for p in store.glob("*.json")}
    assert main(args) == 0
    assert json.loads(capsys.readouterr().out) == rows
    assert {p: p.stat().st_mtime_ns for p in store.glob("*.json")} == stamps


def test_crosscheck_end_to_end_on_a_short_case(tmp_path, capsys, monkeypatch):
    """The command on a shortened torsion-soft case (n = 10, 0.3 s): report, plot, verdict, exit status."""
    from lightsail_mbs.studies import crosscheck

    short = crosscheck.Case("torsion-soft", paper_case("torsion-soft", n=10), RunSettings(t_final=0.3), "short")
    monkeypatch.setitem(crosscheck.CASES, "torsion-soft", short)
    assert main(["crosscheck", "--cases", "torsion-soft", "--out", str(tmp_path), "--quiet"]) == 0
    assert "1/1 cases pass" in capsys.readouterr().out
    report = (tmp_path / "crosscheck.md").read_text()
    row = next(line for line in report.splitlines() if line.startswith("| torsion-soft"))
    assert "✅" in row and (tmp_path / "crosscheck_torsion-soft.png").exists()


def test_reproduce_quick_end_to_end(tmp_path, capsys):
    """reproduce --figure 5 --quick writes the figure and its CSV, whose failure times are the solver's."""
    code = main(
        ["reproduce", "--figure", "5", "--quick", "--solver", "reduced", "--workers", "1", "--quiet"]
        + [
            "--out",
            str(tmp_path),
        ]
    )
    assert code == 0 and "| all |" in capsys.readouterr().out
    assert (tmp_path / "fig5.png").stat().st_size > 10_000
    rows = {float(r["mode"]): r for r in read_csv(tmp_path / "fig5_failure_times.csv")}
    direct = solve(paper_case("rigid", defect_mode=1.5), "reduced", paper_settings("rigid"), uncertainty=False)
    assert float(rows[1.5]["failure_time_ms"]) == direct.failure_time * 1e3
    assert rows[0.5]["failed"] == "False" and rows[1.5]["at_trough"] == "True"


@pytest.mark.parametrize(
    "args, words",
    [
        (["simulate", "--out", "/proc/x.npz"], ["--out", "/proc/x.npz"]),
        (["simulate", "--out", "{tmp}/folder"], ["--out", "a folder"]),
        (["info", "{tmp}/missing.npz"], ["missing.npz", "no such file"]),
        (["info", "{tmp}/text.npz"], ["text.npz", "not a NumPy"]),
        (["render", "{tmp}/truncated.npz", "--out", "{tmp}/frames"], ["truncated.npz"]),
        (["render", "{tmp}/good.npz", "--out", "/proc/frames"], ["--out"]),
        (["render", "{tmp}/good.npz", "--out", "{tmp}/frames", "--movie", "gif", "--fps", "0"], ["fps"]),
        (["montecarlo", "--values", "1e9", "--store", "{tmp}/good.npz"], ["--store"]),
        (["montecarlo", "--values", "1e9,x", "--store", "{tmp}/mc"], ["values"]),
        (["montecarlo", "--values", ",", "--store", "{tmp}/mc"], ["values"]),
        (["reproduce", "--figure", "5", "--out", "/proc/figs"], ["--out"]),
        (["crosscheck", "--out", "/proc/cc"], ["--out"]),
        (["stability", "--factor", "1"], ["factor"]),
        (["stability", "--run-time", "-1"], ["run_time"]),
        (["store", "{tmp}/no-such-store"], ["no-such-store"]),
        (["simulate", "--t-final", "1e300"], ["t_final"]),
    ],
)
def test_foreseeable_failures_end_in_one_line_and_status_2_before_any_work(args, words, tmp_path, capsys, monkeypatch):
    """Bad paths, foreign or damaged files, bad numbers: one line naming the problem, exit 2, and nothing
    solved, rendered or swept first (those functions fail the test if called)."""
    from lightsail_mbs import solvers
    from lightsail_mbs.studies import crosscheck, montecarlo
    from lightsail_mbs.viz import frames

    def never(*args, **kwargs):
        raise AssertionError("work started before the inputs were checked")

    # the commands import these where they call them
    for module, name in ((solvers, "solve"), (frames, "render_frames"), (montecarlo, "run"), (crosscheck, "run")):
        monkeypatch.setattr(module, name, never)
    growing_sine().save(tmp_path / "good")
    (tmp_path / "folder.npz").mkdir()
    (tmp_path / "text.npz").write_text("not a run")
    (tmp_path / "truncated.npz").write_bytes((tmp_path / "good.npz").read_bytes()[:500])
    code = main([a.replace("{tmp}", str(tmp_path)) for a in args])
    err = capsys.readouterr().err.strip()
    assert code == 2 and len(err.splitlines()) == 1 and "Traceback" not in err, err
    assert all(word in err for word in words), err


def test_converge_refines_a_sheet(capsys):
    args = ["converge", "--model", "sheet", "--ny", "2", "--width", "0.5", "--sizes", "4,6", "--t-final", "0.1"]
    assert main([*args, "--no-noise", "--quiet", "--modulus", "4.5e9"]) == 0
    assert "| 6×3 |" in capsys.readouterr().out
    assert main([*args, "--method", "DOP853"]) == 2
    assert "method" in capsys.readouterr().err
