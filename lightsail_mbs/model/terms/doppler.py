"""The Doppler dimming of the beam along the sail's trajectory: every beam load scaled by D(τ) = (1 − β)/(1 + β).

**The frame and its beam.** The solvers work in the frame accelerating with the flat sail, at each moment its
rest frame; their time τ is the sail's proper time from the run's start. The case's intensity I₀ is the
beam's in the laser's (lab) frame. A sail receding at βc sees it dimmed to I₀ D(β), D = (1 − β)/(1 + β)
(:func:`lightsail_mbs.model.relativity.intensity_factor`: one factor of the frequency ratio for each photon's
energy, one for their rate). With ``initial_beta`` β₀ > 0 the run starts at the speed β₀ and β grows along
the constant-power trajectory of the flat craft (:class:`lightsail_mbs.model.relativity.Trajectory`).

**D along the proper time.** The craft of rest mass M (sail and payload, and a carried mass that is no body of
the model, case field carried_mass) intercepting the lab power P = Ī L W (Ī the beam's mean over the flat sail)
has the proper acceleration c d(γβ)/dt = c_n(0) P D/(M c) = g₀ D, with g₀ = c_n(0) Ī L W/(c M)
(SailParameters.trajectory_acceleration: the case's frame acceleration at rest, nominal_acceleration, without a
carried mass; c_n(0) = 2R + α or the table's). A carried mass slows the trajectory and with it D; the sail's own
frame, in which the loads are netted, stays its own (the frame that holds the carried mass takes the rest).
The proper time to reach β from
rest is τ(β) = K β/(1 − β), K = c/g₀ (relativity.Trajectory.proper_time: dτ = K dβ/(1 − β)²), so
β(τ) = τ/(K + τ) and

    D = (1 − β)/(1 + β) = K/(K + 2τ).

Starting at β₀, i.e. at the trajectory's proper time τ₀ = K β₀/(1 − β₀), with K + 2τ₀ = K/D₀,
D₀ = D(β₀):

    D(τ) = K/(K + 2(τ₀ + τ)) = D₀/(1 + r τ),      r = 2 D₀ g₀/c,

and the frame's proper acceleration is g₀(τ) = g₀ D(τ) = g₀ D₀/(1 + r τ): it falls on the proper-time scale
1/r = c/(2 g₀ D₀).

**Or from the run's state.** With the case field ``integrated_trajectory`` the solvers integrate the sail's world
line with its shape (:mod:`lightsail_mbs.model.world_line`) and the factor is D of that state, written into this
term's block before each sum; the closed form above is then what the tests hold the state to.

**What the run uses.** On the flat sail the radiation load (∝ the local intensity I(x) D) and the frame
force −m g₀(τ) ŷ (∝ Ī D) scale by the same factor, so their analytically netted sum, the radiation term,
scales by D(τ) too; so do the payload's share of the frame force (the frame term, c_n(0) Ī l W/c − m g₀,
both parts ∝ D), the first-order velocity-dependent load (∝ the sail-frame intensity) and a payload's own
frame force −m_p g₀(τ), which each solver applies with the payload's body, scaled by
:func:`lightsail_mbs.model.terms.registry.beam_factor`. This term
therefore adds (D(τ) − 1) times the sum of the terms before it in the summation order: the beam's terms
(radiation, frame, velocity), which come first (registry.TERMS); the dead pressure and the in-plane body
force, which are not beam loads, come after it. Nothing else of the case changes along the run: the
stiffnesses, the end tensions and the defect are the sail's own. The wavelength's shift
(λ' = λ/√D) changes nothing for the R/α facet, whose R and α hold at every wavelength. An optical table with a
wavelength axis is read at λ' inside a run whose state holds the world line (model/terms/radiation.py:
set_wavelength); the closed form assumes a constant c_n(0), so the case refuses it with any table, and a table at
one wavelength with the world line too (the journey reads a table at each snapshot's λ': lightsail_mbs.studies.
journey).
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.base.kernels import njit
from lightsail_mbs.model import relativity

ID = 6
FAMILIES = ("chain", "sheet")
TIMED = True  # its forms take the run's time τ (s) after the forces


def active(p) -> bool:
    return p.initial_beta != 0 or p.integrated_trajectory


def reads(p) -> int:
    return 0


def constants(p, family: str) -> np.ndarray:
    """D₀ = (1 − β₀)/(1 + β₀) and r = 2 D₀ g₀/c (1/s): D(τ) = D₀/(1 + r τ). With the trajectory in the run's
    state (integrated_trajectory) r = 0: the solver writes D of its state into the first entry before each sum
    (registry.set_beam_factor), and the factor is that value exactly."""
    start = float(relativity.intensity_factor(p.initial_beta))
    rate = 0.0 if p.integrated_trajectory else 2.0 * start * p.trajectory_acceleration / SPEED_OF_LIGHT
    return np.array([start, rate])


@njit(cache=True)
def factor(block, time):
    """D(τ) = D₀/(1 + r τ) at the run's time τ (s)."""
    return block[0] / (1.0 + block[1] * time)


def _scale(block, forces, time) -> None:
    """forces (rows, …, count) += (D − 1) forces at the time τ: a number or an array of the leading axes (…)."""
    change = block[0] / (1.0 + block[1] * np.asarray(time, float)) - 1.0
    forces += change[..., None] * forces


def chain(p, bodies: np.ndarray, forces: np.ndarray, time) -> None:
    """Adds (D(τ) − 1) times the beam's forces summed so far on every slice (numpy form)."""
    _scale(constants(p, "chain"), forces, time)


def tiles(p, bodies: np.ndarray, forces: np.ndarray, time) -> None:
    """Adds (D(τ) − 1) times the beam's forces summed so far on every tile (numpy form)."""
    _scale(constants(p, "sheet"), forces, time)


@njit(cache=True)
def chain_into(block, bodies, forces, time):
    """Adds (D(τ) − 1) times the forces summed so far on every body (compiled form, chain and sheet alike)."""
    change = factor(block, time) - 1.0
    for r in range(forces.shape[0]):
        for i in range(forces.shape[1]):
            forces[r, i] += change * forces[r, i]


tiles_into = chain_into
