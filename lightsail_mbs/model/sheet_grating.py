"""Gratings on a sheet's tiles: in-plane optical pressures, by sectors of the sail (the case field ``grating``).

**The law.** A tile of area A carries a grating whose grating vector ĝ (across its lines) lies in the tile's
plane and turns with it; with its normal n̂ it spans the grating's frame (ĝ, n̂ × ĝ, n̂). The beam travels along
b̂ = ẑ with the local intensity I; its direction cosines in that frame are

    u₁ = ĝ·b̂,    u₂ = (n̂ × ĝ)·b̂,    cos θ = n̂·b̂

(u₁ the sine of the incidence angle's part across the lines, u₂ along them). The grating adds to the film's
specular facet law (model.loads, the radiation term) the force

    δF = (I A/c) cos θ [c_g(u₁, u₂) ĝ + c_l(u₁, u₂) (n̂ × ĝ) + c_n(u₁, u₂) n̂],

its pressures per unit lit area (cos θ A is the projected area, as in FlexSailSim's tables), each a polynomial
of degree d in (u₁, u₂), its monomials in graded order (:func:`monomials`):

    c(u₁, u₂) = c₀ + c₁ u₁ + c₂ u₂ + c₁₁ u₁² + c₁₂ u₁u₂ + c₂₂ u₂² + c₁₁₁ u₁³ + c₁₁₂ u₁²u₂ + … + c₂…₂ u₂^d,

(d + 1)(d + 2)/2 coefficients: d = 2 is the value, slopes and curvatures at normal incidence; a higher d fits a
table over wider angles. A grating whose table gives its whole normal pressure c_z carries c_n = c_z − c_n,film
(the film's (2R + α) cos θ to the law's degree: c̄ − c̄ (u₁² + u₂²)/2 at d = 2), so that the tile's normal
pressure is the table's. With every coefficient 0 the load is the film's, to the bit.

**Sectors.** A layout (a TOML file, :func:`read`) lists sectors of the sail by polar angle φ about the sail's middle
(L/2, W/2), φ from +x towards +y: each ``[[sector]]`` has ``from`` and ``to`` (degrees, to − from ≤ 360),
``direction`` (the grating vector's angle from the sail's x axis, degrees, in the sail's own axes, which are the
tiles' at rest) and the three coefficient lists ``along`` (c_g), ``across`` (c_l) and ``normal`` (c_n), each
(d + 1)(d + 2)/2 numbers in the order above for some degree d ≤ MAX_DEGREE (a list left out: zeros; a shorter list is
the same polynomial with zeros above its degree: the layout's degree is its longest list's). Sectors may not overlap; a
tile outside every sector is plain film. A tile that straddles sectors carries their laws weighted by the shares of
its area in each (:func:`tile_coefficients`: the tile's polygon cut by the sectors' rays), rotated into the tile's
own axes (x̂_b, ŷ_b) — the rotated law is again a polynomial of degree d in (u_x, u_y) = (R x̂·ẑ, R ŷ·ẑ), so each
tile carries 3 (d + 1)(d + 2)/2 numbers (18 at d = 2): c_x, c_y, c_n in its axes.
"""

from __future__ import annotations

import math
from functools import lru_cache
from pathlib import Path

import numpy as np

from lightsail_mbs.base.validation import ParameterError

MAX_DEGREE = 12
LISTS = ("along", "across", "normal")
KEYS = {"from", "to", "direction", *LISTS, "name"}


def count(degree: int) -> int:
    """The number of coefficients of a law of this degree, (d + 1)(d + 2)/2."""
    return (degree + 1) * (degree + 2) // 2


def degree_of(terms: int) -> int:
    """The degree d of a law of `terms` coefficients (a triangular number: count(d) = terms)."""
    return int(round((math.sqrt(8 * terms + 1) - 3) / 2))


def powers(degree: int) -> list[tuple[int, int]]:
    """The exponents (a, b) of u₁^a u₂^b in graded order: 1, u₁, u₂, u₁², u₁u₂, u₂², u₁³, …"""
    return [(k - j, j) for k in range(degree + 1) for j in range(k + 1)]


def monomials(u1, u2, degree: int = 2) -> np.ndarray:
    """(…, count(degree)): the monomials u₁^a u₂^b in graded order (:func:`powers`), each row of degree k the
    row of degree k − 1 times u₁, its last times u₂ (as the compiled kernel forms them)."""
    u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
    rows = [[np.ones_like(u1)]]
    for _ in range(degree):
        rows.append([m * u1 for m in rows[-1]] + [rows[-1][-1] * u2])
    return np.stack([m for row in rows for m in row], axis=-1)


def _fail(path, what: str):
    raise ParameterError(
        f"grating={str(path)!r} is invalid: {what} (a TOML file of [[sector]] tables with from, to, direction "
        f"in degrees and along, across, normal: (d + 1)(d + 2)/2 numbers each, d ≤ {MAX_DEGREE}; "
        f"model/sheet_grating.py)"
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
            values = s.get(key, [0.0])
            sizes = [count(d) for d in range(MAX_DEGREE + 1)]
            numbers = isinstance(values, list) and all(isinstance(v, (int, float)) for v in values)
            if not numbers or len(values) not in sizes or not all(math.isfinite(v) for v in values):
                _fail(path, f"sector {i + 1}: {key} must be (d + 1)(d + 2)/2 finite numbers ({sizes[1:4]}, …)")
            laws.append([float(v) for v in values])
        sectors.append((start, end, direction, laws))
    terms = max(len(law) for *_, laws in sectors for law in laws)
    padded = [(*head, tuple(tuple(law + [0.0] * (terms - len(law))) for law in laws)) for *head, laws in sectors]
    return tuple(padded)


def read(path: str) -> tuple:
    """The sectors of a layout file: ((from, to, direction) in degrees, ((c_g), (c_l), (c_n))) per sector, every
    list as long as the layout's longest (zeros above a list's own degree), checked (one ParameterError line
    naming the field); read once per file version."""
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
    """(3, T): a sector's law ((c_g), (c_l), (c_n), T coefficients each) as c_x, c_y, c_n against (u_x, u_y) in
    the sail's axes, for its grating vector at `direction` (rad) from x: u₁ = cos ψ u_x + sin ψ u_y,
    u₂ = −sin ψ u_x + cos ψ u_y, c_x = cos ψ c_g − sin ψ c_l, c_y = sin ψ c_g + cos ψ c_l; each monomial
    u₁^a u₂^b multiplied out in (u_x, u_y) (exact but for rounding)."""
    law = np.asarray(law, float)
    degree = degree_of(law.shape[1])
    c, s = math.cos(direction), math.sin(direction)
    index = {pair: i for i, pair in enumerate(powers(degree))}
    change = np.zeros((law.shape[1], law.shape[1]))  # row: a monomial of (u₁, u₂); columns: its (u_x, u_y) form
    for row, (a, b) in enumerate(powers(degree)):
        poly = {(0, 0): 1.0}
        for alpha, beta in [(c, s)] * a + [(-s, c)] * b:  # times (α u_x + β u_y)
            product: dict = {}
            for (i, j), v in poly.items():
                product[(i + 1, j)] = product.get((i + 1, j), 0.0) + alpha * v
                product[(i, j + 1)] = product.get((i, j + 1), 0.0) + beta * v
            poly = product
        for pair, v in poly.items():
            change[row, index[pair]] += v
    local = law @ change
    return np.stack([c * local[0] - s * local[1], s * local[0] + c * local[1], local[2]])


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
    """(N, 3T): c_x, c_y, c_n (T = (d + 1)(d + 2)/2 coefficients each, d the layout's degree) of every tile of
    case p in its own axes (module docstring)."""
    from lightsail_mbs.model import planforms

    sectors = read(p.grating)
    mesh = planforms.mesh_of(p)
    middle = (0.5 * p.length, 0.5 * p.width)
    laws = np.array([rotated(np.array(law), math.radians(d)).ravel() for _, _, d, law in sectors])
    return np.array([shares(np.asarray(o, float), middle, sectors) @ laws for o in mesh.outlines])
