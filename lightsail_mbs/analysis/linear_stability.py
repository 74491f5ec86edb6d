"""Linear stability of the flat accelerating sail, from both solvers.

In the frame accelerating at g₀ the flat sail (θ ≡ 0) is an exact equilibrium: every slice carries
f₀ ŷ from the beam (Eq. 11) and −m g₀ ŷ = −f₀ ŷ from the frame. Tilting slice k by δθ_k changes
its net load, f₀ cos²θ (−sin θ, cos θ) − f₀ ŷ, by

    δF_k = −f₀ δθ_k x̂ + O(δθ²)       (the ŷ part changes only at second order, −(3/2) f₀ δθ²).

With F_k = 0 at the base state, the generalized forces change by δQ = Σ_k J_kᵀ δF_k, and at the
flat state J_kᵀ x̂ = ∂x_k/∂q is non-zero only for the axial coordinates (x₁, the stretches z).
The mass matrix does not couple axial and transverse coordinates there either. So the load
enters the linearised equations only as a one-way coupling from the angles into the axial
rows: the Jacobian is block-triangular and its spectrum is that of the unloaded chain —
the free–free beam (torsion), the tensioned string (TnT) or the free mechanism (rigid,
all frequencies zero). Linear theory has no critical E or T: the instability of the runs is
a finite-amplitude effect (see lightsail_mbs.critical).

Each solver linearises its own equations, through the capabilities it declares (solvers.contract, rule 9;
how each does it: the ``capabilities`` module of its package):

* eigenfrequencies of the chain about the flat state with its supports (the classic validations of
  Appendices A–B), ``angular_frequencies``: Exudyn's ``ComputeODE2Eigenvalues`` of the assembled system
  (symmetric K v = ω² M v, so meant for conservative linearisations, intensity = 0); the reduced
  solver's q̈(q, q̇) with its supports differentiated by central differences about the flat state at rest
  and restricted to the supports' tangent space, ω² = −eig(Nᵀ A N);
* the lit free sail at the flat state, ``linear_spectrum``: from a solver that declares ``linearise``
  (the reduced one), the central-difference Jacobian of ẏ = (q̇, q̈(q, q̇)) (:func:`jacobian`); from one
  that declares ``mass_stiffness`` (Exudyn), M and the elastic/tension stiffness K of the unlit system
  plus the load stiffness by central differences of its own load function (the net slice force, frame
  force included) (:func:`mass_stiffness`). Exudyn's own forward-difference Jacobian of the lit system is
  also available (``load="solver"``); forward differences of a load that is itself second order in the
  angles are noisy to ≈ 1 % of the softest bending frequencies, whatever the difference step (scenario
  stability_linear.py shows it).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightsail_mbs.model import shapes
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.solvers import contract

# modes without restoring force by support: a free sail translates in x, y and rotates
RIGID_MODES = {"free": 3, "cantilever": 0, "pinned": 0}
FD_STEP = 1e-6  # central-difference step of the lit sail's Jacobian: rad for angles, m for positions


def flat(p: SailParameters) -> SailParameters:
    """The same sail without its defect (a₀ = 0): the flat equilibrium state."""
    return p.replace(defect_amplitude=0.0)


def unlit(p: SailParameters) -> SailParameters:
    """The same sail without the beam (I₀ = 0, hence g₀ = 0): the unloaded chain."""
    return p.replace(intensity=0.0)


# ---- linearisations -----------------------------------------------------------------------
def jacobian(
    p: SailParameters,
    step: float = FD_STEP,
    state: shapes.ChainState | None = None,
    *,
    positions_only: bool = False,
    solver: str = "reduced",
) -> np.ndarray:
    """∂ẏ/∂y of a solver's equations (its "linearise") at rest in `state` (default: the flat state),
    y = (q, q̇) (2·dof square), central differences; with ``positions_only`` its first dof columns (2·dof × dof)."""
    if state is None:
        p = flat(p)
        state = shapes.initial_state(p)
    return contract.lookup(solver, p).capability("linearise")(p, state, step, positions_only)


def growth_modes(p: SailParameters) -> tuple[np.ndarray, np.ndarray]:
    """Growth rates Re λ (s⁻¹, descending) and angle parts (n × modes, columns) of the eigenmodes of the reduced
    model linearised at rest in its initial state (:func:`jacobian` at ``shapes.initial_state(p)``: the
    defect shape under the load, where the load's second-order terms act at first order).

    Without dampers (the only velocity-linear terms) ∂ẏ/∂y = [[0, I], [A, 0]] at rest and λ = ±√μ, μ = eig(A): the
    dof position columns and the eigenproblem of the dof × dof block A = ∂q̈/∂q; with dampers the whole 2·dof
    Jacobian."""
    damped = p.total_torsional_damping > 0 or p.total_axial_damping > 0
    jac = jacobian(p, state=shapes.initial_state(p), positions_only=not damped)
    dof = jac.shape[0] // 2
    angles = slice(2, 2 + p.n)
    if damped:
        values, vectors = np.linalg.eig(jac)
        rates, shapes_ = values.real, vectors[:dof][angles]
    else:
        mu, vectors = np.linalg.eig(jac[dof:])
        rates, shapes_ = np.sqrt(mu.astype(complex)).real, vectors[angles]
    order = np.argsort(-rates)
    shapes_ = shapes_[:, order]
    peak = shapes_[np.argmax(np.abs(shapes_), axis=0), np.arange(shapes_.shape[1])]
    return rates[order], (shapes_ * (np.abs(peak) / np.where(peak == 0, 1, peak))).real


def mass_stiffness(
    p: SailParameters,
    *,
    load: str = "central",
    step: float = FD_STEP,
    relative_epsilon: float | None = None,
    solver: str = "exudyn",
):
    """(M, K) of a solver's equations (its "mass_stiffness") at the flat state: M q̈ + K q = 0 (K not symmetric
    with load).

    load="central": K = K(unlit) − ∂Q_net/∂q by central differences of the solver's load function (radiation
    and frame force); "solver": the solver's own Jacobian of the lit system (Exudyn: forward differences with
    ``relative_epsilon``, its default 1e-7, on coordinates ≥ 1).
    """
    return contract.lookup(solver, p).capability("mass_stiffness")(flat(p), load, step, relative_epsilon)


# ---- spectra -------------------------------------------------------------------------------
@dataclass(frozen=True)
class Spectrum:
    """Squared angular frequencies ω² (rad²/s², ascending; negative = divergence) of a linearisation,
    and the largest real part of its eigenvalues (s⁻¹, > 0: exponential growth)."""

    omega_squared: np.ndarray
    max_growth_rate: float

    def frequencies_hz(self) -> np.ndarray:
        """ω/2π of the elastic modes: the free sail's three smallest ω² (translations x, y and the
        rotation, zero up to round-off) and any ω² ≤ 0 dropped."""
        w2 = self.omega_squared[RIGID_MODES["free"] :]
        return np.sqrt(w2[w2 > 0]) / (2 * np.pi)


def spectrum_of_jacobian(jac: np.ndarray) -> Spectrum:
    """ω² = eig(−∂q̈/∂q) (velocity terms vanish at rest without damping) and max Re eig(jac)."""
    dof = jac.shape[0] // 2
    w2 = np.sort(np.linalg.eigvals(-jac[dof:, :dof]).real)
    return Spectrum(w2, float(np.linalg.eigvals(jac).real.max()))


def spectrum_of_system(mass: np.ndarray, stiffness: np.ndarray) -> Spectrum:
    """ω² = eig(K, M) of M q̈ + K q = 0; growth rate max Re √(−ω²)."""
    import scipy.linalg as sl  # here, not at import: solve() uses this module's reduced-model part

    w2 = sl.eigvals(stiffness, mass)
    growth = float(np.sqrt(-w2.astype(complex)).real.max())
    return Spectrum(np.sort(w2.real), growth)


def linear_spectrum(p: SailParameters, solver: str = "reduced", **options) -> Spectrum:
    """The spectrum of the flat accelerating sail linearised with the named solver: from its Jacobian when
    it declares "linearise", else from its (M, K)."""
    if "linearise" in contract.lookup(solver, p).capabilities:
        return spectrum_of_jacobian(jacobian(p, solver=solver, **options))
    return spectrum_of_system(*mass_stiffness(p, solver=solver, **options))


def load_rate_scale(p: SailParameters) -> float:
    """g₀ k (s⁻²), k = 2πν/L: the squared rate at which the load would act if it entered linearly
    (a tilt θ = k w sends f₀θ along the sail per slice mass). The yardstick for spectrum shifts."""
    return p.nominal_acceleration * 2 * np.pi * p.defect_mode / p.length


def load_shift(p: SailParameters, solver: str = "reduced", **options) -> dict:
    """Compare the lit and unlit spectra of one sail: the largest abs(Δω²) over all modes, relative to
    the larger of max ω² and the load scale g₀k, and the growth rates of both."""
    lit, dark = linear_spectrum(p, solver, **options), linear_spectrum(unlit(p), solver, **options)
    scale = max(float(np.abs(dark.omega_squared).max()), load_rate_scale(p))
    return {
        "solver": solver,
        "max_shift": float(np.abs(lit.omega_squared - dark.omega_squared).max()),
        "scale": scale,
        "relative_shift": float(np.abs(lit.omega_squared - dark.omega_squared).max() / scale),
        "growth_rate_lit": lit.max_growth_rate,
        "growth_rate_unlit": dark.max_growth_rate,
        "omega_squared_lit": lit.omega_squared,
        "omega_squared_unlit": dark.omega_squared,
    }


# ---- eigenfrequencies with supports (validations) ---------------------------------------------
def angular_frequencies(p: SailParameters, solver: str = "reduced") -> np.ndarray:
    """ω (rad/s, ascending) of the chain with its supports linearised at the flat state at rest, from the
    named solver's "eigenfrequencies" (module docstring)."""
    return contract.lookup(solver, p).capability("eigenfrequencies")(flat(p))


def elastic(omega: np.ndarray, p: SailParameters) -> np.ndarray:
    """The elastic ω of a solver's spectrum: without the 3 rigid-body modes (x, y, rotation) of a free
    chain (their ω are round-off of the difference quotients, not exactly 0); supported chains have none."""
    return np.asarray(omega, float)[RIGID_MODES[p.boundary] :]
