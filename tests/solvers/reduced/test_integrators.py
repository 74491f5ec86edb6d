"""The reduced solver's compiled integrators: DOP853 takes scipy's steps; Radau IIA with the O(n) Newton matrix
agrees with scipy's Radau and with the explicit path."""

import numpy as np
import pytest

from lightsail_mbs import RunSettings, paper_case, paper_settings, solve
from lightsail_mbs.model import shapes
from lightsail_mbs.solvers.reduced.dynamics import ChainDynamics
from lightsail_mbs.solvers.reduced.kinematics import ChainModel
from lightsail_mbs.solvers.reduced.radau import Radau as CompiledRadau
from lightsail_mbs.solvers.reduced.sampling import state_scales


def test_compiled_dop853_takes_scipys_steps():
    """The compiled DOP853 is scipy's method on the same right-hand side: the same number of
    function evaluations (steps + dense-output stages) and the same states to round-off (at a loose
    tolerance: at tight ones round-off in the error estimate already moves the step sizes)."""
    from scipy.integrate import solve_ivp

    p, settings = paper_case("torsion-stable", n=10), RunSettings(t_final=0.5)
    r = solve(p, "reduced", settings, rtol=1e-6, uncertainty=False)
    model = ChainModel.from_params(p)
    q0 = model.pack(r.x[0, 0], r.y[0, 0], r.theta[0], np.zeros(0))
    ref = solve_ivp(
        ChainDynamics(model).rhs,
        (0, settings.t_final),
        np.concatenate([q0, np.zeros_like(q0)]),
        method="DOP853",
        rtol=r.info["rtol"],
        atol=r.info["rtol"] * state_scales(model, p.defect_mode),
        t_eval=r.time,
    )
    assert r.info["nfev"] == ref.nfev
    theta = ref.y[2 : p.n + 2].T
    np.testing.assert_allclose(r.theta, theta, rtol=0, atol=1e-12 * np.abs(theta).max())


def test_compiled_radau_agrees_with_scipys_radau():
    """The compiled Radau IIA (simplified Newton with the O(n) structured matrix of newton.py) integrates
    the same equations as scipy's Radau with the exact dense Jacobian: at a tight tolerance both give the
    same state to well inside the tolerance (extensible TnT, stiff axial springs)."""
    from scipy.integrate import Radau

    p, t_final = paper_case("tnt-stable", n=8), 0.02
    model = ChainModel.from_params(p)
    dyn = ChainDynamics(model)
    state = shapes.initial_state(p)
    q0 = model.pack(state.x[0], state.y[0], state.theta, state.z)
    y0 = np.concatenate([q0, np.zeros_like(q0)])
    rtol = 1e-10
    atol = rtol * state_scales(model, p.defect_mode)
    compiled = CompiledRadau(dyn.constants, y0, t_final, rtol, atol)
    compiled.advance(np.array([t_final]))
    ref = Radau(dyn.rhs, 0.0, y0, t_final, rtol=rtol, atol=atol, jac=lambda t, y: dyn.jacobian(t, y, atol / rtol))
    while ref.status == "running":
        ref.step()
    theta = slice(2, p.n + 2)
    assert compiled.t == t_final and compiled.steps > 10
    np.testing.assert_allclose(compiled.y[theta], ref.y[theta], rtol=0, atol=1e-7 * np.abs(ref.y[theta]).max())


def theta_difference(a, b):
    """max |Δθ| over the samples of two runs, relative to the largest |θ|."""
    assert a.theta.shape == b.theta.shape
    return np.abs(a.theta - b.theta).max() / np.abs(a.theta).max()


@pytest.mark.parametrize(
    "params, t_final",
    [
        (paper_case("torsion-soft", n=30), 1.0),
        (paper_case("torsion-soft", n=200), 0.3),
        (paper_case("tnt-soft", n=20, youngs_modulus=1e7), 0.5),
    ],
    ids=["torsion-soft-30", "torsion-soft-200", "tnt-extensible-soft-springs"],
)
def test_implicit_and_explicit_paths_agree(params, t_final):
    """The implicit path (Radau IIA with the O(n) Newton matrix) and the explicit one (DOP853) give the same
    trajectory to 1e-6 of its largest angle on cases both can run (the axial springs of the TnT chain made
    soft enough, E = 1e7 Pa, for the explicit method to resolve them)."""
    settings = RunSettings(t_final=t_final, stop_at_failure=False)
    explicit = solve(params, "reduced", settings, method="DOP853", rtol=1e-12)
    implicit = solve(params, "reduced", settings, method="Radau", rtol=1e-10)
    assert explicit.error is None and implicit.error is None
    assert explicit.info["method"] == "DOP853" and implicit.info["method"] == "Radau"
    assert theta_difference(explicit, implicit) < 1e-6


def test_failure_times_of_both_paths_agree():
    """Soft torsion to failure: the two paths at their default tolerances agree on t_f to 1e-4 (the run's
    own tolerance noise, amplified by the instability, is ~1e-5)."""
    p, settings = paper_case("torsion-soft"), paper_settings("torsion-soft")
    explicit = solve(p, "reduced", settings, method="DOP853")
    implicit = solve(p, "reduced", settings, method="Radau")
    assert abs(implicit.failure_time - explicit.failure_time) < 1e-4 * explicit.failure_time
