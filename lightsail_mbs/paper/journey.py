"""The whole acceleration of a Starshot-class sail and of a lab-scale film (docs/journey.md): journeys with their
verdicts, what each effect (Doppler, heat, expansion) changes, and the figures.

**The Starshot-class case** takes Parkin's 0.2 c point design (K. L. G. Parkin, The Breakthrough Starshot system
model, Acta Astronaut. 152, 370 (2018), arXiv:1805.01306): a 4.1 m diameter sail carrying a 1 g payload,
accelerated for 9 minutes by a 1.06 µm beam to 0.2 c. Here the sail is a silicon-nitride strip of the same area
(3.63 m square, 13.2 m²) weighing 1 g (h = 24 nm), framed and pre-tensioned as the paper's TnT chain with a
1 mm defect (ν = 3/2), and the beam power P is the constant power that takes the 2 g craft to 0.2 c in Parkin's
9 minutes along the closed-form trajectory (≈ 42 GW, within the tens to a hundred GW of the mission studies).
The variants change one thing each: the pre-tension (100 N, 10 N), the heat (absorptance 0), the stiffness
model (the unframed torsion sail) and the film (aluminium of the same mass).

**The lab-scale case** is a 1 cm square, 50 nm silicon-nitride membrane in a frame, pre-tensioned by an assumed
250 MPa residual stress (0.125 N across its width), in a room-temperature chamber (T_env = T_ref = 293 K),
under 1 W to 1 kW (a uniform beam, and a 3 mm Gaussian spot at 1 kW), to a target speed of 1e-8 c (3 m/s: a
lab never reaches relativistic speeds; what the journey says there is the heat and tension at switch-on); and
aluminium and Kapton films of the same size at 1 kW.
"""

from __future__ import annotations

import math
from pathlib import Path

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.model import materials, relativity
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.model.theory import time_scale
from lightsail_mbs.studies.journey import JourneySettings, craft_mass, run_journey
from lightsail_mbs.studies.tables import markdown_table, write_csv
from lightsail_mbs.viz.journey import journey_figure

PARKIN_DIAMETER = 4.1  # m, the 0.2 c point design's sail
PARKIN_PAYLOAD = 1e-3  # kg
PARKIN_ACCELERATION_TIME = 9 * 60.0  # s
SAIL_MASS = 1e-3  # kg: the sail of the Starshot-class case
LAB_POWERS = (1.0, 10.0, 100.0, 1000.0)  # W
LAB_TARGET = 1e-8


def starshot_case(n: int = 30, **changes) -> SailParameters:
    """The Starshot-class sail (module docstring): SiN, Parkin's area as a square, 1 g, framed at 100 N."""
    side = math.sqrt(math.pi) * PARKIN_DIAMETER / 2
    density = materials.get("silicon-nitride").density.value
    fields = {"material": "silicon-nitride", "model": "tnt", "n": n, "length": side, "width": side}
    fields.update(thickness=SAIL_MASS / (density * side**2), tension=100.0, defect_amplitude=1e-3)
    return SailParameters(**materials.fill({**fields, **changes}))


def parkin_power(p: SailParameters) -> float:
    """The constant power P that brings the craft (sail and Parkin's payload) to 0.2 c in Parkin's 9 minutes:
    t(β) ∝ 1/P, so P = t(0.2 at 1 W)/(9 min)."""
    one_watt = relativity.Trajectory(1.0, craft_mass(p, PARKIN_PAYLOAD), p.normal_momentum)
    return float(one_watt.time(0.2)) / PARKIN_ACCELERATION_TIME


def lab_case(**changes) -> SailParameters:
    """The lab-scale membrane (module docstring): 1 cm square SiN, 50 nm, 0.125 N, a 1 µm defect."""
    fields = {"material": "silicon-nitride", "model": "tnt", "n": 30, "length": 0.01, "width": 0.01}
    fields.update(thickness=5e-8, tension=2.5e8 * 5e-8 * 0.01, defect_amplitude=1e-6)
    return SailParameters(**materials.fill({**fields, **changes}))


def _lab_settings(power: float, **changes) -> JourneySettings:
    return JourneySettings(power=power, target_speed=LAB_TARGET, environment=293.15, **changes)


def journeys(quick: bool = False, shape_runs: bool = True) -> dict:
    """Every journey of the page: name -> (description, case, settings, report)."""
    n = 10 if quick else 30
    base = starshot_case(n)
    power = parkin_power(base)
    starshot = {"power": power, "carried_mass": PARKIN_PAYLOAD}
    density = materials.get("aluminium").density.value
    cases = {
        "starshot": ("SiN, framed at 100 N", base, JourneySettings(**starshot, shape_runs=shape_runs)),
        "starshot-10N": (
            "SiN, framed at 10 N",
            base.replace(tension=10.0),
            JourneySettings(**starshot, shape_runs=shape_runs),
        ),
        "starshot-10N-cold": (
            "SiN, framed at 10 N, no absorption",
            base.replace(tension=10.0),
            JourneySettings(**starshot, absorptance=0.0),
        ),
        "starshot-unframed": (
            "SiN, unframed (torsion: bending only)",
            SailParameters(**materials.fill({**base.to_dict(), "model": "torsion", "tension": 0.0})),
            JourneySettings(**starshot),
        ),
        "starshot-aluminium": (
            "aluminium of the same mass, framed at 100 N",
            starshot_case(n, material="aluminium", thickness=base.thickness * base.density / density),
            JourneySettings(**starshot),
        ),
    }
    for watts in LAB_POWERS[-1:] if quick else LAB_POWERS:
        cases[f"lab-{watts:g}W"] = (f"SiN 1 cm, {watts:g} W", lab_case(), _lab_settings(watts))
    cases["lab-1000W-spot"] = ("SiN 1 cm, 1 kW in a 3 mm spot", lab_case(beam_waist=3e-3), _lab_settings(1e3))
    for name in ("aluminium", "kapton"):
        thickness = {"aluminium": 5e-8, "kapton": 2.5e-5}[name]
        film = lab_case(material=name, thickness=thickness, tension=1e-3)
        cases[f"lab-1000W-{name}"] = (f"{name} 1 cm, 1 kW", film, _lab_settings(1e3))
    return {name: (text, p, s, run_journey(p, s)) for name, (text, p, s) in cases.items()}


def summary_rows(results: dict) -> list[dict]:
    """One row per journey: power, mass, start and end of the temperature and margin, the tension needed, the
    time to the target, the verdict."""
    rows = []
    for name, (text, _, s, report) in results.items():
        first, last = report["snapshots"][0], report["snapshots"][-1]
        rows.append(
            {
                "journey": name,
                "case": text,
                "power_W": s.power,
                "mass_kg": report["mass"],
                "target_beta": s.target_speed,
                "t_target_s": last["t"],
                "g0_start": first["acceleration"],
                "T_max_start_K": first["temperature_max"],
                "T_limit_K": report["film"]["limit_temperature"],
                "tension_left_start": first["tension"],
                "tension_needed": first["tension_needed"],
                "margin_start": first["margin"],
                "margin_end": last["margin"],
                "thermal_time_s": first["thermal_time"],
                "change_time_s": first["change_time"],
                "thermal_lag": report["thermal_lag"],
                "shape_run": _shape_text(report),
                "verdict": report["verdict"]["text"],
            }
        )
    return rows


def _shape_text(report: dict) -> str:
    runs = [r for r in report["snapshots"] if "shape_failed" in r]
    if not runs:
        return "–"
    failed = [r for r in runs if r["shape_failed"]]
    if not failed:
        return f"none of {len(runs)} fails"
    return f"{len(failed)} of {len(runs)} fail (first in {failed[0]['shape_failure_time']:.3g} s)"


def effects(results: dict) -> list[dict]:
    """What each effect changes in the Starshot-class journey, with numbers."""
    _, p, s, report = results["starshot"]
    first, last = report["snapshots"][0], report["snapshots"][-1]
    trajectory = relativity.Trajectory(s.power, report["mass"], p.normal_momentum)
    no_doppler = trajectory.time_constant * 0.2 / math.sqrt(1 - 0.04)  # γβ = t/K without the Doppler factor
    slack, cold = results["starshot-10N"][3], results["starshot-10N-cold"][3]
    relief = p.tension - first["tension"]
    rate = first["acceleration"] / SPEED_OF_LIGHT
    growth = 1.0 / time_scale(p.replace(intensity=first["intensity_sail"]))
    fall, wavelengths = last["acceleration"] / first["acceleration"], (first["wavelength"], last["wavelength"])
    return [
        {
            "effect": "Doppler (relativistic beam)",
            "changes the verdict": "no (under constant power it only relieves)",
            "by how much": f"t(0.2 c) {last['t']:.4g} s against {no_doppler:.4g} s at the unshifted intensity "
            f"(+{100 * (last['t'] / no_doppler - 1):.3g} %); I' and g₀ fall to {fall:.3g}×, T_max "
            f"{first['temperature_max']:.4g} → {last['temperature_max']:.4g} K, λ' {wavelengths[0] * 1e6:.4g} → "
            f"{wavelengths[1] * 1e6:.4g} µm, margin ×{last['margin'] / first['margin']:.3g}",
        },
        {
            "effect": "heat (absorptance)",
            "changes the verdict": f"yes, at 10 N pre-tension: {cold['verdict']['verdict']} without it, "
            f"{slack['verdict']['verdict']} with it",
            "by how much": f"T_max {first['temperature_max']:.4g} K at the start (limit "
            f"{report['film']['limit_temperature']:.4g} K); thermal lag ≤ {report['thermal_lag']:.2g} of T",
        },
        {
            "effect": "thermal expansion (framed film)",
            "changes the verdict": "yes: it sets the pre-tension a framed sail needs",
            "by how much": f"relieves {relief:.4g} N against T_cr,max = {first['critical']:.3g} N "
            f"({relief / first['critical']:.3g}×): a pre-tension above {first['tension_needed']:.4g} N holds",
        },
        {
            "effect": "velocity-dependent damping (a physics term, --velocity-terms; not in these snapshots)",
            "changes the verdict": "no",
            "by how much": f"a rate of order g₀/c = {rate:.2g} /s against the shape's growth rate 1/t_c = "
            f"{growth:.3g} /s at the start (docs/journey.md: it delays the soft sail's failure by 5.3e-7)",
        },
    ]


def run(out, quick: bool = False, shape_runs: bool = True) -> dict:
    """Write journey.md (the tables included by docs/journey.md), journey_summary.csv, and for the
    Starshot-class and the focused lab journey their CSV and PNG into `out`."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    results = journeys(quick, shape_runs)
    rows = summary_rows(results)
    write_csv(out / "journey_summary.csv", rows)
    for name in ("starshot", "lab-1000W-spot"):
        report = results[name][3]
        write_csv(out / f"journey_{name}.csv", report["snapshots"])
        journey_figure(report, out / f"journey_{name}.png", title=results[name][0])
    columns = {
        "journey": "journey",
        "case": "case",
        "power_W": "P (W)",
        "t_target_s": "t to target (s)",
        "T_max_start_K": "T max (K)",
        "T_limit_K": "T limit (K)",
        "tension_left_start": "tension left (N)",
        "tension_needed": "tension needed (N)",
        "margin_start": "margin",
        "shape_run": "shape runs",
        "verdict": "verdict",
    }
    text = (
        "<!-- written by scenarios/journey.py (lightsail_mbs.paper.journey); do not edit -->\n\n"
        + markdown_table(rows, columns)
        + "\n\n**Time scales at the start** (the film's thermal time ρc_p h/(4εσT³), the time c/(2g₀) over which "
        "the beam changes, and the largest lag of T behind its steady field along the journey).\n\n"
        + markdown_table(
            rows,
            {
                "journey": "journey",
                "thermal_time_s": "τ_th (s)",
                "change_time_s": "c/(2g₀) (s)",
                "thermal_lag": "lag (fraction of T)",
            },
        )  # fmt: skip
        + "\n\n**What each effect changes (the Starshot-class journey).**\n\n"
        + markdown_table(effects(results))
        + "\n"
    )
    (out / "journey.md").write_text(text, encoding="utf-8")
    return results
