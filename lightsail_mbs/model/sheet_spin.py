"""The spinning sheet (model "sheet", case fields ``spin_rate`` Ω and ``spin_tilt`` β): its initial velocities,
the centrifugal loads of its spun state, and the closed forms its validations compare with.

Initial velocities
------------------
The sail starts in rigid rotation at ω = Ω (sin β, 0, cos β) about its centre of mass c_m (β = 0: the spin
about the sail's normal ẑ): tile k's centre moves at v_k = ω × (c_k − c_m) and every tile turns at ω. With
β ≠ 0 the angular velocity is off the sail's symmetry axis and the sail nutates (free_top_rates).

The spun state
--------------
In steady rotation at Ω_z = Ω cos β about ẑ every tile's centre moves on a circle, so its connectors must
supply the centripetal force −m Ω_z² ρ_k (ρ_k = the in-plane part of c_k − c_m). The connectors carry the
centrifugal membrane stress of the *flat* sheet (model.sheet_connectors.spun_prestrain): the rest offsets
that the in-plane problem of the flat grid needs against the loads m Ω_z² ρ_k (model.sheet_connectors.
equilibrium_offsets: of all corrections that balance them, the one of least complementary energy, i.e. the
compatible elastic stress state), added to the case's rest state, in the connectors' own axes, as the edge
tension's pre-stretch is. A flat sail therefore starts in equilibrium: rigid rotation is an exact solution
of the unlit flat sheet (the connectors' strains and forces are invariant under the rotation, and the
markers of each connector coincide, so the relative velocity its damping sees is zero). A defected sail
keeps the residual its shape had unspun, plus the pull of that stress towards flat: on a curved membrane
the stress has the transverse resultant σ_ij w_,ij per area (σ_ij = the membrane force), which no
centrifugal load (it lies in the plane) balances, so the defect is released into the Lamb & Southwell
oscillation below, as a defect under edge tension is (the paper's convention). The stretched positions of
the spun state differ from the initial ones by the strain ρΩ²R²/E (~1e-9 for the paper's film at
100 rad/s); they are not used (the rest lengths absorb them), which keeps the initial shape the case's.

*The exact spun equilibrium of a curved shape* (initial_equilibrium with spin): the residual of static_loads
plus the centrifugal loads C_k = (m Ω_z² ρ_k, −ω × J ω) in the initial shape is cleared by the same elastic
correction, so that the initial shape rests in the turning frame. On a doubly curved soft sheet this is not
a state to start from. Holding the shape needs the transverse resultant σ_ij w_,ij balanced, either by
bending moments (of order σ a₀: rest angles σ/(D k²) ≈ 3e5 times the defect's slopes for the paper's sail at
10 rad/s) or by a redistributed membrane stress; once a₀ exceeds a few film thicknesses (the moments'
complementary energy grows as a₀², the redistribution's does not depend on a₀) the least-energy
correction is the redistribution, and it compresses tiles (to 1.5 times the centre's centrifugal stress on
8 × 8 tiles, a₀ = 10 µm). Rigid tiles joined at their edge midpoints under a compression P per unit length
buckle at the tile scale: a zig-zag of tilts ±θ (tile centres still) shortens each tile's span by aθ²/2
and strains only the soft bending springs (2θ at each joint), so J θ̈ = (P a b − 4 D b/a) θ with
J = ρh a b · a²/12: a rate up to √(12 (P − 4D/a²)/(ρh a²)) ∝ Ω R/a, a mode of the tiles' tilts that grows
as Ω and faster with refinement, with no continuum limit (validation/spin_spectrum.md, part D).

The in-plane stress of a spinning free disc (plane stress, Poisson ratio ν_p; Timoshenko & Goodier §32)::

    σ_r = (3 + ν_p)/8 ρΩ²(R² − r²),   σ_θ = ρΩ²[(3 + ν_p)R² − (1 + 3ν_p)r²]/8,

from the equilibrium dσ_r/dr + (σ_r − σ_θ)/r + ρΩ²r = 0, compatibility, σ_r(R) = 0 and a finite centre.
The sheet's in-plane springs have ν_p = 0 (model.sheet_connectors): σ_r = 3ρΩ²(R² − r²)/8,
σ_θ = ρΩ²(3R² − r²)/8. edge_stresses reads the discrete sheet's normal stress across every shared edge.

The transverse vibrations of a spinning free membrane disc (Lamb & Southwell 1921, Proc. R. Soc. A 99, 272,
§2: the flexural rigidity negligible). In the frame turning with the disc a deflection w(r, θ, t) is driven
only by the spun state's membrane stresses (the centrifugal field lies in the plane, and the Coriolis force
of a velocity along ẑ is zero)::

    ρ ∂²w/∂t² = (1/r) ∂/∂r (r σ_r ∂w/∂r) + (σ_θ/r²) ∂²w/∂θ².

With w = W(x) cos nθ e^(iωt), x = r/R and the stresses above, dividing by ρΩ²R²/8::

    (3 + ν_p)[(1 − x²)W'' + (1/x − 3x)W' − n²W/x²] + (1 + 3ν_p) n² W + 8(ω/Ω)² W = 0.

x = 1 is a regular singular point (σ_r vanishes at the free rim): the solution finite there is a polynomial.
Substituting W = Σ_j a_j x^(n+2j): the lowest power gives the exponent n (regular at the centre), and x^m
has the coefficient −(3 + ν_p)(m² + 2m) + (1 + 3ν_p)n² + 8(ω/Ω)² times a_j (m = n + 2j) plus
(3 + ν_p)((m + 2)² − n²) a_(j+1), so the series stops at m = n + 2s exactly when

    (ω/Ω)² = [(3 + ν_p)(n + 2s)(n + 2s + 2) − (1 + 3ν_p) n²]/8,   s = 0, 1, 2, …

(ν_p = 0: (ω/Ω)² = [3(n + 2s)(n + 2s + 2) − n²]/8; n = 0, s = 0 is the translation along ẑ, ω = 0, and n = 1,
s = 0 the rigid tilt, ω = Ω) (membrane_disc_frequency).

A free symmetric top (I₁ = I₂ ≠ I₃) has constant ω₃ and, in its body axes, Euler's equations
I₁ω̇₁ = −(I₃ − I₁)ω₂ω₃, I₁ω̇₂ = (I₃ − I₁)ω₃ω₁: the transverse body rate ω₁ + iω₂ turns at
λ = (I₃ − I₁)ω₃/I₁ (a thin disc: I₃ = 2I₁, λ = ω₃), (free_top_rates).
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.model import planforms
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.model.sheet_grid import Tiles, flat_centres, quaternion_rotation, relative_displacement


def spin_vector(p: SailParameters) -> np.ndarray:
    """ω = Ω (sin β, 0, cos β) (rad/s): the sail's initial angular velocity."""
    return p.spin_rate * np.array([math.sin(p.spin_tilt), 0.0, math.cos(p.spin_tilt)])


def spin_centre(p: SailParameters, centres: np.ndarray) -> np.ndarray:
    """c_m (3,): the tiles' centre of mass."""
    masses = Tiles.of(p).masses
    return masses @ np.asarray(centres) / masses.sum()


def spin_velocities(p: SailParameters, centres: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(v (N, 3), ω (N, 3)): the tiles' centre velocities ω × (c_k − c_m) and global angular velocities ω
    of the sail's initial rigid rotation (module docstring); zeros when it does not spin."""
    omega = spin_vector(p)
    centres = np.asarray(centres, float)
    velocities = np.cross(omega, centres - spin_centre(p, centres))
    return velocities, np.tile(omega, (len(centres), 1))


def centrifugal_loads(p: SailParameters, centres: np.ndarray, quaternions: np.ndarray) -> np.ndarray:
    """(N, 6): the centrifugal force m Ω_z² ρ_k (global, N) and torque −ω × J ω (global, N m) of every tile in
    the steady spin ω = Ω_z ẑ (Ω_z = Ω cos β), static_loads' layout: the connectors rest in the spun state
    when their loads plus these vanish (module docstring)."""
    t = Tiles.of(p)
    spin = p.spin_rate * math.cos(p.spin_tilt)
    omega = np.array([0.0, 0.0, spin])
    centres = np.asarray(centres, float)
    radial = centres - spin_centre(p, centres)
    radial[:, 2] = 0.0
    out = np.zeros((len(centres), 6))
    out[:, :3] = t.masses[:, None] * spin**2 * radial
    rotations = quaternion_rotation(quaternions)
    inertia = np.einsum("kij,kjl,kml->kim", rotations, t.inertias, rotations)  # R J Rᵀ
    out[:, 3:] = -np.cross(omega, inertia @ omega)
    return out


def rigid_inertia(p: SailParameters, centres: np.ndarray, quaternions: np.ndarray) -> np.ndarray:
    """The sail's inertia tensor (3, 3) about its centre of mass as one rigid body (kg m²): the tiles' own
    (turned to their orientations) plus m(|r|² I − r rᵀ) of their centres."""
    t = Tiles.of(p)
    r = np.asarray(centres, float) - spin_centre(p, centres)
    rotations = quaternion_rotation(quaternions)
    own = np.einsum("kij,kjl,kml->im", rotations, t.inertias, rotations)
    parallel = np.einsum("k,kij->ij", t.masses, np.einsum("ki,ki->k", r, r)[:, None, None] * np.eye(3))
    return own + parallel - np.einsum("k,ki,kj->ij", t.masses, r, r)


def disc_stress(r, radius: float, density: float, spin_rate: float, poisson: float = 0.0):
    """(σ_r, σ_θ) (Pa) of a free disc of `radius` spinning at `spin_rate`, at radii r (module docstring)."""
    r = np.asarray(r, float)
    scale = density * spin_rate**2 / 8.0
    return (
        scale * (3.0 + poisson) * (radius**2 - r**2),
        scale * ((3.0 + poisson) * radius**2 - (1.0 + 3.0 * poisson) * r**2),
    )


def free_top_rates(t, axial: float, transverse: float, inertias: tuple[float, float]) -> np.ndarray:
    """Body rates (T, 3) of a free symmetric top (I₁ = I₂ = inertias[0], I₃ = inertias[1]) that starts at
    ω_b = (transverse, 0, axial): (ω⊥ cos λt, ω⊥ sin λt, ω₃), λ = (I₃ − I₁)ω₃/I₁ (module docstring)."""
    t = np.asarray(t, float)
    rate = (inertias[1] - inertias[0]) / inertias[0] * axial
    return np.stack(
        [transverse * np.cos(rate * t), transverse * np.sin(rate * t), np.full(t.shape, axial)],
        axis=-1,
    )


def edge_stresses(p: SailParameters, offset: np.ndarray, stiffness: np.ndarray):
    """(points (E, 2), directions (E, 2), σ (E,)) of the mesh's shared edges in the flat rest state: the
    connector's marker, the unit vector between the two centres and the normal stress across the edge,
    σ = −(K o)·d/(e h) (the spring pulls b towards a with the force −K o of its rest offset o, over the
    edge's cross-section e h). offset, stiffness: the connectors' (model.sheet_connectors.Connectors),
    whose first E rows are the shared edges."""
    m = planforms.mesh_of(p)
    count = len(m.pairs)
    force = (stiffness[:count, :2] * offset[:count, :2] * m.direction).sum(axis=1)
    return m.centres[m.pairs[:, 0]] + m.marker_a, m.direction, -force / (m.edge_length * p.thickness)


def tile_membrane_forces(p: SailParameters, conn, centres: np.ndarray, quaternions: np.ndarray) -> np.ndarray:
    """(N, 2): the principal membrane forces (N/m, tension positive, ascending) of every tile at rest in a
    state (centres, quaternions) with connectors conn (model.sheet_connectors.Connectors): the in-plane part
    of the virial (1/A) Σ_e r_e ⊗ f_e of the shared edges' spring forces f_e on the tile at its markers r_e
    (from its centre), symmetrised; A the tile's area (its mass over ρh)."""
    inner = conn.tile_a >= 0  # the shared edges (a support's force is left out)
    ta, tb = conn.tile_a[inner], conn.tile_b[inner]
    rotations = quaternion_rotation(quaternions)
    strain = relative_displacement(
        ta, tb, conn.local_a[inner], conn.local_b[inner], centres, quaternions, flat_centres(p), conn.gap[inner]
    )
    on_a = np.einsum("kij,kj->ki", rotations[ta], conn.stiffness[inner, :3] * (strain - conn.offset[inner, :3]))
    virial = np.zeros((len(centres), 3, 3))
    np.add.at(virial, ta, np.einsum("ki,kj->kij", np.einsum("kij,kj->ki", rotations[ta], conn.local_a[inner]), on_a))
    np.add.at(virial, tb, np.einsum("ki,kj->kij", np.einsum("kij,kj->ki", rotations[tb], conn.local_b[inner]), -on_a))
    area = Tiles.of(p).masses / (p.density * p.thickness)
    plane = virial[:, :2, :2] / area[:, None, None]
    return np.linalg.eigvalsh(0.5 * (plane + np.swapaxes(plane, 1, 2)))


def disc_stress_errors(p: SailParameters, offset: np.ndarray, stiffness: np.ndarray) -> tuple[int, float, float]:
    """(shared edges, σ_r error, σ_θ error) of a spinning free disc: the largest difference of the edge stresses
    (edge_stresses) from the closed form (disc_stress, ν_p = 0), over the radial edges (centre line within
    about 45° of the radius) and the circumferential ones, as fractions of the centre's stress 3ρΩ²R²/8."""
    points, direction, sigma = edge_stresses(p, offset, stiffness)
    radius = 0.5 * p.length
    rel = points - radius
    r = np.hypot(rel[:, 0], rel[:, 1])
    radial = np.abs(np.sum(rel * direction, axis=1)) > 0.7 * r
    exact_r, exact_t = disc_stress(r, radius, p.density, p.spin_rate)
    peak = 3.0 / 8.0 * p.density * p.spin_rate**2 * radius**2
    error_r = np.max(np.abs(sigma[radial] - exact_r[radial])) / peak
    error_t = np.max(np.abs(sigma[~radial] - exact_t[~radial])) / peak
    return len(sigma), float(error_r), float(error_t)


def membrane_disc_frequency(n: int, s: int, poisson: float = 0.0) -> float:
    """ω/Ω of the transverse mode with n nodal diameters and s nodal circles (counted inside the rim) of a free
    membrane disc spinning at Ω, in its turning frame (Lamb & Southwell; module docstring)."""
    m = n + 2 * s
    return math.sqrt(((3.0 + poisson) * m * (m + 2) - (1.0 + 3.0 * poisson) * n * n) / 8.0)
