"""FlexSailSim's published case re-posed with bending (docs: spinning-beam, "FlexSailSim's case").

Gao, Kelzenberg & Atwater (Nature Communications 2024) fly a flat 1 m disc of the Si₃N₄ metagrating "Mark 1e",
spun at 120 Hz, 10 % of its radius off the axis of a Gaussian beam 0.4 D wide in both x and y and tilted −2°
about both in-plane axes, at 1 GW/m² for 5 s (their Fig. 6), in FlexSailSim, a spring-mass membrane with no
bending stiffness. Here the same disc is a sheet of tiles with plate bending (model.sheet) in both solvers.

**The numbers** (``PUBLISHED``, each with where it is from; the report prints them). The film's mass comes
from the metagrating's geometry: a substrate t_s = 0.2 µm with resonator bars h_r = 0.4 µm high, widths
w₁ + w₂ in a period Λ, so the areal density is χ = ρ(t_s + h_r (w₁ + w₂)/Λ) per region; the TE-type regions
cover 1/3 of the disc (two 60° sectors about ±x), the TM-type the rest. The sheet carries the area-mean χ as
one film of equivalent thickness h = χ̄/ρ; its membrane stiffness E h is then FlexSailSim's (its springs,
Van Gelder's triangle springs, have ν = 0, as the sheet's). The optics of the metagrating are pressure
tables over the two incidence angles; at normal incidence they give the normal pressure c_n I/c with
c_n = 0.719 (TE) and 0.235 (TM), and in-plane pressures of 0.15 I/c that point in opposite directions on
opposite sectors (the metagrating's restoring force). The sheet has the specular facet law
(I/c) cos θ [2R cos θ n + α ẑ], so the film carries the area mean c̄_n = 2R + α (R = (c̄_n − α)/2, α the
film's absorptance 1 − exp(−4πκt/λ)): the same thrust, a specular angle law. Their optics — each sector's
normal and in-plane pressures and their angle dependence — are the grating term's sectors on top of that film
(paper.flexsail_grating: their tables' fit, checked by our RCWA of their bars; the runs named "grating").

**The runs** (``RUNS``): the disc in polar tiles (model.sheet_planforms.disc) at 17 and 49 tiles, bending on
(D = E h³/12 of the equivalent film) and nearly off (E × 1e-6 in the bending springs, E_m unchanged: D ×
1e-6), in-house solver (in the frame turning with the spin, its default for a spinning sheet), over the
published 5 s at 17 tiles (also at rtol 1e-3 and 1e-5: the tolerance's effect on the path and the spin) and
over 1 s at 49 (the verdict is reached within it); 97 tiles over 0.5 s (cost and a third mesh); Exudyn on
the 17-tile disc over the 5 s, over 0.5 s, at half its step over 0.1 s, and on 49 and 97 tiles over 0.1 and
0.05 s, each against the in-house run's samples of the same span.
Every run is saved (histories and CPU time) as it finishes and is read back rather than rerun
(``OUT/data/flexsail_NAME.npz``), so a cut-off session loses at most the run in progress.

**The rigid prediction** (analysis.ride3d_criterion, the rigid billowed disc without payload): a flat disc is
the limit R_c → ∞ of the cap; its growth rates at R_c = 1e3 and 1e4 m agree to 0.1 %, at rest and at 120 Hz.
Its linear equations of motion, integrated from the runs' start, are set beside the runs (rigid_path).
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np

from lightsail_mbs.analysis.ride3d import sheet_ride
from lightsail_mbs.analysis.ride3d_criterion import cap_criterion
from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.paper import flexsail_grating
from lightsail_mbs.solvers import contract
from lightsail_mbs.studies.tables import markdown_table

CODE = "github.com/Starshot-Lightsail/FlexSailSim, Code for manuscript/Fig6/"
MAIN = CODE + "simulate_flex_5s_Fig6_1e_RK4_v20_052323_RG.m"
AUX = CODE + "Scripts/Auxiliary/"
MATERIALS = AUX + "setupMaterialProperties_v19_final2_RG.m"
TABLES = CODE + "Data/08232021_MEPS_Si3N4_Mark1e_1064_PitchRoll_Pressures_CollectionTables_TE/TM.mat, row (0°, 0°)"
MESH = AUX + "generateMesh_v20_RK4_RG.m"
PAPER = "Gao, Kelzenberg & Atwater, Nat. Commun. 2024, Fig. 6"

# (name, value, unit, source, estimated): the numbers of the published case
PUBLISHED = [
    ("diameter D", 1.0, "m", f"{PAPER}; radiusmm = 500 in {MESH}", False),
    ("spin", 120.0, "Hz", f"{PAPER}; spin_frequency in {MAIN}", False),
    ("peak intensity I₀", 1e9, "W/m²", f"I0 = 1000 W/mm² in {MAIN}", False),
    ("beam width w (I₀e^(−2r²/w²))", 0.4, "D", f"beam_width; Irad = 0.4√2 R in I₀e^(−r²/Irad²), {MAIN}", False),
    ("offset in x and in y", 0.1, "R", f"t0t_x0 = t0t_y0 = 0.1 radiusmm in {MAIN}", False),
    ("tilt about x and about y", -2.0, "°", f"t0t_t0_x = t0t_t0_y = deg2rad(−2) in {MAIN}", False),
    ("beam on", 5.01, "s", f"t_on_dur in {MAIN}", False),
    ("Young's modulus E (Si₃N₄)", 270e9, "Pa", f"Ymod_Si3N4 in {MATERIALS}", False),
    ("density ρ (Si₃N₄)", 2700.0, "kg/m³", f"rho_Si3N4 in {MATERIALS}", False),
    ("Poisson ratio (theirs; springs of ν = 0 in both codes)", 0.27, "", f"nu_Si3N4 in {MATERIALS}", False),
    ("substrate t_s / bar height h_r", 0.2, "µm", f"t_TE, h_TE = 0.4 µm in {MATERIALS}", False),
    ("TE bars w₁ + w₂ / period", 0.8 / 1.6, "", f"w1_TE, w2_TE, dUC_TE in {MATERIALS}", False),
    ("TM bars w₁ + w₂ / period", 0.72 / 1.35, "", f"w1_TM, w2_TM, dUC_TM in {MATERIALS}", False),
    ("TE share of the disc", 1.0 / 3.0, "", f"pizza_angles 0/30/150/210/330°, TE-TM-TE-TM-TE, {MESH}", False),
    ("normal pressure, TE region", 0.71935, "I/c", TABLES, False),
    ("normal pressure, TM region", 0.23503, "I/c", TABLES, False),
    ("in-plane pressure, TE / TM region", 0.1521, "I/c", TABLES + " (TM: 0.1423); the grating term", False),
    ("Si₃N₄ extinction κ at λ = 1064 nm", 2e-6, "", f"k_Si3N4 and Iabs_Si3N4 in {MATERIALS}", False),
    ("payload", 0.0, "kg", f"usetether = 0 in {MESH}", False),
    ("damping", 0.0, "", f"none in {AUX}core_simulate_v1.m; the sheet damps its membrane springs", True),
    ("bending stiffness", 0.0, "N m", "spring mesh (edges only); the sheet: E h³/12 of the equivalent film", True),
    ("mesh", 5400, "triangles", f"radialRings = 30 (2791 nodes) in {MESH}", False),
]
WAVELENGTH = 1064e-9
T_FINAL = 5.0
OUTPUT_INTERVAL = 2.5e-3
RTOL = 1e-4  # the in-house solver's relative tolerance (the report checks it against 1e-5)
STEP = 2.5e-5  # s: Exudyn's step (1/333 of a turn at 120 Hz; the report checks it against half of it)
BENDING_OFF = 1e-6  # factor on E in the bending springs for "bending (nearly) off"


def published(name: str) -> float:
    """The value of one PUBLISHED entry by its name."""
    return next(row[1] for row in PUBLISHED if row[0] == name)


def film() -> dict:
    """The equivalent film of the metagrating (module docstring): areal densities χ (kg/m²), thickness h (m),
    mass (kg), absorptance α, mean normal pressure c̄_n and the sheet's reflectivity R = (c̄_n − α)/2."""
    rho, share = published("density ρ (Si₃N₄)"), published("TE share of the disc")
    t_s, h_r = 0.2e-6, 0.4e-6
    chi = {
        "TE": rho * (t_s + h_r * published("TE bars w₁ + w₂ / period")),
        "TM": rho * (t_s + h_r * published("TM bars w₁ + w₂ / period")),
    }
    kappa = published("Si₃N₄ extinction κ at λ = 1064 nm")
    absorb = {k: 1.0 - math.exp(-4 * math.pi * kappa * (v / rho) / WAVELENGTH) for k, v in chi.items()}
    c_n = {"TE": published("normal pressure, TE region"), "TM": published("normal pressure, TM region")}

    def mean(d):
        return share * d["TE"] + (1 - share) * d["TM"]

    areal, alpha, cn = mean(chi), mean(absorb), mean(c_n)
    D = published("diameter D")
    return dict(
        areal_density=areal,
        thickness=areal / rho,
        mass=areal * math.pi * D * D / 4,
        absorptivity=alpha,
        normal_pressure=cn,
        reflectivity=0.5 * (cn - alpha),
    )


def case(n: int = 5, ny: int = 8, bending: bool = True, grating: str | None = None) -> SailParameters:
    """The published case on the disc of n tiles across and ny sectors; bending off: D × BENDING_OFF; `grating`:
    a layout file of their metagrating's pressures (paper.flexsail_grating), else the specular film alone.

    Poses: the sail sits 0.1 R off the beam axis in +x and +y (so the beam is at L/2 − 0.1 R); FlexSailSim
    turns its nodes by R_y(θ)R_x(φ) with θ = φ = −2° (direction cosine matrix 1-2-3, right-handed, the beam
    along +z), which is the sheet's Q = R_y(−α_x)R_x(α_y) with α_x = +2°, α_y = −2° (model.sheet_pose)."""
    f = film()
    D = published("diameter D")
    E = published("Young's modulus E (Si₃N₄)")
    offset = published("offset in x and in y") * D / 2
    tilt = math.radians(published("tilt about x and about y"))
    return SailParameters(
        model="sheet",
        planform="disc",
        n=n,
        ny=ny,
        length=D,
        width=D,
        thickness=f["thickness"],
        density=published("density ρ (Si₃N₄)"),
        youngs_modulus=E * (1.0 if bending else BENDING_OFF),
        membrane_modulus=E,
        intensity=published("peak intensity I₀"),
        reflectivity=f["reflectivity"],
        absorptivity=f["absorptivity"],
        defect_amplitude=0.0,
        beam_waist=published("beam width w (I₀e^(−2r²/w²))") * D,
        beam_centre=D / 2 - offset,
        beam_centre_y=D / 2 - offset,
        initial_tilt=-tilt,
        initial_tilt_y=tilt,
        spin_rate=2 * math.pi * published("spin"),
        grating=grating,
    )


def rigid_criterion(spin: float | None = None, radius: float = 1e4):
    """The rigid criterion of the case's disc on a cap of radius R_c (flat: R_c → ∞), without payload. The
    criterion's disc is a mirror (2I/c per unit lit area); the sheet's film has every radiation force
    (2R + α)/2 = c̄_n/2 of that (its α term, along the beam rather than the normal, is 1e-5 of it), so the
    criterion runs at the intensity c̄_n I₀/2."""
    p = case()
    p = p.replace(billow_radius=radius, intensity=p.intensity * film()["normal_pressure"] / 2)
    return cap_criterion(p, 0.0, 0.0, spin)


def rigid_prediction() -> list[dict]:
    """The rigid criterion's growth rates of the flat disc (R_c = 1e3 and 1e4 m), at rest and spinning."""
    rows = []
    for spin in (0.0, case().spin_rate):
        rates = [rigid_criterion(spin, R) for R in (1e3, 1e4)]
        slow = rates[1].roots[np.argmax(rates[1].roots.real)]
        rows.append(
            {
                "Ω (rad/s)": f"{spin:.1f}",
                "growth rate at R_c = 1e3 / 1e4 m (1/s)": f"{rates[0].growth_rate:.4g} / {rates[1].growth_rate:.4g}",
                "its frequency (rad/s)": f"{abs(slow.imag):.3g}",
                "e-folding time (s)": f"{1 / rates[1].growth_rate:.3g}",
                "prediction": "rides" if rates[1].stable else "drifts out",
            }
        )
    return rows


def rigid_path(lateral: np.ndarray, tilt: np.ndarray, times: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The rigid criterion's linear motion (analysis.ride3d_criterion, "Motion") of the spinning flat disc
    from the centre of mass at `lateral` (X, Y) with the tilt (α_x, α_y), neither moving (the disc spins about
    its own normal), at `times`: (T, 2) lateral positions and (T, 2) tilts."""
    from scipy.integrate import solve_ivp

    c = rigid_criterion()
    gyro, stiff = c.axial_inertia * c.spin_rate, c.k * c.D * c.D + c.D * (c.edge_force - c.axial_force)

    def rhs(t, y):
        u, du, b, db = y[0:2] @ (1, 1j), y[2:4] @ (1, 1j), y[4:6] @ (1, 1j), y[6:8] @ (1, 1j)
        ddu = (-c.k * u - (c.k * c.D + c.edge_force) * b) / c.mass
        ddb = (1j * gyro * db - c.k * c.D * u - stiff * b) / c.transverse_inertia
        return [v for z in (du, ddu, db, ddb) for v in (z.real, z.imag)]

    y0 = [lateral[0], lateral[1], 0.0, 0.0, tilt[0], tilt[1], 0.0, 0.0]
    sol = solve_ivp(rhs, (0.0, float(times[-1])), y0, t_eval=times, rtol=1e-10, atol=1e-14)
    return sol.y[0:2].T, sol.y[4:6].T


def rigid_rows(runs: dict, times=(0.05, 0.1, 0.15, 0.2)) -> list[dict]:
    """The runs against the rigid linear motion from their common start, at `times`."""
    first = next(iter(runs.values()))
    lateral, tilt = rigid_path(first["lateral"][0], first["tilt"][0], np.asarray(times))
    rows = []
    for k, t in enumerate(times):
        row = {"t (s)": f"{t:g}", "rigid X, Y (m); α_x, α_y (°)": _pose(lateral[k], tilt[k])}
        for name, r in runs.items():
            if name in RIGID_COMPARED and r["time"][-1] >= t - 1e-9:
                i = int(np.argmin(np.abs(r["time"] - t)))
                row[name] = _pose(r["lateral"][i], r["tilt"][i])
        rows.append(row)
    return rows


def _pose(lateral, tilt) -> str:
    degrees = np.degrees(tilt)
    return f"{lateral[0]:+.4f}, {lateral[1]:+.4f}; {degrees[0]:+.3f}, {degrees[1]:+.3f}"


# name: (n, ny, bending, solver, t_final, solver options)
RUNS = {
    "17 tiles": (5, 8, True, "reduced", T_FINAL, {"rtol": RTOL}),
    "17 tiles, bending off": (5, 8, False, "reduced", T_FINAL, {"rtol": RTOL}),
    "49 tiles": (9, 12, True, "reduced", 1.0, {"rtol": RTOL}),
    "49 tiles, bending off": (9, 12, False, "reduced", 1.0, {"rtol": RTOL}),
    "97 tiles": (13, 16, True, "reduced", 0.5, {"rtol": RTOL}),
    "17 tiles, rtol 1e-5": (5, 8, True, "reduced", T_FINAL, {"rtol": 0.1 * RTOL}),
    "17 tiles, rtol 1e-3": (5, 8, True, "reduced", T_FINAL, {"rtol": 10 * RTOL}),
    "17 tiles, Exudyn": (5, 8, True, "exudyn", 0.5, {"step_size": STEP}),
    "17 tiles, Exudyn, 5 s": (5, 8, True, "exudyn", T_FINAL, {"step_size": STEP}),
    "17 tiles, Exudyn, half step": (5, 8, True, "exudyn", 0.1, {"step_size": 0.5 * STEP}),
    "49 tiles, Exudyn": (9, 12, True, "exudyn", 0.1, {"step_size": STEP}),
    "97 tiles, Exudyn": (13, 16, True, "exudyn", 0.05, {"step_size": STEP}),
}
RUNS.update(flexsail_grating.RUNS)  # with their metagrating's pressures (the grating term's sectors)
RIGID_COMPARED = ("17 tiles", "49 tiles", "97 tiles")  # the runs the report sets beside the rigid motion
HISTORIES = ("time", "lateral", "tilt", "spin_rate", "amplitude", "deformation")


def run(name: str, out: Path, spec: tuple | None = None, log=print) -> dict:
    """One of RUNS (or the given spec): read from out/data/flexsail_NAME.npz if saved, else run and save it. Returns
    the histories, the verdict (analysis.ride3d: drifts out at one waist, crumples at 1 cm) and the CPU time."""
    path = out / "data" / ("flexsail_" + name.replace(" ", "_").replace(",", "") + ".npz")
    if path.exists():
        with np.load(path) as data:
            return {k: (data[k].item() if data[k].ndim == 0 else data[k]) for k in data.files}
    n, ny, bending, solver, t_final, options, *variant = spec or RUNS[name]
    layout = flexsail_grating.layout(out / "data", variant[0], film()["normal_pressure"]) if variant else None
    p = case(n, ny, bending, layout)
    log(f"{time.strftime('%H:%M:%S')} {name}: {solver}, {n} × {ny}, bending {bending}, {t_final} s, {options}")
    settings = RunSettings(t_final=t_final, output_interval=OUTPUT_INTERVAL, stop_at_failure=False)
    start = time.process_time()
    engine = contract.lookup(solver, p)  # one run: no twins, no reruns that locate a failure (a₀ = 0)
    engine.check_options(options)
    result = engine.run(p, settings, progress=True, **options)
    cpu = time.process_time() - start
    ride = sheet_ride(result)
    record = {k: np.asarray(getattr(ride, k), float) for k in HISTORIES}
    record.update(
        tiles=len(result.tile_centres[0]),
        cpu=cpu,
        t_final=t_final,
        verdict=ride.verdict,
        error=str(result.error or ""),
        decided_at=np.nan if ride.decided_at is None else ride.decided_at,
        steps=float(result.info.get("steps", np.nan)),
    )
    path.parent.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(path, **record)
    log(f"{time.strftime('%H:%M:%S')} {name}: {ride.verdict}, CPU {cpu:.0f} s, saved {path}")
    return record


def run_rows(runs: dict) -> list[dict]:
    """One row per run: verdict, when, the craft's distance from the axis, tilt, spin and shape, CPU."""
    rows = []
    for name, r in runs.items():
        distance = np.hypot(r["lateral"][:, 0], r["lateral"][:, 1])
        tilt = np.hypot(r["tilt"][:, 0], r["tilt"][:, 1])
        when, reached, error = r["decided_at"], r["time"][-1], str(r.get("error", "")) or "no error recorded"
        rows.append(
            {
                "run": name,
                "tiles": int(r["tiles"]),
                "span (s)": f"{reached:g}"
                + ("" if reached >= r["t_final"] - 1e-9 else f" of {r['t_final']:g}: {error}"),
                "verdict": r["verdict"] + ("" if np.isnan(when) else f" at {when:.3f} s"),
                "distance at 0.1 / 0.2 s / end (m)": " / ".join(f"{v:.4g}" for v in _at(r, distance, (0.1, 0.2))),
                "tilt at 0.1 / 0.2 s / end (°)": " / ".join(f"{math.degrees(v):.3g}" for v in _at(r, tilt, (0.1, 0.2))),
                "beyond 2.5 R (FlexSailSim's stop) at (s)": _first(r["time"], distance >= 2.5 * 0.5),
                "spin at end (Hz)": f"{r['spin_rate'][-1] / (2 * math.pi):.4g}",
                "largest shape amplitude / deformation (mm)": f"{1e3 * r['amplitude'].max():.3g} / "
                f"{1e3 * r['deformation'].max():.3g}",
                "CPU (s) per simulated s": f"{r['cpu']:.0f} / {r['cpu'] / reached:.0f}",
            }
        )
    return rows


def _first(time_: np.ndarray, reached: np.ndarray) -> str:
    """The first time at which `reached` holds, or "—"."""
    k = np.flatnonzero(reached)
    return f"{time_[k[0]]:.3f}" if k.size else "—"


def _at(r: dict, values: np.ndarray, times) -> list[float]:
    """values at the samples nearest the given times (those within the run), then the last."""
    t = r["time"]
    return [values[int(np.argmin(np.abs(t - s)))] for s in times if s <= t[-1]] + [values[-1]]


def compare(a: dict, b: dict, span: float) -> dict:
    """Largest differences of two runs' histories over their common samples up to `span`: lateral position
    and shape amplitude (m), tilt (rad), spin rate (relative), each also relative to a's own largest."""
    ta, tb = a["time"], b["time"]
    common = np.intersect1d(np.round(ta[ta <= span + 1e-12], 9), np.round(tb[tb <= span + 1e-12], 9))
    ia = np.searchsorted(np.round(ta, 9), common)
    ib = np.searchsorted(np.round(tb, 9), common)
    out = {}
    for key in ("lateral", "tilt", "amplitude"):
        x, y = a[key][ia], b[key][ib]
        diff = float(np.max(np.abs(x - y)))
        out[key] = (diff, diff / float(np.max(np.abs(x))))
    spin = float(np.max(np.abs(a["spin_rate"][ia] - b["spin_rate"][ib]) / np.abs(a["spin_rate"][ia])))
    out["spin_rate"] = (spin, spin)
    out["samples"] = len(common)
    return out


SPECULAR_PAIRS = [  # the pairs that test the answer: (a, b, what), b compared against a
    ("49 tiles", "17 tiles", "mesh: 17 against 49 tiles"),
    ("97 tiles", "49 tiles", "mesh: 49 against 97 tiles"),
    ("17 tiles, rtol 1e-5", "17 tiles", "tolerance: rtol 1e-4 against 1e-5"),
    ("17 tiles", "17 tiles, rtol 1e-3", "tolerance: rtol 1e-3 against 1e-4"),
    ("17 tiles, Exudyn, 5 s", "17 tiles", "in-house against Exudyn, 17 tiles, as far as both go"),
    ("17 tiles", "17 tiles, bending off", "bending off against on, 17 tiles"),
    ("49 tiles", "49 tiles, bending off", "bending off against on, 49 tiles"),
    ("17 tiles", "17 tiles, Exudyn", "Exudyn against in-house, 17 tiles"),
    ("17 tiles, Exudyn", "17 tiles, Exudyn, half step", "Exudyn: step 2.5e-5 s against 1.25e-5 s"),
    ("49 tiles", "49 tiles, Exudyn", "Exudyn against in-house, 49 tiles"),
    ("97 tiles", "97 tiles, Exudyn", "Exudyn against in-house, 97 tiles"),
]


def grating_pairs() -> list[tuple]:
    """The grating runs' pairs: those of the specular film's that flexsail_grating.SHARED_PAIRS names, on the
    grating runs of the same mesh and options, then flexsail_grating.EXTRA_PAIRS."""

    def grated(name: str) -> str:
        return name.replace(" tiles", " tiles, grating", 1)

    shared = [(grated(a), grated(b), what) for a, b, what in SPECULAR_PAIRS if what in flexsail_grating.SHARED_PAIRS]
    return shared + flexsail_grating.EXTRA_PAIRS


def convergence_rows(runs: dict, pairs=None) -> list[dict]:
    """The pairs that test the answer (SPECULAR_PAIRS unless `pairs` is given): mesh, tolerance, bending, Exudyn."""
    pairs = pairs or SPECULAR_PAIRS
    rows = []
    for a, b, what, *upto in pairs:  # a pair may give the span it is compared over
        if a not in runs or b not in runs:
            continue
        span = min(runs[a]["time"][-1], runs[b]["time"][-1], *upto)
        c = compare(runs[a], runs[b], span)
        rows.append(
            {
                "comparison": what,
                "span (s), samples": f"{span:g}, {c['samples']}",
                "lateral (m; of its largest)": f"{c['lateral'][0]:.2g} ({c['lateral'][1]:.2g})",
                "tilt (rad; of its largest)": f"{c['tilt'][0]:.2g} ({c['tilt'][1]:.2g})",
                "spin rate (relative)": f"{c['spin_rate'][0]:.2g}",
                "shape amplitude (m; of its largest)": f"{c['amplitude'][0]:.2g} ({c['amplitude'][1]:.2g})",
            }
        )
    return rows


def write(out, quick: bool = False, names=None) -> Path:
    """Run (or read back) RUNS, or only `names`, and write flexsail.md into `out` with the published numbers,
    the equivalent film, the rigid prediction, the runs and their comparisons; quick: 5 ms spans (smoke test)."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    logfile = out / "data" / "flexsail.log"
    logfile.parent.mkdir(parents=True, exist_ok=True)

    def log(line):
        print(line, flush=True)
        with logfile.open("a") as f:
            f.write(line + "\n")

    runs = {}
    for name in names or RUNS:
        n, ny, bending, solver, t_final, *rest = RUNS[name]
        spec = (n, ny, bending, solver, min(t_final, 0.005), *rest) if quick else None
        runs[name] = run(name, out / "quick" if quick else out, spec, log)
    f = film()
    film_rows = [{"quantity": k.replace("_", " "), "value": f"{v:.5g}"} for k, v in f.items()]
    published_rows = [
        {"quantity": q, "value": f"{v:g}", "unit": u, "from": s, "estimated": "yes" if e else ""}
        for q, v, u, s, e in PUBLISHED
    ]
    text = "\n\n".join(
        [
            "# FlexSailSim's published case re-posed with bending",
            "Made by `nice -n 10 python scenarios/flexsail.py --out validation` (lightsail_mbs.paper.flexsail; "
            "runs saved as validation/data/flexsail_*.npz and read back).",
            "## The published numbers",
            markdown_table(published_rows),
            "## The equivalent film (SI units)",
            markdown_table(film_rows),
            "## The rigid criterion for the flat disc (no payload)",
            markdown_table(rigid_prediction()),
            "## The runs against the rigid linear motion from the same start",
            markdown_table(rigid_rows(runs)),
            "## The runs",
            markdown_table(run_rows({k: v for k, v in runs.items() if k not in flexsail_grating.RUNS})),
            "## Convergence, bending and the two solvers (largest differences over the common samples)",
            markdown_table(convergence_rows(runs)),
            "## Their metagrating's pressures: our RCWA of their bars against their tables (paper.flexsail_grating)",
            markdown_table(flexsail_grating.rcwa_rows()),
            "## The runs with their metagrating's pressures (the grating term's sectors; wide: their tables' ±6° law "
            "of degree 8, else the ±3° quadratic)",
            markdown_table(flexsail_grating.ride_rows({k: v for k, v in runs.items() if k in flexsail_grating.RUNS})),
            markdown_table(flexsail_grating.envelope_rows(runs)),
            "## Their pressures: convergence, bending, the two solvers and the angle dependence",
            markdown_table(convergence_rows(runs, grating_pairs())),
        ]
    )
    path = out / ("flexsail_quick.md" if quick else "flexsail.md")
    path.write_text(text + "\n")
    return path
