"""Closed forms the sheet is checked against: Kirchhoff plates and tensioned membranes.

Kirchhoff plate of rigidity D under a uniform pressure q (Timoshenko & Woinowsky-Krieger, *Theory of
Plates and Shells*, 2nd ed., 1959):

* simply supported rectangle a × b (Navier's solution, Sec. 30, Eq. 133)::

      w(x, y) = (16 q/(π⁶ D)) Σ_{m,n odd} sin(mπx/a) sin(nπy/b) / (m n ((m/a)² + (n/b)²)²);

  square plate, centre: 0.00406 q a⁴/D (Table 8; the series converges to 0.0040624);
* clamped square plate (Sec. 44, Table 35): centre 0.00126 q a⁴/D; the converged value of the
  superposition series is 0.00126532 (Taylor & Govindjee, Int. J. Numer. Meth. Eng. 60, 2004).

Both depend on D alone: the plate's Poisson term ν ∫(w_xx w_yy − w_xy²) integrates to zero for w = 0
on the boundary, so the sheet's ν_p = 0 (model.sheet) does not enter these checks.

Free vibration (ρh the areal mass):

* simply supported plate: ω_mn = π² ((m/L)² + (n/W)²) √(D/(ρh));
* membrane under the isotropic tension T (N/m), fixed edges: ω_mn = π √(T/(ρh)) √((m/L)² + (n/W)²).

The paper's strip, per metre of width: E_cr,max (Eq. 8, theory.critical_modulus_max) and
T_cr,max/W = ½(2I₀/c)a₀ (Eq. 10), the scales of the sheet's stability results.
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.model import theory
from lightsail_mbs.model.parameters import SailParameters

CLAMPED_SQUARE_CENTRE = 0.00126532  # w D/(q a⁴) at the centre of the clamped square (converged series)


def bending_rigidity(p: SailParameters) -> float:
    """D = E h³/12 (ν_p = 0, model.sheet), N m."""
    return p.youngs_modulus * p.thickness**3 / 12.0


def navier_deflection(q: float, D: float, a: float, b: float, x: float, y: float, terms: int = 401) -> float:
    """Simply supported a × b plate under uniform pressure q: Navier's double series at (x, y) (m)."""
    m = np.arange(1, terms + 1, 2)[:, None]
    n = np.arange(1, terms + 1, 2)[None, :]
    s = np.sin(m * math.pi * x / a) * np.sin(n * math.pi * y / b) / (m * n * ((m / a) ** 2 + (n / b) ** 2) ** 2)
    return float(16.0 * q / (math.pi**6 * D) * s.sum())


def clamped_square_centre(q: float, D: float, a: float) -> float:
    """Centre deflection of the clamped square plate of side a under uniform pressure q (m)."""
    return CLAMPED_SQUARE_CENTRE * q * a**4 / D


def centre_deflection(p: SailParameters) -> float:
    """The Kirchhoff centre deflection of the supported square sheet p under its dead pressure (m)."""
    D = bending_rigidity(p)
    if p.boundary == "simply_supported":
        return navier_deflection(p.pressure, D, p.length, p.width, 0.5 * p.length, 0.5 * p.width)
    if p.boundary == "clamped" and p.length == p.width:
        return clamped_square_centre(p.pressure, D, p.length)
    raise ValueError("a closed form exists for simply supported plates and the clamped square only")


def plate_frequency(p: SailParameters, m: int, n: int) -> float:
    """ω_mn (rad/s) of the simply supported Kirchhoff plate."""
    return (
        math.pi**2
        * ((m / p.length) ** 2 + (n / p.width) ** 2)
        * math.sqrt(bending_rigidity(p) / (p.density * p.thickness))
    )


def membrane_frequency(p: SailParameters, m: int, n: int) -> float:
    """ω_mn (rad/s) of the membrane under the isotropic tension p.edge_tension, fixed edges."""
    return math.pi * math.sqrt(p.edge_tension / (p.density * p.thickness)) * math.hypot(m / p.length, n / p.width)


def lowest_modes(count: int, length: float = 1.0, width: float = 1.0) -> list[tuple[int, int]]:
    """The first `count` (m, n) by (m/L)² + (n/W)² (ties in (m, n) order; both of a degenerate pair kept)."""
    pairs = [(m, n) for m in range(1, 12) for n in range(1, 12)]
    pairs.sort(key=lambda mn: ((mn[0] / length) ** 2 + (mn[1] / width) ** 2, mn))
    return pairs[:count]


def critical_tension_per_width(p: SailParameters) -> float:
    """T_cr,max/W = ½(2I₀/c)a₀ (N/m): the paper's Eq. (10) per metre of edge."""
    return theory.critical_tension_max(p) / p.width
