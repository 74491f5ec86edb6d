"""The spinning craft's rigid modes against the rigid beam-riding criterion: `nice -n 10 python
validation/spin_spectrum_rigid.py` (writes validation/spin_spectrum_rigid.md; ~5 min of one core).

The spin map's craft (paper.spinning_maps: the 25-tile disc on a cap of R_c = 1 m, a stem payload of the sail's
mass at d = 1.15 d*, the beam centred on the spin axis), of its stiff film (E = 4.5e13 Pa) and of a very stiff
one (paper.spinning_beam.FILMS), in four ways, all in the frame turning at the rate named (λ = s − iΩ of the
criterion's inertial roots s and their conjugates):

* **criterion**: the quartic of analysis.ride3d_criterion (undamped) on the sphere R_c;
* **shape held**: the craft moved as one rigid body by finite displacements and rotations about its centre of
  mass G (step 1e-4 m and rad) in the in-house solver's turning-frame right-hand side
  (solvers.reduced.sheet_rotating.TurningFrame.rates): K from central differences of its net force and its
  torque about G, where the connectors' forces cancel whatever the state; the mass and velocity terms as in
  the next;
* **rigid_modes**: analysis.spin_spectrum.rigid_modes, the Galerkin projection of L on the six linearised rigid
  motions in the bodies' kinetic metric (each tile's mass and inertia tensor);
* **old metric**: the same projection in the metric it had before, the largest tile's mass and inertia on
  every tile (analysis.sheet_spectrum.kinetic_weights).

The Galerkin stiffness differs from the held shape's by the curvature of the rotations, −Σᵢ rᵢ·∂²xᵢ/∂θ_a∂θ_b,
rᵢ = mᵢ(aᵢ − ā) each body's residual force at the state (ā the mass-weighted mean acceleration): zero at an
equilibrium (the connectors' prestress supplies it through L), not at a start whose connectors carry no load.
The column "identity" is ‖K_held − K_Galerkin − that term‖/‖K_held‖.

Part A linearises the start (model.sheet_pose: the connectors unloaded) without spin. Part B linearises the lit
spun equilibrium (the relaxation of solvers.reduced.sheet_relax.relax, repeated here to read its final
velocities): it conserves the craft's angular momentum about the axis (the rigid motion is not damped), so as
the lit cap deforms the craft ends up turning at Ω + δ, δ measured from its bodies' velocities relative to
the frame; the rows "at Ω + δ" linearise in the frame turning at that rate (TurningFrame's rate set to it,
the connectors' spun prestrain of Ω kept).
"""

from __future__ import annotations

import contextlib
import math
import os
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402
import scipy.sparse as sp  # noqa: E402
from scipy.optimize import linear_sum_assignment  # noqa: E402
from scipy.spatial.transform import Rotation  # noqa: E402

from lightsail_mbs.analysis import sheet_spectrum, spin_spectrum  # noqa: E402
from lightsail_mbs.analysis.ride3d_criterion import cap_criterion  # noqa: E402
from lightsail_mbs.model import sheet  # noqa: E402
from lightsail_mbs.paper import spinning_maps as maps  # noqa: E402
from lightsail_mbs.paper.spinning_beam import FILMS  # noqa: E402
from lightsail_mbs.solvers.reduced import sheet_relax, sheet_rotating  # noqa: E402
from lightsail_mbs.solvers.reduced.sheet import SheetModel, state_scales  # noqa: E402
from lightsail_mbs.solvers.reduced.sheet_kernels import STATE  # noqa: E402
from lightsail_mbs.solvers.reduced.sheet_radau import SheetRadau  # noqa: E402
from lightsail_mbs.studies.tables import markdown_table  # noqa: E402

HERE = Path(__file__).resolve().parent
RATIO = 1.15  # d/d*
STEP = 1e-4  # the held shape's finite displacement (m) and rotation (rad)


def case(spin: float, film: str) -> tuple:
    p = maps.BASE.replace(billow_radius=1.0, spin_rate=spin, **FILMS.get(film, {}))
    d = RATIO * maps.d_star(p)
    return p.replace(payload_stem=d), d


@contextlib.contextmanager
def frame_rate(offset: float):
    """TurningFrame's rate Ω + offset (the connectors' prestrain of Ω kept) inside the block."""
    original = sheet_rotating.TurningFrame.__init__

    def shifted(self, p, state=None):
        original(self, p, state)
        self.spin += offset

    sheet_rotating.TurningFrame.__init__ = shifted
    try:
        yield
    finally:
        sheet_rotating.TurningFrame.__init__ = original


def relaxed(p) -> tuple[np.ndarray, float]:
    """(the lit spun state (13B), δ (rad/s): the craft's rigid spin relative to the frame at the end)."""
    model = SheetModel(sheet_relax.relaxing_case(p, True), frame="turning")
    spin = float(np.linalg.norm(model.turning.spin))
    damped = sheet_relax.DampedTurning(model, sheet_relax.DAMPING * spin)
    turn = 2.0 * math.pi / spin
    scales = state_scales(p).reshape(-1, STATE)
    atol = sheet_relax.RTOL * np.vstack([scales, scales[: model.count - model.lit]]).ravel()
    solver = SheetRadau(
        damped.rhs, 0.0, model.y0(), sheet_relax.RELAX_TURNS * turn, rtol=sheet_relax.RTOL, atol=atol,
        jac=damped.jacobian, kinematics=model.kinematics, X=model.position_indices, V=model.velocity_indices,
        h_max=0.25 * turn,
    )  # fmt: skip
    while solver.status == "running":
        solver.step()
    rows = solver.y.reshape(-1, STATE)
    delta = float((sheet.quaternion_rotation(rows[:1, 3:7])[0] @ damped.rigid(rows)[0, 3:6])[2])  # Ω_r · ẑ
    state = np.zeros((model.count, 13))
    state[:, 0:3] = model.flat + rows[:, 0:3] - spin_spectrum._start(p)[0]
    state[:, 3:7] = rows[:, 3:7] / np.linalg.norm(rows[:, 3:7], axis=1)[:, None]
    return state.ravel(), delta


def rigid_blocks(p, state) -> dict:
    """The six rigid motions about G at `state`: mass, Galerkin K and C, the held shape's K, the curvature term."""
    frame = sheet_rotating.TurningFrame(p, state)
    count, masses = frame.count, frame.model.masses
    inertia, rotations = frame.model.inertia, sheet.quaternion_rotation(frame.quaternions)
    arm = frame.centres - masses @ frame.centres / masses.sum()
    V = np.zeros((count, 6, 6))
    for a in range(3):
        e = np.eye(3)[a]
        V[:, a, a] = 1.0
        V[:, 0:3, 3 + a] = np.cross(e, arm)
        V[:, 3:6, 3 + a] = np.einsum("kji,j->ki", rotations, e)
    V = V.reshape(-1, 6)
    blocks = np.zeros((count, 6, 6))
    blocks[:, 0:3, 0:3] = masses[:, None, None] * np.eye(3)
    blocks[:, 3:6, 3:6] = inertia
    M = sp.block_diag(list(blocks), format="csr")
    L = spin_spectrum.rotating_linearisation(p, state)
    n = L.shape[0] // 2

    def held(q):
        turn = Rotation.from_rotvec(q[3:]).as_matrix()
        xi = np.zeros((count, 6))
        xi[:, 0:3] = q[:3] + arm @ turn.T - arm
        xi[:, 3:6] = np.einsum("kji,j->ki", rotations, q[3:])
        rates = frame.rates(xi, np.zeros((count, 6)))
        force = masses[:, None] * rates[:, 6:9]
        torque = np.einsum("ij,kjl,klm,km->ki", turn, rotations, inertia, rates[:, 9:12])
        return np.r_[force.sum(axis=0), (np.cross(arm @ turn.T, force) + torque).sum(axis=0)]

    K_held = np.column_stack([(held(STEP * e) - held(-STEP * e)) / (2 * STEP) for e in np.eye(6)])
    rates = frame.rates(np.zeros((count, 6)), np.zeros((count, 6)))[:, 6:9]
    residual = masses[:, None] * (rates - masses @ rates / masses.sum())
    curvature = np.zeros((6, 6))
    for a in range(3):
        for b in range(3):
            Ea, Eb = (np.cross(np.eye(3)[i], np.eye(3)).T for i in (a, b))  # [e ×]
            curvature[3 + a, 3 + b] = np.sum(residual * (arm @ (0.5 * (Ea @ Eb + Eb @ Ea)).T))
    return dict(
        M=V.T @ M @ V, K=V.T @ M @ (L[n:, :n] @ V), C=V.T @ M @ (L[n:, n:] @ V), K_held=K_held,
        curvature=curvature, L=L,
    )  # fmt: skip


def eigenvalues(M, K, C) -> np.ndarray:
    A = np.block([[np.zeros((6, 6)), np.eye(6)], [np.linalg.solve(M, K), np.linalg.solve(M, C)]])
    return np.linalg.eigvals(A)


def matched(values: np.ndarray, target: np.ndarray) -> tuple[float, float, float]:
    """(largest |λ − λ_c|/|λ_c| of the eight nearest the criterion's, the other four's largest |λ|, max Re λ)."""
    rows, cols = linear_sum_assignment(np.abs(values[:, None] - target[None, :]))
    error = float(np.max(np.abs(values[rows] - target[cols]) / np.abs(target[cols])))
    other = np.delete(values, rows)
    return error, float(np.abs(other).max()), float(values.real.max())


def cell(values, target) -> str:
    error, other, fastest = matched(values, target)
    return f"{error:.2%}; {other:.3g}; {fastest:+.3g}"


def row(label, p, d, state, spin) -> dict:
    c = cap_criterion(p, maps.SAIL_MASS, d, spin)
    target = np.r_[c.roots - 1j * spin, np.conj(c.roots - 1j * spin)]
    b = rigid_blocks(p, state)
    old = sheet_spectrum.kinetic_weights(p)
    old = np.r_[old, [p.payload_mass] * 3, np.diag(spin_spectrum._start(p)[3].inertia)]
    basis = np.sqrt(old)[:, None] * sheet_spectrum.rigid_motions(*_pose(p, state))
    basis = np.linalg.svd(basis, full_matrices=False)[0]
    held = eigenvalues(b["M"], b["K_held"], b["C"])
    identity = np.linalg.norm(b["K_held"] - b["K"] - b["curvature"]) / np.linalg.norm(b["K_held"])
    whole = np.linalg.eigvals(b["L"].toarray())
    out = {
        "case": label,
        "criterion: frequencies |Im λ| (1/s)": ", ".join(f"{v:.2f}" for v in np.sort(np.abs(target.imag))[::2]),
        "shape held": cell(held, target),
        "rigid_modes": cell(spin_spectrum.rigid_modes(p, state=state), target),
        "old metric": cell(sheet_spectrum._deformation_modes(p, b["L"], basis, old).eigenvalues, target),
        "criterion on R_fit: R_fit (m), fastest Re s (1/s)": on_fit(p, d, state, spin),
        "spin stiffness: Galerkin, held (N m)": f"{b['K'][5, 5]:.2g}, {b['K_held'][5, 5]:.2g}",
        "identity": f"{identity:.1e}",
        "whole L: fastest Re λ (1/s)": f"{whole.real.max():+.3g}",
    }
    print(out, flush=True)
    return out


def on_fit(p, d, state, spin) -> str:
    """The criterion on the sphere through the state's apex and rim tiles, R_fit = (r² + s²)/(2s)."""
    tiles = _pose(p, state)[0][:-1]
    radius = np.hypot(*(tiles[:, :2] - tiles[:, :2].mean(axis=0)).T)
    sag = abs(float(tiles[np.argmax(radius), 2] - tiles[np.argmin(radius), 2]))
    fit = (radius.max() ** 2 + sag**2) / (2 * sag)
    return f"{fit:.2f}, {cap_criterion(p.replace(billow_radius=fit), maps.SAIL_MASS, d, spin).growth_rate:+.3g}"


def _pose(p, state):
    flat, centres, quaternions, _ = spin_spectrum._start(p)
    if state is None:
        return centres, quaternions
    rows = state.reshape(-1, 13)
    return flat + rows[:, 0:3], rows[:, 3:7]


def report() -> str:
    rows = []
    for film in ("paper's stiff film", "very stiff"):
        p, d = case(0.0, film)
        rows.append(row(f"{film}, Ω = 0, start (unloaded connectors)", p, d, None, 0.0))
    deltas = []
    film = "paper's stiff film"  # the very stiff film's lit relaxation did not end within 5 min
    for spin in (40.0, 80.0, 120.0):
        p, d = case(spin, film)
        state, delta = relaxed(p)
        deltas.append(f"{film}, Ω = {spin:g}: δ = {delta:+.3g} rad/s")
        rows.append(row(f"{film}, Ω = {spin:g}, lit spun state, frame at Ω", p, d, state, spin))
        with frame_rate(delta):
            rows.append(row(f"{film}, Ω = {spin:g}, lit spun state, frame at Ω + δ", p, d, state, spin + delta))
    lines = [
        "# The spinning craft's rigid modes against the rigid criterion",
        "",
        "Made by `nice -n 10 python validation/spin_spectrum_rigid.py` (its docstring says what each column is).",
        "",
        f"The map's craft (25-tile disc, R_c = 1 m, stem payload of the sail's mass at d = {RATIO:g} d*, beam on the",
        "axis), in the frame turning at the rate named. Each method's cell: the largest relative distance of the",
        "eight eigenvalues nearest the criterion's eight from them; the largest |λ| of its other four (the axial",
        "translation's and the spin's, zero for a rigid craft); its fastest Re λ (1/s).",
        "",
        markdown_table(rows),
        "",
        "The lit craft's spin relative to the frame at the end of the relaxation: " + "; ".join(deltas) + ".",
        "R_fit: the sphere through the state's apex and rim tiles (the lit cap flattens from 80 rad/s).",
        "",
    ]
    return "\n".join(lines)


if __name__ == "__main__":
    text = report()
    (HERE / "spin_spectrum_rigid.md").write_text(text)
    print(text)
