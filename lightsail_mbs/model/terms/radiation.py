"""The radiation load through the beam profile and the optics, net of the frame force it drives.

The law is :mod:`lightsail_mbs.model.loads`' (Eq. 11 generalised to partial reflectors and Gaussian beams)
or an optical table's (:mod:`lightsail_mbs.model.optics_kernels`); the frame force −c_n(0) Ī A/c b̂ of the
frame accelerating with the flat sail is netted with it analytically (their floating-point cancellation
would seed short waves: loads' docstring). Chain: per slice at abscissa x and angle θ,
loads.net_slice_force (the R/α facet) or optics.packed_net_force (a table, with the slices' turned-over
flags). Sheet: per tile at (x, y) with unit normal (n₁, n₂, n_b), loads.net_facet_force in the round beam.
Reads the positions only for a Gaussian beam.
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.base.kernels import njit
from lightsail_mbs.model import loads, optics
from lightsail_mbs.model.loads import gaussian_intensity, net_facet_force, net_slice_force, round_gaussian_intensity
from lightsail_mbs.model.optics_kernels import packed_net_force
from lightsail_mbs.model.sheet_grid import Tiles
from lightsail_mbs.model.terms.bodies import COS, N1, N2, NB, POSITIONS, SIN, THETA, TX, TY, X

ID = 1
FAMILIES = ("chain", "sheet")
CHAIN_HEAD = 8  # peak I₀, Ī, A/c, x_c, w, R, α, c_n(0); then, with a table, the n slice flags and the table
TILE_HEAD = 7  # Ī, I₀, x_c, y_c, w, R, α; then A_k/c of every tile


def active(p) -> bool:
    return True


def reads(p) -> int:
    return 0 if p.uniform_beam else POSITIONS


def constants(p, family: str) -> np.ndarray:
    """Chain: I₀, Ī, l W/c, x_c, w (inf: uniform), R, α, c_n(0) [, flags, packed table]; sheet: Ī, I₀, x_c,
    y_c, w, R, α, then A_k/c of every tile k."""
    if family == "chain":
        head = [p.intensity, p.mean_intensity, p.slice_length * p.width / SPEED_OF_LIGHT, p.beam_centre]
        head += [p.beam_waist, p.reflectivity, p.absorptivity, p.normal_momentum]
        table = optics.solver_block(p) if p.optics is not None else np.zeros(0)
        return np.concatenate([head, table])
    beam = [p.intensity, p.beam_centre, p.sheet_beam_centre_y, p.beam_waist]
    head = np.array([p.mean_intensity, *beam, p.reflectivity, p.absorptivity])
    return np.concatenate([head, Tiles.of(p).areas / SPEED_OF_LIGHT])


def chain(p, bodies: np.ndarray, forces: np.ndarray) -> None:
    """Adds the net force on the slices to forces (numpy form: loads.net_slice_forces; with a table, its
    compiled law chain by chain)."""
    if p.optics is None:
        fx, fy = loads.net_slice_forces(p, bodies[X], bodies[THETA])
        forces[0] += fx
        forces[1] += fy
        return
    block = constants(p, "chain")
    for index in np.ndindex(bodies.shape[1:-1]):
        at = (slice(None), *index)
        chain_into(block, bodies[at], forces[at])


def tiles(p, bodies: np.ndarray, forces: np.ndarray) -> None:
    """Adds the net force on the tiles to forces (numpy form: loads.facet_forces)."""
    local = loads.sheet_intensity(p, bodies[TX], bodies[TY])
    across = np.stack([bodies[N1], bodies[N2]], axis=-1)
    tiles = Tiles.of(p)
    area = tiles.area if tiles.mesh.cell is not None else tiles.areas  # a grid's tiles are alike
    f_across, f_along = loads.facet_forces(
        across, bodies[NB], local, p.mean_intensity, area, p.reflectivity, p.absorptivity
    )
    forces[:2] += np.moveaxis(f_across, -1, 0)
    forces[2] += f_along


@njit(cache=True)
def chain_into(block, bodies, forces):
    """Adds the net force on every slice to forces (compiled form)."""
    peak, mean, area_c, centre, waist = block[0], block[1], block[2], block[3], block[4]
    refl, absorb, momentum = block[5], block[6], block[7]
    n = forces.shape[1]
    table = block[CHAIN_HEAD + n :]
    for i in range(n):
        local = gaussian_intensity(bodies[X, i], peak, centre, waist)
        theta, c, s = bodies[THETA, i], bodies[COS, i], bodies[SIN, i]
        if block.size > CHAIN_HEAD:
            mirrored = block[CHAIN_HEAD + i] != 0.0
            fx, fy = packed_net_force(table, local, mean, area_c, c, s, theta, mirrored, momentum)
        else:
            fx, fy = net_slice_force(theta, c, s, local, mean, area_c, refl, absorb)
        forces[0, i] += fx
        forces[1, i] += fy


@njit(cache=True)
def tiles_into(block, bodies, forces):
    """Adds the net force on every tile to forces (compiled form)."""
    mean, peak, cx, cy, waist, refl, absorb = block[0], block[1], block[2], block[3], block[4], block[5], block[6]
    for k in range(forces.shape[1]):
        local = round_gaussian_intensity(bodies[TX, k], bodies[TY, k], peak, cx, cy, waist)
        area_c = block[TILE_HEAD + k]
        f0, f1, f2 = net_facet_force(bodies[N1, k], bodies[N2, k], bodies[NB, k], local, mean, area_c, refl, absorb)
        forces[0, k] += f0
        forces[1, k] += f1
        forces[2, k] += f2
