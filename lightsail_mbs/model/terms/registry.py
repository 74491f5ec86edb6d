"""The registered physics terms, the one packer of their constants, and the sums every solver calls.

Registering a term (the package's rule 6): its module in :data:`TERMS`, and its compiled form called by its
ID, for each family it declares, in the dispatcher ``_add_term``. The sums take the run's time τ (s, the
sail's proper time from the run's start; 0 outside a run) and hand it to the terms that declare ``TIMED``.
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.base.kernels import njit
from lightsail_mbs.model.terms import body_force, doppler, frame, grating, pressure, radiation, velocity
from lightsail_mbs.model.terms.bodies import COUNT, ENTRY, HEADER, READS, chain_bodies, tile_bodies

# the order of summation: the forces of every body are added in this order (rule 4); the beam's loads come
# first, so that the Doppler term scales exactly them (model/terms/doppler.py), then the loads of other origin
TERMS = (radiation, grating, frame, velocity, doppler, pressure, body_force)


def active_terms(p, family: str) -> tuple:
    """The registered terms that act on case p of `family` ("chain" or "sheet"), in summation order."""
    return tuple(t for t in TERMS if family in t.FAMILIES and t.active(p))


def pack(p, family: str) -> np.ndarray:
    """The constants every kernel of `family` reads for case p: [count, reads, then per active term its ID,
    its block's size and its block] (rule 3)."""
    terms = active_terms(p, family)
    entries, reads = [], 0
    for term in terms:
        block = np.asarray(term.constants(p, family), dtype=float)
        entries += [np.array([term.ID, block.size], dtype=float), block]
        reads |= term.reads(p)
    return np.concatenate([np.array([len(terms), reads], dtype=float), *entries])


def reads(packed: np.ndarray) -> int:
    """What the packed terms read beyond angles or normals (bodies.POSITIONS | bodies.VELOCITIES)."""
    return int(packed[READS])


def _timed(term, time) -> tuple:
    """The further arguments of a term's forms: the time τ for a term that declares TIMED."""
    return (time,) if getattr(term, "TIMED", False) else ()


def chain_forces(p, x, theta, y=None, vx=None, vy=None, omega=None, time=0.0) -> tuple[np.ndarray, np.ndarray]:
    """(f_x, f_y), each (…, n): the sum of the active terms' numpy forms on slices at abscissae x, angles θ
    (and heights y, velocities where a term reads them) at the run's time τ (a number or an array of the
    leading axes …), N."""
    bodies = chain_bodies(x, theta, y, vx, vy, omega)
    forces = np.full((2, *bodies.shape[1:]), -0.0)
    for term in active_terms(p, "chain"):
        term.chain(p, bodies, forces, *_timed(term, time))
    return forces[0], forces[1]


def tile_forces(p, centres, normals, velocities=None, angular_velocities=None, time=0.0, axes=None) -> np.ndarray:
    """(…, N, 3): the sum of the active terms' numpy forms on tiles at `centres` with unit `normals` (their
    x, y components without cancellation), velocities and in-plane axes R x̂ (`axes`) where a term reads them,
    at the run's time τ, N."""
    bodies = tile_bodies(centres, normals, velocities, angular_velocities, axes)
    forces = np.full((3, *bodies.shape[1:]), -0.0)
    for term in active_terms(p, "sheet"):
        term.tiles(p, bodies, forces, *_timed(term, time))
    return np.moveaxis(forces, 0, -1)


@njit(cache=True)
def _add_term(term, block, bodies, forces, tiles, time):
    """The registrations: the compiled form of the term with this ID, for the chain or (tiles) the sheet."""
    if term == radiation.ID and not tiles:
        radiation.chain_into(block, bodies, forces)
    elif term == radiation.ID:
        radiation.tiles_into(block, bodies, forces)
    elif term == frame.ID:
        frame.into(block, bodies, forces, tiles)
    elif term == grating.ID and tiles:
        grating.tiles_into(block, bodies, forces)
    elif term == pressure.ID and tiles:
        pressure.tiles_into(block, bodies, forces)
    elif term == body_force.ID:
        body_force.into(block, bodies, forces, tiles)
    elif term == velocity.ID and not tiles:
        velocity.chain_into(block, bodies, forces)
    elif term == velocity.ID:
        velocity.tiles_into(block, bodies, forces)
    elif term == doppler.ID and not tiles:
        doppler.chain_into(block, bodies, forces, time)
    elif term == doppler.ID:
        doppler.tiles_into(block, bodies, forces, time)
    else:
        raise ValueError("a packed term without a compiled form for this family")


@njit(cache=True)
def _sum_into(packed, bodies, forces, tiles, time):
    """forces = −0.0, then each packed term's compiled form added in the packed order (rules 3–4)."""
    forces[:, :] = -0.0
    at = HEADER
    for _ in range(int(packed[COUNT])):
        size = int(packed[at + 1])
        block = packed[at + ENTRY : at + ENTRY + size]
        _add_term(packed[at], block, bodies, forces, tiles, time)
        at += ENTRY + size


@njit(cache=True)
def chain_forces_into(packed, bodies, forces, time):
    """forces (2, n) = the sum of the packed terms' compiled forms on the slices `bodies` (CHAIN_ROWS, n) at
    the run's time τ (s)."""
    _sum_into(packed, bodies, forces, False, time)


@njit(cache=True)
def tile_forces_into(packed, bodies, forces, time):
    """forces (3, N) = the sum of the packed terms' compiled forms on the tiles `bodies` (TILE_ROWS, N) at
    the run's time τ (s)."""
    _sum_into(packed, bodies, forces, True, time)


@njit(cache=True)
def beam_factor(packed, time):
    """The factor on the beam's loads at the run's time τ: the Doppler term's D(τ) when it is packed, else 1.
    For the beam loads a solver applies outside the terms (a payload's own frame force −m_p g₀)."""
    at = HEADER
    for _ in range(int(packed[COUNT])):
        size = int(packed[at + 1])
        if packed[at] == doppler.ID:
            return doppler.factor(packed[at + ENTRY : at + ENTRY + size], time)
        at += ENTRY + size
    return 1.0


@njit(cache=True)
def set_beam_factor(packed, value):
    """Writes the beam's factor D into the packed Doppler term (a run whose state holds the sail's world line,
    model/world_line.py: the term's rate is 0 there, so its factor is then `value` exactly), and for an optical
    table with a wavelength axis its table at the sail-frame wavelength λ₀/√D into the radiation term
    (radiation.set_wavelength). Returns c_n(0; λ')/c_n(0; λ₀), the factor on the craft's proper acceleration
    beyond D (1 without a wavelength axis)."""
    ratio = 1.0
    at = HEADER
    for _ in range(int(packed[COUNT])):
        size = int(packed[at + 1])
        if packed[at] == doppler.ID:
            packed[at + ENTRY] = value
        elif packed[at] == radiation.ID:
            ratio = radiation.set_wavelength(packed[at + ENTRY : at + ENTRY + size], value)
        at += ENTRY + size
    return ratio
