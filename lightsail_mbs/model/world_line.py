"""The sail's motion along the beam as part of a run's state: its world line, integrated with its shape.

**The state.** The solvers work in the frame accelerating with the flat sail; their time τ is the sail's proper
time. With the case field ``integrated_trajectory`` a run also carries where and when the sail is in the laser's
(lab) frame: two more coordinates, the lab time t and the distance over c, s = (t, x/c) (s), and their rates
along τ, the 4-velocity u = ds/dτ = (γ, γβ). The craft of rest mass M (sail and payload) intercepting the lab
power P has the proper acceleration g = g₀ D along the beam (model/terms/doppler.py: g₀ = c_n(0) Ī L W/(c M),
the case's nominal acceleration at rest, and D = (1 − β)/(1 + β) the beam's Doppler factor in the sail's frame).
A proper acceleration g along x turns the 4-velocity as a boost, du/dτ = (g/c)(u¹, u⁰):

    d²t/dτ² = (g₀/c) D γβ,    d²(x/c)/dτ² = (g₀/c) D γ,    D = (γ − γβ)/(γ + γβ),

second-order equations like the shape's, so both solvers integrate them as two more generalized coordinates (the
in-house solver appends them to its minimal coordinates, Exudyn adds a node with two coordinates and unit mass).
Their solution is the closed form of :class:`lightsail_mbs.model.relativity.Trajectory`: with the rapidity w,
γ = cosh w, γβ = sinh w, the equations say dw/dτ = (g₀/c) e^{−2w}, so e^{2w} = e^{2w₀} + 2g₀τ/c and
D = e^{−2w} = D₀/(1 + 2D₀g₀τ/c): the Doppler term's closed form. The tests hold both solvers' β and t to the
closed forms of d(γβ)/dt = (c_n(0)P/(Mc²))(1 − β)/(1 + β).

**What reads it.** The beam's loads and the netted frame force scale by D (model/terms/doppler.py); with the state
the solver writes D of its current 4-velocity into the Doppler term's block before each sum
(:func:`lightsail_mbs.model.terms.registry.set_beam_factor`), in place of the closed form D₀/(1 + rτ). Along a run
the record of the world line (:func:`record`: lab time, distance, β, D at each output sample) is kept in the
Result's ``info["world_line"]``.
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.base.kernels import njit

COORDINATES = 2  # (t, x/c): appended after the shape's coordinates, their rates after the shape's rates


def rate_constant(p) -> float:
    """g₀/c (1/s): the craft's proper acceleration at rest over c (with a carried mass, the craft's:
    SailParameters.trajectory_acceleration)."""
    return p.trajectory_acceleration / SPEED_OF_LIGHT


def start(beta: float) -> tuple[np.ndarray, np.ndarray]:
    """(s, u) at the run's start: at the origin of the lab's time and distance, with the 4-velocity
    (γ₀, γ₀β₀) of the speed β₀."""
    gamma = 1.0 / math.sqrt(1.0 - beta * beta)
    return np.zeros(COORDINATES), np.array([gamma, gamma * beta])


@njit(cache=True)
def doppler(gamma, gamma_beta):
    """D = (1 − β)/(1 + β) = (γ − γβ)/(γ + γβ) of the 4-velocity (γ, γβ)."""
    return (gamma - gamma_beta) / (gamma + gamma_beta)


@njit(cache=True)
def accelerations(rate, gamma, gamma_beta):
    """(d²t/dτ², d²(x/c)/dτ², D): the 4-velocity's rates (g₀/c) D (γβ, γ) at the 4-velocity (γ, γβ);
    rate = g₀/c."""
    factor = doppler(gamma, gamma_beta)
    turn = rate * factor
    return turn * gamma_beta, turn * gamma, factor


def record(positions, rates) -> dict:
    """The world line at the output samples from the coordinates s (…, 2) and rates u (…, 2): lab time (s),
    distance (m), β and the Doppler factor D (arrays)."""
    positions, rates = np.asarray(positions, float), np.asarray(rates, float)
    gamma, gamma_beta = rates[..., 0], rates[..., 1]
    return {
        "lab_time": positions[..., 0],
        "distance": SPEED_OF_LIGHT * positions[..., 1],
        "beta": gamma_beta / gamma,
        "doppler": (gamma - gamma_beta) / (gamma + gamma_beta),
    }
