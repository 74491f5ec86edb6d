"""The static equilibrium of an unlit spinning sheet in the frame that turns with it (capability
``spun_equilibrium``; the start of a case with ``spin_equilibrium``): damped relaxation of the turning frame's
dynamics.

The equations
-------------
In the frame turning at Ω (solvers.reduced.sheet_turning) a state at rest is an equilibrium when the
connectors' elastic loads (their rest state with the flat sheet's centrifugal stress, model.sheet_connectors.
spun_prestrain; bending; the edge tension's followers; a stem payload's connector) balance the centrifugal
ones: the Coriolis force of a body at rest is zero. The springs keep their rest state and the shape is free to
deform from the case's initial shape (unlike initial_equilibrium with spin, model.sheet_spin, which corrects
the rest state so that the initial shape itself rests and compresses a doubly curved sheet's tiles).

Tethers
-------
A payload on tethers has no unlit spun equilibrium: unlit, the tethers start at their rest lengths (they carry
the payload's share m_p g₀, which is zero without light) and the spinning cap pulls their rim ends in as it
flattens: relaxed, the map's cap at 80 rad/s with six tethers (k = 1e3 N/m) has five of them slack, by up to
1.8 cm, the payload floating 4 mm off the axis. ``spin_equilibrium`` refuses tethers; the lit equilibrium
(``lit=True``, a spectrum's state) holds them taut by the payload's load.

The solve
---------
The same turning-frame equations as a run, unlit (intensity 0: no light, no accelerating frame, the stem
without its pre-load), with a damping force −c m w on every body's velocity relative to the frame and a
torque −c J ω_rel on its rotation relative to it, c = DAMPING Ω:

    ẇ = (the turning frame's rates) − c w,   ω̇_rel = (…) − c ω_rel.

The damping acts on the deformation only: the rigid part of the relative velocities (their mass-weighted
mean and the rotation that carries their angular momentum about the centre of mass) is left out of w and
ω_rel. Damping it too would drive the sail's rigid rotation towards the frame's fixed axis and make a prolate
craft (a payload on a long stem) tip over (the spin about its axis of least inertia is a maximum of the
centrifugal potential, held only gyroscopically). The damping does no work at rest, so the states the
damped motion ends in are exactly the equilibria above.
Every deformation mode of the turning frame decays at least at min(c/2, ω²/c) (ω its frequency; the
membrane's transverse modes of a spinning disc have ω ≳ Ω, Lamb & Southwell, so c = 4Ω gives rates ≳ Ω/4; the
stiff in-plane modes are damped by the connectors as in a run). Integrated by the run's Radau IIA with its
sparse Jacobian over RELAX_TURNS turns: the slowest deformations (ω ≈ Ω, overdamped) decay at ≥ ω²/c = Ω/4,
by e^(−3π) ≈ 8e-5 over the 6 turns. The rigid motion relative to the frame is not damped: a craft that is
not exactly symmetric keeps a small wobble about the frame's axis (on the 7 × 8 map disc with its stem at
80 rad/s the payload wanders by ~2 mm in the plane while the cap's flattening, 2.4 cm, has settled); the
shape returned is the last state's, wobble included.

Why relaxation, not Newton: a static Newton solve on the tiles' coordinates needs the Jacobian of the
connector loads to resolve the soft bending and centrifugal stiffnesses (~1e-7 to 1 N/m on the 7 × 8 map
disc) beside the membrane's (~3e10 N/m); forward or central differences of the loads carry errors of order
k_∥ h/L ≫ the soft stiffnesses, and Newton on the map's cap at 80 rad/s did not reduce the residual. The
implicit integrator handles that stiffness as a run does, and the damped dynamics need no Jacobian accuracy
beyond the integrator's.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp

from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.model.sheet_grid import quaternion_rotation
from lightsail_mbs.solvers.reduced.sheet import SheetModel, state_scales
from lightsail_mbs.solvers.reduced.sheet_kernels import STATE
from lightsail_mbs.solvers.reduced.sheet_radau import SheetRadau

DAMPING = 4.0  # c/Ω
RELAX_TURNS = 6.0  # the relaxation's length in turns: every deformation decays by ≥ e^(−2π·6/DAMPING)
RTOL = 1e-6


def relaxing_case(p: SailParameters, lit: bool = False) -> SailParameters:
    """The case whose turning-frame dynamics are relaxed: p untilted, unlit unless `lit`, started from its initial
    shape (the run's start, model.sheet_pose.initial_motion, tilts the relaxed shape as one body)."""
    q = p.replace(spin_equilibrium=False, initial_tilt=0.0, initial_tilt_y=0.0)
    return q if lit else q.replace(intensity=0.0)


class DampedTurning:
    """The turning-frame right-hand side and Jacobian of a SheetModel with the damping −c (w, ω_rel)."""

    def __init__(self, model: SheetModel, damping: float):
        self.model, self.damping = model, damping
        self.velocities = model.velocity_indices
        diagonal = np.zeros(model.n)
        diagonal[self.velocities] = damping
        self.diagonal = sp.diags(diagonal, format="csc")

    def rhs(self, t, y, out=None):
        out = self.model.rhs(t, y, out).reshape(-1, STATE)
        rows = y.reshape(-1, STATE)
        out[:, 7:13] -= self.damping * (rows[:, 7:13] - self.rigid(rows))
        return out.ravel()

    def rigid(self, rows: np.ndarray) -> np.ndarray:
        """(B, 6): the rigid part of the bodies' velocities relative to the frame (their mass-weighted mean w̄
        and the rotation Ω_r of I Ω_r = Σ m ρ × (w − w̄); per body w̄ + Ω_r × ρ and R_rᵀ Ω_r)."""
        m = self.model.masses
        rho = self.model.flat + rows[:, 0:3]
        rho = rho - m @ rho / m.sum()
        w = rows[:, 7:10]
        mean = m @ w / m.sum()
        inertia = np.einsum("k,kij->ij", m, np.einsum("k,ij->kij", np.einsum("ki,ki->k", rho, rho), np.eye(3)))
        inertia -= np.einsum("k,ki,kj->ij", m, rho, rho)
        spin = np.linalg.solve(inertia, np.einsum("k,ki->i", m, np.cross(rho, w - mean)))
        out = np.empty((len(rows), 6))
        out[:, 0:3] = mean + np.cross(spin, rho)
        out[:, 3:6] = np.einsum("kji,j->ki", quaternion_rotation(rows[:, 3:7]), spin)
        return out

    def jacobian(self, t, y):
        return (self.model.jacobian(t, y) - self.diagonal).tocsc()


def spun_equilibrium(p: SailParameters, lit: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """(centres (B, 3), quaternions (B, 4)) of every body (the tiles, then the payload) at rest in the frame
    turning with the spinning sheet case p, unlit (module docstring), or `lit` by a beam centred on the spin
    axis (the state a spectrum in the turning frame linearises about; the craft's rigid acceleration along
    the axis, its thrust against the frame's g₀, is left to it)."""
    if p.spin_rate == 0:
        raise ParameterError("spin_rate=0 is invalid for a spun equilibrium: allowed a spinning sheet")
    centred = p.beam_centre in (None, 0.5 * p.length) and p.beam_centre_y in (None, 0.5 * p.width)
    if lit and not centred:
        raise ParameterError(
            f"beam_centre={p.beam_centre!r}, beam_centre_y={p.beam_centre_y!r} are invalid for a lit spun "
            "equilibrium: allowed the beam on the spin axis (None, or L/2 and W/2)"
        )
    if p.payload_tethers and not lit:
        raise ParameterError(
            f"spin_equilibrium=True is invalid with payload_tethers={p.payload_tethers}: unlit the tethers carry "
            "nothing (ℓ₀ = ℓ) and the spinning cap slackens them, leaving the payload no equilibrium; allowed a stem "
            "payload (payload_tethers=0) or no payload"
        )
    return relax(p, lit)


def relax(p: SailParameters, lit: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """(centres, quaternions) of every body of the spinning case p's relaxing_case after RELAX_TURNS turns of the
    damped turning-frame dynamics (module docstring), without spun_equilibrium's checks."""
    model = SheetModel(relaxing_case(p, lit), frame="turning")
    spin = float(np.linalg.norm(model.turning.spin))
    damped = DampedTurning(model, DAMPING * spin)
    turn = 2.0 * math.pi / spin
    scales = state_scales(p).reshape(-1, STATE)
    atol = RTOL * np.vstack([scales, scales[: model.count - model.lit]]).ravel()
    y0 = model.y0()
    solver = SheetRadau(
        damped.rhs, 0.0, y0, RELAX_TURNS * turn, rtol=RTOL, atol=atol, jac=damped.jacobian,
        kinematics=model.kinematics, X=model.position_indices, V=model.velocity_indices, h_max=0.25 * turn,
    )  # fmt: skip
    while solver.status == "running":
        if solver.step() is not None and solver.status == "failed":
            raise ParameterError(f"spin_equilibrium=True: the relaxation failed at t = {solver.t:.3g} s")
    rows = solver.y.reshape(-1, STATE)
    return model.flat + rows[:, 0:3], rows[:, 3:7] / np.linalg.norm(rows[:, 3:7], axis=1)[:, None]
