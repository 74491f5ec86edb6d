"""Beam riding of the flexible sail: a billowed sail with a payload on a stem, offset in a Gaussian beam.

Usage: python scenarios/flexible_beam_riding.py [--out DIR] [--quick]. Writes into OUT (default
scenarios/figures): flexible_beam_riding.png (histories and the stem map), flexible_beam_riding.csv (every
run), flexible_beam_riding.md (the tables the docs quote) and flexible_beam_riding.gif (a riding run).

The sail: L = W = 1 m, h = 1 µm, ρ = 1000 kg/m³, n = 10 slices, billowed on an arc of R_c = 2 m concave to
the laser with the torsion springs at rest on it (billow_rest: a sail made curved), no defect, material
damping β = 1e-4 s (damps the bending modes above ~1e4 rad/s, leaves the rigid riding motion alone);
payload m_p = 1 g (the sail's mass) on a stem of length d from the middle towards the laser; Gaussian beam
I₀ = 1e8 W/m², waist w = 0.5 m, its axis 1 cm beside the sail's middle. Verdicts (analysis.beam_riding.
flexible_ride): "crumples" once a slice centre is 1 cm off the rigidly moved initial shape, "drifts out" once
the craft's centre of mass is one waist from the axis, else "rides". Beside them: the same sail locked rigid
(analysis.beam_riding.ride) and the closed-form criterion's boundary d* (analysis.beam_riding.criterion).

1. The two solvers on one riding run (E = 1e19 Pa, d = 6 m, 1 s): lateral position and tilt at 1 s.
2. Histories (d = 6 m, 5 s) for E = 1e17, 1e18, 1e19 Pa, E = 1e19 Pa with the paper's defect on top of the
   arc (a₀ = 10 µm, ν = 3/2), and the rigid body.
3. The stem map: verdicts of 20 s runs for E = 1e18, 1e19, 1e20 Pa and the rigid body over d = 3…8 m.
--quick: 2 s runs, a coarse stem grid, no Exudyn, 8 frames (a smoke run).
"""

import argparse
import csv
import functools
import time
from pathlib import Path

import numpy as np

from lightsail_mbs import RunSettings, SailParameters
from lightsail_mbs import solve as solve_with_estimate
from lightsail_mbs.analysis import beam_riding
from lightsail_mbs.viz.plots import new_figure, save_figure

solve = functools.partial(solve_with_estimate, uncertainty=False)  # single runs: no error bars in this report

HERE = Path(__file__).resolve().parent
OFFSET = 0.01  # m: the sail's middle beside the beam axis
PAYLOAD = 1e-3  # kg
BASE = dict(
    n=10,
    billow_radius=2.0,
    billow_rest=True,
    beam_waist=0.5,
    beam_centre=0.5 - OFFSET,
    defect_amplitude=0.0,
    payload_mass=PAYLOAD,
    stiffness_damping=1e-4,
)


def case(E, d, **changes):
    return SailParameters(**{**BASE, "youngs_modulus": E, "payload_stem": d, **changes})


def flexible(E, d, t_final, solver="reduced", changes=None, **options):
    """(Result, FlexibleRide); a run that crumples within its first second is not continued."""
    p = case(E, d, **(changes or {}))
    first = solve(
        p, solver, RunSettings(t_final=min(1.0, t_final), output_interval=0.01, stop_at_failure=False), **options
    )
    r = first
    if beam_riding.flexible_ride(first).verdict != "crumples" and t_final > 1.0:
        r = solve(p, solver, RunSettings(t_final=t_final, output_interval=0.01, stop_at_failure=False), **options)
    return r, beam_riding.flexible_ride(r)


def rigid(d, t_final):
    sail = beam_riding.RigidSail(case(1e19, d), PAYLOAD, d)
    return beam_riding.ride(sail, t_final, offset=OFFSET, output_interval=0.01)


def log(msg):
    print(msg, flush=True)


def two_solvers(quick):
    if quick:
        return []
    rows = []
    runs = {}
    for solver, options in (("reduced", dict(rtol=1e-10)), ("exudyn", dict(step_size=5e-5))):
        t0 = time.process_time()
        r = solve(
            case(1e19, 6.0), solver, RunSettings(t_final=1.0, output_interval=0.01, stop_at_failure=False), **options
        )
        runs[solver] = (beam_riding.flexible_ride(r), time.process_time() - t0)
    (a, ca), (b, cb) = runs["reduced"], runs["exudyn"]
    for name in ("lateral", "tilt"):
        u, v = getattr(a, name)[-1], getattr(b, name)[-1]
        rows.append(f"| {name} at 1 s | {u:.9g} | {v:.9g} | {abs(u - v) / abs(u):.1e} |")
    rows.append(f"| verdict | {a.verdict} | {b.verdict} | |")
    rows.append(f"| CPU time (s) | {ca:.2f} | {cb:.2f} | |")
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=str(HERE / "figures"))
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    quick = args.quick
    t_hist = 2.0 if quick else 5.0
    t_map = 2.0 if quick else 20.0
    stems = [3.0, 4.0, 6.0] if quick else [3.0, 3.5, 3.8, 3.9, 4.0, 4.1, 4.3, 4.6, 5.0, 6.0, 8.0]
    moduli = [1e18, 1e19] if quick else [1e18, 1e19, 1e20]
    crit = beam_riding.criterion(case(1e19, 6.0), PAYLOAD, 6.0)
    log("two solvers")
    table = two_solvers(quick)
    log("histories")
    hist = {}
    for E in (1e17, 1e18, 1e19):
        r, f = flexible(E, 6.0, t_hist)
        hist[f"E = {E:.0e} Pa"] = (f, r)
    defect = dict(defect_amplitude=1e-5, defect_mode=1.5)
    r, f = flexible(1e19, 6.0, t_hist, changes=defect)
    hist["E = 1e+19 Pa, paper's defect"] = (f, r)
    rr = rigid(6.0, t_hist)
    records = []
    for d in stems:
        rv = rigid(d, t_map)
        records.append(
            dict(model="rigid", E="", d=d, verdict=rv.verdict, decided_at=rv.decided_at, max_deformation=0.0)
        )
        for E in moduli:
            log(f"map: E = {E:.0e}, d = {d}")
            _, f = flexible(E, d, t_map)
            records.append(
                dict(
                    model="flexible",
                    E=E,
                    d=d,
                    verdict=f.verdict,
                    decided_at=f.decided_at,
                    max_deformation=float(f.deformation.max()),
                )
            )
    with open(out / "flexible_beam_riding.csv", "w", newline="") as handle:
        w = csv.DictWriter(handle, fieldnames=list(records[0]))
        w.writeheader()
        w.writerows(records)
    # figure
    fig, axes = new_figure(2, 2, size=(11, 7))
    (ax_x, ax_t), (ax_d, ax_m) = axes
    for label, (f, _) in hist.items():
        ax_x.plot(f.time, f.lateral, label=label)
        ax_t.plot(f.time, f.tilt, label=label)
        ax_d.semilogy(f.time, np.maximum(f.deformation, 1e-9), label=label)
    ax_x.plot(rr.time, rr.lateral, "k--", label="rigid")
    ax_t.plot(rr.time, rr.tilt, "k--", label="rigid")
    ax_x.set(xlabel="t (s)", ylabel="X − x_c (m)", ylim=(-0.6, 0.6), title="lateral position, d = 6 m")
    ax_t.set(xlabel="t (s)", ylabel="tilt φ (rad)", ylim=(-0.5, 0.5), title="tilt")
    ax_d.axhline(0.01, color="grey", lw=0.8)
    ax_d.set(xlabel="t (s)", ylabel="deformation δ (m)", title="shape: largest distance from the rigid fit")
    ax_x.legend(fontsize=8)
    rows = ["rigid"] + [f"{E:.0e}" for E in moduli]
    marker = {
        "rides": ("o", "tab:green"),
        "drifts out": ("x", "tab:red"),
        "crumples": ("s", "tab:purple"),
        "tumbles": ("^", "tab:orange"),
    }
    for rec in records:
        y = 0 if rec["model"] == "rigid" else 1 + moduli.index(rec["E"])
        m, c = marker[rec["verdict"]]
        ax_m.plot(rec["d"], y, m, color=c, ms=8)
    ax_m.axvline(crit.static_boundary, color="k", ls=":", label=f"criterion d* = {crit.static_boundary:.3f} m")
    for name, (m, c) in marker.items():
        ax_m.plot([], [], m, color=c, label=name)
    ax_m.set(
        yticks=range(len(rows)),
        yticklabels=rows,
        xlabel="stem d (m)",
        ylabel="E (Pa)",
        title=f"verdict after {t_map:g} s",
    )
    ax_m.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    save_figure(fig, out / "flexible_beam_riding.png")
    # movie of the riding sail
    from lightsail_mbs.viz.frames import make_movie, render_frames

    riding = hist["E = 1e+19 Pa"][1]
    frames = render_frames(riding, out / "flexible_beam_riding_frames", frames=8 if quick else 50, size="480x240")
    gif = make_movie(frames, out / "flexible_beam_riding.gif", fps=10)
    for f in frames:
        f.unlink()
    (out / "flexible_beam_riding_frames").rmdir()
    # tables
    lines = [
        "# Flexible beam riding" + (" (--quick smoke run)" if quick else ""),
        "",
        f"Closed-form rigid criterion: d* = {crit.static_boundary:.4f} m (rides for d > d*, no flutter band for "
        "w = 0.5 m).",
        "",
        "## The two solvers on one riding run (E = 1e19 Pa, d = 6 m, 1 s)",
        "",
        "| quantity | reduced (DOP853, rtol 1e-10) | Exudyn (generalized-α, h = 5e-5 s) | relative difference |",
        "|---|---|---|---|",
        *table,
        "",
        f"## Histories (d = 6 m, {t_hist:g} s)",
        "",
        "| sail | verdict | decided at (s) | max abs X − x_c (m) | max abs φ (rad) | max δ (m) |",
        "|---|---|---|---|---|---|",
    ]
    for label, (f, _) in hist.items():
        at = "–" if f.decided_at is None else f"{f.decided_at:.3g}"
        lines.append(
            f"| {label} | {f.verdict} | {at} | {np.abs(f.lateral).max():.3g} | {np.abs(f.tilt).max():.3g} | "
            f"{f.deformation.max():.3g} |"
        )
    at = "–" if rr.decided_at is None else f"{rr.decided_at:.3g}"
    lines.append(f"| rigid | {rr.verdict} | {at} | {np.abs(rr.lateral).max():.3g} | {np.abs(rr.tilt).max():.3g} | 0 |")
    lines += [
        "",
        f"## Stem map (verdict after {t_map:g} s; decided at, s)",
        "",
        "| d (m) | rigid | " + " | ".join(f"E = {E:.0e} Pa" for E in moduli) + " |",
        "|---" * (len(moduli) + 2) + "|",
    ]
    for d in stems:
        cells = []
        for rec in [r for r in records if r["d"] == d]:
            when = "" if rec["decided_at"] is None else f" ({rec['decided_at']:.3g})"
            cells.append(rec["verdict"] + when)
        lines.append(f"| {d:g} | " + " | ".join(cells) + " |")
    (out / "flexible_beam_riding.md").write_text("\n".join(lines) + "\n")
    log(f"wrote {out / 'flexible_beam_riding.md'}, .png, .csv, {gif.name}")


if __name__ == "__main__":
    main()
