"""Result: consistent shapes, summary keys, the run settings it keeps, provenance, save/load round trip bit for
bit (property-based), the files of the format before RunSettings, and damaged or foreign files."""

import json
import struct
import warnings
from importlib import metadata

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from lightsail_mbs import Result, RunSettings, SailParameters
from lightsail_mbs.result import ARRAYS, FORMAT_VERSION, TILE_ARRAYS, RunFileError, code_version
from tests import strategies as hs
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
    t = r.time
    k = int(np.argmax(r.amplitude >= 2 * r.amplitude[0]))  # the first sample at 2 a₀
    a0, a1 = r.amplitude[k - 1 : k + 1] / r.amplitude[0]
    chord = t[k - 1] + (2 - a0) / (a1 - a0) * (t[k] - t[k - 1])  # interpolated between the samples
    assert s["failed"] and s["failure_time"] == pytest.approx(chord, abs=1e-12)
    assert t[k - 1] < s["failure_time"] < t[k] and abs(s["failure_time"] - np.log(2)) < (t[1] - t[0]) ** 2 / 8
    assert s["max_amplitude_ratio"] > 2
    assert s["settings"] == RunSettings(t_final=1.0).to_dict() and "t_final" not in s["parameters"]


def test_failure_time_follows_the_failure_ratio_of_the_settings():
    """The amplitude grows as e^t over 1 s: it reaches 2.5× at ln 2.5 and never 3× (e < 3)."""
    r = synthetic(settings=RunSettings(t_final=1.0, failure_ratio=2.5))
    k = int(np.argmax(r.amplitude >= 2.5 * r.amplitude[0]))
    assert r.time[k - 1] < r.failure_time < r.time[k] and abs(r.failure_time - np.log(2.5)) < 1e-3
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


def test_save_load_keeps_every_field(tmp_path):
    """Velocities, info, error, warnings, provenance, wall time and settings come back, not just positions."""
    r = synthetic(model="tnt")
    r.vx[:] = np.linspace(-1, 1, r.vx.size).reshape(r.vx.shape)
    r.omega[:] = 3.0
    r.z_rate[:] = -2.5e-9
    r.error, r.warnings = "Newton did not converge at t = 0.5 s", ["n = 12 is coarse"]
    r.info = {"steps": 12, "rtol": 1e-9, "method": "DOP853", "nested": {"a": [1, 2.5, None]}}
    back = Result.load(r.save(tmp_path / "run"))
    assert_same_run(back, r)


def assert_same_run(back: Result, r: Result) -> None:
    """Bit for bit: every array (bytes, dtype, shape), the case, the settings and every summary entry."""
    assert back.params == r.params and back.solver == r.solver and back.settings == r.settings
    for name in ARRAYS + (TILE_ARRAYS if r.is_sheet else ()):
        a, b = getattr(r, name), getattr(back, name)
        assert b.dtype == a.dtype and b.shape == a.shape and b.tobytes() == a.tobytes(), name
    for name in ("error", "info", "warnings", "provenance"):
        assert canonical(getattr(back, name)) == canonical(getattr(r, name)), name
    assert struct.pack("<d", back.wall_time) == struct.pack("<d", r.wall_time)


def canonical(value) -> str:
    return json.dumps(value, sort_keys=True)


@pytest.mark.parametrize("examples", hs.EXAMPLES)
def test_any_saved_run_round_trips_bit_exactly_through_npz_and_json(examples, tmp_path_factory):
    """Property: any Result (any float64 values, NaN, ±inf and −0.0 included; any JSON info, error, warnings
    and provenance) saved and loaded is the same run bit for bit, and its .json holds the same summary as
    the .npz."""
    folder = tmp_path_factory.mktemp("roundtrip")

    @given(st.data())
    def round_trip(data):
        p = data.draw(hs.accepted_cases(), label="case")
        steps = data.draw(st.integers(1, 12), label="steps")
        sheet = p.model == "sheet"
        springs = p.n - 1 if p.extensible and not sheet else 0
        shapes = {"time": (steps,), "amplitude": (steps,), "z": (steps, springs), "z_rate": (steps, springs)}
        if sheet:  # slice arrays empty, the tile arrays (T, N, 3)
            shapes.update({name: (steps, p.n * p.ny, 3) for name in TILE_ARRAYS})
        names = ARRAYS + TILE_ARRAYS if sheet else ARRAYS
        slices = (steps, 0) if sheet else (steps, p.n)
        arrays = {name: data.draw(hs.float_arrays(shapes.get(name, slices)), label=name) for name in names}
        steps_in_time = data.draw(st.lists(st.floats(1e-9, 1e3), min_size=steps - 1, max_size=steps - 1))
        arrays["time"] = np.cumsum([0.0, *steps_in_time])  # a time axis: 0, strictly increasing
        r = Result(
            params=p,
            solver=data.draw(st.sampled_from(["exudyn", "reduced", "synthetic"])),
            wall_time=data.draw(st.floats(0.0, 1e6)),  # a measured time (JSON keeps no NaN payloads)
            error=data.draw(st.one_of(st.none(), st.text())),
            info=data.draw(st.dictionaries(st.text(max_size=10), hs.JSON_VALUES, max_size=5)),
            settings=data.draw(hs.short_run(p)),
            provenance=data.draw(st.dictionaries(st.text(max_size=10), hs.JSON_SCALARS, max_size=5)),
            warnings=data.draw(st.lists(st.text(), max_size=3)),
            **arrays,
        )
        path = r.save(folder / "run")
        back = Result.load(path)
        assert_same_run(back, r)
        with np.load(path) as saved:
            assert json.loads(path.with_suffix(".json").read_text()) == json.loads(str(saved["summary_json"]))
        assert canonical(back.summary()) == canonical(r.summary())

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # summaries of arbitrary arrays (NaN, inf)
        hs.check_property(round_trip, examples)


def test_provenance_of_a_run_names_its_makers():
    r = synthetic()
    made = r.provenance
    for key in ("package", "version", "code_version", "git_commit", "git_dirty", "python", "platform", "created"):
        assert key in made
    for library in ("exudyn", "numpy", "scipy", "numba"):
        assert made[library] == metadata.version(library)
    assert made["code_version"] == code_version() and len(made["code_version"]) == 16
    assert r.summary()["provenance"] == made


def damaged_copies(folder) -> dict:
    """A saved run and damaged variants of it: file name -> words its RunFileError must contain."""
    r = synthetic()
    good = r.save(folder / "good")
    with np.load(good) as data:
        arrays = {k: data[k] for k in data.files}
    summary = json.loads(str(arrays["summary_json"]))

    def variant(name, summary_text=None, **changes):
        np.savez(folder / name, **{**arrays, "summary_json": np.array(summary_text or json.dumps(summary)), **changes})

    (folder / "text.npz").write_text("not a run\n")
    (folder / "truncated.npz").write_bytes(good.read_bytes()[:2000])
    np.savez(folder / "foreign.npz", a=np.arange(3.0))
    np.save(folder / "pickle.npy", np.array([{}], dtype=object), allow_pickle=True)
    (folder / "pickle.npy").rename(folder / "pickle.npz")
    variant("badjson.npz", "{not json")
    variant("list.npz", "[1, 2]")
    variant("future.npz", json.dumps({**summary, "format_version": FORMAT_VERSION + 1}))
    variant("alien.npz", json.dumps({**summary, "format": "someone else's"}))
    variant("badcase.npz", json.dumps({**summary, "parameters": {**summary["parameters"], "n": -3}}))
    variant("nosolver.npz", json.dumps({k: v for k, v in summary.items() if k != "solver"}))
    variant("shapes.npz", x=arrays["x"][:3])
    variant("strings.npz", y=np.array(["a"] * arrays["y"].size).reshape(arrays["y"].shape))
    return {
        "missing.npz": "no such file",
        "text.npz": "not a NumPy",
        "truncated.npz": "not a readable",
        "foreign.npz": "no summary_json",
        "pickle.npz": "not a NumPy",
        "badjson.npz": "JSONDecodeError",
        "list.npz": "not a JSON object",
        "future.npz": f"version {FORMAT_VERSION + 1}",
        "alien.npz": "someone else's",
        "badcase.npz": "n=-3",
        "nosolver.npz": "no solver",
        "shapes.npz": "x is float64 (3, 12)",
        "strings.npz": "y is <U1",
    }


def test_damaged_or_foreign_files_are_one_run_file_error_naming_the_file(tmp_path):
    for name, words in damaged_copies(tmp_path).items():
        with pytest.raises(RunFileError) as err:
            Result.load(tmp_path / name)
        message = str(err.value)
        assert message.startswith(str(tmp_path / name)) and words in message and "\n" not in message, message


def test_a_run_with_a_table_file_outlives_the_file(tmp_path, monkeypatch):
    """The table is saved with the run: gone or rewritten, the run loads with its own table (a warning says
    so) and repeats bit for bit."""
    from lightsail_mbs import solve
    from tests.helpers import table_file

    monkeypatch.setenv("LIGHTSAIL_MBS_CACHE", str(tmp_path / "cache"))
    table = table_file(tmp_path / "grating.npz")
    p = SailParameters(model="torsion", n=8, youngs_modulus=4.5e9, optics=str(table))
    settings = RunSettings(t_final=0.2)
    run = solve(p, "reduced", settings, uncertainty=False)
    saved = run.save(tmp_path / "run.npz")
    digest = p.optics_digest
    assert json.loads((tmp_path / "run.json").read_text())["optics_table_sha256"] == digest
    same = Result.load(saved)
    assert same.params == p and same.warnings == run.warnings
    table.unlink()
    gone = Result.load(saved)
    assert "cannot be read" in gone.warnings[-1] and "\n" not in gone.warnings[-1]
    assert gone.params.optics != p.optics and gone.params.optics_digest == digest
    again = solve(gone.params, "reduced", settings, uncertainty=False)
    np.testing.assert_array_equal(again.theta, run.theta)
    table_file(tmp_path / "grating.npz", scale=1.8)  # another table at the run's path
    rewritten = Result.load(saved)
    assert "holds another table" in rewritten.warnings[-1] and rewritten.params.optics_digest == digest
    assert Result.load(saved).params.optics == gone.params.optics  # one copy, named by its digest
