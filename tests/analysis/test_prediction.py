"""The failure time predicted from the linear spectrum (lightsail_mbs.analysis.prediction) against time-domain runs."""

import math

import pytest

from lightsail_mbs import solve
from lightsail_mbs.analysis import prediction, resolvedness
from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.model.cases import paper_case

SETTINGS = RunSettings(t_final=6.0)


def soft(n=30, rms=1e-9, seed=0, modulus=4.5e9):
    return paper_case("torsion-soft").replace(n=n, film_rms=rms, film_seed=seed, youngs_modulus=modulus)


def test_fastest_wave_is_the_verdicts_and_the_seed_scales_with_the_film():
    p = soft()
    got = prediction.predict(p)
    assert math.isclose(got.growth_rate, resolvedness.fastest_wave(prediction.ideal(p)).growth_rate, rel_tol=1e-6)
    assert got.wavelength > 0
    # a film ten times rougher puts ten times the seed into the fastest mode (the film is linear in its RMS)
    assert math.isclose(prediction.predict(soft(rms=1e-8)).seed, 10 * got.seed, rel_tol=1e-3)
    # and fails earlier, by about ln 10 / σ
    assert prediction.predict(soft(rms=1e-8)).time < got.time


@pytest.mark.parametrize("rms, seed, modulus", [(1e-10, 0, 4.5e9), (1e-8, 11, 1.5e10)])
def test_trajectory_prediction_within_five_percent(rms, seed, modulus):
    p = soft(rms=rms, seed=seed, modulus=modulus)
    ideal_run = solve(prediction.ideal(p), "reduced", SETTINGS, uncertainty=False)
    measured = solve(p, "reduced", SETTINGS, uncertainty=False).failure_time
    predicted = prediction.predict(p, trajectory=ideal_run).time
    assert abs(predicted - measured) <= 0.05 * measured


@pytest.mark.slow
def test_validation_set_trajectory_beats_spectrum():
    from tests.helpers import validation_script

    module = validation_script("prediction")
    errors = []
    for p, _, measured, spectrum, along in module.rows():
        errors.append(abs(along.time - measured) / measured)
        assert errors[-1] < abs(spectrum.time - measured) / measured, (p.n, p.film_rms)
        assert errors[-1] <= 0.13, (p.n, p.film_rms)  # validation/prediction.md: +12.3 % at worst
    assert len(errors) >= 10
