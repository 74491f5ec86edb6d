"""The command line (lightsail_mbs.cli): as a user runs it (JSON output, clear one-line errors, no traceback),
and each subcommand in-process (options, stability, render, reproduce, crosscheck)."""

import json
import subprocess
import sys

import pytest

from lightsail_mbs import RunSettings, SailParameters
from lightsail_mbs.cli import build_parser, main
from lightsail_mbs.cli.options import params_from_args, settings_from_args
from tests.helpers import read_image


def cli(*args):
    return subprocess.run([sys.executable, "-m", "lightsail_mbs.cli", *args], capture_output=True, text=True)


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
    return [subprocess.CompletedProcess(proc.args, proc.returncode, *proc.communicate()) for proc in procs]


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
        assert out.returncode != 0
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
