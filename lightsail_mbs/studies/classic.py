"""The classic validations (paper Appendices A–B): cases, runs and measurements shared by
validation/{cantilever,string,modes}.py and tests/test_validation_classic.py.

* cantilever (Appendix A): steel beam L = 1 m, h = 0.2 m, W = 0.1 m, ρ = 7800 kg/m³, E = 200 GPa,
  slice 1 clamped, P(t) = P₀(1 − e^(−t/τ)) at the centre of slice n, P₀ = 100 N, τ = 0.3 s, 2 s.
* G3 string (Appendix B): L = 0.6477 m, d = 0.43 mm, ρ = 7800 kg/m³, E = 210 GPa, T = 72.485 N,
  half sine a₀ = 0.1 mm (ν = ½). The chain's rectangular section W × h is chosen with the wire's
  area and second moment, W h = πd²/4 and W h³/12 = πd⁴/64 (h = (√3/2) d, W = πd/(2√3)). Ends:
  hinge 0 pinned, hinge n on a roller carrying the follower tension (SailParameters.boundary
  "pinned"), instead of the paper's fixed first slice centre with a free right end.
* free–free beam: the paper's torsion sail (Sec. IV.B) without the beam, both ends free.
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.analysis.frequencies import SineFit, fit_sinusoid
from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.model import chain_theory as ct
from lightsail_mbs.model.parameters import SailParameters

WIRE_DIAMETER = 0.43e-3  # m, D'Addario G3 (paper Appendix B)
CANTILEVER_RUN = RunSettings(t_final=2.0, stop_at_failure=False)  # Appendix A: 2 s
STRING_RUN = RunSettings(t_final=0.05, output_interval=1e-5, stop_at_failure=False)  # Appendix B: 50 ms
FREE_RUN = RunSettings(stop_at_failure=False)


def cantilever_case(n: int = 30, **changes) -> SailParameters:
    """Paper Appendix A: the clamped steel chain under the ramped tip load (Eq. 43)."""
    base = dict(
        model="torsion",
        n=n,
        length=1.0,
        width=0.1,
        thickness=0.2,
        density=7800.0,
        youngs_modulus=200e9,
        intensity=0.0,
        defect_amplitude=0.0,
        boundary="cantilever",
        tip_load=100.0,
        tip_load_time_constant=0.3,
    )
    return SailParameters(**{**base, **changes})


def g3_string_case(n: int = 20, **changes) -> SailParameters:
    """Paper Appendix B: the G3 string as an extensible TnT chain, pinned ends, half-sine pluck."""
    d = WIRE_DIAMETER
    base = dict(
        model="tnt",
        n=n,
        length=0.6477,
        width=math.pi * d / (2 * math.sqrt(3)),
        thickness=math.sqrt(3) / 2 * d,
        density=7800.0,
        youngs_modulus=210e9,
        tension=72.485,
        intensity=0.0,
        defect_amplitude=1e-4,
        defect_mode=0.5,
        boundary="pinned",
    )
    return SailParameters(**{**base, **changes})


def free_beam_case(n: int = 30, **changes) -> SailParameters:
    """The paper's torsion sail (L = W = 1 m, h = 1 µm, ρ = 1000 kg/m³, E = 4.5e13 Pa), unlit, free–free."""
    base = dict(model="torsion", n=n, intensity=0.0, defect_amplitude=0.0)
    return SailParameters(**{**base, **changes})


def bending_stiffness(p: SailParameters) -> float:
    """EI (N·m²)."""
    return p.youngs_modulus * p.second_moment_of_area


def line_density(p: SailParameters) -> float:
    """μ = ρ W h (kg/m)."""
    return p.density * p.width * p.thickness


# ---- cantilever ---------------------------------------------------------------------------
def fitted_order(n, error) -> float:
    """Least-squares slope p of log|error| = c − p log n."""
    slope, _ = np.polyfit(np.log(np.asarray(n, float)), np.log(np.abs(np.asarray(error, float))), 1)
    return float(-slope)


def paper_error(p: SailParameters, x: np.ndarray, y: np.ndarray) -> float:
    """Paper Eq. (44): max_i abs(δ(x_i) − y_i) with δ the Euler–Bernoulli deflection of Eq. (42) under P₀
    at the tip x = L, at the slice centres of one state."""
    delta = ct.euler_bernoulli_cantilever(p.tip_load, p.length, bending_stiffness(p), x)
    return float(np.max(np.abs(delta - y)))


def quasi_static_tip(p: SailParameters, time: np.ndarray) -> np.ndarray:
    """The tip response to Eq. (43) without its free vibration, in the first-mode approximation:
    y_s [1 − e^(−t/τ) ω₁²/(ω₁² + τ⁻²)] (the exact forced part of the one-mode oscillator)."""
    ys = ct.cantilever_tip_deflection(p.tip_load, p.length, bending_stiffness(p), p.n)
    w1 = ct.chain_angular_frequencies(p)[0]
    tau = p.tip_load_time_constant
    return ys * (1.0 - np.exp(-time / tau) * w1**2 / (w1**2 + tau**-2))


def plateau(p: SailParameters, time: np.ndarray, tip: np.ndarray, start: float = 0.5) -> SineFit:
    """Sinusoid fit of the free vibration left by the ramp, tip − quasi_static_tip, for t ≥ start."""
    keep = time >= start
    return fit_sinusoid(time[keep], tip[keep] - quasi_static_tip(p, time[keep]))


def error_budget(p: SailParameters, settings: RunSettings = CANTILEVER_RUN) -> dict:
    """The parts of the paper's end-of-run error at t_final (Eq. 44), from the exact chain (m): the
    static chain against Euler–Bernoulli, the load deficit P₀e^(−t/τ) at the tip, the free vibration
    left by the ramp (mode 1, and the sum over all modes: a bound for its value at t_final)."""
    EI = bending_stiffness(p)
    centres = p.slice_length * (np.arange(1, p.n + 1) - 0.5)
    static = ct.cantilever_deflection(p.tip_load, p.length, EI, p.n)
    _, vibration = ct.tip_ramp_vibration(p)
    return {
        "discretisation": paper_error(p, centres, static),
        "load_deficit": static[-1] * math.exp(-settings.t_final / p.tip_load_time_constant),
        "vibration": float(vibration[0]),
        "vibration_bound": float(vibration.sum()),
    }


# ---- string -------------------------------------------------------------------------------
def string_signal(result) -> tuple[np.ndarray, np.ndarray]:
    """(time, y of the middle slice's centre) of a string run."""
    return result.time, result.y[:, result.params.n // 2]


def string_fit(result) -> SineFit:
    """Least-squares sinusoid of the middle slice's transverse motion (fundamental)."""
    return fit_sinusoid(*string_signal(result))


def string_references(p: SailParameters) -> dict:
    """Fundamental frequencies (Hz): exact discrete chain (chain_theory, extensible segments when
    the chain is), the continuous string of the nominal length and mass (Eq. 45, μ = ρA), and the
    continuous string of the chain's stretched length L(1 + T/EA) with the same total mass."""
    mu = line_density(p)
    stretched = p.length + (p.n - 1) * p.tension / p.axial_stiffness if p.extensible else p.length
    return {
        "discrete": float(ct.chain_angular_frequencies(p)[0] / (2 * math.pi)),
        "continuous": ct.string_frequency(p.tension, mu, p.length),
        "continuous_stretched": ct.string_frequency(p.tension, mu * p.length / stretched, stretched),
    }


# ---- linearised modes ---------------------------------------------------------------------
def beam_references(p: SailParameters, count: int) -> np.ndarray:
    """Euler–Bernoulli ω (rad/s) of the chain's beam for its boundary (free–free or cantilever)."""
    roots = ct.free_free_beam_roots(count) if p.boundary == "free" else ct.cantilever_beam_roots(count)
    return ct.beam_angular_frequencies(roots, bending_stiffness(p), line_density(p), p.length)
