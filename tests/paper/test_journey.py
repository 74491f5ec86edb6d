"""The whole-acceleration page's pipeline: Parkin's point design reproduced by the power chosen, the verdicts the
page states, the files it writes; and a snapshot's shape run agreeing with its margin."""

import pytest

from lightsail_mbs.paper import journey


def test_the_parkin_power_reaches_0_2c_in_nine_minutes():
    p = journey.starshot_case(10)
    assert p.density * p.thickness * p.length * p.width == pytest.approx(journey.SAIL_MASS, rel=1e-12)
    assert p.length * p.width == pytest.approx(3.14159265 * 2.05**2, rel=1e-8)
    results = journey.journeys(quick=True, shape_runs=False)
    assert results["starshot"][3]["snapshots"][-1]["t"] == pytest.approx(540.0, rel=1e-12)
    assert 1e10 < results["starshot"][2].power < 1e11  # tens of GW, as the mission studies


def test_the_pages_verdicts_and_files(tmp_path):
    results = journey.run(tmp_path, quick=True, shape_runs=False)
    verdicts = {name: r[3]["verdict"]["verdict"] for name, r in results.items()}
    assert verdicts["starshot"] == "intact" and verdicts["starshot-10N"] == "shape"
    assert verdicts["starshot-10N-cold"] == "intact" and verdicts["starshot-unframed"] == "shape"
    assert verdicts["starshot-aluminium"] == "temperature" and verdicts["lab-1000W-aluminium"] == "temperature"
    assert verdicts["lab-1000W"] == "intact"
    for name in ("journey.md", "journey_summary.csv", "journey_starshot.png", "journey_lab-1000W-spot.csv"):
        assert (tmp_path / name).stat().st_size > 0


def test_a_slack_snapshot_fails_its_shape_run_and_a_tensioned_one_does_not():
    from lightsail_mbs.studies.journey import Journey, JourneySettings, shape_run

    settings = JourneySettings(power=4e10, carried_mass=1e-3)
    for tension, fails in ((100.0, False), (10.0, True)):
        p = journey.starshot_case(10, tension=tension)
        row = Journey(p, settings).snapshot(0.0)
        assert (row["margin"] < 1) == fails
        assert shape_run(p, row, 20.0)["shape_failed"] == fails
