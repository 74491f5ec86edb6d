"""FlexSailSim's metagrating optics on the sheet: the in-plane and normal pressures of its TE and TM regions near
normal incidence and over ±6°, as the grating term's sectors (model/sheet_grating.py; docs: spinning-beam,
"FlexSailSim's case").

**Their tables** (github.com/Starshot-Lightsail/FlexSailSim, Code for manuscript/Fig6/Data/08232021_MEPS_Si3N4_
Mark1e_1064_PitchRoll_Pressures_CollectionTables_TE.mat and …_TM.mat, which their Fig. 6 run reads): rows (roll,
pitch, p_x, p_z) on a 0.1° grid within ±9° (0.2° to ±15°, 1° to ±25°), pressures per unit projected area divided by c
(their core_simulate_v1.m multiplies by c and by cos(pitch) cos(roll) A I/c). p_x is the in-plane pressure across
the grating lines (their TE regions push along ±x, TM along ±y, opposite on opposite sectors), p_z the normal
one. The TE table varies with pitch, the TM table with roll: each with the tilt in the plane of the normal and
its grating vector, the transverse tilt of the grating.

**The fits** (:func:`fit`, when the files are at hand; the tests hold the committed numbers to a refit when the
files are present), least squares, even in u₂ as the tables are: ``COEFFICIENTS``, quadratics in (u₁, u₂) = (sine
of the transverse tilt, sine of the other) over |angles| ≤ FIT_WINDOW (3°), residuals ≤ 0.0054 I/c; ``WIDE``,
polynomials of degree WIDE_DEGREE (8) over ±WIDE_WINDOW (6°) in the exact direction cosines their simulation reads
the tables with (:func:`table_rows`), residuals ≤ 0.0018 I/c. Beyond ±3° the quadratics miss the TM region's
resonance at 6.5–7.5° of lean (by 0.05 I/c at 5°, 0.15 at 6°); beyond ±6° the degree-8 law diverges. The normal
pressure enters the grating term as its excess over the film's specular law (paper.flexsail.film: c̄_n the area
mean at normal incidence, (2R + α) cos θ = c̄_n (1 − u₁² − u₂²)^½ to the law's degree, :func:`film_law`), so each
sector's normal pressure is its table's.

**The sign of the transverse tilt, from our RCWA.** The tables' own frame (their normal pressure is negative: their
COMSOL frame is flipped against the simulation's) leaves open whether a positive tabulated angle tilts the incident
light towards the in-plane pressure's direction or away from it. Our RCWA (model/rcwa.py, meent) of their bars —
Si₃N₄ of n = 2 + 2e-6i (n_Si3N4, k_Si3N4 in their setupMaterialProperties_v19_final2_RG.m), a 0.2 µm substrate under
0.4 µm bars facing the laser, w₁ = 0.6 and w₂ = 0.2 µm in 1.6 µm (TE), 0.52 and 0.2 µm in 1.35 µm (TM), the gap
between the bars (which their files do not give) ``GAPS``, chosen as the one of a 0.02 µm scan that reproduces their
(0°, 0°) row, TE light in the TE table and TM in the TM table — reproduces their (0°, 0°) rows to 6e-4 and 2e-3, and
their tables across ±6° to 0.017 (TE) and 0.004 (TM, the resonance's shoulder included) when the tabulated angle is
read as our θ (TE) and as −θ (TM) (:func:`rcwa_rows`; read the other way, off by up to 0.16 and 0.08 within ±3°
already), where θ > 0 tilts the beam towards the in-plane pressure (model/rcwa.py: beam cos θ n̂ + sin θ t̂, the
pressure along +t̂). So ``TILT_SIGN``: u₁ = sin(pitch) in the TE table, −sin(roll) in the TM table; in both, the
in-plane pressure grows as the light leans towards its direction. The layouts are written for that reading
(``"tables"``: the quadratics; ``"wide"``: the ±6° law), for the values at normal incidence alone (``"flat"``: what
the angle dependence does) and for the slopes reversed (``"reversed"``). The in-plane pressures point outward on
every sector (the metagrating's restoring design: the brighter sector, nearer the beam's axis, pushes the sail
back).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.model import sheet_grating

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
WIDE_WINDOW, WIDE_DEGREE = 6.0, 8  # degrees, and the law's degree: the ±WIDE_WINDOW law (fit(…, exact=True))
# per region and pressure, the coefficients of u₁^a u₂^b with b even (graded order; those with b odd are 0), fitted
# over |roll|, |pitch| ≤ 6° (14641 rows each); the largest residuals 0.0005, 0.0018 (TE), 0.0010, 0.0009 (TM)
WIDE_TEXT = """
TE in-plane
0.1525763395 1.235238288 -2.75645001 -0.3020643802 76.51596872 -8.348906901 -235.3333894 90.95979831 1.513148789
-1519.204281 -668.3926876 31.73756449 29799.21292 -18881.0984 -908.7228879 -54.24068399 -135225.1171 89934.83138
-5779.649351 -426.7351035 -1229860.931 1036827.377 101110.8712 4240.767981 605.4754252
TE normal
0.7183363527 -2.590581502 17.04002842 -2.382762936 -107.832743 17.76361528 -738.4231406 114.1927125 2.126173738
11776.24986 -947.0412867 47.32964676 -57955.576 -2368.421206 -8482.081053 -70.10833429 -232281.7482 -56790.69087
10845.16287 398.286609 3658959.236 630706.5806 660170.859 6153.296475 2848.97075
TM in-plane
0.1422837597 -0.6075672658 1.70716482 0.1035877653 -55.60177655 -2.556333259 -115.7346576 120.0836715
2.088794029 920.0899771 676.8850427 63.49563692 53734.43528 -36644.62651 276.4593978 -32.74750588 -726156.7549
179286.3509 -28554.23464 1033.39053 -4783418.182 2643216.357 -169261.8561 12727.48786 -351.1034489
TM normal
0.2352432557 0.2129257715 0.2175834421 0.4294792084 10.82865334 -3.434564926 792.9863081 157.2459942 3.65830215
2682.723684 -720.2761539 -50.91412477 -141311.5763 -2199.8952 -4045.104679 45.43333129 21475.17588 18241.62779
19331.45681 -280.5562701 13627561.88 -3163048.926 625221.8452 -27160.42779 566.6895526
"""


def _wide() -> dict:
    """WIDE_TEXT as {region: (in-plane, normal)}, each the WIDE_DEGREE law's coefficients in graded order."""
    even = [b % 2 == 0 for _, b in sheet_grating.powers(WIDE_DEGREE)]
    out: dict = {}
    for block in WIDE_TEXT.split("T")[1:]:
        region, _, *numbers = ("T" + block).split()
        law = np.zeros(len(even))
        law[even] = np.array(numbers, float)
        out[region] = out.get(region, ()) + (tuple(float(v) for v in law),)
    return out


WIDE = _wide()
# the pizza (their generateMesh_v20_RK4_RG.m, pizza_angles 0/30/150/210/330°): (from, to, grating direction, region)
SECTORS = ((-30, 30, 0, "TE"), (30, 150, 90, "TM"), (150, 210, 180, "TE"), (210, 330, 270, "TM"))
VARIANTS = ("tables", "flat", "reversed", "wide")
TILT_SIGN = {"TE": 1.0, "TM": -1.0}  # u₁ = sign × sine of the tabulated transverse angle (our RCWA, docstring)
GAPS = {"TE": 0.18e-6, "TM": 0.20e-6}  # m: the gap between the two bars (inferred, docstring)
BARS = {"TE": (1.6e-6, 0.6e-6, 0.2e-6), "TM": (1.35e-6, 0.52e-6, 0.2e-6)}  # period, w₁, w₂ (m)
PUBLISHED_NORMAL_INCIDENCE = {"TE": (0.15211, 0.71935), "TM": (0.14230, 0.23503)}  # their (0°, 0°) rows


def table_rows(folder, region: str, window: float, exact: bool = False) -> tuple:
    """(u₁, u₂, c_g, |c_z|) of their table's rows (the .mat file in `folder`) with both angles within ±window
    (degrees): u₁ across the lines with the tabulated sign (TILT_SIGN applied later, :func:`region_laws`), u₂ along
    them. exact: (u₁, u₂) the beam's direction cosines as their simulation reads the tables (core_simulate_v1.m:
    pitch = asin of the component along their x, roll = atan2 of the other two, so the cosine along their y is
    sin(roll) cos(pitch)); else the sines of the tabulated angles (COEFFICIENTS, whose ±3° differ from the exact
    reading by a factor cos ≥ 0.9986 on one cosine)."""
    from scipy.io import loadmat

    name = Path(TABLES.format(region)).name
    data = loadmat(str(Path(folder) / name))[f"pressure_{region}_small_tables"]
    rows = np.concatenate([data[:, :, k] for k in range(data.shape[2])])
    rows = rows[np.any(rows != 0, axis=1)]
    roll, pitch = rows[:, 0], rows[:, 1]
    keep = (np.abs(roll) <= math.radians(window) + 1e-9) & (np.abs(pitch) <= math.radians(window) + 1e-9)
    roll, pitch, rows = roll[keep], pitch[keep], rows[keep]
    along_y = np.sin(roll) * (np.cos(pitch) if exact else 1.0)
    u1, u2 = (np.sin(pitch), along_y) if region == "TE" else (along_y, np.sin(pitch))
    return u1, u2, SPEED_OF_LIGHT * rows[:, 2], np.abs(SPEED_OF_LIGHT * rows[:, 3])


def fit(folder, window: float = FIT_WINDOW, degree: int = 2, exact: bool = False) -> dict:
    """Per region, (in-plane c_g, normal |c_z|) fitted to their two .mat files in `folder`: least squares over the
    rows with both angles within ±window (degrees, :func:`table_rows`), a polynomial of `degree` in (u₁, u₂)
    (model.sheet_grating's graded order), even in u₂ as the tables are (their rows at ± the angle along the lines
    agree to 1e-10 I/c)."""
    out = {}
    for region in ("TE", "TM"):
        u1, u2, *values = table_rows(folder, region, window, exact)
        scale = math.sin(math.radians(window))  # the fit in u/scale (each monomial ≤ 1 in the window)
        even = np.array([b % 2 == 0 for _, b in sheet_grating.powers(degree)])
        basis = sheet_grating.monomials(u1 / scale, u2 / scale, degree)[:, even]
        unscale = np.array([scale ** -(a + b) for a, b in sheet_grating.powers(degree)])
        laws = []
        for pressure in values:
            law = np.zeros(even.size)
            law[even] = np.linalg.lstsq(basis, pressure, rcond=None)[0]
            laws.append(tuple(float(v) for v in law * unscale))
        out[region] = tuple(laws)
    return out


def _flip_across(law) -> np.ndarray:
    """The law with u₁ → −u₁ (odd powers of u₁ change sign)."""
    law = np.asarray(law, float)
    return law * [(-1) ** a for a, _ in sheet_grating.powers(sheet_grating.degree_of(law.size))]


def region_laws(wide: bool = False) -> dict:
    """Per region: (in-plane c_g, normal c_z) against (u₁ = ĝ·b̂, u₂), the ±3° quadratic (COEFFICIENTS) or the
    ±WIDE_WINDOW law (WIDE), with TILT_SIGN applied."""
    table = WIDE if wide else COEFFICIENTS
    return {
        region: tuple(_flip_across(law) if TILT_SIGN[region] < 0 else np.array(law) for law in laws)
        for region, laws in table.items()
    }


def film_law(mean_normal: float, degree: int) -> np.ndarray:
    """The film's normal pressure per lit area c̄_n cos θ = c̄_n (1 − u₁² − u₂²)^½ to the given degree: the
    binomial series Σ_m C(½, m) (−1)^m (u₁² + u₂²)^m, each power multiplied out."""
    index = {pair: i for i, pair in enumerate(sheet_grating.powers(degree))}
    law = np.zeros(len(index))
    for m in range(degree // 2 + 1):
        series = math.prod(0.5 - k for k in range(m)) / math.factorial(m) * (-1) ** m
        for i in range(m + 1):
            law[index[(2 * i, 2 * (m - i))]] += mean_normal * series * math.comb(m, i)
    return law


def sector_laws(variant: str, mean_normal: float) -> dict:
    """Per region: (along, across, normal) of the grating term for a variant (VARIANTS), with the normal
    pressure less the film's c̄_n cos θ to the law's degree (:func:`film_law`)."""
    out = {}
    for region, laws in region_laws(wide=variant == "wide").items():
        if variant == "flat":
            laws = [np.r_[law[0], np.zeros(5)] for law in laws]
        elif variant == "reversed":
            laws = [_flip_across(law) for law in laws]
        film = film_law(mean_normal, sheet_grating.degree_of(len(laws[1])))
        out[region] = (laws[0], np.zeros(len(laws[0])), laws[1] - film)
    return out


RCWA_ANGLES = tuple(range(-6, 7))  # degrees: the transverse tilts of the report's table


def law_at(law, u1: float, u2: float = 0.0) -> float:
    """A law (graded coefficients, model.sheet_grating) at (u₁, u₂)."""
    law = np.asarray(law, float)
    return float(sheet_grating.monomials(u1, u2, sheet_grating.degree_of(law.size)) @ law)


def rcwa_rows(angles=RCWA_ANGLES) -> list[dict]:
    """Our RCWA of their bars (docstring) against their tables — the ±WIDE_WINDOW law (WIDE, their tables to
    ≤ 0.002; at 0° their published row) and the ±3° quadratic (COEFFICIENTS) carried beyond its window — across the
    transverse tilt θ (u₁ = sin θ): in-plane and normal pressure per unit lit area, c_t/cos θ and c_n/cos θ."""
    from lightsail_mbs.model.rcwa import Bar, Grating, Layer, force_coefficients, orders

    index = complex(2.0, 2e-6)
    wide, quadratic = region_laws(wide=True), region_laws()
    rows = []
    for region, (period, w1, w2) in BARS.items():
        gap = GAPS[region]
        bars = (Bar(0.0, w1 / period, index), Bar((w1 + gap) / period, (w1 + gap + w2) / period, index))
        grating = Grating(1.064e-6, period, (Layer(0.4e-6, 1.0, bars), Layer(0.2e-6, index)))
        for degrees in angles:
            theta = math.radians(degrees)
            c_n, c_t = force_coefficients(orders(grating, theta, region, harmonics=30))
            theirs = [law_at(law, math.sin(theta)) for law in wide[region]]
            if degrees == 0:
                theirs = list(PUBLISHED_NORMAL_INCIDENCE[region])
            fit3 = [law_at(law, math.sin(theta)) for law in quadratic[region]]
            ours = (c_t / math.cos(theta), c_n / math.cos(theta))
            rows.append(
                {
                    "region": region,
                    "θ (°)": degrees,
                    **{
                        f"{what}: our RCWA / their tables / the ±3° fit (I/c)": f"{a:.4f} / {b:.4f} / {c:.4f}"
                        for what, a, b, c in zip(("in-plane", "normal"), ours, theirs, fit3)
                    },
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
    "17 tiles, wide grating": (5, 8, True, "reduced", 5.0, {"rtol": 1e-4}, "wide"),
    "17 tiles, wide grating, Exudyn, 5 s": (5, 8, True, "exudyn", 5.0, {"step_size": 2.5e-5}, "wide"),
    "49 tiles, wide grating": (9, 12, True, "reduced", 1.0, {"rtol": 1e-4}, "wide"),
    "49 tiles, wide grating, Exudyn": (9, 12, True, "exudyn", 1.0, {"step_size": 2.5e-5}, "wide"),
    "17 tiles, wide grating, 15 s": (5, 8, True, "reduced", 15.0, {"rtol": 1e-4}, "wide"),
    "17 tiles, grating, 15 s": (5, 8, True, "reduced", 15.0, {"rtol": 1e-4}, "tables"),
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
    ("17 tiles, grating", "17 tiles, wide grating", "the ±6° law against the ±3° fit, 17 tiles, 5 s"),
    ("17 tiles, grating", "17 tiles, wide grating", "the ±6° law against the ±3° fit, 17 tiles, 1 s", 1.0),
    ("49 tiles, grating", "49 tiles, wide grating", "the ±6° law against the ±3° fit, 49 tiles, 1 s"),
    (
        "17 tiles, wide grating",
        "17 tiles, wide grating, Exudyn, 5 s",
        "±6° law: Exudyn against in-house, 17 tiles, 5 s",
    ),
    (
        "17 tiles, wide grating",
        "17 tiles, wide grating, Exudyn, 5 s",
        "±6° law: Exudyn against in-house, 17 tiles, 1 s",
        1.0,
    ),
    (
        "17 tiles, wide grating",
        "17 tiles, wide grating, Exudyn, 5 s",
        "±6° law: Exudyn against in-house, 17 tiles, 0.2 s",
        0.2,
    ),
    ("49 tiles, wide grating", "49 tiles, wide grating, Exudyn", "±6° law: Exudyn against in-house, 49 tiles, 1 s"),
    ("49 tiles, wide grating", "17 tiles, wide grating", "±6° law: mesh, 17 against 49 tiles, 1 s"),
]


ENVELOPED = ("17 tiles, grating, 15 s", "17 tiles, wide grating, 15 s", "17 tiles, wide grating, Exudyn, 5 s")


def envelope_rows(runs: dict, names=ENVELOPED) -> list[dict]:
    """Whether a ride stays bounded: per run (those of `names` at hand), the largest distance from the axis (mm)
    and tilt (°) within each second."""
    rows = []
    for name in (n for n in names if n in runs):
        r = runs[name]
        t = r["time"]
        distance = 1e3 * np.hypot(r["lateral"][:, 0], r["lateral"][:, 1])
        tilt = np.degrees(np.hypot(r["tilt"][:, 0], r["tilt"][:, 1]))
        seconds = [(t >= k) & (t <= k + 1) for k in range(int(round(t[-1])))]
        rows.append(
            {
                "run": name,
                "largest distance from the axis in each second (mm)": " ".join(
                    f"{distance[s].max():.0f}" for s in seconds
                ),
                "largest tilt in each second (°)": " ".join(f"{tilt[s].max():.1f}" for s in seconds),
            }
        )
    return rows


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
