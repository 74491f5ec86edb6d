"""The start of a spinning sheet case with ``spin_equilibrium``: the shape at rest in its turning frame, found
by the in-house solver's ``spun_equilibrium`` capability (solvers.reduced.sheet_relax) and shared by both
solvers' runs (model.sheet_pose.initial_motion starts the bodies there, spinning rigidly at Ω)."""

from __future__ import annotations

from functools import lru_cache

from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.solvers import contract


@lru_cache(maxsize=8)
def _equilibrium(p: SailParameters):
    return contract.lookup("reduced", p).capability("spun_equilibrium")(p)


def spun_shape(p: SailParameters):
    """None, or (centres (B, 3), quaternions (B, 4)) of every body (the tiles, then a payload) to start from:
    the spun equilibrium of a case with spin_equilibrium (computed once per case in a process)."""
    if not p.spin_equilibrium:
        return None
    centres, quaternions = _equilibrium(p)
    return centres.copy(), quaternions.copy()
