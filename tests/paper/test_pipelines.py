"""The paper's figure pipelines (lightsail_mbs.paper): Fig. 5's verdicts, Figs 18–23's trends, the stability-map
figure, and ``reproduce --all``.

The map figure runs the fake solver of tests/sweep_fake.py (fails iff E < E_cr,max); the Fig. 5 test runs the
reduced solver. The full Fig. 5 check, the Figs 18–23 trend statements and --all are slow.
"""

import numpy as np
import pytest

from lightsail_mbs import RunSettings, SailParameters
from lightsail_mbs.cli import main
from lightsail_mbs.paper import PIPELINES, fig5, fig18_23, pipeline
from lightsail_mbs.paper.common import stability_map_figure
from tests.helpers import read_csv
from tests.sweep_fake import fake_case


def test_every_figure_has_its_pipeline():
    for number, name in PIPELINES.items():
        assert number in pipeline(name).FIGURES


def test_map_figure_survives_a_thickness_where_every_run_errs(tmp_path):
    """A solver error is a result: the map is drawn, and the row says 'error'."""
    base = SailParameters(model="torsion", n=8)
    rows = stability_map_figure(
        tmp_path,
        "map",
        0,
        base,
        [1e-7, 1e-6],
        [1.5, 2.0],
        settings=RunSettings(t_final=0.1),
        solver="fake",
        workers=1,
        progress=False,
        case_function=fake_case,
        options={"error_modes": [2.0]},
    )
    assert [r["status"] for r in rows] == ["converged", "error", "converged", "error"]
    assert (tmp_path / "map.png").exists()


def fig5_rows(out):
    rows = read_csv(out / "fig5_failure_times.csv")
    return {float(r["mode"]): r for r in rows}


def check_fig5(rows):
    """Paper Sec. IV.A: every mode ν ≥ 1 fails at a trough within 10 ms; ν = 1/2 does not fail."""
    assert rows[0.5]["failed"] == "False" and float(rows[0.5]["t_end_ms"]) == pytest.approx(10.0, rel=1e-6)
    for nu, row in rows.items():
        if nu >= 1:
            assert row["failed"] == "True" and row["at_trough"] == "True", (nu, row)
            assert 0 < float(row["failure_time_ms"]) < 10.0


def test_figure_5_quick_writes_files_and_fails_at_troughs(tmp_path, capsys):
    """fig5.run (quick, reduced): files, the paper's verdicts, and a rerun that finds every case in the store."""
    pytest.importorskip("lightsail_mbs.solvers.reduced")
    fig5.run(tmp_path, solver="reduced", workers=1, quick=True, progress=False)
    printed = capsys.readouterr().out
    assert "Fig. 5" in printed
    for name in ("fig5.png", "fig5_failure_times.csv", "fig5_shapes.csv"):
        assert (tmp_path / name).stat().st_size > 0
    check_fig5(fig5_rows(tmp_path))
    # a rerun finds every case in the store: same table, nothing recomputed
    records = sorted((tmp_path / "store" / "fig5").glob("*.json"))
    stamps = [p.stat().st_mtime_ns for p in records]
    fig5.run(tmp_path, solver="reduced", workers=1, quick=True, progress=False)
    assert [p.stat().st_mtime_ns for p in records] == stamps


@pytest.mark.slow
@pytest.mark.parametrize("solver, module", [("reduced", "reduced.solver"), ("exudyn", "exudyn.chain")])
def test_figure_5_all_modes_fail_at_a_trough_but_one_half(tmp_path, solver, module):
    pytest.importorskip(f"lightsail_mbs.solvers.{module}")
    fig5.run(tmp_path, solver=solver, progress=False)
    rows = fig5_rows(tmp_path)
    assert sorted(rows) == [0.5 * k for k in range(1, 11)]
    check_fig5(rows)


@pytest.mark.slow
def test_figures_18_to_23_trends(tmp_path):
    """Appendix C: frequency rises with tension and as thickness falls (stable regime); failure time
    falls with thickness and hardly depends on tension or mode (unstable regime). A sail that does
    not fail within the run (h = 10 µm: the failure time scales as √h) counts as failing later."""
    pytest.importorskip("lightsail_mbs.solvers.reduced")
    fig18_23.run(tmp_path, solver="reduced", progress=False)
    trends = {int(r["figure"]): r for r in read_csv(tmp_path / "fig18_23_trends.csv")}
    runs = read_csv(tmp_path / "fig18_23_runs.csv")
    stable = [r for r in runs if r["regime"] == "stable"]
    unstable = [r for r in runs if r["regime"] == "unstable"]
    assert all(r["failed"] == "False" and float(r["frequency_Hz"]) > 0 for r in stable)
    assert all(r["failed"] == "True" for r in unstable if float(r["thickness_m"]) <= 1e-6)
    assert trends[18]["direction"] == "increasing"  # frequency vs tension
    assert trends[19]["direction"] == "decreasing"  # frequency vs thickness
    fig23 = [r for r in unstable if r["figure"] == "23"]
    times = [float(r["failure_time_s"]) if r["failed"] == "True" else np.inf for r in fig23]
    assert [float(r["thickness_m"]) for r in fig23] == sorted(float(r["thickness_m"]) for r in fig23)
    assert np.all(np.diff(times) > 0)  # failure time vs thickness
    assert float(trends[21]["spread_max_over_min"]) < 1.2  # failure time vs tension (T ≪ T_cr,max)
    assert float(trends[22]["spread_max_over_min"]) < 2.0  # failure time vs mode: same order


@pytest.mark.slow
def test_reproduce_all_quick_writes_every_figure(tmp_path, capsys):
    pytest.importorskip("lightsail_mbs.solvers.reduced")
    assert main(["reproduce", "--all", "--quick", "--solver", "reduced", "--quiet", "--out", str(tmp_path)]) == 0
    for number in (5, 6, 7, 8, 9, 10, 11, 12, 18, 19, 20, 21, 22, 23):
        assert (tmp_path / f"fig{number}.png").stat().st_size > 0
    for name in ("fig9_boundaries", "fig12_boundaries", "fig18_23_trends"):
        assert read_csv(tmp_path / f"{name}.csv")
    assert "| all |" in capsys.readouterr().out
