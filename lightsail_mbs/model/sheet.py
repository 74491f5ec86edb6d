"""The sail as a sheet: n × ny rigid tiles moving in 3-D, joined along their shared edges.

A case with ``SailParameters(model="sheet", n=nx, ny=ny, ...)``; this module holds its geometry,
initial shapes and defects, edge connections and loads, shared by both sheet solvers
(:mod:`lightsail_mbs.solvers.exudyn.sheet`, :mod:`lightsail_mbs.solvers.reduced.sheet`).

Geometry
--------
The flat sail spans 0 ≤ x ≤ L, 0 ≤ y ≤ W in the plane z = 0; the beam travels along +z. It is cut
into nx × ny rectangular tiles of a × b (a = L/nx, b = W/ny, nx = params.n). Tile (i, j) (flat index
k = j·nx + i) has its centre at x_i = (i + ½)a, y_j = (j + ½)b in the flat state, mass m = ρhab and
the centroidal inertia of a thin cuboid, diag(m(b² + h²), m(a² + h²), m(a² + b²))/12.

Edge connections (one per shared edge, at the edge midpoint)
-----------------------------------------------------------
Neighbours are joined at the midpoint of their shared edge by a linear 6-DOF spring acting on the
relative displacement δ of the two edge-midpoint markers and on the relative rotation φ (Tait–Bryan
xyz angles of R_Aᵀ R_B), both resolved in the frame of the first tile A (Exudyn's
``ObjectConnectorRigidBodySpringDamper``, non-intrinsic formulation; the second solver implements the
same law). For an edge of length e between tile centres a span s apart (x-edge: e = b, s = a; y-edge:
e = a, s = b), with the membrane modulus E_m (default E) and the plate bending rigidity D, the diagonal
stiffness in tile A's frame is, for an x-edge (components x, y, z, about x, about y, about z)

    k_∥ = E_m h e/s (both in-plane directions),   k_⊥ = κ (E_m/2) h e/s (κ = 5/6),
    k_twist = k_bend = D e/s,   k_drill = D_m e/s  (D_m = E_m h³/12),

and the same with x and y exchanged for a y-edge. Derivation (patch tests: tiles placed on a surface
w(x, y), turned to its slope; the energy per tile compared with the continuum):

* Bending, w = ½κx²: the x-edge midpoints of neighbours coincide exactly (no transverse-shear strain)
  and their relative rotation about y is κa: energy per x-edge ½(D b/a)(κa)² = ½Dκ² ab, the plate's
  energy of one tile. Same for y.
* Twist, w = κxy: the midpoints again coincide; the relative rotation about the edge normal is κa
  (x-edges) and κb (y-edges): ½(D b/a)(κa)² + ½(D a/b)(κb)² = Dκ² ab, the plate's twisting energy
  D(1 − ν_p)·2·½ w_xy² ab for ν_p = 0.
* Poisson ratio: a spring on one relative-rotation component cannot produce the plate's
  2ν_p w_xx w_yy (it couples curvatures measured across different edges), and
  w_xx² + w_yy² + 2(1 − ν_p) w_xy² is invariant under rotations of the axes (isotropic) only for
  ν_p = 0, where it is tr(H²) = |∇∇w|². So the edge-spring grid *is* the isotropic Kirchhoff plate with
  ν_p = 0 exactly: D = E h³/12, twist stiffness D(1 − ν_p) = D. Any other D can be entered through E,
  but the anticlastic coupling of ν_p ≠ 0 is absent. For simply supported and clamped plates the ν_p
  term integrates to zero (a null Lagrangian for w = 0 on the boundary), so their deflections and
  frequencies test D and the twist stiffness, not ν_p.
* Membrane (ν = 0, G = E_m/2): uniform stretch ε stores ½(E_m h b/a)(εa)² = ½E_m h ε² ab per tile;
  pure shear γ is shared by x- and y-edges (relative tangential displacement γa/2, γb/2), so the
  tangential spring is 2G h e/s = E_m h e/s. In-plane bending of the sheet is carried by the normal
  springs of its columns (the within-tile part ∫ y² dy of a column is left out: O(1/ny²) of the
  sheet's in-plane bending stiffness).
* Drilling (relative rotation about the normal): tiles joined at edge midpoints leave one in-plane
  mechanism free, the checkerboard of counter-rotating tiles (each shared midpoint moves alike on
  both tiles). The drilling spring only suppresses it, at the plate's own scale D_m e/s. It must not
  be stiffer: the connector applies the moment A₀ K φ of the Tait–Bryan angles φ of R_Aᵀ R_B, which is
  not the gradient T(φ)ᵀ K φ of a potential; tilts about x and y make a drilling angle of second order
  (the surface's angular defect), and the difference couples in-plane rotation to tilt with a
  circulatory stiffness ~ k_drill |θ|. With k_drill = E_m h e³/(12 s) (the within-tile in-plane bending,
  (e/h)² ≈ 1e9 times larger) that coupling was ~1e6 times the bending stiffness of the paper's sail
  and made a doubly curved sheet with E_m = E diverge at ~17/s, unlit as well as lit (docs: sheet).
* Transverse shear (Mindlin, κ = 5/6) is a stiff penalty that keeps edge midpoints together: thin
  plates are Kirchhoff plates (k_⊥/(D/s²) ≈ 12 s²/h², 3e10 for the paper's sail).

Chain limit: with a defect uniform across the width and free side edges, every column of tiles moves
as one, the y-edge springs are not strained at all (δ = b(I − R_y)ŷ = 0 for rotations about y), the
ny x-edge springs between two columns add up to the chain's k_T = Σ D b/a = E (W h³/12)/l (paper
Sec. III.B), and the stiff translational springs stand in for the chain's hinges. So 1-D defects use
the chain's own exact-chord construction (:mod:`lightsail_mbs.model.shapes`).

Boundaries
----------
"free" (the sail), "simply_supported" and "clamped" (plate and membrane validations): each boundary
tile is joined to the ground at its outer edge midpoint by the same kind of connector over half a
span (all stiffnesses doubled); a simple support has no bending spring (the twist spring stays: w = 0
along the edge, so the half cell between centre and edge twists with the plate).

Reference state and pre-stress
------------------------------
Bending and twist springs are at rest flat (bending_reference="flat", as in the paper's chain: the
defect is an elastically loaded initial shape) or in the initial shape ("initial": a stress-free,
manufactured defect). The translational springs are at rest in the initial shape
(membrane_reference="initial": a doubly curved defect laid down free of membrane stress; for a 1-D
defect nothing changes) or flat ("flat"). The initial rest state is realised by the marker positions,
not by an offset in the spring law: B's marker is moved by the (~1e-10 m) mismatch of the two edge
midpoints in the initial shape (Connectors.gap). The connector law applies +f at p_a and −f at p_b;
with markers δ₀ apart at rest, an offset δ₀ in the law would make that pair a couple δ₀ × f that no
potential produces (a circulatory stiffness ∝ E_m |δ₀|). With both at "initial" the unlit initial
shape is an exact equilibrium. With bending at rest flat, a doubly curved defect is not: flattening it
strains the membrane (Gauss's theorema egregium), so the bending springs load the membrane, and a stiff
membrane holds the shell in shape (docs: sheet, the membrane modulus). Rest states are computed from
small quantities only (tile displacements u, and R − I from the quaternions' small components), so the
initial springs are at rest to ~1e-21 m.
An edge tension T (N per metre of edge) pre-stretches every connector so that the flat sheet carries
the isotropic membrane force T (an exact equilibrium), and on a free boundary acts as a follower force
T·e at each boundary tile's outer edge midpoint along the tile's own outward in-plane axis (the
chain's TnT end tension, one dimension up). On a supported boundary the ground connectors carry it.

Membrane damping
----------------
The in-plane component of the load, switched on at t = 0, rings the in-plane lattice
(ω ~ 1e4–1e5 rad/s for the paper's sail), which neither solver should have to resolve. The stiff
springs (in-plane, transverse shear, drilling) get the damping β_m k with β_m = 2/ω_max by default
(critical for the highest in-plane lattice mode, ω_max² = 4(k_x + k_y)/m); Kirchhoff bending of a
1-D defect does not strain those springs, so it is not damped by them (the chain-limit failure time
moves by < 1e-8 relative when β_m is ×10). A doubly curved sheet is different: its bending strains
the membrane (docs: sheet), so β_m is recorded with every case and its effect measured there.

Loads (:func:`lightsail_mbs.model.loads.facet_forces`)
-------------------------------------------------------
Each tile carries at its centre the net force of the one facet law of every solver: radiation
(I ab/c) cos θ [2R cos θ n + α ẑ] with n = R_tile ẑ, cos θ = n_z, minus the frame force
(2R + α) Ī ab/c ẑ (the frame accelerates with the flat sail at g₀ = (2R + α)Ī/(cρh)), their
cancellation done analytically from the normal's small components (n_x, n_y); I is uniform or the
round Gaussian at the tile centre. A dead pressure p (params.pressure, the plate validations) adds
p·ab ẑ.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import loads, shapes
from lightsail_mbs.model.parameters import SailParameters

SHEAR_CORRECTION = 5.0 / 6.0  # Mindlin's κ on the transverse-shear penalty
PERTURBATION_SEED = 20240917  # the seeded tile offsets of a perturbed start (solvers' perturbation option)


def require_sheet(p: SailParameters) -> None:
    if p.model != "sheet":
        raise ParameterError(f"model={p.model!r} is invalid here: allowed 'sheet'")


@dataclass(frozen=True)
class Tiles:
    """Derived quantities of a sheet case.

    Attributes
    ----------
    nx, ny : int
        Tiles along L and across W.
    a, b : float
        Tile length L/nx and width W/ny (m).
    mass : float
        m = ρ h a b (kg).
    inertia : ndarray (3,)
        Principal centroidal inertia of the thin cuboid tile (kg m²).
    bending_rigidity : float
        D = E h³/12 (ν_p = 0; 0 with bending off) (N m).
    membrane_modulus : float
        E_m of the in-plane springs (Pa).
    membrane_damping : float
        β_m on the stiff springs (s).
    """

    nx: int
    ny: int
    a: float
    b: float
    mass: float
    inertia: np.ndarray
    bending_rigidity: float
    membrane_modulus: float
    membrane_damping: float

    @classmethod
    def of(cls, p: SailParameters) -> Tiles:
        require_sheet(p)
        a, b, h = p.length / p.n, p.width / p.ny, p.thickness
        m = p.density * h * a * b
        em = float(p.youngs_modulus if p.membrane_modulus is None else p.membrane_modulus)
        if p.membrane_damping is None:
            omega_max = math.sqrt(4.0 * em * h * (b / a + a / b) / m)
            beta = 2.0 / omega_max
        else:
            beta = float(p.membrane_damping)
        return cls(
            nx=p.n,
            ny=p.ny,
            a=a,
            b=b,
            mass=m,
            inertia=m / 12.0 * np.array([b * b + h * h, a * a + h * h, a * a + b * b]),
            bending_rigidity=p.youngs_modulus * h**3 / 12.0 if p.bending else 0.0,
            membrane_modulus=em,
            membrane_damping=beta,
        )

    @property
    def count(self) -> int:
        return self.nx * self.ny

    @property
    def area(self) -> float:
        return self.a * self.b


def flat_centres(p: SailParameters) -> np.ndarray:
    """(N, 3) tile centres of the flat sail, k = j·nx + i (m)."""
    i, j = np.meshgrid(np.arange(p.n), np.arange(p.ny), indexing="xy")
    x = (i.ravel() + 0.5) * p.length / p.n
    y = (j.ravel() + 0.5) * p.width / p.ny
    return np.column_stack([x, y, np.zeros_like(x)])


# ---- rotations ---------------------------------------------------------------------------------
def rotation_xyz(angles: np.ndarray) -> np.ndarray:
    """R = R_x(φ₀) R_y(φ₁) R_z(φ₂) (Exudyn's Tait–Bryan convention) of (..., 3) angles, (..., 3, 3)."""
    a = np.asarray(angles, float)
    c0, c1, c2 = np.cos(a[..., 0]), np.cos(a[..., 1]), np.cos(a[..., 2])
    s0, s1, s2 = np.sin(a[..., 0]), np.sin(a[..., 1]), np.sin(a[..., 2])
    R = np.empty(a.shape[:-1] + (3, 3))
    R[..., 0, 0] = c1 * c2
    R[..., 0, 1] = -c1 * s2
    R[..., 0, 2] = s1
    R[..., 1, 0] = c0 * s2 + s0 * s1 * c2
    R[..., 1, 1] = c0 * c2 - s0 * s1 * s2
    R[..., 1, 2] = -s0 * c1
    R[..., 2, 0] = s0 * s2 - c0 * s1 * c2
    R[..., 2, 1] = s0 * c2 + c0 * s1 * s2
    R[..., 2, 2] = c0 * c1
    return R


def angles_xyz(R: np.ndarray) -> np.ndarray:
    """The xyz angles of rotation matrices (..., 3, 3), the inverse of rotation_xyz away from φ₁ = ±π/2."""
    R = np.asarray(R, float)
    phi1 = np.arctan2(R[..., 0, 2], np.hypot(R[..., 1, 2], R[..., 2, 2]))
    phi0 = np.arctan2(-R[..., 1, 2], R[..., 2, 2])
    phi2 = np.arctan2(-R[..., 0, 1], R[..., 0, 0])
    return np.stack([phi0, phi1, phi2], axis=-1)


def normal_xyz(angles: np.ndarray) -> np.ndarray:
    """Tile normal n = R ẑ = (sin φ₁, −sin φ₀ cos φ₁, cos φ₀ cos φ₁) of (..., 3) xyz angles."""
    a = np.asarray(angles, float)
    c1 = np.cos(a[..., 1])
    return np.stack([np.sin(a[..., 1]), -np.sin(a[..., 0]) * c1, np.cos(a[..., 0]) * c1], axis=-1)


def tilt_rotation(normal: np.ndarray) -> np.ndarray:
    """(..., 3, 3): the rotation about the axis ẑ × n that takes ẑ to the unit normal n (no twist).

    Rodrigues' formula with K built from the unnormalised axis ẑ × n (|ẑ × n| = sin θ):
    R = I + K + K²/(1 + cos θ)."""
    n = np.asarray(normal, float)
    n = n / np.linalg.norm(n, axis=-1, keepdims=True)
    axis = np.stack([-n[..., 1], n[..., 0], np.zeros_like(n[..., 0])], axis=-1)
    K = np.zeros(n.shape[:-1] + (3, 3))
    K[..., 0, 1], K[..., 0, 2] = -axis[..., 2], axis[..., 1]
    K[..., 1, 0], K[..., 1, 2] = axis[..., 2], -axis[..., 0]
    K[..., 2, 0], K[..., 2, 1] = -axis[..., 1], axis[..., 0]
    return np.eye(3) + K + K @ K / (1.0 + n[..., 2])[..., None, None]


def rotation_minus_identity(q: np.ndarray) -> np.ndarray:
    """R − I of the rotations of (not necessarily unit) quaternions q (..., 4), scalar first, from small
    products only (accurate to the ulps of its own entries, not of 1), (..., 3, 3)."""
    q = np.asarray(q, float)
    q0, q1, q2, q3 = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    n = 2.0 / np.sum(q * q, axis=-1)
    out = np.empty(q.shape[:-1] + (3, 3))
    out[..., 0, 0] = -(q2 * q2 + q3 * q3) * n
    out[..., 0, 1] = (q1 * q2 - q0 * q3) * n
    out[..., 0, 2] = (q1 * q3 + q0 * q2) * n
    out[..., 1, 0] = (q1 * q2 + q0 * q3) * n
    out[..., 1, 1] = -(q1 * q1 + q3 * q3) * n
    out[..., 1, 2] = (q2 * q3 - q0 * q1) * n
    out[..., 2, 0] = (q1 * q3 - q0 * q2) * n
    out[..., 2, 1] = (q2 * q3 + q0 * q1) * n
    out[..., 2, 2] = -(q1 * q1 + q2 * q2) * n
    return out


def quaternion_rotation(q: np.ndarray) -> np.ndarray:
    """The rotation matrices (..., 3, 3) of quaternions q (..., 4), scalar first."""
    return np.eye(3) + rotation_minus_identity(q)


def tilt_quaternion(normal: np.ndarray) -> np.ndarray:
    """(..., 4) unit quaternions of the twist-free rotations taking ẑ to the (not necessarily unit) normals:
    q ∝ (|n| + n_z, −n_y, n_x, 0), the half-angle form of the rotation about ẑ × n."""
    n = np.asarray(normal, float)
    q = np.stack([np.linalg.norm(n, axis=-1) + n[..., 2], -n[..., 1], n[..., 0], np.zeros_like(n[..., 0])], axis=-1)
    return q / np.linalg.norm(q, axis=-1, keepdims=True)


# ---- defects -------------------------------------------------------------------------------------
def multimode_coefficients(p: SailParameters):
    """Seeded random 2-D defect w = Σ_kl a_kl sin(2πν_k x/L + φ_kl) sin(2πν_l y/W + ψ_kl), ν_k = k/2.

    k, l = 1…K (K = defect_mode_count); a_kl = (ν_k² + ν_l²)^(−β/2) |g_kl| with g standard normal
    (β = defect_spectrum), phases uniform in [0, 2π), from numpy's default generator seeded with
    defect_seed; scaled so that the RMS of w over the sail is a₀/2, the RMS of the doubly sinusoidal
    defect of amplitude a₀ (as the chain's multi-mode defect has the RMS of the paper's sine).
    Returns (ν (K,), a (K, K), φ (K, K), ψ (K, K))."""
    rng = np.random.default_rng(p.defect_seed)
    K = p.defect_mode_count
    nu = 0.5 * np.arange(1, K + 1)
    a = (nu[:, None] ** 2 + nu[None, :] ** 2) ** (-0.5 * p.defect_spectrum) * np.abs(rng.standard_normal((K, K)))
    phx = rng.uniform(0, 2 * np.pi, (K, K))
    phy = rng.uniform(0, 2 * np.pi, (K, K))
    xs = np.linspace(0, p.length, 257)
    ys = np.linspace(0, p.width, 257)
    w = _multimode(p, (nu, a, phx, phy), xs[:, None], ys[None, :])
    rms = math.sqrt(np.trapezoid(np.trapezoid(w * w, ys, axis=1), xs) / (p.length * p.width))
    return nu, a * (0.5 * p.defect_amplitude / rms), phx, phy


def _multimode(p, coefficients, x, y, derivative=None):
    nu, a, phx, phy = coefficients
    kx = 2 * np.pi * nu / p.length
    ky = 2 * np.pi * nu / p.width
    x = np.asarray(x, float)[..., None, None]
    y = np.asarray(y, float)[..., None, None]
    ax = kx[:, None] * x + phx
    ay = ky[None, :] * y + phy
    if derivative is None:
        terms = np.sin(ax) * np.sin(ay)
    elif derivative == "x":
        terms = kx[:, None] * np.cos(ax) * np.sin(ay)
    else:
        terms = ky[None, :] * np.sin(ax) * np.cos(ay)
    return (a * terms).sum(axis=(-1, -2))


def defect_surface(p: SailParameters):
    """(w, w_x, w_y) of a 2-D defect (defect_mode_y set) as functions of (x, y): the doubly sinusoidal
    w = a₀ sin(2πν x/L) sin(2πν_y y/W), or with defect_seed the seeded 2-D multi-mode defect."""
    if p.defect_seed is not None:
        coefficients = multimode_coefficients(p)
        return (
            lambda x, y: _multimode(p, coefficients, x, y),
            lambda x, y: _multimode(p, coefficients, x, y, "x"),
            lambda x, y: _multimode(p, coefficients, x, y, "y"),
        )
    kx = 2 * np.pi * p.defect_mode / p.length
    ky = 2 * np.pi * p.defect_mode_y / p.width
    a0 = p.defect_amplitude
    return (
        lambda x, y: a0 * np.sin(kx * x) * np.sin(ky * y),
        lambda x, y: a0 * kx * np.cos(kx * x) * np.sin(ky * y),
        lambda x, y: a0 * ky * np.sin(kx * x) * np.cos(ky * y),
    )


def initial_state(p: SailParameters) -> tuple[np.ndarray, np.ndarray]:
    """Tile centres (N, 3) and rotation matrices (N, 3, 3) of the initial (defect) shape, at rest
    (initial_quaternions, whose quaternions carry the small rotations without round-off of 1)."""
    centres, q = initial_quaternions(p)
    return centres, quaternion_rotation(q)


def initial_quaternions(p: SailParameters) -> tuple[np.ndarray, np.ndarray]:
    """Tile centres (N, 3) and unit quaternions (N, 4, scalar first) of the initial (defect) shape.

    1-D defects (defect_mode_y None): every column of tiles is a slice of the chain
    (shapes.initial_state: hinge points on the profile, every chord exactly a long), the tile along its
    chord, turned about y by −θ_i (θ the chain's angle from +x towards its transverse axis, here +z):
    q = (cos(θ/2), 0, −sin(θ/2), 0).
    2-D defects: centres on the surface above the flat grid points, each tile turned by the twist-free
    rotation that takes ẑ to the surface normal (−w_x, −w_y, 1)/|…| (tilt_quaternion)."""
    require_sheet(p)
    flat = flat_centres(p)
    count = flat.shape[0]
    identity = np.tile([1.0, 0.0, 0.0, 0.0], (count, 1))
    if p.defect_amplitude == 0:
        return flat, identity
    if p.defect_mode_y is None:
        chain = shapes.initial_state(p)
        i = np.tile(np.arange(p.n), p.ny)
        centres = np.column_stack([chain.x[i], flat[:, 1], chain.y[i]])
        half = 0.5 * chain.theta[i]
        q = np.column_stack([np.cos(half), 0 * half, -np.sin(half), 0 * half])
        return centres, q
    w, wx, wy = defect_surface(p)
    x, y = flat[:, 0], flat[:, 1]
    centres = np.column_stack([x, y, w(x, y)])
    return centres, tilt_quaternion(np.column_stack([-wx(x, y), -wy(x, y), np.ones_like(x)]))


def perturbed(p: SailParameters, centres: np.ndarray, perturbation: float) -> np.ndarray:
    """The centres with seeded random offsets along z of RMS `perturbation` (m; PERTURBATION_SEED, the
    same for both solvers): a start perturbed at a chosen level, e.g. round-off."""
    if perturbation == 0:
        return centres
    rng = np.random.default_rng(PERTURBATION_SEED)
    out = np.array(centres, float)
    out[:, 2] += perturbation * rng.standard_normal(out.shape[0])
    return out


# ---- connectors ----------------------------------------------------------------------------------
@dataclass
class Connectors:
    """All edge connections of a sheet.

    Attributes
    ----------
    tile_a, tile_b : ndarray (C,)
        The two tiles (tile_a = −1: the ground).
    local_a, local_b : ndarray (C, 3)
        Marker points in the tiles' frames (the ground's: global).
    stiffness, damping : ndarray (C, 6)
        Diagonals [x, y, z, about x, about y, about z] in tile A's frame.
    offset : ndarray (C, 6)
        Rest values of δ (the edge-tension pre-stress) and φ (bending_reference "initial").
    kind : ndarray (C,)
        0: x-edge, 1: y-edge, 2: ground.
    gap : ndarray (C, 3)
        (X_b + l_b) − (X_a + l_a) on the flat grid (global, m): 0, unless B's marker was moved so that
        the two markers coincide in a doubly curved initial shape (membrane_reference "initial").
    """

    tile_a: np.ndarray
    tile_b: np.ndarray
    local_a: np.ndarray
    local_b: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    offset: np.ndarray
    kind: np.ndarray
    gap: np.ndarray

    def __len__(self) -> int:
        return len(self.tile_a)


def edge_stiffness(p: SailParameters, tiles: Tiles, edge: float, span: float, bending: bool = True) -> np.ndarray:
    """[k_x, k_y, k_z, k_rx, k_ry, k_rz] of an x-edge (normal along local x) of length `edge` between
    centres `span` apart (module docstring); a y-edge swaps the x and y entries."""
    em, h, D = tiles.membrane_modulus, p.thickness, tiles.bending_rigidity
    k_par = em * h * edge / span
    return np.array(
        [
            k_par,
            k_par,
            SHEAR_CORRECTION * 0.5 * k_par,
            D * edge / span,
            D * edge / span if bending else 0.0,
            em * h**3 / 12.0 * edge / span,
        ]
    )


def _y_edge(k: np.ndarray) -> np.ndarray:
    return k[[1, 0, 2, 4, 3, 5]]


def connectors(
    p: SailParameters, centres: np.ndarray | None = None, quaternions: np.ndarray | None = None
) -> Connectors:
    """The edge connections: interior x-edges, interior y-edges, then the ground connections of a
    supported boundary, with the rest state of the initial shape (centres, quaternions; default
    initial_quaternions(p)) and the edge-tension pre-stress."""
    t = Tiles.of(p)
    a, b, T, nx = t.a, t.b, p.edge_tension, t.nx
    rows = []  # (tile a, tile b, local a, local b, stiffness, kind, pre-stress force on b along local x/y)
    kx, ky = edge_stiffness(p, t, b, a), _y_edge(edge_stiffness(p, t, a, b))
    for j in range(t.ny):
        for i in range(nx - 1):
            rows.append((j * nx + i, j * nx + i + 1, (0.5 * a, 0, 0), (-0.5 * a, 0, 0), kx, 0, (T * b, 0.0)))
    for j in range(t.ny - 1):
        for i in range(nx):
            rows.append((j * nx + i, (j + 1) * nx + i, (0, 0.5 * b, 0), (0, -0.5 * b, 0), ky, 1, (0.0, T * a)))
    if p.boundary != "free":
        bend = p.boundary == "clamped"
        flat = flat_centres(p)
        gx = 2.0 * edge_stiffness(p, t, b, a, bending=bend)
        gy = 2.0 * _y_edge(edge_stiffness(p, t, a, b, bending=bend))
        for j in range(t.ny):
            for i, sign in ((0, -1.0), (nx - 1, 1.0)):
                k = j * nx + i
                point = flat[k] + (sign * 0.5 * a, 0, 0)
                # the ground's marker at the edge point, the tile's at its outer edge midpoint; the
                # tension pulls the tile outwards (force −sign·T b on the tile along x)
                rows.append((-1, k, tuple(point), (sign * 0.5 * a, 0, 0), gx, 2, (-sign * T * b, 0.0)))
        for i in range(nx):
            for j, sign in ((0, -1.0), (t.ny - 1, 1.0)):
                k = j * nx + i
                point = flat[k] + (0, sign * 0.5 * b, 0)
                rows.append((-1, k, tuple(point), (0, sign * 0.5 * b, 0), gy, 2, (0.0, -sign * T * a)))
    ta = np.array([r[0] for r in rows], int)
    tb = np.array([r[1] for r in rows], int)
    la = np.array([r[2] for r in rows], float).reshape(-1, 3)
    lb = np.array([r[3] for r in rows], float).reshape(-1, 3)
    K = np.array([r[4] for r in rows], float).reshape(-1, 6)
    kind = np.array([r[5] for r in rows], int)
    pre = np.array([r[6] for r in rows], float).reshape(-1, 2)
    offset = np.zeros((len(rows), 6))
    # pre-stress: the spring force on tile b is −A₀ K(δ − offset); a tension F pulls b towards a, so
    # K(0 − offset) = F along the a → b direction: offset = −F/k
    offset[:, :2] = -pre / K[:, :2]
    gap = np.zeros((len(rows), 3))
    if p.defect_amplitude > 0 and "initial" in (p.membrane_reference, p.bending_reference):
        if centres is None or quaternions is None:
            centres, quaternions = initial_quaternions(p)
        rotations = quaternion_rotation(quaternions)
        if p.membrane_reference == "initial":
            # the rest state of the translational springs is the initial shape: B's marker moves by the
            # markers' mismatch there (~1e-10 m for a₀ = 10 µm), so that the force pair of every spring acts
            # at coincident points at rest (an offset in the spring law instead would apply ±f at points
            # δ₀ apart: a couple no potential produces, a circulatory stiffness ∝ E_m |δ₀|, module docstring)
            mismatch = relative_displacement(ta, tb, la, lb, centres, quaternions, flat_centres(p), gap)
            ra = np.where((ta < 0)[:, None, None], np.eye(3), rotations[np.maximum(ta, 0)])
            gap = -np.einsum("kji,kj->ki", rotations[tb], np.einsum("kij,kj->ki", ra, mismatch))
            lb = lb + gap
        if p.bending_reference == "initial":
            ra = np.where((ta < 0)[:, None, None], np.eye(3), rotations[np.maximum(ta, 0)])
            offset[:, 3:] = angles_xyz(np.einsum("kji,kjl->kil", ra, rotations[tb]))
    damping = p.stiffness_damping * K
    damping[:, [0, 1, 2, 5]] += t.membrane_damping * K[:, [0, 1, 2, 5]]
    out = Connectors(ta, tb, la, lb, K, damping, offset, kind, gap)
    if p.initial_equilibrium:
        if centres is None or quaternions is None:
            centres, quaternions = initial_quaternions(p)
        out.offset = equilibrium_offsets(p, out, centres, quaternions)
    return out


def static_loads(p: SailParameters, conn: Connectors, centres: np.ndarray, quaternions: np.ndarray) -> np.ndarray:
    """(N, 6) force (global, N) and torque about the centre (global, N m) on every tile from the connectors
    and the follower edge tension in a state at rest: the connector law of both solvers (module docstring,
    solvers.reduced.sheet) without its damping, evaluated in numpy from small quantities."""
    flat = flat_centres(p)
    rotations = quaternion_rotation(quaternions)
    ground = conn.tile_a < 0
    a = np.maximum(conn.tile_a, 0)
    RA = np.where(ground[:, None, None], np.eye(3), rotations[a])
    RB = rotations[conn.tile_b]
    delta = relative_displacement(
        conn.tile_a, conn.tile_b, conn.local_a, conn.local_b, centres, quaternions, flat, conn.gap
    )
    rmi = rotation_minus_identity(quaternions)
    rmi_a = np.where(ground[:, None, None], 0.0, rmi[a])
    # R_Aᵀ R_B − I from the small parts: (R_A − I)ᵀ + (R_B − I) + (R_A − I)ᵀ(R_B − I)
    rmi_b = rmi[conn.tile_b]
    relative = np.eye(3) + np.swapaxes(rmi_a, 1, 2) + rmi_b + np.einsum("kji,kjl->kil", rmi_a, rmi_b)
    strain = np.concatenate([delta, angles_xyz(relative)], axis=1)
    local = conn.stiffness * (strain - conn.offset)
    force = np.einsum("kij,kj->ki", RA, local[:, :3])
    moment = np.einsum("kij,kj->ki", RA, local[:, 3:])
    lever_a = np.where(ground[:, None], 0.0, np.einsum("kij,kj->ki", RA, conn.local_a))
    lever_b = np.einsum("kij,kj->ki", RB, conn.local_b)
    out = np.zeros((len(flat), 6))
    np.add.at(out[:, :3], conn.tile_b, -force)
    np.add.at(out[:, 3:], conn.tile_b, -(np.cross(lever_b, force) + moment))
    inner = ~ground
    np.add.at(out[:, :3], conn.tile_a[inner], force[inner])
    np.add.at(out[:, 3:], conn.tile_a[inner], np.cross(lever_a[inner], force[inner]) + moment[inner])
    tiles, points, forces = edge_followers(p)
    if len(tiles):
        f = np.einsum("kij,kj->ki", rotations[tiles], forces)
        np.add.at(out[:, :3], tiles, f)
        np.add.at(out[:, 3:], tiles, np.cross(np.einsum("kij,kj->ki", rotations[tiles], points), f))
    return out


def _load_map(p: SailParameters, conn: Connectors, centres: np.ndarray, quaternions: np.ndarray):
    """G (6N × 6C, sparse): the tiles' forces and torques (static_loads' layout, flattened) per unit change
    of the connectors' local loads K(strain − offset)."""
    import scipy.sparse as sparse

    rotations = quaternion_rotation(quaternions)
    ground = conn.tile_a < 0
    RA = np.where(ground[:, None, None], np.eye(3), rotations[np.maximum(conn.tile_a, 0)])
    rows, cols, vals = [], [], []

    def block(tile, lever, sign, keep):
        cross = np.zeros((len(lever), 3, 3))
        cross[:, 0, 1], cross[:, 0, 2], cross[:, 1, 2] = -lever[:, 2], lever[:, 1], -lever[:, 0]
        cross[:, 1, 0], cross[:, 2, 0], cross[:, 2, 1] = lever[:, 2], -lever[:, 1], lever[:, 0]
        full = np.zeros((len(lever), 6, 6))
        full[:, :3, :3] = RA
        full[:, 3:, :3] = cross @ RA
        full[:, 3:, 3:] = RA
        c = np.nonzero(keep)[0]
        r = 6 * tile[c, None, None] + np.arange(6)[None, :, None]
        q = 6 * c[:, None, None] + np.arange(6)[None, None, :]
        rows.append(np.broadcast_to(r, (len(c), 6, 6)).ravel())
        cols.append(np.broadcast_to(q, (len(c), 6, 6)).ravel())
        vals.append(sign * full[c].ravel())

    lever_b = np.einsum("kij,kj->ki", rotations[conn.tile_b], conn.local_b)
    block(conn.tile_b, lever_b, -1.0, np.ones(len(conn), bool))
    lever_a = np.einsum("kij,kj->ki", RA, conn.local_a)
    block(np.maximum(conn.tile_a, 0), lever_a, 1.0, ~ground)
    n = 6 * len(centres)
    return sparse.csc_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), (n, 6 * len(conn)))


def equilibrium_offsets(
    p: SailParameters, conn: Connectors, centres: np.ndarray, quaternions: np.ndarray, iterations: int = 4
) -> np.ndarray:
    """The connectors' rest offsets (C, 6) corrected so that the unlit sheet, edge tension included, is at
    rest in the given state (initial_equilibrium).

    The residual r (static_loads, 6N) is linear in the offsets: a change Δo of the rest strains changes the
    connectors' local loads by −K Δo and the tiles' loads by −G K Δo (G: _load_map). Of all Δo that cancel r
    the one of least complementary energy ½ Δℓᵀ K⁻¹ Δℓ (Δℓ = −K Δo) is Δo = −Gᵀλ with (G K Gᵀ) λ = −r:
    the elastic answer, the rest state from which the sheet is pulled into the given shape by the loads
    that r would otherwise release. G K Gᵀ is the connectors' linear stiffness; a free sheet has 6 rigid
    modes, removed by holding one tile, and its r is first cleared of its net force and moment (the
    followers on a tilted edge have a net transverse force, of order T·W times the edge's slope; that
    remainder moves the sheet as a rigid body, which the plane fit of the failure rule removes). The few
    connector laws that are not linear in the state (the rotation's xyz angles, the lever arms) are met
    by repeating the step with the new residual."""
    from scipy.sparse.linalg import splu

    offset = np.array(conn.offset, float)
    G = _load_map(p, conn, centres, quaternions)
    S = (G @ G.T.multiply(conn.stiffness.ravel()[:, None]).tocsc()).tocsc()
    keep = np.arange(S.shape[0])
    free = not np.any(conn.tile_a < 0)
    if free:
        held = int(np.argmin(np.linalg.norm(centres[:, :2] - centres[:, :2].mean(axis=0), axis=1)))
        keep = np.setdiff1d(keep, 6 * held + np.arange(6))
        rigid = np.zeros((S.shape[0], 6))
        for i in range(3):
            rigid[i::6, i] = 1.0
            axis = np.zeros(3)
            axis[i] = 1.0
            rigid[0::6, 3 + i], rigid[1::6, 3 + i], rigid[2::6, 3 + i] = np.cross(axis, centres).T
            rigid[3 + i :: 6, 3 + i] = 1.0
    lu = splu(S[keep][:, keep].tocsc())
    for _ in range(iterations):
        r = static_loads(p, Connectors(**{**conn.__dict__, "offset": offset}), centres, quaternions).ravel()
        if free:
            r = r - rigid @ np.linalg.lstsq(rigid, r, rcond=None)[0]
        lam = np.zeros(S.shape[0])
        lam[keep] = lu.solve(-r[keep])
        offset = offset - (G.T @ lam).reshape(-1, 6) * (conn.stiffness > 0)
    return offset


def relative_displacement(ta, tb, la, lb, centres, quaternions, flat, gap=None) -> np.ndarray:
    """A₀ᵀ(p_b − p_a) of every connector in a given state (its translational strain measure), (C, 3).

    Evaluated from small quantities only: on the flat grid the markers of every connector coincide up to
    the small known gap = (X_b + l_b) − (X_a + l_a) (Connectors.gap), so
    p_b − p_a = gap + (u_b − u_a) + (R_b − I) l_b − (R_a − I) l_a with u = centre − flat grid point; no
    ~1 m coordinates are differenced, and R − I comes from the quaternions' small components (round-off
    ~1e-21 m, not 1e-16 m)."""
    u = np.asarray(centres) - flat
    RmI = rotation_minus_identity(quaternions)
    rotations = np.eye(3) + RmI
    ground = ta < 0
    a = np.maximum(ta, 0)
    d = u[tb] + np.einsum("kij,kj->ki", RmI[tb], lb)
    if gap is not None:
        d = d + gap
    d -= np.where(ground[:, None], 0.0, u[a] + np.einsum("kij,kj->ki", RmI[a], la))
    Ra = np.where(ground[:, None, None], np.eye(3), rotations[a])
    return np.einsum("kji,kj->ki", Ra, d)


def edge_followers(p: SailParameters):
    """The follower edge tension on a free boundary: (tiles, local points, local forces) of every
    boundary tile's outer edge midpoint (force T·e along the tile's own outward in-plane axis)."""
    if p.edge_tension == 0 or p.boundary != "free":
        return np.zeros(0, int), np.zeros((0, 3)), np.zeros((0, 3))
    a, b, T, nx = p.length / p.n, p.width / p.ny, p.edge_tension, p.n
    tiles, points, forces = [], [], []
    for j in range(p.ny):
        for i, s in ((0, -1.0), (nx - 1, 1.0)):
            tiles.append(j * nx + i)
            points.append((s * 0.5 * a, 0, 0))
            forces.append((s * T * b, 0, 0))
    for i in range(nx):
        for j, s in ((0, -1.0), (p.ny - 1, 1.0)):
            tiles.append(j * nx + i)
            points.append((0, s * 0.5 * b, 0))
            forces.append((0, s * T * a, 0))
    return np.array(tiles, int), np.array(points, float), np.array(forces, float)


# ---- loads ---------------------------------------------------------------------------------------
def tile_forces(p: SailParameters, centres: np.ndarray, normals: np.ndarray) -> np.ndarray:
    """(..., N, 3) applied force on each tile centre in the accelerating frame: the net radiation and
    frame force (loads.facet_forces, cancellation done analytically) plus the dead pressure p·ab ẑ (N).

    normals: the tiles' unit normals R ẑ, their x and y components computed without cancellation."""
    t = Tiles.of(p)
    normals = np.asarray(normals, float)
    centres = np.asarray(centres, float)
    local = loads.sheet_intensity(p, centres[..., 0], centres[..., 1])
    f_across, f_along = loads.facet_forces(
        normals[..., :2], normals[..., 2], local, p.mean_intensity, t.area, p.reflectivity, p.absorptivity
    )
    out = np.empty(normals.shape)
    out[..., :2] = f_across
    out[..., 2] = f_along + p.pressure * t.area
    return out


# ---- the chain this sheet reduces to, and what the grid resolves ----------------------------------
def as_strip(p: SailParameters) -> SailParameters:
    """The paper's torsion chain of the same sail (n slices, the sheet's E, beam and defect along x): the
    sheet's limit for a 1-D defect, free side edges and no edge tension (module docstring)."""
    require_sheet(p)
    return SailParameters(
        model="torsion",
        n=p.n,
        length=p.length,
        width=p.width,
        thickness=p.thickness,
        density=p.density,
        youngs_modulus=p.youngs_modulus,
        intensity=p.intensity,
        defect_amplitude=p.defect_amplitude,
        defect_mode=p.defect_mode,
        defect_seed=p.defect_seed,
        defect_mode_count=p.defect_mode_count,
        defect_spectrum=p.defect_spectrum,
        beam_waist=p.beam_waist,
        beam_center=p.beam_center,
        reflectivity=p.reflectivity,
        absorptivity=p.absorptivity,
        bending=p.bending,
    )


MIN_TILES_PER_HALF_WAVE = shapes.MIN_SLICES_PER_HALF_WAVE
# A doubly curved defect needs more: the E_m = E critical modulus of ν_x = ν_y = 1.5 (docs/sheet.md,
# paper.sheet_physics) is about 3× the converged value at 4 tiles per half wavelength, 1.14× at 6 and
# 1.04× at 8 (bisection brackets on 12, 18, 24 and 30/36 tiles along L).
CONVERGED_TILES_PER_HALF_WAVE_2D = 8


def defect_warnings(p: SailParameters, initial_amplitude: float) -> list[str]:
    """Why a grid of tiles may not carry the case's defect: the chain's checks along x
    (shapes.defect_warnings), too few tiles per half wavelength across the width, and, for a doubly
    curved defect, fewer than CONVERGED_TILES_PER_HALF_WAVE_2D tiles per half wavelength in either
    direction (resolved, but its stability results are not yet converged in the grid)."""
    notes = shapes.defect_warnings(p, initial_amplitude, element="tiles")
    if p.defect_mode_y is not None and p.defect_amplitude > 0:
        shortest_y = shapes.shortest_mode(p, p.defect_mode_y)
        per_half_wave_y = p.ny / (2.0 * shortest_y)
        if per_half_wave_y < MIN_TILES_PER_HALF_WAVE:
            notes.append(
                f"ny = {p.ny} gives {per_half_wave_y:.3g} tiles per half wavelength of the defect across the "
                f"width (ν_y = {shortest_y:g}); at least {MIN_TILES_PER_HALF_WAVE} are needed to resolve it"
            )
        shortest_x = shapes.shortest_mode(p, p.defect_mode)
        coarsest = min(p.n / (2.0 * shortest_x), per_half_wave_y)
        if MIN_TILES_PER_HALF_WAVE <= coarsest < CONVERGED_TILES_PER_HALF_WAVE_2D:
            notes.append(
                f"{p.n} × {p.ny} tiles give {coarsest:.3g} tiles per half wavelength of the doubly curved "
                f"defect; its stability results converge from about {CONVERGED_TILES_PER_HALF_WAVE_2D} (measured "
                "on the critical modulus of ν = 1.5 × 1.5: about 3× too high at 4, 1.14× at 6, 1.04× at 8)"
            )
    return notes
