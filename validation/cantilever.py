"""Euler–Bernoulli cantilever (paper Appendix A): `python validation/cantilever.py`.

Writes validation/cantilever.md and cantilever_*.png:
1. static tip deflection of the clamped chain under P₀, both solvers' static equilibria against the
   exact discrete closed form (chain_theory) and Euler–Bernoulli P L³/(3EI), n = 10 … 1000, with
   the fitted convergence order;
2. the paper's dynamic run (n = 30, P(t) = P₀(1 − e^(−t/τ)), 2 s) with both solvers: the free
   vibration left on the plateau against the chain's first eigenfrequency, and the paper's error
   measure (Eq. 44) at t = 2 s next to its 1.84e-7 m, split into its parts.
"""

import argparse
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from lightsail_mbs.analysis.statics import static_state  # noqa: E402
from lightsail_mbs.model import chain_theory as ct  # noqa: E402
from lightsail_mbs.solvers import solve  # noqa: E402
from lightsail_mbs.studies import classic  # noqa: E402
from lightsail_mbs.viz.plots import new_figure, save_figure  # noqa: E402

OUT = Path(__file__).resolve().parent
STATIC_N = [10, 20, 30, 50, 100, 200, 500, 1000]
REDUCED_STATIC_MAX_N = 100  # the reduced static solve is dense (O(n³) per Jacobian column)
PAPER_PLATEAU_ERROR = 1.84e-7  # m, Appendix A
EXUDYN_STEP = 5e-5  # s: ω₁h = 0.053, generalized-α period error ≈ (ω₁h)²/12 ≈ 2.4e-4
REDUCED_RTOL = 1e-8  # at 1e-6 Radau damps the 169 Hz vibration by 5 % over 2 s


def static_rows(ns):
    rows = []
    for n in ns:
        p = classic.cantilever_case(n)
        EI = classic.bending_stiffness(p)
        exact = ct.cantilever_tip_deflection(p.tip_load, p.length, EI, n)
        row = {"n": n, "closed form (m)": exact}
        for solver in ("exudyn", "reduced"):
            if solver == "reduced" and n > REDUCED_STATIC_MAX_N:
                row[solver] = None
                continue
            t0 = time.perf_counter()
            row[solver] = float(static_state(p, solver).y[-1])
            row[f"{solver} wall (s)"] = time.perf_counter() - t0
        row["error vs PL³/3EI"] = exact / (p.tip_load * p.length**3 / (3 * EI)) - 1
        row["predicted −3/n+11/4n²−3/4n³"] = float(ct.cantilever_relative_error(n))
        rows.append(row)
        print(f"static n={n}: closed {exact:.9e}  exudyn {row['exudyn']:.9e}  reduced {row['reduced']}", flush=True)
    return rows


def dynamic_runs(n=30):
    p, settings = classic.cantilever_case(n), classic.CANTILEVER_RUN.replace(output_interval=1e-4)
    runs = {}
    t0 = time.perf_counter()
    runs["exudyn"] = solve(p, "exudyn", settings, step_size=EXUDYN_STEP)
    print(f"exudyn dynamic: {time.perf_counter() - t0:.1f} s, error {runs['exudyn'].error}", flush=True)
    t0 = time.perf_counter()
    runs["reduced"] = solve(p, "reduced", settings, method="Radau", rtol=REDUCED_RTOL)
    print(f"reduced dynamic: {time.perf_counter() - t0:.1f} s, error {runs['reduced'].error}", flush=True)
    return p, runs


def fmt(v, spec=".4g"):
    return "–" if v is None else format(v, spec)


def plots(rows, p, runs):
    fig, axes = new_figure(1, 1, (6.0, 4.0))
    ax = axes[0, 0]
    dense = np.logspace(1, 3, 100)
    ax.loglog(dense, np.abs(ct.cantilever_relative_error(dense)), "k-", lw=1, label="closed form (discrete chain)")
    ax.loglog(dense, 3 / dense, "k:", lw=1, label="3/n")
    EI = classic.bending_stiffness(p)
    eb = p.tip_load * p.length**3 / (3 * EI)
    for solver, marker in (("exudyn", "o"), ("reduced", "x")):
        pts = [(r["n"], abs(r[solver] / eb - 1)) for r in rows if r[solver] is not None]
        ax.loglog(*zip(*pts), marker, ms=6, mfc="none", label=f"{solver} static solve")
    ax.set_xlabel("n (slices)")
    ax.set_ylabel("|y_tip / (PL³/3EI) − 1|")
    ax.set_title("Cantilever: static tip deflection vs Euler–Bernoulli", fontsize=9)
    ax.legend(fontsize=7)
    save_figure(fig, OUT / "cantilever_convergence.png")

    fig, axes = new_figure(2, 1, (7.0, 6.0))
    ax = axes[0, 0]
    for solver, run in runs.items():
        ax.plot(run.time, run.y[:, -1] * 1e6, lw=0.8, label=solver)
    ys = ct.cantilever_tip_deflection(p.tip_load, p.length, EI, p.n)
    t = runs["exudyn"].time
    ax.plot(t, ys * np.array([p.tip_force(s) for s in t]) / p.tip_load * 1e6, "k--", lw=0.8, label="y_static · P(t)/P₀")
    ax.set_ylabel("tip deflection (µm)")
    ax.set_title(
        f"Cantilever n = {p.n}: P(t) = P₀(1 − e^(−t/τ)), P₀ = {p.tip_load:g} N, τ = {p.tip_load_time_constant:g} s",
        fontsize=9,
    )
    ax.legend(fontsize=7)
    ax = axes[1, 0]
    for solver, run in runs.items():
        keep = run.time >= 1.9
        ax.plot(
            run.time[keep], (run.y[keep, -1] - classic.quasi_static_tip(p, run.time[keep])) * 1e9, lw=0.8, label=solver
        )
    ax.set_xlabel("t (s)")
    ax.set_ylabel("tip − quasi-static (nm)")
    ax.set_title("free vibration left by the ramp (last 0.1 s)", fontsize=9)
    ax.legend(fontsize=7)
    save_figure(fig, OUT / "cantilever_dynamic.png")

    fig, axes = new_figure(2, 1, (6.5, 5.5))
    run = runs["exudyn"]
    x, y = run.x[-1], run.y[-1]
    xx = np.linspace(0, p.length, 200)
    axes[0, 0].plot(
        xx,
        ct.euler_bernoulli_cantilever(p.tip_load, p.length, EI, xx) * 1e6,
        "k-",
        lw=1,
        label="Euler–Bernoulli, Eq. (42)",
    )
    axes[0, 0].plot(x, y * 1e6, "o", ms=3, mfc="none", label=f"chain n = {p.n}, t = {run.time[-1]:g} s (exudyn)")
    axes[0, 0].set_ylabel("deflection (µm)")
    axes[0, 0].legend(fontsize=7)
    axes[1, 0].plot(x, (ct.euler_bernoulli_cantilever(p.tip_load, p.length, EI, x) - y) * 1e9, "o-", ms=3)
    axes[1, 0].set_xlabel("x (m)")
    axes[1, 0].set_ylabel("δ(x_i) − y_i (nm)")
    save_figure(fig, OUT / "cantilever_shape.png")


def report(rows, p, runs):
    EI = classic.bending_stiffness(p)
    ns = [r["n"] for r in rows]
    order = classic.fitted_order(ns, [r["exudyn"] / (p.tip_load * p.length**3 / (3 * EI)) - 1 for r in rows])
    order_tail = classic.fitted_order(
        ns[-4:], [r["exudyn"] / (p.tip_load * p.length**3 / (3 * EI)) - 1 for r in rows[-4:]]
    )
    lines = [
        "# Cantilever: Euler–Bernoulli beam (paper Appendix A)",
        "",
        "Generated by `python validation/cantilever.py`. Steel chain L = 1 m, h = 0.2 m, W = 0.1 m, "
        "ρ = 7800 kg/m³, E = 200 GPa (EI = 1.333e7 N·m²); slice 1 clamped "
        '(`boundary="cantilever"`), transverse load at the centre of slice n (`tip_load`), as in the '
        "paper's Fig. 13b.",
        "",
        "## Static tip deflection",
        "",
        "Exact discrete chain (springs k_T = EI/l at hinges 1…n−1, clamp over slice 1, load at "
        "x = L − l/2): y_tip = (P L³/EI)(n−1)(2n−1)(2n−3)/(12n³) = (P L³/3EI)(1 − 3/n + 11/(4n²) − 3/(4n³)) "
        "(`lightsail_mbs.chain_theory`). Both solvers' static equilibria (Exudyn `SolveStatic`; reduced: "
        "Newton on its own accelerations at rest, `lightsail_mbs.statics`) are nonlinear; they differ from the "
        "linear closed form only by the large-rotation term (≈ 6e-12 relative).",
        "",
        "| n | closed form (m) | exudyn (m) | rel. diff | reduced (m) | rel. diff | error vs PL³/3EI "
        "| −3/n + 11/4n² − 3/4n³ |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        c = r["closed form (m)"]
        red = r["reduced"]
        lines.append(
            f"| {r['n']} | {c:.9e} | {r['exudyn']:.9e} | {r['exudyn'] / c - 1:.1e} | "
            f"{fmt(red, '.9e')} | {fmt(None if red is None else red / c - 1, '.1e')} | "
            f"{r['error vs PL³/3EI']:.4e} | {r['predicted −3/n+11/4n²−3/4n³']:.4e} |"
        )
    lines += [
        "",
        f"Fitted order of the error vs P L³/(3EI) (Exudyn, least squares over all n): **{order:.3f}**; "
        f"over n ≥ {ns[-4]}: **{order_tail:.3f}**. The closed form predicts first order, error → −3/n: "
        "the chain is clamped over its whole first slice (first spring at x = l, not at x = 0) and the "
        "load acts l/2 short of the tip. (The rigid-slice chain's eigenfrequencies converge much faster, "
        "see modes.md.)",
        "",
        "![convergence](cantilever_convergence.png)",
        "",
        "## Dynamic run, n = 30 (the paper's case)",
        "",
    ]
    w1 = ct.chain_angular_frequencies(p)[0]
    f1 = w1 / (2 * np.pi)
    f_eb = classic.beam_references(p, 1)[0] / (2 * np.pi)
    budget = classic.error_budget(p)
    lines += [
        f"First eigenfrequency of the clamped chain (exact discrete, `chain_theory`): {f1:.4f} Hz "
        f"(Euler–Bernoulli cantilever 1.8751² √(EI/μL⁴)/2π = {f_eb:.4f} Hz; the chain is stiffer by the "
        f"same first-order clamp offset). The ramp is slow (ω₁τ ≈ {w1 * p.tip_load_time_constant:.0f}) but its "
        "kink at t = 0 leaves a free vibration: mode k keeps c_k/(τ√(ω_k² + τ⁻²)) of the static tip deflection "
        f"c_k it carries (`chain_theory.tip_ramp_vibration`): {budget['vibration']:.4e} m for mode 1, all "
        f"modes together ≤ {budget['vibration_bound']:.4e} m.",
        "",
        "| solver | settings | wall (s) | plateau frequency (Hz) | vs chain f₁ | plateau amplitude (m) | "
        "vs exact mode 1 | tip at 2 s (m) | paper error Eq. 44 at 2 s (m) |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for solver, run in runs.items():
        fit = classic.plateau(p, run.time, run.y[:, -1])
        settings = f"generalized-α, h = {EXUDYN_STEP:g} s" if solver == "exudyn" else f"Radau, rtol = {REDUCED_RTOL:g}"
        lines.append(
            f"| {solver} | {settings} | {run.wall_time:.1f} | {fit.frequency:.4f} | "
            f"{fit.frequency / f1 - 1:+.2e} | {fit.amplitude:.4e} | "
            f"{fit.amplitude / budget['vibration'] - 1:+.1e} | {run.y[-1, -1]:.6e} | "
            f"{classic.paper_error(p, run.x[-1], run.y[-1]):.4e} |"
        )
    lines += [
        "",
        f"**Plateau error next to the paper's {PAPER_PLATEAU_ERROR:.3g} m.** The paper's measure (Eq. 44, "
        "max over the slice centres of |δ(x_i) − y_i| at t = 2 s, δ the continuum deflection of Eq. 42 "
        "with the load at x = L) is, from the exact chain:",
        "",
        "| part | value (m) |",
        "|---|---|",
        f"| static chain vs Euler–Bernoulli at the slice centres (discretisation, at the tip) | "
        f"{budget['discretisation']:.4e} |",
        f"| load not yet at P₀: y_tip P₀ e^(−2/0.3) | {budget['load_deficit']:.3e} |",
        f"| free vibration left by the ramp (mode-1 amplitude, sign set by its phase at 2 s) | "
        f"± {budget['vibration']:.3e} |",
        "",
        "So our n = 30 error (table above) matches the paper's 1.84e-7 m, and it is almost all "
        "discretisation error: the chain's own static deflection is short of the continuum one by "
        "≈ (9/4n) P L³/(3EI) at its last centre, the first-order clamp and load-position offsets of the "
        "closed form. The paper's explanation (P(t) never quite reaching P₀) accounts for only "
        f"{budget['load_deficit'] / budget['discretisation'] * 100:.1f} % of it, and the free vibration for "
        f"≤ {budget['vibration'] / budget['discretisation'] * 100:.1f} %. Unlike the paper's Fig. 15a, the error "
        "does not plateau beyond n = 30 in our chain: it keeps falling as 1/n (static table), so a plateau "
        "would have to come from the paper's run (e.g. its integrator tolerance or output), not from the model.",
        "",
        "Plateau: the reduced solver (Radau, error-controlled) reproduces the exact chain's f₁; Exudyn's "
        "generalized-α lowers it by its period elongation ≈ (ω₁h)²/12 at the step used. Both keep the exact "
        "mode-1 amplitude (Radau needs rtol ≲ 1e-8 for that: at 1e-6 its numerical damping takes 5 % off it "
        "over 2 s).",
        "",
        "![dynamic](cantilever_dynamic.png)",
        "",
        "![shape](cantilever_shape.png)",
        "",
    ]
    (OUT / "cantilever.md").write_text("\n".join(lines), encoding="utf-8")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.parse_args(argv)
    rows = static_rows(STATIC_N)
    p, runs = dynamic_runs()
    plots(rows, p, runs)
    report(rows, p, runs)
    print(f"wrote {OUT / 'cantilever.md'}")


if __name__ == "__main__":
    sys.exit(main())
