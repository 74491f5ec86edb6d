"""One Result type, whatever solver made it: arrays, summary, save/load (.npz + .json)."""
from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import analysis
from .parameters import SailParameters

ARRAYS = ("time", "x", "y", "theta", "z", "vx", "vy", "omega", "z_rate", "amplitude")


@dataclass
class Result:
    """A run: slice-centre trajectories in the frame accelerating at g₀ and its summary.

    Arrays: time (T,), x, y, theta, vx, vy, omega (T, n), z, z_rate (T, n−1) for the
    extensible TnT chain and (T, 0) otherwise, amplitude (T,).
    """

    params: SailParameters
    solver: str
    time: np.ndarray
    x: np.ndarray
    y: np.ndarray
    theta: np.ndarray
    z: np.ndarray
    vx: np.ndarray
    vy: np.ndarray
    omega: np.ndarray
    z_rate: np.ndarray
    amplitude: np.ndarray
    wall_time: float = 0.0
    error: str | None = None          # a solver failure (divergence, no Newton convergence), recorded
    info: dict = field(default_factory=dict)  # solver settings and statistics (steps, tolerances, ...)

    @classmethod
    def from_trajectory(cls, params: SailParameters, solver: str, time, x, y, theta, vx, vy, omega,
                        z=None, z_rate=None, wall_time: float = 0.0, error: str | None = None,
                        info: dict | None = None) -> "Result":
        """Build a Result from raw solver output; the amplitude is computed here (analysis.amplitude)."""
        time = np.asarray(time, float)
        steps = time.shape[0]
        empty = np.zeros((steps, 0))
        names = ("x", "y", "theta", "vx", "vy", "omega")
        arrays = {k: np.asarray(a, float).reshape(steps, -1) for k, a in zip(names, (x, y, theta, vx, vy, omega))}
        arrays["z"] = empty if z is None else np.asarray(z, float).reshape(steps, -1)
        arrays["z_rate"] = empty if z_rate is None else np.asarray(z_rate, float).reshape(steps, -1)
        return cls(params, solver, time, **arrays,
                   amplitude=np.atleast_1d(analysis.amplitude(arrays["x"], arrays["y"])),
                   wall_time=float(wall_time), error=error, info=dict(info or {}))

    # ---- summary ---------------------------------------------------------------------------
    @property
    def failure_time(self) -> float | None:
        return analysis.failure_time(self.time, self.amplitude, self.params.failure_ratio)

    @property
    def failed(self) -> bool:
        return self.failure_time is not None

    @property
    def max_amplitude_ratio(self) -> float:
        return float(np.max(self.amplitude) / self.amplitude[0])

    def summary(self) -> dict:
        return {
            "solver": self.solver,
            "model": self.params.model,
            "n": self.params.n,
            "failed": self.failed,
            "failure_time": self.failure_time,
            "max_amplitude_ratio": self.max_amplitude_ratio,
            "initial_amplitude": float(self.amplitude[0]),
            "t_end": float(self.time[-1]),
            "wall_time": self.wall_time,
            "error": self.error,
            "info": self.info,
            "parameters": self.params.to_dict(),
        }

    # ---- persistence -----------------------------------------------------------------------
    def save(self, path) -> Path:
        """Write PATH.npz (arrays + summary) and PATH.json (summary); returns the .npz path."""
        path = Path(path).with_suffix(".npz")
        path.parent.mkdir(parents=True, exist_ok=True)
        summary = json.dumps(self.summary(), indent=2, default=_jsonable)
        np.savez_compressed(path, summary_json=np.array(summary), **{k: getattr(self, k) for k in ARRAYS})
        path.with_suffix(".json").write_text(summary + "\n")
        return path

    @classmethod
    def load(cls, path) -> "Result":
        with np.load(Path(path), allow_pickle=False) as data:
            summary = json.loads(str(data["summary_json"]))
            arrays = {k: np.array(data[k]) for k in ARRAYS}
        return cls(params=SailParameters.from_dict(summary["parameters"]), solver=summary["solver"],
                   wall_time=summary["wall_time"], error=summary["error"], info=summary["info"], **arrays)


def _jsonable(value):
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    raise TypeError(f"not JSON serialisable: {type(value).__name__}")
