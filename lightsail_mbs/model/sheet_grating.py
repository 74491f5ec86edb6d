"""Gratings on a sheet's tiles: in-plane optical pressures, by sectors of the sail (the case field ``grating``).

**The law.** A tile of area A carries a grating whose grating vector ĝ (across its lines) lies in the tile's
plane and turns with it; with its normal n̂ it spans the grating's frame (ĝ, n̂ × ĝ, n̂). The beam travels along
b̂ = ẑ with the local intensity I; its direction cosines in that frame are

    u₁ = ĝ·b̂,    u₂ = (n̂ × ĝ)·b̂,    cos θ = n̂·b̂

(u₁ the sine of the incidence angle's part across the lines, u₂ along them). The grating adds to the film's
specular facet law (model.loads, the radiation term) the force

    δF = (I A/c) cos θ [c_g(u₁, u₂) ĝ + c_l(u₁, u₂) (n̂ × ĝ) + c_n(u₁, u₂) n̂],

its pressures per unit lit area (cos θ A is the projected area, as in FlexSailSim's tables), each a quadratic
c(u₁, u₂) = c₀ + c₁ u₁ + c₂ u₂ + c₁₁ u₁² + c₁₂ u₁u₂ + c₂₂ u₂²: its value, slopes and curvatures at normal
incidence. A grating whose table gives its whole normal pressure c_z carries c_n = c_z − c_n,film (the film's
(2R + α) cos θ expanded to second order: c̄ − c̄ (u₁² + u₂²)/2), so that the tile's normal pressure is the
table's. With every coefficient 0 the load is the film's, to the bit.

**Sectors.** A layout (a TOML file, :func:`read`) lists sectors of the sail by polar angle φ about the sail's
middle (L/2, W/2), φ from +x towards +y: each ``[[sector]]`` has ``from`` and ``to`` (degrees, to − from ≤ 360),
``direction`` (the grating vector's angle from the sail's x axis, degrees, in the sail's own axes, which are the
tiles' at rest) and the three coefficient lists ``along`` (c_g), ``across`` (c_l) and ``normal`` (c_n), six
numbers each in the order above (a list left out: zeros). Sectors may not overlap; a tile outside every sector
is plain film. A tile that straddles sectors carries their laws weighted by the shares of its area in each
(:func:`tile_coefficients`: the tile's polygon cut by the sectors' rays), rotated into the tile's own axes
(x̂_b, ŷ_b) — the rotated law is again quadratic in (u_x, u_y) = (R x̂·ẑ, R ŷ·ẑ), so each tile carries 18 numbers:
c_x, c_y, c_n in its axes (:data:`PER_TILE`).
"""

from __future__ import annotations

import math
from functools import lru_cache
from pathlib import Path

import numpy as np

from lightsail_mbs.base.validation import ParameterError

TERMS = 6  # c₀, c₁, c₂, c₁₁, c₁₂, c₂₂
PER_TILE = 3 * TERMS  # c_x, c_y, c_n of a tile in its own axes
LISTS = ("along", "across", "normal")
KEYS = {"from", "to", "direction", *LISTS, "name"}


def monomials(u1, u2) -> np.ndarray:
    """(…, 6): 1, u₁, u₂, u₁², u₁u₂, u₂²."""
    u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
    return np.stack([np.ones_like(u1), u1, u2, u1 * u1, u1 * u2, u2 * u2], axis=-1)


def _fail(path, what: str):
    raise ParameterError(
        f"grating={str(path)!r} is invalid: {what} (a TOML file of [[sector]] tables with from, to, direction "
        f"in degrees and along, across, normal: 6 numbers each; model/sheet_grating.py)"
    )


@lru_cache(maxsize=32)
def _read(path: str, stamp: float) -> tuple:
    from lightsail_mbs.model.casefile import tomllib

    try:
        with open(path, "rb") as handle:
            data = tomllib.load(handle)
    except (OSError, ValueError) as exc:
        _fail(path, f"unreadable ({exc})")
    if set(data) != {"sector"} or not isinstance(data["sector"], list) or not data["sector"]:
        _fail(path, "it must hold one or more [[sector]] tables and nothing else")
    sectors = []
    for i, s in enumerate(data["sector"]):
        extra = set(s) - KEYS
        if extra or not {"from", "to", "direction"} <= set(s):
            _fail(path, f"sector {i + 1} has keys {sorted(s)}; allowed: {sorted(KEYS)}, from, to, direction required")
        start, end, direction = (float(s[k]) for k in ("from", "to", "direction"))
        if not all(math.isfinite(v) for v in (start, end, direction)) or not 0 < end - start <= 360:
            _fail(path, f"sector {i + 1}: finite angles with 0 < to − from ≤ 360")
        laws = []
        for key in LISTS:
            values = s.get(key, [0.0] * TERMS)
            if len(values) != TERMS or not all(isinstance(v, (int, float)) and math.isfinite(v) for v in values):
                _fail(path, f"sector {i + 1}: {key} must be {TERMS} finite numbers")
            laws.append([float(v) for v in values])
        sectors.append((start, end, direction, tuple(map(tuple, laws))))
    return tuple(sectors)


def read(path: str) -> tuple:
    """The sectors of a layout file: ((from, to, direction) in degrees, ((c_g), (c_l), (c_n))) per sector,
    checked (one ParameterError line naming the field); read once per file version."""
    file = Path(path)
    if not file.is_file():
        _fail(path, "no such file")
    sectors = _read(str(file), file.stat().st_mtime)
    for i, (a0, a1, *_) in enumerate(sectors):
        for j, (b0, b1, *_) in enumerate(sectors[:i]):
            if _overlap(a0, a1, b0, b1):
                _fail(path, f"sectors {j + 1} and {i + 1} overlap")
    return sectors


def _overlap(a0, a1, b0, b1) -> bool:
    """Whether the arcs [a0, a1) and [b0, b1) (degrees) share more than a point."""
    probe = np.linspace(0.0, 360.0, 14401)[:-1] + 0.0125
    return bool(np.any(_inside(probe, a0, a1) & _inside(probe, b0, b1)))


def _inside(phi, start, end) -> np.ndarray:
    return np.mod(np.asarray(phi) - start, 360.0) < end - start


def rotated(law: np.ndarray, direction: float) -> np.ndarray:
    """(3, 6): a sector's law ((c_g), (c_l), (c_n)) as c_x, c_y, c_n against (u_x, u_y) in the sail's axes, for
    its grating vector at `direction` (rad) from x: u₁ = cos ψ u_x + sin ψ u_y, u₂ = −sin ψ u_x + cos ψ u_y,
    c_x = cos ψ c_g − sin ψ c_l, c_y = sin ψ c_g + cos ψ c_l (exact: the quadratic is fitted at 6 points)."""
    c, s = math.cos(direction), math.sin(direction)
    points = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0], [1.0, 1.0]])
    basis = monomials(points[:, 0], points[:, 1])
    local = monomials(c * points[:, 0] + s * points[:, 1], -s * points[:, 0] + c * points[:, 1]) @ np.asarray(law).T
    values = np.stack([c * local[:, 0] - s * local[:, 1], s * local[:, 0] + c * local[:, 1], local[:, 2]], axis=1)
    return np.linalg.solve(basis, values).T


def _area(polygon: np.ndarray) -> float:
    x, y = polygon[:, 0], polygon[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))) if len(polygon) >= 3 else 0.0


def _clip(polygon: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """The convex polygon cut to the half-plane normal·p ≥ 0 (Sutherland–Hodgman)."""
    out = []
    for a, b in zip(polygon, np.roll(polygon, -1, axis=0)):
        da, db = float(normal @ a), float(normal @ b)
        if da >= 0:
            out.append(a)
        if (da >= 0) != (db >= 0):
            out.append(a + (b - a) * da / (da - db))
    return np.array(out).reshape(-1, 2)


def _wedge_area(polygon: np.ndarray, start: float, end: float) -> float:
    """The area of a convex polygon (about the apex at the origin) within polar angles [start, end] (degrees)."""
    if end - start >= 360.0:
        return _area(polygon)
    if end - start > 180.0:
        return _wedge_area(polygon, start, start + 180.0) + _wedge_area(polygon, start + 180.0, end)
    a, b = math.radians(start), math.radians(end)
    inside = _clip(_clip(polygon, np.array([-math.sin(a), math.cos(a)])), np.array([math.sin(b), -math.cos(b)]))
    return _area(inside)


def shares(outline: np.ndarray, middle, sectors) -> np.ndarray:
    """(S,): the share of a tile's area (its convex polygon, (V, 2)) in each sector by polar angle about
    `middle`: the polygon cut by the sector's rays."""
    polygon = np.asarray(outline, float) - np.asarray(middle, float)
    return np.array([_wedge_area(polygon, start, end) for start, end, *_ in sectors]) / _area(polygon)


def tile_coefficients(p) -> np.ndarray:
    """(N, 18): c_x, c_y, c_n (6 coefficients each) of every tile of case p in its own axes (module docstring)."""
    from lightsail_mbs.model import planforms

    sectors = read(p.grating)
    mesh = planforms.mesh_of(p)
    middle = (0.5 * p.length, 0.5 * p.width)
    laws = np.array([rotated(np.array(law), math.radians(d)).ravel() for _, _, d, law in sectors])
    return np.array([shares(np.asarray(o, float), middle, sectors) @ laws for o in mesh.outlines])
