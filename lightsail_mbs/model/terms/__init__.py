"""Physics terms: every load on the bodies of a model family written once, packed once, summed by every solver.

A term is one load or effect on the bodies — the radiation through the beam profile and the optics with the
frame force netted analytically (:mod:`~lightsail_mbs.model.terms.radiation`), a payload's share of the
frame force (:mod:`~lightsail_mbs.model.terms.frame`), the Doppler dimming of the beam along the sail's
trajectory (:mod:`~lightsail_mbs.model.terms.doppler`), a dead pressure (:mod:`~lightsail_mbs.model.terms.pressure`)
— in one module with one numpy form and one compiled form per family it acts on. One packer
(:func:`pack`) lays the constants of the active terms out as the one float vector that every compiled
kernel reads (the reduced chain's right-hand side, the Exudyn tree's force function, the reduced sheet's
right-hand side); the Exudyn sheet sums the numpy forms (:func:`tile_forces`). The rules a term keeps (a
new one follows them from this docstring alone):

1. **One module** in this package with ``ID`` (a unique positive integer), ``FAMILIES`` (a subset of
   ``("chain", "sheet")``), ``active(p)`` (whether it acts on case p: an inactive term is not packed and
   costs nothing), ``reads(p)`` (``bodies.POSITIONS | bodies.VELOCITIES | bodies.AXES``, what it reads beyond angles or
   normals: the kernels may skip computing what no active term reads) and ``constants(p, family)`` (its
   block: a 1-D float array; the case and its derived quantities are read here, never in a kernel).
2. **Bodies in, forces out.** For each family it declares, a numpy form ``chain(p, bodies, forces)`` or
   ``tiles(p, bodies, forces)`` and a compiled form ``chain_into(block, bodies, forces)`` or
   ``tiles_into(block, bodies, forces)`` (``base.kernels.njit(cache=True)``), or one compiled form
   ``into(block, bodies, forces, tiles)`` for both families where they share it (a force per body along one
   axis: :mod:`~lightsail_mbs.model.terms.uniform`). ``bodies`` holds the bodies'
   state row by row (:mod:`~lightsail_mbs.model.terms.bodies`: centres, angle or normal, velocities,
   angular velocities, in the frame accelerating with the flat sail); both forms *add* the force on each
   body centre, in inertial directions (N), into ``forces`` (2 or 3 rows, one column per body). The numpy
   form takes any leading axes; the compiled one (rows, count) arrays and allocates nothing per body.
   A term whose law depends on time declares ``TIMED = True``; its four forms then take one more argument,
   ``time``: the run's time τ (s), the sail's proper time from the run's start, which every solver passes to
   the sums (:func:`chain_forces_into`, :func:`tile_forces_into` and the numpy sums' ``time``; a number, or
   for the numpy forms an array of the leading axes).
3. **One layout.** :func:`pack` writes ``[count, reads, (ID, size, block) per active term]``; the kernels
   pass it whole to :func:`chain_forces_into` / :func:`tile_forces_into`, which hand each term its block.
   No kernel reads a term's constants by position.
4. **Order is arithmetic.** The sum starts at −0.0 (the exact additive identity, so the first term's force
   is kept to the bit) and adds the terms in :data:`TERMS` order; a term's form keeps its own operation
   order. Moving a term or an operation changes the last bits of every run. The beam's terms come first:
   the Doppler term adds a multiple of the forces summed before it, so it scales exactly them.
5. **Cancellation stays inside a term.** Forces that nearly cancel (the radiation load and the frame force:
   their sum is O(θ²) of each) are one term, netted analytically in its law (:mod:`~lightsail_mbs.model.loads`);
   two terms summed in floating point keep only the digits the cancellation leaves and seed short waves.
6. **One registration**, in ``registry.py``: the module in :data:`TERMS`, and its compiled form called by
   its ID, for each family it declares, in the dispatcher ``registry._add_term``.
   A packed term that a dispatcher lacks raises at the first call; the tests hold every term's compiled
   sum to its numpy sum for both families.
7. **Not a term**: the connections' laws (joint springs and dampers, the sheet's edge connectors and their
   damping), the follower edge tension and a payload's own body: they act at points or between bodies,
   and Exudyn runs them natively (joint P/D control, C++ connectors, body-fixed loads), so they stay with
   the family's model (:mod:`~lightsail_mbs.model.sheet_connectors`, the chains' joints); a payload's own
   frame force follows the beam's factor there (:func:`beam_factor`).
"""

from lightsail_mbs.model.terms.registry import (
    TERMS,
    active_terms,
    beam_factor,
    chain_forces,
    chain_forces_into,
    pack,
    reads,
    set_beam_factor,
    tile_forces,
    tile_forces_into,
)

__all__ = [
    "TERMS",
    "active_terms",
    "beam_factor",
    "chain_forces",
    "chain_forces_into",
    "pack",
    "reads",
    "set_beam_factor",
    "tile_forces",
    "tile_forces_into",
]
