"""The in-house sheet's equations linearised in the frame that turns with a spinning sail (capability
``linearise_rotating``).

A sail spinning at Ω about ẑ through its centre of mass c_m under a load that does not change when the sail
turns about that axis (unlit, a uniform beam, a round Gaussian beam centred on the axis) has equations that
commute with rotations about it, so in the frame turning at Ω the spun state is steady (or frozen, as
:func:`~lightsail_mbs.solvers.reduced.sheet.linearise` freezes a released defect): small deviations from it
obey a linear system with constant coefficients, whose eigenvalues λ are the growth rates (Re λ) and the
frequencies seen in the turning frame.

Coordinates. Per tile the centre c_r and the orientation R_r in the turning frame (at t = 0 it coincides
with the inertial one), perturbed as c_r = c + Δc, R_r = R exp([Δθ_b]), and their rates w = ċ_r and the
body-frame rate relative to the frame ω_rel. The inertial state the solver integrates is then

    v = w + Ω ẑ × (c_r − c_m),    ω_b = ω_rel + R_rᵀ Ω ẑ

(R = Q(t) R_r with Q̇ = [Ωẑ] Q, so Rᵀ Ṙ = [R_rᵀ Ωẑ + ω_rel]), and with the solver's accelerations a = v̇ and
ω̇_b (its right-hand side, the same kernel as a run) the turning frame's equations are

    ċ_r = w,    ẇ = a − 2Ω ẑ × w + Ω² (c_r − c_m)_⊥        (Coriolis; centrifugal, ⊥: the part ⊥ ẑ)
    Δθ̇_b = ω_rel,  ω̇_rel = ω̇_b + ω_rel × R_rᵀ Ω ẑ                (d(R_rᵀΩẑ)/dt = −ω_rel × R_rᵀΩẑ)

(Δθ̇_b = ω_rel + O(Δθ_b ω_rel), exact at first order about a state at rest in the frame). Linearised about
ξ = (Δc, Δθ_b) = 0, η = (w, ω_rel) = 0:  ξ̇ = η,  η̇ = K ξ + C η, L = [[0, I], [K, C]], the layout of
``linearise`` (6 entries per tile, tile by tile). K holds the connectors' and loads' stiffness with the
centrifugal softening and the prestress of the spun state; C the damping, Coriolis and the tiles'
gyroscopic coupling. At Ω = 0 it is ``linearise``'s L.

A payload (model.sheet_payload) is one more body, its ξ and η after the tiles'; the frame turns about the
tiles' centre of mass, on whose axis it sits. Its tethers linearise where they are taut (their law is smooth
there); a slack or just-taut tether is refused.

K and C come from central differences of the right-hand side: the tiles of one colour of the solver's
distance-2 colouring are displaced together (their neighbourhoods do not overlap), 24 evaluations per colour.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import sheet, sheet_spin
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.solvers.reduced.sheet import SheetModel, _rotate_quaternions
from lightsail_mbs.solvers.reduced.sheet_kernels import STATE

DOF = 6  # ξ per tile: Δc (3), Δθ_b (3)
STEP = 1e-7  # central-difference step, × the sail's size for Δc and w/Ω-scaled rates, rad for angles
SLACK = 1e-5  # a tether's least stretch for a linearisation, × its rest length (≫ STEP × the sail's size)


class TurningFrame:
    """The turning frame's rates (ξ̇, η̇) of (ξ, η) about a frozen state (module docstring)."""

    def __init__(self, p: SailParameters, state: np.ndarray | None = None):
        self.model = SheetModel(p)
        y = self.model.y0() if state is None else np.array(state, float)
        rows = y.reshape(-1, STATE)
        self.count = rows.shape[0]
        self.centres = self.model.flat + rows[:, 0:3]
        self.quaternions = rows[:, 3:7].copy()
        self.axis = sheet_spin.spin_centre(p, self.centres[: self.model.lit])  # the tiles' (a payload is on it)
        self.spin = p.spin_rate * np.cos(p.spin_tilt)
        _require_taut(self.model, self.centres, self.quaternions)

    def rates(self, xi: np.ndarray, eta: np.ndarray) -> np.ndarray:
        """(N, 12): (ξ̇, η̇) per tile of the displacements ξ (N, 6) and rates η (N, 6) in the turning frame."""
        zhat = np.array([0.0, 0.0, self.spin])
        y = np.zeros((self.count, STATE))
        centres = self.centres + xi[:, 0:3]
        y[:, 0:3] = centres - self.model.flat
        y[:, 3:7] = self.quaternions
        flat = y.ravel()
        _rotate_quaternions(flat, xi[:, 3:6])
        frame_rate = np.einsum("kji,j->ki", sheet.quaternion_rotation(y[:, 3:7]), zhat)  # R_rᵀ Ω ẑ
        radial = centres - self.axis
        y[:, 7:10] = eta[:, 0:3] + np.cross(zhat, radial)
        y[:, 10:13] = eta[:, 3:6] + frame_rate
        f = self.model.rhs(0.0, flat).reshape(self.count, STATE)
        out = np.empty((self.count, 2 * DOF))
        out[:, 0:DOF] = eta
        radial[:, 2] = 0.0
        out[:, 6:9] = f[:, 7:10] - 2.0 * np.cross(zhat, eta[:, 0:3]) + self.spin**2 * radial
        out[:, 9:12] = f[:, 10:13] + np.cross(eta[:, 3:6], frame_rate)
        return out


def _require_taut(model: SheetModel, centres: np.ndarray, quaternions: np.ndarray) -> None:
    """A tether's law max(k(ℓ − ℓ₀) + c ℓ̇, 0) has no derivative at ℓ = ℓ₀ and none of slack's use: every
    tether must be stretched by more than SLACK × its rest length at the linearised state."""
    tile, point, rest, _ = model.tethers
    if not len(tile):
        return
    ends = centres[tile] + np.einsum("kij,kj->ki", sheet.quaternion_rotation(quaternions[tile]), point)
    stretch = np.linalg.norm(centres[model.lit] - ends, axis=1) - rest
    if np.any(stretch <= SLACK * rest):
        raise ParameterError(
            f"payload_tethers={len(tile)} is invalid for a linearisation at this state: tether stretches "
            f"{np.array2string(stretch, precision=2)} m, allowed every tether taut (stretch > {SLACK:g} × its rest "
            "length; a slack or just-taut cable has no linearisation, e.g. an unlit case, whose tethers carry nothing)"
        )


def linearise_rotating(p: SailParameters, state: np.ndarray | None = None) -> sp.csc_matrix:
    """L (12N × 12N, sparse) of the sheet's equations in the frame turning at Ω cos β about ẑ through the
    centre of mass, about `state` (the solver's 13N state, velocities ignored; default the initial shape,
    the spun equilibrium's connectors): ξ̇ = η, η̇ = K ξ + C η (module docstring)."""
    frame = TurningFrame(p, state)
    N = frame.count
    size = max(p.length, p.width)
    rate = max(abs(frame.spin), 1.0)
    scales = np.r_[[size] * 3, [1.0] * 3, [size * rate] * 3, [rate] * 3] * STEP
    neighbours = [{k} for k in range(N)]
    for a, b in [*zip(frame.model.ta, frame.model.tb), *((k, frame.model.lit) for k in frame.model.tethers[0])]:
        if a >= 0:
            neighbours[a].add(b)
            neighbours[b].add(a)
    rows, cols, values = [], [], []
    for tiles in frame.model.groups:
        owner = np.full(N, -1)
        for j in tiles:
            owner[list(neighbours[j])] = j
        seen = np.nonzero(owner >= 0)[0]
        for s in range(2 * DOF):
            delta = np.zeros((N, 2 * DOF))
            delta[tiles, s] = scales[s]
            plus = frame.rates(delta[:, :DOF], delta[:, DOF:])
            minus = frame.rates(-delta[:, :DOF], -delta[:, DOF:])
            column = (plus - minus)[seen] / (2.0 * scales[s])
            rows.append((2 * DOF * seen[:, None] + np.arange(2 * DOF)).ravel())
            cols.append(np.repeat(2 * DOF * owner[seen] + s, 2 * DOF))
            values.append(column.ravel())
    J = sp.csr_matrix((np.concatenate(values), (np.concatenate(rows), np.concatenate(cols))), shape=(12 * N, 12 * N))
    order = np.r_[(2 * DOF * np.arange(N)[:, None] + np.arange(DOF)).ravel()]
    order = np.r_[order, order + DOF]  # (ξ of every tile, then η of every tile)
    L = J[order][:, order].tolil()
    L[: DOF * N, :] = 0.0
    L[: DOF * N, DOF * N :] = sp.identity(DOF * N)
    return L.tocsc()
