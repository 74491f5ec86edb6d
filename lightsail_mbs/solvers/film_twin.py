"""The film twin of the uncertainty estimate (:mod:`lightsail_mbs.solvers.uncertainty`, item 4): its case, what its
answer says of a real film against the ideal defect, and what it says of the probe twin.

**The film bounds the probe.** The probe twin starts the base run from the shape plus a seeded roughness of
PROBE_LEVEL · a₀, sine coefficients p_j at the chain's wavenumbers q_j = πj/L, j = 1 … n
(shapes.roughness_coefficients); the film twin starts it from the shape plus a film, coefficients (a_j, b_j) at
the same q_j (model.film.film_profile; for a case with its own film, the change from its seed to the next). While
a perturbation stays small the answer responds to it linearly, mode by mode, so with

    c = max_j |p_j| / √(a_j² + b_j²)

the probe is at most c times the film twin's perturbation at every wave, and S = |q_probe − q_base| is estimated
by c · |q_film − q_ref| (q_ref: the run of the film twin's options; an estimate, not a bound: the modes' responses
could cancel in the film's sum and not in the probe's, which the margins below leave room for). On the paper's
chains c = 3.8e-8 (the rigid sail, a₀ = 1 mm: 1.8e-5); on the 160 seeded chains of validation/accuracy.md, 6e-9 to
3e-5 (median 8e-7). The estimate stands for the probe only where the film twin finds the run defect-dominated (it
moves q by at most FILM_TOL · |q|: the film's waves have stayed small) and it is at most CONDITION_TOL · |q|; there
the probe twin is not run. Where the film is roughness-dominated its waves have grown beyond the linear regime and
say nothing of a perturbation a million times smaller: the probe runs. A run the probe would call ill-conditioned
(S > CONDITION_TOL · |q|) would, linearly, be moved by the film by more than CONDITION_TOL · |q| / c, ≥ 3 |q|:
roughness-dominated by a factor of 3000, so the probe runs for it. The film twin runs at the loose twin's options
(generalized-α: twice the step) and the probe at the base run's, whose grid-scale waves may grow at another rate
(uncertainty's docstring, item 2); validation/accuracy.md compares the verdicts with those of the probe run on
every case. Sheets keep their probe (its tile offsets are no sum of the film's modes).
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.model import film, shapes
from lightsail_mbs.model.parameters import SailParameters

FILM_TOL = 1e-3  # defect-dominated: the film twin moves q by ≤ FILM_TOL · |q|


def film_twin(params: SailParameters) -> tuple[SailParameters | None, str]:
    """(the film twin's case, what it is): the case with the reference film (model.film.REFERENCE_FILM) when
    it has none, with its own film at the next seed when it has one (a chain's line scan, a sheet's surface)."""
    if params.film_rms == 0:
        ref = film.REFERENCE_FILM
        twin = params.replace(film_rms=ref.rms, film_correlation_length=ref.correlation_length, film_hurst=ref.hurst)
        return twin, f"the reference film ({ref.describe()})"
    return params.replace(film_seed=params.film_seed + 1), f"the same film at seed {params.film_seed + 1}"


def film_sensitivity(records: dict, text: str, quantity: str, reference: str = "base") -> dict:
    """What the film twin says (module docstring, item 4): its answer (at the options of `reference`), the shift
    from the answer of `reference` (the run of the same options: "loose", or "base" in the fallback), and the
    verdict "defect-dominated" (shift ≤ FILM_TOL · |q|) or "roughness-dominated", with, for a case without a
    film, the RMS below which the ideal-defect answer holds, estimated as linear in the film's RMS."""
    if "film" not in records:
        return {"assessed": False, "film": text}
    twin, base = records["film"], records[reference]
    if twin["error"] is not None:
        return {"assessed": False, "film": text, "error": twin["error"]}
    shift = abs(twin["value"] - base["value"]) if twin["failed"] == base["failed"] else math.inf
    relative = shift / abs(base["value"]) if base["value"] else math.inf
    verdict = "defect-dominated" if relative <= FILM_TOL else "roughness-dominated"
    holds_below = None
    if verdict == "roughness-dominated" and text.startswith("the reference film") and math.isfinite(relative):
        holds_below = film.REFERENCE_FILM.rms * FILM_TOL / relative
    return {
        "assessed": True,
        "film": text,
        "quantity": quantity,
        "value": twin["value"],
        "failed": twin["failed"],
        "shift": shift,
        "relative_shift": relative,
        "verdict": verdict,
        "holds_below": holds_below,
    }


def probe_ratio(params: SailParameters, probe_amplitude: float) -> float:
    """c of the module docstring: the largest ratio, over the chain's modes, of the probe's sine coefficient (a
    roughness of `probe_amplitude`, m, seed shapes.PERTURBATION_SEED) to the film twin's perturbation; inf for a
    sheet or where the film twin puts nothing into a mode."""
    if params.model == "sheet":
        return math.inf
    twin, _ = film_twin(params)
    probe = np.abs(shapes.roughness_coefficients(params, probe_amplitude, shapes.PERTURBATION_SEED))
    seed = twin.film_seed
    heights = film.film_profile(film.of_case(twin), params.length, params.n, seed)
    cosine, sine = heights.cosine, heights.sine
    if params.film_rms != 0:  # the film twin changes the case's film from its seed to the next
        own = film.film_profile(film.of_case(params), params.length, params.n, params.film_seed)
        cosine, sine = cosine - own.cosine, sine - own.sine
    change = np.hypot(cosine, sine)
    return float(np.max(probe / change)) if np.all(change > 0) else math.inf


def probe_estimate(params: SailParameters, records: dict, reference: str, probe_amplitude: float, limit: float):
    """S ≈ c · |q_film − q_ref| (module docstring; an estimate, not a bound) where the film twin of `records` ran,
    gave the verdict of the run of options `reference`, moved its answer by at most FILM_TOL · |q| and the estimate
    is at most `limit` (the probe's); else None: the probe twin runs."""
    twin, base = records.get("film"), records[reference]
    if twin is None or twin["error"] is not None or twin["failed"] != base["failed"]:
        return None
    shift = abs(twin["value"] - base["value"])
    if shift > FILM_TOL * abs(base["value"]):
        return None
    estimate = probe_ratio(params, probe_amplitude) * shift
    return estimate if estimate <= limit else None
