"""Case files and case sources on the command line: `lightsail-mbs simulate case.toml`, options over the file,
--save-case, a saved run or a paper case as the source, one-line errors for bad files; the generated case
options and the surface a user reads (--help, --version, theory's criteria, info's verdict)."""

import dataclasses
import json

import pytest

from lightsail_mbs import RunSettings, SailParameters, paper_case, paper_settings
from lightsail_mbs.cli import build_parser, main
from lightsail_mbs.cli.options import option_name, params_from_args, settings_from_args

QUICK = ["--solver", "reduced", "--t-final", "0.02", "--no-uncertainty", "--quiet"]


def parsed(*args):
    return build_parser().parse_args([str(a) for a in args])


def test_simulate_runs_a_case_file_and_options_override_it(tmp_path, capsys):
    case = tmp_path / "case.toml"
    SailParameters(n=10, youngs_modulus=4.5e9).to_toml(case, RunSettings(t_final=0.5))
    assert main(["simulate", str(case), *QUICK, "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["parameters"]["n"] == 10 and summary["parameters"]["youngs_modulus"] == 4.5e9
    assert summary["settings"]["t_final"] == 0.02  # --t-final over the file's [run] table
    args = parsed("simulate", case, "--n", 14, "--model", "tnt", "--tension", 1e-3)
    assert params_from_args(args) == SailParameters(n=14, model="tnt", tension=1e-3, youngs_modulus=4.5e9)
    assert settings_from_args(args) == RunSettings(t_final=0.5)


def test_a_default_that_follows_another_field_follows_it_over_a_file(tmp_path):
    """The file of a torsion sail holds neither its bending (on for torsion) nor its beam axis (L/2): --model tnt
    turns bending off and --length 2 moves the axis to 1 m, as with no file."""
    case = SailParameters(beam_waist=0.3).to_toml(tmp_path / "c.toml")
    p = params_from_args(parsed("theory", case, "--model", "tnt", "--tension", 1e-3, "--length", 2))
    assert p.bending is False and p.beam_centre == 1.0


def test_the_older_spelling_of_the_beam_axis_is_read_from_files_and_options(tmp_path):
    """beam_center / --beam-center (the spelling before beam_centre): a case file, a saved run's summary and
    the command line still take it; --help shows only the new spelling."""
    case = tmp_path / "old.toml"
    case.write_text('model = "sheet"\nn = 4\nny = 3\nbeam_waist = 0.5\nbeam_center = 0.3\nbeam_center_y = 0.6\n')
    expected = SailParameters(model="sheet", n=4, ny=3, beam_waist=0.5, beam_centre=0.3, beam_centre_y=0.6)
    assert SailParameters.from_toml(case) == expected
    summary = tmp_path / "old.json"
    parameters = {"beam_center" if k == "beam_centre" else k: v for k, v in SailParameters(n=6).to_dict().items()}
    summary.write_text(json.dumps({"format": "lightsail-mbs result", "format_version": 1, "parameters": parameters}))
    assert params_from_args(parsed("theory", summary)) == SailParameters(n=6)
    args = parsed("theory", "--model", "sheet", "--beam-center", 0.3, "--beam-center-y", 0.6)
    assert (params_from_args(args).beam_centre, params_from_args(args).beam_centre_y) == (0.3, 0.6)
    text = build_parser()._subparsers._group_actions[0].choices["simulate"].format_help()
    assert "--beam-centre-y" in text and "beam-center" not in text


@pytest.mark.parametrize(
    "options",
    [["--n", "9", "--modulus", "4.5e10", "--beam-waist", "0.3"], ["--model", "sheet", "--nx", "6", "--ny", "4"]],
    ids=["chain", "sheet"],
)
def test_save_case_round_trips(options, tmp_path, capsys):
    saved = tmp_path / "saved.toml"
    args = parsed("theory", *options)
    assert main(["theory", *options, "--save-case", str(saved)]) == 0
    assert "wrote the case to" in capsys.readouterr().err
    assert SailParameters.from_toml(saved) == params_from_args(args) != SailParameters()
    assert params_from_args(parsed("theory", saved)) == SailParameters.from_toml(saved)


def test_save_case_keeps_the_run_given(tmp_path, capsys):
    saved = tmp_path / "run.toml"
    assert main(["simulate", "torsion-soft", "--n", "8", *QUICK, "--save-case", str(saved)]) == 0
    again = parsed("simulate", saved)
    assert params_from_args(again) == paper_case("torsion-soft", n=8)
    assert settings_from_args(again) == paper_settings("torsion-soft", t_final=0.02)


def test_a_saved_run_is_a_case_source(tmp_path, capsys):
    """RUN.json (next to RUN.npz) and RUN.npz give the case and the run that made it."""
    run = tmp_path / "run.npz"
    assert main(["simulate", "--n", "8", "--modulus", "4.5e10", *QUICK, "--out", str(run)]) == 0
    capsys.readouterr()
    for source in (run.with_suffix(".json"), run):
        args = parsed("simulate", source)
        assert params_from_args(args) == SailParameters(n=8, youngs_modulus=4.5e10)
        assert settings_from_args(args) == RunSettings(t_final=0.02)


def test_a_paper_case_by_name_is_its_case_and_run():
    args = parsed("simulate", "rigid")
    assert params_from_args(args) == paper_case("rigid") and settings_from_args(args) == paper_settings("rigid")


BAD_FILES = [
    ("syntax", "n = = 3", ["not valid TOML", "line 1"]),
    ("unknown key", "thicknes = 1e-6", ["thicknes", "did you mean thickness"]),
    ("wrong type", 'thickness = "thin"', ["thickness", "allowed a number"]),
    ("out of range", "thickness = -1e-6", ["thickness=-1e-06", "> 0"]),
    ("another family's field", "ny = 3", ["ny=3", "unless model='sheet'"]),
    ("newer version", "version = 7", ["version = 7", "up to version 2"]),
    ("key in the wrong table", "[beam]\nny = 3", ["beam.ny", "allowed in [sheet]"]),
    ("unknown table", "[hull]\nn = 12", ["unknown table [hull]", "[sail]"]),
    ("another family's table", '[sail]\nmodel = "torsion"\n[sheet]\nny = 3', ["ny=3", "unless model='sheet'"]),
    ("bad run entry", "[run]\nfailure_ratio = 0.5", ["[run] failure_ratio", "> 1"]),
]


@pytest.mark.parametrize("text, words", [b[1:] for b in BAD_FILES], ids=[b[0] for b in BAD_FILES])
def test_a_bad_case_file_is_one_line_naming_the_file_and_the_key(text, words, tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text(text + "\n")
    assert main(["simulate", str(path), *QUICK]) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and f"error: {path}: " in err and "Traceback" not in err, err
    for word in words:
        assert word in err, err


def test_a_missing_or_foreign_source_is_named(tmp_path, capsys):
    assert main(["theory", str(tmp_path / "none.toml")]) == 2
    assert "none.toml: no such file" in capsys.readouterr().err
    (tmp_path / "other.json").write_text('{"format": "something else"}')
    assert main(["theory", str(tmp_path / "other.json")]) == 2
    assert "other.json: not a saved lightsail-mbs run" in capsys.readouterr().err


def test_an_option_over_a_bad_file_entry_fixes_it(tmp_path, capsys):
    path = tmp_path / "thin.toml"
    path.write_text("thickness = -1e-6\n")
    assert main(["theory", str(path), "--thickness", "2e-6", "--json"]) == 0
    assert main(["theory", str(path), "--n", "1"]) == 2
    assert capsys.readouterr().err.count("\n") == 1


def test_converge_takes_a_case_source_or_case_not_both(capsys):
    assert main(["converge", "torsion-soft", "--case", "rigid"]) == 2
    assert "--case" in capsys.readouterr().err


def test_every_case_field_has_an_option_in_simulate_help(capsys):
    with pytest.raises(SystemExit):
        main(["simulate", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    for field in dataclasses.fields(SailParameters):
        assert option_name(field.name) + " " in text or option_name(field.name) + "," in text, field.name
    assert "default: the sail's middle L/2" in text and "[default: 4.5e+13]" in text
    assert "45000000000000.0" not in text and "100000000.0" not in text
    for option in ("--boundary", "--tip-load", "--pressure", "--membrane-damping", "--initial-equilibrium"):
        assert option in text


def test_the_new_case_options_reach_the_case():
    p = params_from_args(parsed("simulate", "--model", "sheet", "--boundary", "clamped", "--pressure", "0.1"))
    assert p.boundary == "clamped" and p.pressure == 0.1
    p = params_from_args(parsed("simulate", "--boundary", "cantilever", "--tip-load", "1e-6"))
    assert p.tip_load == 1e-6 and p.boundary == "cantilever"


def test_version_and_a_help_written_for_users(capsys):
    with pytest.raises(SystemExit) as done:
        main(["--version"])
    assert done.value.code == 0 and capsys.readouterr().out.startswith("lightsail-mbs ")
    with pytest.raises(SystemExit):
        main(["--help"])
    text = capsys.readouterr().out
    assert "keep its shape" in text and "parse, call the library" not in text
    assert all(command in text for command in ("theory", "simulate", "info", "stability", "montecarlo"))


def test_theory_prints_the_stiffness_ratios_and_the_papers_prediction(capsys):
    """E/E_cr,max of the soft torsion sail is 1/100 (Fig. 7: it fails), T/T_cr,max of the stable TnT one 1000."""
    assert main(["theory", "torsion-soft", "--json"]) == 0
    soft = json.loads(capsys.readouterr().out)
    assert soft["e_over_e_cr_max"] == pytest.approx(0.01, rel=0.01) and soft["paper_prediction"].startswith("fails")
    assert main(["theory", "tnt-stable", "--json"]) == 0
    tnt = json.loads(capsys.readouterr().out)
    assert tnt["t_over_t_cr_max"] == pytest.approx(1000, rel=0.01) and "keeps its shape" in tnt["paper_prediction"]
    assert tnt["e_over_e_cr_max"] == 0  # the paper's TnT sail has no bending springs


def test_info_prints_the_answer_with_its_error_bar_and_the_verdict(tmp_path, capsys):
    run = tmp_path / "soft.npz"
    args = ["simulate", "torsion-soft", "--n", "8", "--solver", "reduced", "--t-final", "3", "--quiet"]
    assert main([*args, "--out", str(run)]) == 0
    capsys.readouterr()
    assert main(["info", str(run)]) == 0
    out = capsys.readouterr().out
    assert "answer: FAILED at t = " in out and " ± " in out
    assert "conditioning: well-conditioned" in out or "conditioning: ILL-CONDITIONED" in out
    assert main(["info", str(run.with_suffix(".json"))]) == 0  # the summary written beside the run names it
    assert capsys.readouterr().out == out
