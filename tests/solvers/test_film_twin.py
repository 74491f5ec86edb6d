"""The film in the case (model.film through SailParameters.film_*) and the film twin of the uncertainty
estimate: the verdict defect- or roughness-dominated."""

import numpy as np
import pytest

from lightsail_mbs import ParameterError, RunSettings, SailParameters, paper_case, solve
from lightsail_mbs.model import film, shapes


def test_film_fields_are_checked_in_one_line_naming_them():
    for changes, words in (
        ({"film_rms": -1e-9}, "film_rms=-1e-09 is invalid"),
        ({"film_rms": 1e-9, "film_hurst": 1.5}, "film_hurst=1.5 is invalid: allowed 0 < H ≤ 1"),
        ({"film_correlation_length": 0.0}, "film_correlation_length=0.0 is invalid"),
        ({"film_seed": -1}, "film_seed=-1 is invalid"),
    ):
        with pytest.raises(ParameterError, match=words) as caught:
            SailParameters(**changes)
        assert "\n" not in str(caught.value)
    assert SailParameters(model="sheet", n=4, ny=4, film_rms=1e-9).film_rms == 1e-9


def test_a_case_without_a_film_keeps_its_record():
    assert not any(name.startswith("film") for name in SailParameters().to_dict())
    assert SailParameters(film_rms=1e-9).to_dict()["film_rms"] == 1e-9


def test_the_film_is_added_to_the_start_at_its_carried_rms():
    """The slice centres move off the ideal defect by about the film's RMS on the waves the chain carries, and
    the same film on a finer chain keeps its long waves (the same mode coefficients)."""
    p = paper_case("torsion-soft")
    spectrum = film.REFERENCE_FILM
    rough = p.replace(film_rms=spectrum.rms, film_correlation_length=spectrum.correlation_length)
    moved = shapes.initial_state(rough).y - shapes.initial_state(p).y
    carried = np.sqrt(film.carried_variance(spectrum, p.length, p.n))
    assert 0.3 * carried < np.sqrt(np.mean(moved**2)) < 3 * carried
    coarse, fine = (film.film_profile(spectrum, p.length, n, rough.film_seed) for n in (30, 60))
    assert np.array_equal(fine.cosine[:30], coarse.cosine) and np.array_equal(fine.sine[:30], coarse.sine)


def test_the_paper_soft_sail_is_roughness_dominated_and_the_stiff_one_defect_dominated():
    """A nanometre film moves the soft sail's failure time by ~13 % at n = 30 (its short waves grow from it);
    the stable sail's largest amplitude ratio hardly moves."""
    soft = solve(paper_case("torsion-soft"), "reduced", RunSettings(t_final=6.0))
    verdict = soft.uncertainty["film_sensitivity"]
    assert verdict["verdict"] == "roughness-dominated" and 0.05 < verdict["relative_shift"] < 0.3
    assert verdict["value"] < soft.failure_time and 0 < verdict["holds_below"] < film.REFERENCE_FILM.rms
    assert "roughness-dominated" in soft.film_text()
    stiff = solve(paper_case("torsion-stable"), "reduced", RunSettings(t_final=1.0))
    verdict = stiff.uncertainty["film_sensitivity"]
    assert verdict["verdict"] == "defect-dominated" and verdict["relative_shift"] <= 1e-3
    assert verdict["holds_below"] is None


def test_a_filmed_case_is_twinned_with_its_film_at_the_next_seed():
    r = solve(paper_case("torsion-soft", film_rms=1e-9), "reduced", RunSettings(t_final=6.0))
    assert r.uncertainty["film_sensitivity"]["film"] == "the same film at seed 1"
    assert r.uncertainty["film"]["value"] != r.uncertainty["base"]["value"]


def test_both_sheet_solvers_start_a_filmed_sheet_alike_and_agree_to_their_error_bars():
    """A 6 × 6 soft sheet with the reference film, 0.5 s: Exudyn and the reduced solver agree on the largest
    amplitude ratio within their combined U, the film moves it by more than that U, and each solver's film
    twin (the same film at the next seed) assesses the sheet."""
    ref = film.REFERENCE_FILM
    p = SailParameters(model="sheet", n=6, ny=6, youngs_modulus=4.5e9, film_rms=ref.rms)
    settings = RunSettings(t_final=0.5)
    runs = {name: solve(p, name, settings) for name in ("exudyn", "reduced")}
    a, b = (runs[name].uncertainty for name in ("exudyn", "reduced"))
    assert a["estimated"] and b["estimated"] and a["quantity"] == b["quantity"] == "max_amplitude_ratio"
    assert abs(a["value"] - b["value"]) <= a["uncertainty"] + b["uncertainty"]
    ideal = solve(p.replace(film_rms=0.0), "reduced", settings)
    assert abs(ideal.uncertainty["value"] - b["value"]) > a["uncertainty"] + b["uncertainty"]
    for run in runs.values():
        verdict = run.uncertainty["film_sensitivity"]
        assert verdict["assessed"] and verdict["film"] == "the same film at seed 1"
        assert verdict["verdict"] in ("defect-dominated", "roughness-dominated") and verdict["shift"] > 0
        assert run.film_text().startswith("film: with the same film at seed 1")


def test_the_film_twin_of_a_sheet_without_a_film_is_the_reference_film():
    p = SailParameters(model="sheet", n=4, ny=4, youngs_modulus=4.5e9)
    r = solve(p, "reduced", RunSettings(t_final=0.3))
    verdict = r.uncertainty["film_sensitivity"]
    assert verdict["assessed"] and verdict["film"].startswith("the reference film")
    assert verdict["value"] != r.uncertainty["value"]
