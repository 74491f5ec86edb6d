"""Beyond the uniform perfect mirror: Gaussian beams and partial reflectivity/absorption.

The paper's torsion sail (h = 1 µm, I₀ = 0.1 GW/m², a₀ = 10 µm, ν = 3/2, n = 30) at its stable modulus
(E = 4.5e13 Pa, Fig. 6) and soft modulus (4.5e9 Pa, Fig. 7), 6 s or to failure, under

* centred Gaussian beams of waist w = 2, 1, 0.5 m next to the uniform beam: the beam's curvature pushes the
  middle harder than the edges, a load the flat-sail frame does not cancel (50 ms runs, 10 µs samples);
* a perfect mirror (R = 1), a partial one (R = 0.9, α = 0.1) and a black absorber (R = 0, α = 1):
  g₀ = (2R + α)Ī/(cρh) falls, so the defect grows more slowly;

and, on a flat sail (a₀ = 0), beams of w = 1 m centred off the middle by 1–20 % of L (0.2 s runs, 0.1 ms
samples, past failure): the torque turns the sail as a rigid plate; the time to turn by 1° is reported
next to the estimate t = √(2 · 1° · J_sail / τ), τ = Σ f_j (x_j − L/2) (loads.radiation_forces at rest).

Writes beam_optics.png, beam_optics_profile.csv and beam_optics_tilt.csv; the runs go to the store
OUT/store/beam_optics. Quick: n = 10, 1 s runs (the Gaussian runs stay 50 ms).
Run: lightsail-mbs reproduce --scenario beam_optics, or python scenarios/beam_optics.py.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from lightsail_mbs import paper_case, paper_settings
from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.model import loads, shapes
from lightsail_mbs.paper.common import sweep_options
from lightsail_mbs.studies.sweep import run_cases
from lightsail_mbs.studies.tables import print_table, write_csv
from lightsail_mbs.viz.plots import new_figure, save_figure

NAME = "beam_optics"
WAISTS = (math.inf, 2.0, 1.0, 0.5)  # m
OPTICS = ((1.0, 0.0), (0.9, 0.1), (0.0, 1.0))  # (R, α)
OFFSETS = (0.01, 0.05, 0.2)  # (x_c − L/2)/L
TURN = math.radians(1.0)
CUPPING = dict(t_final=0.05, output_interval=1e-5)  # a Gaussian beam cups the sail within milliseconds
TILT = RunSettings(t_final=0.2, output_interval=1e-4, stop_at_failure=False)


def profile_cases(quick: bool = False) -> list[tuple]:
    """(params, settings) of the profile and optics runs: per sail, the beams of WAISTS (uniform first),
    then the partial reflector and the absorber under the uniform beam."""
    changes = dict(n=10) if quick else {}
    out = []
    for case in ("torsion-stable", "torsion-soft"):
        settings = paper_settings(case, **(dict(t_final=1.0) if quick else {}))
        for w in WAISTS:
            out.append(
                (paper_case(case, beam_waist=w, **changes), settings if math.isinf(w) else settings.replace(**CUPPING))
            )
        for r, a in OPTICS[1:]:
            out.append((paper_case(case, reflectivity=r, absorptivity=a, **changes), settings))
    return out


def tilt_cases(quick: bool = False) -> list[tuple]:
    """(params, settings) of the flat sail under a beam of w = 1 m off the middle by OFFSETS × L."""
    base = paper_case("torsion-stable", defect_amplitude=0.0, beam_waist=1.0, **(dict(n=10) if quick else {}))
    return [(base.replace(beam_centre=base.length * (0.5 + d)), TILT) for d in OFFSETS]


def turn_estimate(p) -> float:
    """√(2 · 1° · J_sail / τ): the rigid flat sail's time to turn 1° under the initial torque."""
    state = shapes.initial_state(p)
    fx, fy = loads.radiation_forces(p, state.x, state.theta)
    torque = float(np.sum((state.x - state.x.mean()) * fy - (state.y - state.y.mean()) * fx))
    inertia = p.slice_mass * p.n * p.length**2 / 12.0
    return math.sqrt(2.0 * TURN * inertia / abs(torque))


def profile_row(p, record: dict) -> dict:
    return dict(
        kind="profile",
        E_Pa=p.youngs_modulus,
        beam_waist_m=p.beam_waist,
        reflectivity=p.reflectivity,
        absorptivity=p.absorptivity,
        g0=p.nominal_acceleration,
        failed=record.get("failed"),
        failure_time_s=record.get("failure_time"),
        max_amplitude_ratio=record.get("max_amplitude_ratio"),
        error=record.get("error"),
    )


def tilt_row(p, record: dict, result) -> dict:
    """The first sample time at which the mean slice angle reaches 1° (None: not within the run)."""
    turn = None
    if result is not None:
        mean_angle = np.abs(result.theta.mean(axis=1))
        beyond = np.nonzero(mean_angle >= TURN)[0]
        turn = float(result.time[beyond[0]]) if beyond.size else None
    return dict(
        kind="tilt",
        beam_centre_m=p.beam_centre,
        offset_over_L=p.beam_centre / p.length - 0.5,
        turn_1deg_s=turn,
        turn_1deg_estimate_s=turn_estimate(p),
        error=record.get("error"),
    )


def compute(*, solver="reduced", quick=False, store_dir, workers=None, scheduler=None, progress=True) -> list[dict]:
    """Run (or find in the store) every case; one row per case, kind 'profile' or 'tilt'."""
    profiles, tilts = profile_cases(quick), tilt_cases(quick)
    cases = profiles + tilts
    done = run_cases(
        [p for p, _ in cases],
        store_dir,
        [s for _, s in cases],
        solver=solver,
        workers=workers,
        scheduler=scheduler,
        label="beam and optics",
        progress=progress,
    )
    rows = [profile_row(p, record) for (p, _), (record, _) in zip(profiles, done)]
    rows += [tilt_row(p, record, result) for (p, _), (record, result) in zip(tilts, done[len(profiles) :])]
    return rows


def run(out, *, solver="reduced", quick=False, **options) -> dict:
    """The study into `out`; options: workers, scheduler, store, progress (paper package docstring)."""
    out = Path(out)
    rows = compute(solver=solver, quick=quick, **sweep_options(out, NAME, **options))
    for kind, title in (
        ("profile", f"Beam profile and optics, torsion sail ({solver})"),
        ("tilt", "Off-centre beam (w = 1 m) on a flat sail: time to turn 1°"),
    ):
        mine = [r for r in rows if r["kind"] == kind]
        write_csv(out / f"beam_optics_{kind}.csv", mine)
        print_table(title, mine)
    plot(out / "beam_optics.png", rows)
    return {"rows": rows}


def plot(path, rows) -> Path:
    """Left: failure time against the beam waist (R = 1); right: time to turn 1° against the beam offset."""
    fig, ax = new_figure(1, 2, size=(10.0, 4.0))
    for E in sorted({r["E_Pa"] for r in rows if r["kind"] == "profile"}):
        mine = [r for r in rows if r["kind"] == "profile" and r["E_Pa"] == E and r["reflectivity"] == 1.0]
        x = [min(r["beam_waist_m"], 10.0) for r in mine]
        y = [r["failure_time_s"] if r["failed"] else np.nan for r in mine]
        uniform = "fails" if mine[0]["failed"] else "stable"
        ax[0, 0].loglog(x, y, "o-", label=f"E = {E:.2g} Pa (uniform beam: {uniform})")
    ax[0, 0].set_xlabel("beam waist w (m; 10 = uniform)")
    ax[0, 0].set_ylabel("failure time (s)")
    ax[0, 0].legend(fontsize=7)
    tilt = [r for r in rows if r["kind"] == "tilt"]
    ax[0, 1].loglog([r["offset_over_L"] for r in tilt], [r["turn_1deg_s"] or np.nan for r in tilt], "o-", label="run")
    ax[0, 1].loglog(
        [r["offset_over_L"] for r in tilt],
        [r["turn_1deg_estimate_s"] for r in tilt],
        "k:",
        label="rigid plate estimate",
    )
    ax[0, 1].set_xlabel("beam offset (x_c − L/2)/L")
    ax[0, 1].set_ylabel("time to turn 1° (s)")
    ax[0, 1].legend(fontsize=8)
    fig.suptitle("Gaussian beam, partial reflector, off-centre beam (torsion sail)", fontsize=10)
    return save_figure(fig, path)
