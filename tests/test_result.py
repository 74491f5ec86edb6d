"""Result: consistent shapes, summary keys, the run settings it keeps, save/load round trip (and the
files of the format before RunSettings)."""

import json

import numpy as np
import pytest

from lightsail_mbs import Result, RunSettings, SailParameters
from tests.helpers import synthetic_sheet

ONE_SECOND = RunSettings(t_final=1.0)


def synthetic(model="tnt", n=12, steps=50, settings=ONE_SECOND):
    p = SailParameters(model=model, n=n, tension=1e-3 if model == "tnt" else 0.0)
    t = np.linspace(0, 1, steps)
    x = np.tile((np.arange(n) + 0.5) / n, (steps, 1))
    y = 1e-5 * np.exp(t)[:, None] * np.sin(3 * np.pi * x)
    th = np.zeros((steps, n))
    z = np.zeros((steps, n - 1)) if p.extensible else None
    return Result.from_trajectory(
        p, "test", t, x, y, th, 0 * x, 0 * y, th, z=z, z_rate=z, wall_time=0.5, settings=settings
    )


def test_summary_and_failure():
    r = synthetic()
    s = r.summary()
    for key in (
        "failed",
        "failure_time",
        "max_amplitude_ratio",
        "wall_time",
        "solver",
        "model",
        "n",
        "parameters",
        "settings",
    ):
        assert key in s
    assert s["failed"] and abs(s["failure_time"] - np.log(2)) < 0.02
    assert s["max_amplitude_ratio"] > 2
    assert s["settings"] == RunSettings(t_final=1.0).to_dict() and "t_final" not in s["parameters"]


def test_failure_time_follows_the_failure_ratio_of_the_settings():
    """The amplitude grows as e^t over 1 s: it reaches 2.5× at ln 2.5 and never 3× (e < 3)."""
    assert abs(synthetic(settings=RunSettings(t_final=1.0, failure_ratio=2.5)).failure_time - np.log(2.5)) < 0.02
    assert not synthetic(settings=RunSettings(t_final=1.0, failure_ratio=3.0)).failed
    assert synthetic().settings == RunSettings(t_final=1.0)


def test_save_load_roundtrip(tmp_path):
    r = synthetic()
    path = r.save(tmp_path / "run")
    assert path.suffix == ".npz" and path.with_suffix(".json").exists()
    back = Result.load(path)
    assert back.params == r.params and back.solver == "test" and back.settings == r.settings
    for name in ("time", "x", "y", "theta", "z", "amplitude"):
        np.testing.assert_array_equal(getattr(back, name), getattr(r, name))
    assert back.x.shape == (50, 12) and back.z.shape == (50, 11) and back.amplitude.shape == (50,)
    assert json.loads(path.with_suffix(".json").read_text())["failure_time"] == r.failure_time


def test_inextensible_chain_has_empty_z():
    assert synthetic(model="torsion").z.shape == (50, 0)


def test_loads_the_files_of_the_format_before_run_settings(tmp_path):
    """Older files kept the run in the parameters under the old field names; no 'settings' entry."""
    r = synthetic(settings=RunSettings(t_final=1.0, output_interval=0.02, failure_ratio=3.0))
    path = r.save(tmp_path / "new")
    summary = json.loads(path.with_suffix(".json").read_text())
    old = dict(summary["parameters"])
    old["amplitude"], old["mode"], old["defect_modes"] = (
        old.pop("defect_amplitude"),
        old.pop("defect_mode"),
        old.pop("defect_mode_count"),
    )
    old.update(summary.pop("settings"))
    summary["parameters"] = old
    with np.load(path) as data:
        arrays = {k: data[k] for k in data.files if k != "summary_json"}
    np.savez_compressed(tmp_path / "old.npz", summary_json=np.array(json.dumps(summary)), **arrays)
    back = Result.load(tmp_path / "old.npz")
    assert back.params == r.params and back.settings == r.settings
    np.testing.assert_array_equal(back.amplitude, r.amplitude)
    assert back.failure_time == r.failure_time


def test_sheet_result_amplitude_summary_and_roundtrip(tmp_path):
    r = synthetic_sheet()
    np.testing.assert_allclose(r.amplitude / r.amplitude[0], np.exp(r.time), rtol=1e-12)
    assert r.is_sheet and r.x.shape == (5, 0) and r.tile_centres.shape == (5, 48, 3)
    assert r.failure_time == pytest.approx(0.6931, abs=0.03)  # e^t = 2, interpolated on 0.25 s samples
    s = r.summary()
    assert s["ny"] == 6 and s["tiles"] == 48 and s["dissipated_energy"] is None
    path = r.save(tmp_path / "sheet")
    back = Result.load(path)
    assert back.is_sheet and back.params == r.params
    for name in ("tile_centres", "tile_angles", "tile_velocities", "tile_angular_velocities", "amplitude"):
        np.testing.assert_array_equal(getattr(back, name), getattr(r, name))
    np.testing.assert_array_equal(back.deflection(), r.deflection())


def test_chain_runs_are_saved_without_tile_arrays(tmp_path, run):
    path = run.save(tmp_path / "chain")
    with np.load(path) as data:
        assert not [k for k in data.files if k.startswith("tile_")]
    assert not Result.load(path).is_sheet and "ny" not in run.summary()
