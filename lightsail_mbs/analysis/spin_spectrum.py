"""The spectrum of a spinning sheet in the frame that turns with it.

The solver's ``linearise_rotating`` capability (solvers.reduced.sheet_rotating) gives L = [[0, I], [K, C]] of
the sheet's equations in the frame turning at Ω about ẑ through the centre of mass, about the initial state
(the spun equilibrium's connectors), with the centrifugal and Coriolis terms: a load that does not change
when the sail turns about that axis (unlit, a uniform beam, a round beam centred on the axis) makes the
spun state steady there, so the eigenvalues λ of L are the growth rates (Re λ) and the frequencies seen by
the turning sail.

**Transverse modes of a flat disc** (:func:`transverse_modes`). On a flat sheet the deflection Δc_z and the
tilts Δθ_x, Δθ_y decouple from the in-plane motion at first order (the Coriolis force of a velocity along ẑ
is zero, the tiles' gyroscopic terms couple only their two tilts), so the transverse block of L, rows and
columns (Δc_z, Δθ_x, Δθ_y) and their rates, holds the membrane's transverse modes. Each mode's nodal
diameters n are read from the deflection w_k of the tile centres at polar angles θ_k: the largest of the
mass-weighted Fourier powers |Σ_k m_k w_k e^(∓inθ_k)|²; its nodal circles s count the modes of the same n
below it (a pair of modes cos nθ, sin nθ counted once). model.sheet_spin.membrane_disc_frequency is the
closed form they are compared with (Lamb & Southwell).

**Deformation spectrum** (:func:`rotating_spectrum`): L restricted, as analysis.sheet_spectrum restricts
``linearise``, to the kinetic-metric complement of the six rigid-body motions; the fastest Re λ is the
growth rate of the shape. The kinetic metric (:func:`mass_metric`) is the bodies' own mass matrix: each tile's
mass and inertia tensor (a polar mesh's tiles differ, and their tensors are not diagonal in the tiles' axes).

**With a payload** (model.sheet_payload: a stem, or tethers taut at the state) the payload is one more body,
its mass and inertia in the kinetic metric; the rigid-body motions are the whole craft's.
**Rigid modes** (:func:`rigid_modes`): L restricted to those six motions (Galerkin, in that metric): the craft's
beam-riding modes with its shape held. In a round Gaussian beam centred on the spin axis a rigid craft's are the
roots s of the rigid criterion's quartic (analysis.ride3d_criterion, for U = x + iy in the inertial frame) seen
from the turning frame, s − iΩ and their conjugates, beside the axial translation's and the spin's zero pairs.
The projection is that of the held shape only at an equilibrium: it moves the bodies along the linearised rigid
motions, whose second derivatives ∂²xᵢ/∂θ_a∂θ_b (the rotations' curvature) the bodies' residual forces rᵢ at
the state (each body's mass times its acceleration less the mean) work on, so its stiffness differs from the
held shape's by −Σᵢ rᵢ·∂²xᵢ/∂θ_a∂θ_b; at an equilibrium the connectors' prestress, through L, supplies the
loads' share of that term exactly. About a start whose connectors carry none of the light's load (Ω = 0, the
map's cap) the eight beam-riding roots are off by 28 % and the spin is a real pair ±13.7/s; about
:func:`lit_state` at 40 rad/s they are the criterion's within 0.33 % (validation/spin_spectrum_rigid.md).
The lit state itself is at rest in a frame turning slightly slower than Ω: its relaxation conserves the
craft's angular momentum about the axis, so as the lit cap deforms the craft ends up turning at Ω + δ
(δ = −5.4e-3 rad/s at 40 rad/s), its connectors balancing that rate's centrifugal load. Linearised at Ω, the
radial residual forces 2Ω|δ| mᵢ ρᵢ (ρᵢ a body's distance from the axis) give the spin a stiffness and a real
pair (±0.63/s at 40 rad/s, the whole L's fastest Re λ there too); in the frame turning at Ω + δ it is ±0.07i.

**Critical spin rate** (:func:`critical_spin`): the spin from which the fastest deformation grows slower than
a threshold, by default ln 2/(6 s): a shape that grows no faster does not double within the paper's 6 s
run, the rule behind the critical edge tension (paper.sheet_physics). The spectrum is scanned on a
geometric grid of spins and the last crossing below the threshold is bisected (in log space), so the
bracket is the smallest spin from which every scanned faster spin is stable.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from lightsail_mbs.analysis import sheet_spectrum
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import planforms, sheet, sheet_payload, sheet_pose
from lightsail_mbs.model.parameters import SailParameters

TRANSVERSE = (2, 3, 4)  # Δc_z, Δθ_x, Δθ_y of the 6 generalised displacements per tile
MAX_DIAMETERS = 6  # nodal diameters tried when a mode of a sheet that is not a polar disc is classified
PAIR_TOLERANCE = 1e-3  # relative: two frequencies of one pair; |Re λ|/|Im λ| of an oscillating mode
ZERO = 1e-3  # Im λ below this × the band's top: the translation along ẑ (its Jordan pair split by round-off)
DENSE = 2000  # transverse blocks up to this size by a dense eigensolver, larger ones by shift-invert Arnoldi
SPARSE_MODES = 120
RUN_LENGTH = 6.0  # s: the paper's run, in which a stable shape must not double


def rotating_linearisation(p: SailParameters, state: np.ndarray | None = None, solver: str = "reduced"):
    """L (12N × 12N, sparse) of the named solver's ``linearise_rotating`` capability (module docstring)."""
    from lightsail_mbs.solvers import contract

    if p.model != "sheet" or p.boundary != "free":
        raise ParameterError(
            f"model={p.model!r}, boundary={p.boundary!r} is invalid for a spin spectrum: allowed a free sheet"
        )
    return contract.lookup(solver, p).capability("linearise_rotating")(p, state)


@dataclass(frozen=True)
class TransverseMode:
    """A transverse mode of a spinning flat sheet: its frequency in the turning frame ω (rad/s), its growth
    rate Re λ (1/s), nodal diameters n and nodal circles s."""

    frequency: float
    growth_rate: float
    diameters: int
    circles: int


def _transverse_block(L: sp.spmatrix, count: int) -> sp.csc_matrix:
    dof = (6 * np.arange(count)[:, None] + np.array(TRANSVERSE)).ravel()
    index = np.r_[dof, dof + 6 * count]
    return L.tocsr()[index][:, index].tocsc()


def _diameters(p: SailParameters, w: np.ndarray, largest: int) -> int:
    """The nodal diameters n ≤ largest of a deflection w (N,) (module docstring; on a polar mesh of m sectors
    n and m − n alias, so largest = m/2)."""
    mesh = planforms.mesh_of(p)
    rel = mesh.centres - mesh.centres.mean(axis=0)
    theta = np.arctan2(rel[:, 1], rel[:, 0])
    radius = np.hypot(rel[:, 0], rel[:, 1])
    ring = np.unique(np.round(radius / radius.max(), 9), return_inverse=True)[1]
    n = np.arange(largest + 1)
    power = np.zeros(n.size)
    for r in range(ring.max() + 1):  # ring by ring: an elastic mode's net Σ m w is zero (orthogonal to the translation)
        on = ring == r
        weighted = mesh.areas[on] * w[on]
        for sign in (-1, 1):
            power += np.abs(np.exp(sign * 1j * np.outer(n, theta[on])) @ weighted) ** 2
    return int(np.argmax(power))


def transverse_modes(p: SailParameters, below: float, solver: str = "reduced") -> list[TransverseMode]:
    """The oscillating transverse modes of a flat spinning sheet (|Re λ| < PAIR_TOLERANCE·|Im λ|) with
    frequencies in (ZERO·below, below) (rad/s) in its turning frame, ascending, after the translation along ẑ
    (n = s = 0, ω = 0) (module docstring): each pair ±iω once, a cos/sin pair (same n, frequencies within
    PAIR_TOLERANCE) once; the heavily damped modes of the stiff connectors are left out."""
    import scipy.linalg as sl
    from scipy.sparse.linalg import eigs

    L = rotating_linearisation(p, None, solver)
    count = L.shape[0] // 12
    block = _transverse_block(L, count)
    if block.shape[0] <= DENSE:
        values, vectors = sl.eig(block.toarray())
    else:  # shift-invert about the middle of the band: the SPARSE_MODES eigenvalues nearest to it
        start = np.ones(block.shape[0])  # a fixed start vector: the same modes on every call
        values, vectors = eigs(block, k=SPARSE_MODES, sigma=0.5j * below, v0=start)
    oscillating = (values.imag > ZERO * below) & (np.abs(values.real) < PAIR_TOLERANCE * values.imag)
    keep = np.nonzero(oscillating & (values.imag < below))[0]
    keep = keep[np.argsort(values[keep].imag)]
    modes, paired = [TransverseMode(0.0, 0.0, 0, 0)], set()  # (0, 0): the translation along ẑ, a null vector
    for k in keep:
        n = _diameters(p, vectors[0 : 3 * count : 3, k], p.ny // 2 if p.planform == "disc" else MAX_DIAMETERS)
        frequency = float(values[k].imag)
        previous = [m for m in modes if m.diameters == n]
        close = previous and abs(previous[-1].frequency - frequency) <= PAIR_TOLERANCE * frequency
        if n > 0 and close and len(modes) - 1 not in paired:
            paired.add(modes.index(previous[-1]))
            continue
        modes.append(TransverseMode(frequency, float(values[k].real), n, len(previous)))
    return modes


@dataclass(frozen=True)
class RotatingSpectrum:
    """The deformation spectrum of a spinning sheet in its turning frame: eigenvalues λ (1/s, by descending
    Re λ), each mode's share of kinetic energy in the tiles' tilts (the rest in their centres' motion), the
    fastest growth rate, and the fastest of the modes that move mostly the centres (tilt share below ½: the
    sheet's shape; a mode of mostly tilts is the tiles' own rotation, which a membrane does not have)."""

    eigenvalues: np.ndarray
    tilt_shares: np.ndarray

    @property
    def growth_rate(self) -> float:
        return float(self.eigenvalues.real[0])

    @property
    def tilt_share(self) -> float:
        return float(self.tilt_shares[0])

    @property
    def shape_rate(self) -> float:
        return float(self.eigenvalues.real[self.tilt_shares < 0.5].max(initial=-np.inf))


def lit_state(p: SailParameters, solver: str = "reduced") -> np.ndarray:
    """The solver's 13B state of the spinning sheet case p at rest in its turning frame under its beam, centred
    on the spin axis (the ``spun_equilibrium`` capability, lit; module docstring: the relaxed craft turns at
    Ω + δ, slightly off the frame's rate)."""
    from lightsail_mbs.solvers import contract

    centres, quaternions = contract.lookup(solver, p).capability("spun_equilibrium")(p, lit=True)
    rows = np.zeros((len(centres), 13))
    rows[:, 0:3] = centres - _start(p)[0]
    rows[:, 3:7] = quaternions
    return rows.ravel()


def _start(p: SailParameters) -> tuple:
    """(reference points (B, 3), start centres (B, 3), quaternions (B, 4), the payload or None) of every body
    (the tiles, then a payload) of the case's start (model.sheet_pose.initial_motion; a spun equilibrium's shape
    with spin_equilibrium)."""
    from lightsail_mbs.solvers.spun_start import spun_shape

    centres, q = sheet.initial_quaternions(p)
    payload = sheet_payload.payload(p, centres, q, sheet.connectors(p, centres, q))
    flat = sheet.flat_centres(p)
    start, quaternions, _, _ = sheet_pose.initial_motion(p, centres, q, payload, spun_shape(p))
    return (flat if payload is None else np.vstack([flat, payload.start])), start, quaternions, payload


def mass_metric(p: SailParameters) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """(M^½, M^-½) (6B × 6B, block diagonal) of the bodies' mass matrix M on ξ: per body m I₃ for Δc and its
    inertia tensor J (its own axes) for Δθ_b, each tile's own (a polar mesh's differ from tile to tile and are
    not diagonal), then a payload's."""
    tiles = sheet.Tiles.of(p)
    masses, inertias = tiles.masses, tiles.inertias
    payload = _start(p)[3]
    if payload is not None:
        masses, inertias = np.r_[masses, payload.mass], np.concatenate([inertias, payload.inertia[None]])
    values, axes = np.linalg.eigh(inertias)
    blocks = []
    for power in (0.5, -0.5):
        block = np.zeros((len(masses), 6, 6))
        block[:, 0:3, 0:3] = (masses**power)[:, None, None] * np.eye(3)
        block[:, 3:6, 3:6] = np.einsum("kij,kj,klj->kil", axes, values**power, axes)
        blocks.append(sp.block_diag(list(block), format="csr"))
    return blocks[0], blocks[1]


def _bodies(p: SailParameters, state: np.ndarray | None) -> tuple[tuple, np.ndarray]:
    """((M^½, M^-½) of :func:`mass_metric`, the rigid-body motions orthonormal in z = M^½ ξ (6B × 6)) of the
    bodies at `state` (default the case's start): the rigid motions about the bodies' centres and orientations
    (a supported sheet: none)."""
    flat, centres, quaternions, payload = _start(p)
    if state is not None:
        rows = np.asarray(state, float).reshape(-1, 13)
        centres, quaternions = flat + rows[:, 0:3], rows[:, 3:7]
    half, inverse = mass_metric(p)
    rigid = half @ sheet_spectrum.rigid_motions(centres, quaternions)
    if p.boundary != "free":
        return (half, inverse), rigid[:, :0]
    u, sigma, _ = np.linalg.svd(rigid, full_matrices=False)
    return (half, inverse), u[:, sigma > 1e-8 * sigma.max()]


def rotating_spectrum(p: SailParameters, solver: str = "reduced", state: np.ndarray | None = None) -> RotatingSpectrum:
    """The spectrum of L in the turning frame about `state` (default the case's start; :func:`lit_state`: the
    lit equilibrium) restricted to the deformations (module docstring; dense, meant for grids up to about
    12 × 12), the case's payload included (a stem, or tethers taut at the state)."""
    L = rotating_linearisation(p, state, solver)
    metric, rigid = _bodies(p, state)
    full, _ = np.linalg.qr(rigid, mode="complete")
    modes = sheet_spectrum._deformation_modes(p, L, full[:, rigid.shape[1] :], metric)
    energy = (np.abs(metric[0] @ modes.vectors) ** 2).reshape(-1, 6, modes.vectors.shape[1])
    shares = energy[:, 3:].sum(axis=(0, 1)) / energy.sum(axis=(0, 1))
    return RotatingSpectrum(modes.eigenvalues, shares)


def rigid_modes(p: SailParameters, solver: str = "reduced", state: np.ndarray | None = None) -> np.ndarray:
    """The eigenvalues λ (12, by descending Re λ; 1/s) of L in the turning frame about `state` restricted to the
    craft's six rigid-body motions (Galerkin, kinetic metric; module docstring): its beam-riding modes with its
    shape held."""
    L = rotating_linearisation(p, state, solver)
    metric, rigid = _bodies(p, state)
    return sheet_spectrum._deformation_modes(p, L, rigid, metric).eigenvalues


def critical_spin(
    p: SailParameters,
    spins: tuple[float, float],
    steps: int = 28,
    width: float = 1.05,
    threshold: float = math.log(2.0) / RUN_LENGTH,
) -> tuple[float, float]:
    """(Ω₋, Ω₊) (rad/s): the bracket, at most `width` wide, of the smallest spin in spins = (low, high) from
    which the fastest deformation of p spun at Ω (rotating_spectrum) grows slower than threshold (1/s) at
    every scanned faster spin (module docstring); (0, low) if it is already stable at low, (high, inf) if
    not at high."""
    low, high = spins
    if not 0.0 < low < high or width <= 1.0 or steps < 1:
        raise ParameterError(
            f"spins={spins!r}, width={width!r}, steps={steps!r} are invalid: 0 < low < high, width > 1"
        )
    grid = low * (high / low) ** (np.arange(steps + 1) / steps)
    grows = [rotating_spectrum(p.replace(spin_rate=float(w))).growth_rate >= threshold for w in grid]
    if not any(grows):
        return 0.0, low
    last = int(np.nonzero(grows)[0][-1])
    if last == steps:
        return high, math.inf
    below, above = float(grid[last]), float(grid[last + 1])
    while above / below > width:
        middle = math.sqrt(below * above)
        if rotating_spectrum(p.replace(spin_rate=middle)).growth_rate >= threshold:
            below = middle
        else:
            above = middle
    return below, above
