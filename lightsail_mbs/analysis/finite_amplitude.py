"""Finite-amplitude stability of the defective sail: scaling, critical E or T, failure time.

Linear theory sees nothing (lightsail_mbs.analysis.linear_stability): the load's first-order change acts along the
sail. At second order it does two things to a sail of transverse deflection w(x, t) (per unit
width, p = 2I₀/c, g₀ = p/(ρh), slopes small):

* its axial part −p w′ is carried by an axial force N(x) = T + p (w − ℓ), ℓ the chord through the
  ends (axial balance N′ = ρh ü + p w′ with N = T at both free ends): compression in the troughs
  (w < ℓ), tension on the crests — hence the paper's trough failures;
* its transverse part changes by −(3/2) p w′².

The transverse balance ρh w_tt = (N w′)′ − E I w'''' /W + f_y then reads

    w_tt = (T/ρh) w″ − (E h²/12ρ) w'''' + g₀ [((w − ℓ) w′)′ − (3/2) w′²].

With w = a₀ W, x = X/k (k = 2πν/L) and t = t_c τ, t_c = 1/(k √(g₀ a₀)), every term but the
stiffness ones is O(1), and those two become

    T/(p a₀ W) = T / (2 T_cr,max)       and       E h³ k²/(12 p a₀) = E / (2 E_cr,max)      (Eqs 8, 10).

So in the small-slope limit the motion, and whether and when the amplitude doubles, depends on
E/E_cr,max (or T/T_cr,max), ν and the run length in units of t_c only (and on n, see below):
E_cr ∝ p a₀/(ν² h³) and T_cr ∝ p a₀ exactly, with constants the quasi-static balance cannot give,
and the failure time is t_f = t_c F(E/E_cr,max, ν). Without bending the compressed troughs are
unstable at all wavelengths down to the slice length (growth rate ∝ wavenumber), so for
E ≪ E_cr,max (and the rigid chain) F depends on n.

This module measures the constants on the reduced solver in these units: short runs (a few t_c)
bisected in the stiffness ratio (critical_ratio), paired runs for the divergence of neighbouring
trajectories (divergence), and the stiffness ratio (stiffness_ratio). The scales k and t_c are the
model's (model.theory.wavenumber, model.theory.time_scale; importable from here too).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from lightsail_mbs import analysis
from lightsail_mbs.base.validation import ParameterError, check, finite
from lightsail_mbs.model import shapes, theory
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.model.theory import time_scale, wavenumber
from lightsail_mbs.solvers import contract

MIN_FACTOR, MAX_FACTOR = 1.001, 10.0  # allowed final bracket widths hi/lo of critical_ratio
BLOWUP_RATIO = 10.0  # scaled runs past failure end here (the sail has crumpled; slopes no longer small)
STIFFNESS = theory.STIFFNESS  # swept stiffness of each model and its analytic critical value


def log_bisect(fails, lo: float, hi: float, factor: float) -> tuple[float, float]:
    """Bisect in log space between a failing lo and a stable hi until hi/lo ≤ factor; returns (lo, hi)."""
    while hi / lo > factor:
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if fails(mid) else (lo, mid)
    return lo, hi


def _stiffness(p: SailParameters):
    if p.model not in STIFFNESS:
        raise ParameterError(f"model={p.model!r} is invalid: allowed one of {', '.join(STIFFNESS)}")
    return STIFFNESS[p.model]


def stiffness_ratio(p: SailParameters) -> float:
    """E/E_cr,max (torsion) or T/T_cr,max (TnT): the one stiffness number of the scaled problem."""
    name, critical = _stiffness(p)
    return getattr(p, name) / critical(p)


def with_ratio(p: SailParameters, ratio: float) -> SailParameters:
    """The same sail with E = ratio·E_cr,max (torsion) or T = ratio·T_cr,max (TnT)."""
    name, critical = _stiffness(p)
    return p.replace(**{name: float(ratio) * critical(p)})


FREE_FREE_BETA1_L = 4.730040745  # lowest free–free beam mode: cos βL cosh βL = 1


def lowest_mode_buckling_ratio(p: SailParameters) -> float:
    """r_b = 2 (kL/β₁L)²: the E/E_cr,max at which the compression p a₀ of the defect's troughs equals the
    Euler load of the lowest free–free bending mode, E h³ β₁²/(12 L²) = p a₀. A semi-analytic estimate of
    the first-passage boundary; measured (n = 30): within 5 % for ν = 1 and 3/2, not for ν ≥ 2."""
    return 2.0 * (wavenumber(p) * p.length / FREE_FREE_BETA1_L) ** 2


# ---- runs in the scaled time ---------------------------------------------------------------
@dataclass
class ScaledRun:
    """A reduced-solver run sampled in τ = t/t_c: amplitude ratio a(τ)/a(0), the slice angles θ(τ)
    (for paired runs), and τ_f, the first τ with a ≥ failure_ratio·a(0) (None: no failure)."""

    tau: np.ndarray
    amplitude_ratio: np.ndarray
    theta: np.ndarray
    failure_tau: float | None


def scaled_run(
    p: SailParameters,
    tau_final: float,
    *,
    samples_per_tau: int = 50,
    rtol: float = 1e-8,
    theta_perturbation: np.ndarray | None = None,
    stop_at_failure: bool = True,
    failure_ratio: float = 2.0,
) -> ScaledRun:
    """Integrate the reduced model's equations (its "equations" capability; scipy's DOP853, atol = rtol × the
    state scales) from rest in the defect shape (plus an optional small angle perturbation, rad per slice) up to
    τ = tau_final, or to failure (amplitude ≥ failure_ratio·a(0), located by an event, when stop_at_failure), or
    until the amplitude reaches BLOWUP_RATIO·a(0) (past failure)."""
    if p.extensible:
        raise ParameterError("scaled runs use the inextensible chain: set axial_springs=False for tnt")
    tc = time_scale(p)
    equations = reduced_equations(p)
    start = shapes.initial_state(p)
    theta = start.theta + (0.0 if theta_perturbation is None else np.asarray(theta_perturbation, float))
    q0 = equations.coordinates(shapes.ChainState(start.x, start.y, theta, start.z))
    y0 = np.concatenate([q0, np.zeros_like(q0)])
    amp0 = analysis.amplitude(start.x, start.y)
    limit = failure_ratio * amp0

    def amplitude_of(y):
        x, yy = equations.centres(y[: equations.dof])
        return analysis.amplitude(x, yy)

    def failed(t, y):
        return amplitude_of(y) - limit

    failed.terminal = stop_at_failure
    failed.direction = 1

    def left_small_slopes(t, y):
        return amplitude_of(y) - BLOWUP_RATIO * amp0

    left_small_slopes.terminal = True

    t_eval = tc * np.linspace(0.0, tau_final, int(round(tau_final * samples_per_tau)) + 1)
    sol = solve_ivp(
        equations.rhs,
        (0.0, t_eval[-1]),
        y0,
        method="DOP853",
        t_eval=t_eval,
        rtol=rtol,
        atol=rtol * equations.state_scales(p.defect_mode),
        events=[failed, left_small_slopes],
    )
    x, yy = equations.centres(sol.y[: equations.dof])
    amp = np.atleast_1d(analysis.amplitude(x.T, yy.T)) / amp0
    fail = sol.t_events[0]
    theta = equations.angles(sol.y[: equations.dof]).T
    return ScaledRun(sol.t / tc, amp, theta, float(fail[0] / tc) if fail.size else None)


def reduced_equations(p: SailParameters):
    """The reduced solver's equations of motion of the chain (its "equations" capability, solvers.contract)."""
    return contract.lookup("reduced", p).capability("equations")(p)


def failure_tau(p: SailParameters, tau_final: float, **options) -> float | None:
    """τ_f = t_f/t_c of one sail within tau_final (None: no failure)."""
    return scaled_run(p, tau_final, samples_per_tau=4, **options).failure_tau


@dataclass
class CriticalRatio:
    """The stiffness ratio at which the amplitude stops doubling within tau_final: bracketed by
    ``failed_ratio`` < ``stable_ratio`` (hi/lo ≤ factor), value = their geometric mean."""

    failed_ratio: float
    stable_ratio: float
    tau_final: float
    runs: int

    @property
    def value(self) -> float:
        return math.sqrt(self.failed_ratio * self.stable_ratio)


def critical_ratio(
    p: SailParameters, tau_final: float = 8.0, *, lo: float = 1.0, hi: float = 30.0, factor: float = 1.02, **options
) -> CriticalRatio:
    """Bisect E/E_cr,max (or T/T_cr,max) in log space with runs of tau_final·t_c: the smallest
    stiffness ratio at which the amplitude does not double within the run (failed below).
    ParameterError before any run for tau_final ≤ 0 or a factor outside MIN_FACTOR…MAX_FACTOR."""
    tau = finite("tau_final", tau_final)
    check("tau_final", tau_final, tau > 0, "> 0 (run length in units of t_c)")
    ratio = finite("factor", factor)
    check("factor", factor, MIN_FACTOR <= ratio <= MAX_FACTOR, f"{MIN_FACTOR} ≤ factor ≤ {MAX_FACTOR} (final hi/lo)")
    runs = 0

    def fails(ratio):
        nonlocal runs
        runs += 1
        return failure_tau(with_ratio(p, ratio), tau_final, **options) is not None

    while not fails(lo):
        lo /= 4.0
        if lo < 1e-6:
            raise ParameterError(
                f"tau_final={tau_final:.3g} is too short: no failure within {tau_final:.3g} t_c even at "
                "1e-6 × the analytic critical value (the softest sails need ≈ 1.6 t_c)"
            )
    while fails(hi):
        lo, hi = hi, hi * 4.0
        if hi > 1e6:
            raise ParameterError("failure even at 1e6 × the analytic critical value within the run")
    lo, hi = log_bisect(fails, lo, hi, factor)
    return CriticalRatio(lo, hi, tau_final, runs)


def divergence(
    p: SailParameters,
    tau_final: float,
    *,
    size: float = 1e-9,
    seed: int = 0,
    samples_per_tau: int = 20,
    rtol: float = 1e-10,
) -> tuple[np.ndarray, np.ndarray]:
    """Paired runs: (τ, ‖Δθ(τ)‖/‖Δθ(0)‖) between the defect run and one started with a random angle
    perturbation of RMS size × (defect slope 2πνa₀/L); both run past failure up to tau_final or
    until either leaves the small-slope regime (then the arrays end)."""
    rng = np.random.default_rng(seed)
    slope = wavenumber(p) * p.defect_amplitude
    kick = rng.standard_normal(p.n)
    kick *= size * slope / np.sqrt(np.mean(kick**2))
    a = scaled_run(p, tau_final, samples_per_tau=samples_per_tau, rtol=rtol, stop_at_failure=False)
    b = scaled_run(
        p, tau_final, samples_per_tau=samples_per_tau, rtol=rtol, theta_perturbation=kick, stop_at_failure=False
    )
    m = min(a.tau.size, b.tau.size)
    sep = np.linalg.norm(a.theta[:m] - b.theta[:m], axis=1) / np.linalg.norm(kick)
    return a.tau[:m], sep


# ---- one-mode (Galerkin) model -------------------------------------------------------------
def _shape(p: SailParameters, a: float):
    """Chain state of the defect shape a sin(kx) (a of either sign; exact chords)."""
    k = wavenumber(p)
    return shapes.initial_state(p, profile=lambda x: a * np.sin(k * x))


def one_mode_force(p: SailParameters, amplitudes: np.ndarray, step: float = 1e-3) -> np.ndarray:
    """Generalized force F(a) = Σ_j F_j·∂r_j/∂a + Σ_j τ_j ∂θ_j/∂a on the one-parameter family of
    sine shapes a sin(kx): load and frame force (model.terms.chain_forces), end tension and bending
    torques of the chain, with the family's rigid translation removed (central differences, step·a₀)."""
    equations = reduced_equations(p)
    da = step * p.defect_amplitude
    out = np.empty(len(amplitudes))
    for i, a in enumerate(amplitudes):
        s, plus, minus = _shape(p, a), _shape(p, a + da), _shape(p, a - da)
        drx, dry = (plus.x - minus.x) / (2 * da), (plus.y - minus.y) / (2 * da)
        drx, dry = drx - drx.mean(), dry - dry.mean()
        dth = (plus.theta - minus.theta) / (2 * da)
        fx, fy, tau = equations.slice_loads(s)
        out[i] = fx @ drx + fy @ dry + tau @ dth
    return out


@dataclass
class OneModeModel:
    """V(a; r) = V₀(a) + r (V₁(a) − V₀(a)): the one-mode potential at stiffness ratio r (the load part
    V₀ at zero stiffness, V₁ at the analytic critical value), on a grid a/a₀ ∈ [−span, span]."""

    a_over_a0: np.ndarray
    load_potential: np.ndarray
    unit_stiffness_potential: np.ndarray

    def potential(self, ratio: float) -> np.ndarray:
        return self.load_potential + ratio * self.unit_stiffness_potential

    def reach(self, ratio: float) -> tuple[float, float]:
        """(lowest, highest) a/a₀ reached from rest at a = a₀: the connected set V(a) ≤ V(a₀)."""
        v = self.potential(ratio)
        i0 = int(np.argmin(np.abs(self.a_over_a0 - 1.0)))
        ok = v <= v[i0] + 1e-12 * np.abs(v).max()
        lo = hi = i0
        while lo > 0 and ok[lo - 1]:
            lo -= 1
        while hi < v.size - 1 and ok[hi + 1]:
            hi += 1
        return float(self.a_over_a0[lo]), float(self.a_over_a0[hi])

    def fails(self, ratio: float, failure_ratio: float = 2.0) -> bool:
        lo, hi = self.reach(ratio)
        return max(-lo, hi) >= failure_ratio

    def critical_ratio(self, failure_ratio: float = 2.0, lo: float = 1e-4, hi: float = 1e4) -> float:
        """The smallest stiffness ratio whose one-mode orbit stays within abs(a) < failure_ratio·a₀."""
        if not self.fails(lo, failure_ratio) or self.fails(hi, failure_ratio):
            return float("nan")
        lo, hi = log_bisect(lambda r: self.fails(r, failure_ratio), lo, hi, 1.001)
        return math.sqrt(lo * hi)


def one_mode_model(p: SailParameters, span: float = 2.5, points: int = 201) -> OneModeModel:
    """Build the one-mode model of a sail (torsion or TnT) by integrating one_mode_force in a."""
    a = np.linspace(-span, span, points) * p.defect_amplitude
    potentials = []
    for ratio in (0.0, 1.0):
        force = one_mode_force(with_ratio(p, ratio), a)
        v = np.concatenate([[0.0], np.cumsum(0.5 * (force[1:] + force[:-1]) * np.diff(a))])
        potentials.append(-(v - np.interp(0.0, a, v)))
    return OneModeModel(a / p.defect_amplitude, potentials[0], potentials[1] - potentials[0])


def boundary_for_run(ratios, failure_taus, tau_run: float) -> float | None:
    """The stiffness ratio a stability map with runs of τ_run = t_final/t_c would find, from the failure
    curve τ_f(r) (ascending r; None or inf: no failure within the sampled runs): above the last sample
    that fails within τ_run (τ_f ≤ τ_run; τ_f(r) is not monotone near a threshold), log-interpolated
    towards the next one. None when no sampled sail fails within the run (the map is 'stable'
    everywhere); inf when every sampled sail fails."""
    r = np.asarray(ratios, float)
    tau = np.array([np.inf if t is None else float(t) for t in failure_taus])
    failing = np.nonzero(tau <= tau_run)[0]
    if not failing.size:
        return None
    i = int(failing[-1]) + 1
    if i == r.size:
        return float("inf")
    lo, hi = tau[i - 1], tau[i]
    if not np.isfinite(hi):
        return float(np.sqrt(r[i - 1] * r[i]))
    w = (tau_run - lo) / (hi - lo)
    return float(r[i - 1] * (r[i] / r[i - 1]) ** w)
