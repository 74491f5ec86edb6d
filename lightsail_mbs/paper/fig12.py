"""Paper Fig. 12, made fine: the TnT sail's stability map (k_T = 0, inextensible slices as in fig10_11.py) over
thickness h = 0.01–10 µm for modes ν = 1, 3/2, 2 (I₀ = 0.1 GW/m², a₀ = 0.01 mm, n = 30, 6 s runs).
At each h and ν the stable/failed boundary in T is bisected in log space to a bracket ≤ 1.5 wide and
compared with T_cr,max (Eq. 10, independent of h and ν); every boundary is bisected again with 12 s
runs to show how it depends on the run time. Writes fig12.png, fig12_boundaries.csv, fig12_points.csv.
Run: lightsail-mbs reproduce --figure 12 --out DIR [--quick].
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs import RunSettings, paper_case
from lightsail_mbs.paper.common import stability_map_figure
from lightsail_mbs.studies.tables import print_table

FIGURES = (12,)
THICKNESSES = np.logspace(-8, -5, 7)  # m: 0.01 … 10 µm, half decades
MODES = (1.0, 1.5, 2.0)


def run(out, *, solver="exudyn", quick=False, **options) -> dict:
    """The figures into `out`; options: workers, scheduler, store, progress (paper package docstring)."""
    base = paper_case("tnt-stable", n=30, axial_springs=False)
    settings = RunSettings(t_final=6.0)
    thicknesses = THICKNESSES
    if quick:
        base, settings, thicknesses = base.replace(n=10), RunSettings(t_final=1.0), np.logspace(-7, -5, 3)
    rows = stability_map_figure(
        out,
        "fig12",
        12,
        base,
        thicknesses,
        MODES,
        settings=settings,
        solver=solver,
        recheck_all=True,
        **options,
    )
    print_table(
        f"Fig. 12 — TnT map, {settings.t_final:g} s: boundary T vs T_cr,max (Eq. 10)",
        [
            {
                "h_um": r["thickness_m"] * 1e6,
                "mode": r["mode"],
                "T_cr_max_N": r["analytic"],
                "T_stable_N": r["stable_value"],
                "T_failed_N": r["unstable_value"],
                "ratio": r["ratio"],
                "runs": r["evaluations"],
                "status": r["status"],
                "ratio_2t": r["ratio_2t"],
            }
            for r in rows
        ],
    )
    return {"rows": rows}
