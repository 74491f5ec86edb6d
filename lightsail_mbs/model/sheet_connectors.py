"""The sheet's edge connections (model "sheet", :mod:`lightsail_mbs.model.sheet`): one connector per shared
edge and per supported boundary edge, their stiffnesses and damping, their rest state and pre-stress, and
the edge tension's follower forces.

Edge connections (one per shared edge, at the edge midpoint)
------------------------------------------------------------
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
defect nothing changes) or flat ("flat"). A billowed sheet (billow_radius, model.sheet_shapes.cap) counts its
cap as part of the initial shape, and with billow_rest its "flat" springs rest in the cap without the defect
(sheet_shapes.rest_quaternions). The initial rest state is realised by the marker positions,
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
chain's TnT end tension, one dimension up). On a supported boundary the ground connectors carry it. A
spinning sheet's connectors carry the flat sheet's centrifugal stress the same way (spun_prestrain,
model.sheet_spin).

Membrane damping
----------------
The in-plane component of the load, switched on at t = 0, rings the in-plane lattice
(ω ~ 1e4–1e5 rad/s for the paper's sail), which neither solver should have to resolve. The stiff
springs (in-plane, transverse shear, drilling) get the damping β_m k with β_m = 2/ω_max by default
(critical for the highest in-plane lattice mode, ω_max² = 4(k_x + k_y)/m); Kirchhoff bending of a
1-D defect does not strain those springs, so it is not damped by them (the chain-limit failure time
moves by < 1e-8 relative when β_m is ×10). A doubly curved sheet is different: its bending strains
the membrane (docs: sheet), so β_m is recorded with every case and its effect measured there.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightsail_mbs.model import planforms, sheet_spin
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.model.sheet_grid import (
    Tiles,
    angles_xyz,
    flat_centres,
    quaternion_rotation,
    relative_displacement,
    rotation_minus_identity,
)
from lightsail_mbs.model.sheet_shapes import initial_quaternions, rest_quaternions

SHEAR_CORRECTION = 5.0 / 6.0  # Mindlin's κ on the transverse-shear penalty


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
        0: x-edge, 1: y-edge, 2: ground, 3: an edge of another direction.
    gap : ndarray (C, 3)
        (X_b + l_b) − (X_a + l_a) on the flat grid (global, m): 0, unless B's marker was moved so that
        the two markers coincide in a doubly curved initial shape (membrane_reference "initial").
    frame : ndarray (C, 3, 3)
        A support's axes in the ground (x along the edge's outward normal, z = ẑ; the global axes for a
        support along x or y, whose stiffness is permuted instead); the global axes between tiles.
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
    frame: np.ndarray

    def __len__(self) -> int:
        return len(self.tile_a)


def edge_stiffness(p: SailParameters, tiles: Tiles, edge, span, bending: bool = True) -> np.ndarray:
    """[k_x, k_y, k_z, k_rx, k_ry, k_rz] of an x-edge (normal along local x) of length `edge` between
    centres `span` apart (module docstring; arrays of edges give (E, 6)); a y-edge swaps the x and y
    entries."""
    em, h, D = tiles.membrane_modulus, p.thickness, tiles.bending_rigidity
    edge, span = np.asarray(edge, float), np.asarray(span, float)
    k_par = em * h * edge / span
    return np.stack(
        [
            k_par,
            k_par,
            SHEAR_CORRECTION * 0.5 * k_par,
            D * edge / span,
            D * edge / span if bending else 0.0 * k_par,
            em * h**3 / 12.0 * edge / span,
        ],
        axis=-1,
    )


def _y_edge(k: np.ndarray) -> np.ndarray:
    return k[..., [1, 0, 2, 4, 3, 5]]


def _along(T: float, e: np.ndarray, d: np.ndarray) -> np.ndarray:
    """T e d (C, 2), exactly 0 where d is."""
    return np.where(d != 0, T * e[:, None] * d, 0.0)


def _support_frames(normal: np.ndarray):
    """(stiffness permutation, frames (B, 3, 3), kinds) of supports with outward normals (B, 2): an x-edge
    pattern along x, swapped along y, else the pattern in the frame (n̂, ẑ × n̂, ẑ) (module docstring)."""
    along_x = normal[:, 1] == 0
    along_y = normal[:, 0] == 0
    frames = np.tile(np.eye(3), (len(normal), 1, 1))
    tilted = ~(along_x | along_y)
    frames[tilted, 0, 0] = frames[tilted, 1, 1] = normal[tilted, 0]
    frames[tilted, 1, 0] = normal[tilted, 1]
    frames[tilted, 0, 1] = -normal[tilted, 1]
    return along_y, frames


def connectors(
    p: SailParameters, centres: np.ndarray | None = None, quaternions: np.ndarray | None = None
) -> Connectors:
    """The edge connections: the mesh's shared edges (model.sheet_mesh; on a grid the interior x-edges, then
    the y-edges), then the ground connections of a supported boundary, with the rest state of the initial
    shape (centres, quaternions; default initial_quaternions(p)) and the edge-tension pre-stress."""
    t = Tiles.of(p)
    m, T = t.mesh, p.edge_tension
    direction = m.direction
    K = edge_stiffness(p, t, m.edge_length, m.span)  # isotropic in the plane when bending is on
    K = np.where((direction[:, 0] == 0)[:, None], _y_edge(K), K)
    kind = np.where(direction[:, 1] == 0, 0, np.where(direction[:, 0] == 0, 1, 3))
    ta, tb = m.pairs[:, 0], m.pairs[:, 1]
    la = np.column_stack([m.marker_a, np.zeros(len(ta))])
    lb = np.column_stack([m.marker_b, np.zeros(len(ta))])
    pre = _along(T, m.edge_length, direction)  # the tension T e on b, along a → b
    frame = np.tile(np.eye(3), (len(ta), 1, 1))
    if p.boundary != "free":
        bend = p.boundary == "clamped"
        flat = flat_centres(p)
        swap, frames = _support_frames(m.boundary_normal)
        G = 2.0 * edge_stiffness(p, t, m.boundary_length, m.boundary_span, bending=bend)
        G = np.where(swap[:, None], _y_edge(G), G)
        tiles = m.boundary_tile
        marker = np.column_stack([m.boundary_marker, np.zeros(len(tiles))])
        # the ground's marker at the edge point, the tile's on its edge line; the tension pulls the tile
        # outwards (a force T e along the ground → tile direction −n̂ on the ground's side)
        ta = np.concatenate([ta, np.full(len(tiles), -1)])
        tb = np.concatenate([tb, tiles])
        la = np.concatenate([la, flat[tiles] + marker])
        lb = np.concatenate([lb, marker])
        K = np.concatenate([K, G])
        kind = np.concatenate([kind, np.full(len(tiles), 2)])
        pre = np.concatenate([pre, _along(T, m.boundary_length, -m.boundary_normal)])
        frame = np.concatenate([frame, frames])
    ta, tb, kind = ta.astype(int), tb.astype(int), kind.astype(int)
    offset = np.zeros((len(ta), 6))
    # pre-stress: the spring force on tile b is −A₀ K(δ − offset); a tension F pulls b towards a, so
    # K(0 − offset) = F along the a → b direction: offset = −F/k; in a support's frame F lies along its x
    local_pre = np.einsum("kji,kj->ki", frame[:, :2, :2], pre)
    offset[:, :2] = -np.where(_identity(frame)[:, None], pre, local_pre) / K[:, :2]
    gap = np.zeros((len(ta), 3))
    if centres is None or quaternions is None:
        centres, quaternions = initial_quaternions(p)
    membrane_rest = rest_quaternions(p, p.membrane_reference, centres, quaternions)
    if membrane_rest is not None:
        # the rest state of the translational springs is that shape: B's marker moves by the markers'
        # mismatch there (~1e-10 m for a₀ = 10 µm), so that the force pair of every spring acts at
        # coincident points at rest (an offset in the spring law instead would apply ±f at points δ₀
        # apart: a couple no potential produces, a circulatory stiffness ∝ E_m |δ₀|, module docstring)
        rotations = quaternion_rotation(membrane_rest[1])
        ra = frames_a(ta, frame, rotations)
        mismatch = relative_displacement(ta, tb, la, lb, *membrane_rest, flat_centres(p), gap, frame)
        gap = -np.einsum("kji,kj->ki", rotations[tb], np.einsum("kij,kj->ki", ra, mismatch))
        lb = lb + gap
    bending_rest = rest_quaternions(p, p.bending_reference, centres, quaternions)
    if bending_rest is not None:
        rotations = quaternion_rotation(bending_rest[1])
        offset[:, 3:] = angles_xyz(relative_rotation(ta, tb, frame, rotations))
    damping = p.stiffness_damping * K
    damping[:, [0, 1, 2, 5]] += t.membrane_damping * K[:, [0, 1, 2, 5]]
    out = Connectors(ta, tb, la, lb, K, damping, offset, kind, gap, frame)
    if p.spin_rate != 0:  # the flat sheet's centrifugal stress (model.sheet_spin)
        out.offset = out.offset + spun_prestrain(p, out)
    if p.initial_equilibrium:  # spinning: the exact spun equilibrium of the initial shape (model.sheet_spin)
        load = sheet_spin.centrifugal_loads(p, centres, quaternions) if p.spin_rate != 0 else None
        out.offset = equilibrium_offsets(p, out, centres, quaternions, load=load)
    return out


def spun_prestrain(p: SailParameters, conn: Connectors) -> np.ndarray:
    """(C, 6): the rest offsets that load the flat sheet with its centrifugal membrane stress in steady spin
    (model.sheet_spin), in the connectors' local axes: equilibrium_offsets of the in-plane problem on the
    flat grid, with conn's springs and markers and no other load."""
    flat = flat_centres(p)
    level = np.tile([1.0, 0.0, 0.0, 0.0], (len(flat), 1))
    bare = Connectors(**{**conn.__dict__, "local_b": conn.local_b - conn.gap, "gap": 0.0 * conn.gap})
    bare.offset = np.zeros_like(conn.offset)
    load = sheet_spin.centrifugal_loads(p, flat, level)
    return equilibrium_offsets(p.replace(edge_tension=0.0), bare, flat, level, load=load, plane=True)


def _identity(frame: np.ndarray) -> np.ndarray:
    return np.all(frame == np.eye(3), axis=(1, 2))


def frames_a(ta: np.ndarray, frame: np.ndarray, rotations: np.ndarray) -> np.ndarray:
    """A₀ of every connector (C, 3, 3): tile a's rotation, or the support's frame (ta = −1)."""
    return np.where((ta < 0)[:, None, None], frame, rotations[np.maximum(ta, 0)])


def relative_rotation(ta, tb, frame, rotations, rmi=None) -> np.ndarray:
    """A₀ᵀ A₁ of every connector (C, 3, 3): R_aᵀ R_b between tiles, frameᵀ R_b frame at a support. With
    rmi (R − I of every tile) it is formed from the small parts, (R_a − I)ᵀ + (R_b − I) + (R_a − I)ᵀ(R_b − I)
    added to I."""
    ground = ta < 0
    if rmi is None:
        relative = np.einsum("kji,kjl->kil", frames_a(ta, frame, rotations), rotations[tb])
    else:
        rmi_a = np.where(ground[:, None, None], 0.0, rmi[np.maximum(ta, 0)])
        rmi_b = rmi[tb]
        relative = np.eye(3) + np.swapaxes(rmi_a, 1, 2) + rmi_b + np.einsum("kji,kjl->kil", rmi_a, rmi_b)
    tilted = ground & ~_identity(frame)
    if np.any(tilted):
        f = frame[tilted]
        relative[tilted] = np.einsum("kji,kjl,klm->kim", f, rotations[tb[tilted]], f)
    return relative


def static_loads(p: SailParameters, conn: Connectors, centres: np.ndarray, quaternions: np.ndarray) -> np.ndarray:
    """(N, 6) force (global, N) and torque about the centre (global, N m) on every tile from the connectors
    and the follower edge tension in a state at rest: the connector law of both solvers (module docstring,
    solvers.reduced.sheet) without its damping, evaluated in numpy from small quantities."""
    flat = flat_centres(p)
    rotations = quaternion_rotation(quaternions)
    ground = conn.tile_a < 0
    RA = frames_a(conn.tile_a, conn.frame, rotations)
    RB = rotations[conn.tile_b]
    delta = relative_displacement(
        conn.tile_a, conn.tile_b, conn.local_a, conn.local_b, centres, quaternions, flat, conn.gap, conn.frame
    )
    # R_Aᵀ R_B − I from the small parts: (R_A − I)ᵀ + (R_B − I) + (R_A − I)ᵀ(R_B − I)
    relative = relative_rotation(conn.tile_a, conn.tile_b, conn.frame, rotations, rotation_minus_identity(quaternions))
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
    RA = frames_a(conn.tile_a, conn.frame, rotations)
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
    p: SailParameters,
    conn: Connectors,
    centres: np.ndarray,
    quaternions: np.ndarray,
    iterations: int = 4,
    load: np.ndarray | None = None,
    plane: bool = False,
) -> np.ndarray:
    """The connectors' rest offsets (C, 6) corrected so that the unlit sheet, edge tension included, is at
    rest in the given state (initial_equilibrium), or, with a load (N, 6, static_loads' layout), in
    equilibrium with it (static_loads + load = 0: the spun equilibrium, model.sheet_spin).

    The residual r (static_loads, 6N) is linear in the offsets: a change Δo of the rest strains changes the
    connectors' local loads by −K Δo and the tiles' loads by −G K Δo (G: _load_map). Of all Δo that cancel r
    the one of least complementary energy ½ Δℓᵀ K⁻¹ Δℓ (Δℓ = −K Δo) is Δo = −Gᵀλ with (G K Gᵀ) λ = −r:
    the elastic answer, the rest state from which the sheet is pulled into the given shape by the loads
    that r would otherwise release. G K Gᵀ is the connectors' linear stiffness; a free sheet has 6 rigid
    modes, removed by holding one tile, and its r is first cleared of its net force and moment (the
    followers on a tilted edge have a net transverse force, of order T·W times the edge's slope; that
    remainder moves the sheet as a rigid body, which the plane fit of the failure rule removes). The few
    connector laws that are not linear in the state (the rotation's xyz angles, the lever arms) are met
    by repeating the step with the new residual. plane: a flat sheet (identity rotations) under in-plane
    loads, whose in-plane and transverse problems decouple: only its in-plane motions (x, y, about z) are
    solved for (the transverse part is singular without bending springs)."""
    from scipy.sparse.linalg import splu

    offset = np.array(conn.offset, float)
    G = _load_map(p, conn, centres, quaternions)
    S = (G @ G.T.multiply(conn.stiffness.ravel()[:, None]).tocsc()).tocsc()
    keep = np.arange(S.shape[0])
    if plane:  # a flat sheet under in-plane loads: its in-plane motion alone (the tilts decouple)
        keep = keep[np.isin(keep % 6, (0, 1, 5))]
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
        if load is not None:
            r = r + load.ravel()
        if free:
            r = r - rigid @ np.linalg.lstsq(rigid, r, rcond=None)[0]
        lam = np.zeros(S.shape[0])
        lam[keep] = lu.solve(-r[keep])
        offset = offset - (G.T @ lam).reshape(-1, 6) * (conn.stiffness > 0)
    return offset


def edge_followers(p: SailParameters):
    """The follower edge tension on a free boundary: (tiles, local points, local forces) of every boundary
    edge of the mesh (force T·e along the tile's own outward in-plane normal, at the edge point on the
    normal's line through the centre: model.sheet_mesh)."""
    if p.edge_tension == 0 or p.boundary != "free":
        return np.zeros(0, int), np.zeros((0, 3)), np.zeros((0, 3))
    m = planforms.mesh_of(p)
    zeros = np.zeros(len(m.boundary_tile))
    forces = _along(p.edge_tension, m.boundary_length, m.boundary_normal)
    return (
        np.array(m.boundary_tile, int),
        np.column_stack([m.boundary_marker, zeros]),
        np.column_stack([forces, zeros]),
    )
