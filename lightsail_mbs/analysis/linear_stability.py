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

Eigenfrequencies of the chain about the flat state with its supports (the classic validations of
Appendices A–B), from each solver's own equations, are here too:

* exudyn: the assembled Exudyn system (supports included) and Exudyn's ``ComputeODE2Eigenvalues`` (mass
  matrix and static-solver Jacobian at the flat state; with supports, Exudyn projects both on the null
  space of the constraint Jacobian). Exudyn solves the symmetric problem K v = ω² M v, so this is meant
  for conservative linearisations (intensity = 0).
* reduced: the reduced solver's q̈(q, q̇) (ChainDynamics for free chains, BoundedChainDynamics with
  supports) differentiated by central differences about the flat state at rest, A = ∂q̈/∂q, restricted
  to the tangent space of the supports (orthonormal basis N: the free coordinates of the cantilever, the
  null space of G for the pinned chain); ω² = −eig(Nᵀ A N).

Two independent linearisations of the lit free sail, both at the flat state:

* reduced solver: central-difference Jacobian of ẏ = (q̇, q̈(q, q̇)) (reduced_dynamics), all
  columns in one vectorised call;
* Exudyn: M and the elastic/tension stiffness K from ``ComputeLinearizedSystem`` of the unlit
  KinematicTree, plus the load stiffness by central differences of the tree's own load
  function (solvers.exudyn.tree.generalized_force: the net slice force, frame force included).
  Exudyn's own forward-difference Jacobian of the lit system is also available
  (``exudyn_load="solver"``); forward differences of a load that is itself second order in the
  angles are noisy to ≈ 1 % of the softest bending frequencies, whatever the difference step
  (scenario stability_linear.py shows it).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import shapes
from lightsail_mbs.model.parameters import SailParameters

# modes without restoring force by support: a free sail translates in x, y and rotates
RIGID_MODES = {"free": 3, "cantilever": 0, "pinned": 0}
FD_STEP = 1e-6  # central-difference step of the lit sail's Jacobian: rad for angles, m for positions
# Central-difference step of the eigenfrequencies (rad for angles, × l for positions): the error
# ∝ (ω_max/ω₁)² step² from the geometric nonlinearity plus round-off ∝ 1/step is ≈ 1e-11 on the
# validation chains at 1e-8.
MODE_STEP = 1e-8


def flat(p: SailParameters) -> SailParameters:
    """The same sail without its defect (a₀ = 0): the flat equilibrium state."""
    return p.replace(defect_amplitude=0.0)


def unlit(p: SailParameters) -> SailParameters:
    """The same sail without the beam (I₀ = 0, hence g₀ = 0): the unloaded chain."""
    return p.replace(intensity=0.0)


# ---- reduced solver ------------------------------------------------------------------------
def reduced_jacobian(
    p: SailParameters, step: float = FD_STEP, state: shapes.ChainState | None = None, *, positions_only: bool = False
) -> np.ndarray:
    """∂ẏ/∂y of the reduced model at rest in `state` (default: the flat state), y = (q, q̇)
    (2·dof square), central differences; with ``positions_only`` its first dof columns (2·dof × dof)."""
    from lightsail_mbs.solvers.reduced.dynamics import ChainDynamics
    from lightsail_mbs.solvers.reduced.kinematics import ChainModel

    if state is None:
        p = flat(p)
        state = shapes.initial_state(p)
    model = ChainModel.from_params(p)
    q0 = model.pack(state.x[0], state.y[0], state.theta, state.z)
    y0 = np.concatenate([q0, np.zeros_like(q0)])
    size = y0.size
    shifts = step * np.eye(size)[:, : q0.size if positions_only else size]
    cols = np.concatenate([y0[:, None] + shifts, y0[:, None] - shifts], axis=1)
    dof = model.dof
    acc = ChainDynamics(model).accelerations(cols[:dof], cols[dof:])
    rates = np.concatenate([cols[dof:], acc])
    half = shifts.shape[1]
    return (rates[:, :half] - rates[:, half:]) / (2.0 * step)


def growth_modes(p: SailParameters) -> tuple[np.ndarray, np.ndarray]:
    """Growth rates Re λ (s⁻¹, descending) and angle parts (n × modes, columns) of the eigenmodes of the reduced
    model linearised at rest in its initial state (:func:`reduced_jacobian` at ``shapes.initial_state(p)``: the
    defect shape under the load, where the load's second-order terms act at first order).

    Without dampers (the only velocity-linear terms) ∂ẏ/∂y = [[0, I], [A, 0]] at rest and λ = ±√μ, μ = eig(A): the
    dof position columns and the eigenproblem of the dof × dof block A = ∂q̈/∂q; with dampers the whole 2·dof
    Jacobian."""
    damped = p.total_torsional_damping > 0 or p.total_axial_damping > 0
    jac = reduced_jacobian(p, state=shapes.initial_state(p), positions_only=not damped)
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


# ---- Exudyn --------------------------------------------------------------------------------
def exudyn_linearization(
    p: SailParameters, *, exudyn_load: str = "central", step: float = FD_STEP, relative_epsilon: float | None = None
):
    """(M, K) of the Exudyn KinematicTree at the flat state: M q̈ + K q = 0 (K not symmetric with load).

    exudyn_load="central": K = K_exudyn(unlit) − ∂Q_net/∂q by central differences of the tree's load
    function (radiation and frame force); "solver": Exudyn's own Jacobian of the lit system (forward
    differences with ``relative_epsilon``, Exudyn's default 1e-7, on coordinates ≥ 1).
    """
    import exudyn as exu

    from lightsail_mbs.solvers.exudyn import chain as exudyn_chain
    from lightsail_mbs.solvers.exudyn.console import silenced
    from lightsail_mbs.solvers.exudyn.tree import generalized_force

    if exudyn_load not in ("central", "solver"):
        raise ParameterError(f"exudyn_load={exudyn_load!r} is invalid: allowed 'central' or 'solver'")
    p = flat(p)
    settings = exu.SimulationSettings()
    if relative_epsilon is not None:
        settings.staticSolver.newton.numericalDifferentiation.relativeEpsilon = float(relative_epsilon)
        settings.staticSolver.newton.numericalDifferentiation.minimumCoordinateSize = 1.0
    with silenced():
        system = exudyn_chain.build(p if exudyn_load == "solver" else unlit(p))
        mbs, layout = system[1], system[2]
        mass, stiffness, _ = mbs.ComputeLinearizedSystem(settings)
    if exudyn_load == "solver":
        return np.asarray(mass), np.asarray(stiffness)
    beam, tension_only = generalized_force(p, layout), generalized_force(unlit(p), layout)
    q0 = layout.coordinates(shapes.initial_state(p))

    def load(q):
        return beam(q).copy() - tension_only(q)

    jac = np.column_stack([(load(q0 + step * e) - load(q0 - step * e)) / (2 * step) for e in np.eye(q0.size)])
    return np.asarray(mass), np.asarray(stiffness) - jac


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
    """The spectrum of the flat accelerating sail linearised with the named solver."""
    if solver == "reduced":
        return spectrum_of_jacobian(reduced_jacobian(p, **options))
    if solver == "exudyn":
        return spectrum_of_system(*exudyn_linearization(p, **options))
    raise ParameterError(f"solver={solver!r} is invalid: allowed 'reduced' or 'exudyn'")


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
def exudyn_angular_frequencies(p: SailParameters) -> np.ndarray:
    """ω (rad/s) from Exudyn's ComputeODE2Eigenvalues of the built system (flat state)."""
    from lightsail_mbs.solvers.exudyn import chain as exudyn_chain
    from lightsail_mbs.solvers.exudyn.console import silenced

    with silenced():
        _, mbs, *_ = exudyn_chain.build(flat(p))
        values, _ = mbs.ComputeODE2Eigenvalues()
    return np.sort(np.sqrt(np.abs(np.asarray(values, float))))


def reduced_acceleration_jacobian(p: SailParameters):
    """(A = ∂q̈/∂q at the flat state at rest, N: orthonormal basis of the supports' tangent space)."""
    from lightsail_mbs.solvers.reduced.kinematics import centre_jacobian
    from lightsail_mbs.solvers.reduced.supports import dynamics_of

    p = flat(p)
    dynamics, model = dynamics_of(p)
    start = shapes.initial_state(p)
    q0 = model.pack(start.x[0], start.y[0], start.theta, start.z)
    dof = model.dof
    scale = np.full(dof, p.slice_length)
    scale[2 : p.n + 2] = 1.0  # angles (rad)
    step = MODE_STEP * scale
    shifts = np.concatenate([np.diag(step), -np.diag(step)], axis=1)
    states = np.concatenate([q0[:, None] + shifts, np.zeros((dof, 2 * dof))])
    qdd = np.stack([dynamics.rhs(0.0, state)[dof:] for state in states.T], axis=1)
    A = (qdd[:, :dof] - qdd[:, dof:]) / (2 * step)
    if p.boundary == "pinned":
        from scipy.linalg import null_space

        basis = null_space(dynamics.constraint_jacobian(q0, centre_jacobian(model, q0)))
    elif p.boundary == "cantilever":
        basis = np.eye(dof)[:, dynamics.free]
    else:
        basis = np.eye(dof)
    return A, basis


def reduced_angular_frequencies(p: SailParameters) -> np.ndarray:
    """ω (rad/s) of the reduced solver's linearised right-hand side (module docstring)."""
    A, N = reduced_acceleration_jacobian(p)
    w2 = -np.linalg.eigvals(N.T @ A @ N).real
    return np.sort(np.sqrt(np.clip(w2, 0.0, None)))


def elastic(omega: np.ndarray, p: SailParameters) -> np.ndarray:
    """The elastic ω of a solver's spectrum: without the 3 rigid-body modes (x, y, rotation) of a free
    chain (their ω are round-off of the difference quotients, not exactly 0); supported chains have none."""
    return np.asarray(omega, float)[RIGID_MODES[p.boundary] :]
