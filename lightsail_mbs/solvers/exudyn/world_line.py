"""The sail's world line in an Exudyn run: a node of two coordinates integrated with the chain.

A case with ``integrated_trajectory`` carries the sail's lab time and distance over c, s = (t, x/c), with their
rates along the proper time, the 4-velocity u = (γ, γβ) (:mod:`lightsail_mbs.model.world_line`). Here they are
one ``NodeGenericODE2`` of two coordinates and an ``ObjectGenericODE2`` of unit mass whose force user function
is the boost du/dτ = (g₀/c) D (γβ, γ), D = (γ − γβ)/(γ + γβ) (times c_n(0; λ')/c_n(0; λ₀) for an optical table
with a wavelength axis): the same integrator steps them with the tree.
The tree's force user function reads the node's current 4-velocity (the stage or Newton iterate being
evaluated) and writes its D into the packed Doppler term before it sums the loads (:func:`beam_factor_reader`).
The node's coordinates come after the tree's in the system's ODE2 vector, so the sampler's q, q̇ carry them.
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.model import terms, world_line
from lightsail_mbs.model.parameters import SailParameters


def add_world_line(p: SailParameters, mbs) -> int:
    """Adds the world line's node and its object to mbs; returns the node's number."""
    from exudyn.itemInterface import NodeGenericODE2, ObjectGenericODE2

    s0, u0 = world_line.start(p.initial_beta)
    rate = world_line.rate_constant(p)
    node = mbs.AddNode(
        NodeGenericODE2(
            referenceCoordinates=[0.0] * world_line.COORDINATES,
            initialCoordinates=list(s0),
            initialCoordinates_t=list(u0),
            numberOfODE2Coordinates=world_line.COORDINATES,
        )
    )
    force = np.zeros(world_line.COORDINATES)
    packed = terms.pack(p, "chain")  # its own copy: with a wavelength axis, c_n(0) at λ' scales the acceleration

    def boost(mbs, t, item, q, q_t):
        ratio = terms.set_beam_factor(packed, world_line.doppler(q_t[0], q_t[1]))
        force[0], force[1], _ = world_line.accelerations(rate * ratio, q_t[0], q_t[1])
        return force

    mbs.AddObject(
        ObjectGenericODE2(
            nodeNumbers=[node],
            massMatrix=np.eye(world_line.COORDINATES),
            forceUserFunction=boost,
        )
    )
    return node


def beam_factor_reader(mbs, node: int):
    """A function () ↦ D of the node's current 4-velocity (model.world_line.doppler)."""
    import exudyn as exu

    rates = exu.OutputVariableType.Coordinates_t

    def factor() -> float:
        u = mbs.GetNodeOutput(node, rates)
        return float(world_line.doppler(u[0], u[1]))

    return factor
