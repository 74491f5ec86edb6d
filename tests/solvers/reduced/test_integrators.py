"""The reduced solver's compiled integrators (dop853, radau) are scipy's methods: same steps, same states."""

import numpy as np

from lightsail_mbs import RunSettings, paper_case, solve
from lightsail_mbs.model import shapes
from lightsail_mbs.solvers.reduced import solver as reduced
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


def test_compiled_radau_takes_scipys_steps():
    """The compiled Radau IIA is scipy's method (same Jacobian): same steps, Jacobians and LU
    factorisations, same state to round-off (extensible TnT, stiff axial springs)."""
    from scipy.integrate import Radau

    p, t_final = paper_case("tnt-stable"), 0.05
    model = ChainModel.from_params(p)
    dyn = ChainDynamics(model)
    state = shapes.initial_state(p)
    q0 = model.pack(state.x[0], state.y[0], state.theta, state.z)
    y0 = np.concatenate([q0, np.zeros_like(q0)])
    rtol = reduced.DEFAULT_RTOL["Radau"]
    atol = rtol * state_scales(model, p.defect_mode)
    scales = atol / rtol
    compiled = CompiledRadau(dyn.constants, y0, t_final, rtol, atol, scales)
    compiled.advance(np.array([t_final]))
    ref = Radau(dyn.rhs, 0.0, y0, t_final, rtol=rtol, atol=atol, jac=lambda t, y: dyn.jacobian(t, y, scales))
    steps = 0
    while ref.status == "running":
        ref.step()
        steps += 1
    assert (compiled.steps, compiled.njev, compiled.nlu) == (steps, ref.njev, ref.nlu) and steps > 5
    np.testing.assert_allclose(compiled.y, ref.y, rtol=0, atol=1e-12 * np.abs(ref.y).max())
