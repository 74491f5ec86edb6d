"""Supports and tip load of the Exudyn chain (validations, paper Appendices A–B; SailParameters.boundary).

Added to the assembled KinematicTree (exudyn_model: q = [X, Y, θ₁, (z₁), φ₂, …], X, Y = hinge 0):

* cantilever: slice 1 clamped at its initial pose: X, Y and θ₁ held at their initial values by
  three ``ObjectConnectorCoordinate`` constraints to a ground coordinate (linear, exact);
* pinned: hinge 0 pinned (X, Y held the same way) and hinge n (the right end of slice n, a
  ``MarkerKinematicTreeRigid``) on a roller: an ``ObjectJointGeneric`` to a ground frame that
  constrains only the y translation, at hinge n's initial height. The follower end tension of the
  TnT chain still acts (Eq. 32): at the pin it loads the support, at the roller its x part is the
  tension the string carries;
* tip load P(t) = P₀(1 − e^(−t/τ)) ŷ (Eq. 43) at the centre of slice n: a ``LoadForceVector`` on a
  ``MarkerKinematicTreeRigid`` (a user function only when τ > 0).

The constraints make the system a DAE (index 3, Lagrange multipliers), which Exudyn's
generalized-α and static solvers handle directly; ComputeODE2Eigenvalues projects on the null
space of their Jacobian.
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.solvers.exudyn.tree import ChainLayout


def add_supports(p: SailParameters, mbs, node: int, tree: int, layout: ChainLayout, q0: np.ndarray) -> None:
    """Add the constraints of p.boundary and the tip load to mbs (before Assemble)."""
    from exudyn.itemInterface import (
        LoadForceVector,
        MarkerBodyRigid,
        MarkerKinematicTreeRigid,
        MarkerNodeCoordinate,
        NodePointGround,
        ObjectConnectorCoordinate,
        ObjectGround,
        ObjectJointGeneric,
    )

    l = layout.slice_length
    last = int(layout.angle_index[-1])
    if p.boundary != "free":
        ground_node = mbs.AddNode(NodePointGround())
        ground_coordinate = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground_node, coordinate=0))
        held = [0, 1] + ([int(layout.angle_index[0])] if p.boundary == "cantilever" else [])
        for i in held:
            marker = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=node, coordinate=i))
            mbs.AddObject(ObjectConnectorCoordinate(markerNumbers=[ground_coordinate, marker], offset=float(q0[i])))
    if p.boundary == "pinned":
        x, y, theta, _ = layout.positions(q0)
        end = [x[-1] + 0.5 * l * np.cos(theta[-1]), y[-1] + 0.5 * l * np.sin(theta[-1]), 0.0]
        ground = mbs.AddObject(ObjectGround(referencePosition=[0.0, 0.0, 0.0]))
        support = mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=end))
        tip = mbs.AddMarker(MarkerKinematicTreeRigid(objectNumber=tree, linkNumber=last, localPosition=[l, 0.0, 0.0]))
        mbs.AddObject(ObjectJointGeneric(markerNumbers=[support, tip], constrainedAxes=[0, 1, 0, 0, 0, 0]))
    if p.tip_load:
        centre = mbs.AddMarker(
            MarkerKinematicTreeRigid(objectNumber=tree, linkNumber=last, localPosition=[0.5 * l, 0.0, 0.0])
        )
        kwargs = {}
        if p.tip_load_time_constant:
            kwargs["loadVectorUserFunction"] = lambda mbs, t, load: [0.0, p.tip_force(t), 0.0]
        mbs.AddLoad(LoadForceVector(markerNumber=centre, loadVector=[0.0, p.tip_load, 0.0], **kwargs))
