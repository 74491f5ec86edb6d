"""Maps of the 3-D ride verdict through the sweep engine (studies.ride_maps): a 2 × 2 map of tiny, short
runs resumed from its store, and its cells against analysis.ride3d.sheet_ride of the same runs."""

import math

import numpy as np
import pytest

from lightsail_mbs import ParameterError, RunSettings, SailParameters
from lightsail_mbs.analysis.ride3d import classify, sheet_ride
from lightsail_mbs.solvers import solve
from lightsail_mbs.studies.ride_maps import cell_of, grid, growth_rate, ride_map
from lightsail_mbs.studies.store import CaseStore

BASE = SailParameters(
    model="sheet",
    n=5,
    ny=6,
    planform="disc",
    billow_radius=1.0,
    billow_rest=True,
    youngs_modulus=1e18,
    membrane_modulus=1e12,
    defect_amplitude=0.0,
    intensity=1e8,
    beam_waist=0.5,
    payload_mass=7.85e-4,
    payload_stem=2.0,
)
SETTINGS = RunSettings(t_final=0.04, output_interval=0.01)
# width 0.1 × 0.5 m = 5 cm: the beam 2 cm off rides, 8 cm off has drifted out from the first sample
THRESHOLDS = dict(crumple=0.05, drift_factor=0.1)
AXES = (("beam_centre", [0.52, 0.58]), ("spin_rate", [0.0, 30.0]))


@pytest.fixture(scope="module")
def mapped(tmp_path_factory):
    store = tmp_path_factory.mktemp("ride_map")
    cases = grid(BASE, *AXES)
    cells = ride_map(cases, store_dir=store, settings=SETTINGS, workers=1, progress=False, **THRESHOLDS)
    return store, cases, cells


def test_a_map_resumed_from_its_store_gives_the_same_cells(mapped):
    """Every finished cell is on disk; with one record deleted the map runs that case alone again and
    gives the same cells (the others are read back, not run)."""
    store, cases, cells = mapped
    keys = {cell.key for cell in cells.values()}
    assert keys <= set(CaseStore(store).keys()) and len(keys) == 4
    gone = cells[(0.58, 30.0)].key
    CaseStore(store).record_path(gone).unlink()
    others = {k: CaseStore(store).record_path(k).stat().st_mtime_ns for k in keys - {gone}}
    again = ride_map(cases, store_dir=store, settings=SETTINGS, workers=1, progress=False, **THRESHOLDS)
    assert {k: CaseStore(store).record_path(k).stat().st_mtime_ns for k in others} == others
    assert CaseStore(store).has(gone)
    for cell, value in cells.items():
        a, b = value.as_dict(), again[cell].as_dict()
        assert a.keys() == b.keys()
        for name in a:
            x, y = a[name], b[name]
            assert x == y or (isinstance(x, float) and math.isnan(x) and math.isnan(y)), (cell, name)


def test_the_maps_cells_are_sheet_ride_of_the_same_runs(mapped):
    """Each cell's verdict, decision time, largest distance and deformation are those of sheet_ride on the
    case solved directly (no failure within the runs, so solve's run is the map's); the 8 cm offset drifts
    out at the first sample, the 2 cm one rides."""
    _, cases, cells = mapped
    verdicts = set()
    for cell, p in cases.items():
        result = solve(p, "reduced", SETTINGS, uncertainty=False)
        ride = sheet_ride(result, **THRESHOLDS)
        got = cells[cell]
        assert (got.verdict, got.decided_at) == (ride.verdict, ride.decided_at), cell
        assert got.max_distance == pytest.approx(float(ride.distance.max()), rel=1e-12)
        assert got.max_deformation == pytest.approx(float(ride.deformation.max()), rel=1e-9, abs=1e-15)
        verdicts.add(got.verdict)
    assert cells[(0.52, 0.0)].verdict == "rides" and cells[(0.58, 0.0)].verdict == "drifts out"
    assert cells[(0.58, 30.0)].decided_at == 0.0
    assert verdicts == {"rides", "drifts out"}


def test_classify_takes_the_first_threshold_reached():
    t = np.array([0.0, 1.0, 2.0, 3.0])
    assert classify(t, [0, 1, 2, 3], [0, 0, 0, 0], 2.5, 1.0) == ("drifts out", 3.0)
    assert classify(t, [0, 1, 2, 3], [0, 0, 1, 1], 2.5, 1.0) == ("crumples", 2.0)
    assert classify(t, [0, 1, 2, 3], [0, 0, 1, 1], 2.0, 1.0) == ("crumples", 2.0)  # a tie: crumples
    assert classify(t, [0, 1, 2, 3], [0, 0, 0, 0], math.inf, 1.0) == ("rides", None)


def test_growth_rate_of_an_exponential_and_a_record_without_histories():
    t = np.linspace(0.0, 2.0, 101)
    fifth = 20
    # the largest in each fifth: the last sample of the first fifth, the last of the run
    expected = math.log(math.exp(3.0 * t[-1]) / math.exp(3.0 * t[fifth - 1])) / (t[-1] - t[fifth])
    assert growth_rate(t, np.exp(3.0 * t)) == pytest.approx(expected, rel=1e-12)
    cell = cell_of({"key": "k", "status": "ok"}, 0.5, 0.05)
    assert cell.status == "error" and "ride3d" in cell.error


def test_a_run_ended_early_without_a_verdict_tips_over_or_stopped():
    """A record whose run ended at 0.3 s of 1 s with neither threshold reached: "tips over" at the first
    sample past 45° of tilt, "stopped" when it never got there; a run to its end rides."""
    t = [0.0, 0.1, 0.2, 0.3]
    ride = dict(time=t, distance=[0.1] * 4, deformation=[0.0] * 4, tilt=[0.0, 0.5, 0.8, 0.9], spin_rate=[0.0] * 4)
    record = {"key": "k", "status": "ok", "settings": {"t_final": 1.0}, "ride3d": ride}
    assert (cell_of(record, 0.5, 0.05).verdict, cell_of(record, 0.5, 0.05).decided_at) == ("tips over", 0.2)
    record["ride3d"] = {**ride, "tilt": [0.0] * 4}
    assert cell_of(record, 0.5, 0.05).verdict == "stopped"
    record["settings"]["t_final"] = 0.3
    assert cell_of(record, 0.5, 0.05).verdict == "rides"


def test_bad_input_is_one_line_before_solving(tmp_path):
    with pytest.raises(ParameterError, match="crumple"):
        ride_map({}, store_dir=tmp_path, settings=SETTINGS, crumple=0.0)
    with pytest.raises(ParameterError, match="sheet cases"):
        ride_map({(1, 1): SailParameters()}, store_dir=tmp_path, settings=SETTINGS)
