"""What the Exudyn solvers offer analysis besides a run (solvers.contract, rules 9 and 10).

For the chain, from the assembled system of chain.build (supports included):

* ``mass_stiffness``: M and K of M q̈ + K q = 0 at the initial state from Exudyn's
  ``ComputeLinearizedSystem``. With ``load="central"``, K is that of the unlit system minus the load
  stiffness ∂Q/∂q by central differences of the tree's own load function (tree.generalized_force: the net
  slice force, frame force included); with ``load="solver"``, Exudyn's own forward-difference Jacobian of
  the lit system (``relative_epsilon``: its relative difference step, Exudyn's default 1e-7, on
  coordinates ≥ 1). K is not symmetric with the load.
* ``eigenfrequencies``: Exudyn's ``ComputeODE2Eigenvalues`` (mass matrix and static-solver Jacobian at the
  initial state; with supports, Exudyn projects both on the null space of the constraint Jacobian). It
  solves the symmetric problem K v = ω² M v, so it is meant for conservative linearisations (unlit).
* ``statics``: Exudyn's static solver (``mbs.SolveStatic``, Newton on the constrained equilibrium).

The sheet's statics and eigenfrequencies are sheet.static_centres and sheet.eigenfrequencies.
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import shapes
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.solvers.exudyn import chain
from lightsail_mbs.solvers.exudyn.console import silenced
from lightsail_mbs.solvers.exudyn.tree import generalized_force

LOADS = ("central", "solver")


def mass_stiffness(p: SailParameters, load: str, step: float, relative_epsilon: float | None = None):
    """(M, K) of the chain at rest in its initial state (module docstring); `step`: the central
    differences' step of the load stiffness (rad for angles, m for positions)."""
    import exudyn as exu

    if load not in LOADS:
        raise ParameterError(f"load={load!r} is invalid: allowed 'central' or 'solver'")
    unlit = p.replace(intensity=0.0)
    settings = exu.SimulationSettings()
    if relative_epsilon is not None:
        settings.staticSolver.newton.numericalDifferentiation.relativeEpsilon = float(relative_epsilon)
        settings.staticSolver.newton.numericalDifferentiation.minimumCoordinateSize = 1.0
    with silenced():
        system = chain.build(p if load == "solver" else unlit)
        mbs, layout = system[1], system[2]
        mass, stiffness, _ = mbs.ComputeLinearizedSystem(settings)
    if load == "solver":
        return np.asarray(mass), np.asarray(stiffness)
    beam, tension_only = generalized_force(p, layout), generalized_force(unlit, layout)
    q0 = layout.coordinates(shapes.initial_state(p))

    def net(q):
        return beam(q).copy() - tension_only(q)

    jac = np.column_stack([(net(q0 + step * e) - net(q0 - step * e)) / (2 * step) for e in np.eye(q0.size)])
    return np.asarray(mass), np.asarray(stiffness) - jac


def eigenfrequencies(p: SailParameters) -> np.ndarray:
    """ω (rad/s, ascending) from Exudyn's ComputeODE2Eigenvalues of the built chain."""
    with silenced():
        _, mbs, *_ = chain.build(p)
        values, _ = mbs.ComputeODE2Eigenvalues()
    return np.sort(np.sqrt(np.abs(np.asarray(values, float))))


def statics(p: SailParameters) -> shapes.ChainState:
    """Slice centres, angles and extensions of the chain's static equilibrium under its loads."""
    import exudyn as exu

    settings = exu.SimulationSettings()
    settings.solution.file.write = False
    settings.linearSolver.solverType = exu.LinearSolverType.EXUdense
    settings.staticSolver.verboseMode = 0
    settings.staticSolver.newton.relativeTolerance = 1e-12
    with silenced():
        _, mbs, layout, *_ = chain.build(p)
        if not mbs.SolveStatic(settings):
            raise RuntimeError(f"Exudyn static solver did not converge for n={p.n}")
        q = np.array(mbs.systemData.GetODE2Coordinates())
    x, y, theta, z = layout.positions(q)
    return shapes.ChainState(x=x, y=y, theta=theta, z=z)


def given(options: dict, name: str, default):
    """The option's value in `options`, or `default` when it is absent or None."""
    value = options.get(name)
    return default if value is None else value


def chain_defaults(params: SailParameters, settings: RunSettings, **options) -> dict:
    """The options of an Exudyn chain run given `options` (contract rule 10): the method "auto" resolves to,
    the rtol, and for generalized-α its step (chain.default_step_size, before it is made to divide the output
    interval) and Newton tolerances (× (rtol/DEFAULT_RTOL)²); DOPRI5 chooses its own steps (None)."""
    rtol = options.get("rtol") or chain.DEFAULT_RTOL
    step_size, rel_tol, abs_tol = (options.get(name) for name in ("step_size", "newton_rel_tol", "newton_abs_tol"))
    method, _ = chain._method(params, options.get("method") or "auto", step_size, rel_tol, abs_tol)
    implicit = method == "generalized-alpha"
    scale = (rtol / chain.DEFAULT_RTOL) ** 2
    if implicit:
        step_size = step_size or chain.default_step_size(params, settings, rtol)
        rel_tol = chain.NEWTON_REL_TOL * scale if rel_tol is None else rel_tol
        abs_tol = chain.default_abs_tol(params) * scale if abs_tol is None else abs_tol
    return {
        "method": method,
        "rtol": rtol,
        "step_size": step_size,
        "newton_rel_tol": rel_tol,
        "newton_abs_tol": abs_tol,
        "spectral_radius": given(options, "spectral_radius", chain.SPECTRAL_RADIUS if implicit else None),
        "samples_per_check": options.get("samples_per_check") or chain.SAMPLES_PER_CHECK,
        "perturbation": options.get("perturbation") or 0.0,
    }


def sheet_defaults(params: SailParameters, settings: RunSettings, **options) -> dict:
    """The options of an Exudyn sheet run given `options` (contract rule 10): sheet.default_step_size (before
    it is made to divide the output interval), sheet.NEWTON_REL_TOL, sheet.default_abs_tol, ρ∞."""
    from lightsail_mbs.solvers.exudyn import sheet

    abs_tol = options.get("newton_abs_tol")
    return {
        "step_size": options.get("step_size") or sheet.default_step_size(params, settings),
        "newton_rel_tol": options.get("newton_rel_tol") or sheet.NEWTON_REL_TOL,
        "newton_abs_tol": sheet.default_abs_tol(params) if abs_tol is None else abs_tol,
        "spectral_radius": given(options, "spectral_radius", sheet.SPECTRAL_RADIUS),
        "perturbation": options.get("perturbation") or 0.0,
    }
