"""The failure-time law of the unstable regime, held against runs.

Law (analysis.finite_amplitude): t_f = F(r, ν) · t_c with t_c = 1/(k √(g₀ a₀)), k = 2πν/L,
g₀ = 2I₀/(cρh), r = E/E_cr,max (torsion) or T/T_cr,max (TnT). So t_f ∝ g₀^(−1/2) a₀^(−1/2) ∝ √(h/I₀) / √a₀
at fixed r. Scaled runs of the reduced equations (finite_amplitude.failure_tau, up to 20 t_c), n = 30,
ν = 3/2, over h = 0.1–10 µm (g₀ over two decades) × a₀ = 1–100 µm (two decades) at r = 0.1, 1, 4
(torsion) and r = 0.5, 2 (TnT, inextensible); fitted exponents of t_f in g₀ and a₀ next to −1/2;
F(r) over r; F against ν; the soft limit's dependence on n.

Writes stability_failure_time.png and stability_failure_time_{grid,fits,curve,modes,n}.csv. The runs
are integrated in this process (the solver, workers, scheduler and store arguments are not used).
Quick: h and a₀ at 0.1 and 10 µm / 1 and 100 µm, one ratio per model, a third of the curve, n = 15
and 30. Run: lightsail-mbs reproduce --scenario stability_failure_time, or
python scenarios/stability_failure_time.py.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from lightsail_mbs import SailParameters
from lightsail_mbs.analysis import finite_amplitude as cr
from lightsail_mbs.studies.tables import print_table, write_csv
from lightsail_mbs.viz.plots import new_figure, save_figure

TORSION = SailParameters(model="torsion", n=30, defect_mode=1.5)
TNT = SailParameters(model="tnt", n=30, defect_mode=1.5, axial_springs=False, tension=1e-8)
THICKNESSES = (1e-7, 1e-6, 1e-5)
AMPLITUDES = (1e-6, 1e-5, 1e-4)
RATIOS = {"torsion": (0.1, 1.0, 4.0), "tnt": (0.5, 2.0)}
CURVE_RATIOS = (0.03, 0.1, 0.3, 0.5, 1, 2, 3, 4, 5, 6, 7, 7.5)
MODES = (1.0, 1.5, 2.0, 3.0)
SOFT_N = (15, 30, 60, 120)
TAU_MAX = 20.0


# ---- computation -----------------------------------------------------------------------------
def grid_rows(base, ratios, thicknesses, amplitudes) -> list[dict]:
    """One scaled run per (r, h, a₀): g₀, t_c, t_f and F = t_f/t_c (None: no failure within TAU_MAX)."""
    rows = []
    for r in ratios:
        for h in thicknesses:
            for a0 in amplitudes:
                p = cr.with_ratio(base.replace(thickness=h, defect_amplitude=a0), r)
                tau = cr.failure_tau(p, TAU_MAX)
                tc = cr.time_scale(p)
                rows.append(
                    dict(
                        model=p.model,
                        ratio=r,
                        thickness_m=h,
                        amplitude_m=a0,
                        g0=p.nominal_acceleration,
                        t_c=tc,
                        t_f=None if tau is None else tau * tc,
                        F=tau,
                    )
                )
    return rows


def fit_exponents(rows) -> dict:
    """log t_f = c + α log g₀ + β log a₀ (least squares over the failed runs)."""
    ok = [r for r in rows if r["t_f"] is not None]
    A = np.column_stack([np.ones(len(ok)), np.log([r["g0"] for r in ok]), np.log([r["amplitude_m"] for r in ok])])
    coef, *_ = np.linalg.lstsq(A, np.log([r["t_f"] for r in ok]), rcond=None)
    return {"g0_exponent": coef[1], "a0_exponent": coef[2]}


def grid_and_fits(quick: bool = False) -> tuple[list[dict], list[dict]]:
    """The (r, h, a₀) grid of both models and, per (model, r), the fitted exponents and F's spread."""
    thick, amps = (THICKNESSES[::2], AMPLITUDES[::2]) if quick else (THICKNESSES, AMPLITUDES)
    fits, grid = [], []
    for base in (TORSION, TNT):
        for r in RATIOS[base.model][:1] if quick else RATIOS[base.model]:
            rows = grid_rows(base, [r], thick, amps)
            grid += rows
            F = np.array([x["F"] for x in rows if x["F"] is not None])
            fits.append(
                dict(
                    model=base.model,
                    ratio=r,
                    runs=len(rows),
                    failed=len(F),
                    **fit_exponents(rows),
                    analytic_exponent=-0.5,
                    F_mean=F.mean(),
                    F_spread=(F.max() - F.min()) / F.mean(),
                )
            )
    return grid, fits


def curve_rows(quick: bool = False) -> list[dict]:
    """F(r) of both models over CURVE_RATIOS."""
    return [
        dict(model=base.model, ratio=r, F=cr.failure_tau(cr.with_ratio(base, r), TAU_MAX))
        for base in (TORSION, TNT)
        for r in (CURVE_RATIOS[::3] if quick else CURVE_RATIOS)
    ]


def mode_rows() -> list[dict]:
    """F against ν (torsion, r = 0.5)."""
    return [
        dict(
            model="torsion",
            mode=nu,
            ratio=0.5,
            F=cr.failure_tau(cr.with_ratio(TORSION.replace(defect_mode=nu), 0.5), TAU_MAX),
        )
        for nu in MODES
    ]


def slice_count_rows(quick: bool = False) -> list[dict]:
    """F against n at r = 0.001 (the soft limit) and r = 1 (torsion)."""
    return [
        dict(n=n, ratio=r, F=cr.failure_tau(cr.with_ratio(TORSION.replace(n=n), r), TAU_MAX))
        for r in (0.001, 1.0)
        for n in (SOFT_N[:2] if quick else SOFT_N)
    ]


# ---- pipeline --------------------------------------------------------------------------------
def run(out, *, solver="reduced", workers=None, scheduler=None, quick=False, store=None, progress=True) -> dict:
    out = Path(out)
    grid, fits = grid_and_fits(quick)
    curve, modes, soft = curve_rows(quick), mode_rows(), slice_count_rows(quick)
    write_csv(out / "stability_failure_time_grid.csv", grid)
    write_csv(out / "stability_failure_time_fits.csv", fits)
    write_csv(out / "stability_failure_time_curve.csv", curve)
    write_csv(out / "stability_failure_time_modes.csv", modes)
    write_csv(out / "stability_failure_time_n.csv", soft)
    print_table("Failure time t_f = F(r) t_c: exponents of t_f in g0 and a0 (two decades each) vs analytic -1/2", fits)
    print_table("F(r) = t_f/t_c against the stiffness ratio r (nu = 3/2, n = 30)", curve)
    print_table("F against the mode nu (torsion, r = 0.5)", modes)
    print_table("F against n: the soft limit (r = 0.001) is set by the slice length, r = 1 converges", soft)
    plot(out / "stability_failure_time.png", grid, curve)
    return {"grid": grid, "fits": fits, "curve": curve, "modes": modes, "n": soft}


def plot(path, grid, curve) -> Path:
    """Left: t_f against t_c over the grid, with lines t_f = F t_c; right: F(r)."""
    fig, axes = new_figure(1, 2, size=(10.0, 4.2))
    ax, bx = axes[0]
    markers = {"torsion": "o", "tnt": "s"}
    groups = sorted({(r["model"], r["ratio"]) for r in grid})
    for i, (model, ratio) in enumerate(groups):
        pts = [(r["t_c"], r["t_f"]) for r in grid if (r["model"], r["ratio"]) == (model, ratio) and r["t_f"]]
        if pts:
            ax.loglog(*zip(*pts), markers[model], ms=6, mfc="none", color=f"C{i}", label=f"{model}, r = {ratio:g}")
    tc = np.array([r["t_c"] for r in grid])
    span = np.array([tc.min() / 1.5, tc.max() * 1.5])
    for F, style in ((1.6, ":"), (3.7, "--")):
        ax.loglog(span, F * span, "k" + style, lw=0.8, label=f"t_f = {F} t_c")
    ax.legend(fontsize=7, ncol=2)
    ax.set_xlabel("t_c = 1/(k √(g₀ a₀))  (s)")
    ax.set_ylabel("failure time t_f (s)")
    ax.set_title("runs over h = 0.1–10 µm, a₀ = 1–100 µm (o torsion, □ TnT)", fontsize=9)
    for model in ("torsion", "tnt"):
        pts = [(r["ratio"], r["F"]) for r in curve if r["model"] == model and r["F"] is not None]
        if pts:
            bx.semilogx(
                *zip(*pts),
                markers[model] + "-",
                label=f"{model}: r = {'E/E_cr,max' if model == 'torsion' else 'T/T_cr,max'}",
            )
    bx.set_xlabel("stiffness ratio r")
    bx.set_ylabel("F = t_f / t_c")
    bx.set_title("the law's one function F(r) (ν = 3/2, n = 30)", fontsize=9)
    bx.legend(fontsize=8)
    return save_figure(fig, path)
