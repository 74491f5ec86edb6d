"""The failure located by event, and output sampling that follows the case's own time scales.

Every solver samples its output on ``settings.sample_times()`` (skeleton rule 2), and the failure time
t_f is the first root of a(t) = ratio · a(0) on those samples: between the samples k − 1 and k that
bracket it (a_(k−1) < ratio · a(0) ≤ a_k), the root of the line through them,

    t_lin = t_(k−1) + (ratio · a(0) − a_(k−1)) / (a_k − a_(k−1)) · (t_k − t_(k−1))

(model.failure.failure_time, at the sample model.failure.crossing finds). Its **location error** is
estimated from the samples themselves: the root in the bracket of the parabola through the samples
k − 2, k − 1 and k, t_quad, differs from t_lin by about the line's own error (the line errs by
~a'' Δt²/(8 a'), the parabola by O(Δt³)), and the bound is

    E_loc = LOCATION_SAFETY · |t_lin − t_quad|.

A bracket is **unresolved** (E_loc = inf) when it starts at the first sample (k = 1: no parabola, and
the amplitude at t = 0 says nothing about how it grew), or when the amplitude grows by more than
MAX_BRACKET_GROWTH across it (a sail that cups 65,000-fold within one output interval: a line through
the two ends means nothing).

**Refinement.** When E_loc > LOCATE_RTOL · t_f, the run is repeated with an output interval that puts
enough samples in the bracket for the line to be within the tolerance (E_loc ∝ Δt²: the interval
divided by R = 2√(E_loc/(LOCATE_RTOL · t_f)), at least MIN_REFINEMENT; UNRESOLVED_REFINEMENT for an
unresolved bracket), ending at min(t_final, 2 t_k + Δt) when the run stops at failure (so that twins of
the uncertainty estimate that fail a little later still fail within it), and again until E_loc is within
the tolerance, MAX_REFINEMENTS times at most. The sample count is capped by memory (SAMPLE_MEMORY numbers
in all); where the cap stops the refinement, E_loc stays in the ± and a warning says so. Every rerun is a
whole run of the same solver with the same options: the reported Result is the last one; it keeps the
settings asked for (``solve`` repeats the same refinement from them), and ``info["sampling"]`` the
output interval and end of the run it is. A rerun that does not fail where the coarser run did (Exudyn
ties its step to the output interval; near a round-off floor the step decides) is not reported as a
survivor cut short at its shortened t_final: the coarser run is kept, unlocated, with a warning.

**Default sampling.** With ``output_interval=None`` the interval is min(1 ms, t_final/1000), unless the
case has a faster time scale τ: the finite-amplitude time t_c = 1/(k√(g₀a₀)) (Eq. 16's scale) or a
Gaussian beam's cupping time √(2a₀/Δg), with Δg = g₀(1 − exp(−2d²/w²)) the lag of the sail's farthest
point (at distance d from the beam's centre) behind its centre; then it is τ/SAMPLES_PER_TIME_SCALE,
but no finer than the memory cap allows over t_final (the refinement then locates the failure).
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.model import failure, planforms

LOCATION_SAFETY = 2.0  # E_loc = LOCATION_SAFETY · |t_lin − t_quad|
LOCATE_RTOL = 1e-6  # a failure time is located to E_loc ≤ LOCATE_RTOL · t_f, or its run is refined
MAX_BRACKET_GROWTH = 1.5  # a bracket across which the amplitude grows more than this is unresolved
MIN_REFINEMENT = 4  # a refined run divides the output interval by at least this
UNRESOLVED_REFINEMENT = 100  # ... and by this for an unresolved bracket
MAX_REFINEMENTS = 6  # reruns at most (each at least MIN_REFINEMENT× finer)
SAMPLES_PER_TIME_SCALE = 20  # default output interval: the case's fastest time scale / this
SAMPLE_MEMORY = 4e6  # numbers the samples of one run may hold (32 MB), for the default and refined intervals


def location_error(time: np.ndarray, amplitude: np.ndarray, ratio: float) -> float | None:
    """E_loc of the failure time found on the samples (module docstring): LOCATION_SAFETY · |t_lin − t_quad|
    (s), inf for an unresolved bracket, None when the run did not fail."""
    time, amplitude = np.asarray(time, float), np.asarray(amplitude, float)
    k = failure.crossing(amplitude, ratio)
    if k is None:
        return None
    if k < 2 or amplitude[k] > MAX_BRACKET_GROWTH * amplitude[k - 1]:
        return math.inf
    limit = ratio * amplitude[0]
    t, a = time[k - 2 : k + 1], amplitude[k - 2 : k + 1]
    t_lin = failure.failure_time(time, amplitude, ratio)
    # the parabola through the three samples, in s = t − t_(k−1): a(s) = a₁ + b s + c s²
    h0, h2 = t[0] - t[1], t[2] - t[1]
    d0, d2 = (a[0] - a[1]) / h0, (a[2] - a[1]) / h2
    c = (d2 - d0) / (h2 - h0)
    b = d0 - c * h0
    roots = np.roots([c, b, a[1] - limit]) if c != 0 else np.array([(limit - a[1]) / b])
    roots = roots[np.isreal(roots)].real
    inside = roots[(roots >= -1e-12 * h2) & (roots <= h2 * (1 + 1e-12))]
    if not inside.size:
        return math.inf
    t_quad = t[1] + inside[np.argmin(np.abs(inside - (t_lin - t[1])))]
    return float(LOCATION_SAFETY * abs(t_lin - t_quad))


def peak_error(amplitude: np.ndarray) -> float:
    """How far the largest amplitude ratio may lie above the largest sample: LOCATION_SAFETY × the rise of
    the parabola through the largest sample and its two neighbours to its vertex, over a(0) (0 at either end)."""
    a = np.asarray(amplitude, float)
    j = int(np.argmax(a))
    if j == 0 or j == a.size - 1 or not a[0] > 0:
        return 0.0
    left, mid, right = a[j - 1], a[j], a[j + 1]
    curvature = left - 2 * mid + right
    if curvature >= 0:
        return 0.0
    return float(LOCATION_SAFETY * (right - left) ** 2 / (-8.0 * curvature) / a[0])


def numbers_per_sample(params) -> int:
    """The numbers one output sample holds: 12 per tile of a sheet, 8 per slice of a chain."""
    return 12 * planforms.mesh_of(params).count if params.model == "sheet" else 8 * params.n


def time_scales(params) -> dict:
    """The case's time scales that sampling must resolve (s): 'finite amplitude' t_c and, for a Gaussian
    beam, 'cupping' (module docstring); empty when the sail is flat or unlit."""
    g0, a0 = params.nominal_acceleration, params.defect_amplitude
    if not (g0 > 0 and a0 > 0):
        return {}
    wavenumber = 2.0 * math.pi * params.defect_mode / params.length
    scales = {"finite amplitude": 1.0 / (wavenumber * math.sqrt(g0 * a0))}
    if math.isfinite(params.beam_waist):
        centre_x = params.length / 2 if params.beam_centre is None else params.beam_centre
        d2 = max(centre_x, params.length - centre_x) ** 2
        if params.model == "sheet":
            centre_y = params.sheet_beam_centre_y
            d2 += max(centre_y, params.width - centre_y) ** 2
        lag = g0 * -math.expm1(-2.0 * d2 / params.beam_waist**2)
        if lag > 0:
            scales["cupping"] = math.sqrt(2.0 * a0 / lag)
    return scales


def default_sampling(params, settings: RunSettings) -> tuple[RunSettings, str | None]:
    """(settings, note): with output_interval None and a time scale τ of the case below
    SAMPLES_PER_TIME_SCALE × the default interval, the settings with interval τ/SAMPLES_PER_TIME_SCALE
    (no finer than the memory cap over t_final); otherwise the settings unchanged. The note says which
    time scale set the interval, or that the cap kept it coarser than τ asks."""
    if settings.output_interval is not None:
        return settings, None
    scales = time_scales(params)
    if not scales:
        return settings, None
    name = min(scales, key=scales.get)
    wanted = scales[name] / SAMPLES_PER_TIME_SCALE
    if wanted >= settings.sample_interval:
        return settings, None
    floor = settings.t_final * numbers_per_sample(params) / SAMPLE_MEMORY
    interval = max(wanted, floor)
    if interval >= settings.sample_interval:
        return settings, None
    note = f"output interval {interval:.3g} s: the {name} time {scales[name]:.3g} s / {SAMPLES_PER_TIME_SCALE}"
    if interval > wanted:
        note += f" asks {wanted:.3g} s, which the memory cap over t_final = {settings.t_final:g} s does not allow"
    return settings.replace(output_interval=interval), note


def refined_settings(result, settings: RunSettings) -> tuple[RunSettings | None, str | None]:
    """(settings of the next refinement, or None when the failure is located or cannot be refined; a note
    when the memory cap stops a refinement the tolerance asks for)."""
    time, amplitude, ratio = result.time, result.amplitude, settings.failure_ratio
    error = location_error(time, amplitude, ratio)
    if error is None or result.error is not None:
        return None, None
    k = failure.crossing(amplitude, ratio)
    tolerance = LOCATE_RTOL * float(result.failure_time)  # > 0: the crossing is at a sample k ≥ 1
    if error <= tolerance:
        return None, None
    width = float(time[k] - time[k - 1])
    factor = UNRESOLVED_REFINEMENT if math.isinf(error) else max(MIN_REFINEMENT, 2.0 * math.sqrt(error / tolerance))
    interval = width / math.ceil(factor)
    t_end = min(settings.t_final, 2.0 * float(time[k]) + width) if settings.stop_at_failure else settings.t_final
    floor = t_end * numbers_per_sample(result.params) / SAMPLE_MEMORY
    if interval < floor:
        interval = floor
        if interval > width / MIN_REFINEMENT:
            return None, (
                f"the failure time is located to ± {error:.2g} s only: resolving it needs output samples "
                f"finer than the memory cap allows over {t_end:.3g} s (set a shorter t_final)"
            )
    return settings.replace(t_final=t_end, output_interval=interval), None


def unconfirmed_note(result, settings: RunSettings, finer: RunSettings, refined) -> str:
    """The warning of a failure that a rerun sampled more finely does not reproduce (located_run)."""
    return (
        f"the failure at {float(result.failure_time):.6g} s is not confirmed: the rerun sampled every "
        f"{finer.sample_interval:.3g} s to locate it did not fail by {finer.t_final:.3g} s (largest amplitude "
        f"ratio {refined.max_amplitude_ratio:.4g}), so whether and when this sail fails depends on the solver's "
        f"numerics (a step that follows the output interval, tolerances or round-off), not on the physics "
        f"alone; the run sampled every {settings.sample_interval:.3g} s is kept, its failure unlocated"
    )


def located_run(module, params, settings: RunSettings, options: dict, progress: bool = False):
    """(Result, the settings it was made with): module.run on the case's default sampling
    (default_sampling), repeated at finer output intervals until its failure time is located
    (refined_settings). info["sampling"] records the interval and end of the run, the reruns and their wall
    time (also added to the Result's wall_time), the location error and the notes; a note that limits the
    location is also a warning. A rerun that does not fail where its coarser run did (its step or round-off
    decides the failure) is not reported: the coarser run is kept, with a warning (unconfirmed_note)."""
    settings, note = default_sampling(params, settings)
    result = module.run(params, settings, progress=progress, **options)
    notes = [note] if note else []
    refinements, earlier_wall = 0, 0.0
    while refinements < MAX_REFINEMENTS:
        finer, cap_note = refined_settings(result, settings)
        if cap_note:
            notes.append(cap_note)
            result.warnings.append(cap_note)
        if finer is None:
            break
        refined = module.run(params, finer, progress=progress, **options)
        refinements += 1
        if result.failed and not refined.failed and refined.error is None:
            note = unconfirmed_note(result, settings, finer, refined)
            notes.append(note)
            result.warnings.append(note)
            earlier_wall += refined.wall_time
            break
        settings, earlier_wall, result = finer, earlier_wall + result.wall_time, refined
    result.wall_time += earlier_wall
    result.info["sampling"] = {
        "output_interval": settings.sample_interval,
        "t_final": settings.t_final,
        "refinements": refinements,
        "location_error": location_error(result.time, result.amplitude, settings.failure_ratio),
        "notes": notes,
        "refinement_wall_time": earlier_wall,
    }
    return result, settings
