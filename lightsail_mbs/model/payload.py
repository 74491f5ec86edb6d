"""A payload on a rigid stem from the sail's middle: where it sits and the composite slice it makes.

The payload is a body of mass m_p and centroidal inertia J_p at the end of a rigid, massless stem of
length d that leaves the sail's middle towards the laser (−ŷ, the beam travels along +ŷ), in the sail's
axes at t = 0. The stem is welded to slice j, the slice that holds the middle: slice (n − 1)/2 (its
centre) for n odd, slice n/2 − 1 (its right end) for n even, counting from 0. Its offset from slice j's
centre is fixed in slice j's axes (e_j, p_j) = ((cos θ_j, sin θ_j), (−sin θ_j, cos θ_j)) at the
initial angle θ_j(0), so on a billowed or defected sail the stem still points along −ŷ at t = 0, not
along slice j's own normal:

    ρ = ρ_e e_j + ρ_p p_j,   (ρ_e, ρ_p) = R(−θ_j(0)) (m − c_j(0) − d ŷ),

m the middle point and c_j the slice centre. Welded, slice j and the payload are one rigid body of mass
M = m + m_p with its centre of mass at ρ_c = (m_p/M) ρ from the slice centre and inertia about it

    J_c = J + J_p + m |ρ_c|² + m_p |ρ − ρ_c|² = J + J_p + (m m_p/M) |ρ|².

Forces: the light pushes slice j at its centre only (the payload sits in the sail's shadow); the frame
force −m_p g₀ ŷ acts on the payload, and g₀ is the acceleration of the whole craft,
g₀ = c_n(0) Ī L W/(c (M_sail + m_p)) (SailParameters.nominal_acceleration).
"""

from __future__ import annotations

from dataclasses import dataclass

from lightsail_mbs.model import shapes
from lightsail_mbs.model.parameters import SailParameters


@dataclass(frozen=True)
class Attachment:
    """Where the payload is welded and the composite slice it makes (SI units; module docstring)."""

    slice_index: int  # j
    along: float  # ρ_e: offset of the payload from slice j's centre along e_j
    across: float  # ρ_p: along p_j
    mass: float  # M = m + m_p
    inertia: float  # J_c, about the composite centre of mass
    centre_along: float  # ρ_c along e_j
    centre_across: float  # ρ_c along p_j


def attachment(p: SailParameters) -> Attachment | None:
    """The payload's attachment of case p, None without a payload."""
    if p.payload_mass <= 0.0:
        return None
    j, along, across = shapes.stem_offset(p)
    m, mp = p.slice_mass, p.payload_mass
    total = m + mp
    inertia = p.slice_inertia + p.payload_inertia + m * mp / total * (along**2 + across**2)
    return Attachment(j, float(along), float(across), total, float(inertia), mp / total * along, mp / total * across)


def position(p: SailParameters, x, y, theta):
    """The payload's position (x_p, y_p) from slice centres and angles (arrays (…, n)); None without one."""
    if p.payload_mass <= 0.0:
        return None
    return shapes.stem_end(p, x, y, theta)
