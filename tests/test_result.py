"""Result: consistent shapes, summary keys, save/load round trip."""
import json

import numpy as np

from lightsail_mbs import Result, SailParameters


def synthetic(model="tnt", n=12, steps=50):
    p = SailParameters(model=model, n=n, tension=1e-3 if model == "tnt" else 0.0, t_final=1.0)
    t = np.linspace(0, 1, steps)
    x = np.tile((np.arange(n) + 0.5) / n, (steps, 1))
    y = 1e-5 * np.exp(t)[:, None] * np.sin(3 * np.pi * x)
    th = np.zeros((steps, n))
    z = np.zeros((steps, n - 1)) if p.extensible else None
    return Result.from_trajectory(p, "test", t, x, y, th, 0 * x, 0 * y, th, z=z, z_rate=z, wall_time=0.5)


def test_summary_and_failure():
    r = synthetic()
    s = r.summary()
    for key in ("failed", "failure_time", "max_amplitude_ratio", "wall_time", "solver", "model", "n", "parameters"):
        assert key in s
    assert s["failed"] and abs(s["failure_time"] - np.log(2)) < 0.02
    assert s["max_amplitude_ratio"] > 2


def test_save_load_roundtrip(tmp_path):
    r = synthetic()
    path = r.save(tmp_path / "run")
    assert path.suffix == ".npz" and path.with_suffix(".json").exists()
    back = Result.load(path)
    assert back.params == r.params and back.solver == "test"
    for name in ("time", "x", "y", "theta", "z", "amplitude"):
        np.testing.assert_array_equal(getattr(back, name), getattr(r, name))
    assert back.x.shape == (50, 12) and back.z.shape == (50, 11) and back.amplitude.shape == (50,)
    assert json.loads(path.with_suffix(".json").read_text())["failure_time"] == r.failure_time


def test_inextensible_chain_has_empty_z():
    assert synthetic(model="torsion").z.shape == (50, 0)
