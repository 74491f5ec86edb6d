"""A snapshot journey kept on disk resumes: half of it computed, then a rerun in the same folder, gives the
uninterrupted journey's rows exactly and computes only the other half; another case's rows are started afresh; a
row cut short by an interruption is computed again."""

import math

import numpy as np

from lightsail_mbs import SailParameters
from lightsail_mbs.model import materials
from lightsail_mbs.studies.journey import Journey, JourneySettings, run_journey, snapshot_speeds
from lightsail_mbs.studies.journey_store import ROWS_FILE, RowStore, key_of

SETTINGS = JourneySettings(power=4e10, carried_mass=1e-3, step=0.1)


def case(**changes):
    fields = {"material": "silicon-nitride", "model": "tnt", "n": 20, "length": 3.6, "width": 3.6}
    fields.update(thickness=2.5e-8, tension=100.0, defect_amplitude=1e-3, beam_waist=1.5)
    return SailParameters(**materials.fill({**fields, **changes}))


def store(folder, p, s=SETTINGS):
    from dataclasses import asdict

    return RowStore(folder, key_of(p.to_dict(), asdict(s)), snapshot_speeds(s.target_speed, s.step))


def same(a, b):
    assert a.keys() == b.keys()
    for k in a:
        assert a[k] == b[k] or (isinstance(a[k], float) and math.isnan(a[k]) and math.isnan(b[k])), k


def counted(monkeypatch):
    calls = []
    original = Journey.snapshot

    def snapshot(self, beta):
        calls.append(beta)
        return original(self, beta)

    monkeypatch.setattr(Journey, "snapshot", snapshot)
    return calls


def test_a_journey_resumed_from_half_its_snapshots_equals_the_uninterrupted_one(tmp_path, monkeypatch):
    p = case()
    whole = run_journey(p, SETTINGS)
    count = len(whole["snapshots"])
    half = count // 2
    partial = Journey(p, SETTINGS).run(store=store(tmp_path, p), limit=half)
    assert len(partial) == half
    calls = counted(monkeypatch)
    resumed = run_journey(p, SETTINGS, folder=tmp_path)
    assert resumed["resume"]["resumed"] == half and resumed["resume"]["discarded"] is None
    np.testing.assert_array_equal(calls, snapshot_speeds(SETTINGS.target_speed, SETTINGS.step)[half:])
    assert len(resumed["snapshots"]) == count and resumed["verdict"] == whole["verdict"]
    for a, b in zip(resumed["snapshots"], whole["snapshots"]):
        same(a, b)
    calls.clear()
    again = run_journey(p, SETTINGS, folder=tmp_path)  # finished: nothing computed
    assert calls == [] and again["resume"]["resumed"] == count


def test_another_case_starts_afresh_and_a_cut_short_row_is_computed_again(tmp_path, monkeypatch):
    p = case()
    Journey(p, SETTINGS).run(store=store(tmp_path, p), limit=3)
    path = tmp_path / ROWS_FILE
    path.write_text(path.read_text()[:-20])  # the third row cut short
    calls = counted(monkeypatch)
    rows = Journey(p, SETTINGS).run(store=store(tmp_path, p), limit=1)
    assert len(rows) == 3 and len(calls) == 1
    other = case(tension=90.0)
    calls.clear()
    report = run_journey(other, SETTINGS, folder=tmp_path)
    assert report["resume"]["resumed"] == 0 and "started afresh" in report["resume"]["discarded"]
    assert len(calls) == len(report["snapshots"]) and report["case"]["tension"] == 90.0


def test_the_verdict_column_is_intact_until_the_verdicts_moment():
    slack = run_journey(case(tension=10.0), SETTINGS)
    assert slack["verdict"]["verdict"] == "shape"
    assert {r["verdict"] for r in slack["snapshots"]} == {"shape"}  # decided at τ = 0
    intact = run_journey(case(), SETTINGS)
    assert intact["verdict"]["verdict"] == "intact" and {r["verdict"] for r in intact["snapshots"]} == {"intact"}


def test_the_command_resumes_in_its_output_folder(tmp_path, capsys):
    from lightsail_mbs.cli import main

    args = ["journey", "--model", "tnt", "--material", "silicon-nitride", "--length", "3.6", "--width", "3.6"]
    args += ["--thickness", "2.5e-8", "--tension", "100", "--defect-amplitude", "1e-3", "--power", "4e10"]
    args += ["--carried-mass", "1e-3", "--step", "0.1", "--out", str(tmp_path), "--quiet"]
    assert main(args) == 0
    first = (tmp_path / "journey.csv").read_text()
    assert "resumed" not in capsys.readouterr().out
    assert main(args) == 0
    count = len(snapshot_speeds(0.2, 0.1))
    assert f"resumed: {count} of {count} snapshots" in capsys.readouterr().out
    assert (tmp_path / "journey.csv").read_text() == first
    assert main(["0.2" if a == "0.1" else a for a in args]) == 0  # another step: other settings
    assert "started afresh" in capsys.readouterr().err
