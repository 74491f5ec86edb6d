"""The journey as one time-domain run (studies/journey_run.py, `journey --time-domain`): its rows come from the
run's record and agree with the closed-form trajectory and the snapshots' heat and tension; a framed sail that
heating leaves slack fails by shape at the start in both solvers at the same moment; the command writes the
journey's files and refuses what the run cannot take in one line."""

import csv

import numpy as np
import pytest

from lightsail_mbs import ParameterError
from lightsail_mbs.model import relativity
from lightsail_mbs.paper.journey import PARKIN_PAYLOAD, parkin_power, starshot_case
from lightsail_mbs.studies.journey import Journey, JourneySettings, craft_mass
from lightsail_mbs.studies.journey_run import run_time_domain

TARGET = 0.002  # β: about 4.3 s of the Starshot-class journey (the whole journey: validation/journey_benchmark.py)


def settings(p, **changes):
    return JourneySettings(power=parkin_power(p), carried_mass=PARKIN_PAYLOAD, target_speed=TARGET, **changes)


def test_the_rows_are_the_runs_record_and_agree_with_the_trajectory_and_the_snapshots():
    p = starshot_case(10)
    s = settings(p)
    report = run_time_domain(p, s, samples=20)
    rows = report["snapshots"]
    assert report["verdict"]["verdict"] == "intact" and len(rows) == 21
    trajectory = relativity.Trajectory(s.power, craft_mass(p, s.carried_mass), p.normal_momentum)
    tau = np.array([r["tau"] for r in rows])
    beta = np.array([trajectory.beta_at_proper_time(t) for t in tau])
    np.testing.assert_allclose([r["beta"] for r in rows], beta, rtol=0, atol=1e-9)
    np.testing.assert_allclose([r["t"] for r in rows], [trajectory.time(b) for b in beta], rtol=1e-9)
    assert rows[-1]["beta"] == pytest.approx(TARGET, rel=1e-9)
    journey = Journey(p, s)
    for row in (rows[0], rows[-1]):
        snapshot = journey.snapshot(row["beta"])
        for key in ("temperature_max", "temperature_mean", "tension", "critical", "margin", "acceleration"):
            assert row[key] == pytest.approx(snapshot[key], rel=1e-6), key


def test_a_slack_sail_fails_at_the_start_in_both_solvers():
    """Framed at 10 N, heating leaves the film slack at switch-on: both solvers' runs fail by shape within
    1e-3 of each other and within their combined uncertainty (each below 1e-2 of it), milliseconds after the
    start, as the snapshots' verdict says; each journey's failure time lies within its ± of the uncertainty rule's
    rerun over the window, and the verdict column turns to 'shape' at the last row, after the failure."""
    p = starshot_case(10, tension=10.0)
    s = settings(p)
    assert Journey(p, s).verdict([Journey(p, s).snapshot(0.0)])["verdict"] == "shape"
    reports = {solver: run_time_domain(p, s, solver, samples=2000) for solver in ("reduced", "exudyn")}
    verdicts = {solver: r["verdict"] for solver, r in reports.items()}
    times = {solver: v["tau"] for solver, v in verdicts.items()}
    assert all(v["verdict"] == "shape" for v in verdicts.values())
    assert 1e-3 < times["reduced"] < 0.1
    assert times["exudyn"] == pytest.approx(times["reduced"], rel=1e-3)
    spread = {solver: v["failure_time_uncertainty"] for solver, v in verdicts.items()}
    assert all(0 < u < 1e-2 * times["reduced"] for u in spread.values())
    for solver, v in verdicts.items():
        assert abs(v["failure_time"] - times[solver]) <= spread[solver]
        assert "±" in v["text"]
        assert [r["verdict"] for r in reports[solver]["snapshots"]][-2:] == ["intact", "shape"]
    assert abs(times["exudyn"] - times["reduced"]) <= spread["exudyn"] + spread["reduced"]


def test_journey_time_domain_writes_the_files_and_refuses_in_one_line(tmp_path, capsys):
    from lightsail_mbs.cli import main

    p = starshot_case(10)
    args = ["journey", "--model", "tnt", "--material", "silicon-nitride", "--n", "10", "--length", str(p.length)]
    args += ["--width", str(p.width), "--thickness", str(p.thickness), "--tension", "100", "--defect-amplitude"]
    args += ["1e-3", "--power", str(parkin_power(p)), "--carried-mass", str(PARKIN_PAYLOAD), "--quiet"]
    args += ["--target-speed", str(TARGET), "--time-domain", "--samples", "10", "--out", str(tmp_path / "j")]
    assert main(args) == 0
    assert "intact" in capsys.readouterr().out
    with open(tmp_path / "j" / "journey.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    assert len(rows) == 11
    for column in ("t", "beta", "temperature_max", "tension", "margin", "amplitude"):
        assert column in rows[0]
    assert (tmp_path / "j" / "journey.png").is_file() and (tmp_path / "j" / "journey.json").is_file()
    with pytest.raises(ParameterError, match="emissivity_front=0.5 is invalid: allowed the material's"):
        run_time_domain(p, settings(p, emissivity_front=0.5))
    with pytest.raises(ParameterError, match="model='sheet' is invalid"):
        run_time_domain(p.replace(model="sheet", n=4, ny=4, tension=0.0), settings(p))


def test_a_table_with_a_wavelength_axis_is_read_inside_the_run(tmp_path, monkeypatch):
    """The framed strip of tests/studies/test_journey_spectrum.py with its table whose c_n(0) falls with λ, run to
    β = 0.05 (λ' from 1.064 to 1.12 µm): the run's lab time and proper time at each sample's β are the snapshots'
    quadrature trajectory's, to 1e-8."""
    from lightsail_mbs.model.optics import SpectralTable
    from tests.studies.test_journey_spectrum import GRID, LASER, case, table

    monkeypatch.setenv("LIGHTSAIL_MBS_CACHE", str(tmp_path / "cache"))
    tables = tuple(table(c, 0.0, lossless=True) for c in (1.9, 1.5))
    path = SpectralTable(np.array(GRID), tables, LASER).save(tmp_path / "falling.npz")
    p = case(str(path)).replace(n=10)
    s = JourneySettings(power=4e10, carried_mass=1e-3, target_speed=0.05)
    report = run_time_domain(p, s, samples=10)
    journey = Journey(p, s)
    for row in report["snapshots"][1:]:
        assert row["tau"] == pytest.approx(journey.trajectory.proper_time(row["beta"]), rel=1e-8)
        assert row["t"] == pytest.approx(journey.trajectory.time(row["beta"]), rel=1e-8)
    assert report["snapshots"][-1]["beta"] == pytest.approx(0.05, rel=1e-8)
    with pytest.raises(ParameterError, match="wavelength=1.03e-06 is invalid: allowed the optical table's laser"):
        run_time_domain(p, JourneySettings(power=4e10, wavelength=1.03e-6))


def test_the_heat_reads_the_tables_absorptance_at_the_sail_frame_wavelength(tmp_path, monkeypatch):
    """A table whose absorptance rises from 1e-5 at 1.0 µm to 3e-5 at 1.4 µm, run to β = 0.05: each sample's
    temperatures are the snapshots' (which read the table's 1 − R − T at λ') to 2e-6, the tension to 1e-6 of N₀,
    and the film
    heats as it speeds up (A(λ') rises faster than I' falls), where the film's own absorptance would cool it."""
    from lightsail_mbs.model.optics import SpectralTable
    from tests.studies.test_journey_spectrum import GRID, LASER, case, table

    monkeypatch.setenv("LIGHTSAIL_MBS_CACHE", str(tmp_path / "cache"))
    tables = (table(1.9, 1e-5, lossless=False), table(1.5, 3e-5, lossless=False))
    path = SpectralTable(np.array(GRID), tables, LASER).save(tmp_path / "absorbing.npz")
    p = case(str(path)).replace(n=10)
    s = JourneySettings(power=4e10, carried_mass=1e-3, target_speed=0.05)
    rows = run_time_domain(p, s, samples=10)["snapshots"]
    journey = Journey(p, s)
    errors = []
    for row in rows:
        snapshot = journey.snapshot(row["beta"])
        errors.append(abs(row["temperature_max"] / snapshot["temperature_max"] - 1))
        # the heating table's linear interpolation in ln D of a T whose A(λ') changes with D too: 2e-6 of T
        for key in ("temperature_max", "temperature_mean"):
            assert row[key] == pytest.approx(snapshot[key], rel=2e-6), key
        # the tension N₀ − relief, to 1e-6 of N₀
        assert row["tension"] == pytest.approx(snapshot["tension"], rel=0, abs=1e-6 * p.tension)
    assert rows[-1]["temperature_max"] > rows[0]["temperature_max"] * 1.01
    print(
        f"largest |ΔT/T| {max(errors):.2g}; T from {rows[0]['temperature_max']:.6g} "
        f"to {rows[-1]['temperature_max']:.6g} K"
    )
