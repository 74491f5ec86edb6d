"""The rigid-body beam-riding criterion of a curved (billowed) disc with a payload in a round Gaussian beam,
spinning or not: the planar strip's criterion (:mod:`lightsail_mbs.analysis.beam_riding`) one dimension up.

**Body.** The sheet's billowed disc (model.sheet_shapes.cap): a disc of diameter L laid on a sphere of
radius R (> 0: concave towards the laser, centre of curvature C a distance R upstream of the apex), a flat
point at radius r going to the polar angle ψ = r/R from the apex (meridians kept), so the sail's mass and
its tiles' areas are spread as ρh R² ψ dψ dχ over ψ ≤ ψ_e = L/(2R); a mirror (each element's force
(2I/c) cos²ψ A along its normal); the payload m_p (inertia J_p) on the axis a distance d upstream of the
apex; the beam I₀ exp(−2ρ²/w²) along +z. Positions along the axis are measured from C (apex at +R,
payload at R − d, the sail's centre of mass at z_s = R⟨cos ψ⟩).

**Loads.** Every element's force lies along its radius, so the radiation force passes through C whatever
the pose (the strip's step 1). With C displaced laterally by u = x_C + i y_C and the axis tilted by
β = α_x + i α_y (α_x turns the x axis towards the beam, model.sheet_pose), to first order

    F_⊥ = −k u − F_e β,   F_z = F₀,
    k   = (8π R³/(c w²)) ∫ I(R sin ψ) cos²ψ sin³ψ · ψ/sin ψ dψ,
    F_e = (2π R²/c) [I(R sin ψ_e) cos²ψ_e sin ψ_e · ψ_e − ∫ I(R sin ψ) cos²ψ (sin ψ − ψ cos ψ) dψ],
    F₀  = (4π R²/c) ∫ I(R sin ψ) cos³ψ · ψ dψ,

over [0, ψ_e] (the factor ψ/sin ψ: the sheet's tiles keep their flat areas; on a true spherical shell it
is 1). k is the lateral force of the lit cap moved across the beam (∂I/∂x = −4x I/w², the azimuth average
⟨cos²χ⟩ = ½); F_e that of the lit window moved by the tilt (the rim at azimuth χ moves out by R β cos χ),
less that of the tiles' density on the sphere, ψ/sin ψ, turned with the body (0 on a true shell). The three
are held to central differences of the discrete sheet's own load (tests/analysis/test_ride3d.py: 0.05 %,
0.1 % and 0.07 % on 33 × 48 tiles).
With D = z_G − z_C (G downstream of C: D > 0) and u = U + D β (U: G's lateral position) the moment about G
is D (F_⊥ + F₀ β), as in the plane.

**Motion.** An axisymmetric body spinning at Ω about its axis, with transverse and axial inertias I_t, I_a
about G: for small tilts the transverse angular momentum I_t β̇ − i I_a Ω β turns with the spin, and

    M Ü = −k U − (kD + F_e) β,
    I_t β̈ − i I_a Ω β̇ = −kD U − (kD² + D(F_e − F₀)) β.

Modes e^(st): (M s² + k)(I_t s² − i I_a Ω s + kD² + D(F_e − F₀)) − kD(kD + F_e) = 0, a quartic whose four
roots describe every motion of the real 4-DOF system (U, β complex). **The sail rides (bounded oscillation
about the axis) iff every root has Re s ≤ 0**; undamped, that means every root on the imaginary axis. For
Ω = 0 the quartic factors as the planar λ² − Sλ + P (λ = −s²) in each plane: riding needs P > 0 ⟺ kD < 0,
i.e. (R > 0) D < 0, the centre of mass beyond the centre of curvature on the laser side — d > d* =
R + (M_s/m_p) R⟨cos ψ⟩ — and no flutter (S² ≥ 4P). Spin adds the gyroscopic term only: it leaves the
product of the four roots, −kD F₀/(M I_t), unchanged but not the roots themselves. Below d* each plane has one
unstable direction, two in all, and two can be stabilised gyroscopically (Kelvin–Tait–Chetaev): the quartic
finds the cap of tests/analysis/test_ride3d.py (R = 1 m, w = 0.6 m, m_p = M_s) stable at d = 0.9 d* from
Ω ≈ 300 rad/s on (growth 4.4/s at rest). The radiation load is circulatory and the model undamped; damping
is known to destroy gyroscopic stabilisation in conservative systems, and whether it does here is not
analysed.

**Literature.** Popova, Efendiev & Gabitov (Math. Meth. Appl. Sci. 40, 1346, 2017; abstract read):
the rigid spherical sail is stable when the payload is removed from the sail so that the distance from
the sail to the craft's centre of mass exceeds the sail's radius of curvature; stability does not require
spin; a flat sail is never stable. That is condition P > 0 above (d > d*) at Ω = 0; their abstract states no
flutter band, which the criterion here finds for wide beams (as the strip's), and no gyroscopic
stabilisation below d*, which the undamped quartic here finds at high spin.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.base.validation import check, finite
from lightsail_mbs.model.parameters import SailParameters


@dataclass
class CapCriterion:
    """The closed form of the module docstring for a case's billowed disc, a payload and a spin rate."""

    k: float  # N/m
    edge_force: float  # F_e (N)
    axial_force: float  # F₀ (N)
    D: float  # z_G − z_C (m)
    mass: float
    transverse_inertia: float
    axial_inertia: float
    spin_rate: float
    roots: np.ndarray  # the quartic's s (1/s)
    growth_rate: float  # max Re s (1/s)
    static_boundary: float  # d* (m): the stem that puts G on C
    stable: bool


def _moments(R: float, psi_e: float, inten) -> tuple[float, float, float, dict]:
    """k, F_e, F₀ and the sail's mass moments per ρh (m², m³, m⁴) of the cap (module docstring)."""
    k = quad(lambda u: inten(R * math.sin(u)) * math.cos(u) ** 2 * math.sin(u) ** 2 * u, 0.0, psi_e)[0]
    f0 = quad(lambda u: inten(R * math.sin(u)) * math.cos(u) ** 3 * u, 0.0, psi_e)[0]
    edge = inten(R * math.sin(psi_e)) * math.cos(psi_e) ** 2 * math.sin(psi_e) * psi_e
    edge -= quad(lambda u: inten(R * math.sin(u)) * math.cos(u) ** 2 * (math.sin(u) - u * math.cos(u)), 0.0, psi_e)[0]
    area = 2 * math.pi * R * R * quad(lambda u: u, 0.0, psi_e)[0]
    first = 2 * math.pi * R**3 * quad(lambda u: math.cos(u) * u, 0.0, psi_e)[0]
    axial = 2 * math.pi * R**4 * quad(lambda u: math.cos(u) ** 2 * u, 0.0, psi_e)[0]
    radial = 2 * math.pi * R**4 * quad(lambda u: math.sin(u) ** 2 * u, 0.0, psi_e)[0]
    return k, edge, f0, dict(area=area, first=first, axial=axial, radial=radial)


def cap_criterion(p: SailParameters, payload_mass: float, payload_distance: float, spin_rate: float | None = None):
    """The criterion for case p's disc on its cap (billow_radius finite, > 0 or < 0), its Gaussian beam and
    a mirror, with a payload m_p a distance d upstream of the apex, spinning at Ω (default the case's)."""
    R = float(p.billow_radius)
    check("billow_radius", R, math.isfinite(R), "finite (the criterion is for a curved sail; flat never rides)")
    check("beam_waist", p.beam_waist, math.isfinite(p.beam_waist), "finite (a Gaussian beam)")
    mp, d = finite("payload_mass", payload_mass), finite("payload_distance", payload_distance)
    check("payload_mass", mp, mp >= 0, "≥ 0")
    spin = p.spin_rate if spin_rate is None else finite("spin_rate", spin_rate)
    a, w = abs(R), p.beam_waist
    psi_e = p.length / (2 * a)

    def inten(x):
        return p.intensity * math.exp(-2.0 * (x / w) ** 2)

    k_int, edge, f0_int, m = _moments(a, psi_e, inten)
    k = 8 * math.pi * R * a * a / (SPEED_OF_LIGHT * w * w) * k_int
    Fe = 2 * math.pi * a * a / SPEED_OF_LIGHT * edge
    F0 = 4 * math.pi * a * a / SPEED_OF_LIGHT * f0_int
    rho_h = p.density * p.thickness
    Ms = rho_h * m["area"]
    M = Ms + mp
    z_s = math.copysign(1.0, R) * m["first"] / m["area"]  # the sail's centre of mass from C, towards the apex
    z_p = R - d
    z_g = (Ms * z_s + mp * z_p) / M
    # about C: ∫ (z² + x²) dm = ρh(axial + radial/2); then the parallel-axis shift to G
    transverse = rho_h * (m["axial"] + 0.5 * m["radial"]) + mp * z_p**2 + p.payload_inertia - M * z_g**2
    axial = rho_h * m["radial"] + p.payload_inertia
    D = z_g
    e = k * D * D + D * (Fe - F0)
    quartic = np.polymul([M, 0.0, k], [transverse, -1j * axial * spin, e])
    quartic[-1] -= k * D * (k * D + Fe)
    roots = np.roots(quartic)
    growth = float(np.max(roots.real))
    scale = float(np.max(np.abs(roots)))
    d_star = R + Ms / mp * z_s if mp > 0 else math.inf
    return CapCriterion(k, Fe, F0, D, M, transverse, axial, spin, roots, growth, d_star, growth <= 1e-9 * scale)


def stem_boundaries(p: SailParameters, payload_mass: float, d_min: float, d_max: float, samples: int = 300) -> list:
    """The stems d in [d_min, d_max] where the criterion changes (stable ↔ unstable), as (d, stable above),
    by bisection of the growth rate's sign between samples (log-spaced)."""
    ds = np.geomspace(d_min, d_max, samples)

    def margin(d):
        c = cap_criterion(p, payload_mass, d)
        return c.growth_rate - 1e-9 * float(np.max(np.abs(c.roots)))

    values = np.array([margin(d) for d in ds])
    out = []
    for i in np.nonzero((values[1:] > 0) != (values[:-1] > 0))[0]:
        d = brentq(margin, ds[i], ds[i + 1], xtol=1e-10 * ds[i + 1])
        out.append((d, bool(values[i + 1] <= 0)))
    return out
