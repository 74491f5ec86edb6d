"""Paper-figure reproduction: spectral frequency, stability-map bisection, `lightsail-mbs reproduce`.

Fast tests use closed forms and the fake solver of tests/sweep_fake.py (fails iff E < E_cr,max);
the scenario tests run the reduced solver (skipped until it is installed). The full Fig. 5 check and
the Figs 18–23 trend statements are slow.
"""
import csv
import sys
from pathlib import Path

import numpy as np
import pytest

from lightsail_mbs import SailParameters
from lightsail_mbs.model import theory
from lightsail_mbs.cli import main
from lightsail_mbs.analysis.spectral import angle_frequency, dominant_frequency
from lightsail_mbs.studies.maps import boundary_map

sys.path.insert(0, str(Path(__file__).parent))
from sweep_fake import fake_case, fake_result  # noqa: E402


def read_csv(path):
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


@pytest.mark.parametrize("frequency", [0.4, 2.74, 17.0])
def test_dominant_frequency_of_a_drifting_multi_slice_signal(frequency):
    t = np.arange(0.0, 6.0, 1e-3)
    signals = np.column_stack([np.sin(2 * np.pi * frequency * t + phase) + 0.3 * np.sin(2 * np.pi * 2.3 * frequency * t)
                               + 0.05 * t for phase in (0.0, 1.0, 2.0)])
    # resolution of the raw FFT is 1/6 Hz; the refined peak is far better
    assert dominant_frequency(t, signals) == pytest.approx(frequency, rel=2e-3)


def test_angle_frequency_ignores_rigid_rotation():
    p = SailParameters(n=12)
    result = fake_result(p, growth_rate=0.0)
    t = result.time = np.linspace(0.0, 4.0, 2001)
    x = (np.arange(p.n) + 0.5) / p.n
    result.theta = 0.3 * t[:, None] + 1e-4 * np.cos(2 * np.pi * 3.0 * t)[:, None] * np.cos(3 * np.pi * x)[None, :]
    assert angle_frequency(result) == pytest.approx(3.0, rel=2e-3)


def test_spectrum_rejects_uneven_sampling():
    with pytest.raises(ValueError, match="uniform"):
        dominant_frequency(np.r_[0.0, np.cumsum(np.linspace(1.0, 2.0, 20))], np.ones(21))


def test_boundary_map_brackets_the_known_threshold(tmp_path):
    """The fake solver fails iff E < E_cr,max: every bisected boundary must bracket it within 1.5×."""
    base = SailParameters(model="torsion", n=8, t_final=0.1)
    rows = boundary_map(base, [(1e-7, 1.5), (1e-6, 1.5), (1e-6, 3.0)], store_dir=tmp_path, solver="fake",
                        workers=1, progress=False, case_function=fake_case)
    for row in rows:
        exact = theory.critical_modulus_max(base.replace(thickness=row.thickness, mode=row.mode))
        assert row.status == "converged" and row.analytic == pytest.approx(exact)
        assert row.unstable_value < exact <= row.stable_value <= 1.5 * row.unstable_value
        assert 1 / 1.5 < row.ratio < 1.5
        assert all(s == (v >= exact) for v, s in row.points)


def test_map_figure_survives_a_thickness_where_every_run_errs(tmp_path):
    """A solver error is a result: the map is drawn, and the row says 'error'."""
    from lightsail_mbs.paper.common import stability_map_figure
    base = SailParameters(model="torsion", n=8, t_final=0.1)
    rows = stability_map_figure(tmp_path, "map", 0, base, [1e-7, 1e-6], [1.5, 2.0], solver="fake", workers=1,
                                progress=False, case_function=fake_case, options={"error_modes": [2.0]})
    assert [r["status"] for r in rows] == ["converged", "error", "converged", "error"]
    assert (tmp_path / "map.png").exists()


def test_reproduce_rejects_an_unknown_figure(capsys):
    with pytest.raises(SystemExit):
        main(["reproduce", "--figure", "4"])
    assert "invalid choice" in capsys.readouterr().err


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


def test_reproduce_figure_5_quick_writes_files_and_fails_at_troughs(tmp_path, capsys):
    pytest.importorskip("lightsail_mbs.solvers.reduced")
    assert main(["reproduce", "--figure", "5", "--quick", "--solver", "reduced", "--workers", "1", "--quiet",
                 "--out", str(tmp_path)]) == 0
    printed = capsys.readouterr().out
    assert "Fig. 5" in printed and "wall time" in printed
    for name in ("fig5.png", "fig5_failure_times.csv", "fig5_shapes.csv"):
        assert (tmp_path / name).stat().st_size > 0
    check_fig5(fig5_rows(tmp_path))
    # a rerun finds every case in the store: same table, nothing recomputed
    records = sorted((tmp_path / "store" / "fig5").glob("*.json"))
    stamps = [p.stat().st_mtime_ns for p in records]
    assert main(["reproduce", "--figure", "5", "--quick", "--solver", "reduced", "--workers", "1", "--quiet",
                 "--out", str(tmp_path)]) == 0
    assert [p.stat().st_mtime_ns for p in records] == stamps


@pytest.mark.slow
@pytest.mark.parametrize("solver, module", [("reduced", "reduced.solver"), ("exudyn", "exudyn.chain")])
def test_figure_5_all_modes_fail_at_a_trough_but_one_half(tmp_path, solver, module):
    pytest.importorskip(f"lightsail_mbs.solvers.{module}")
    assert main(["reproduce", "--figure", "5", "--solver", solver, "--quiet", "--out", str(tmp_path)]) == 0
    rows = fig5_rows(tmp_path)
    assert sorted(rows) == [0.5 * k for k in range(1, 11)]
    check_fig5(rows)


@pytest.mark.slow
def test_figures_18_to_23_trends(tmp_path):
    """Appendix C: frequency rises with tension and as thickness falls (stable regime); failure time
    falls with thickness and hardly depends on tension or mode (unstable regime). A sail that does
    not fail within the run (h = 10 µm: the failure time scales as √h) counts as failing later."""
    pytest.importorskip("lightsail_mbs.solvers.reduced")
    assert main(["reproduce", "--figure", "18", "--solver", "reduced", "--quiet", "--out", str(tmp_path)]) == 0
    trends = {int(r["figure"]): r for r in read_csv(tmp_path / "fig18_23_trends.csv")}
    runs = read_csv(tmp_path / "fig18_23_runs.csv")
    stable = [r for r in runs if r["regime"] == "stable"]
    unstable = [r for r in runs if r["regime"] == "unstable"]
    assert all(r["failed"] == "False" and float(r["frequency_Hz"]) > 0 for r in stable)
    assert all(r["failed"] == "True" for r in unstable if float(r["thickness_m"]) <= 1e-6)
    assert trends[18]["direction"] == "increasing"      # frequency vs tension
    assert trends[19]["direction"] == "decreasing"      # frequency vs thickness
    fig23 = [r for r in unstable if r["figure"] == "23"]
    times = [float(r["failure_time_s"]) if r["failed"] == "True" else np.inf for r in fig23]
    assert [float(r["thickness_m"]) for r in fig23] == sorted(float(r["thickness_m"]) for r in fig23)
    assert np.all(np.diff(times) > 0)                   # failure time vs thickness
    assert float(trends[21]["spread_max_over_min"]) < 1.2   # failure time vs tension (T ≪ T_cr,max)
    assert float(trends[22]["spread_max_over_min"]) < 2.0   # failure time vs mode: same order


@pytest.mark.slow
def test_reproduce_all_quick_writes_every_figure(tmp_path, capsys):
    pytest.importorskip("lightsail_mbs.solvers.reduced")
    assert main(["reproduce", "--all", "--quick", "--solver", "reduced", "--quiet", "--out", str(tmp_path)]) == 0
    for number in (5, 6, 7, 8, 9, 10, 11, 12, 18, 19, 20, 21, 22, 23):
        assert (tmp_path / f"fig{number}.png").stat().st_size > 0
    for name in ("fig9_boundaries", "fig12_boundaries", "fig18_23_trends"):
        assert read_csv(tmp_path / f"{name}.csv")
    assert "| all |" in capsys.readouterr().out
