"""The film twin of the uncertainty estimate (:mod:`lightsail_mbs.solvers.uncertainty`, item 4): its case, and
what its answer says of a real film against the ideal defect."""

from __future__ import annotations

import math

from lightsail_mbs.model import film
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
