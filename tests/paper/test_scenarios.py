"""The studies beyond the paper as package pipelines (lightsail_mbs.paper.SCENARIOS), run quick: beam
optics, material damping, the animations, the stability studies."""

import numpy as np
import pytest

from lightsail_mbs.paper import scenario
from tests.helpers import growing_sine


def test_beam_optics_scenario(tmp_path):
    """paper.beam_optics (quick): a narrower centred Gaussian cups the sail sooner; a darker sail
    has a smaller g₀; an off-centre beam turns the flat sail 1° faster the farther off it is, within 20 %
    of the rigid-plate estimate."""
    rows = scenario("beam_optics").run(tmp_path, quick=True, workers=1, progress=False)["rows"]
    assert {p.name for p in tmp_path.iterdir()} >= {
        "beam_optics.png",
        "beam_optics_profile.csv",
        "beam_optics_tilt.csv",
    }
    stiff = [r for r in rows if r["kind"] == "profile" and r["E_Pa"] == 4.5e13]
    gauss = sorted(
        (r for r in stiff if r["reflectivity"] == 1 and np.isfinite(r["beam_waist_m"])), key=lambda r: r["beam_waist_m"]
    )
    assert all(r["failed"] for r in gauss)
    assert all(a["failure_time_s"] < b["failure_time_s"] for a, b in zip(gauss, gauss[1:]))
    g0 = [r["g0"] for r in stiff if np.isinf(r["beam_waist_m"])]
    assert g0[0] > g0[1] > g0[2]  # R = 1; R = 0.9, α = 0.1; R = 0, α = 1
    tilt = [r for r in rows if r["kind"] == "tilt"]
    assert all(a["turn_1deg_s"] > b["turn_1deg_s"] for a, b in zip(tilt, tilt[1:]))
    assert all(abs(r["turn_1deg_s"] / r["turn_1deg_estimate_s"] - 1) < 0.2 for r in tilt)


def test_dissipation_scenario_heat_rises_with_tension(tmp_path):
    """paper.dissipation (quick): only damped runs make heat, and in the stable regime the mean
    power rises with the tension (through the frequency, P ∝ β ω² × energy)."""
    rows = scenario("dissipation").run(tmp_path, quick=True, workers=1, progress=False)["rows"]
    assert (tmp_path / "dissipation.png").exists() and (tmp_path / "dissipation.csv").exists()
    assert all(r["heat_J"] == 0.0 for r in rows if r["beta_s"] == 0.0)
    stable = [r for r in rows if r["beta_s"] > 0 and not r["failed"] and r["T_over_T_cr"] >= 10]
    powers = [r["mean_power_W"] for r in sorted(stable, key=lambda r: r["T_N"])]
    assert len(powers) >= 3 and all(b > a > 0 for a, b in zip(powers, powers[1:]))


def test_animations_render_saved_runs(tmp_path):
    """paper.animations: reads STORE/animations/<case>.npz when present, cuts at the amplitude ratio, writes
    the GIF."""
    import imageio.v2 as imageio

    animations = scenario("animations")
    growing_sine(rate=3.0).save(tmp_path / "runs" / "animations" / "soft_torsion.npz")
    animations.run(
        tmp_path / "docs",
        store=tmp_path / "runs",
        cases=["soft_torsion"],
        frames=4,
        size="300x150",
        until_ratio=3,
        progress=False,
    )
    frames = imageio.mimread(tmp_path / "docs" / "soft_torsion.gif")
    assert len(frames) == 4 and frames[0].shape[:2] == (150, 300)
    cut = animations.cut_at_ratio(growing_sine(rate=3.0), 3.0)
    assert cut.amplitude[-1] >= 3 * cut.amplitude[0] > cut.amplitude[-2]


@pytest.mark.slow
def test_stability_scenarios_quick(tmp_path):
    """The three stability pipelines run (quick; the linear one in full) and the failure-time fit finds
    t_f ∝ (g₀ a₀)^(−1/2)."""
    modules = {name: scenario(name) for name in ("stability_linear", "stability_critical", "stability_failure_time")}
    fits = modules["stability_failure_time"].run(tmp_path, quick=True)["fits"]
    for fit in fits:
        assert fit["g0_exponent"] == pytest.approx(-0.5, abs=0.01)
        assert fit["a0_exponent"] == pytest.approx(-0.5, abs=0.01)
    critical = modules["stability_critical"].run(tmp_path, quick=True)
    assert all(f["a0_exponent"] == pytest.approx(1.0, abs=0.03) for f in critical["fits"])
    rows = modules["stability_linear"].run(tmp_path)["rows"]
    assert max(r["elastic_relative_shift"] for r in rows) < 1e-6
    for png in ("stability_linear.png", "stability_critical.png", "stability_failure_time.png"):
        assert (tmp_path / png).stat().st_size > 10_000


@pytest.mark.slow
def test_sheet_physics_scenario(tmp_path):
    """paper.sheet_physics (quick): every boundary bracketed or reported, the frames and tables written, and
    a narrower centred Gaussian fails the strip sooner."""
    rows = scenario("sheet_physics").run(tmp_path, quick=True, workers=1, progress=False)
    assert {p.name for p in tmp_path.iterdir()} >= {
        "sheet_physics.png",
        "sheet_physics_failure.png",
        "sheet_physics_modulus.csv",
        "sheet_physics_tension.csv",
        "sheet_physics_gaussian.csv",
        "sheet_physics_twin.csv",
        "sheet_physics_unlit.csv",
        "sheet_physics_horizon.csv",
        "sheet_physics_resolution.csv",
        "sheet_physics_scan.csv",
        "sheet_physics.md",
    }
    assert all(r["status"] in ("converged", "unbracketed") for r in rows["modulus"] + rows["tension"] + rows["twin"])
    assert {r["grid"] for r in rows["horizon"]} == {6}
    strip = sorted((r for r in rows["gaussian"] if r["case"] == "strip"), key=lambda r: r["waist_m"])
    assert all(a["failure_time_ms"] < b["failure_time_ms"] for a, b in zip(strip, strip[1:]))


def test_sheet_long_horizon_writes_its_table(tmp_path):
    """paper.sheet_physics.long_horizon on one small grid: a row per (grid, E/E_cr,max), CSV and Markdown."""
    from lightsail_mbs import RunSettings
    from lightsail_mbs.paper import sheet_physics

    rows = sheet_physics.long_horizon(
        tmp_path, grids=(6,), ratios=(0.3, 2.0), settings=RunSettings(t_final=2.0, output_interval=0.01), progress=False
    )
    assert [(r["grid"], r["ratio"]) for r in rows] == [(6, 0.3), (6, 2.0)]
    assert all(r["error"] is None and r["max_ratio"] >= 1.0 for r in rows)
    assert "E/E_cr,max" in (tmp_path / "sheet_long_horizon.md").read_text()
    assert (tmp_path / "sheet_long_horizon.csv").read_text().count("\n") == 3
    assert all(r["max_ratio_rtol10"] >= 1.0 for r in rows)  # each case again at rtol/10


@pytest.mark.slow
def test_spinning_maps_quick_writes_its_maps_and_movie(tmp_path):
    """The maps' pipeline on 2 × 2 maps of 0.1 s runs: its table, figure, CSV, a GIF under 2 MB and the movie's
    ride histories (spinning at 20 rad/s); a rerun reads every cell back from the store."""
    from lightsail_mbs.paper import spinning_maps

    path = spinning_maps.write(tmp_path, workers=1, quick=True)
    text = path.read_text()
    assert text.count("| 0.85 |") == 3 and "spin rate" in text
    assert (tmp_path / "spinning_maps.png").stat().st_size > 10_000
    assert 10_000 < (tmp_path / "spinning_ride.gif").stat().st_size < 2_000_000
    header, *ride = (tmp_path / "spinning_ride.csv").read_text().splitlines()
    assert header == "time_s,distance_m,deformation_m,tilt_rad,spin_rate_rad_s" and len(ride) == 6  # 0.1 s by 20 ms
    assert all(abs(float(row.split(",")[4]) - 20.0) < 0.2 for row in ride)  # the movie's 20 rad/s kept
    stored = sorted((tmp_path / "store" / "spinning_maps").glob("*.json"))
    assert len(stored) == 10  # 3 maps of 4 cells, two shared between the R_c and the spin map
    before = [p.stat().st_mtime_ns for p in stored]
    spinning_maps.run_maps(tmp_path / "store" / "spinning_maps", workers=1, quick=True, progress=False)
    assert [p.stat().st_mtime_ns for p in stored] == before
