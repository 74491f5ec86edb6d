"""Is a run's answer resolved in n? A verdict from the growth-rate spectrum of the chain at its initial state.

The defect shape under the load carries an axial force N = T + p (w − ℓ) (docs: stability analysis), compressive
in the troughs. A transverse wave of wavenumber q on a stretch under compression P (force on the whole width W)
grows at

    ρ h W σ² = (P − T) q² − E I q⁴,     I = W h³/12,

so without bending (E I = 0) and without a tension T that outweighs the compression, σ rises in proportion to q
all the way to the shortest wave the chain carries (q = π n/L, two slices per wavelength): refining the chain
adds faster-growing waves, the answer moves with n and with whatever seeds those waves (round-off, roughness),
and there is no continuum limit. Bending cuts the growth off at q*² = (P − T)/(2 E I), λ* = 2π/q*; a chain of
slices l ≤ λ*/2 carries that wave, and its largest growth rate converges as n grows.

The measurement (:func:`assess`): the growth rates of the reduced model linearised at rest in the initial state
(:func:`lightsail_mbs.analysis.linear_stability.growth_modes`), at n and at 2n. The fastest-growing deformation
mode (the translations and the near-rigid turn excluded) gives σ and, from the Fourier spectrum of its slice
angles, its wavelength in slices. The rule: with the grid-scale growth σ ∝ q the ratio σ(2n)/σ(n) is 2 (measured
2.03–2.10 on the rigid, the membrane and the uniform-beam Starshot-like torsion sail); once the chain carries λ*
it tends to 1 (measured 0.999–1.07: the paper's torsion sails at n = 30, the membrane at T ≥ 2 T_cr,max). The
case is called ill-posed in n at this n when σ(2n)/σ(n) > √2 (RATE_EXPONENT_LIMIT = 1/2 in log₂). On the
torsion sail (ν = 3/2, n = 30) the ratio jumps from 1.84 at E = 0.0032 E_cr,max to 1.07 at 0.01 E_cr,max,
where λ*/l passes 2; on the inextensible membrane from 2.09 at T = 1.5 T_cr,max to 0.98 at 2 T_cr,max, where the
tension outweighs the largest trough compression p a₀ W = 2 T_cr,max.

The extensible membrane (TnT with axial springs) is assessed in its inextensible limit: at rest in the initial
state its springs carry only the pre-tension, and the trough compression builds up after one axial wave
crossing (L/√(E/ρ), about 1e-4 s), far faster than any growth; the inextensible chain carries it at once.
A chain heated inside the run (``heated``) is assessed with the end tension its film has at the start
(model.heating.cold_equivalent); at a constant absorptance the film cools along a journey and that tension
rises, so the start is the least stable moment the run passes through (a table's absorptance rising at λ' can
heat it later, which the check does not see).

Where the case is well posed, the discretisation error of the fastest growth rate, δσ = abs(σ(n) − σ(2n)), gives a
rough n-error of a failure time that scales as ln(ratio)/σ: δt_f ≈ t_f δσ/σ(2n) (``relative_n_error``). The n-error
a run's ± holds is :mod:`lightsail_mbs.analysis.n_error`'s (coarser twins; this estimate only as its floor for a
grid-scale fastest wave). A well-posed case whose fastest rate still moves by more than UNRESOLVED_RATE_CHANGE
between n and 2n is not resolved at n (bending cuts the growth off, but near the grid scale: the torsion sail
at E = 0.001 E_cr,max and n = 120 has its fastest wave at 2 slices, σ = 27.2 /s at n and 19.7 /s at 2n); its
run says so in one line (:meth:`Resolvedness.warning`).

Cost: two Jacobians by central differences (2·dof vectorised right-hand-side calls each) and the eigenproblem
of the dof × dof block; about 5 ms at n = 30, 0.8 s at n = 240 (with 480 for the twin). Above MAX_SLICES, on
sheets and on supported chains the verdict is "not assessed".
"""

from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass

import numpy as np

from lightsail_mbs.model import heating, theory
from lightsail_mbs.model.parameters import SailParameters

MAX_SLICES = 240  # the twin at 2n = 480 costs about 1 s; above, the verdict is not assessed
RATE_EXPONENT_LIMIT = 0.5  # log₂ σ(2n)/σ(n) above this: the growth still rises toward the grid scale
UNRESOLVED_RATE_CHANGE = 0.1  # well posed, but abs(σ(n) − σ(2n))/σ(2n) above this: not yet resolved at n
MIN_DEFORMATION = 0.5  # modes whose angles deviate from their mean by less than this fraction are rigid turns
FFT_PADDING = 16  # zero-padding factor of the mode's angle spectrum (wavelength resolution)


@dataclass(frozen=True)
class FastestWave:
    """The fastest-growing deformation mode of a chain at its initial state: growth rate σ (s⁻¹, 0 when nothing
    grows) and wavelength in slices (None when nothing grows)."""

    n: int
    growth_rate: float
    slices_per_wavelength: float | None


@dataclass(frozen=True)
class Resolvedness:
    """The verdict on one case (module docstring). ``well_posed`` is None when not assessed (``reason`` says why)."""

    assessed: bool
    well_posed: bool | None
    reason: str
    n: int
    growth_rate: float | None = None  # σ at n (s⁻¹)
    growth_rate_refined: float | None = None  # σ at 2n (s⁻¹)
    slices_per_wavelength: float | None = None  # of the fastest-growing wave at n
    stiffness_ratios: dict | None = None  # E/E_cr,max, T/T_cr,max where they apply
    stabilising_tension: float | None = None  # T + (P − T): the edge tension (N) that outweighs the compression
    model: str | None = None  # the case's model (only the tnt chain takes a boundary tension)
    cutoff_wavelength: float | None = None  # λ* (m) at which bending cuts the growth off (0: no bending)
    carrying_n: float | None = None  # n = 2L/λ* from which the chain carries λ*
    relative_n_error: float | None = None  # abs(σ(n) − σ(2n))/σ(2n), well-posed cases
    cpu_time: float = 0.0

    @property
    def rate_ratio(self) -> float | None:
        """σ(2n)/σ(n)."""
        if not self.growth_rate or self.growth_rate_refined is None:
            return None
        return self.growth_rate_refined / self.growth_rate

    def to_dict(self) -> dict:
        """The verdict as a record (Result.info), without its CPU time: records of repeated runs stay equal."""
        record = {**asdict(self), "rate_ratio": self.rate_ratio, "resolved": self.resolved}
        del record["cpu_time"]
        return record

    @property
    def resolved(self) -> bool | None:
        """Well posed and its fastest growth rate within UNRESOLVED_RATE_CHANGE between n and 2n (None: not
        assessed or ill-posed)."""
        if not self.well_posed:
            return None
        return self.relative_n_error is None or self.relative_n_error <= UNRESOLVED_RATE_CHANGE

    def warning(self) -> str | None:
        """One line for Result.warnings when the case is ill-posed in n at this n, or well posed but not yet
        resolved at it; else None."""
        if self.resolved is False:
            return (
                f"not resolved in n: the fastest-growing wave spans {self.slices_per_wavelength:.3g} slices and its "
                f"growth rate moves from {self.growth_rate:.3g} /s at n = {self.n} to "
                f"{self.growth_rate_refined:.3g} /s at n = {2 * self.n} ({self.relative_n_error:.0%}); bending cuts "
                f"the short waves off near the grid scale, so the answer still moves with n (its ± carries the "
                f"n-error of the coarser twins): refine n"
            )
        if self.well_posed is not False:
            return None
        ratios = ", ".join(f"{name} = {value:.2g}" for name, value in (self.stiffness_ratios or {}).items())
        if self.cutoff_wavelength:
            limit = (
                f" below n ≈ {self.carrying_n:.2g} (bending, {ratios}, cuts the short waves off only at "
                f"λ ≈ {self.cutoff_wavelength:.2g} m)"
            )
        else:
            limit = f" ({ratios + '; ' if ratios else ''}no bending stiffness: nothing cuts the short waves off)"
        tension = "tension, "
        if self.stabilising_tension:
            where = "" if self.model == "tnt" else " (a boundary tension, as the tnt model has)"
            tension = f"tension above ≈ {self.stabilising_tension:.2g} N{where}, "
        return (
            f"ill-posed in n: the fastest-growing wave sits at the grid scale ({self.slices_per_wavelength:.3g} "
            f"slices per wavelength, growth rate σ = {self.growth_rate:.3g} /s at n = {self.n} and "
            f"{self.growth_rate_refined:.3g} /s at n = {2 * self.n}), so this answer depends on n and on noise "
            f"and has no continuum limit{limit}; bending stiffness, {tension}or a physical cut-off would give it one"
        )


def stiffness_ratios(p: SailParameters) -> dict:
    """E/E_cr,max (where the chain bends) and T/T_cr,max (the membrane), Eqs 8 and 10, at the intensity of the
    run's start (theory.at_start: Doppler-dimmed from β₀); empty without a defect."""
    if p.defect_amplitude <= 0 or p.intensity <= 0:
        return {}
    p = theory.at_start(p)
    ratios = {}
    if p.torsional_stiffness > 0:
        ratios["E/E_cr,max"] = p.youngs_modulus / theory.critical_modulus_max(p)
    if p.model == "tnt":
        ratios["T/T_cr,max"] = p.tension / theory.critical_tension_max(p)
    return ratios


def dominant_wavelength(angles: np.ndarray) -> float:
    """Slices per wavelength of the peak of the Fourier spectrum of a mode's slice angles (their mean, a rigid
    turn, removed); 2 for the alternating zig-zag."""
    deformation = angles - angles.mean()
    size = FFT_PADDING * angles.size
    power = np.abs(np.fft.rfft(deformation, size)) ** 2
    return size / (1 + int(np.argmax(power[1:])))


def fastest_wave(p: SailParameters) -> FastestWave:
    """The fastest-growing deformation mode of the chain `p` at its initial state (module docstring)."""
    from lightsail_mbs.analysis.linear_stability import growth_modes

    p = heating.cold_equivalent(p)
    rates, angles = growth_modes(p.replace(axial_springs=False) if p.extensible else p)
    for rate, mode in zip(rates, angles.T):
        if rate <= 0:
            break
        norm = np.linalg.norm(mode)
        if norm > 0 and np.linalg.norm(mode - mode.mean()) > MIN_DEFORMATION * norm:
            return FastestWave(p.n, float(rate), dominant_wavelength(mode))
    return FastestWave(p.n, 0.0, None)


def not_assessed(p: SailParameters) -> str | None:
    """Why the verdict is not computed for `p`, or None."""
    if p.model == "sheet":
        return "not assessed for sheets (the growth spectrum is computed for chains only)"
    if p.boundary != "free":
        return f"not assessed for a supported chain (boundary {p.boundary!r})"
    if p.n > MAX_SLICES:
        return f"not assessed above n = {MAX_SLICES} (the spectrum at 2n would cost seconds)"
    return None


def assess(p: SailParameters) -> Resolvedness:
    """The resolvedness verdict of the case `p` at its n (module docstring)."""
    reason = not_assessed(p)
    if reason:
        return Resolvedness(False, None, reason, p.n)
    start = time.process_time()
    p = heating.cold_equivalent(p)
    coarse, fine = fastest_wave(p), fastest_wave(p.replace(n=2 * p.n))
    sigma, sigma2 = coarse.growth_rate, fine.growth_rate
    common = dict(
        n=p.n,
        model=p.model,
        growth_rate=sigma,
        growth_rate_refined=sigma2,
        slices_per_wavelength=coarse.slices_per_wavelength,
        stiffness_ratios=stiffness_ratios(p),
    )
    if sigma <= 0 or math.log2(max(sigma2, 1e-300) / sigma) <= RATE_EXPONENT_LIMIT:
        relative = abs(sigma - sigma2) / sigma2 if sigma > 0 and sigma2 > 0 else None
        what = "no wave grows at the initial state" if sigma <= 0 else "the fastest growth rate converges in n"
        if relative is not None and relative > UNRESOLVED_RATE_CHANGE:
            what = "bending cuts the growth off, but near the grid scale (not yet resolved at this n)"
        return Resolvedness(
            True, True, f"well posed in n: {what}", relative_n_error=relative, cpu_time=_since(start), **common
        )
    q = math.pi * p.n / p.length  # the shortest wave the chain carries
    bending = p.torsional_stiffness * p.slice_length  # E I
    line_mass = p.density * p.thickness * p.width
    compression = line_mass * sigma**2 / q**2 + bending * q**2
    cutoff = 2 * math.pi * math.sqrt(2 * bending / compression) if bending > 0 else 0.0
    return Resolvedness(
        True,
        False,
        "ill-posed in n: the fastest growth rate still rises toward the grid scale",
        stabilising_tension=compression + (p.tension if p.model == "tnt" else 0.0),
        cutoff_wavelength=cutoff,
        carrying_n=2 * p.length / cutoff if cutoff > 0 else None,
        cpu_time=_since(start),
        **common,
    )


def _since(start: float) -> float:
    return time.process_time() - start


def annotate(params: SailParameters, result) -> None:
    """Record the verdict in ``result.info["resolvedness"]``, its one-line warning in ``result.warnings`` when the
    case is ill-posed in n or not resolved at its n, and, for a well-posed failure, the failure time's n-error estimate
    (``failure_time_n_error``, s). An assessment that raises is recorded as not assessed."""
    try:
        verdict = assess(params)
    except (ArithmeticError, ValueError, np.linalg.LinAlgError) as exc:
        verdict = Resolvedness(False, None, f"not assessed: {exc}", params.n)
    record = verdict.to_dict()
    if verdict.relative_n_error is not None and result.failure_time is not None:
        record["failure_time_n_error"] = result.failure_time * verdict.relative_n_error
    result.info["resolvedness"] = record
    note = verdict.warning()
    if note:
        result.warnings.append(note)
