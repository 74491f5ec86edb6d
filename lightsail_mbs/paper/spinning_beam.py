"""Spinning sails in the beam (docs: spinning-beam): the rigid criterion of a billowed disc with a payload, a
very stiff and a flexible disc run across its boundary, and the two solvers on a spinning, tilted, offset
disc. ``write(out)`` runs them and writes spinning_beam.md (python scenarios/spinning_beam.py).

* **Criterion** (:mod:`lightsail_mbs.analysis.ride3d_criterion`): for caps of radius R = 1 and 2 m in
  beams of waist w = 0.5 and 1 m, with a payload of the sail's own mass, the stems d where the rigid craft
  starts or stops riding at rest (Ω = 0), and the spin above which the stem 0.9 d* rides (gyroscopic).
* **Boundary runs**: the 49-tile disc on the cap R = 1 m in the beam w = 0.5 m (I₀ = 0.1 GW/m², axis 0.5 mm
  off the middle), stem at 0.9 d* and 1.1 d*, 2 s with the in-house solver; very stiff (E = 1e21 Pa,
  E_m = 1e13 Pa: a rigid body to the beam) and the paper's stiff film (E = 4.5e13 Pa, E_m = 4.5e9 Pa);
  verdict (analysis.ride3d: crumples once a tile is 5 cm from the rigidly moved cap; a run stops where its
  plane amplitude, the cap's sag at the start, has doubled) and the growth of the
  centre of mass's distance from the axis, log(last fifth's largest / first fifth's)/time between them.
* **Cross-check**: the disc of tests/solvers/test_sheet_ride.py, 1 s, both solvers (Exudyn at 0.1 ms).
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np

from lightsail_mbs import solvers
from lightsail_mbs.analysis.ride3d import sheet_ride
from lightsail_mbs.analysis.ride3d_criterion import cap_criterion, stem_boundaries
from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.studies.tables import markdown_table

DISC = dict(model="sheet", n=9, ny=12, planform="disc")  # 49 tiles
CAP = SailParameters(**DISC, billow_radius=1.0, billow_rest=True, beam_waist=0.5, defect_amplitude=0.0, intensity=1e8)
CAP = CAP.replace(beam_centre=0.5005)
SAIL_MASS = 1e-3 * math.pi / 4  # ρh πL²/4 of the 1 µm film
FILMS = {"very stiff": dict(youngs_modulus=1e21, membrane_modulus=1e13), "paper's stiff film": {}}
# the two-solver ride: a disc stiff in bending (E = 1e18 Pa) holds its 1 mm defect, so it starts in the exact spun
# equilibrium of that shape (initial_equilibrium), not released in the flat centrifugal stress
CROSSCHECK = SailParameters(**DISC, youngs_modulus=1e18, membrane_modulus=4.5e9, intensity=1e6, spin_rate=20.0)
CROSSCHECK = CROSSCHECK.replace(
    defect_amplitude=1e-3, bending_reference="initial", beam_waist=0.4, initial_equilibrium=True
)
CROSSCHECK = CROSSCHECK.replace(beam_centre=0.45, beam_centre_y=0.52, initial_tilt=0.02, initial_tilt_y=-0.01)


def criterion_rows() -> list[dict]:
    rows = []
    for R in (1.0, 2.0):
        for w in (0.5, 1.0):
            p = CAP.replace(billow_radius=R, beam_waist=w, beam_centre=None)
            c = cap_criterion(p, SAIL_MASS, 1.0)
            crossings = stem_boundaries(p, SAIL_MASS, 0.2 * c.static_boundary, 50 * c.static_boundary)
            spins = np.geomspace(1.0, 1e4, 161)
            below = [s for s in spins if cap_criterion(p, SAIL_MASS, 0.9 * c.static_boundary, s).stable]
            rows.append(
                {
                    "R (m)": R,
                    "w (m)": w,
                    "d* (m)": f"{c.static_boundary:.4f}",
                    "rides at rest for d in": ", ".join(_spans(crossings)),
                    "0.9 d* rides from Ω (rad/s)": f"{below[0]:.3g}" if below else "no spin ≤ 1e4",
                }
            )
    return rows


def _spans(crossings: list) -> list[str]:
    spans, start = [], None
    for d, stable_above in crossings:
        if stable_above:
            start = d
        elif start is not None:
            spans.append(f"({start:.4g}, {d:.4g})")
            start = None
    if start is not None:
        spans.append(f"({start:.4g}, ∞)")
    return spans


def boundary_rows(fractions=(0.9, 1.1), t_final: float = 2.0) -> list[dict]:
    d_star = cap_criterion(CAP, SAIL_MASS, 1.0).static_boundary
    rows = []
    for film, fields in FILMS.items():
        for f in fractions:
            p = CAP.replace(payload_mass=SAIL_MASS, payload_stem=f * d_star, **fields)
            c = cap_criterion(p, SAIL_MASS, f * d_star)
            start = time.process_time()
            # stopped where the plane amplitude doubles (the cap's sag: a crumpled sail), else run to t_final
            r = solvers.solve(p, "reduced", RunSettings(t_final=t_final, output_interval=0.02))
            ride = sheet_ride(r, crumple=0.05)
            fifth = max(len(r.time) // 5, 1)
            first, last = ride.distance[:fifth].max(), ride.distance[-fifth:].max()
            growth = math.log(last / first) / (r.time[-1] - r.time[fifth]) if r.time[-1] > r.time[fifth] else math.nan
            rows.append(
                {
                    "film": film,
                    "d/d*": f,
                    "criterion": f"{'rides' if c.stable else 'drifts out'} (growth {c.growth_rate:.2f}/s)",
                    "run": ride.verdict + (f" at {ride.decided_at:.2f} s" if ride.decided_at is not None else ""),
                    "max distance, first / last fifth (m)": f"{first:.2g} / {last:.2g}",
                    "its growth (1/s)": f"{growth:.2f}",
                    "largest deformation (m)": f"{ride.deformation.max():.2g}",
                    "CPU (s)": f"{time.process_time() - start:.0f}",
                }
            )
    return rows


def crosscheck_rows(t_final: float = 1.0) -> list[dict]:
    settings = RunSettings(t_final=t_final, output_interval=0.05, stop_at_failure=False)
    rides = {
        "reduced": sheet_ride(solvers.solve(CROSSCHECK, "reduced", settings)),
        "exudyn": sheet_ride(solvers.solve(CROSSCHECK, "exudyn", settings, step_size=1e-4)),
    }
    a, b = rides["reduced"], rides["exudyn"]
    rows = []
    for name, x, y, scale in (
        ("lateral X (m)", a.lateral[-1, 0], b.lateral[-1, 0], abs(a.lateral[-1, 0])),
        ("lateral Y (m)", a.lateral[-1, 1], b.lateral[-1, 1], abs(a.lateral[-1, 1])),
        ("tilt α_x (rad)", a.tilt[-1, 0], b.tilt[-1, 0], abs(a.tilt[-1, 0])),
        ("tilt α_y (rad)", a.tilt[-1, 1], b.tilt[-1, 1], abs(a.tilt[-1, 1])),
        ("spin rate (rad/s)", a.spin_rate[-1], b.spin_rate[-1], abs(a.spin_rate[-1])),
        ("shape amplitude (m)", a.amplitude[-1], b.amplitude[-1], CROSSCHECK.defect_amplitude),
    ):
        unit = "a₀" if name.startswith("shape") else "relative"
        rows.append(
            {
                "at 1 s": name,
                "reduced": f"{x:.8g}",
                "exudyn": f"{y:.8g}",
                "difference": f"{abs(x - y) / scale:.2g} {unit}",
            }
        )
    largest = np.max(np.abs(a.amplitude - b.amplitude)) / CROSSCHECK.defect_amplitude
    rows.append({"at 1 s": "largest shape difference over the run", "difference": f"{largest:.2g} a₀"})
    return rows


def write(out, quick: bool = False) -> Path:
    """Run the three parts and write spinning_beam.md into `out`; quick: short runs (a smoke test)."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    criterion = criterion_rows()
    boundary = boundary_rows(t_final=0.1 if quick else 2.0)
    cross = crosscheck_rows(t_final=0.05 if quick else 1.0)
    text = "\n\n".join(
        [
            "# Spinning sails in the beam: tables",
            "Made by `python scenarios/spinning_beam.py --out scenarios/figures` (lightsail_mbs.paper.spinning_beam).",
            "## The rigid criterion (payload of the sail's mass)",
            markdown_table(criterion),
            "## A very stiff and a flexible disc across the boundary (cap R = 1 m, w = 0.5 m)",
            markdown_table(boundary),
            "## The two solvers on a spinning, tilted, offset disc",
            markdown_table(cross),
        ]
    )
    path = out / "spinning_beam.md"
    path.write_text(text + "\n")
    return path
