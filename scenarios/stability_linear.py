"""Linearised flat accelerating sail, with and without the beam, from both solvers (issue 8, part 1).

For the paper's cases (n = 30) the spectra of the flat state's Jacobian with the load and without it
(I₀ = 0) are compared mode by mode (lightsail_mbs.stability.load_shift): the load changes no frequency
and adds no growth rate. The torsion spectrum is set next to the free–free Euler–Bernoulli beam,
ω_j = (β_j L)² √(EI/(ρhW L⁴)). Exudyn's own forward-difference Jacobian of the lit tree is also shown
against its difference step: its load part is noise (see stability.py).
Writes stability_linear.png and stability_linear.csv. Usage: python scenarios/stability_linear.py [--out DIR]
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from lightsail_mbs import paper_case
from lightsail_mbs.analysis import linear_stability as st
from lightsail_mbs.paper.common import new_figure, print_table, save_figure, write_csv

CASES = {"torsion-stable": paper_case("torsion-stable"), "torsion-soft": paper_case("torsion-soft"),
         "tnt-stable (inextensible)": paper_case("tnt-stable", axial_springs=False),
         "tnt-stable (extensible)": paper_case("tnt-stable"), "rigid": paper_case("rigid")}
EXUDYN_CASES = ("torsion-stable", "torsion-soft", "tnt-stable (inextensible)", "rigid")
BETA_L = np.array([4.730041, 7.853205, 10.995608, 14.137165, 17.278760])   # free–free beam roots
EPSILONS = (1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11)


def elastic_relative_shift(lit, dark) -> float:
    w2 = dark.omega_squared
    keep = w2 > 1e-9 * max(w2.max(), 1e-300)
    return float(np.max(np.abs(lit.omega_squared[keep] - w2[keep]) / w2[keep])) if keep.any() else 0.0


def run(out) -> dict:
    out = Path(out)
    rows = []
    for name, p in CASES.items():
        for solver in ("reduced", "exudyn") if name in EXUDYN_CASES else ("reduced",):
            lit, dark = st.linear_spectrum(p, solver), st.linear_spectrum(st.unlit(p), solver)
            f = dark.frequencies_hz()
            rows.append(dict(case=name, solver=solver, elastic_relative_shift=elastic_relative_shift(lit, dark),
                             shift_over_g0k=float(np.abs(lit.omega_squared - dark.omega_squared).max()
                                                  / st.load_rate_scale(p)),
                             growth_rate_lit=lit.max_growth_rate, growth_rate_unlit=dark.max_growth_rate,
                             f1_hz=f[0] if f.size else 0.0, f2_hz=f[1] if f.size > 1 else 0.0))
    p = CASES["torsion-stable"]
    beam = BETA_L ** 2 * np.sqrt(p.youngs_modulus * p.second_moment_of_area
                                 / (p.density * p.thickness * p.width * p.length ** 4)) / (2 * np.pi)
    lit = {s: st.linear_spectrum(p, s) for s in ("reduced", "exudyn")}
    dark = st.linear_spectrum(st.unlit(p), "reduced")
    dark_exudyn = st.linear_spectrum(st.unlit(p), "exudyn")
    noise = []
    for eps in EPSILONS:
        solver_fd = st.spectrum_of_system(*st.exudyn_linearization(p, exudyn_load="solver", relative_epsilon=eps))
        noise.append(dict(relative_epsilon=eps, elastic_relative_shift=elastic_relative_shift(solver_fd, dark_exudyn)))
    write_csv(out / "stability_linear.csv", rows)
    write_csv(out / "stability_linear_exudyn_fd.csv", noise)
    print_table("Flat state: spectrum with load vs without (max |dw2|/w2 over elastic modes; growth rates 1/s)", rows)
    print_table("Torsion-stable: first free-free frequencies (Hz), chain n = 30 vs Euler-Bernoulli beam",
                [dict(mode=j + 1, beam=beam[j], reduced_lit=lit["reduced"].frequencies_hz()[j],
                      exudyn_lit=lit["exudyn"].frequencies_hz()[j], reduced_unlit=dark.frequencies_hz()[j])
                 for j in range(3)])
    print_table("Exudyn's own forward-difference Jacobian of the lit tree: spurious shift vs step", noise)

    fig, axes = new_figure(1, 2, size=(10.0, 4.0))
    ax, bx = axes[0]
    f_dark = dark.frequencies_hz()
    for solver, marker in (("reduced", "o"), ("exudyn", "x")):
        ax.loglog(f_dark, lit[solver].frequencies_hz(), marker, mfc="none", label=f"{solver}, with load")
    ax.loglog(beam, beam, "k+", ms=10, label="free–free beam (unloaded)")
    ax.loglog(f_dark[[0, -1]], f_dark[[0, -1]], "k:", lw=0.8)
    ax.set_xlabel("frequency without load (Hz)")
    ax.set_ylabel("frequency with load (Hz)")
    ax.set_title("torsion sail, E = 4.5e13 Pa, n = 30: flat-state modes", fontsize=9)
    ax.legend(fontsize=8)
    bx.loglog([r["relative_epsilon"] for r in noise], [r["elastic_relative_shift"] for r in noise], "o-",
              label="Exudyn Jacobian of the lit tree")
    central = elastic_relative_shift(lit["exudyn"], dark_exudyn)
    bx.axhline(max(central, 1e-16), color="k", ls="--", lw=0.8, label="central-difference load stiffness")
    bx.set_xlabel("Exudyn relativeEpsilon")
    bx.set_ylabel("max |Δω²|/ω² (lit vs unlit)")
    bx.set_title("the load's linear effect is nil; forward differences are not", fontsize=9)
    bx.legend(fontsize=8)
    save_figure(fig, out / "stability_linear.png")
    return {"rows": rows, "noise": noise}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=str(Path(__file__).parent / "figures"))
    run(ap.parse_args(argv).out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
