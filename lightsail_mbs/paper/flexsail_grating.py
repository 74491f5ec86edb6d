"""FlexSailSim's metagrating optics on the sheet: the in-plane and normal pressures of its TE and TM regions near
normal incidence, as the grating term's sectors (model/sheet_grating.py; docs: spinning-beam, "FlexSailSim's case").

**Their tables** (github.com/Starshot-Lightsail/FlexSailSim, Code for manuscript/Fig6/Data/08232021_MEPS_Si3N4_
Mark1e_1064_PitchRoll_Pressures_CollectionTables_TE.mat and …_TM.mat, which their Fig. 6 run reads): rows (roll,
pitch, p_x, p_z) on a 0.1° grid within ±6° (coarser to ±25°), pressures per unit projected area divided by c
(their core_simulate_v1.m multiplies by c and by cos(pitch) cos(roll) A I/c). p_x is the in-plane pressure across
the grating lines (their TE regions push along ±x, TM along ±y, opposite on opposite sectors), p_z the normal
one. The TE table varies with pitch, the TM table with roll: each with the tilt in the plane of the normal and
its grating vector, the transverse tilt of the grating.

**The fit** (:func:`fit`, when the files are at hand): per table, quadratics in (u₁, u₂) = (sine of the transverse
tilt, sine of the other) over |angles| ≤ FIT_WINDOW, least squares; ``COEFFICIENTS`` holds the result (the test
holds it to a refit when the files are present). The normal pressure enters the grating term as its excess over
the film's specular law (paper.flexsail.film: c̄_n the area mean at normal incidence, (2R + α) cos θ ≈
c̄_n (1 − (u₁² + u₂²)/2)), so each sector's normal pressure is its table's.

**The sign of the transverse tilt, from our RCWA.** The tables' own frame (their normal pressure is negative: their
COMSOL frame is flipped against the simulation's) leaves open whether a positive tabulated angle tilts the incident
light towards the in-plane pressure's direction or away from it. Our RCWA (model/rcwa.py, meent) of their bars —
Si₃N₄ of n = 2 + 2e-6i (n_Si3N4, k_Si3N4 in their setupMaterialProperties_v19_final2_RG.m), a 0.2 µm substrate
under 0.4 µm bars facing the laser, w₁ = 0.6 and w₂ = 0.2 µm in 1.6 µm (TE), 0.52 and 0.2 µm in 1.35 µm (TM), the
gap between the bars (which their files do not give) ``GAPS``, chosen as the one of a 0.02 µm scan that reproduces
their (0°, 0°) row, TE light in the TE table and TM in the TM table — reproduces their (0°, 0°) rows to 6e-4 and
2e-3, and their tables' fit across ±3° to 0.012 when the tabulated angle is read as our θ (TE) and as −θ (TM)
(:func:`rcwa_rows`; read the other way, off by up to 0.16 and 0.08), where θ > 0 tilts the beam towards the
in-plane pressure (model/rcwa.py: beam cos θ n̂ + sin θ t̂, the pressure along +t̂). So ``TILT_SIGN``: u₁ =
sin(pitch) in the TE table, −sin(roll) in the TM table; in both, the in-plane pressure grows as the light leans
towards its direction. The
layouts are written for that reading (``"tables"``), for the values at normal incidence alone (``"flat"``: what the
angle dependence does) and for the slopes reversed (``"reversed"``). The in-plane pressures point outward on every
sector (the metagrating's restoring design: the brighter sector, nearer the beam's axis, pushes the sail back).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from lightsail_mbs.base.constants import SPEED_OF_LIGHT

FIT_WINDOW = 3.0  # degrees: the fit's range in both angles (the rides tilt the tiles by up to a few degrees)
TABLES = (
    "github.com/Starshot-Lightsail/FlexSailSim, Code for manuscript/Fig6/Data/"
    "08232021_MEPS_Si3N4_Mark1e_1064_PitchRoll_Pressures_CollectionTables_{}.mat"
)
# (region: in-plane p_x, normal |p_z|), each c₀, c₁, c₂, c₁₁, c₁₂, c₂₂ in (u₁ transverse, u₂ along the lines), fitted
# over |roll|, |pitch| ≤ 3° (3721 rows each); the largest residuals 0.0047, 0.0054 (TE), 0.0034, 0.0017 (TM)
COEFFICIENTS = {
    "TE": ((0.1527, 1.3515, 0.0, -3.1685, 0.0, -0.2411), (0.7188, -2.7222, 0.0, 15.1124, 0.0, -2.2885)),
    "TM": ((0.1422, -0.7041, 0.0, 1.7393, 0.0, 0.1615), (0.2348, 0.2357, 0.0, 1.6887, 0.0, 0.5578)),
}
# the pizza (their generateMesh_v20_RK4_RG.m, pizza_angles 0/30/150/210/330°): (from, to, grating direction, region)
SECTORS = ((-30, 30, 0, "TE"), (30, 150, 90, "TM"), (150, 210, 180, "TE"), (210, 330, 270, "TM"))
VARIANTS = ("tables", "flat", "reversed")
TILT_SIGN = {"TE": 1.0, "TM": -1.0}  # u₁ = sign × sine of the tabulated transverse angle (our RCWA, docstring)
GAPS = {"TE": 0.18e-6, "TM": 0.20e-6}  # m: the gap between the two bars (inferred, docstring)
BARS = {"TE": (1.6e-6, 0.6e-6, 0.2e-6), "TM": (1.35e-6, 0.52e-6, 0.2e-6)}  # period, w₁, w₂ (m)
PUBLISHED_NORMAL_INCIDENCE = {"TE": (0.15211, 0.71935), "TM": (0.14230, 0.23503)}  # their (0°, 0°) rows


def fit(folder) -> dict:
    """COEFFICIENTS refitted from their two .mat files in `folder` (module docstring)."""
    from scipy.io import loadmat

    out = {}
    for region in ("TE", "TM"):
        name = Path(TABLES.format(region)).name
        data = loadmat(str(Path(folder) / name))[f"pressure_{region}_small_tables"]
        rows = np.concatenate([data[:, :, k] for k in range(data.shape[2])])
        rows = rows[np.any(rows != 0, axis=1)]
        roll, pitch = rows[:, 0], rows[:, 1]
        across, along = (pitch, roll) if region == "TE" else (roll, pitch)
        keep = (np.abs(across) <= math.radians(FIT_WINDOW) + 1e-9) & (np.abs(along) <= math.radians(FIT_WINDOW) + 1e-9)
        u1, u2 = np.sin(across[keep]), np.sin(along[keep])
        basis = np.stack([np.ones_like(u1), u1, u2, u1 * u1, u1 * u2, u2 * u2], axis=1)
        laws = [np.linalg.lstsq(basis, SPEED_OF_LIGHT * rows[keep, 2], rcond=None)[0]]
        laws.append(np.linalg.lstsq(basis, np.abs(SPEED_OF_LIGHT * rows[keep, 3]), rcond=None)[0])
        out[region] = tuple(tuple(float(v) for v in law) for law in laws)
    return out


def region_laws() -> dict:
    """Per region: (in-plane c_g, normal c_z) against (u₁ = ĝ·b̂, u₂), the fit with TILT_SIGN applied."""
    flip = np.array([1, -1, 1, 1, -1, 1])  # u₁ → −u₁
    return {
        region: tuple(np.array(law) * (flip if TILT_SIGN[region] < 0 else 1) for law in laws)
        for region, laws in COEFFICIENTS.items()
    }


def sector_laws(variant: str, mean_normal: float) -> dict:
    """Per region: (along, across, normal) of the grating term for a variant (VARIANTS), with the normal
    pressure less the film's mean c̄_n cos θ to second order."""
    film = np.array([mean_normal, 0.0, 0.0, -0.5 * mean_normal, 0.0, -0.5 * mean_normal])
    out = {}
    for region, laws in region_laws().items():
        if variant == "flat":
            laws = [np.r_[law[0], np.zeros(5)] for law in laws]
        elif variant == "reversed":
            laws = [law * [1, -1, 1, 1, -1, 1] for law in laws]
        out[region] = (laws[0], np.zeros(6), laws[1] - film)
    return out


def rcwa_rows(angles=(-3, -2, -1, 0, 1, 2, 3)) -> list[dict]:
    """Our RCWA of their bars (docstring) against their tables (COEFFICIENTS, their fit; at 0° their published
    row), across the transverse tilt θ (u₁ = sin θ): in-plane and normal pressure per unit lit area, c_t/cos θ and
    c_n/cos θ."""
    from lightsail_mbs.model.rcwa import Bar, Grating, Layer, force_coefficients, orders

    index = complex(2.0, 2e-6)
    laws = region_laws()
    rows = []
    for region, (period, w1, w2) in BARS.items():
        gap = GAPS[region]
        bars = (Bar(0.0, w1 / period, index), Bar((w1 + gap) / period, (w1 + gap + w2) / period, index))
        grating = Grating(1.064e-6, period, (Layer(0.4e-6, 1.0, bars), Layer(0.2e-6, index)))
        for degrees in angles:
            theta = math.radians(degrees)
            c_n, c_t = force_coefficients(orders(grating, theta, region, harmonics=30))
            basis = np.array([1.0, math.sin(theta), 0.0, math.sin(theta) ** 2, 0.0, 0.0])
            theirs = [float(basis @ law) for law in laws[region]]
            if degrees == 0:
                theirs = list(PUBLISHED_NORMAL_INCIDENCE[region])
            rows.append(
                {
                    "region": region,
                    "θ (°)": degrees,
                    "in-plane: our RCWA / their tables (I/c)": f"{c_t / math.cos(theta):.4f} / {theirs[0]:.4f}",
                    "normal: our RCWA / their tables (I/c)": f"{c_n / math.cos(theta):.4f} / {theirs[1]:.4f}",
                }
            )
    return rows


def layout_text(variant: str, mean_normal: float) -> str:
    """The layout file (TOML) of the pizza for a variant (VARIANTS)."""
    laws = sector_laws(variant, mean_normal)
    lines = [f"# FlexSailSim's Mark 1e pizza, {variant}: written by lightsail_mbs.paper.flexsail_grating"]
    for start, end, direction, region in SECTORS:
        lines += ["[[sector]]", f"from = {start}", f"to = {end}", f"direction = {direction}"]
        for key, law in zip(("along", "across", "normal"), laws[region]):
            lines.append(f"{key} = [{', '.join(repr(float(v)) for v in law)}]")
    return "\n".join(lines) + "\n"


def layout(folder, variant: str, mean_normal: float) -> str:
    """The path of the layout file of a variant, written into `folder` (flexsail_grating_VARIANT.toml)."""
    path = Path(folder) / f"flexsail_grating_{variant}.toml"
    path.parent.mkdir(parents=True, exist_ok=True)
    text = layout_text(variant, mean_normal)
    if not path.exists() or path.read_text() != text:
        path.write_text(text)
    return str(path)


# name: (n, ny, bending, solver, t_final, solver options, variant): the case with their metagrating's pressures
RUNS = {
    "17 tiles, grating": (5, 8, True, "reduced", 5.0, {"rtol": 1e-4}, "tables"),
    "17 tiles, grating, bending off": (5, 8, False, "reduced", 5.0, {"rtol": 1e-4}, "tables"),
    "49 tiles, grating": (9, 12, True, "reduced", 1.0, {"rtol": 1e-4}, "tables"),
    "49 tiles, grating, bending off": (9, 12, False, "reduced", 1.0, {"rtol": 1e-4}, "tables"),
    "49 tiles, grating, 5 s": (9, 12, True, "reduced", 5.0, {"rtol": 1e-4}, "tables"),
    "97 tiles, grating": (13, 16, True, "reduced", 0.5, {"rtol": 1e-4}, "tables"),
    "17 tiles, grating, rtol 1e-5": (5, 8, True, "reduced", 5.0, {"rtol": 1e-5}, "tables"),
    "17 tiles, grating, Exudyn": (5, 8, True, "exudyn", 1.0, {"step_size": 2.5e-5}, "tables"),
    "17 tiles, grating, Exudyn, 5 s": (5, 8, True, "exudyn", 5.0, {"step_size": 2.5e-5}, "tables"),
    "17 tiles, grating, Exudyn, half step": (5, 8, True, "exudyn", 0.2, {"step_size": 1.25e-5}, "tables"),
    "49 tiles, grating, Exudyn": (9, 12, True, "exudyn", 1.0, {"step_size": 2.5e-5}, "tables"),
    "49 tiles, grating, Exudyn, 5 s": (9, 12, True, "exudyn", 5.0, {"step_size": 2.5e-5}, "tables"),
    "17 tiles, grating at normal incidence only": (5, 8, True, "reduced", 5.0, {"rtol": 1e-4}, "flat"),
    "17 tiles, grating slopes reversed": (5, 8, True, "reduced", 1.0, {"rtol": 1e-4}, "reversed"),
}
# the pairs that test the grating runs beside those of the specular film's (flexsail.grating_pairs): (a, b, what
# [, span]), b compared against a
SHARED_PAIRS = (
    "mesh: 17 against 49 tiles",
    "mesh: 49 against 97 tiles",
    "tolerance: rtol 1e-4 against 1e-5",
    "bending off against on, 17 tiles",
    "bending off against on, 49 tiles",
    "Exudyn against in-house, 17 tiles",
    "Exudyn: step 2.5e-5 s against 1.25e-5 s",
    "Exudyn against in-house, 49 tiles",
)
EXTRA_PAIRS = [
    ("17 tiles, grating", "17 tiles, grating, Exudyn, 5 s", "Exudyn against in-house, 17 tiles, 5 s"),
    ("17 tiles, grating", "17 tiles, grating, Exudyn", "Exudyn against in-house, 17 tiles, 0.2 s", 0.2),
    ("17 tiles, grating", "17 tiles, grating, Exudyn, half step", "Exudyn at half its step against in-house, 0.2 s"),
    ("49 tiles, grating, 5 s", "49 tiles, grating, Exudyn, 5 s", "Exudyn against in-house, 49 tiles, 5 s"),
    ("49 tiles, grating, 5 s", "17 tiles, grating", "mesh: 17 against 49 tiles, 5 s"),
    ("17 tiles, grating", "17 tiles, grating at normal incidence only", "the angle dependence: without it, 17 tiles"),
]


def ride_rows(runs: dict) -> list[dict]:
    """One row per grating run: the verdict, and whether the ride stays bounded — the largest distance from the
    axis and tilt over the first and over the last 0.5 s of the run — with the spin, the shape and the CPU time."""
    rows = []
    for name, r in runs.items():
        t, end = r["time"], r["time"][-1]
        distance = np.hypot(r["lateral"][:, 0], r["lateral"][:, 1])
        tilt = np.degrees(np.hypot(r["tilt"][:, 0], r["tilt"][:, 1]))
        first, last = t <= min(0.5, end), t >= end - min(0.5, end)
        when = r["decided_at"]
        rows.append(
            {
                "run": name,
                "span (s)": f"{end:g}" + ("" if end >= r["t_final"] - 1e-9 else f" of {r['t_final']:g}"),
                "verdict": r["verdict"] + ("" if np.isnan(when) else f" at {when:.3f} s"),
                "largest distance from the axis, first / last 0.5 s (m)": f"{distance[first].max():.4f} / "
                f"{distance[last].max():.4f}",
                "largest tilt, first / last 0.5 s (°)": f"{tilt[first].max():.2f} / {tilt[last].max():.2f}",
                "spin at end (Hz)": f"{r['spin_rate'][-1] / (2 * math.pi):.4g}",
                "largest shape amplitude (mm)": f"{1e3 * r['amplitude'].max():.3g}",
                "CPU (s) per simulated s": f"{r['cpu']:.0f} / {r['cpu'] / end:.0f}",
            }
        )
    return rows
