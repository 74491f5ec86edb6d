"""The in-house sheet solver (`solve(params, "reduced")` for model "sheet"), independent of Exudyn.

Why a second implementation of the *same* discrete model, not a continuum plate: the cross-check
holds failure times to 1 % and deflections to 1e-3 a₀ on an unstable sail that amplifies every model
difference, so two discretisations (tiles and finite differences) would differ by their own
O((a/L)²) error long before that. A second implementation of the same tiles and connectors checks
the Exudyn build (connector frames and offsets, load, frame force, follower tension) to solver
tolerance; the plate and membrane validations then check the discrete model against continuum theory.

What is independent of Exudyn:

* coordinates: per tile the centre displacement u from its flat grid point, a unit quaternion
  (scalar first) and the body-frame angular velocity ω_b; first-order Newton–Euler equations::

      u̇ = v,  q̇ = ½ q ⊗ (0, ω_b),  m v̇ = F,  J ω̇_b = τ_b − ω_b × J ω_b

  (Exudyn: Tait–Bryan angles, a second-order system with a state-dependent mass matrix). The springs'
  relative displacement is formed from small quantities only,
  p_b − p_a = gap + (u_b − u_a) + (R_b − I) l_b − (R_a − I) l_a (gap: the markers' small known
  mismatch on the flat grid, model.sheet.Connectors), so its
  round-off is ~1e-21 m where Exudyn's, formed from ~1 m positions, is ~1e-16 m;
* the load: the physics terms' compiled forms (model/terms; the radiation's facet law,
  loads.net_facet_force) on the normal's components
  (2(q₁q₃ + q₀q₂), 2(q₂q₃ − q₀q₁), …)/|q|², never a difference of O(1) numbers;
* integrator: Radau IIA, order 5, adaptive (sheet_radau: velocity-reduced sparse solve, quantised
  steps), with a sparse Jacobian from graph-coloured finite differences: tiles of one colour of a
  distance-2 colouring of the mesh's adjacency (distance2_colouring) have closed neighbourhoods that
  never overlap, so 13 right-hand sides per colour give the whole Jacobian (a grid takes 5 colours, 65
  right-hand sides) (Exudyn: generalized-α, fixed step, modified Newton);
* code: the right-hand side is one numba-compiled pass over tiles, connectors, followers and loads
  (solvers.reduced.sheet_kernels).

What is shared on purpose: the model data (model.sheet: connectors, offsets, initial shape, edge
followers) and the connector law, which follows Exudyn's ObjectConnectorRigidBodySpringDamper
(non-intrinsic): δ = A₀ᵀ(p₁ − p₀), φ = xyz angles of A₀ᵀA₁, f_loc = K(δ − δ₀) + D A₀ᵀ(ṗ₁ − ṗ₀),
m_loc = K_r(φ − φ₀) + D_r A₀ᵀ(ω₁ − ω₀), force A₀f_loc on body 0 at p₀ and −A₀f_loc on body 1 at p₁,
torques ±A₀m_loc.

Options: rtol (default 1e-7: deflections within 1.4e-7 a₀ of rtol 1e-9 on the cross-check cases),
max_step (default 10 ms; output samples between steps come from the collocation polynomial, O(h⁴)),
perturbation (m: seeded tile offsets along z at the start, model.sheet.perturbed), frame (inertial, or
turning: the state in the frame that turns with the spin, solvers.reduced.sheet_turning; the default for a
spinning sheet).
"""

from __future__ import annotations

import math
import time as _time

import numpy as np
import scipy.sparse as sp

from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import failure, sheet, sheet_payload, sheet_pose, terms
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.result import Result
from lightsail_mbs.solvers.progress import Progress
from lightsail_mbs.solvers.reduced.sheet_jacobian import DenseRows
from lightsail_mbs.solvers.reduced.sheet_kernels import STATE, fill_jacobian, rhs_kernel, unpack_into
from lightsail_mbs.solvers.reduced.sheet_options import (  # noqa: F401 (DEFAULT_*, OPTIONS: this solver's)
    DEFAULT_MAX_STEP,
    DEFAULT_RTOL,
    OPTIONS,
    checked_options,
    state_scales,
)
from lightsail_mbs.solvers.reduced.sheet_radau import SheetRadau, distance2_colouring, empty_small_pages
from lightsail_mbs.solvers.reduced.sheet_tethers import append_payload, split_bodies
from lightsail_mbs.solvers.reduced.sheet_turning import TurningFrame
from lightsail_mbs.solvers.skeleton import FailureMonitor
from lightsail_mbs.solvers.spun_start import spun_shape


class SheetModel:
    """The right-hand side, sparse Jacobian and initial state of one sheet case."""

    def __init__(self, p: SailParameters, perturbation: float = 0.0, frame: str = "inertial", jacobian="coloured"):
        self.p = p
        self.tiles = sheet.Tiles.of(p)
        self.flat = sheet.flat_centres(p)
        self.centres0, self.q0 = sheet.initial_quaternions(p)
        c = sheet.connectors(p, self.centres0, self.q0)
        self.conn = c
        self.start = sheet.perturbed(p, self.centres0, perturbation)
        self.ta, self.tb = c.tile_a.astype(np.int64), c.tile_b.astype(np.int64)
        self.la, self.lb = np.ascontiguousarray(c.local_a), np.ascontiguousarray(c.local_b)
        self.gap = np.ascontiguousarray(c.gap)
        self.K, self.Dm = np.ascontiguousarray(c.stiffness), np.ascontiguousarray(c.damping)
        self.off = np.ascontiguousarray(c.offset)
        self.frame = np.ascontiguousarray(c.frame)
        self.framed = ~np.all(c.frame == np.eye(3), axis=(1, 2))
        ft, fp, ff = sheet.edge_followers(p)
        self.followers = (ft.astype(np.int64), np.ascontiguousarray(fp), np.ascontiguousarray(ff))
        self.load = terms.pack(p, "sheet")  # the physics terms (model/terms)
        self.masses = np.ascontiguousarray(self.tiles.masses)
        self.inertia = np.ascontiguousarray(self.tiles.inertias)
        self.inverse = np.linalg.inv(self.inertia)
        off_diagonal = self.inertia - np.einsum("kii->ki", self.inertia)[:, :, None] * np.eye(3)
        self.diagonal = ~np.any(off_diagonal != 0, axis=(1, 2))
        self.payload = sheet_payload.payload(p, self.centres0, self.q0, c)
        append_payload(self, self.payload)  # the payload: body N, its stem a connector, its tethers
        self.count = len(self.flat)  # bodies: the tiles, then the payload
        self.n = STATE * self.count
        self.calls = 0
        self._pattern(jacobian)
        self.shape = spun_shape(p)  # None, or the spun equilibrium to start from (solvers.spun_start)
        self.turning = TurningFrame(self) if frame == "turning" else None  # the state's frame (sheet_turning)

    def y0(self) -> np.ndarray:
        return self.inertial_y0() if self.turning is None else self.turning.start.copy()

    def inertial_y0(self) -> np.ndarray:
        centres, q, velocities, omega = sheet_pose.initial_motion(self.p, self.start, self.q0, self.payload, self.shape)
        y = np.zeros((self.count, STATE))
        y[:, 0:3] = centres - self.flat
        y[:, 3:7] = q
        if self.p.spin_rate != 0:  # rigid rotation (model.sheet_spin); ω in the bodies' axes
            y[:, 7:10] = velocities
            y[:, 10:13] = np.einsum("kji,kj->ki", sheet.quaternion_rotation(q), omega)
        return y.ravel()

    def inertial(self, times, rows) -> np.ndarray:
        """The inertial states of state rows (T, 13N) at the times (T,) (the turning frame's transformed)."""
        return np.asarray(rows) if self.turning is None else self.turning.inertial(times, rows)

    def rhs(self, t, y, out=None):
        out = np.empty(self.n) if out is None else out
        if self.turning is not None:
            return self.turning.rates(t, y, self.inertial_rhs, out)
        return self.inertial_rhs(t, y, out)

    def inertial_rhs(self, t, y, out):
        """ẏ of the inertial state y into out (the compiled kernel)."""
        self.calls += 1
        rhs_kernel(
            y,
            self.flat,
            self.masses,
            self.inertia,
            self.inverse,
            self.diagonal,
            self.ta,
            self.tb,
            self.la,
            self.lb,
            self.gap,
            self.K,
            self.Dm,
            self.off,
            self.frame,
            self.framed,
            *self.followers,
            self.load,
            float(t),
            self.lit,
            self.dead,
            *self.tethers,
            out,
        )
        return out

    def _pattern(self, jacobian: str):
        """CSC sparsity of ∂ẏ/∂y (each tile's 13 rows depend on its own and its neighbours' 13 columns) and
        the colouring of the tiles (distance2_colouring of the mesh's adjacency; jacobian "split": the dense
        rows apart, sheet_jacobian.DenseRows)."""
        N = self.count
        neighbours = [{k} for k in range(N)]
        for a, b in [*zip(self.ta, self.tb), *((k, self.lit) for k in self.tethers[0])]:
            if a >= 0:
                neighbours[a].add(b)
                neighbours[b].add(a)
        pairs = np.array([(ct, rt) for ct in range(N) for rt in neighbours[ct]], dtype=np.int64)
        block = np.arange(STATE)  # entries (row tile rt, column tile ct): rows along the last axis
        rows = np.broadcast_to(STATE * pairs[:, 1, None, None] + block, (len(pairs), STATE, STATE)).ravel()
        cols = np.broadcast_to(STATE * pairs[:, 0, None, None] + block[:, None], (len(pairs), STATE, STATE)).ravel()
        M = sp.csc_matrix((np.ones(rows.size), (rows, cols)), shape=(self.n, self.n))
        M.sort_indices()
        self.indptr, self.indices = M.indptr.astype(np.int64), M.indices.astype(np.int64)
        self.dense = DenseRows.of(self, neighbours) if jacobian == "split" else None
        colour = distance2_colouring(neighbours, () if self.dense is None else self.dense.tiles)
        self.groups = [np.nonzero(colour == col)[0] for col in range(colour.max() + 1)]
        size = max(self.p.length, self.p.width)
        self.scale = np.tile(np.r_[[size] * 3, [1.0] * 4, [size] * 3, [1.0] * 3], N)

    def jacobian(self, t, y):
        f0 = self.rhs(t, y)
        data = np.empty(self.indices.size)
        fp = np.empty(self.n)
        for tiles in self.groups:
            for s in range(STATE):
                cols = STATE * tiles + s
                yp = y.copy()
                yp[cols] += self.increments(y, cols)
                self.rhs(t, yp, fp)
                fill_jacobian(data, self.indptr, self.indices, f0, fp, cols.astype(np.int64), yp[cols] - y[cols])
        if self.dense is not None:
            self.dense.fill(data, t, y)
        return sp.csc_matrix((data, self.indices, self.indptr), shape=(self.n, self.n))

    def increments(self, y, cols):
        """The difference quotients' increments of the state entries `cols` (before rounding to y + ε)."""
        return 1e-8 * np.maximum(np.abs(y[cols]), 1e-3 * self.scale[cols])

    @property
    def position_indices(self) -> np.ndarray:
        """Indices of X = (u, q) of every tile in the state vector."""
        return (STATE * np.arange(self.count)[:, None] + np.arange(7)).ravel()

    @property
    def velocity_indices(self) -> np.ndarray:
        """Indices of V = (v, ω_b) of every tile in the state vector."""
        return (STATE * np.arange(self.count)[:, None] + np.arange(7, 13)).ravel()

    def kinematics(self, y: np.ndarray) -> sp.csr_matrix:
        """B(X) with Ẋ = B V: per tile I₃ (u̇ = v) and ½ Q(q) (q̇ = ½ q ⊗ (0, ω_b)), 7N × 6N."""
        N = self.count
        q0, q1, q2, q3 = y.reshape(N, STATE)[:, 3:7].T
        blocks = np.zeros((N, 7, 6))
        blocks[:, 0, 0] = blocks[:, 1, 1] = blocks[:, 2, 2] = 1.0
        blocks[:, 3:7, 3:6] = 0.5 * np.stack(
            [
                np.stack([-q1, -q2, -q3], -1),
                np.stack([q0, -q3, q2], -1),
                np.stack([q3, q0, -q1], -1),
                np.stack([-q2, q1, q0], -1),
            ],
            axis=1,
        )
        return sp.block_diag(list(blocks), format="csr")

    def unpack(self, Y: np.ndarray):
        """(centres, xyz angles, velocities, global angular velocities) of state rows (T, 13N), each (T, N, 3)."""
        arrays = tuple(np.empty((len(Y), self.count, 3)) for _ in range(4))
        self.unpack_to(Y, arrays, 0)
        return arrays

    def unpack_to(self, rows: np.ndarray, arrays: tuple, at: int) -> None:
        """Writes :meth:`unpack` of state rows (T, 13N) into `arrays` (each (samples, N, 3)) from sample `at` on,
        in place (no temporaries of the rows' size: at 100 × 100 tiles each would be fresh pages)."""
        Y = np.ascontiguousarray(np.asarray(rows).reshape(len(rows), self.count, STATE))
        centres, angles, velocities, omega = (a[at : at + len(rows)] for a in arrays)
        np.add(self.flat, Y[..., 0:3], out=centres)
        velocities[...] = Y[..., 7:10]
        unpack_into(Y, angles, omega)

    def stiffness(self, y: np.ndarray) -> sp.csc_matrix:
        """K = ∂a/∂ξ = A_X B: accelerations per generalised displacement ξ = (Δu, Δθ_b) of every tile."""
        J = self.jacobian(0.0, y).tocsr()
        return (J[self.velocity_indices][:, self.position_indices] @ self.kinematics(y)).tocsc()


def run(params: SailParameters, settings: RunSettings, *, progress: bool = False, **options) -> Result:
    """Integrate one sheet case to t_final or to failure and return its Result (solver "reduced");
    options: rtol, max_step, perturbation, frame (module docstring), rate_scale, jacobian (sheet_options)."""
    chosen = checked_options(options, params)
    rtol, max_step, perturbation, frame = chosen.rtol, chosen.max_step, chosen.perturbation, chosen.frame
    start = _time.perf_counter()
    cpu = _time.process_time()
    model = SheetModel(params, perturbation, frame, chosen.jacobian)
    y0 = model.y0()
    scales = state_scales(params, chosen.rate_scale).reshape(-1, STATE)
    atol = rtol * np.vstack([scales, scales[: model.count - model.lit]]).ravel()  # the payload as a tile
    dt = settings.sample_interval
    if max_step >= dt:
        h_max = dt * max(1, int(round(max_step / dt)))
    else:
        h_max = dt / 2 ** math.ceil(math.log2(dt / max_step))
    solver = SheetRadau(
        model.rhs,
        0.0,
        y0,
        settings.t_final,
        rtol=rtol,
        atol=atol,
        jac=model.jacobian,
        kinematics=model.kinematics,
        X=model.position_indices,
        V=model.velocity_indices,
        h_max=h_max,
    )
    times = settings.sample_times()
    monitor = FailureMonitor(failure.plane_amplitude(model.start), settings)
    bar = Progress(settings.t_final, progress, label=f"reduced sheet {sheet.tile_count(params)} tiles")
    # the bodies' (centres, angles, velocities, angular velocities) at every sample, unpacked as they come
    arrays = tuple(empty_small_pages((len(times), model.count, 3)) for _ in range(4))  # pages touched as written
    model.unpack_to(model.inertial([0.0], y0[None]), arrays, 0)
    error, k = None, 1
    try:
        while solver.status == "running" and k < len(times):
            message = solver.step()
            if solver.status == "failed":
                error = f"Radau failed: {message}"
                break
            new = []
            while k + len(new) < len(times) and times[k + len(new)] <= solver.t + 1e-9 * dt:
                new.append(times[k + len(new)])
            if not new:
                continue
            exact = abs(new[-1] - solver.t) <= 1e-9 * dt
            between = new[:-1] if exact else new
            rows = solver.sol(np.array(between)).T if between else np.empty((0, model.n))
            model.unpack_to(model.inertial(new, np.vstack([rows, solver.y]) if exact else rows), arrays, k)
            bar.update(solver.t)
            stop = monitor.first_failure(failure.plane_amplitude(arrays[0][k : k + len(new), : model.lit]))
            k += len(new) if stop is None else stop + 1
            if stop is not None:
                break
    finally:
        bar.close()
    wall = _time.perf_counter() - start
    solver.lus.clear()  # the cached factors (GBs at 100 × 100 tiles) are not needed past the last step
    samples = k
    (centres, angles, velocities, omega), extra = split_bodies(params, model.lit, tuple(a[:samples] for a in arrays))
    info = {
        "formulation": "tiles in maximal coordinates (quaternions), Radau IIA with a velocity-reduced sparse solve",
        "rtol": rtol,
        "max_step": h_max,
        "perturbation": perturbation,
        "frame": frame,
        "rate_scale": chosen.rate_scale,
        "jacobian": chosen.jacobian,
        "colours": len(model.groups),
        "steps": solver.nsteps,
        "rejected_steps": solver.nrejected,
        "nfev": model.calls,
        "njev": solver.njev,
        "nlu": solver.nlu,
        "states": model.n,
        "connectors": len(model.conn),
        "membrane_modulus": model.tiles.membrane_modulus,
        "membrane_damping": model.tiles.membrane_damping,
        "cpu_time": _time.process_time() - cpu,
        **extra,
    }
    return Result.from_tiles(
        params,
        "reduced",
        times[:samples],
        centres,
        angles,
        velocities,
        omega,
        wall_time=wall,
        error=error,
        info=info,
        settings=settings,
    )


def _rotate_quaternions(y: np.ndarray, dtheta: np.ndarray) -> None:
    """q ← q ⊗ exp(Δθ_b/2) in place for (N, 3) body-frame rotation increments."""
    N = dtheta.shape[0]
    Y = y.reshape(N, STATE)
    angle = np.linalg.norm(dtheta, axis=1)
    s = np.where(angle > 0, np.sin(0.5 * angle) / np.where(angle > 0, angle, 1.0), 0.5)
    r = np.column_stack([np.cos(0.5 * angle), dtheta * s[:, None]])
    q = Y[:, 3:7].copy()
    Y[:, 3] = q[:, 0] * r[:, 0] - np.sum(q[:, 1:] * r[:, 1:], axis=1)
    Y[:, 4:7] = q[:, 0:1] * r[:, 1:] + r[:, 0:1] * q[:, 1:] + np.cross(q[:, 1:], r[:, 1:])
    Y[:, 3:7] /= np.linalg.norm(Y[:, 3:7], axis=1, keepdims=True)


def static_centres(p: SailParameters, tol: float = 1e-12, max_iterations: int = 30) -> np.ndarray:
    """Tile centres (N, 3) at static equilibrium under the case's loads: Newton on the accelerations
    a(X) = 0 (V = 0) with the tangent K = A_X B in the 6 generalised displacements per tile. For
    supported boundaries (a free sail has rigid-body modes)."""
    from scipy.sparse.linalg import spsolve

    if p.boundary == "free":
        raise ParameterError("boundary='free' is invalid for a static solve: allowed a supported sheet")
    model = SheetModel(p)
    y = model.y0()
    N = model.tiles.count
    for _ in range(max_iterations):
        a = model.rhs(0.0, y)[model.velocity_indices]
        xi = spsolve(model.stiffness(y), -a).reshape(N, 6)
        Y = y.reshape(N, STATE)
        Y[:, 0:3] += xi[:, 0:3]
        _rotate_quaternions(y, xi[:, 3:6])
        if np.max(np.abs(xi[:, 0:3])) < tol * p.length:
            break
    return model.flat + y.reshape(N, STATE)[:, 0:3]


def eigenfrequencies(p: SailParameters, count: int = 10) -> np.ndarray:
    """The `count` lowest undamped ω (rad/s) at the initial state: eigenvalues −ω² of K = A_X B (exact for
    pre-stressed connectors: K need not be symmetric), by shift-invert Arnoldi about a small shift."""
    from scipy.sparse.linalg import eigs

    model = SheetModel(p)
    values = eigs(model.stiffness(model.y0()), k=count, sigma=-1e-9, which="LM", return_eigenvectors=False)
    return np.sort(np.sqrt(np.abs(values.real)))


def linearise(p: SailParameters, state: np.ndarray | None = None) -> sp.csc_matrix:
    """The Jacobian L (12N × 12N, sparse) of the sheet's equations linearised at rest in `state` (the solver's
    13N state vector, velocities ignored; default the initial shape), in a minimal parametrisation.

    The solver's state carries a unit quaternion per tile, 4 parameters for 3 rotations: its Jacobian has a
    spurious direction per tile (q scaled along itself). Perturbing a tile as q ⊗ exp(Δθ_b/2) instead keeps
    q on the unit sphere, and Ẋ = B V (:meth:`SheetModel.kinematics`) maps the body-frame rates onto its
    tangent space, so with ξ = (Δu, Δθ_b) per tile and V = (v, ω_b) at rest

        ξ̇ = V,    V̇ = K ξ + C V,    K = ∂a/∂X · B = :meth:`SheetModel.stiffness`,  C = ∂a/∂V,

    (the gyroscopic term ω_b × J ω_b is quadratic in V and vanishes at rest). L = [[0, I], [K, C]] in the
    order (ξ of every tile, 6 per tile: Δu_x, Δu_y, Δu_z, Δθ_x, Δθ_y, Δθ_z; then V of every tile in the same
    order), tile k = j·nx + i. Its eigenvalues λ are the growth rates (Re λ) and frequencies of the sheet
    frozen in that state: where the state is not an equilibrium (a released defect) they describe small
    deviations about the state before it has moved."""
    model = SheetModel(p)
    y = model.y0() if state is None else np.array(state, float)
    y.reshape(model.count, STATE)[:, 7:] = 0.0
    J = model.jacobian(0.0, y).tocsr()
    V = model.velocity_indices
    K = J[V][:, model.position_indices] @ model.kinematics(y)
    C = J[V][:, V]
    return sp.bmat([[None, sp.identity(V.size)], [K, C]], format="csc")
