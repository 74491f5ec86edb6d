"""The growth-rate spectrum of a sheet and its modes' symmetry families.

**The linearisation.** The solver's ``linearise`` capability (solvers.contract rule 9) gives the Jacobian L of
the sheet's equations at rest in a state, in the minimal coordinates ξ = (Δu, Δθ_b) per tile and their rates
(:func:`lightsail_mbs.solvers.reduced.sheet.linearise`): ξ̇ = V, V̇ = K ξ + C V. Its eigenvalues λ are the
growth rates Re λ of small deviations from the state. At the initial state of a released defect (not an
equilibrium: the bending springs at rest flat and the beam push it) they are the rates of the frozen state,
before it has moved; the load's second-order terms act at first order there.

**The families.** A square sheet (n = ny tiles, L = W) has the symmetries of the square: the mirrors
M_x: x → L − x, M_y: y → W − y and the swap S: x ↔ y, which generate the dihedral group of order 8. On the
tile fields each acts by a permutation of the tiles and a 3 × 3 matrix D on each vector: the centre
displacement is a polar vector (D = the reflection), the rotation an axial vector (D = −the reflection,
det = −1); both hold in the body frame too, since a mirrored tile's rotation is R' = D R D. The five
irreducible representations are the families, named by the parities of the deflection w(x, y):

* ``A1``: even in x and y, symmetric under x ↔ y (the doubly sinusoidal defect ν_x = ν_y = 1.5 itself);
* ``A2``: even in x and y, antisymmetric under x ↔ y;
* ``B1``: odd in x and y, symmetric under x ↔ y (a twist, w ∝ xy);
* ``B2``: odd in x and y, antisymmetric under x ↔ y (and the spin about z);
* ``E``: odd in one direction and even in the other, a pair exchanged by x ↔ y (the rigid tilts, the
  in-plane translations).

Projectors P_± = (I ± M)/2 of each mirror give A1 = P_x+ P_y+ P_s+, A2 = P_x+ P_y+ P_s−, B1 = P_x− P_y− P_s+,
B2 = P_x− P_y− P_s−, E = P_x+ P_y− + P_x− P_y+ (S commutes with M_x M_y, so each product is a projector);
they are orthogonal, and they add up to I because P_s+ + P_s− = I and the four mirror products do. If L
commutes with the three generators, each family's subspace is invariant: a state in one family stays
there, a symmetric defect drives only A1, and a mode of another family grows only from what breaks the
symmetry (the finite differences of the Jacobian, the connectors' Tait–Bryan angles, which are not
symmetric under a mirror beyond first order, round-off). Then L splits into one block per family
(:func:`family_spectrum`, the ``E`` block once, on its x-odd/y-even half: the other half repeats it), and
the commutators ‖G L − L G‖ measure how far it does not. For the sheet with a doubly curved defect L
commutes with the swap to ~1e-11 but with the mirrors only to ~1e-5 of its norm, in proportion to a₀ and to
the tile size: the connector law measures a connection in the frame of its first tile, and a mirror makes the
second tile the first (their frames differ by the neighbours' relative rotation). Through the stiff membrane
that moves eigenvalues at second order by far more than its size: the family blocks are then a diagnostic,
and :func:`spectrum` (the whole L, every mode classified) is the answer.

**Rigid modes.** A free sheet (a supported one has none) has six: three translations and three
rotations (ξ_rigid: Δu = t + ω × r, Δθ_b = R_kᵀ ω). The failure measure (the best-fit plane removed) does
not see them, and at a state that is not an equilibrium they are not null vectors of K (a rigid rotation
turns the state's own accelerations with it), so their zero eigenvalues, in Jordan chains (a tilt feeds a
translation through the load), split into spurious rates ~ ε^(1/4) of any perturbation ε. The spectra here
are of the deformations: L restricted (Galerkin, in the kinetic-energy metric M) to the M-orthogonal
complement of the rigid span. That drops the rigid motion's feedback on the deformation (under a uniform
beam: a tilt of a curved sheet, of second order in slope × tilt).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import sheet
from lightsail_mbs.model.parameters import SailParameters

FAMILIES = ("A1", "A2", "B1", "B2", "E")
# parities (M_x, M_y, S) of the one-dimensional families; E is odd under exactly one mirror
PARITIES = {"A1": (1, 1, 1), "A2": (1, 1, -1), "B1": (-1, -1, 1), "B2": (-1, -1, -1)}
GENERATORS = ("mirror_x", "mirror_y", "swap")
DOF = 6  # generalised displacements per tile


def require_square(p: SailParameters) -> None:
    """The families need the square's symmetries: a rectangular sheet (its grid of tiles) of n = ny tiles with
    L = W."""
    if p.model != "sheet" or p.planform != "rectangle" or p.n != p.ny or p.length != p.width:
        raise ParameterError(
            f"model={p.model!r}, planform={p.planform!r}, n={p.n}, ny={p.ny}, length={p.length}, width={p.width} "
            "is invalid for the symmetry families: allowed a rectangular sheet with n = ny and length = width"
        )


def _generator(p: SailParameters, name: str) -> sp.csr_matrix:
    """The 6N × 6N signed permutation of one generator on tile fields ξ (tile k = j·nx + i)."""
    n = p.n
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="xy")
    i, j = i.ravel(), j.ravel()
    if name == "mirror_x":
        target, reflection = j * n + (n - 1 - i), np.diag([-1.0, 1.0, 1.0])
    elif name == "mirror_y":
        target, reflection = (n - 1 - j) * n + i, np.diag([1.0, -1.0, 1.0])
    else:
        target, reflection = i * n + j, np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    block = sp.block_diag([reflection, -reflection])  # polar displacement, axial rotation
    move = sp.csr_matrix((np.ones(n * n), (target, np.arange(n * n))), shape=(n * n, n * n))
    return sp.kron(move, block, format="csr")


def generators(p: SailParameters) -> dict[str, sp.csr_matrix]:
    """{"mirror_x", "mirror_y", "swap"}: the symmetry operators on tile fields ξ (6N)."""
    require_square(p)
    return {name: _generator(p, name) for name in GENERATORS}


def projectors(p: SailParameters) -> dict[str, sp.csr_matrix]:
    """The orthogonal projector of each family on tile fields ξ (6N × 6N), plus "E+-" (x-odd, y-even half of E)."""
    g = generators(p)
    eye = sp.identity(g["swap"].shape[0], format="csr")
    half = {(name, s): 0.5 * (eye + s * g[name]) for name in GENERATORS for s in (1, -1)}
    out = {
        family: half[("mirror_x", px)] @ half[("mirror_y", py)] @ half[("swap", ps)]
        for family, (px, py, ps) in PARITIES.items()
    }
    out["E+-"] = half[("mirror_x", -1)] @ half[("mirror_y", 1)]
    out["E"] = out["E+-"] + half[("mirror_x", 1)] @ half[("mirror_y", -1)]
    return out


def family_basis(projector: sp.csr_matrix) -> sp.csr_matrix:
    """An orthonormal basis (columns, sparse) of a family projector's range, orbit by orbit: the projector
    couples only entries of one orbit of the group (≤ 8 tiles × 6 components), so each connected block is
    a small dense projector whose eigenvectors of eigenvalue 1 span its part of the range."""
    from scipy.sparse.csgraph import connected_components

    count, label = connected_components(abs(projector) + sp.identity(projector.shape[0]), directed=False)
    order = np.argsort(label, kind="stable")
    bounds = np.searchsorted(label[order], np.arange(count + 1))
    rows, cols, values, column = [], [], [], 0
    dense = projector.tocsr()
    for c in range(count):
        index = order[bounds[c] : bounds[c + 1]]
        w, v = np.linalg.eigh(dense[index][:, index].toarray())
        keep = v[:, w > 0.5]
        for k in range(keep.shape[1]):
            nonzero = np.abs(keep[:, k]) > 1e-14
            rows.append(index[nonzero])
            values.append(keep[nonzero, k])
            cols.append(np.full(nonzero.sum(), column))
            column += 1
    if not column:
        return sp.csr_matrix((projector.shape[0], 0))
    return sp.csr_matrix(
        (np.concatenate(values), (np.concatenate(rows), np.concatenate(cols))), shape=(projector.shape[0], column)
    )


def linearisation(p: SailParameters, state: np.ndarray | None = None, solver: str = "reduced") -> sp.csc_matrix:
    """L (12N × 12N) of the named solver's ``linearise`` capability (module docstring)."""
    from lightsail_mbs.solvers import contract

    return contract.lookup(solver, p).capability("linearise")(p, state)


def commutator_defects(p: SailParameters, L: sp.spmatrix) -> dict[str, float]:
    """‖G L − L G‖_F / ‖L‖_F of each generator G (on ξ and V alike): how far L breaks each symmetry."""
    norm = sp.linalg.norm(L)
    out = {}
    for name, g in generators(p).items():
        G = sp.block_diag([g, g], format="csr")
        out[name] = float(sp.linalg.norm(G @ L - L @ G) / norm)
    return out


def kinetic_weights(p: SailParameters) -> np.ndarray:
    """The kinetic-energy metric's diagonal M on ξ (6N): tile mass for Δu, principal inertia for Δθ_b, of the
    rectangle's grid, whose tiles are all alike (other planforms' tiles differ: spin_spectrum.mass_metric)."""
    tiles = sheet.Tiles.of(p)
    return np.tile(np.r_[[tiles.mass] * 3, np.asarray(tiles.inertia, float)], tiles.count)


def rigid_basis(p: SailParameters, state: np.ndarray | None = None) -> np.ndarray:
    """The six rigid-body displacements ξ (6N × 6) about the tiles' centres and orientations in `state`
    (the solver's 13N state, default the initial shape): Δu = t + ω × (r − r̄), Δθ_b = R_kᵀ ω."""
    centres, q = sheet.initial_quaternions(p)
    if state is not None:
        rows = np.asarray(state).reshape(-1, 13)
        centres, q = sheet.flat_centres(p) + rows[:, 0:3], rows[:, 3:7]
    return rigid_motions(centres, q)


def rigid_motions(centres: np.ndarray, q: np.ndarray) -> np.ndarray:
    """The six rigid-body displacements ξ (6B × 6) of bodies at centres (B, 3) with quaternions q (B, 4)."""
    rotations = sheet.quaternion_rotation(q)
    r = centres - centres.mean(axis=0)
    out = np.zeros((centres.shape[0], DOF, 6))
    for axis in range(3):
        e = np.eye(3)[axis]
        out[:, axis, axis] = 1.0
        out[:, 0:3, 3 + axis] = np.cross(e, r)
        out[:, 3:6, 3 + axis] = np.einsum("kji,j->ki", rotations, e)
    return out.reshape(-1, 6)


def family_weights(p: SailParameters, xi: np.ndarray) -> dict[str, np.ndarray]:
    """The share of each column of ξ (6N or 6N × m) in each family, in the kinetic metric (they add to 1)."""
    xi = np.asarray(xi).reshape(np.shape(xi)[0], -1)
    m = np.sqrt(kinetic_weights(p))[:, None]
    total = np.sum(np.abs(m * xi) ** 2, axis=0)
    proj = projectors(p)
    return {f: np.sum(np.abs(m * (proj[f] @ xi)) ** 2, axis=0) / total for f in FAMILIES}


@dataclass(frozen=True)
class Modes:
    """Deformation modes of a linearisation: eigenvalues λ (s⁻¹, by descending Re λ), their displacement parts ξ
    (6N × modes), the fastest growth rate max Re λ and that mode's deflection Δu_z (ny × nx, peak +1)."""

    eigenvalues: np.ndarray
    vectors: np.ndarray
    growth_rate: float
    shape: np.ndarray


def _deformation_modes(p: SailParameters, L: sp.spmatrix, basis: np.ndarray, weights=None) -> Modes:
    """Eigen-decomposition of L restricted (Galerkin, kinetic metric) to the deformations spanned by `basis`
    (columns orthonormal in the scaled coordinates z = M^½ ξ, free of rigid-body motion): with ξ = M^-½ Q η,
    η̈ = Qᵀ M^½ (K M^-½ Q η + C M^-½ Q η̇). weights: M's diagonal (default the tiles', kinetic_weights), or
    the pair (M^½, M^-½) of a mass matrix that is not diagonal."""
    import scipy.linalg as sl

    n = L.shape[0] // 2
    if isinstance(weights, tuple):
        root, inverse = weights
        back = inverse @ basis  # M^-½ Q: ξ of each basis vector

        def half(forces):
            return root @ forces
    else:
        m = np.sqrt(kinetic_weights(p) if weights is None else weights)
        back = basis / m[:, None]

        def half(forces):
            return m[:, None] * forces

    K, C = L[n:, :n], L[n:, n:]
    k = basis.T @ half(K @ back)
    c = basis.T @ half(C @ back)
    size = basis.shape[1]
    values, vectors = sl.eig(np.block([[np.zeros((size, size)), np.eye(size)], [k, c]]))
    order = np.argsort(-values.real)
    values, xi = values[order], back @ vectors[:size, order]
    return Modes(values, xi, float(values.real[0]), _deflection(p, xi[:, 0]))


def _scaled_rigid(p: SailParameters, state, projector=None) -> np.ndarray:
    """Orthonormal columns spanning the rigid-body motions (of one family, with `projector`) in z = M^½ ξ; a
    projection below 1e-8 of the rigid motions' own size is round-off, not a direction."""
    rigid = np.sqrt(kinetic_weights(p))[:, None] * rigid_basis(p, state)
    if p.boundary != "free":  # a supported sheet has no rigid-body motion
        return rigid[:, :0]
    size = np.linalg.norm(rigid, 2)
    if projector is not None:
        rigid = projector @ rigid
    u, sigma, _ = np.linalg.svd(rigid, full_matrices=False)
    return u[:, sigma > 1e-8 * size]


def family_spectrum(p: SailParameters, state: np.ndarray | None = None, solver: str = "reduced") -> dict:
    """{family: Modes} of each family's block of L, the rigid-body motions removed (module docstring); "E" from
    its x-odd, y-even half (the other half repeats its eigenvalues). Exactly the spectrum of L where L commutes
    with the symmetries, else of its symmetric part (the group average of G L G⁻¹)."""
    import scipy.linalg as sl

    require_square(p)
    L = linearisation(p, state, solver)
    proj = projectors(p)
    m = np.sqrt(kinetic_weights(p))[:, None]
    out = {}
    for family in FAMILIES:
        P = proj["E+-" if family == "E" else family]
        z = m * family_basis(P).toarray()
        rigid = _scaled_rigid(p, state, P)
        out[family] = _deformation_modes(p, L, sl.orth(z - rigid @ (rigid.T @ z), rcond=1e-10))
    return out


@dataclass(frozen=True)
class SheetSpectrum:
    """The deformation spectrum of a sheet linearised at rest without assuming its symmetry: the modes, each mode's
    family (the one holding most of its kinetic-energy norm) and that share, the fastest mode's family, each
    family's fastest rate and the commutator defects of L."""

    modes: Modes
    families: tuple[str, ...]
    purity: np.ndarray
    family: str
    family_rates: dict[str, float]
    symmetry_defects: dict[str, float] = field(default_factory=dict)

    @property
    def growth_rate(self) -> float:
        return self.modes.growth_rate


def spectrum(p: SailParameters, state: np.ndarray | None = None, solver: str = "reduced") -> SheetSpectrum:
    """The whole deformation spectrum of L (dense: 12(N − 1) × 12(N − 1), meant for grids up to about 16 × 16),
    every mode classified by family; checks :func:`family_spectrum` where L is not symmetric."""
    require_square(p)
    L = linearisation(p, state, solver)
    rigid = _scaled_rigid(p, state)
    full, _ = np.linalg.qr(rigid, mode="complete")
    modes = _deformation_modes(p, L, full[:, rigid.shape[1] :])
    weights = np.stack([w for w in family_weights(p, modes.vectors).values()])
    families = tuple(FAMILIES[k] for k in np.argmax(weights, axis=0))
    rates = {
        f: float(modes.eigenvalues.real[[k for k, g in enumerate(families) if g == f]].max(initial=-np.inf))
        for f in FAMILIES
    }
    return SheetSpectrum(modes, families, weights.max(axis=0), families[0], rates, commutator_defects(p, L))


def _deflection(p: SailParameters, xi: np.ndarray) -> np.ndarray:
    """Δu_z of a mode (ny × nx on a grid, else one per tile), real, scaled to a peak of +1."""
    w = xi.reshape(-1, DOF)[:, 2]
    w = (w * np.exp(-1j * np.angle(w[np.argmax(np.abs(w))]))).real
    peak = w[np.argmax(np.abs(w))]
    w = w / (peak if peak else 1.0)
    return w.reshape(p.ny, p.n) if w.size == p.ny * p.n else w


def run_state(result, k: int) -> np.ndarray:
    """The solver's 13N state of sample k of a sheet run (a Result), at rest: centre displacements from the flat
    grid and unit quaternions of the xyz angles, q = q_x(φ₀) ⊗ q_y(φ₁) ⊗ q_z(φ₂) (R = R_x R_y R_z), to linearise
    the sheet frozen in the state the run has reached."""
    half = 0.5 * np.asarray(result.tile_angles[k], float)
    c, s = np.cos(half), np.sin(half)
    q = np.column_stack([c[:, 0], s[:, 0], np.zeros_like(c[:, 0]), np.zeros_like(c[:, 0])])
    for axis in (1, 2):
        r = np.zeros_like(q)
        r[:, 0], r[:, 1 + axis] = c[:, axis], s[:, axis]
        q = np.column_stack(
            [
                q[:, 0] * r[:, 0] - np.sum(q[:, 1:] * r[:, 1:], axis=1),
                q[:, 0:1] * r[:, 1:] + r[:, 0:1] * q[:, 1:] + np.cross(q[:, 1:], r[:, 1:]),
            ]
        )
    state = np.zeros((q.shape[0], 13))
    state[:, 0:3] = result.tile_centres[k] - sheet.flat_centres(result.params)
    state[:, 3:7] = q
    return state.ravel()


def deflection_families(p: SailParameters, centres: np.ndarray, a0: float | None = None) -> dict[str, np.ndarray]:
    """Each family's part of the deflection u_z of tile centres (..., N, 3) (a run's samples), as half its
    peak-to-peak spread (m, or in units of a0): u_z projected exactly (signed permutations, no round-off
    beyond the differences themselves), A1 without its mean and E without its rigid tilt (its least-squares
    fit to x and y), so that a family's part is a deformation the failure measure sees."""
    require_square(p)
    w = np.asarray(centres)[..., 2]
    flat = sheet.flat_centres(p)
    n = p.n
    grid = w.reshape(w.shape[:-1] + (n, n))  # [..., j, i]

    def mx(f):
        return f[..., :, ::-1]

    def my(f):
        return f[..., ::-1, :]

    def sw(f):
        return np.swapaxes(f, -1, -2)

    parts = {}
    for family, (px, py, ps) in PARITIES.items():
        f = 0.5 * (grid + px * mx(grid))
        f = 0.5 * (f + py * my(f))
        parts[family] = 0.5 * (f + ps * sw(f))
    odd_x, even_x = 0.5 * (grid - mx(grid)), 0.5 * (grid + mx(grid))
    parts["E"] = 0.5 * (odd_x + my(odd_x)) + 0.5 * (even_x - my(even_x))
    out = {}
    for family, f in parts.items():
        f = f.reshape(w.shape)
        if family == "A1":
            f = f - f.mean(axis=-1, keepdims=True)
        elif family == "E":
            xy = flat[:, :2] - flat[:, :2].mean(axis=0)
            f = f - (f @ xy) @ np.linalg.solve(xy.T @ xy, xy.T)
        spread = 0.5 * (f.max(axis=-1) - f.min(axis=-1))
        out[family] = spread / a0 if a0 else spread
    return out
