"""Round-off budget of the soft torsion sail: what each formulation injects, what the chain makes of it.

Writes validation/roundoff.md. The paper's soft torsion sail (Fig. 7, n = 30, E = 4.5e9 Pa), over 0.3 s:

1. **Injected.** Each formulation's slice angular accelerations θ̈ at the initial state against an
   extended-precision reference: the joint-force recursion of solvers.reduced.dynamics written again in
   numpy ``longdouble`` (x87 80-bit, ε = 1.1e-19) with the net load of model.loads, solved by Gaussian
   elimination. Formulations: the reduced solver and Exudyn as they are (net slice force, cancellation done
   analytically), the same joint-force recursion in double with the per-slice sum f₀cos³θ − m g₀ (the
   reduced solver's former load), and Exudyn with the frame force as the tree's gravity and the
   radiation load alone in the force function (its former formulation).
2. **Response.** The growth the linearisation predicts: the error pattern e held as a constant forcing
   of the chain linearised about its initial state, ẏ = A y + (0, e), A the reduced solver's Jacobian
   (its unstable modes grow at up to 7/s), integrated exactly (matrix exponential); the predicted
   deviation is max|Δθ(t)| / max|θ(t)|.
3. **Observed.** Exudyn at refined steps (generalized-α, tight Newton) and tolerances (DOPRI5) against
   the reduced solver at rtol 1e-13, and the reduced solver at its own tolerances; the level double
   precision allows: twin runs of the reduced solver whose start differs by a seeded roughness of
   1e-15 a₀ (a few ulps of the coordinates).

    python validation/roundoff.py    # about 2 min
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import scipy.linalg

from lightsail_mbs import RunSettings, paper_case, solve
from lightsail_mbs.model import loads, shapes
from lightsail_mbs.model.parameters import SPEED_OF_LIGHT
from lightsail_mbs.solvers.reduced.dynamics import ChainDynamics
from lightsail_mbs.solvers.reduced.kinematics import ChainModel

CASE = paper_case("torsion-soft")
RUN = RunSettings(t_final=0.3, output_interval=0.01)
TIMES = (0.01, 0.1, 0.3)


# ---- 1. injected ------------------------------------------------------------------------------
def recursion_accelerations(p, theta, omega, dtype=np.longdouble, naive: bool = False) -> np.ndarray:
    """θ̈ of the free inextensible chain (uniform mirror, no tension) by the joint-force recursion in `dtype`:
    the net load written without cancellation (naive=False) or as f₀cos³θ − m g₀ per slice (naive=True)."""
    n = p.n
    th, om = np.asarray(theta, dtype), np.asarray(omega, dtype)
    one = dtype(1)
    l = dtype(p.length) / dtype(n)
    b = l / 2
    m = dtype(p.density) * dtype(p.thickness) * dtype(p.width) * l
    J = m * l * l / dtype(12)
    f0 = dtype(2) * dtype(p.intensity) / dtype(SPEED_OF_LIGHT) * l * dtype(p.width)
    k_t, c_t = dtype(p.torsional_stiffness), dtype(p.total_torsional_damping)
    c, s = np.cos(th), np.sin(th)
    fx = -f0 * c * c * s
    if naive:
        g0 = dtype(2) * dtype(p.intensity) / (dtype(SPEED_OF_LIGHT) * dtype(p.density) * dtype(p.thickness))
        fy = f0 * c * c * c - m * g0
    else:
        half = np.sin(th / 2)
        fy = -f0 * (2 * half * half) * (one + c + c * c)
    tau = np.zeros(n, dtype)
    moment = k_t * (th[1:] - th[:-1]) + c_t * (om[1:] - om[:-1])
    tau[:-1] += moment
    tau[1:] -= moment
    wx = -b * om[:-1] ** 2 * c[:-1] - b * om[1:] ** 2 * c[1:]
    wy = -b * om[:-1] ** 2 * s[:-1] - b * om[1:] ** 2 * s[1:]
    px, py = -s, c

    def slices(lx, ly):
        ax, ay, al = fx.copy(), fy.copy(), tau.copy()
        ax[1:] += lx
        ay[1:] += ly
        al[1:] -= b * (px[1:] * lx + py[1:] * ly)
        ax[:-1] -= lx
        ay[:-1] -= ly
        al[:-1] -= b * (px[:-1] * lx + py[:-1] * ly)
        return ax / m, ay / m, al / J

    def residual(ax, ay, al):
        gx = ax[1:] - ax[:-1] + b * al[:-1] * s[:-1] + b * al[1:] * s[1:] - wx
        gy = ay[1:] - ay[:-1] - b * al[:-1] * c[:-1] - b * al[1:] * c[1:] - wy
        return gx, gy

    zero = np.zeros(n - 1, dtype)
    g0x, g0y = residual(*slices(zero, zero))
    size = 2 * (n - 1)
    K = np.zeros((size, size), dtype)
    for j in range(size):
        unit = np.zeros(size, dtype)
        unit[j] = one
        gx, gy = residual(*slices(unit[0::2], unit[1::2]))
        K[0::2, j], K[1::2, j] = gx - g0x, gy - g0y
    rhs = np.empty(size, dtype)
    rhs[0::2], rhs[1::2] = -g0x, -g0y
    lam = _gauss(K, rhs)
    return slices(lam[0::2], lam[1::2])[2]


def _gauss(A, b):
    """Gaussian elimination with partial pivoting in A's dtype (numpy's solvers work in double)."""
    A, b = A.copy(), b.copy()
    size = len(b)
    for k in range(size):
        pivot = k + int(np.argmax(np.abs(A[k:, k])))
        A[[k, pivot]], b[[k, pivot]] = A[[pivot, k]], b[[pivot, k]]
        f = A[k + 1 :, k] / A[k, k]
        A[k + 1 :, k:] -= f[:, None] * A[k, k:]
        b[k + 1 :] -= f * b[k]
    x = np.zeros(size, A.dtype)
    for k in range(size - 1, -1, -1):
        x[k] = (b[k] - A[k, k + 1 :] @ x[k + 1 :]) / A[k, k]
    return x


def reduced_accelerations(p, state) -> np.ndarray:
    model = ChainModel.from_params(p)
    q = model.pack(state.x[0], state.y[0], state.theta, state.z)
    return ChainDynamics(model).accelerations(q, np.zeros_like(q))[2 : 2 + p.n]


def exudyn_accelerations(p, state, former: bool = False) -> np.ndarray:
    """θ̈ = cumsum of the relative-angle accelerations M⁻¹ RHS of the assembled Exudyn tree at rest in `state`;
    former=True: the frame force as the tree's gravity and the radiation load alone in the force function."""
    import exudyn as exu
    from exudyn.itemInterface import NodeGenericODE2, ObjectKinematicTree

    from lightsail_mbs.solvers.exudyn import chain
    from lightsail_mbs.solvers.exudyn.console import silenced
    from lightsail_mbs.solvers.exudyn.tree import ChainLayout, tree_arguments

    if not former:
        _, mbs, layout, _, _ = chain.build(p, state)
    else:
        layout = ChainLayout.of(p)
        q0 = layout.coordinates(state)
        load = radiation_generalized_force(p, layout)
        mbs = exu.SystemContainer().AddSystem()
        node = mbs.AddNode(
            NodeGenericODE2(
                referenceCoordinates=[0.0] * layout.size,
                initialCoordinates=q0,
                initialCoordinates_t=[0.0] * layout.size,
                numberOfODE2Coordinates=layout.size,
            )
        )
        arguments = tree_arguments(p, layout, exu)
        arguments["gravity"] = [0.0, -p.nominal_acceleration, 0.0]
        mbs.AddObject(
            ObjectKinematicTree(nodeNumber=node, forceUserFunction=lambda mbs, t, i, q, q_t: load(q), **arguments)
        )
        mbs.Assemble()
    settings = exu.SimulationSettings()
    settings.solution.file.write = False
    settings.timeIntegration.solverType = exu.DynamicSolverType.RK44
    solver = exu.MainSolverExplicit()
    with silenced():
        solver.InitializeSolver(mbs, settings)
        solver.ComputeMassMatrix(mbs)
        mass = np.asarray(solver.GetSystemMassMatrix())
        solver.ComputeODE2RHS(mbs)
        rhs = np.asarray(solver.GetSystemResidual())[: layout.size]
    return np.cumsum(np.linalg.solve(mass, rhs)[layout.angle_index])


def radiation_generalized_force(p, layout):
    """Virtual work of the radiation load alone (loads.radiation_forces) at the slice centres, q ↦ Q."""

    def force(q):
        q = np.asarray(q, float)
        theta = np.cumsum(q[layout.angle_index])
        e = np.exp(1j * theta)
        x, _, _, _ = layout.positions(q)
        fx, fy = loads.radiation_forces(p, x, theta)
        f = fx + 1j * fy
        carried = np.cumsum(f[::-1])[::-1] - f  # Σ_{k>j} f_k
        torque = p.slice_length * (np.conj(e) * carried).imag + 0.5 * p.slice_length * (np.conj(e) * f).imag
        Q = np.zeros(layout.size)
        Q[0], Q[1] = f.sum().real, f.sum().imag
        Q[layout.angle_index] = np.cumsum(torque[::-1])[::-1]
        return Q

    return force


# ---- 2. response --------------------------------------------------------------------------------
def predicted_deviation(p, state, error: np.ndarray, theta_scale: np.ndarray) -> list[float]:
    """max|Δθ(t)| / max|θ(t)| at TIMES for the constant forcing `error` (rad/s² per slice) of the chain
    linearised about its initial state (exact integration of ẏ = A y + e with the augmented exponential)."""
    model = ChainModel.from_params(p)
    q = model.pack(state.x[0], state.y[0], state.theta, state.z)
    y0 = np.concatenate([q, np.zeros_like(q)])
    from lightsail_mbs.solvers.reduced.sampling import state_scales

    A = ChainDynamics(model).jacobian(0.0, y0, state_scales(model, p.defect_mode))
    size = y0.size
    augmented = np.zeros((size + 1, size + 1))
    augmented[:size, :size] = A
    augmented[model.dof + 2 : model.dof + 2 + p.n, size] = error
    out = []
    for t, scale in zip(TIMES, theta_scale, strict=True):
        response = scipy.linalg.expm(augmented * t)[:size, size]
        out.append(float(np.abs(response[2 : 2 + p.n]).max() / scale))
    return out


# ---- 3. observed --------------------------------------------------------------------------------
def deviation(run, reference) -> list[float]:
    """max|Δθ| / max|θ| at TIMES (samples every 10 ms)."""
    out = []
    for t in TIMES:
        k = int(round(t / RUN.output_interval))
        out.append(float(np.abs(run.theta[k] - reference.theta[k]).max() / np.abs(reference.theta[k]).max()))
    return out


def row(cells) -> str:
    return "| " + " | ".join(cells) + " |"


def main() -> None:
    start = time.perf_counter()
    p = CASE
    state = shapes.initial_state(p)
    reference = recursion_accelerations(p, state.theta, np.zeros(p.n))
    peak = float(np.abs(reference).max())
    formulations = {
        "reduced (net slice force)": reduced_accelerations(p, state),
        "Exudyn (net slice force, gravity off)": exudyn_accelerations(p, state),
        "joint-force recursion, f₀cos³θ − m g₀ per slice (reduced, former)": recursion_accelerations(
            p, state.theta, np.zeros(p.n), np.float64, naive=True
        ),
        "Exudyn, gravity −m g₀ + radiation load (former)": exudyn_accelerations(p, state, former=True),
    }
    clean = solve(p, "reduced", RUN, rtol=1e-13, uncertainty=False)
    theta_scale = [float(np.abs(clean.theta[int(round(t / RUN.output_interval))]).max()) for t in TIMES]
    lines = [
        "# Round-off budget: the soft torsion sail over 0.3 s",
        "",
        "Generated by `python validation/roundoff.py` (see its docstring for the method). The paper's soft "
        f"torsion sail (n = {p.n}, E = 4.5e9 Pa, a₀ = 10 µm, ν = 3/2), max |θ̈| = {peak:.3g} rad/s² at rest in "
        "its initial shape. Deviations are max |Δθ| / max |θ| at 0.01 / 0.1 / 0.3 s.",
        "",
        "## Injected error and the growth the linearisation predicts",
        "",
        row(["formulation", "RMS error of θ̈ (rad/s²)", "max error / max θ̈", "predicted deviation 0.01 / 0.1 / 0.3 s"]),
        "|---|---|---|---|",
    ]
    for name, acc in formulations.items():
        error = np.asarray(acc - reference, float)
        predicted = predicted_deviation(p, state, error, theta_scale)
        lines.append(
            row(
                [
                    name,
                    f"{np.sqrt(np.mean(error**2)):.2g}",
                    f"{np.abs(error).max() / peak:.2g}",
                    " / ".join(f"{d:.1e}" for d in predicted),
                ]
            )
        )
        print(lines[-1], flush=True)
    lines += [
        "",
        "## Observed: Exudyn and the reduced solver against the reduced solver at rtol 1e-13",
        "",
        row(["run", "deviation 0.01 / 0.1 / 0.3 s", "steps"]),
        "|---|---|---|",
    ]
    runs = [(f"reduced, rtol {rtol:g}", "reduced", dict(rtol=rtol)) for rtol in (1e-9, 1e-11)]
    runs += [
        (
            f"Exudyn generalized-α, h = {h * 1e3:g} ms, Newton 1e-12",
            "exudyn",
            dict(step_size=h, newton_rel_tol=1e-12, newton_abs_tol=1e-22),
        )
        for h in (1e-3, 2.5e-4, 6.25e-5, 1.5625e-5)
    ]
    runs += [(f"Exudyn DOPRI5, rtol {rtol:g}", "exudyn", dict(method="DOPRI5", rtol=rtol)) for rtol in (1e-7, 1e-10)]
    runs += [
        (
            "reduced twin, start + seeded roughness 1e-15 a₀ (double precision's level)",
            "reduced",
            dict(rtol=1e-13, perturbation=1e-15 * p.defect_amplitude),
        )
    ]
    observed = {}
    for name, solver, options in runs:
        result = solve(p, solver, RUN, uncertainty=False, **options)
        observed[name] = deviation(result, clean)
        lines.append(row([name, " / ".join(f"{d:.1e}" for d in observed[name]), str(result.info["steps"])]))
        print(lines[-1], flush=True)
    injected = {name: np.abs(np.asarray(acc - reference, float)).max() / peak for name, acc in formulations.items()}
    former, exact = "Exudyn, gravity −m g₀ + radiation load (former)", "Exudyn (net slice force, gravity off)"
    finest = observed[runs[5][0]][-1]
    dopri = [observed[name][-1] for name, _, options in runs if options.get("method") == "DOPRI5"]
    floor = observed[runs[-1][0]][-1]
    predicted_exact = predicted_deviation(p, state, np.asarray(formulations[exact] - reference, float), theta_scale)[-1]
    lines += [
        "",
        "## Reading",
        "",
        f"* **Where the former ~1e-7 floor came from.** Exudyn's former formulation added the tree's gravity "
        f"−m g₀ and the radiation load as generalized forces of order f₀ n L/2 that cancel to about 1e-8 of "
        f"each: its θ̈ was wrong by {injected[former]:.1g} of max |θ̈|, concentrated at short waves. Held as a "
        "constant forcing of the linearised chain this predicts the deviation of 0.3 s to within an order of "
        "magnitude (an upper bound later on: the real error pattern changes with the state and partly averages "
        "out); no Newton tolerance touches it, because it is in the right-hand side, not in the solve.",
        f"* **Now.** With the net slice force (the cancellation done analytically, gravity off) Exudyn injects "
        f"{injected[exact]:.1g} of max |θ̈| (the remaining round-off of its mass-matrix solve in relative "
        f"coordinates), the reduced solver {injected['reduced (net slice force)']:.1g}. Exudyn's deviation from "
        f"the reduced solution at 0.3 s falls as h² with generalized-α's step down to {finest:.1g} at "
        f"h = 15.6 µs, and DOPRI5 sits at {min(dopri):.2g}–{max(dopri):.2g} at rtol 1e-7 and 1e-10 alike: that is "
        f"Exudyn's own round-off floor, about 1e5 times below the former one.",
        f"* **The level double precision allows** (twin runs of the reduced solver whose start differs by a "
        f"few ulps): {floor:.1g} at 0.3 s. Exudyn's floor ({min(dopri):.1g}) is about {min(dopri) / floor:.0f}× "
        f"above it; the budget predicts {predicted_exact:.1g} from Exudyn's injected error, "
        f"{min(dopri) / predicted_exact:.0f}× below what is observed — the same order of magnitude, so the "
        "remaining gap is Exudyn's own arithmetic (its relative-coordinate mass matrix), not an error in the "
        "model or the load. Neither floor matters for an answer: the uncertainty estimate's probe perturbs the "
        "start by 1e-12 a₀, far above both.",
        "",
        f"({time.perf_counter() - start:.0f} s on the shared 2-core machine.)",
        "",
    ]
    path = Path(__file__).with_name("roundoff.md")
    path.write_text("\n".join(lines))
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
