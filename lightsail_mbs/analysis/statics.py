"""Static equilibrium of a supported chain under its full tip load, from each solver's own equations.

* exudyn: the assembled system (solvers.exudyn_chain.build with its supports) and Exudyn's static
  solver (``mbs.SolveStatic``, Newton on the constrained equilibrium) with P = P₀;
* reduced: Newton on the reduced solver's accelerations at rest, q̈_f(q) = 0 on the free
  coordinates of the clamped chain (q̈ = M⁻¹Q at q̇ = 0, so this is Q_f(q) = 0), with the
  linearised Jacobian of linear_stability.reduced_acceleration_jacobian as a fixed (chord) Newton matrix; the
  tip load adds only ≈ P L²/EI relative load stiffness, so a few iterations reach round-off.

Meant for the cantilever validation (paper Appendix A): the load is the constant P₀ (τ ignored).
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import shapes
from lightsail_mbs.model.parameters import SailParameters

NEWTON_ITERATIONS = 20
NEWTON_TOLERANCE = 1e-14  # relative to the largest coordinate change of the first iterate


def full_load(p: SailParameters) -> SailParameters:
    """The case with its tip load at P₀ from the start (τ = 0), flat and unlit."""
    return p.replace(tip_load_time_constant=0.0, defect_amplitude=0.0, intensity=0.0)


def static_state(p: SailParameters, solver: str = "exudyn") -> shapes.ChainState:
    """Slice centres, angles and extensions of the static equilibrium under P₀ (module docstring)."""
    if solver == "exudyn":
        return _exudyn_static(full_load(p))
    if solver == "reduced":
        return _reduced_static(full_load(p))
    raise ParameterError(f"solver={solver!r} is invalid: allowed 'exudyn' or 'reduced'")


def _exudyn_static(p: SailParameters) -> shapes.ChainState:
    import exudyn as exu

    from lightsail_mbs.solvers.exudyn import chain as exudyn_chain
    from lightsail_mbs.solvers.exudyn.console import silenced

    settings = exu.SimulationSettings()
    settings.solution.file.write = False
    settings.linearSolver.solverType = exu.LinearSolverType.EXUdense
    settings.staticSolver.verboseMode = 0
    settings.staticSolver.newton.relativeTolerance = 1e-12
    with silenced():
        _, mbs, layout, *_ = exudyn_chain.build(p)
        if not mbs.SolveStatic(settings):
            raise RuntimeError(f"Exudyn static solver did not converge for n={p.n}")
        q = np.array(mbs.systemData.GetODE2Coordinates())
    x, y, theta, z = layout.positions(q)
    return shapes.ChainState(x=x, y=y, theta=theta, z=z)


def _reduced_static(p: SailParameters) -> shapes.ChainState:
    from lightsail_mbs.analysis.linear_stability import reduced_acceleration_jacobian
    from lightsail_mbs.solvers.reduced.kinematics import centres
    from lightsail_mbs.solvers.reduced.supports import dynamics_of

    if p.boundary != "cantilever":
        raise ParameterError(f"boundary={p.boundary!r} is invalid for the reduced static solve: allowed 'cantilever'")
    dynamics, model = dynamics_of(p)
    start = shapes.initial_state(p)
    q = model.pack(start.x[0], start.y[0], start.theta, start.z)
    A, N = reduced_acceleration_jacobian(p)
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
