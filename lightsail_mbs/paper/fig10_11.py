"""Paper Figs 10–11: the TnT sail (k_T = 0; h = 1 µm, ν = 3/2, I₀ = 0.1 GW/m², a₀ = 0.01 mm, n = 30, 6 s).

Fig. 10: T = 3.34e-3 N (1000 × T_cr,max = 3.34e-6 N) — stable oscillatory; Fig. 11: T = 3.34e-8 N
(T_cr,max / 100) — fails (the paper: at roughly 2 s). The slices are run in their inextensible limit
(axial_springs=False): the paper gives no E, and with E = 1e11 Pa the springs (k_s ≈ 2.9e6 N/m) stretch
by T/k_s ≈ 1e-9 m, while their ~10⁵ rad/s axial modes make a run 20–90× slower. Checked with the
reduced solver: over 1 s the stable case's angles agree within 5e-9 rad (θ ~ 1e-4 rad), frequency
2.811 Hz both; the soft case fails at 2.102 s with springs, 2.107 s without.
Writes fig10.png, fig11.png, fig10_11_angles_{stable,soft}.csv and fig10_11_summary.csv.
Run: lightsail-mbs reproduce --figure 10 --out DIR [--quick].
"""

from __future__ import annotations

from lightsail_mbs import RunSettings, paper_case
from lightsail_mbs.model import theory
from lightsail_mbs.paper.common import angle_history_figures

FIGURES = (10, 11)


def describe(p) -> str:
    return (
        f"TnT, h = {p.thickness * 1e6:g} µm, ν = {p.defect_mode:g}, T = {p.tension:.3g} N "
        f"(T_cr,max = {theory.critical_tension_max(p):.3g} N)"
    )


def run(out, *, solver="exudyn", quick=False, **options) -> dict:
    """The figures into `out`; options: workers, scheduler, store, progress (paper package docstring)."""
    changes = dict(n=10) if quick else {}
    settings = RunSettings(t_final=1.0 if quick else 6.0)
    cases = {
        "stable": paper_case("tnt-stable", axial_springs=False, **changes),
        "soft": paper_case("tnt-soft", axial_springs=False, **changes),
    }
    rows = angle_history_figures(
        out,
        "fig10_11",
        cases,
        [(10, "stable", None), (11, "soft", None)],
        describe,
        settings=settings,
        solver=solver,
        columns=lambda p: dict(T_N=p.tension, T_cr_max_N=theory.critical_tension_max(p)),
        title=f"Figs 10–11 — TnT sail, h = 1 µm, ν = 3/2, {settings.t_final:g} s",
        **options,
    )
    return {"rows": rows}
