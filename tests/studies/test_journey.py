"""The journey: snapshots on the closed-form trajectory with the spacing they promise, the heat and tension of each
moment against the model's closed forms, the three verdicts, the quasi-steady check, and the command's files."""

import csv
import json
import math

import numpy as np
import pytest

from lightsail_mbs import ParameterError, SailParameters
from lightsail_mbs.cli import main
from lightsail_mbs.model import materials, relativity, thermal
from lightsail_mbs.studies.journey import Journey, JourneySettings, run_journey, snapshot_speeds


def starshot_like(**changes):
    """A framed silicon-nitride strip of Parkin's sail area (3.6 m square, 25 nm: 1 g), tensioned to 100 N."""
    fields = {"material": "silicon-nitride", "model": "tnt", "n": 20, "length": 3.6, "width": 3.6}
    fields.update(thickness=2.5e-8, tension=100.0, defect_amplitude=1e-3)
    return SailParameters(**materials.fill({**fields, **changes}))


SETTINGS = JourneySettings(power=4e10, carried_mass=1e-3)


def test_snapshots_change_g0_by_at_most_the_step_and_end_at_the_target():
    for target, step in ((0.2, 0.05), (0.5, 0.01), (1e-6, 0.05)):
        betas = snapshot_speeds(target, step)
        g = relativity.intensity_factor(betas)
        assert betas[0] == 0 and betas[-1] == target and np.all(np.diff(betas) > 0)
        assert np.all(g[1:] / g[:-1] >= 1 - step - 1e-12)


def test_each_snapshot_is_the_closed_forms_of_its_moment():
    p = starshot_like()
    journey = Journey(p, SETTINGS)
    row = journey.snapshot(0.1)
    mass = 3100 * 2.5e-8 * 3.6**2 + 1e-3
    trajectory = relativity.Trajectory(4e10, mass)
    assert row["t"] == pytest.approx(float(trajectory.time(0.1)), rel=1e-12)
    intensity = 4e10 / 3.6**2 * 0.9 / 1.1
    assert row["intensity_sail"] == pytest.approx(intensity, rel=1e-12)
    assert row["acceleration"] == pytest.approx(2 * intensity * 3.6**2 / (mass * 299792458.0), rel=1e-12)
    sin = materials.get("silicon-nitride")
    T = float(thermal.equilibrium_temperature(sin.absorptance.value * intensity, sin.emissivity))
    assert row["temperature_max"] == pytest.approx(T, rel=1e-12)
    relief = sin.youngs_modulus.value * 2.5e-8 * 3.6 * sin.thermal_expansion.value * (T - 293.15)
    assert row["tension"] == pytest.approx(100.0 - relief, rel=1e-12)
    assert row["tension_needed"] == pytest.approx(relief + row["critical"], rel=1e-12)
    assert row["wavelength"] == pytest.approx(1.064e-6 * math.sqrt(1.1 / 0.9), rel=1e-12)


def test_the_three_verdicts():
    """100 N survives the heated start; 10 N is less than the ~50 N expansion relieves (slack at τ = 0); an
    aluminium film of the same mass absorbs 6 % of 3 GW/m² and is far beyond its melting point at τ = 0."""
    intact = run_journey(starshot_like(), SETTINGS)
    assert intact["verdict"]["verdict"] == "intact" and intact["thermal_lag"] < 1e-6
    slack = run_journey(starshot_like(tension=10.0), SETTINGS)
    assert slack["verdict"]["verdict"] == "shape" and slack["verdict"]["tau"] == 0.0
    cold = run_journey(starshot_like(tension=10.0), JourneySettings(power=4e10, carried_mass=1e-3, absorptance=0.0))
    assert cold["verdict"]["verdict"] == "intact"  # no heat, no relief: the expansion decides the verdict
    metal = run_journey(starshot_like(material="aluminium", thickness=2.5e-8 * 3100 / 2700), SETTINGS)
    assert metal["verdict"]["verdict"] == "temperature" and metal["snapshots"][0]["temperature_max"] > 933


def test_a_film_too_slow_to_follow_the_beam_is_refused():
    """A silica film absorbing 1e-13 of 1e10 W/m² sits near 13 K, where it radiates so little that its thermal
    time is longer than the time its beam changes over: it would lag the steady field by ~25 %."""
    p = SailParameters(**materials.fill({"material": "silica", "model": "tnt", "tension": 1.0, "thickness": 1e-7}))
    with pytest.raises(ParameterError, match="lags by 0.2"):
        run_journey(p, JourneySettings(power=1e10, absorptance=1e-13))


def test_a_case_without_a_material_is_one_line():
    with pytest.raises(ParameterError, match="material=None"):
        run_journey(SailParameters(), SETTINGS)


def test_the_command_writes_csv_json_and_png(tmp_path, capsys):
    out = tmp_path / "journey"
    args = ["journey", "--model", "tnt", "--material", "silicon-nitride", "--length", 3.6, "--width", 3.6]
    args += ["--thickness", 2.5e-8, "--tension", 10, "--defect-amplitude", 1e-3, "--power", 4e10]
    assert main([str(a) for a in [*args, "--carried-mass", 1e-3, "--out", out, "--quiet"]]) == 0
    assert "fails by shape" in capsys.readouterr().out
    with open(out / "journey.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    assert {"t", "beta", "temperature_max", "margin"} <= set(rows[0]) and float(rows[-1]["beta"]) == 0.2
    report = json.loads((out / "journey.json").read_text())
    assert report["verdict"]["verdict"] == "shape" and report["film"]["material"] == "silicon-nitride"
    assert (out / "journey.png").stat().st_size > 10000


def test_both_solvers_agree_on_a_heated_doppler_shifted_snapshot_run_to_failure():
    """The Starshot-class chain at β = 0.15 (I' = 0.74 I), pre-tensioned so that heating leaves half the
    critical tension: both solvers' shape runs fail, at times within 1e-3 of each other."""
    from lightsail_mbs.paper.journey import starshot_case
    from lightsail_mbs.studies.journey import shape_run

    p = starshot_case(10)
    row = Journey(p, SETTINGS).snapshot(0.15)
    p = p.replace(tension=p.tension - row["tension"] + 0.5 * row["critical"])
    row = Journey(p, SETTINGS).snapshot(0.15)
    assert row["margin"] == pytest.approx(0.5, rel=1e-9)
    runs = [shape_run(p, row, 20.0, solver) for solver in ("reduced", "exudyn")]
    assert all(r["shape_failed"] for r in runs)
    assert runs[0]["shape_failure_time"] == pytest.approx(runs[1]["shape_failure_time"], rel=1e-3)


def test_a_journey_refuses_a_case_that_starts_receding():
    """The journey follows the sail from rest and lights each snapshot's shape run at its moment's Doppler-shifted
    intensity; a case with initial_beta would dim those runs a second time, so it is refused before any work."""
    with pytest.raises(ParameterError, match="initial_beta=0.1 is invalid: allowed 0 for a journey"):
        Journey(starshot_like().replace(initial_beta=0.1), JourneySettings(power=4e10, shape_runs=True))
