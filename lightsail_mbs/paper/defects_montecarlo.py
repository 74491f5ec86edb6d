"""Random multi-mode defects: failure probability and failure-time spread against E.

The paper's torsion sail (h = 1 µm, I₀ = 0.1 GW/m², n = 30, 6 s) with random defects of K = 10 modes
ν_k = k/2, spectrum β = 1, RMS equal to the a₀ = 10 µm sine's (shapes.multimode_profile), seeds 0…N−1
(N = 50) at E = 0.1, 1, 10, 100 × E_cr,max of the ν = 3/2 sine; the same sweep as
`lightsail-mbs montecarlo` (studies.montecarlo). Per E: runs, failures, P(fail) with its 95 % Wilson
interval, median and quartiles of the failure time.

Writes montecarlo.png and montecarlo.csv; the runs go to the store OUT/store/montecarlo.
Quick: n = 10, 2 s runs. Run: lightsail-mbs reproduce --scenario montecarlo, or
python scenarios/montecarlo.py [--seeds N].
"""

from __future__ import annotations

import functools
from dataclasses import asdict
from pathlib import Path

import numpy as np

from lightsail_mbs import RunSettings, SailParameters
from lightsail_mbs.model import theory
from lightsail_mbs.paper.common import publish, sweep_options
from lightsail_mbs.studies import montecarlo
from lightsail_mbs.viz.plots import new_figure, save_figure

NAME = "montecarlo"
MODULUS_RATIOS = (0.1, 1.0, 10.0, 100.0)  # E / E_cr,max (ν = 3/2 sine)
SEEDS = 50


def base_case(quick: bool = False) -> tuple[SailParameters, RunSettings]:
    return (SailParameters(model="torsion", n=10 if quick else 30), RunSettings(t_final=2.0 if quick else 6.0))


def compute(
    *, seeds=SEEDS, solver="reduced", quick=False, store_dir, workers=None, scheduler=None, progress=True
) -> list[dict]:
    """Run (or resume) the sweep; one row per E."""
    base, settings = base_case(quick)
    critical = theory.critical_modulus_max(base)
    found = montecarlo.run(
        base,
        "youngs_modulus",
        [r * critical for r in MODULUS_RATIOS],
        seeds,
        store_dir,
        solver=solver,
        settings=settings,
        workers=workers,
        scheduler=scheduler,
        progress=progress,
    )
    return [
        dict(E_Pa=r.value, E_over_E_cr=r.value / critical, **{k: v for k, v in asdict(r).items() if k != "value"})
        for r in found
    ]


def run(out, *, solver="reduced", quick=False, seeds: int = SEEDS, **options) -> dict:
    """The study into `out`; options: workers, scheduler, store, progress (paper package docstring)."""
    out = Path(out)
    rows = compute(seeds=seeds, solver=solver, quick=quick, **sweep_options(out, NAME, **options))
    base, settings = base_case(quick)
    title = (
        f"Monte Carlo: {seeds} random multi-mode defects per E, torsion n = {base.n}, {settings.t_final:g} s ({solver})"
    )
    return publish(out, "montecarlo", rows, f"{title} ({solver})", functools.partial(plot, seeds=seeds))


def plot(path, rows, seeds) -> Path:
    """Left: P(fail) with its Wilson interval against E/E_cr,max; right: median failure time and quartiles."""
    fig, ax = new_figure(1, 2, size=(10.0, 4.0))
    x = np.array([r["E_over_E_cr"] for r in rows])
    p = np.array([r["probability"] for r in rows])
    err = np.array(
        [
            [r["probability"] - r["probability_low"] for r in rows],
            [r["probability_high"] - r["probability"] for r in rows],
        ]
    )
    ax[0, 0].errorbar(x, p, yerr=err, fmt="o-", capsize=3)
    ax[0, 0].set_xscale("log")
    ax[0, 0].set_xlabel("E / E_cr,max (ν = 3/2 sine)")
    ax[0, 0].set_ylabel(f"P(fail), 95 % Wilson interval ({seeds} seeds)")
    timed = [r for r in rows if r["failure_time_median"] is not None]
    ax[0, 1].errorbar(
        [r["E_over_E_cr"] for r in timed],
        [r["failure_time_median"] for r in timed],
        yerr=[
            [r["failure_time_median"] - r["failure_time_q25"] for r in timed],
            [r["failure_time_q75"] - r["failure_time_median"] for r in timed],
        ],
        fmt="s-",
        capsize=3,
    )
    ax[0, 1].set_xscale("log")
    ax[0, 1].set_xlabel("E / E_cr,max (ν = 3/2 sine)")
    ax[0, 1].set_ylabel("failure time: median and quartiles (s)")
    fig.suptitle("Random multi-mode defects: how often and how fast the sail fails", fontsize=10)
    return save_figure(fig, path)
