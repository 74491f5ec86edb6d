"""What the reduced-Lagrangian solvers offer analysis besides a run (solvers.contract, rules 9 and 10).

The chain's equations of motion in minimal coordinates q = (x₁, y₁, θ, z) (Eqs 13–16, 30–32), their
linearisation, the static state and the spectrum of the supported chain, and the default options of the
chain and sheet runs. Analysis reaches them through ``lookup("reduced", params).capability(name)``.

* ``linearise``: ∂ẏ/∂y of ẏ = (q̇, q̈(q, q̇)) at rest in a state, by central differences with all
  columns in one vectorised call of the compiled right-hand side.
* ``eigenfrequencies``: the right-hand side of the supported chain (ChainDynamics for free chains,
  BoundedChainDynamics with supports) differentiated by central differences about the initial state at
  rest, A = ∂q̈/∂q, restricted to the tangent space of the supports (orthonormal basis N: the free
  coordinates of the cantilever, the null space of G for the pinned chain); ω² = −eig(Nᵀ A N).
* ``statics``: Newton on the accelerations at rest, q̈_f(q) = 0 on the free coordinates of the clamped
  chain (q̈ = M⁻¹Q at q̇ = 0, so this is Q_f(q) = 0), with Nᵀ A N as a fixed (chord) Newton matrix; a
  tip load adds only ≈ P L²/EI relative load stiffness, so a few iterations reach round-off.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import shapes
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.solvers.reduced.dynamics import ChainDynamics
from lightsail_mbs.solvers.reduced.kinematics import ChainModel, body_forces, centre_jacobian, centres, torsion_torques
from lightsail_mbs.solvers.reduced.sampling import state_scales

# Central-difference step of the eigenfrequencies (rad for angles, × l for positions): the error
# ∝ (ω_max/ω₁)² step² from the geometric nonlinearity plus round-off ∝ 1/step is ≈ 1e-11 on the
# validation chains at 1e-8.
MODE_STEP = 1e-8
NEWTON_ITERATIONS = 20
NEWTON_TOLERANCE = 1e-14  # relative to the largest coordinate change of the first iterate


class ChainEquations:
    """The free chain's equations of motion (capability "equations"; supports are not applied): y = (q, q̇)
    with q = (x₁, y₁, θ₁…θₙ, z₁…zₙ₋₁) (z only for the extensible chain)."""

    def __init__(self, p: SailParameters):
        self.model = ChainModel.from_params(p)
        self.dof = self.model.dof
        self.dynamics = ChainDynamics(self.model)
        self.rhs = self.dynamics.rhs  # ẏ(t, y): one state (2·dof,) or columns (2·dof, k)
        self.accelerations = self.dynamics.accelerations  # q̈(q, q̇): states (dof,) or (dof, k)

    def coordinates(self, state: shapes.ChainState) -> np.ndarray:
        """q of a chain state."""
        return self.model.pack(state.x[0], state.y[0], state.theta, state.z)

    def centres(self, q: np.ndarray):
        """Slice centres (x_j, y_j), each (n, …), of q (dof, …)."""
        return centres(self.model, q)

    def angles(self, q: np.ndarray) -> np.ndarray:
        """The slice angles θ (n, …) of q (dof, …)."""
        return self.model.split(q)[2]

    def state_scales(self, waves: float) -> np.ndarray:
        """Typical magnitudes of y (the absolute tolerances of a run; sampling.state_scales)."""
        return state_scales(self.model, waves)

    def slice_loads(self, state: shapes.ChainState):
        """(F_x, F_y, τ) on each slice at rest in `state`: the load and frame force at the centres with the
        end tensions, and the bending torques."""
        fx, fy = body_forces(self.model, state.x, state.theta)
        return fx, fy, torsion_torques(self.model, state.theta, np.zeros_like(state.theta))


def linearise(p: SailParameters, state: shapes.ChainState, step: float, positions_only: bool = False) -> np.ndarray:
    """∂ẏ/∂y of the free chain at rest in `state`, y = (q, q̇) (2·dof square), central differences of
    size `step`; with ``positions_only`` its first dof columns (2·dof × dof)."""
    equations = ChainEquations(p)
    q0 = equations.coordinates(state)
    y0 = np.concatenate([q0, np.zeros_like(q0)])
    size = y0.size
    shifts = step * np.eye(size)[:, : q0.size if positions_only else size]
    cols = np.concatenate([y0[:, None] + shifts, y0[:, None] - shifts], axis=1)
    dof = equations.dof
    acc = equations.accelerations(cols[:dof], cols[dof:])
    rates = np.concatenate([cols[dof:], acc])
    half = shifts.shape[1]
    return (rates[:, :half] - rates[:, half:]) / (2.0 * step)


def acceleration_jacobian(p: SailParameters):
    """(A = ∂q̈/∂q at the initial state at rest, N: orthonormal basis of the supports' tangent space)."""
    from lightsail_mbs.solvers.reduced.supports import dynamics_of

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


def eigenfrequencies(p: SailParameters) -> np.ndarray:
    """ω (rad/s, ascending) of the chain with its supports linearised at rest in its initial state."""
    A, N = acceleration_jacobian(p)
    w2 = -np.linalg.eigvals(N.T @ A @ N).real
    return np.sort(np.sqrt(np.clip(w2, 0.0, None)))


def statics(p: SailParameters) -> shapes.ChainState:
    """The static state of the cantilever under its loads (module docstring), from its initial state."""
    from lightsail_mbs.solvers.reduced.supports import dynamics_of

    if p.boundary != "cantilever":
        raise ParameterError(f"boundary={p.boundary!r} is invalid for the reduced static solve: allowed 'cantilever'")
    dynamics, model = dynamics_of(p)
    start = shapes.initial_state(p)
    q = model.pack(start.x[0], start.y[0], start.theta, start.z)
    A, N = acceleration_jacobian(p)
    chord = np.linalg.inv(N.T @ A @ N)
    rest = np.zeros(model.dof)
    first = None
    for _ in range(NEWTON_ITERATIONS):
        step = -N @ (chord @ (N.T @ dynamics.rhs(0.0, np.concatenate([q, rest]))[model.dof :]))
        q = q + step
        size = np.max(np.abs(step))
        first = first or size
        if size <= NEWTON_TOLERANCE * first:
            break
    else:
        raise RuntimeError(f"reduced static Newton did not converge for n={p.n}")
    x, y = centres(model, q[:, None])
    _, _, theta, z = model.split(q)
    return shapes.ChainState(x=x[:, 0], y=y[:, 0], theta=theta, z=z)


def chain_defaults(params: SailParameters, settings: RunSettings, **options) -> dict:
    """The options of a reduced chain run given `options` (contract rule 10): the method "auto" resolves to
    (solver.choose_method), its rtol (solver.DEFAULT_RTOL; supports.DEFAULT_RTOL with supports or a tip
    load), atol = rtol × the state scales; max_step and first_step are left to the integrator (None)."""
    from lightsail_mbs.solvers.reduced import solver

    method = options.get("method")
    if params.boundary != "free" or params.tip_load != 0.0:
        from lightsail_mbs.solvers.reduced import supports  # scipy's stiff integrators: imported where used

        method, rtol, waves = method or "Radau", supports.DEFAULT_RTOL, 1.0
    else:
        method = solver.choose_method(params)[0] if method in (None, "auto") else method
        rtol, waves = solver.DEFAULT_RTOL.get(method, 1e-6), params.defect_mode
    rtol = options.get("rtol") or rtol
    atol = options.get("atol")
    return {
        "method": method,
        "rtol": rtol,
        "atol": rtol * state_scales(ChainModel.from_params(params), waves) if atol is None else atol,
        "max_step": options.get("max_step"),
        "first_step": options.get("first_step"),
        "perturbation": options.get("perturbation") or 0.0,
    }


def sheet_defaults(params: SailParameters, settings: RunSettings, **options) -> dict:
    """The options of a reduced sheet run given `options` (contract rule 10): those the run takes, checked and
    completed with its defaults (sheet_options.checked_options; the turning frame for a spinning sheet)."""
    from lightsail_mbs.solvers.reduced.sheet_options import checked_options

    return dataclasses.asdict(checked_options(options, params))
