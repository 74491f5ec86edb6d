"""The Exudyn solver of the sheet (`solve(params, "exudyn")` for model "sheet"): native rigid bodies and
C++ edge connectors, one vectorised load exact at every Newton iterate.

Model (model.sheet): one ``NodeRigidBodyRxyz`` + ``ObjectRigidBody`` per tile (6 ODE2 coordinates:
centre displacement from the flat grid point and Tait–Bryan xyz angles, far from their singularity
at φ₁ = ±π/2 for a sail that stays nearly flat), one ``ObjectConnectorRigidBodySpringDamper``
(non-intrinsic) per shared edge and per supported boundary edge between edge-midpoint markers,
``LoadForceVector(bodyFixed=True)`` follower loads for the edge tension. The closed loops of the grid
rule out ``ObjectKinematicTree``.

The load (the physics terms' compiled forms, model.terms.tile_forces_into: radiation and frame force, net;
dead pressure; one compiled pass, solvers.exudyn.sheet_load): ``ObjectGenericODE2`` items of LOAD_BLOCK
nodes each (one spanning all N nodes makes Exudyn's one Jacobian O(N²): 17.6 s of CPU at 50 × 50 tiles against
0.27 s in blocks), whose constant ``forceVector`` (6 entries a node) is rewritten
by a ``PreNewtonResidualUserFunction`` before every residual evaluation from the current Newton
iterate. Exudyn calls that function before every residual,
including the one that decides convergence, but not while it differentiates the residual for the
Jacobian; so the converged state satisfies the equations with the load of that state, and the load's
own Jacobian is simply absent from the Newton matrix (modified Newton converges in 1.0–1.2 iterations
per step, one Jacobian per run; the load stiffness is ~1e-3 of the tiles' m/h²). Measured
alternatives (docs: sheet, "where the time goes"): the same load as the GenericODE2's
forceUserFunction is differentiated numerically at every Jacobian (×3 per step), one Python load
function per tile costs 400 calls per residual (×4.5), full Newton a numerical Jacobian of every
connector per iteration (×40), a dense LU ×9.

Integrator: generalized-α (ρ∞ = 0.9), modified Newton, sparse LU (Eigen), one fixed step h that
divides the output interval (default 0.026 √(L/g₀), 1 ms for the paper's sail, as the chain's);
a post-step function records the state on the output grid, checks failure every SAMPLES_PER_CHECK
samples and stops the solver there. A Newton failure, an Exudyn error or a non-finite state is
recorded in Result.error with the trajectory up to there.

Round-off: every connector differences marker positions of order L (Exudyn keeps positions as
reference + displacement), so its force carries ~k_∥ ε L of noise (k_∥ = E_m h e/s). Newton's absolute
tolerance is kept above that floor (default_abs_tol: requested below it, Newton iterates forever).
Where the floor exceeds the load's transverse force on a tile, f₀ θ² (θ the defect's slope), the
run's result depends on step and tolerance (measured: the stiff sail with E_m = E = 4.5e13 Pa), and
the Result carries a warning (round_off_warning): use the reduced solver, or a smaller membrane
modulus, which does not change 1-D results (docs: sheet).
"""

from __future__ import annotations

import math
import time as _time

import numpy as np

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import failure, sheet, sheet_payload, sheet_pose, sheet_ride, terms
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.model.sheet_grid import Tiles
from lightsail_mbs.model.terms.bodies import VELOCITIES
from lightsail_mbs.result import Result
from lightsail_mbs.solvers.exudyn.console import check_size, silenced, solve_steps
from lightsail_mbs.solvers.exudyn.sheet_load import COORDINATES, add_load_items, load_into
from lightsail_mbs.solvers.exudyn.sheet_tethers import add_payload_links
from lightsail_mbs.solvers.progress import Progress
from lightsail_mbs.solvers.skeleton import FailureMonitor
from lightsail_mbs.solvers.spun_start import spun_shape

STEP_FACTOR = 0.026  # h = STEP_FACTOR · sqrt(L/g₀), as the chain's
SPECTRAL_RADIUS = 0.9
NEWTON_REL_TOL = 1e-8
NEWTON_ABS_FACTOR = 1e-8  # the chain's rule: 1e-8 f₀ × defect slope
ROUND_OFF_FACTOR = 2.0  # Newton's absolute tolerance ≥ this × the residual's round-off floor
SAMPLES_PER_CHECK = 20
LOAD_BLOCK = 64  # nodes per ObjectGenericODE2 of the load: one spanning all makes its Jacobian O(N²)
ON_STEP = 1e-3  # a step within this many steps of an output time is taken as on it (round-off of Σh)
OPTIONS = ("step_size", "newton_rel_tol", "newton_abs_tol", "spectral_radius", "perturbation")


def default_step_size(p: SailParameters, settings: RunSettings) -> float:
    """h = STEP_FACTOR · sqrt(L/g₀), at most the output interval (which it then divides)."""
    g0 = p.nominal_acceleration
    h = STEP_FACTOR * math.sqrt(p.length / g0) if g0 > 0 else math.inf
    return min(h, settings.sample_interval)


def round_off_floor(p: SailParameters, conn: sheet.Connectors | None = None) -> float:
    """Estimated 2-norm of the residual's round-off (N): each connector differences marker positions of
    size ~max(L, W), so its force carries ~k_∥ ε max(L, W)."""
    conn = sheet.connectors(p) if conn is None else conn
    k = conn.stiffness[:, :2].max(axis=1)
    return float(np.finfo(float).eps * max(p.length, p.width) * np.sqrt(np.sum(k * k)))


def defect_slope(p: SailParameters) -> float:
    mode = p.defect_mode if p.defect_mode_y is None else max(p.defect_mode, p.defect_mode_y)
    return 2.0 * math.pi * mode * p.defect_amplitude / p.length


def default_abs_tol(p: SailParameters, conn: sheet.Connectors | None = None) -> float:
    """max(NEWTON_ABS_FACTOR × f₀ × defect slope (the chain's rule, f₀ per tile), ROUND_OFF_FACTOR ×
    round_off_floor): Newton cannot go below the round-off of the stiff in-plane springs (5e-11 N for
    the 30-tile chain limit at E = 4.5e9 Pa against 2e-14 N from the chain's rule)."""
    t = sheet.Tiles.of(p)  # the largest tile's area and mass
    flat_force = 2.0 * p.intensity / SPEED_OF_LIGHT * t.area
    scale = flat_force if flat_force > 0 else max(abs(p.pressure) * t.area, t.mass)
    slope = defect_slope(p)
    return max(NEWTON_ABS_FACTOR * scale * (slope if slope > 0 else 1.0), ROUND_OFF_FACTOR * round_off_floor(p, conn))


def round_off_warning(p: SailParameters, conn: sheet.Connectors | None = None) -> str | None:
    """A warning when one connector's round-off force k_∥ ε L exceeds the load's transverse force on a
    tile, f₀ θ² (module docstring); None otherwise or for an unlit sheet."""
    conn = sheet.connectors(p) if conn is None else conn
    t = sheet.Tiles.of(p)
    transverse = 2.0 * p.intensity / SPEED_OF_LIGHT * t.area * defect_slope(p) ** 2
    noise = np.finfo(float).eps * max(p.length, p.width) * float(conn.stiffness[:, :2].max())
    if transverse <= 0 or noise <= transverse:
        return None
    return (
        f"Exudyn's connector round-off (~{noise:.2g} N per connector at E_m = {t.membrane_modulus:.3g} Pa) exceeds "
        f"the load's transverse force on a tile (~{transverse:.2g} N): the result can depend on step and "
        "tolerance; use solver 'reduced' (no such floor) or a smaller membrane_modulus"
    )


def angular_velocity_xyz(angles: np.ndarray, rates: np.ndarray) -> np.ndarray:
    """Global angular velocity of R = R_x(φ₀)R_y(φ₁)R_z(φ₂): ω = φ̇₀ x̂ + R_x φ̇₁ ŷ + R_x R_y φ̇₂ ẑ."""
    p0, p1 = angles[..., 0], angles[..., 1]
    d0, d1, d2 = rates[..., 0], rates[..., 1], rates[..., 2]
    c0, s0, c1, s1 = np.cos(p0), np.sin(p0), np.cos(p1), np.sin(p1)
    return np.stack([d0 + s1 * d2, c0 * d1 - s0 * c1 * d2, s0 * d1 + c0 * c1 * d2], axis=-1)


class SheetSystem:
    """The assembled Exudyn system of one sheet case (module docstring).

    Attributes: SC, mbs, flat (grid points), centres0 and q0 (the initial shape), conn (connectors),
    generic (the load's ObjectGenericODE2 items, one per LOAD_BLOCK nodes), blocks (their node ranges),
    load_calls and load_time (the load updates so far).
    """

    def __init__(self, p: SailParameters, perturbation: float = 0.0):
        import exudyn as exu
        from exudyn.itemInterface import (
            LoadForceVector,
            MarkerBodyRigid,
            NodeRigidBodyRxyz,
            ObjectConnectorRigidBodySpringDamper,
            ObjectGround,
            ObjectRigidBody,
        )

        self.p = p
        self.tiles = sheet.Tiles.of(p)
        self.flat = sheet.flat_centres(p)
        self.centres0, self.q0 = sheet.initial_quaternions(p)
        self.conn = sheet.connectors(p, self.centres0, self.q0)
        self.payload = sheet_payload.payload(p, self.centres0, self.q0, self.conn)
        start = sheet.perturbed(p, self.centres0, perturbation)
        shape = spun_shape(p)  # None, or the spun equilibrium to start from (solvers.spun_start)
        start, q, velocities, omega = sheet_pose.initial_motion(p, start, self.q0, self.payload, shape)  # all bodies
        angles0 = sheet.angles_xyz(sheet.quaternion_rotation(q))
        rates = np.zeros_like(velocities)
        if p.spin_rate != 0:  # rigid rotation (model.sheet_spin); the angles' rates φ̇ = G⁻¹ω
            G = angular_velocity_xyz(angles0[:, None, :], np.eye(3)).transpose(0, 2, 1)  # ω = G φ̇
            rates = np.linalg.solve(G, omega[:, :, None])[:, :, 0]
        else:
            velocities = np.zeros_like(velocities)
        reference = self.flat if self.payload is None else np.vstack([self.flat, self.payload.start])
        self.SC = exu.SystemContainer()
        mbs = self.mbs = self.SC.AddSystem()
        J = self.tiles.inertias  # Exudyn's order: J_xx, J_yy, J_zz, J_yz, J_xz, J_xy
        masses = sheet_pose.body_masses(p, self.payload)
        J = J if self.payload is None else np.concatenate([J, self.payload.inertia[None]])
        inertias = [[J[k, 0, 0], J[k, 1, 1], J[k, 2, 2], J[k, 1, 2], J[k, 0, 2], J[k, 0, 1]] for k in range(len(J))]
        self.nodes, self.bodies = [], []
        for k in range(len(J)):
            node = mbs.AddNode(
                NodeRigidBodyRxyz(
                    referenceCoordinates=[*reference[k], 0.0, 0.0, 0.0],
                    initialCoordinates=[*(start[k] - reference[k]), *angles0[k]],
                    initialVelocities=[*velocities[k], *rates[k]],
                )
            )
            self.nodes.append(node)
            self.bodies.append(
                mbs.AddObject(ObjectRigidBody(mass=float(masses[k]), inertia=inertias[k], nodeNumber=node))
            )
        ground = mbs.AddObject(ObjectGround())
        c = self.conn
        plain = np.all(c.frame == np.eye(3), axis=(1, 2))  # connectors in the global axes
        for q in range(len(c)):
            body_a = ground if c.tile_a[q] < 0 else self.bodies[c.tile_a[q]]
            body_b = self.bodies[c.tile_b[q]]
            if plain[q]:
                ma = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body_a, localPosition=list(c.local_a[q])))
                mb = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body_b, localPosition=list(c.local_b[q])))
            else:  # a support's axes (Connectors.frame) turn both markers: A₀ = frame, A₁ = R_B frame
                ma = mbs.AddMarker(
                    MarkerBodyRigid(bodyNumber=body_a, localHT=exu.HT(rotation=c.frame[q], translation=c.local_a[q]))
                )
                mb = mbs.AddMarker(
                    MarkerBodyRigid(bodyNumber=body_b, localHT=exu.HT(rotation=c.frame[q], translation=c.local_b[q]))
                )
            mbs.AddObject(
                ObjectConnectorRigidBodySpringDamper(
                    markerNumbers=[ma, mb],
                    stiffness=np.diag(c.stiffness[q]),
                    damping=np.diag(c.damping[q]),
                    offset=list(c.offset[q]),
                )
            )
        for tile, point, force in zip(*sheet.edge_followers(p)):
            marker = mbs.AddMarker(MarkerBodyRigid(bodyNumber=self.bodies[tile], localPosition=list(point)))
            mbs.AddLoad(LoadForceVector(markerNumber=marker, loadVector=list(force), bodyFixed=True))
        self.tether_rows = add_payload_links(mbs, self.bodies, self.payload)  # the stem or the tethers
        self.force = np.zeros(6 * len(self.nodes))
        self.packed = terms.pack(p, "sheet")
        self.reads_velocities = bool(terms.reads(terms.pack(p, "sheet")) & VELOCITIES)
        self.load_calls, self.load_time = 0, 0.0
        self.generic, self.blocks = add_load_items(mbs, self.nodes, self.force, LOAD_BLOCK)
        mbs.Assemble()
        self.update_load(0.0)
        mbs.SetPreNewtonResidualUserFunction(lambda _mbs, t, _iteration, _discontinuous: self.update_load(t))

    def force_vector(self, q: np.ndarray, q_t: np.ndarray | None = None, t: float = 0.0) -> np.ndarray:
        """The load's generalised force (6N) at coordinates q (velocities q_t, read where a physics term
        reads them) and the time t: the terms' tile forces at the centres, no torques."""
        t0 = _time.perf_counter()
        rates = np.zeros(0) if q_t is None else np.asarray(q_t, float)
        load_into(self.packed, self.flat, np.asarray(q, float), rates, self.tiles.count, float(t), self.force)
        if self.payload is not None:  # its own frame force −m_p g₀ ẑ, with the beam's factor
            self.force[-4] = self.payload.frame_force * terms.beam_factor(self.packed, t)
        self.load_calls += 1
        self.load_time += _time.perf_counter() - t0
        return self.force

    def update_load(self, t: float) -> None:
        data = self.mbs.systemData
        q_t = data.GetODE2Coordinates_t() if self.reads_velocities else None
        force = self.force_vector(data.GetODE2Coordinates(), q_t, t)
        for item, (a, b) in zip(self.generic, self.blocks):
            self.mbs.SetObjectParameter(item, "forceVector", force[COORDINATES * a : COORDINATES * b])

    def centres(self, q: np.ndarray) -> np.ndarray:
        """Tile centres (…, N, 3) of coordinate rows (…, 6N)."""
        q = np.asarray(q)[..., : 6 * self.tiles.count]
        return self.flat + q.reshape(q.shape[:-1] + (self.tiles.count, 6))[..., :3]

    def state(self, q: np.ndarray, q_t: np.ndarray):
        """(centres, angles, velocities, angular velocities), each (…, N, 3), of coordinate rows (…, 6N)."""
        N = self.tiles.count
        q = np.asarray(q)[..., : 6 * N]
        q = q.reshape(q.shape[:-1] + (N, 6))
        v = np.asarray(q_t)[..., : 6 * N].reshape(q.shape)
        return (
            self.flat + q[..., :3],
            q[..., 3:].copy(),
            v[..., :3].copy(),
            angular_velocity_xyz(q[..., 3:], v[..., 3:]),
        )


def simulation_settings(t_final: float, step_size: float, rel_tol: float, abs_tol: float, spectral_radius: float):
    """Exudyn's SimulationSettings of one generalized-α run (fixed step, modified Newton, sparse LU)."""
    import exudyn as exu

    s = exu.SimulationSettings()
    ti = s.timeIntegration
    steps = t_final / step_size
    if abs(steps - round(steps)) <= 1e-9 * max(1.0, steps):  # a whole number of steps ends at t_final
        ti.endTime, ti.numberOfSteps = t_final, max(1, int(round(steps)))
    else:  # steps of exactly step_size (on the output grid), the last one past t_final
        ti.endTime, ti.numberOfSteps = math.ceil(steps) * step_size, int(math.ceil(steps))
    ti.newton.relativeTolerance = rel_tol
    ti.newton.absoluteTolerance = abs_tol
    ti.generalizedAlpha.spectralRadius = spectral_radius
    ti.minimumStepSize = step_size * 1e-4
    ti.verboseMode = 0
    s.solution.file.write = False
    s.solution.sensors.active = False
    s.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    return s


def run(params: SailParameters, settings: RunSettings, *, progress: bool = False, **options) -> Result:
    """Integrate one sheet case to t_final or to failure (module docstring); options: step_size,
    newton_rel_tol, newton_abs_tol, spectral_radius, perturbation (m, seeded tile offsets at the start)."""
    import exudyn as exu

    unknown = sorted(set(options) - set(OPTIONS))
    if unknown:
        raise ParameterError(f"option {unknown[0]!r} is invalid for a sheet: allowed {', '.join(OPTIONS)}")
    p = params
    tiles, payload = Tiles.of(p).count, p.payload_mass > 0
    check_size(6 * (tiles + payload), f"a sheet of {tiles} tiles" + (" and its payload" if payload else ""), 6)
    dt = settings.sample_interval
    h = options.get("step_size") or default_step_size(p, settings)
    if not (h > 0 and math.isfinite(h)):
        raise ParameterError(f"step_size={h!r} is invalid: allowed a finite value > 0 (s)")
    h = dt / math.ceil(dt / h * (1 - 1e-12))  # whole steps per output sample
    spectral_radius = float(options.get("spectral_radius", SPECTRAL_RADIUS))
    if not 0 <= spectral_radius <= 1:
        raise ParameterError(f"spectral_radius={spectral_radius!r} is invalid: allowed 0 ≤ ρ∞ ≤ 1")
    start = _time.perf_counter()
    cpu = _time.process_time()
    system = SheetSystem(p, float(options.get("perturbation") or 0.0))
    rel_tol = float(options.get("newton_rel_tol") or NEWTON_REL_TOL)
    abs_tol = options.get("newton_abs_tol")
    abs_tol = default_abs_tol(p, system.conn) if abs_tol is None else float(abs_tol)
    mbs = system.mbs
    s = simulation_settings(settings.t_final, h, rel_tol, abs_tol, spectral_radius)
    monitor = FailureMonitor(failure.plane_amplitude(system.centres(mbs.systemData.GetODE2Coordinates())), settings)
    bar = Progress(settings.t_final, progress, label=f"exudyn sheet {system.tiles.count} tiles")
    recorder = Recorder(mbs, system, monitor, h, settings.sample_times(), bar)
    mbs.SetPostStepUserFunction(recorder)
    solver = exu.MainSolverImplicitSecondOrder()
    error = solve_steps(solver, mbs, s, bar, failure="Newton did not converge", stopped=lambda: recorder.failed)
    wall = _time.perf_counter() - start
    whole = min(len(recorder.rows_q), len(recorder.rows_v), len(recorder.times))  # an interrupt may cut a record
    rows_q, rows_v = np.array(recorder.rows_q[:whole]), np.array(recorder.rows_v[:whole])
    state, times = system.state(rows_q, rows_v), recorder.times[:whole]
    stop = monitor.first_failure(failure.plane_amplitude(state[0]))
    if stop is not None:  # end at the first sample past failure
        state = tuple(a[: stop + 1] for a in state)
        times, rows_q, rows_v = times[: stop + 1], rows_q[: stop + 1], rows_v[: stop + 1]
    tail = (a[:, 6 * system.tiles.count :].reshape(len(a), -1, 6)[..., :3] for a in (rows_q, rows_v))
    payload = sheet_payload.record(*tail)  # the payload's displacement and velocity
    if payload:
        payload["payload_centre"] = (np.array(payload["payload_centre"]) + system.payload.start).tolist()
    info = {
        "formulation": "rigid tiles (NodeRigidBodyRxyz) and ObjectConnectorRigidBodySpringDamper edges, "
        "generalized-alpha, modified Newton, sparse LU",
        "method": "generalized-alpha",
        "step_size": h,
        "newton_rel_tol": rel_tol,
        "newton_abs_tol": abs_tol,
        "newton_abs_tol_floor": ROUND_OFF_FACTOR * round_off_floor(p, system.conn),
        "spectral_radius": spectral_radius,
        "perturbation": float(options.get("perturbation") or 0.0),
        "steps": recorder.steps,
        "newton_iterations": int(solver.it.newtonStepsCount),
        "njev": int(solver.it.newtonJacobiCount),
        "load_calls": system.load_calls,
        "load_time": system.load_time,
        "coordinates": 6 * system.tiles.count,
        "connectors": len(system.conn),
        "membrane_modulus": system.tiles.membrane_modulus,
        "membrane_damping": system.tiles.membrane_damping,
        "cpu_time": _time.process_time() - cpu,
        **payload,
        **sheet_ride.record(p, state[0], state[3], payload),
    }
    result = Result.from_tiles(p, "exudyn", times, *state, wall_time=wall, error=error, info=info, settings=settings)
    note = round_off_warning(p, system.conn)
    if note:
        result.warnings.append(note)
    return result


class Recorder:
    """The post-step function of a sheet run: the state at every output time (the step that lands on it;
    by time, not by count: Exudyn shortens and redoes a step that Newton failed, and its later steps may
    pass an output time, as the last step passes a t_final that the interval does not divide: then the
    cubic Hermite interpolant of the two steps around it), and the stop rule every SAMPLES_PER_CHECK
    samples. Attributes: rows_q, rows_v and times of the samples, steps, failed (the stop rule fired)."""

    def __init__(self, mbs, system: SheetSystem, monitor: FailureMonitor, h: float, grid: np.ndarray, bar):
        self.system, self.monitor, self.h, self.grid, self.bar = system, monitor, h, grid, bar
        self.rows_q = [np.array(mbs.systemData.GetODE2Coordinates())]
        self.rows_v = [np.array(mbs.systemData.GetODE2Coordinates_t())]
        self.times = [0.0]
        self.steps, self.failed = 0, False
        self.previous = (0.0, self.rows_q[0], self.rows_v[0])  # the last step: (t, q, q̇)

    def __call__(self, mbs, t) -> bool:
        if t < 0.5 * self.h:  # Exudyn also calls this once at initialisation
            return True
        self.steps += 1
        if len(self.times) == self.grid.size:  # past the last output time
            return True
        target, data, previous = self.grid[len(self.times)], mbs.systemData, self.previous
        q, v = np.array(data.GetODE2Coordinates()), np.array(data.GetODE2Coordinates_t())
        self.previous = (t, q, v)
        if t < target - ON_STEP * self.h:
            return True
        if t > target + ON_STEP * self.h:  # a step past the output time (a shortened step, the end)
            t, q, v = (target, *hermite(previous, (t, q, v), target))
        self.rows_q.append(q)
        self.rows_v.append(v)
        self.times.append(t)
        if (len(self.times) - 1) % SAMPLES_PER_CHECK == 0:
            self.bar.update(t)
            if self.monitor.active:
                centres = self.system.centres(np.array(self.rows_q[-SAMPLES_PER_CHECK:]))
                if self.monitor.first_failure(failure.plane_amplitude(centres)) is not None:
                    self.failed = True
                    return False
        return True


def hermite(start, end, time: float) -> tuple[np.ndarray, np.ndarray]:
    """Coordinates and their rates at `time` in the step from start = (t₀, q₀, q̇₀) to end = (t₁, q₁, q̇₁):
    the cubic Hermite polynomial and its derivative."""
    (t0, q0, v0), (t1, q1, v1) = start, end
    span = t1 - t0
    s = (time - t0) / span
    q = (2 * s**3 - 3 * s**2 + 1) * q0 + (s**3 - 2 * s**2 + s) * span * v0 + (3 * s**2 - 2 * s**3) * q1
    q = q + (s**3 - s**2) * span * v1
    v = (6 * s**2 - 6 * s) / span * (q0 - q1) + (3 * s**2 - 4 * s + 1) * v0 + (3 * s**2 - 2 * s) * v1
    return q, v


def static_centres(p: SailParameters, rel_tol: float = 1e-10) -> np.ndarray:
    """Tile centres (N, 3) at static equilibrium under the case's loads: Exudyn's static solver, one load
    step, Newton tolerance above the round-off floor. For supported boundaries only."""
    import exudyn as exu

    if p.boundary == "free":
        raise ParameterError("boundary='free' is invalid for a static solve: allowed a supported sheet")
    system = SheetSystem(p)
    s = simulation_settings(1.0, 1.0, rel_tol, 1.0, SPECTRAL_RADIUS)
    st = s.staticSolver
    st.newton.relativeTolerance = rel_tol
    t = system.tiles
    st.newton.absoluteTolerance = max(
        1e-14 * max(abs(p.pressure), 1e-30) * t.area * t.count, ROUND_OFF_FACTOR * round_off_floor(p, system.conn)
    )
    st.numberOfLoadSteps = 1
    st.verboseMode = 0
    with silenced():
        exu.MainSolverStatic().SolveSystem(system.mbs, s)
    q = np.asarray(system.mbs.systemData.GetODE2Coordinates())
    return system.centres(q)


def eigenfrequencies(p: SailParameters, count: int | None = None) -> np.ndarray:
    """Undamped ω (rad/s) of the linearised sheet at its initial state, ascending, by Exudyn's
    ComputeODE2Eigenvalues (dense numerical K and M; practical up to ~20 × 20 tiles).

    Wrong for a pre-stressed sheet (edge_tension > 0): the pre-stressed connector's tangent stiffness is
    not symmetric, and the routine solves the symmetric generalised eigenproblem (measured +24–27 % on
    the tensioned membrane; the time-domain frequencies of the same Exudyn model are right). Raises
    ParameterError then."""
    if p.edge_tension > 0:
        raise ParameterError(
            "edge_tension > 0 is invalid for Exudyn's eigenvalue solver (non-symmetric pre-stressed stiffness): "
            "allowed 0; use the reduced solver's eigenfrequencies or a time-domain fit"
        )
    system = SheetSystem(p)
    with silenced():
        values, _ = system.mbs.ComputeODE2Eigenvalues(useAbsoluteValues=True)
    omega = np.sqrt(np.sort(np.asarray(values)))
    return omega if count is None else omega[:count]
