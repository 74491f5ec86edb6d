"""Paper Fig. 9, made fine: the torsion sail's stability map over thickness h = 0.01–10 µm (ν = 3/2,
I₀ = 0.1 GW/m², a₀ = 0.01 mm, n = 30, 6 s runs). At each h the stable/failed boundary in E is bisected
in log space to a bracket ≤ 1.5 wide and compared with E_cr,max (Eq. 8); every boundary is bisected again
with 12 s runs to show how it depends on the run time. Writes fig9.png, fig9_boundaries.csv, fig9_points.csv.
Run: lightsail-mbs reproduce --figure 9 --out DIR [--quick].
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs import RunSettings, SailParameters
from lightsail_mbs.paper.common import stability_map_figure
from lightsail_mbs.studies.tables import print_table

FIGURES = (9,)
THICKNESSES = np.logspace(-8, -5, 7)  # m: 0.01 … 10 µm, half decades


def run(out, *, solver="exudyn", quick=False, **options) -> dict:
    """The figures into `out`; options: workers, scheduler, store, progress (paper package docstring)."""
    base = SailParameters(model="torsion", defect_mode=1.5, n=30)
    settings = RunSettings(t_final=6.0)
    thicknesses = THICKNESSES
    if quick:
        base, settings, thicknesses = base.replace(n=10), RunSettings(t_final=1.0), np.logspace(-7, -5, 3)
    rows = stability_map_figure(
        out,
        "fig9",
        9,
        base,
        thicknesses,
        [1.5],
        settings=settings,
        solver=solver,
        recheck_all=True,
        **options,
    )
    print_table(
        f"Fig. 9 — torsion map, ν = 3/2, {settings.t_final:g} s: boundary E vs E_cr,max (Eq. 8)",
        [_short(r) for r in rows],
    )
    return {"rows": rows}


def _short(r: dict) -> dict:
    return {
        "h_um": r["thickness_m"] * 1e6,
        "E_cr_max_Pa": r["analytic"],
        "E_stable_Pa": r["stable_value"],
        "E_failed_Pa": r["unstable_value"],
        "ratio": r["ratio"],
        "runs": r["evaluations"],
        "status": r["status"],
        "ratio_2t": r["ratio_2t"],
    }
