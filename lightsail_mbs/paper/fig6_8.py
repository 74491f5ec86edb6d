"""Paper Figs 6–8: the torsion sail (h = 1 µm, ν = 3/2, I₀ = 0.1 GW/m², a₀ = 0.01 mm, n = 30, 6 s).

Fig. 6: E = 4.5e13 Pa (100 × E_cr,max = 4.5e11 Pa) — stable oscillatory; Fig. 7: E = 4.5e9 Pa
(E_cr,max / 100) — fails; Fig. 8: the soft run's first 100 ms, where it still looks stable.
Writes fig6.png, fig7.png, fig8.png, fig6_8_angles_{stable,soft}.csv (θ of the plotted slices)
and fig6_8_summary.csv. Run: lightsail-mbs reproduce --figure 6 --out DIR [--quick].
"""

from __future__ import annotations

from lightsail_mbs import RunSettings, paper_case
from lightsail_mbs.model import theory
from lightsail_mbs.paper.common import angle_history_figures

FIGURES = (6, 7, 8)


def describe(p) -> str:
    return (
        f"torsion, h = {p.thickness * 1e6:g} µm, E = {p.youngs_modulus:.2g} Pa "
        f"(E_cr,max = {theory.critical_modulus_max(p):.2g} Pa)"
    )


def run(out, *, solver="exudyn", quick=False, **options) -> dict:
    """The figures into `out`; options: workers, scheduler, store, progress (paper package docstring)."""
    changes = dict(n=10) if quick else {}
    settings = RunSettings(t_final=1.0 if quick else 6.0)
    cases = {"stable": paper_case("torsion-stable", **changes), "soft": paper_case("torsion-soft", **changes)}
    rows = angle_history_figures(
        out,
        "fig6_8",
        cases,
        [(6, "stable", None), (7, "soft", None), (8, "soft", 0.1)],
        describe,
        settings=settings,
        solver=solver,
        columns=lambda p: dict(E_Pa=p.youngs_modulus, E_cr_max_Pa=theory.critical_modulus_max(p)),
        title=f"Figs 6–8 — torsion sail, h = 1 µm, ν = 3/2, {settings.t_final:g} s",
        **options,
    )
    return {"rows": rows}
