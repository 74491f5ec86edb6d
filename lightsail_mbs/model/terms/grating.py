"""The in-plane (and normal) optical pressures of gratings on a sheet's tiles (model.sheet_grating: the law, the
sectors and the case field ``grating``).

Per tile k with in-plane axes x̂_k = R x̂, ŷ_k = n̂ × x̂_k (R ŷ) and normal n̂ = R ẑ, the beam's direction cosines
u_x = x̂_k·ẑ, u_y = ŷ_k·ẑ and cos θ = n_b give

    δF_k = (I(x_k, y_k) A_k/c) cos θ [c_x(u) x̂_k + c_y(u) ŷ_k + c_n(u) n̂],

the tile's coefficients (3T numbers: c_x, c_y, c_n as polynomials of the layout's degree d in (u_x, u_y), T =
(d + 1)(d + 2)/2 coefficients each, sheet_grating.tile_coefficients) turning with it. A tile lit from behind (cos θ ≤ 0)
carries none. The load is not netted against the frame force: the frame accelerates with the film's c_n(0) (the
radiation term), and a layout whose normal pressures differ by sector adds their differences (zero on the area mean
for a layout whose mean is the film's).
Reads the positions (the local intensity of a Gaussian beam) and the tiles' in-plane axes (bodies.E1X…E1Z).
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.base.kernels import njit
from lightsail_mbs.model import loads
from lightsail_mbs.model.loads import round_gaussian_intensity
from lightsail_mbs.model.sheet_grating import degree_of, monomials, tile_coefficients
from lightsail_mbs.model.sheet_grid import Tiles
from lightsail_mbs.model.terms.bodies import AXES, E1X, E1Y, E1Z, N1, N2, NB, POSITIONS, TX, TY

ID = 7
FAMILIES = ("sheet",)
HEAD = 5  # I₀, x_c, y_c, w, T; then per tile A_k/c and its 3T coefficients


def active(p) -> bool:
    return p.grating is not None


def reads(p) -> int:
    return (0 if p.uniform_beam else POSITIONS) | AXES


def constants(p, family: str) -> np.ndarray:
    """I₀, x_c, y_c, w, T, then per tile k: A_k/c and c_x, c_y, c_n (T coefficients each, in the tile's axes)."""
    coefficients = tile_coefficients(p)
    per_tile = np.column_stack([Tiles.of(p).areas / SPEED_OF_LIGHT, coefficients])
    head = [p.intensity, p.beam_centre, p.sheet_beam_centre_y, p.beam_waist, coefficients.shape[1] // 3]
    return np.concatenate([head, per_tile.ravel()])


def _frame(bodies):
    """x̂_k, ŷ_k = n̂ × x̂_k, n̂ (each (3, …)) and (u_x, u_y, cos θ) of the tiles."""
    e1 = bodies[E1X : E1Z + 1]
    n = bodies[[N1, N2, NB]]
    if not np.any(e1):
        raise ValueError("the grating term reads the tiles' in-plane axes R x̂: pass axes to terms.tile_forces")
    e2 = np.cross(n, e1, axis=0)
    return e1, e2, n, e1[2], e2[2], n[2]


def tiles(p, bodies: np.ndarray, forces: np.ndarray) -> None:
    """Adds δF on every tile (numpy form)."""
    block = constants(p, "sheet")
    terms = int(block[HEAD - 1])
    per_tile = block[HEAD:].reshape(-1, 1 + 3 * terms)
    e1, e2, n, ux, uy, cos = _frame(bodies)
    basis = monomials(ux, uy, degree_of(terms))  # (…, N, T)
    c = [np.sum(basis * per_tile[:, 1 + terms * i : 1 + terms * (i + 1)], axis=-1) for i in range(3)]
    scale = loads.sheet_intensity(p, bodies[TX], bodies[TY]) * per_tile[:, 0] * np.maximum(cos, 0.0)
    forces += scale * (c[0] * e1 + c[1] * e2 + c[2] * n)


@njit(cache=True)
def _monomials(ux, uy, degree, out):
    """out[:T] = the monomials in graded order (sheet_grating.monomials: row k is row k − 1 times u_x, its last
    times u_y)."""
    out[0] = 1.0
    start = 0  # where the row of degree k − 1 begins
    for k in range(1, degree + 1):
        at = start + k  # where the row of degree k begins
        for j in range(k):
            out[at + j] = out[start + j] * ux
        out[at + k] = out[start + k - 1] * uy
        start = at


@njit(cache=True)
def _poly(block, at, basis, terms):
    total = 0.0
    for i in range(terms):
        total += block[at + i] * basis[i]
    return total


@njit(cache=True)
def tiles_into(block, bodies, forces):
    """Adds δF on every tile (compiled form)."""
    peak, cx, cy, waist, terms = block[0], block[1], block[2], block[3], int(block[4])
    degree = int(round((math.sqrt(8.0 * terms + 1.0) - 3.0) / 2.0))
    basis = np.empty(terms)
    for k in range(forces.shape[1]):
        n0, n1, n2 = bodies[N1, k], bodies[N2, k], bodies[NB, k]
        if n2 <= 0.0:
            continue
        a0, a1, a2 = bodies[E1X, k], bodies[E1Y, k], bodies[E1Z, k]
        b0, b1, b2 = n1 * a2 - n2 * a1, n2 * a0 - n0 * a2, n0 * a1 - n1 * a0  # ŷ_k = n̂ × x̂_k
        at = HEAD + (1 + 3 * terms) * k
        scale = round_gaussian_intensity(bodies[TX, k], bodies[TY, k], peak, cx, cy, waist) * block[at] * n2
        _monomials(a2, b2, degree, basis)
        c_x = _poly(block, at + 1, basis, terms)
        c_y = _poly(block, at + 1 + terms, basis, terms)
        c_n = _poly(block, at + 1 + 2 * terms, basis, terms)
        forces[0, k] += scale * (c_x * a0 + c_y * b0 + c_n * n0)
        forces[1, k] += scale * (c_x * a1 + c_y * b1 + c_n * n1)
        forces[2, k] += scale * (c_x * a2 + c_y * b2 + c_n * n2)
