"""The payload's links in the Exudyn sheet (model.sheet_payload): the stem as one more
``ObjectConnectorRigidBodySpringDamper`` (the sheet's own connector law), the tethers as
``ObjectConnectorSpringDamper`` cables whose force law (slack in compression) is a ``springForceUserFunction``.

Exudyn's spring-damper pulls its two markers together with f(ΔL, ΔL̇) for ΔL = ℓ − ℓ₀ (``referenceLength``
ℓ₀); the cable's law is model.sheet_payload's, T = max(k ΔL + c ΔL̇, 0) for ΔL > 0, else 0, evaluated in
Python for each tether (a few per residual). The payload body itself and its frame force are the sheet
solver's (solvers.exudyn.sheet: one more rigid body, one more node of the load's GenericODE2).
"""

from __future__ import annotations


def cable_force(stiffness: float, damping: float):
    """Exudyn's springForceUserFunction of a cable: (mbs, t, item, ΔL, ΔL̇, k, c, force) → T (N)."""

    def force(mbs, t, item, stretch, rate, k, c, preload):
        if stretch <= 0.0:
            return 0.0
        return max(stiffness * stretch + damping * rate, 0.0)

    return force


def add_payload_links(mbs, bodies: list, payload) -> list:
    """Adds the stem or the tethers between the tiles' bodies and the payload's (the last of `bodies`);
    returns the tethers' Exudyn object numbers (empty for a stem or without a payload)."""
    if payload is None:
        return []
    import numpy as np
    from exudyn.itemInterface import (
        MarkerBodyPosition,
        MarkerBodyRigid,
        ObjectConnectorRigidBodySpringDamper,
        ObjectConnectorSpringDamper,
    )

    body = bodies[-1]
    stem = payload.stem
    if stem is not None:
        ma = mbs.AddMarker(MarkerBodyRigid(bodyNumber=bodies[stem["tile_a"]], localPosition=list(stem["local_a"])))
        mb = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body, localPosition=list(stem["local_b"])))
        link = ObjectConnectorRigidBodySpringDamper(
            markerNumbers=[ma, mb],
            stiffness=np.diag(stem["stiffness"]),
            damping=np.diag(stem["damping"]),
            offset=list(stem["offset"]),
        )
        mbs.AddObject(link)
        return []
    centre = mbs.AddMarker(MarkerBodyPosition(bodyNumber=body, localPosition=[0.0, 0.0, 0.0]))
    law = cable_force(payload.tether_stiffness, payload.tether_damping)
    rows = []
    for tile, point, rest in zip(payload.tether_tile, payload.tether_point, payload.tether_rest):
        end = mbs.AddMarker(MarkerBodyPosition(bodyNumber=bodies[int(tile)], localPosition=list(point)))
        cable = ObjectConnectorSpringDamper(
            markerNumbers=[end, centre],
            referenceLength=float(rest),
            stiffness=payload.tether_stiffness,
            damping=payload.tether_damping,
            springForceUserFunction=law,
        )
        rows.append(mbs.AddObject(cable))
    return rows
