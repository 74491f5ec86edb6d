"""
A Monte Carlo over films
========================

No film is flat: a real film carries roughness at every wavelength (a K-correlation spectrum of RMS σ,
correlation length ξ and Hurst exponent H, :doc:`../film`). One film is one draw, so the failure time of
a rough sail is a distribution. Here the paper's soft torsion sail (Fig. 7, at its n = 30) carries
its ν = 3/2 defect plus films of σ = 1 nm drawn from 12 seeds; each run goes through a resumable store.
The failure probability is given with its 95 % Wilson interval and the mean failure time with its 95 %
confidence half-width, next to the ideal sail's failure time with its numerical uncertainty.

From the command line::

    lightsail-mbs montecarlo torsion-soft --film-rms 1e-9 --t-final 4 --over film --seeds 12 \\
        --solver reduced --store runs/films
"""

import tempfile

import matplotlib.pyplot as plt

from lightsail_mbs import RunSettings, paper_case, solve
from lightsail_mbs.base.formatting import with_uncertainty
from lightsail_mbs.studies import montecarlo
from lightsail_mbs.studies.sweep import run_sweep

SEEDS = 12
settings = RunSettings(t_final=4.0)
base = paper_case("torsion-soft", film_rms=1e-9)

ideal = solve(base.replace(film_rms=0.0), "reduced", settings=settings)
cases = montecarlo.cases(
    base, "youngs_modulus", [base.youngs_modulus], SEEDS, "reduced", settings=settings, over="film"
)
records = run_sweep(cases, tempfile.mkdtemp(), workers=1, progress=False)
(row,) = montecarlo.summarise([base.youngs_modulus], SEEDS, records)

# %%
# The numbers: the ideal sine's answer with its ±, then the films'.
print(f"ideal sine defect: {ideal.answer_text()}; warnings: {ideal.warnings or 'none'}")
print(
    f"{row.runs} films (σ = {base.film_rms:g} m): {row.failures} failed, "
    f"P(fail) = {row.probability:.2f} (95 % CI {row.probability_low:.2f}–{row.probability_high:.2f})"
)
print(
    f"mean failure time {with_uncertainty(row.failure_time_mean, row.failure_time_mean_halfwidth)} s (95 % CI), "
    f"median {row.failure_time_median:.3f} s, 5–95 % {row.failure_time_q05:.3f}–{row.failure_time_q95:.3f} s"
)

times = [r["failure_time"] for r in records if r["status"] == "ok" and r["failed"]]
fig, ax = plt.subplots(figsize=(7, 3.2))
ax.hist(times, bins=8, color="tab:blue", alpha=0.7, label=f"{len(times)} films, σ = 1 nm")
ax.axvline(ideal.failure_time, color="black", ls="--", label="ideal sine defect")
ax.axvspan(
    row.failure_time_mean - row.failure_time_mean_halfwidth,
    row.failure_time_mean + row.failure_time_mean_halfwidth,
    color="tab:red",
    alpha=0.25,
    label="mean ± 95 % CI",
)
ax.set_xlabel("failure time t_f (s)")
ax.set_ylabel("films")
ax.legend(fontsize=8, loc="upper center")
fig.tight_layout()
