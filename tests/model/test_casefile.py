"""Case files (lightsail_mbs.model.casefile) and the field table (lightsail_mbs.model.fields): every field is
described; a case written and read back is the same case; a bad file is one line naming the file and key."""

import dataclasses
import math
from pathlib import Path

import pytest
from hypothesis import given

from lightsail_mbs import ParameterError, RunSettings, SailParameters, paper_case, paper_settings
from lightsail_mbs.model import casefile
from lightsail_mbs.model.casefile import tomllib  # the standard library's, or tomli on Python 3.10
from lightsail_mbs.model.cases import PAPER_CASES
from lightsail_mbs.model.fields import FIELDS, number
from lightsail_mbs.model.parameters import read_case_file
from tests.strategies import EXAMPLES, case_kwargs, check_property


def test_the_field_table_describes_every_field_and_no_other():
    names = [f.name for f in dataclasses.fields(SailParameters)]
    assert list(FIELDS) == names
    for name, info in FIELDS.items():
        assert info.help and info.family in ("all", "chain", "sheet"), name
        annotation = next(f.type for f in dataclasses.fields(SailParameters) if f.name == name)
        assert bool(info.allowed) != annotation.startswith("bool"), name  # True/False needs no range text


def test_fields_of_the_other_family_are_refused_away_from_their_defaults():
    """The table's family agrees with the validation: a non-default value of a sheet field is refused for
    a chain (and the chain fields that a sheet refuses are marked chain)."""
    for name in (n for n, info in FIELDS.items() if info.family == "sheet"):
        value = {"ny": 3, "membrane_reference": "flat", "bending_reference": "initial", "initial_equilibrium": True}
        with pytest.raises(ParameterError, match=f"{name}="):
            SailParameters(**{name: value.get(name, 0.5)})


@pytest.mark.parametrize(
    "value, text", [(4.5e13, "4.5e+13"), (1e-6, "1e-06"), (0.5, "0.5"), (3.34e-3, "0.00334"), (3.34e-8, "3.34e-08")]
)
def test_numbers_read_as_a_user_reads_them(value, text):
    assert number(value) == text and float(number(value)) == value
    assert number(299_792_458.0) == "2.99792458e+08" and number(3) == "3" and number(math.inf) == "inf"


@pytest.mark.parametrize("name", list(PAPER_CASES))
def test_the_paper_cases_are_their_files_and_run_as_the_paper_did(name):
    """Each paper case is its shipped file, and the file's [run] table is the paper's run."""
    path = PAPER_CASES.path(name)
    assert paper_case(name) == SailParameters.from_toml(path)
    assert RunSettings(**read_case_file(path)[1]) == paper_settings(name)
    assert sorted(p.stem for p in PAPER_CASES.folder.glob("*.toml")) == sorted(PAPER_CASES)


def test_paper_cases_keep_their_physics():
    """The paper's numbers: the stable torsion sail has E = 100 E_cr,max, the soft one E_cr,max/100; the
    TnT sails T = 1000 T_cr,max and T_cr,max/100 (Eqs 8, 10)."""
    from lightsail_mbs.model import theory

    for name, expected in (("torsion-stable", 100), ("torsion-soft", 0.01)):
        p = paper_case(name)
        assert p.youngs_modulus / theory.critical_modulus_max(p) == pytest.approx(expected, rel=0.01)
    ratio = {k: theory.critical_tension_max(paper_case(k)) for k in ("tnt-stable", "tnt-soft")}
    assert paper_case("tnt-stable").tension / ratio["tnt-stable"] == pytest.approx(1000, rel=0.01)
    assert paper_case("tnt-soft").tension / ratio["tnt-soft"] == pytest.approx(0.01, rel=0.01)


@pytest.mark.parametrize("examples", EXAMPLES)
def test_a_case_written_and_read_back_is_the_same_case(examples, tmp_path):
    @given(case_kwargs())
    def round_trip(kwargs):
        try:
            p = SailParameters(**kwargs)
        except ParameterError:
            return
        path = p.to_toml(tmp_path / "case.toml", RunSettings(t_final=0.25))
        assert SailParameters.from_toml(path) == p
        assert read_case_file(path)[1] == {"t_final": 0.25, "stop_at_failure": True, "failure_ratio": 2.0}
        tomllib.loads(path.read_text())  # a TOML file any reader takes

    check_property(round_trip, examples)


def test_a_case_file_holds_what_describes_the_sail(tmp_path):
    """Defaults that follow other fields stay out at their followed value (so they follow an override), and so
    do the other family's fields; every line says what it is."""
    text = SailParameters(model="tnt", tension=1e-3, beam_waist=0.4).to_toml(tmp_path / "c.toml").read_text()
    keys = {
        key: value for table in tomllib.loads(text).values() if isinstance(table, dict) for key, value in table.items()
    }
    assert not {"beam_centre", "bending", "ny", "edge_tension"} & set(keys) and keys["tension"] == 1e-3
    assert 'format = "lightsail-mbs case"' in text.splitlines()[0] and "beam_waist = 0.4  # Gaussian" in text
    assert "youngs_modulus = 4.5e+13  # Young's modulus E (Pa)" in text
    moved = SailParameters(beam_centre=0.2).to_toml(tmp_path / "m.toml")
    assert SailParameters.from_toml(moved).beam_centre == 0.2


@pytest.mark.parametrize(
    "text, words",
    [
        ("n = = 3", ["line 1"]),
        ("thicknes = 1e-6", ["thicknes", "did you mean thickness", "allowed"]),
        ("n = 2.5", ["n = 2.5", "an integer"]),
        ('thickness = "thin"', ["thickness", "a number"]),
        ("n = 1", ["n=1", "2 ≤ n ≤ 5000"]),
        ("ny = 3", ["ny=3", "unless model='sheet'"]),
        ("version = 3\nn = 12", ["version = 3", "up to version 2"]),
        ('version = "2"\nn = 12', ['version = "2"', "an integer 1 … 2", "up to version 2)"]),
        ('format = "other"', ["format", "lightsail-mbs case"]),
        ("[hull]\nn = 3", ["[hull]", "allowed", "[sail]"]),
        ("version = 1\n[sheet]\nny = 3", ["[sheet]", "version 1"]),
        ("version = 2\nn = 12", ["n at the top", "allowed in [sail]"]),
        ("[beam]\nny = 3", ["beam.ny", "wrong table", "allowed in [sheet]"]),
        ("[beam]\nbeam_wasit = 0.3", ["beam.beam_wasit", "did you mean beam_waist", "allowed in [beam]"]),
        ('[beam]\nbeam_waist = "wide"', ["beam.beam_waist", "a number"]),
        ('[sail]\nmodel = "torsion"\n[sheet]\nny = 3', ["ny=3", "unless model='sheet'"]),
        ('[sail]\nmodel = "torsion"\n[supports]\ninitial_tilt_y = 0.1', ["initial_tilt_y", "unless model='sheet'"]),
        ("[run]\nt_fnal = 1.0", ["run.t_fnal", "t_final"]),
        ("[run]\nstop_at_failure = 1", ["run.stop_at_failure = 1", "allowed true or false"]),
        ("[run]\nt_final = true", ["run.t_final = true", "allowed a number"]),
        ("[beam]\nbeam_centre = 0.3\nbeam_center = 0.4", ["beam.beam_centre and beam.beam_center", "one of them"]),
        ("amplitude = 1e-5\ndefect_amplitude = 2e-5", ["amplitude and defect_amplitude", "same field"]),
        ("[beams]\nintensity = 1e8", ["[beams]", "did you mean beam?"]),
        ("t_final = 2.0", ["t_final at the top", "allowed in [run] (run.t_final)"]),
        ("[sail]\nfailure_ratio = 3.0", ["sail.failure_ratio is in the wrong table", "allowed in [run]"]),
    ],
)
def test_a_bad_case_file_is_one_line_naming_the_file_and_the_key(text, words, tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(text + "\n")
    with pytest.raises(ParameterError) as err:
        SailParameters.from_toml(path)
    message = str(err.value)
    assert len(message.splitlines()) == 1 and message.startswith(str(path)), message
    for word in words:
        assert word in message, message


def test_a_missing_case_file_is_named(tmp_path):
    with pytest.raises(ParameterError, match="nothere.toml: no such file"):
        SailParameters.from_toml(tmp_path / "nothere.toml")
    with pytest.raises(casefile.CaseFileError, match="a folder"):
        casefile.read(tmp_path, {})


def test_a_version_1_file_and_its_version_2_file_are_the_same_case(tmp_path):
    """A flat (version 1) file reads as it always did; its case written again is a version 2 file of section
    tables, older field names included (beam_center), and reads back to the same case."""
    flat = tmp_path / "flat.toml"
    flat.write_text('version = 1\nmodel = "sheet"\nn = 4\nny = 3\nbeam_waist = 0.5\nbeam_center = 0.3\n')
    p = SailParameters.from_toml(flat)
    assert p == SailParameters(model="sheet", n=4, ny=3, beam_waist=0.5, beam_centre=0.3)
    text = p.to_toml(tmp_path / "sections.toml").read_text()
    tables = tomllib.loads(text)
    assert tables["version"] == 2 and tables["sail"]["model"] == "sheet" and tables["sheet"]["ny"] == 3
    assert tables["beam"]["beam_centre"] == 0.3 and "optics" not in tables  # the chain's sections left out
    assert SailParameters.from_toml(tmp_path / "sections.toml") == p
    old = tmp_path / "old_names.toml"
    old.write_text('[sail]\nmodel = "sheet"\nn = 4\nny = 3\n[beam]\nbeam_waist = 0.5\nbeam_center = 0.3\n')
    with pytest.raises(ParameterError, match="sail.ny is in the wrong table: allowed in \\[sheet\\]"):
        SailParameters.from_toml(old)
    old.write_text('[sail]\nmodel = "sheet"\nn = 4\n[sheet]\nny = 3\n[beam]\nbeam_waist = 0.5\nbeam_center = 0.3\n')
    assert SailParameters.from_toml(old) == p


def test_a_table_path_in_a_case_file_is_relative_to_its_folder(tmp_path, monkeypatch):
    """A case saved next to its optical table reads from any working folder, and a case saved into another
    folder names the table from there; the case read is the one written (the same table, the same digest)."""
    from lightsail_mbs.model import optics

    project = tmp_path / "project"
    project.mkdir()
    monkeypatch.chdir(project)
    optics.facet(0.9, 0.0).save("facet.npz")
    p = SailParameters(optics="facet.npz")
    p.to_toml("case.toml")
    (tmp_path / "elsewhere").mkdir()
    p.to_toml(tmp_path / "elsewhere" / "case.toml")
    assert 'optics = "../project/facet.npz"' in (tmp_path / "elsewhere" / "case.toml").read_text()
    monkeypatch.chdir(tmp_path)
    for path in (project / "case.toml", tmp_path / "elsewhere" / "case.toml"):
        back = SailParameters.from_toml(path)
        assert Path(back.optics).resolve() == (project / "facet.npz").resolve()
        assert back.optics_digest == p.replace(optics=str(project / "facet.npz")).optics_digest


def test_the_run_settings_written_with_a_case_read_back(tmp_path):
    from lightsail_mbs.model.parameters import run_settings_of_case_file

    path = SailParameters().to_toml(tmp_path / "c.toml", RunSettings(t_final=0.25, failure_ratio=3.0))
    assert run_settings_of_case_file(path) == RunSettings(t_final=0.25, failure_ratio=3.0)
    assert run_settings_of_case_file(SailParameters().to_toml(tmp_path / "bare.toml")) is None
    (tmp_path / "bad.toml").write_text("[run]\nt_final = -1.0\n")
    with pytest.raises(ParameterError, match=r"bad.toml: \[run\] t_final=-1.0 is invalid"):
        run_settings_of_case_file(tmp_path / "bad.toml")
