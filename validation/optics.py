"""Optics checks: `python validation/optics.py [--quick]`.

Writes validation/optics.md and optics_table.png: the force tables of the chosen grating (the Si
bigrating on silica, model/rcwa.GRATINGS) and of a symmetric grating, by RCWA (meent, 60 harmonics,
0.25° nodes on ±85°, breaks at the Rayleigh anomalies), and every check on them:

1. the mirror table against Eq. (11) (model/loads.py) at every tabulated angle, numpy and compiled;
2. zero index contrast against the independent thin-film formulas at every tabulated angle: the bar
   layer filled with silicon against Airy's film, the filled stack against the Abelès matrix, and an
   absorbing film against Airy (the sign convention of absorption);
3. energy conservation of the lossless gratings at every tabulated angle (ΣR + ΣT = 1);
4. the symmetric grating's c_t(−θ) = −c_t(θ) and c_n(−θ) = c_n(θ) at every node (exactly symmetric nodes);
5. RCWA convergence in the number of harmonics, against 200;
6. meent against grcwa (same geometry, 40 harmonics);
7. the table's interpolation error, against RCWA at interval midpoints;
8. the cost of evaluating a table (CPU time, minimum of repeats).

--quick: 20 harmonics, 2° nodes, no convergence and backend tables (a smoke run; its report says so).
RCWA runs on one BLAS thread (model/rcwa.py sets it); tables are cached (model/optics.cache_directory).
"""

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

from lightsail_mbs.model import optics, rcwa
from lightsail_mbs.model.loads import radiation_forces
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.viz.plots import new_figure, save_figure

OUT = Path(__file__).resolve().parent
DEG = math.pi / 180


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def mirror_check(theta):
    p = SailParameters(n=len(theta), intensity=1e9)
    x = np.linspace(0, 1, theta.size)
    a = optics.mirror().forces(p, x, theta)
    b = radiation_forces(p, x, theta)
    rel = np.hypot(a[0] - b[0], a[1] - b[1]) / np.hypot(b[0], b[1])
    packed = optics.mirror().packed()
    scale = p.intensity * p.slice_length * p.width / optics.SPEED_OF_LIGHT
    k = np.array([optics.packed_force(packed, scale, t, False) for t in theta])
    rel_k = np.hypot(k[:, 0] - b[0], k[:, 1] - b[1]) / np.hypot(b[0], b[1])
    return float(rel.max()), float(rel_k.max())


def zero_contrast(g, theta, harmonics):
    """max |ΔR|, |ΔT| of three zero-contrast structures against the thin-film formulas, every angle."""
    bar = g.layers[0]
    lossy = 3.48 + 0.05j
    cases = [
        (
            "bar layer filled with Si (n = 3.48), alone",
            "Airy (one film)",
            rcwa.Grating(g.wavelength, g.period, (g.filled(rcwa.N_SI).layers[0],)),
            lambda th, p: rcwa.airy_rt(rcwa.N_SI, bar.thickness, g.wavelength, th, p),
        ),
        (
            "whole stack, bar layer filled with Si",
            "Abelès matrix (two films)",
            g.filled(rcwa.N_SI),
            lambda th, p: rcwa.abeles_rt(
                [rcwa.N_SI, rcwa.N_SIO2], [layer.thickness for layer in g.layers], g.wavelength, th, p
            ),
        ),
        (
            "absorbing film n = 3.48 + 0.05i patterned with bars of its own index",
            "Airy (one film)",
            rcwa.Grating(g.wavelength, g.period, (g.filled(lossy).layers[0],)),
            lambda th, p: rcwa.airy_rt(lossy, bar.thickness, g.wavelength, th, p),
        ),
    ]
    rows = []
    for name, ref_name, structure, ref in cases:
        for pol in rcwa.POLARIZATIONS:
            dR = dT = 0.0
            absorbed = []
            for th in theta:
                o = rcwa.orders(structure, float(th), pol, harmonics)
                R, T = ref(th, pol)
                dR = max(dR, abs(o.reflected.sum() - R))
                dT = max(dT, abs(o.transmitted.sum() - T))
                absorbed.append(1 - R - T)
            rows.append((name, ref_name, pol, dR, dT, min(absorbed), max(absorbed)))
            log(f"  zero contrast {pol}: {name}: {dR:.1e} {dT:.1e}")
    return rows


def convergence(g, angles, Ns, ref_N):
    rows = []
    for pol in rcwa.POLARIZATIONS:
        for th in angles:
            ref = np.array(rcwa.force_coefficients(rcwa.orders(g, th * DEG, pol, ref_N)))
            errs = [
                float(np.max(np.abs(np.array(rcwa.force_coefficients(rcwa.orders(g, th * DEG, pol, N))) - ref)))
                for N in Ns
            ]
            rows.append((pol, th, ref, errs))
            log(f"  convergence {pol} {th}°: {errs}")
    return rows


def backends(g, angles, N):
    rows = []
    for pol in rcwa.POLARIZATIONS:
        for th in angles:
            a = rcwa.orders(g, th * DEG, pol, N, "meent")
            b = rcwa.orders(g, th * DEG, pol, N, "grcwa")
            ca, cb = rcwa.force_coefficients(a), rcwa.force_coefficients(b)
            rows.append((pol, th, ca, cb, a.info["cpu_seconds"], b.info["cpu_seconds"]))
    return rows


def interpolation(g, table, pol, harmonics, every=3):
    """The spline against RCWA at the quarter point of every `every`-th interval and of the intervals beside
    each Rayleigh anomaly: angles neither the nodes nor the refinement's midpoints ever sampled."""
    th = table.theta
    anomalies = np.array(table.metadata["rayleigh_anomalies"])
    idx = set(range(0, th.size - 1, every))
    for a in anomalies:
        k = int(np.argmin(np.abs(th - a)))
        idx |= {k - 1, k}
    near, far = [], []
    for k in sorted(i for i in idx if 0 <= i < th.size - 1):
        q = th[k] + 0.25 * (th[k + 1] - th[k])
        exact = np.array(rcwa.force_coefficients(rcwa.orders(g, float(q), pol, harmonics)))
        approx = np.array([float(v) for v in table.coefficients(q)])
        err = float(np.max(np.abs(exact - approx)))
        touches = anomalies.size and np.min(np.abs(anomalies - q)) < 1.01 * (th[k + 1] - th[k])
        (near if touches else far).append(err)
    return near, far


def evaluation_cost(table, repeats=5):
    from numba import njit

    @njit
    def loop(packed, angles):
        total = 0.0
        for t in angles:
            cn, ct = optics.packed_coefficients(packed, t, False)
            total += cn + ct
        return total

    packed = table.packed()
    angles = np.random.default_rng(0).uniform(-0.3, 0.3, 200000)
    loop(packed, angles[:10])  # compile
    best_kernel = min(_cpu(lambda: loop(packed, angles)) for _ in range(repeats)) / angles.size
    x = angles[:30]
    best_numpy = min(_cpu(lambda: [table.coefficients(x) for _ in range(1000)]) for _ in range(repeats)) / 1000
    return best_kernel, best_numpy


def _cpu(fn):
    t0 = time.process_time()
    fn()
    return time.process_time() - t0


def figure(tables, path):
    fig, axes = new_figure(1, 2, (10.0, 3.8))
    th = np.linspace(-85, 85, 3401)
    for pol, table in tables.items():
        cn, ct = table.coefficients(th * DEG)
        axes[0, 0].plot(th, cn, lw=0.9, label=pol)
        axes[0, 1].plot(th, ct, lw=0.9, label=pol)
    axes[0, 0].plot(th, 2 * np.cos(th * DEG) ** 2, "k--", lw=0.8, label="mirror (Eq. 11)")
    axes[0, 1].axhline(0, color="k", ls="--", lw=0.8, label="mirror")
    for ax, name in ((axes[0, 0], "c_n"), (axes[0, 1], "c_t")):
        for a in next(iter(tables.values())).metadata["rayleigh_anomalies"]:
            ax.axvline(a / DEG, color="0.7", lw=0.6)
        ax.set_xlabel("angle of incidence θ (deg)")
        ax.set_ylabel(name)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    axes[0, 0].set_title("normal force coefficient (grey: Rayleigh anomalies)", fontsize=9)
    axes[0, 1].set_title("tangential force coefficient", fontsize=9)
    save_figure(fig, path)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="a smoke run: 20 harmonics, 2° nodes, fewer tables")
    args = ap.parse_args(argv)
    harmonics = 20 if args.quick else optics.DEFAULT_HARMONICS
    step = 2 * DEG if args.quick else optics.DEFAULT_STEP
    big, sym = rcwa.GRATINGS["bigrating"], rcwa.GRATINGS["symmetric"]
    t0 = time.process_time()
    tables = {}
    for name, g in (("bigrating", big), ("symmetric", sym)):
        for pol in ("TE", "TM", "mean"):
            log(f"table {name} {pol}")
            tables[name, pol] = optics.grating_table(g, pol, harmonics=harmonics, step=step)
    theta = tables["bigrating", "TE"].theta
    lines = [
        "# Optics checks",
        "",
        f"Made by `python validation/optics.py{' --quick' if args.quick else ''}`"
        + (" (a smoke run: 20 harmonics, 2° nodes — not the committed numbers)." if args.quick else "."),
        f"Tables: meent {optics.backend_version('meent')} (numpy backend), {harmonics} harmonics (orders −N…N), "
        f"{theta.size} nodes on ±85° (spacing ≤ {step / DEG:g}°, breaks at the Rayleigh anomalies "
        f"±{abs(big.rayleigh_anomalies()[0]) / DEG:.4f}°). CPU time of the RCWA behind each table "
        "(one BLAS thread; from the cache when it was computed before):",
        "",
        "| grating | polarisation | CPU (s) | c_n(0) | c_t(0) |",
        "|---|---|---|---|---|",
    ]
    for (name, pol), t in tables.items():
        cn0, ct0 = (float(v) for v in t.coefficients(0.0))
        lines.append(f"| {name} | {pol} | {t.metadata['rcwa_cpu_seconds']:.0f} | {cn0:.6f} | {ct0:+.6f} |")
    figure({pol: tables["bigrating", pol] for pol in ("TE", "TM", "mean")}, OUT / "optics_table.png")
    lines += [
        "",
        "![The chosen grating's force table](optics_table.png)",
        "",
        f"The chosen grating ({big.name}: λ = {big.wavelength * 1e6:g} µm, Λ = {big.period * 1e6:g} µm, two Si bars "
        "0.40 µm tall at 0.05–0.34 Λ and 0.47–0.54 Λ on a 0.30 µm silica film, n_Si = 3.48, n_SiO₂ = 1.45): "
        "c_n and c_t against the angle of incidence, TE, TM and their mean, with the mirror's.",
        "",
        "## 1. The mirror table is Eq. (11)",
        "",
    ]
    wide = np.concatenate([theta, np.linspace(-1.5, 1.5, 601)])
    rel_np, rel_k = mirror_check(wide)
    lines += [
        f"Largest relative difference |f_table − f_Eq.11| / |f_Eq.11| over {wide.size} angles (the {theta.size} "
        f"nodes and 601 more on ±86°): numpy {rel_np:.1e}, compiled kernel {rel_k:.1e} (target 1e-12).",
        "",
    ]
    log("zero contrast")
    zc = zero_contrast(big, theta, harmonics)
    lines += [
        "## 2. Zero index contrast = thin-film optics, every tabulated angle",
        "",
        f"{theta.size} angles, {harmonics} harmonics; target 1e-8.",
        "",
        "| structure | reference | pol | max \\|ΔR\\| | max \\|ΔT\\| | absorbed (min … max) |",
        "|---|---|---|---|---|---|",
    ]
    for name, ref, pol, dR, dT, amin, amax in zc:
        lines.append(f"| {name} | {ref} | {pol} | {dR:.1e} | {dT:.1e} | {amin:.3f} … {amax:.3f} |")
    lines += [
        "",
        "## 3. Energy conservation of the lossless gratings, every tabulated angle",
        "",
        "| grating | pol | max \\|1 − ΣR − ΣT\\| | nodes |",
        "|---|---|---|---|",
    ]
    for name in ("bigrating", "symmetric"):
        for pol in rcwa.POLARIZATIONS:
            t = tables[name, pol]
            lines.append(f"| {name} | {pol} | {np.max(np.abs(t.extra[f'A_{pol}'])):.1e} | {t.theta.size} |")
    lines += [
        "",
        "## 4. The symmetric grating: c_t odd, c_n even",
        "",
        "| pol | max \\|c_t(−θ) + c_t(θ)\\| | max \\|c_n(−θ) − c_n(θ)\\| | max \\|c_t\\| |",
        "|---|---|---|---|",
    ]
    for pol in ("TE", "TM", "mean"):
        t = tables["symmetric", pol]
        assert np.array_equal(t.theta, -t.theta[::-1])
        cn, ct = t.c_n, t.c_t
        lines.append(
            f"| {pol} | {np.max(np.abs(ct + ct[::-1])):.1e} | {np.max(np.abs(cn - cn[::-1])):.1e} | "
            f"{np.max(np.abs(ct)):.3f} |"
        )
    ct = tables["bigrating", "TE"].c_t
    lines += [
        "",
        f"The asymmetric bigrating gives max |c_t(−θ) + c_t(θ)| = {np.max(np.abs(ct + ct[::-1])):.3f} (TE): the check "
        "can fail.",
        "",
    ]
    if not args.quick:
        log("convergence")
        Ns, ref_N = (10, 20, 40, 60, 80, 120), 200
        conv = convergence(big, (0, 5, 15, 30, 60), Ns, ref_N)
        lines += [
            "## 5. RCWA convergence in the number of harmonics",
            "",
            f"The bigrating; max(|Δc_n|, |Δc_t|) against N = {ref_N} (orders −N…N). The tables use N = {harmonics}.",
            "",
            f"| pol | θ (deg) | c_n (N={ref_N}) | c_t (N={ref_N}) | " + " | ".join(f"N={n}" for n in Ns) + " |",
            "|---|---|---|---|" + "---|" * len(Ns),
        ]
        for pol, th, ref, errs in conv:
            lines.append(
                f"| {pol} | {th} | {ref[0]:.6f} | {ref[1]:+.6f} | " + " | ".join(f"{e:.1e}" for e in errs) + " |"
            )
        log("backends")
        rows = backends(big, (0, 10, 40), 40)
        lines += [
            "",
            "## 6. meent against grcwa",
            "",
            "The bigrating, 40 harmonics in both (grcwa: the grating as a 2-D lattice with a negligible second "
            "period; Laurent's rule in TM, where it converges more slowly); CPU seconds of one solve.",
            "",
            "| pol | θ (deg) | meent c_n, c_t | grcwa c_n, c_t | max \\|Δ\\| | meent CPU (s) | grcwa CPU (s) |",
            "|---|---|---|---|---|---|---|",
        ]
        for pol, th, ca, cb, sa, sb in rows:
            d = max(abs(ca[0] - cb[0]), abs(ca[1] - cb[1]))
            lines.append(
                f"| {pol} | {th} | {ca[0]:.5f}, {ca[1]:+.5f} | {cb[0]:.5f}, {cb[1]:+.5f} | {d:.1e} | {sa:.3f} | "
                f"{sb:.3f} |"
            )
        lines.append("")
    log("interpolation")
    plain = optics.grating_table(big, "TE", harmonics=harmonics, step=step, tolerance=0.0, grade=0)
    lines += [
        "## 7. Interpolation error of the table",
        "",
        "The bigrating, TE: the spline against RCWA at the quarter points of every third interval and of the "
        "intervals beside each Rayleigh anomaly (angles never sampled for the table), with uniform nodes (no "
        "grading, no refinement) and as built (graded beside the anomalies, refined to the tolerance).",
        "",
    ]
    built = tables["bigrating", "TE"]
    meta = built.metadata
    lines += [
        f"As built: {built.theta.size} nodes ({plain.theta.size} uniform, "
        f"{2 * len(meta['rayleigh_anomalies']) * meta['grade']} "
        f"graded beside the anomalies, {meta['refinement_nodes']} added in {meta['refinement_passes']} refinement "
        f"passes; tolerance {meta['tolerance']:g}, last pass's largest midpoint error "
        f"{meta['refinement_last_error']:.1e}).",
        "",
    ]
    for label, table in (("uniform nodes", plain), ("as built", built)):
        near, far = interpolation(big, table, "TE", harmonics)
        lines += [
            f"{label}:",
            "",
            "| where | quarter points | max \\|Δc\\| | median \\|Δc\\| |",
            "|---|---|---|---|",
            f"| beside an anomaly | {len(near)} | {max(near):.1e} | {np.median(near):.1e} |",
            f"| elsewhere | {len(far)} | {max(far):.1e} | {np.median(far):.1e} |",
            "",
        ]
    kernel, vector = evaluation_cost(tables["bigrating", "TE"])
    lines += [
        "## 8. Cost of evaluating a table",
        "",
        f"{theta.size}-node table, CPU time, minimum of 5 repeats: compiled `packed_coefficients` "
        f"{kernel * 1e9:.0f} ns per angle (inside a compiled loop, as a solver's kernel calls it); "
        f"numpy `coefficients` for 30 slices at once {vector * 1e6:.0f} µs.",
        "",
        f"Total CPU time of this script: {time.process_time() - t0:.0f} s.",
        "",
    ]
    (OUT / "optics.md").write_text("\n".join(lines))
    log(f"wrote {OUT / 'optics.md'}")


if __name__ == "__main__":
    main()
