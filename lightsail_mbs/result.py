"""One Result type, whatever solver made it: arrays, summary, provenance, save/load (.npz + .json).

Provenance: every Result records what made it (:func:`~lightsail_mbs.base.provenance.provenance`): this
package's version and ``code_version``, the git commit when it runs from a checkout, the versions of Exudyn,
numpy, scipy and numba, Python and the platform, and the time it was made.
"""

from __future__ import annotations

import json
import math
import zipfile
import zlib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from lightsail_mbs.base.files import write_atomically
from lightsail_mbs.base.formatting import n_error_clause, with_uncertainty
from lightsail_mbs.base.provenance import (  # noqa: F401 - re-exported: what made a Result
    LIBRARIES,
    PACKAGE,
    RESULT_SOURCES,
    code_version,
    provenance,
    result_source_files,
)
from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import energy, failure, planforms, shapes
from lightsail_mbs.model.parameters import RUN_FIELDS, SailParameters

ARRAYS = ("time", "x", "y", "theta", "z", "vx", "vy", "omega", "z_rate", "amplitude")
# the sheet's tile arrays (T, N, 3): saved and loaded only when a Result has them
TILE_ARRAYS = ("tile_centres", "tile_angles", "tile_velocities", "tile_angular_velocities")
FORMAT = "lightsail-mbs result"  # the "format" entry of a saved run's summary
TABLE_PREFIX = "optics_table_"  # the .npz arrays of the optical table a run used (Result.save)
FORMAT_VERSION = 2  # 1: no format entry, run control inside "parameters"
# what a saved summary must hold (format 1 files too)
SUMMARY_ENTRIES = ("solver", "parameters", "wall_time", "error", "info")


class RunFileError(ValueError):
    """A file that should hold a saved run is missing, unreadable or something else; the message names it."""


@dataclass
class Result:
    """A run: slice-centre (chain) or tile (sheet) trajectories in the frame accelerating at g₀ and its summary.

    Chain arrays: time (T,), x, y, theta, vx, vy, omega (T, n) (x along the sail, y along the beam),
    z, z_rate (T, n−1) for the extensible TnT chain and (T, 0) otherwise, amplitude (T,).

    Sheet arrays (model "sheet", N tiles of its mesh; on a grid N = n·ny, tile k = j·n + i): tile_centres
    (T, N, 3) (x, y in the sail's plane, z along the beam), tile_angles (T, N, 3) (Tait–Bryan xyz angles of each tile's
    rotation, R = R_x(φ₀) R_y(φ₁) R_z(φ₂)), tile_velocities and tile_angular_velocities (T, N, 3),
    global; the chain's arrays are then (T, 0). For a chain the tile arrays are None (and a saved
    chain run has none).
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
    tile_centres: np.ndarray | None = None  # sheet: (T, N, 3) tile centres (m)
    tile_angles: np.ndarray | None = None  # sheet: (T, N, 3) Tait–Bryan xyz angles (rad)
    tile_velocities: np.ndarray | None = None  # sheet: (T, N, 3) centre velocities (m/s)
    tile_angular_velocities: np.ndarray | None = None  # sheet: (T, N, 3) angular velocities, global (rad/s)
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
        amplitude=None,
    ) -> Result:
        """Build a Result from raw solver output. The amplitude is computed here (failure.amplitude)
        unless the solver passes it (a compiled twin of failure.amplitude, tested equal to it)."""
        time = np.asarray(time, float)
        steps = time.shape[0]
        empty = np.zeros((steps, 0))
        names = ("x", "y", "theta", "vx", "vy", "omega")
        arrays = {k: np.asarray(a, float).reshape(steps, -1) for k, a in zip(names, (x, y, theta, vx, vy, omega))}
        arrays["z"] = empty if z is None else np.asarray(z, float).reshape(steps, -1)
        arrays["z_rate"] = empty if z_rate is None else np.asarray(z_rate, float).reshape(steps, -1)
        if amplitude is None:
            amplitude = failure.amplitude(arrays["x"], arrays["y"])
        amplitude = np.atleast_1d(np.asarray(amplitude, float))
        return cls(
            params,
            solver,
            time,
            **arrays,
            amplitude=amplitude,
            warnings=shapes.defect_warnings(params, float(amplitude[0])),
            **_run_record(wall_time, error, info, settings),
        )

    @classmethod
    def from_tiles(
        cls,
        params: SailParameters,
        solver: str,
        time,
        centres,
        angles,
        velocities,
        angular_velocities,
        wall_time: float = 0.0,
        error: str | None = None,
        info: dict | None = None,
        settings: RunSettings | None = None,
    ) -> Result:
        """Build a sheet's Result from tile trajectories (T, N, 3); the amplitude is computed here
        (failure.plane_amplitude)."""
        from lightsail_mbs.model import sheet

        time = np.asarray(time, float)
        steps = time.shape[0]
        tiles = {
            name: np.asarray(a, float).reshape(steps, -1, 3)
            for name, a in zip(TILE_ARRAYS, (centres, angles, velocities, angular_velocities))
        }
        empty = np.zeros((steps, 0))
        amplitude = np.atleast_1d(failure.plane_amplitude(tiles["tile_centres"]))
        return cls(
            params,
            solver,
            time,
            **{name: empty for name in ARRAYS if name not in ("time", "amplitude")},
            amplitude=amplitude,
            warnings=sheet.defect_warnings(params, float(amplitude[0])),
            **tiles,
            **_run_record(wall_time, error, info, settings),
        )

    @property
    def is_sheet(self) -> bool:
        """True for a run of the sheet model (tile arrays), False for a chain."""
        return self.tile_centres is not None

    def deflection(self) -> np.ndarray:
        """Offsets from the best-fit line (chain, (T, n)) or plane (sheet, (T, N)) over time (m): what the
        failure rule measures."""
        if self.is_sheet:
            return failure.plane_offsets(self.tile_centres)
        return failure.line_offsets(self.x, self.y)

    # ---- summary ---------------------------------------------------------------------------
    @property
    def failure_time(self) -> float | None:
        return failure.failure_time(self.time, self.amplitude, self.settings.failure_ratio)

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
    def base_wall_time(self) -> float:
        """Wall time (s) of the base run alone; ``wall_time`` is the sum over every run when the uncertainty
        was estimated (solvers.uncertainty)."""
        u = self.uncertainty or {}
        return float(u["base"]["wall_time"]) if "base" in u else self.wall_time

    @property
    def well_conditioned(self) -> bool | None:
        """Whether the answer is insensitive to perturbations at round-off level; None when not estimated."""
        return (self.uncertainty or {}).get("well_conditioned")

    def film_text(self) -> str | None:
        """One line on the film twin (solvers.uncertainty): the answer with a real film and the verdict
        defect- or roughness-dominated; None when the estimate did not run it."""
        film = (self.uncertainty or {}).get("film_sensitivity")
        if not film or not film.get("assessed"):
            return None
        what = "fails at" if film["failed"] else "survives with max amplitude ratio"
        unit = " s" if film["failed"] else ""
        text = f"film: with {film['film']} the sail {what} {film['value']:.6g}{unit}"
        if not math.isfinite(film["shift"]):
            return text + ": roughness-dominated (the film changes the verdict)"
        text += f" ({film['relative_shift']:.2g} relative): {film['verdict']}"
        if film.get("holds_below"):
            text += (
                f"; the ideal-defect answer holds only below at most about {film['holds_below']:.1g} m RMS (linear "
                "from the reference film; a response concave in the RMS, as on the paper's soft sail, puts it lower)"
            )
        return text

    def answer_text(self) -> str:
        """The answer with its error bar: 'FAILED at t = 2.1112 ± 0.0001 s' or 'not failed (max amplitude
        ratio 1.2460 ± 0.0005)', with '(ill-conditioned)' when it is and the n-error's clause
        (base.formatting.n_error_clause); a ratio of exactly 1 in every run (the largest amplitude is the
        initial one) says so instead of '1 ± 0'."""
        u = self.uncertainty or {}
        location = (self.info.get("sampling") or {}).get("location_error")
        if self.failed and self.failure_time_uncertainty is None and location is not None:
            text = f"FAILED at t = {with_uncertainty(self.failure_time, location)} s (between-sample location only)"
        elif self.failed:
            text = f"FAILED at t = {with_uncertainty(self.failure_time, self.failure_time_uncertainty)} s"
        elif self.max_amplitude_ratio == 1.0 and not self.max_amplitude_ratio_uncertainty:
            text = "not failed (max amplitude ratio 1: the amplitude never exceeded its initial value)"
        else:
            ratio = with_uncertainty(self.max_amplitude_ratio, self.max_amplitude_ratio_uncertainty)
            text = f"not failed (max amplitude ratio {ratio})"
        if u.get("estimated") and not u.get("well_conditioned"):
            text += " (ill-conditioned)"
        clause = n_error_clause(u.get("n_error"), " s" if self.failed else "")
        return f"{text} ({clause})" if clause else text

    @property
    def dissipated_energy(self) -> np.ndarray:
        """Heat generated by the dampers since t = 0 (J), per sample (energy.dissipated_energy; nan for a
        sheet, whose connector dampers are not accounted)."""
        if self.is_sheet:
            return np.full(self.time.shape, np.nan)
        return energy.dissipated_energy(self)

    def summary(self) -> dict:
        sheet = {"ny": self.params.ny, "tiles": planforms.mesh_of(self.params).count} if self.is_sheet else {}
        return {
            "solver": self.solver,
            "model": self.params.model,
            "n": self.params.n,
            **sheet,
            "failed": self.failed,
            "failure_time": self.failure_time,
            "failure_time_uncertainty": self.failure_time_uncertainty,
            "max_amplitude_ratio": self.max_amplitude_ratio,
            "max_amplitude_ratio_uncertainty": self.max_amplitude_ratio_uncertainty,
            "well_conditioned": self.well_conditioned,
            "uncertainty": self.uncertainty,
            "initial_amplitude": float(self.amplitude[0]),
            "t_end": float(self.time[-1]),
            "dissipated_energy": None if self.is_sheet else float(self.dissipated_energy[-1]),
            "wall_time": self.wall_time,
            "error": self.error,
            "warnings": self.warnings,
            "info": self.info,
            "parameters": self.params.to_dict(),
            "optics_table_sha256": self.params.optics_digest,
            "settings": self.settings.to_dict(),
            "provenance": self.provenance,
            "format": FORMAT,
            "format_version": FORMAT_VERSION,
        }

    # ---- persistence -----------------------------------------------------------------------
    def save(self, path) -> Path:
        """Write PATH.npz (arrays + summary) and PATH.json (summary); returns the .npz path.

        A case whose force law is an optical table file carries a copy of the table in the .npz (arrays
        ``optics_table_*``; its digest in the summary), so that the run can be read and repeated after the
        file is moved or rewritten (:meth:`load`). Each file is written to a temporary file in the same
        folder and then renamed over its name, so a run killed while saving leaves the previous file or
        none, never a truncated one."""
        path = Path(path).with_suffix(".npz")
        path.parent.mkdir(parents=True, exist_ok=True)
        summary = json.dumps(self.summary(), indent=2, default=_jsonable)
        arrays = {k: getattr(self, k) for k in ARRAYS}
        arrays.update({k: getattr(self, k) for k in TILE_ARRAYS if getattr(self, k) is not None})
        if self.params.optics_file:
            arrays.update({TABLE_PREFIX + k: v for k, v in self.params.optical_table().to_arrays().items()})
        write_atomically(path, lambda handle: np.savez_compressed(handle, summary_json=np.array(summary), **arrays))
        write_atomically(path.with_suffix(".json"), lambda handle: handle.write((summary + "\n").encode()))
        return path

    @classmethod
    def load(cls, path) -> Result:
        """Read a run saved by :meth:`save` (or by an earlier version of this package).

        Raises RunFileError, naming the file, if it is missing, is not a NumPy archive, is truncated or
        corrupt, is not a whole saved run (a summary entry or an array missing, arrays of the wrong type
        or of shapes that do not fit the case), or holds a case that is not valid here.

        An optical table file the case names that is gone or holds another table than the run's is
        replaced by the copy saved with the run (:func:`~lightsail_mbs.model.optics.stored_copy`), and a
        warning in ``Result.warnings`` says so.
        """
        path = Path(path)
        if not path.is_file():
            raise RunFileError(f"{path}: no such file (expected a saved run, .npz)")
        try:
            with path.open("rb") as handle:
                magic = handle.read(4)
            if magic not in (b"PK\x03\x04", b"PK\x05\x06"):
                raise RunFileError(f"{path}: not a saved lightsail-mbs run (not a NumPy .npz archive)")
            with np.load(path, allow_pickle=False) as data:
                missing = [k for k in ("summary_json", *ARRAYS) if k not in data.files]
                if missing:
                    raise RunFileError(f"{path}: not a saved lightsail-mbs run (no {', '.join(missing)})")
                summary = json.loads(str(data["summary_json"]))
                arrays = {k: np.array(data[k]) for k in ARRAYS}
                arrays.update({k: np.array(data[k]) for k in TILE_ARRAYS if k in data.files})
                table = {k[len(TABLE_PREFIX) :]: np.array(data[k]) for k in data.files if k.startswith(TABLE_PREFIX)}
        except RunFileError:
            raise
        except (OSError, ValueError, EOFError, KeyError, zipfile.BadZipFile, zlib.error) as exc:
            # truncated or damaged archive, pickled objects, bad JSON
            raise RunFileError(f"{path}: not a readable saved run ({type(exc).__name__}: {exc})") from None
        if not isinstance(summary, dict):
            raise RunFileError(f"{path}: not a saved lightsail-mbs run (its summary is not a JSON object)")
        version = summary.get("format_version", 1)
        if summary.get("format", FORMAT) != FORMAT or not isinstance(version, int) or version > FORMAT_VERSION:
            raise RunFileError(
                f"{path}: format {summary.get('format')!r} version {version!r} is not one this "
                f"version of lightsail-mbs reads (up to {FORMAT_VERSION})"
            )
        absent = [k for k in SUMMARY_ENTRIES if k not in summary]
        if absent:
            raise RunFileError(f"{path}: not a whole saved run (its summary has no {', '.join(absent)})")
        parameters = summary["parameters"]
        if not isinstance(parameters, dict):
            raise RunFileError(f"{path}: not a whole saved run (its parameters are not a JSON object)")
        settings = summary.get("settings") or {k: parameters[k] for k in RUN_FIELDS if k in parameters}
        warnings = list(summary.get("warnings", []))
        if table:
            parameters, note = _with_saved_table(path, parameters, table)
            warnings += [note] if note else []
        try:
            params, settings = SailParameters.from_dict(parameters), RunSettings.from_dict(settings)
        except (ParameterError, TypeError) as exc:
            raise RunFileError(f"{path}: its case is not valid in this version of lightsail-mbs ({exc})") from None
        _check_arrays(path, arrays, params)
        return cls(
            params=params,
            solver=summary["solver"],
            wall_time=summary["wall_time"],
            error=summary["error"],
            info=summary["info"],
            settings=settings,
            provenance=summary.get("provenance", {}),
            warnings=warnings,
            uncertainty=summary.get("uncertainty"),
            **arrays,
        )


def _run_record(wall_time, error, info, settings) -> dict:
    """The fields of a new Result that record its run: wall time, error, solver info, settings, provenance."""
    return dict(
        wall_time=float(wall_time),
        error=error,
        info=dict(info or {}),
        settings=settings or RunSettings(),
        provenance=provenance(),
    )


def _with_saved_table(path: Path, parameters: dict, arrays: dict) -> tuple[dict, str | None]:
    """(parameters, warning): the saved run's parameters with ``optics`` pointing at the table saved in it
    when the file it names is gone or holds another table, and the warning that says so (None when the
    file is the run's table)."""
    from lightsail_mbs.model import optics

    try:
        saved = optics.OpticalTable.from_arrays(arrays, f"{path} (its optical table)")
    except optics.OpticsFileError as exc:
        raise RunFileError(str(exc)) from None
    named = parameters.get("optics")
    try:
        if optics.read_table(named).digest == saved.digest:
            return parameters, None
        state = "holds another table"
    except optics.OpticsFileError:
        state = "cannot be read"
    copy = optics.stored_copy(saved)
    note = (
        f"optics: the table file {named} {state}; this run used the table saved with it, now at {copy} "
        f"(digest {saved.digest})"
    )
    return {**parameters, "optics": str(copy)}, note


def _check_arrays(path: Path, arrays: dict, params: SailParameters) -> None:
    """RunFileError unless the arrays are real numbers of the shapes a run of params has: time and
    amplitude (T,) with T ≥ 1, the slice arrays (T, n), z and z_rate (T, n − 1) or (T, 0); a sheet's slice
    arrays are (T, 0) and its four tile arrays (T, N, 3), N its mesh's tiles."""
    steps = arrays["time"].shape[0] if arrays["time"].ndim == 1 else -1
    sheet = params.model == "sheet"
    spring = (params.n - 1) if params.extensible and not sheet else 0
    expected = {"time": (steps,), "amplitude": (steps,), "z": (steps, spring), "z_rate": (steps, spring)}
    if sheet:
        missing = [k for k in TILE_ARRAYS if k not in arrays]
        if missing:
            raise RunFileError(f"{path}: not a whole saved run of a sheet (no {', '.join(missing)})")
        expected.update({k: (steps, planforms.mesh_of(params).count, 3) for k in TILE_ARRAYS})
    for name, array in arrays.items():
        shape = expected.get(name, (steps, 0) if sheet else (steps, params.n))
        if array.dtype.kind != "f" or array.shape != shape or steps < 1:
            raise RunFileError(
                f"{path}: not a whole saved run ({name} is {array.dtype} {array.shape}, expected float {shape} "
                f"for n = {params.n})"
            )


def _jsonable(value):
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    raise TypeError(f"not JSON serialisable: {type(value).__name__}")
