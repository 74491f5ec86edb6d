"""Heat from material damping in the oscillating TnT sail (the paper's "limitations": higher tension →
higher frequency → more heat).

The paper's TnT sail (h = 1 µm, ν = 3/2, I₀ = 0.1 GW/m², a₀ = 10 µm, n = 30, extensible slices with
E = 1e11 Pa, 6 s) with its bending springs on (k_T = EI/l, so curvature dissipates too) and material
damping c = β k on every spring (SailParameters.stiffness_damping; a loss factor η at ω is β = η/ω), at
tensions from T_cr,max/100 (fails) to 10⁴ T_cr,max, each with and without damping. Per case: the
oscillation frequency, the heat D(t_end) = ∫ P dt (Result.dissipated_energy), the mean power D/t_end,
that power over the laser power a sail of absorptivity 1e-6 would absorb, and whether and when the
sail fails with and without damping.

The heat is a second-order quantity (the damper's power is c·q̇², q̇ the small oscillation's rate), so its
relative error is far larger than the state's: at the reduced solver's default rtol 1e-6 the mean heat
is 12 times too high at 10 T_cr,max and 12 % too high at 1000 T_cr,max, while rtol 1e-8 and 1e-9 agree to
1e-4. The reduced solver runs these cases at HEAT_OPTIONS' tighter tolerance; Exudyn at its defaults.

Writes dissipation.png and dissipation.csv; the runs go to the store OUT/store/dissipation.
Quick: n = 10, 1 s runs. Run: lightsail-mbs reproduce --scenario dissipation, or
python scenarios/dissipation.py [--beta S].
"""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np

from lightsail_mbs import paper_case, paper_settings
from lightsail_mbs.analysis.frequencies import angle_frequency
from lightsail_mbs.model import theory
from lightsail_mbs.paper.common import publish, sweep_options
from lightsail_mbs.studies.sweep import run_cases
from lightsail_mbs.viz.plots import new_figure, save_figure

NAME = "dissipation"
TENSION_RATIOS = (1e-2, 1e1, 1e2, 1e3, 1e4)  # T / T_cr,max
REFERENCE_ABSORPTIVITY = 1e-6
BETA = 1e-4  # s
HEAT_OPTIONS = {"reduced": {"rtol": 1e-8}}  # per solver: the tolerance the heat needs (module docstring)


def cases(beta: float = BETA, quick: bool = False) -> list:
    """The sails: per tension ratio, undamped then damped with β."""
    base = paper_case("tnt-stable", bending=True, **(dict(n=10) if quick else {}))
    critical = theory.critical_tension_max(base)
    return [base.replace(tension=r * critical, stiffness_damping=b) for r in TENSION_RATIOS for b in (0.0, beta)]


def settings(quick: bool = False):
    return paper_settings("tnt-stable", **(dict(t_final=1.0) if quick else {}))


def row(p, record: dict, result) -> dict:
    out = dict(
        T_N=p.tension,
        T_over_T_cr=p.tension / theory.critical_tension_max(p),
        beta_s=p.stiffness_damping,
        failed=record.get("failed"),
        failure_time_s=record.get("failure_time"),
        error=record.get("error"),
    )
    if result is not None:
        heat = float(result.dissipated_energy[-1])
        power = heat / result.time[-1]
        laser = REFERENCE_ABSORPTIVITY * p.intensity * p.length * p.width
        out.update(
            frequency_Hz=None if result.failed else angle_frequency(result),
            max_amplitude_ratio=result.max_amplitude_ratio,
            heat_J=heat,
            mean_power_W=power,
            power_over_absorbed=power / laser,
        )
    return out


def compute(
    *, beta=BETA, solver="reduced", quick=False, store_dir, workers=None, scheduler=None, progress=True
) -> list[dict]:
    """Run (or find in the store) every case; one row per case."""
    params = cases(beta, quick)
    done = run_cases(
        params,
        store_dir,
        settings(quick),
        solver=solver,
        workers=workers,
        scheduler=scheduler,
        label="dissipation",
        progress=progress,
        options=HEAT_OPTIONS.get(solver),
    )
    return [row(p, record, result) for p, (record, result) in zip(params, done)]


def run(out, *, solver="reduced", quick=False, beta: float = BETA, **options) -> dict:
    """The study into `out`; options: workers, scheduler, store, progress (paper package docstring)."""
    out = Path(out)
    rows = compute(beta=beta, solver=solver, quick=quick, **sweep_options(out, NAME, **options))
    title = (
        f"Material damping β = {beta:g} s in the TnT sail (bending on), {settings(quick).t_final:g} s "
        f"({solver}); absorbed reference: α = {REFERENCE_ABSORPTIVITY:g}"
    )
    return publish(out, "dissipation", rows, title, functools.partial(plot, beta=beta))


def plot(path, rows, beta) -> Path:
    """Left: mean dissipated power against frequency (damped stable runs); right: max amplitude ratio
    against T/T_cr,max with and without damping."""
    fig, ax = new_figure(1, 2, size=(10.0, 4.0))
    damped = [r for r in rows if r["beta_s"] > 0 and r.get("frequency_Hz")]
    f = np.array([r["frequency_Hz"] for r in damped])
    power = np.array([r["mean_power_W"] for r in damped])
    ax[0, 0].loglog(f, power, "o-", label=f"β = {beta:g} s")
    if f.size:
        ax[0, 0].loglog(f, power[-1] * (f / f[-1]) ** 2, "k:", lw=0.8, label="∝ f² (reference)")
    for r in damped:
        ax[0, 0].annotate(f"{r['T_over_T_cr']:.0e} T_cr", (r["frequency_Hz"], r["mean_power_W"]), fontsize=7)
    ax[0, 0].set_xlabel("oscillation frequency (Hz)")
    ax[0, 0].set_ylabel("mean dissipated power (W)")
    ax[0, 0].legend(fontsize=8)
    for b, style in ((0.0, "s--"), (beta, "o-")):
        mine = [r for r in rows if r["beta_s"] == b and r.get("max_amplitude_ratio") is not None]
        ax[0, 1].semilogx(
            [r["T_over_T_cr"] for r in mine], [r["max_amplitude_ratio"] for r in mine], style, label=f"β = {b:g} s"
        )
    ax[0, 1].axhline(2.0, color="k", lw=0.8, ls=":")
    ax[0, 1].set_xlabel("T / T_cr,max")
    ax[0, 1].set_ylabel("max amplitude / a₀ (2: failure)")
    ax[0, 1].legend(fontsize=8)
    fig.suptitle("Heat from material damping in the oscillating TnT sail", fontsize=10)
    return save_figure(fig, path)
