"""Maps of the 3-D ride verdict of the billowed disc with a stem payload, and a movie of one spinning sail in
the beam (docs: spinning-beam). ``write(out)`` runs them (python scenarios/spinning_beam.py --only maps).

* **Case**: the 25-tile disc (n = 7, ny = 8) of the paper's stiff film (E = 4.5e13 Pa) on a cap of radius
  R_c, stress-free there (billow_rest), a stem payload of the sail's own mass at d = (d/d*) d*, d* the rigid
  criterion's boundary for that cap (analysis.ride3d_criterion), I₀ = 0.1 GW/m², the beam's axis 0.2 w off
  the sail's middle; 1.2 s with the in-house solver at rtol 1e-4, output every 20 ms, stopped where the
  plane amplitude reaches 3 × its start (a crumpled cap). A spinning cap starts at rest in its turning frame
  (spin_equilibrium: the unlit shape relaxed under the centrifugal loads, solvers.reduced.sheet_relax), then
  lit; the flat sheet's centrifugal stress (the spinning sheet's default start) does not hold a deep cap.
* **Maps** (studies.ride_maps, one store, resumable): d/d* against R_c (w = 0.5 m, Ω = 0), against the
  beam waist w (R_c = 1 m, Ω = 0) and against the spin rate Ω (R_c = 1 m, w = 0.5 m). Verdict: crumples
  once a tile is 5 cm from the rigidly moved cap, drifts out at a waist from the axis, else rides; each
  cell also gives the distance's growth rate (1/s); a run the failure rule ended early past 45° of tilt
  "tips over" (studies.ride_maps). Over each map the rigid criterion's riding region
  (the undamped quartic of analysis.ride3d_criterion, on a 41 × 41 grid) is outlined.
* **Movie**: the same disc at d = 1.3 d* spinning at 20 rad/s from its spun equilibrium, 5 cm off the axis
  and tilted by (0.02, −0.01) rad, 1.5 s, as a GIF (viz.ride), its ride histories (studies.ride_maps) as a CSV.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from lightsail_mbs import solvers
from lightsail_mbs.analysis.ride3d_criterion import cap_criterion
from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.paper.spinning_beam import CAP, SAIL_MASS
from lightsail_mbs.studies.ride_maps import grid, ride_histories, ride_map
from lightsail_mbs.studies.tables import markdown_table, series_csv, write_csv

BASE = CAP.replace(n=7, ny=8, payload_mass=SAIL_MASS, beam_centre=None)
SETTINGS = RunSettings(t_final=1.2, output_interval=0.02, failure_ratio=3.0)
OPTIONS = {"rtol": 1e-4}
OFFSET = 0.2  # the beam's axis from the sail's middle, in waists
RATIOS = [0.7, 0.85, 0.95, 1.05, 1.15, 1.3]  # d/d*
# name -> (x axis: label, field, values; the other fields of the map's cases)
MAPS = {
    "billow": ("billow radius R_c (m)", "billow_radius", [0.75, 1.0, 1.25, 1.5, 2.0, 2.5], {}),
    "waist": ("beam waist w (m)", "beam_waist", [0.3, 0.4, 0.5, 0.75, 1.0, 1.5], {}),
    "spin": ("spin rate Ω (rad/s)", "spin_rate", [0.0, 40.0, 80.0, 120.0, 160.0], {}),
}
SPIN_RATIOS = [0.7, 0.85, 1.0, 1.15, 1.3]
MOVIE = dict(spin_rate=20.0, initial_tilt=0.02, initial_tilt_y=-0.01)
MOVIE_RATIO, MOVIE_OFFSET, MOVIE_TIME = 1.3, 0.05, 1.5
SHORT = {"rides": "R", "drifts out": "D", "tips over": "T", "crumples": "C", "stopped": "S"}
COLOURS = {
    "rides": "#74c476",
    "drifts out": "#fd8d3c",
    "tips over": "#9e9ac8",
    "crumples": "#de2d26",
    "stopped": "#f0f0f0",
    None: "#bdbdbd",
}


def d_star(p) -> float:
    """The rigid criterion's boundary stem d* (m) of case p's cap with the sail's mass as payload."""
    return cap_criterion(p, SAIL_MASS, 1.0).static_boundary


def make(field: str):
    """make(base, x, d/d*) of a map along `field`: the field set, the stem at d/d* × d*, the axis 0.2 w off, a
    spinning cap started at rest in its turning frame (spin_equilibrium)."""

    def build(p, value, ratio):
        p = p.replace(**{field: value})
        p = p.replace(beam_centre=0.5 + OFFSET * p.beam_waist, spin_equilibrium=bool(p.spin_rate != 0))
        return p.replace(payload_stem=ratio * d_star(p))

    return build


def criterion_region(field: str, xs, ratios, samples: int = 41) -> tuple:
    """(x, d/d*, stable) on a samples × samples grid over the map's ranges: the rigid criterion."""
    x = np.linspace(min(xs), max(xs), samples)
    y = np.linspace(min(ratios), max(ratios), samples)
    build = make(field)
    stable = np.array(
        [[cap_criterion(build(BASE, u, v), SAIL_MASS, v * d_star(build(BASE, u, 1.0))).stable for u in x] for v in y]
    )
    return x, y, stable


def edges(values) -> np.ndarray:
    v = np.asarray(values, float)
    mid = 0.5 * (v[1:] + v[:-1])
    return np.concatenate([[v[0] - (mid[0] - v[0])], mid, [v[-1] + (v[-1] - mid[-1])]])


def draw(path: Path, maps: dict) -> Path:
    """The maps side by side: cells coloured by verdict, labelled with the growth rate (1/s), the rigid
    criterion's riding region hatched and outlined (black)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.patches import Patch

    fig = Figure(figsize=(5.0 * len(maps), 4.6), dpi=100)
    FigureCanvasAgg(fig)
    for k, (name, (xs, ys, cells, region)) in enumerate(maps.items()):
        ax = fig.add_subplot(1, len(maps), k + 1)
        ex, ey = edges(xs), edges(ys)
        for i, u in enumerate(xs):
            for j, v in enumerate(ys):
                c = cells[(u, v)]
                ax.fill_between([ex[i], ex[i + 1]], ey[j], ey[j + 1], color=COLOURS[c.verdict], lw=0)
                label = "err" if c.verdict is None else f"{c.growth:.1f}"
                ax.text(u, v, label, ha="center", va="center", fontsize=7)
        x, y, stable = region
        if stable.any():
            ax.contourf(x, y, stable.astype(float), levels=[0.5, 1.5], colors="none", hatches=["//"])
            ax.contour(x, y, stable.astype(float), levels=[0.5], colors="k", linewidths=1.2)
        ax.set_xlim(ex[0], ex[-1])
        ax.set_ylim(ey[0], ey[-1])
        ax.set_xlabel(MAPS[name][0])
        ax.set_ylabel("payload distance d / d*")
        ax.set_title(f"{name}: verdict at {SETTINGS.t_final:g} s, growth (1/s)", fontsize=9)
    handles = [Patch(color=COLOURS[v], label=v) for v in SHORT]
    fig.legend(
        handles=handles + [Patch(facecolor="none", edgecolor="k", hatch="//", label="rigid criterion rides")],
        loc="lower center",
        ncol=6,
        fontsize=8,
    )
    fig.subplots_adjust(bottom=0.2, wspace=0.3)
    fig.savefig(path)
    return path


def cell_text(c) -> str:
    """A map cell as the tables print it: its verdict (SHORT), decision time and growth, or "error"."""
    when = "" if c.decided_at is None else f" {c.decided_at:.2f} s"
    return "error" if c.verdict is None else f"{SHORT[c.verdict]}{when} ({c.growth:.1f}/s)"


def table(name: str, xs, ys, cells) -> list[dict]:
    """Rows d/d* (top: the largest), one column per x: verdict (SHORT), decision time, growth."""
    return [{"d/d*": v, **{f"{u:g}": cell_text(cells[(u, v)]) for u in xs}} for v in sorted(ys, reverse=True)]


def run_maps(store, workers=None, quick: bool = False, progress: bool = True) -> dict:
    """{name: (xs, d/d* values, cells, criterion region)} of every map (module docstring)."""
    settings = SETTINGS.replace(t_final=0.1) if quick else SETTINGS
    maps = {}
    for name, (_, field, xs, changes) in MAPS.items():
        ratios = SPIN_RATIOS if name == "spin" else RATIOS
        if quick:
            xs, ratios = xs[:2], ratios[:2]
        cases = grid(BASE.replace(**changes), (field, xs), ("payload_stem", ratios), make=make(field))
        cells = ride_map(
            cases, store_dir=store, settings=settings, options=OPTIONS, workers=workers, progress=progress, label=name
        )
        maps[name] = (xs, ratios, cells, criterion_region(field, xs, ratios, 11 if quick else 41))
    return maps


def movie(out: Path, frames: int = 40, quick: bool = False) -> Path:
    """The movie's run (module docstring) rendered as OUT/spinning_ride.gif; its ride histories in
    OUT/spinning_ride.csv: the centre of mass's distance from the beam's axis (m), the deformation (m), the
    tilt (rad) and the spin rate (rad/s) against time."""
    from lightsail_mbs.viz.frames import make_movie
    from lightsail_mbs.viz.ride import render_ride_frames

    p = BASE.replace(**MOVIE).replace(beam_centre=0.5 + MOVIE_OFFSET, spin_equilibrium=True)
    p = p.replace(payload_stem=MOVIE_RATIO * d_star(p))
    settings = RunSettings(t_final=0.1 if quick else MOVIE_TIME, output_interval=0.02, stop_at_failure=False)
    result = solvers.solve(p, "reduced", settings, uncertainty=False, **OPTIONS)
    ride = ride_histories(result)
    units = {"distance": "m", "deformation": "m", "tilt": "rad", "spin_rate": "rad_s"}
    series_csv(out / "spinning_ride.csv", np.asarray(ride["time"]), {f"{k}_{u}": ride[k] for k, u in units.items()})
    paths = render_ride_frames(
        result, out / "spinning_ride_frames", frames=min(frames, len(result.time)), size=(640, 320)
    )
    return make_movie(paths, out / "spinning_ride.gif", fps=12.0)


def write(out, store=None, workers=None, quick: bool = False) -> Path:
    """Run the maps and the movie; write spinning_maps.md, .png, .csv and spinning_ride.gif into `out`."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    maps = run_maps(store or out / "store" / "spinning_maps", workers=workers, quick=quick)
    draw(out / "spinning_maps.png", maps)
    parts = [
        "# Maps of the ride verdict",
        "Made by `python scenarios/spinning_beam.py --only maps --out scenarios/figures`"
        " (lightsail_mbs.paper.spinning_maps).",
    ]
    rows = []
    for name, (xs, ys, cells, _) in maps.items():
        parts += [f"## d/d* against {MAPS[name][0]}", markdown_table(table(name, xs, ys, cells))]
        rows += [{"map": name, "x": u, "d/d*": v, **cells[(u, v)].as_dict()} for v in ys for u in xs]
    write_csv(out / "spinning_maps.csv", rows)
    movie(out, quick=quick)
    path = out / "spinning_maps.md"
    path.write_text("\n\n".join(parts) + "\n")
    return path
