"""The linearised flat accelerating sail, with and without the beam, from both solvers.

For the paper's cases (n = 30) the spectra of the flat state's Jacobian with the load and without it
(I₀ = 0) are compared mode by mode (analysis.linear_stability): the load changes no frequency and adds
no growth rate. The torsion spectrum is set next to the free–free Euler–Bernoulli beam,
ω_j = (β_j L)² √(EI/(ρhW L⁴)). Exudyn's own forward-difference Jacobian of the lit tree is also shown
against its difference step: its load part carries the forward difference's truncation error, linear in
the step (the central-difference load stiffness of analysis.linear_stability is second order).

Writes stability_linear.png, stability_linear.csv (per case and solver) and stability_linear_exudyn_fd.csv
(the spurious shift against Exudyn's relativeEpsilon). No time integration and no store: both solvers'
linearisations are always computed (the solver, workers, scheduler and store arguments are not used).
Quick: n = 10, three difference steps. Run: lightsail-mbs reproduce --scenario stability_linear, or
python scenarios/stability_linear.py.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from lightsail_mbs import paper_case
from lightsail_mbs.analysis import linear_stability as st
from lightsail_mbs.studies.tables import print_table, write_csv
from lightsail_mbs.viz.plots import new_figure, save_figure

CASES = {
    "torsion-stable": ("torsion-stable", {}),
    "torsion-soft": ("torsion-soft", {}),
    "tnt-stable (inextensible)": ("tnt-stable", dict(axial_springs=False)),
    "tnt-stable (extensible)": ("tnt-stable", {}),
    "rigid": ("rigid", {}),
}
EXUDYN_CASES = ("torsion-stable", "torsion-soft", "tnt-stable (inextensible)", "rigid")
BETA_L = np.array([4.730041, 7.853205, 10.995608, 14.137165, 17.278760])  # free–free beam roots
EPSILONS = (1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11)
QUICK_EPSILONS = (1e-6, 1e-8, 1e-10)


def cases(quick: bool = False) -> dict:
    """{label: SailParameters} of the paper's cases (n = 10 when quick)."""
    changes = dict(n=10) if quick else {}
    return {label: paper_case(name, **{**extra, **changes}) for label, (name, extra) in CASES.items()}


def elastic_relative_shift(lit, dark) -> float:
    """max |ω²_lit − ω²_dark| / ω²_dark over the elastic modes (ω² > 1e-9 × the largest)."""
    w2 = dark.omega_squared
    keep = w2 > 1e-9 * max(w2.max(), 1e-300)
    return float(np.max(np.abs(lit.omega_squared[keep] - w2[keep]) / w2[keep])) if keep.any() else 0.0


def spectrum_rows(params: dict) -> list[dict]:
    """Per case and solver: the load's shift of the spectrum, the growth rates with and without the
    load, and the first two frequencies."""
    rows = []
    for name, p in params.items():
        for solver in ("reduced", "exudyn") if name in EXUDYN_CASES else ("reduced",):
            lit, dark = st.linear_spectrum(p, solver), st.linear_spectrum(st.unlit(p), solver)
            f = dark.frequencies_hz()
            rows.append(
                dict(
                    case=name,
                    solver=solver,
                    elastic_relative_shift=elastic_relative_shift(lit, dark),
                    shift_over_g0k=float(np.abs(lit.omega_squared - dark.omega_squared).max() / st.load_rate_scale(p)),
                    growth_rate_lit=lit.max_growth_rate,
                    growth_rate_unlit=dark.max_growth_rate,
                    f1_hz=f[0] if f.size else 0.0,
                    f2_hz=f[1] if f.size > 1 else 0.0,
                )
            )
    return rows


def torsion_spectra(p) -> dict:
    """The torsion sail's frequencies (Hz): the free–free beam, lit (both solvers) and unlit (reduced),
    and the elastic shift of Exudyn's central-difference linearisation (lit vs unlit)."""
    beam = (
        BETA_L**2
        * np.sqrt(p.youngs_modulus * p.second_moment_of_area / (p.density * p.thickness * p.width * p.length**4))
        / (2 * np.pi)
    )
    lit = {s: st.linear_spectrum(p, s) for s in ("reduced", "exudyn")}
    dark = st.linear_spectrum(st.unlit(p), "reduced")
    dark_exudyn = st.linear_spectrum(st.unlit(p), "exudyn")
    return dict(
        beam=beam,
        lit={s: v.frequencies_hz() for s, v in lit.items()},
        unlit=dark.frequencies_hz(),
        central_shift=elastic_relative_shift(lit["exudyn"], dark_exudyn),
    )


def forward_difference_rows(p, epsilons=EPSILONS) -> list[dict]:
    """The spurious elastic shift of Exudyn's own forward-difference Jacobian of the lit tree per step."""
    dark_exudyn = st.linear_spectrum(st.unlit(p), "exudyn")
    rows = []
    for eps in epsilons:
        solver_fd = st.spectrum_of_system(*st.mass_stiffness(p, load="solver", relative_epsilon=eps))
        rows.append(dict(relative_epsilon=eps, elastic_relative_shift=elastic_relative_shift(solver_fd, dark_exudyn)))
    return rows


def run(out, *, solver="reduced", workers=None, scheduler=None, quick=False, store=None, progress=True) -> dict:
    out = Path(out)
    params = cases(quick)
    rows = spectrum_rows(params)
    torsion = torsion_spectra(params["torsion-stable"])
    noise = forward_difference_rows(params["torsion-stable"], QUICK_EPSILONS if quick else EPSILONS)
    write_csv(out / "stability_linear.csv", rows)
    write_csv(out / "stability_linear_exudyn_fd.csv", noise)
    print_table("Flat state: spectrum with load vs without (max |dw2|/w2 over elastic modes; growth rates 1/s)", rows)
    n = params["torsion-stable"].n
    print_table(
        f"Torsion-stable: first free-free frequencies (Hz), chain n = {n} vs Euler-Bernoulli beam",
        [
            dict(
                mode=j + 1,
                beam=torsion["beam"][j],
                reduced_lit=torsion["lit"]["reduced"][j],
                exudyn_lit=torsion["lit"]["exudyn"][j],
                reduced_unlit=torsion["unlit"][j],
            )
            for j in range(3)
        ],
    )
    print_table("Exudyn's own forward-difference Jacobian of the lit tree: spurious shift vs step", noise)
    plot(out / "stability_linear.png", torsion, noise, n)
    return {"rows": rows, "noise": noise, "torsion": torsion}


def plot(path, torsion: dict, noise: list[dict], n: int = 30) -> Path:
    """Left: the torsion sail's frequencies with the load against those without; right: the spurious shift
    of Exudyn's forward-difference Jacobian against its step."""
    fig, axes = new_figure(1, 2, size=(10.0, 4.0))
    ax, bx = axes[0]
    f_dark, beam = torsion["unlit"], torsion["beam"]
    for solver, marker in (("reduced", "o"), ("exudyn", "x")):
        ax.loglog(f_dark, torsion["lit"][solver], marker, mfc="none", label=f"{solver}, with load")
    ax.loglog(beam, beam, "k+", ms=10, label="free–free beam (unloaded)")
    ax.loglog(f_dark[[0, -1]], f_dark[[0, -1]], "k:", lw=0.8)
    ax.set_xlabel("frequency without load (Hz)")
    ax.set_ylabel("frequency with load (Hz)")
    ax.set_title(f"torsion sail, E = 4.5e13 Pa, n = {n}: flat-state modes", fontsize=9)
    ax.legend(fontsize=8)
    bx.loglog(
        [r["relative_epsilon"] for r in noise],
        [r["elastic_relative_shift"] for r in noise],
        "o-",
        label="Exudyn Jacobian of the lit tree",
    )
    bx.axhline(
        max(torsion["central_shift"], 1e-16), color="k", ls="--", lw=0.8, label="central-difference load stiffness"
    )
    bx.set_xlabel("Exudyn relativeEpsilon")
    bx.set_ylabel("max |Δω²|/ω² (lit vs unlit)")
    bx.set_title("the load's linear effect is nil; forward differences are not", fontsize=9)
    bx.legend(fontsize=8)
    return save_figure(fig, path)
