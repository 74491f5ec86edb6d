"""The case store (studies.store): only current records are served; stale, corrupt, truncated and incomplete
ones are recomputed, never fatal; the code version follows the sources and libraries that decide a run."""

import json
import shutil

import pytest

from lightsail_mbs.base import provenance as provenance_module
from lightsail_mbs.cli import main
from lightsail_mbs.studies import store as store_module
from lightsail_mbs.studies.store import CaseStore
from lightsail_mbs.studies.sweep import run_sweep
from tests.sweep_fake import executions, fake_case, small_sweep


def sweep(cases, folder, markers=None):
    return run_sweep(cases, folder, workers=1, progress=False, case_function=fake_case)


def test_a_record_made_by_other_code_is_not_served(tmp_path, markers, monkeypatch):
    """After a change of code version every record is stale: the next sweep recomputes each case once and
    stamps it with the new version; a record whose version was changed by hand is stale on its own."""
    cases = small_sweep(markers)[:4]
    first = sweep(cases, tmp_path)
    assert executions(markers) == {c.key: 1 for c in cases}
    store = CaseStore(tmp_path)
    assert all(store.state(c.key) == "current" for c in cases)

    monkeypatch.setattr(store_module, "code_version", lambda: "another-version")
    assert all(store.state(c.key) == "stale" for c in cases) and store.records() == []
    second = sweep(cases, tmp_path)
    assert executions(markers) == {c.key: 2 for c in cases}  # every case recomputed, once
    assert all(r["code_version"] == "another-version" for r in second)
    monkeypatch.undo()

    assert all(store.state(c.key) == "stale" for c in cases)  # back to the first code: stale again
    record = json.loads(store.record_path(cases[0].key).read_text())
    record["failed"] = not record["failed"]  # what serving the stale record would show
    store.record_path(cases[0].key).write_text(json.dumps(record))
    third = sweep(cases, tmp_path)
    assert executions(markers) == {c.key: 3 for c in cases}
    assert [r["failed"] for r in third] == [r["failed"] for r in first]
    assert all(r["code_version"] == provenance_module.code_version() for r in third)


@pytest.mark.parametrize(
    "damage",
    [
        pytest.param(lambda text, key: text[: len(text) // 2], id="truncated"),
        pytest.param(lambda text, key: "", id="empty"),
        pytest.param(lambda text, key: "\x00\x01garbage", id="binary"),
        pytest.param(lambda text, key: "[1, 2, 3]", id="not-an-object"),
        pytest.param(lambda text, key: json.dumps({"key": key, "status": "ok"}), id="no-code-version"),
        pytest.param(lambda text, key: text.replace(key, "0" * len(key)), id="other-key"),
    ],
)
def test_a_truncated_or_corrupt_record_is_recomputed(tmp_path, markers, damage):
    cases = small_sweep(markers)[:3]
    first = sweep(cases, tmp_path)
    store = CaseStore(tmp_path)
    path = store.record_path(cases[1].key)
    path.write_text(damage(path.read_text(), cases[1].key))
    assert store.state(cases[1].key) == "corrupt" and store.audit()["corrupt"] == [cases[1].key]
    again = sweep(cases, tmp_path)
    assert executions(markers) == {cases[0].key: 1, cases[1].key: 2, cases[2].key: 1}
    assert [r["failed"] for r in again] == [r["failed"] for r in first]
    assert store.audit()["corrupt"] == [] and store.state(cases[1].key) == "current"


@pytest.mark.parametrize("damage", ["truncate", "delete", "foreign"])
def test_a_record_whose_saved_result_is_damaged_is_recomputed(tmp_path, markers, damage):
    cases = small_sweep(markers, as_result=True)[:2]
    cases = [type(c)(c.params, c.solver, c.options, save_result=True) for c in cases]
    sweep(cases, tmp_path)
    store = CaseStore(tmp_path)
    saved = store.result_path(cases[0].key)
    if damage == "truncate":
        saved.write_bytes(saved.read_bytes()[:300])
    elif damage == "delete":
        saved.unlink()
    else:
        shutil.copy(store.result_path(cases[1].key), saved)  # a whole run, but of another case
    assert store.state(cases[0].key, with_result=True) == "incomplete"
    sweep(cases, tmp_path)
    assert executions(markers)[cases[0].key] == 2
    assert executions(markers)[cases[1].key] == 1


def test_store_command_reports_each_state(tmp_path, markers, capsys):
    cases = small_sweep(markers)[:5]
    sweep(cases, tmp_path)
    store = CaseStore(tmp_path)
    store.record_path(cases[0].key).write_text("{")
    record = json.loads(store.record_path(cases[1].key).read_text())
    store.record_path(cases[1].key).write_text(json.dumps({**record, "code_version": "0" * 16}))
    assert main(["store", str(tmp_path), "--json"]) == 0
    found = json.loads(capsys.readouterr().out)
    assert found == {
        "current": sorted(c.key for c in cases[2:]),
        "stale": [cases[1].key],
        "corrupt": [cases[0].key],
        "incomplete": [],
    }
    assert main(["store", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert provenance_module.code_version() in out
    assert "2 record(s) will be recomputed" in out
    assert [line.split() for line in out.splitlines()[1:5]] == [
        ["current", "3"],
        ["stale", "1"],
        ["corrupt", "1"],
        ["incomplete", "0"],
    ]


@pytest.fixture
def package_copy(tmp_path, monkeypatch):
    """The package's sources copied to a folder that code_version reads instead of the installed ones."""
    copy = tmp_path / "lightsail_mbs"
    shutil.copytree(provenance_module.PACKAGE, copy, ignore=shutil.ignore_patterns("__pycache__"))
    monkeypatch.setattr(provenance_module, "PACKAGE", copy)
    return copy


def test_code_version_follows_the_sources_that_decide_results_and_only_them(package_copy, monkeypatch):
    version = provenance_module.code_version.__wrapped__
    base = version()
    assert base == provenance_module.code_version()  # the copy is the installed package
    for source in ("solvers/reduced/dynamics.py", "model/loads.py", "model/energy.py", "studies/runners.py"):
        path = package_copy / source
        original = path.read_text()
        path.write_text(original + "\n# a change\n")
        assert version() != base, source
        path.write_text(original)
    for source in ("viz/plots.py", "cli/info.py", "studies/maps.py", "paper/fig5.py"):
        (package_copy / source).write_text((package_copy / source).read_text() + "\n# a change\n")
    assert version() == base  # what only draws or reports results does not make records stale
    monkeypatch.setattr(provenance_module, "_library_version", lambda name: "0.0" if name == "numpy" else "1")
    assert version() != base  # nor do the libraries' versions go unnoticed


def test_code_version_follows_a_new_module_at_any_depth_of_a_deciding_folder(package_copy):
    version = provenance_module.code_version.__wrapped__
    base = version()
    nested = package_copy / "model" / "planforms" / "meshes" / "disc.py"
    nested.parent.mkdir(parents=True)
    nested.write_text("RINGS = 8\n")
    assert nested in provenance_module.result_source_files()
    with_module = version()
    assert with_module != base
    nested.write_text("RINGS = 9\n")
    assert version() not in (base, with_module)
    (package_copy / "viz" / "extra").mkdir()
    (package_copy / "viz" / "extra" / "plot.py").write_text("COLOUR = 'k'\n")
    nested.write_text("RINGS = 8\n")
    assert version() == with_module  # a new module outside the deciding folders does not count
