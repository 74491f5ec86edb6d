"""The radiation load through the beam profile and the optics, net of the frame force it drives.

The law is :mod:`lightsail_mbs.model.loads`' (Eq. 11 generalised to partial reflectors and Gaussian beams)
or an optical table's (:mod:`lightsail_mbs.model.optics_kernels`); the frame force −c_n(0) Ī A/c b̂ of the
frame accelerating with the flat sail is netted with it analytically (their floating-point cancellation
would seed short waves: loads' docstring). Chain: per slice at abscissa x and angle θ,
loads.net_slice_force (the R/α facet) or optics.packed_net_force (a table, with the slices' turned-over
flags). Sheet: per tile at (x, y) with unit normal (n₁, n₂, n_b), loads.net_facet_force in the round beam.
Reads the positions only for a Gaussian beam.

**A table with a wavelength axis inside a run** (a chain whose state holds its world line, integrated_trajectory;
model/world_line.py): the block also carries the packed tables of the grid's wavelengths (:func:`spectral_section`),
and before each sum the solver writes the table at the sail-frame wavelength λ' = λ₀/√D into the block's table and
its c_n(0) into the head (:func:`set_wavelength`, through registry.set_beam_factor), as
optics_spectrum.SpectralTable.at makes it: linear in λ between the grid wavelengths. c_n(0; λ') nets the frame force
of the moment, and its ratio to c_n(0; λ₀) scales the craft's proper acceleration in the world line.
"""

from __future__ import annotations

import math

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
# peak I₀, Ī, A/c, x_c, w, R, α, c_n(0), the start of a wavelength axis's section (0: none); then, with a table,
# the n slice flags and the table (and, with a wavelength axis in a run that integrates its world line, the section)
CHAIN_HEAD = 9
SPECTRAL_HEAD = 4  # the section: wavelengths M, λ₀, the packed table's size, c_n(0; λ₀); then λ_k, c_n(0; λ_k), tables
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
        head += [p.beam_waist, p.reflectivity, p.absorptivity, p.normal_momentum, 0.0]
        table = optics.solver_block(p) if p.optics is not None else np.zeros(0)
        block = np.concatenate([head, table])
        spectrum = spectrum_in_run(p)
        if spectrum is None:
            return block
        block[CHAIN_HEAD - 1] = block.size
        return np.concatenate([block, spectral_section(spectrum)])
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


# ---- a wavelength axis inside a run -----------------------------------------------------------------------------
def spectrum_in_run(p):
    """The case's table with a wavelength axis (optics_spectrum.SpectralTable) when its run integrates the sail's
    world line (integrated_trajectory): the run reads it at the sail-frame wavelength of its state; else None."""
    if not (p.integrated_trajectory and p.optics_file):
        return None
    from lightsail_mbs.model.optics_spectrum import read_spectrum

    return read_spectrum(p.optics, single=True)


def spectral_section(spectrum) -> np.ndarray:
    """[M, λ₀, size, c_n(0; λ₀), λ_1…λ_M, c_n(0; λ_1)…c_n(0; λ_M), the M packed tables (size each)]."""
    packed = [t.packed() for t in spectrum.tables]
    normal = [t.normal_at_zero for t in spectrum.tables]
    head = [len(packed), spectrum.wavelength, packed[0].size, spectrum.rest().normal_at_zero]
    return np.concatenate([head, spectrum.wavelengths, normal, *packed])


@njit(cache=True)
def _weights(section, wavelength):
    """(k, w) of SpectralTable.weights: λ = (1 − w) λ_k + w λ_{k+1}, a wavelength within 1e-12 of a grid
    wavelength taken as it; k = −1 outside the grid's range."""
    count = int(section[0])
    grid = section[SPECTRAL_HEAD : SPECTRAL_HEAD + count]
    if not grid[0] * (1 - 1e-12) <= wavelength <= grid[count - 1] * (1 + 1e-12):
        return -1, 0.0
    v = min(max(wavelength, grid[0]), grid[count - 1])
    nearest = int(np.argmin(np.abs(grid - v)))
    if abs(grid[nearest] - v) <= 1e-12 * v:
        v = grid[nearest]
    k = 0
    while k < count - 2 and grid[k + 1] <= v:
        k += 1
    return k, (v - grid[k]) / (grid[k + 1] - grid[k])


@njit(cache=True)
def set_wavelength(block, factor):
    """Writes the table at the sail-frame wavelength λ' = λ₀/√D (D = factor) into the block's table, as
    SpectralTable.at makes it (linear in λ between the grid wavelengths: the constants and nodes of the lower
    one, the coefficients mixed), and its c_n(0) into the head; returns c_n(0; λ')/c_n(0; λ₀) (NaN outside the
    table's wavelengths, which then stops the run as non-finite). A block without a wavelength axis: 1."""
    start = int(block[CHAIN_HEAD - 1])
    if start == 0:
        return 1.0
    section = block[start:]
    count, size = int(section[0]), int(section[2])
    k, w = _weights(section, section[1] / math.sqrt(factor))
    if k < 0:
        block[7] = math.nan
        return math.nan
    normal = section[SPECTRAL_HEAD + count :]
    tables = section[SPECTRAL_HEAD + 2 * count :]
    lower, upper = tables[k * size : (k + 1) * size], tables[(k + 1) * size : (k + 2) * size]
    slot = block[start - size : start]
    first = 5 + int(lower[1])  # the coefficients follow the header and the nodes
    if w == 1.0:
        slot[:] = upper
    else:
        slot[:] = lower
        if w != 0.0:
            slot[2] = 1.0  # bounded, as SpectralTable.at makes a mixed table
            for i in range(first, size):
                slot[i] = (1.0 - w) * lower[i] + w * upper[i]
    momentum = normal[k] if w == 0.0 else (normal[k + 1] if w == 1.0 else (1.0 - w) * normal[k] + w * normal[k + 1])
    block[7] = momentum
    return momentum / section[3]
