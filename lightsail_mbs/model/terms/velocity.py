"""The first-order velocity-dependent radiation load: Doppler and aberration of each body's own velocity.

**The frame.** The solvers work in the frame accelerating with the flat sail, at each moment the rest frame of
the flat sail; the beam there has the intensity I (the case's: the journey sets it to the lab intensity times
(1 − β)/(1 + β) of the sail's speed, :mod:`lightsail_mbs.model.relativity`) and travels along b̂. A body of the
sail moves relative to this frame with its small shape velocity v (β = v/c ≪ 1); the flat sail at rest in
it feels nothing of this term, so the frame's acceleration g₀ is unchanged.

**The facet law in the facet's rest frame.** The radiation term's law (:mod:`lightsail_mbs.model.loads`), for a
flat facet of area A, unit normal n̂, reflectivity R and absorptivity α lit along k̂ with intensity I',

    F' = (I' A/c) cos θ' [2R cos θ' n̂ + α k̂],        cos θ' = n̂·k̂,

holds in the rest frame of the facet. Boosting the beam's photons (four-momentum ħω(1, k̂)/c) from the sail's
frame into the facet's by β and keeping first order (the standard Doppler and aberration formulae, e.g.
Einstein 1905 §7–8; Rindler, *Relativity: Special, General and Cosmological*, 2006, §4.4):

    I' = I (1 − β·b̂)² ≈ I (1 − 2 β·b̂)          (one factor for each photon's energy, one for their rate)
    k̂' ≈ b̂ − β_⊥,    β_⊥ = β − (β·b̂) b̂        (aberration: the beam seems to come from ahead of the motion)
    cos θ' ≈ cos θ − n̂·β_⊥,                      cos θ = n̂·b̂.

The facet's rest mass stays constant (the absorbed power is re-radiated alike from both faces, as the radiation
term and :mod:`~lightsail_mbs.model.relativity` assume), so the force in the sail's frame is F' to first order
(F_∥ = F'_∥, F_⊥ = F'_⊥/γ). Expanding F' to first order in β (derived here, after the rigid-sail analyses of
Mackintosh et al., "Poynting–Robertson damping of laser beam driven lightsails", arXiv:2401.16924 (2024), and
J. Y. Lin, C. M. de Sterke, M. S. Wheatland, A. Y. Song and B. T. Kuhlmey, "All-optical damping forces enhanced
by metasurfaces for stable relativistic lightsail propulsion", arXiv:2408.14486 (2024)), with
cos θ β_b + n̂·β_⊥ = n̂·β:

    δF = −(I A/c) [ 4R cos θ (n̂·β) n̂ + α ((2 cos θ β_b + n̂·β_⊥) b̂ + cos θ β_⊥) ],     β_b = β·b̂.

- **Specular part**: only the facet's velocity along its own normal acts (a mirror sliding in its own plane
  sees the same light: Doppler and aberration cancel). A flat mirror moving along the beam at v_b feels
  −(2IA/c)(2v_b/c) b̂: a damping of rate 2g₀/c per unit mass on the normal velocity (g₀ = 2I/(cρh)), so a
  shape mode of a lit mirror decays at g₀/c. A flat mirror moving across the beam feels nothing at this order.
- **Absorbed part**: the absorbed momentum arrives along the aberrated k̂': a flat facet moving across the beam
  at v_⊥ feels the drag −α (IA/c)(v_⊥/c) (the Poynting–Robertson drag), along the beam −2α(IA/c)(v_b/c) b̂.
- Transmitted light exerts no force in the facet's frame, so it adds nothing.

R and α are the facet's at every wavelength, so the Doppler shift of the wavelength (first order too) changes
nothing here; an optical table's wavelength and angle derivatives would, and the case refuses this term with a
table. The force acts at the body's centre with the centre's velocity: the velocity varies linearly across a
rotating body and the law is linear in it, so a symmetric facet in a uniform beam has its exact first-order
force there; the moment of that variation, −(4RI/c²)·(ω l³W/12) per slice, is not applied (it falls as l²
relative to the slices' forces as the chain is refined).

Chain: b̂ = ŷ, n̂ = (−sin θ, cos θ), β_⊥ = β_x x̂; sheet: b̂ = ẑ, n̂ = (n₁, n₂, n_b), β_⊥ = (β_x, β_y, 0).
Reads the velocities (and the positions in a Gaussian beam: I is the local intensity).
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.base.kernels import njit
from lightsail_mbs.model import loads
from lightsail_mbs.model.loads import gaussian_intensity, round_gaussian_intensity
from lightsail_mbs.model.sheet_grid import Tiles
from lightsail_mbs.model.terms.bodies import (
    COS,
    N1,
    N2,
    NB,
    POSITIONS,
    SIN,
    TVX,
    TVY,
    TVZ,
    TX,
    TY,
    VELOCITIES,
    VX,
    VY,
    X,
)

ID = 5
FAMILIES = ("chain", "sheet")
TILE_HEAD = 6  # I₀, x_c, y_c, w, R, α; then A_k/c² of every tile


def active(p) -> bool:
    return p.velocity_terms


def reads(p) -> int:
    return VELOCITIES if p.uniform_beam else VELOCITIES | POSITIONS


def constants(p, family: str) -> np.ndarray:
    """Chain: I₀, x_c, w (inf: uniform), l W/c², R, α; sheet: I₀, x_c, y_c, w, R, α, then A_k/c² of every tile."""
    if family == "chain":
        area = p.slice_length * p.width / SPEED_OF_LIGHT**2
        return np.array([p.intensity, p.beam_centre, p.beam_waist, area, p.reflectivity, p.absorptivity])
    head = [p.intensity, p.beam_centre, p.sheet_beam_centre_y, p.beam_waist, p.reflectivity, p.absorptivity]
    return np.concatenate([head, Tiles.of(p).areas / SPEED_OF_LIGHT**2])


def chain(p, bodies: np.ndarray, forces: np.ndarray) -> None:
    """Adds δF on every slice (numpy form)."""
    scale = loads.intensity(p, bodies[X]) * (p.slice_length * p.width / SPEED_OF_LIGHT**2)
    c, s, vx, vy = bodies[COS], bodies[SIN], bodies[VX], bodies[VY]
    normal = 4.0 * p.reflectivity * c * (-s * vx + c * vy)  # 4R cos θ (n̂·v)
    absorb = p.absorptivity
    forces[0] -= scale * (normal * -s + absorb * c * vx)
    forces[1] -= scale * (normal * c + absorb * (2.0 * c * vy - s * vx))


def tiles(p, bodies: np.ndarray, forces: np.ndarray) -> None:
    """Adds δF on every tile (numpy form)."""
    scale = loads.sheet_intensity(p, bodies[TX], bodies[TY]) * (Tiles.of(p).areas / SPEED_OF_LIGHT**2)
    n1, n2, nb, vx, vy, vz = bodies[N1], bodies[N2], bodies[NB], bodies[TVX], bodies[TVY], bodies[TVZ]
    normal = 4.0 * p.reflectivity * nb * (n1 * vx + n2 * vy + nb * vz)
    absorb = p.absorptivity
    forces[0] -= scale * (normal * n1 + absorb * nb * vx)
    forces[1] -= scale * (normal * n2 + absorb * nb * vy)
    forces[2] -= scale * (normal * nb + absorb * (2.0 * nb * vz + (n1 * vx + n2 * vy)))


@njit(cache=True)
def chain_into(block, bodies, forces):
    """Adds δF on every slice (compiled form)."""
    peak, centre, waist, area, refl, absorb = block[0], block[1], block[2], block[3], block[4], block[5]
    for i in range(forces.shape[1]):
        scale = gaussian_intensity(bodies[X, i], peak, centre, waist) * area
        c, s, vx, vy = bodies[COS, i], bodies[SIN, i], bodies[VX, i], bodies[VY, i]
        normal = 4.0 * refl * c * (-s * vx + c * vy)
        forces[0, i] -= scale * (normal * -s + absorb * c * vx)
        forces[1, i] -= scale * (normal * c + absorb * (2.0 * c * vy - s * vx))


@njit(cache=True)
def tiles_into(block, bodies, forces):
    """Adds δF on every tile (compiled form)."""
    peak, cx, cy, waist, refl, absorb = block[0], block[1], block[2], block[3], block[4], block[5]
    for k in range(forces.shape[1]):
        scale = round_gaussian_intensity(bodies[TX, k], bodies[TY, k], peak, cx, cy, waist) * block[TILE_HEAD + k]
        n1, n2, nb = bodies[N1, k], bodies[N2, k], bodies[NB, k]
        vx, vy, vz = bodies[TVX, k], bodies[TVY, k], bodies[TVZ, k]
        normal = 4.0 * refl * nb * (n1 * vx + n2 * vy + nb * vz)
        forces[0, k] -= scale * (normal * n1 + absorb * nb * vx)
        forces[1, k] -= scale * (normal * n2 + absorb * nb * vy)
        forces[2, k] -= scale * (normal * nb + absorb * (2.0 * nb * vz + (n1 * vx + n2 * vy)))
