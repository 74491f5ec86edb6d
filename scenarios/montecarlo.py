"""Random multi-mode defects (issue 9): failure probability and failure-time spread against E.

The paper's torsion sail (h = 1 µm, I₀ = 0.1 GW/m², n = 30, 6 s) with random defects of K = 10 modes
ν_k = k/2, spectrum β = 1, RMS equal to the a₀ = 10 µm sine's (shapes.multimode_profile), seeds 0…N−1 at
E = 0.1, 1, 10, 100 × E_cr,max of the ν = 3/2 sine; the same sweep as `lightsail-mbs montecarlo`
(lightsail_mbs.montecarlo), resumable through its store. Per E: runs, failures, P(fail) with its 95 %
Wilson interval, median and quartiles of the failure time.
Writes montecarlo.png and montecarlo.csv. Usage: python scenarios/montecarlo.py [--out DIR] [--seeds N]
[--solver reduced|exudyn] [--quick]
"""
from __future__ import annotations

import sys
from dataclasses import asdict
from pathlib import Path

import numpy as np

from lightsail_mbs import SailParameters
from lightsail_mbs.studies import montecarlo
from lightsail_mbs.model import theory
from lightsail_mbs.paper.common import new_figure, print_table, save_figure, scenario_parser, write_csv

MODULUS_RATIOS = (0.1, 1.0, 10.0, 100.0)     # E / E_cr,max (ν = 3/2 sine)


def run(out, *, seeds: int = 50, solver: str = "reduced", quick: bool = False, workers=None,
        progress: bool = True) -> list[dict]:
    out = Path(out)
    base = SailParameters(model="torsion", n=10 if quick else 30, t_final=2.0 if quick else 6.0)
    critical = theory.critical_modulus_max(base)
    values = [r * critical for r in MODULUS_RATIOS]
    found = montecarlo.run(base, "youngs_modulus", values, seeds, out / "store" / "montecarlo", solver=solver,
                           workers=workers, progress=progress)
    rows = [dict(E_Pa=r.value, E_over_E_cr=r.value / critical, **{k: v for k, v in asdict(r).items() if k != "value"})
            for r in found]
    write_csv(out / "montecarlo.csv", rows)
    print_table(f"Monte Carlo: {seeds} random multi-mode defects per E, torsion n = {base.n}, "
                f"{base.t_final:g} s ({solver})", rows)
    plot(out / "montecarlo.png", rows, seeds)
    return rows


def plot(path, rows, seeds) -> None:
    fig, ax = new_figure(1, 2, size=(10.0, 4.0))
    x = np.array([r["E_over_E_cr"] for r in rows])
    p = np.array([r["probability"] for r in rows])
    err = np.array([[r["probability"] - r["probability_low"] for r in rows],
                    [r["probability_high"] - r["probability"] for r in rows]])
    ax[0, 0].errorbar(x, p, yerr=err, fmt="o-", capsize=3)
    ax[0, 0].set_xscale("log")
    ax[0, 0].set_xlabel("E / E_cr,max (ν = 3/2 sine)")
    ax[0, 0].set_ylabel(f"P(fail), 95 % Wilson interval ({seeds} seeds)")
    timed = [r for r in rows if r["failure_time_median"] is not None]
    ax[0, 1].errorbar([r["E_over_E_cr"] for r in timed], [r["failure_time_median"] for r in timed],
                      yerr=[[r["failure_time_median"] - r["failure_time_q25"] for r in timed],
                            [r["failure_time_q75"] - r["failure_time_median"] for r in timed]], fmt="s-", capsize=3)
    ax[0, 1].set_xscale("log")
    ax[0, 1].set_xlabel("E / E_cr,max (ν = 3/2 sine)")
    ax[0, 1].set_ylabel("failure time: median and quartiles (s)")
    fig.suptitle("Random multi-mode defects: how often and how fast the sail fails", fontsize=10)
    save_figure(fig, path)


def main(argv=None) -> int:
    parser = scenario_parser(__doc__, "n = 10, 2 s runs (smoke test)")
    parser.add_argument("--seeds", type=int, default=50)
    args = parser.parse_args(argv)
    run(args.out, seeds=args.seeds, solver=args.solver, quick=args.quick)
    return 0


if __name__ == "__main__":
    sys.exit(main())
