"""One Result type, whatever solver made it: arrays, summary, provenance, save/load (.npz + .json).

Provenance: every Result records what made it (:func:`provenance`): this package's version and
``code_version``, the git commit when it runs from a checkout, the versions of Exudyn, numpy, scipy and
numba, Python and the platform, and the time it was made. ``code_version`` is a hash of the source files
that decide a run's numbers (:data:`RESULT_SOURCES`: the case and its physics, the solvers, the Result
and the failure rule), so a change to any of them, and only that, makes stored results stale.
"""

from __future__ import annotations

import functools
import hashlib
import json
import math
import platform
import subprocess
from dataclasses import dataclass, field
from datetime import datetime, timezone
from importlib import metadata
from pathlib import Path

import numpy as np

from lightsail_mbs import analysis
from lightsail_mbs.model import shapes
from lightsail_mbs.model.parameters import RUN_FIELDS, SailParameters
from lightsail_mbs.solvers.settings import RunSettings

ARRAYS = ("time", "x", "y", "theta", "z", "vx", "vy", "omega", "z_rate", "amplitude")
FORMAT = "lightsail-mbs result"  # the "format" entry of a saved run's summary
FORMAT_VERSION = 2  # 1: no format entry, run control inside "parameters"


class RunFileError(ValueError):
    """A file that should hold a saved run is missing, unreadable or something else; the message names it."""


PACKAGE = Path(__file__).resolve().parent
# the sources that decide the numbers of a run (globs relative to the package folder)
RESULT_SOURCES = ("model/*.py", "solvers/*.py", "solvers/*/*.py", "result.py", "analysis/failure.py")
LIBRARIES = ("exudyn", "numpy", "scipy", "numba")


@functools.cache
def code_version() -> str:
    """SHA-256 (first 16 hex digits) of the source files that decide a run's numbers (RESULT_SOURCES)."""
    digest = hashlib.sha256()
    for pattern in RESULT_SOURCES:
        for path in sorted(PACKAGE.glob(pattern)):
            digest.update(path.relative_to(PACKAGE).as_posix().encode())
            digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


@functools.cache
def _static_provenance() -> dict:
    from lightsail_mbs import __version__

    def version(name):
        try:
            return metadata.version(name)
        except metadata.PackageNotFoundError:
            return None

    return {
        "package": "lightsail-mbs",
        "version": __version__,
        "code_version": code_version(),
        **_git(),
        **{name: version(name) for name in LIBRARIES},
        "python": platform.python_version(),
        "platform": platform.platform(),
    }


def _git() -> dict:
    """The commit (and whether the tree had uncommitted changes) when the package runs from a git checkout."""
    top = next((d for d in (PACKAGE, *PACKAGE.parents) if (d / ".git").exists()), None)
    if top is None:
        return {"git_commit": None, "git_dirty": None}
    try:
        run = functools.partial(subprocess.run, cwd=top, capture_output=True, text=True, timeout=5, check=True)
        commit = run(["git", "rev-parse", "HEAD"]).stdout.strip()
        dirty = bool(run(["git", "status", "--porcelain", "--untracked-files=no"]).stdout.strip())
    except (OSError, subprocess.SubprocessError):
        return {"git_commit": None, "git_dirty": None}
    return {"git_commit": commit, "git_dirty": dirty}


def provenance() -> dict:
    """What makes a Result now: versions, code_version, git commit, platform and the time (UTC)."""
    return {**_static_provenance(), "created": datetime.now(timezone.utc).isoformat(timespec="seconds")}


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
    error: str | None = None  # a solver failure (divergence, no Newton convergence), recorded
    info: dict = field(default_factory=dict)  # solver settings and statistics (steps, tolerances, ...)
    settings: RunSettings = field(default_factory=RunSettings)  # the run control it was made with
    provenance: dict = field(default_factory=dict)  # what made it (module function provenance)
    warnings: list = field(default_factory=list)  # why the numbers may not mean what they seem
    uncertainty: dict | None = None  # error bar and conditioning of the answer (solvers.uncertainty); None: not asked

    @classmethod
    def from_trajectory(
        cls,
        params: SailParameters,
        solver: str,
        time,
        x,
        y,
        theta,
        vx,
        vy,
        omega,
        z=None,
        z_rate=None,
        wall_time: float = 0.0,
        error: str | None = None,
        info: dict | None = None,
        settings: RunSettings | None = None,
    ) -> Result:
        """Build a Result from raw solver output; the amplitude is computed here (analysis.amplitude)."""
        time = np.asarray(time, float)
        steps = time.shape[0]
        empty = np.zeros((steps, 0))
        names = ("x", "y", "theta", "vx", "vy", "omega")
        arrays = {k: np.asarray(a, float).reshape(steps, -1) for k, a in zip(names, (x, y, theta, vx, vy, omega))}
        arrays["z"] = empty if z is None else np.asarray(z, float).reshape(steps, -1)
        arrays["z_rate"] = empty if z_rate is None else np.asarray(z_rate, float).reshape(steps, -1)
        amplitude = np.atleast_1d(analysis.amplitude(arrays["x"], arrays["y"]))
        return cls(
            params,
            solver,
            time,
            **arrays,
            amplitude=amplitude,
            wall_time=float(wall_time),
            error=error,
            info=dict(info or {}),
            settings=settings or RunSettings(),
            provenance=provenance(),
            warnings=shapes.defect_warnings(params, float(amplitude[0])),
        )

    # ---- summary ---------------------------------------------------------------------------
    @property
    def failure_time(self) -> float | None:
        return analysis.failure_time(self.time, self.amplitude, self.settings.failure_ratio)

    @property
    def failed(self) -> bool:
        return self.failure_time is not None

    @property
    def max_amplitude_ratio(self) -> float:
        """max amplitude / initial amplitude (nan for a sail that starts flat)."""
        if self.amplitude[0] == 0:
            return float("nan")
        return float(np.max(self.amplitude) / self.amplitude[0])

    @property
    def failure_time_uncertainty(self) -> float | None:
        """The failure time's uncertainty (s; inf when a twin run's verdict differs); None when the run did
        not fail or no estimate was made (solvers.uncertainty)."""
        u = self.uncertainty or {}
        return u.get("uncertainty") if u.get("estimated") and u.get("quantity") == "failure_time" else None

    @property
    def max_amplitude_ratio_uncertainty(self) -> float | None:
        """The largest amplitude ratio's uncertainty for a sail that did not fail; None otherwise."""
        u = self.uncertainty or {}
        return u.get("uncertainty") if u.get("estimated") and u.get("quantity") == "max_amplitude_ratio" else None

    @property
    def well_conditioned(self) -> bool | None:
        """Whether the answer is insensitive to perturbations at round-off level; None when not estimated."""
        return (self.uncertainty or {}).get("well_conditioned")

    def answer_text(self) -> str:
        """The answer with its error bar: 'FAILED at t = 2.1112 ± 0.0001 s' or 'not failed (max amplitude
        ratio 1.2460 ± 0.0005)', with '(ill-conditioned)' when it is."""
        u = self.uncertainty or {}
        if self.failed:
            text = f"FAILED at t = {with_uncertainty(self.failure_time, self.failure_time_uncertainty)} s"
        else:
            ratio = with_uncertainty(self.max_amplitude_ratio, self.max_amplitude_ratio_uncertainty)
            text = f"not failed (max amplitude ratio {ratio})"
        if u.get("estimated") and not u.get("well_conditioned"):
            text += " (ill-conditioned)"
        return text

    @property
    def dissipated_energy(self) -> np.ndarray:
        """Heat generated by the dampers since t = 0 (J), per sample (analysis.dissipated_energy)."""
        return analysis.dissipated_energy(self)

    def summary(self) -> dict:
        return {
            "solver": self.solver,
            "model": self.params.model,
            "n": self.params.n,
            "failed": self.failed,
            "failure_time": self.failure_time,
            "failure_time_uncertainty": self.failure_time_uncertainty,
            "max_amplitude_ratio": self.max_amplitude_ratio,
            "max_amplitude_ratio_uncertainty": self.max_amplitude_ratio_uncertainty,
            "well_conditioned": self.well_conditioned,
            "uncertainty": self.uncertainty,
            "initial_amplitude": float(self.amplitude[0]),
            "t_end": float(self.time[-1]),
            "dissipated_energy": float(self.dissipated_energy[-1]),
            "wall_time": self.wall_time,
            "error": self.error,
            "warnings": self.warnings,
            "info": self.info,
            "parameters": self.params.to_dict(),
            "settings": self.settings.to_dict(),
            "provenance": self.provenance,
            "format": FORMAT,
            "format_version": FORMAT_VERSION,
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
    def load(cls, path) -> Result:
        """Read a run saved by :meth:`save` (or by an earlier version of this package).

        Raises RunFileError, naming the file, if it is missing or is not a saved run; ParameterError if
        its parameters are not valid here.
        """
        path = Path(path)
        if not path.is_file():
            raise RunFileError(f"{path}: no such file (expected a saved run, .npz)")
        try:
            with np.load(path, allow_pickle=False) as data:
                missing = [k for k in ("summary_json", *ARRAYS) if k not in data.files]
                if missing:
                    raise RunFileError(f"{path}: not a saved lightsail-mbs run (no {', '.join(missing)})")
                summary = json.loads(str(data["summary_json"]))
                arrays = {k: np.array(data[k]) for k in ARRAYS}
        except RunFileError:
            raise
        except (OSError, ValueError, EOFError) as exc:  # not a zip, truncated, pickled objects, bad JSON
            raise RunFileError(f"{path}: not a readable saved run ({type(exc).__name__}: {exc})") from None
        version = summary.get("format_version", 1)
        if summary.get("format", FORMAT) != FORMAT or not isinstance(version, int) or version > FORMAT_VERSION:
            raise RunFileError(
                f"{path}: format {summary.get('format')!r} version {version!r} is not one this "
                f"version of lightsail-mbs reads (up to {FORMAT_VERSION})"
            )
        parameters = summary["parameters"]
        settings = summary.get("settings") or {k: parameters[k] for k in RUN_FIELDS if k in parameters}
        return cls(
            params=SailParameters.from_dict(parameters),
            solver=summary["solver"],
            wall_time=summary["wall_time"],
            error=summary["error"],
            info=summary["info"],
            settings=RunSettings.from_dict(settings),
            provenance=summary.get("provenance", {}),
            warnings=summary.get("warnings", []),
            uncertainty=summary.get("uncertainty"),
            **arrays,
        )


def with_uncertainty(value: float | None, uncertainty: float | None, digits: int = 6) -> str:
    """'2.1112 ± 0.0001': the value rounded to the uncertainty's first significant digit (two when it
    starts with 1); without an uncertainty, `digits` significant digits; '± inf' when infinite."""
    if value is None:
        return "–"
    if uncertainty is None:
        return f"{value:.{digits}g}"
    if not math.isfinite(uncertainty):
        return f"{value:.{digits}g} ± inf"
    if uncertainty <= 0:
        return f"{value:.{digits}g} ± 0"
    exponent = math.floor(math.log10(uncertainty))
    if f"{uncertainty:.0e}"[0] == "1":
        exponent -= 1
    decimals = max(0, -exponent)
    step = 10.0**exponent
    shown = math.ceil(uncertainty / step - 1e-9) * step
    if decimals:
        return f"{value:.{decimals}f} ± {shown:.{decimals}f}"
    return f"{round(value / step) * step:.0f} ± {shown:.0f}"


def _jsonable(value):
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    raise TypeError(f"not JSON serialisable: {type(value).__name__}")
