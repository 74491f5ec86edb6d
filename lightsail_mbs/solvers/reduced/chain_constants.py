"""The constants of one chain as the float vector the compiled kernels read, and the rows of their workspace.

`constants(model)` packs a ChainModel (kinematics.py): slice mass and inertia, springs and dampers, end
tension, payload, at the indices named below, followed by the case's physics terms as model/terms packs
them (the load law: radiation through beam and optics, frame force). The kernels of dynamics.py,
joints.py, newton.py, radau.py and dop853.py read them by these names.
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.model import heating, payload, terms, world_line
from lightsail_mbs.model.terms import bodies
from lightsail_mbs.model.terms.bodies import CHAIN_ROWS, X, Y
from lightsail_mbs.solvers.reduced.kinematics import ChainModel

# layout of the constants vector of one chain (read by the compiled kernels); the packed physics terms follow
(
    N,
    MASS,
    INERTIA,
    HALF,
    K_T,
    C_T,
    K_S,
    C_S,
    TENSION,
    EXTENSIBLE,
    PAY_SLICE,
    PAY_MASS,
    PAY_INERTIA,
    PAY_CE,
    PAY_CP,
    PAY_RE,
    PAY_RP,
    REST_TURN,
    FRAME,
    WORLD,
    WORLD_RATE,
    HEAT,
) = range(22)
N_CONSTANTS = 22  # the packed terms (model/terms: terms.pack(p, "chain")) start here

# rows of the workspace of one right-hand-side evaluation: first the slices as the terms read them
# (model/terms/bodies.py), then the sweeps' own rows
ABSCISSA, HEIGHT, THETA, COS, SIN, VX, VY, OMEGA = (
    X,
    Y,
    bodies.THETA,
    bodies.COS,
    bodies.SIN,
    bodies.VX,
    bodies.VY,
    bodies.OMEGA,
)
(ARM, AX, AY, AL, I_XX, I_XY, I_YY, U_XX, U_XY, U_YY, R_X, R_Y) = range(CHAIN_ROWS, CHAIN_ROWS + 12)
WORK_ROWS = CHAIN_ROWS + 12


def constants(model: ChainModel, world: bool = False) -> np.ndarray:
    """The chain's constants as the float vector the compiled kernels read (indices above), then its packed
    physics terms (the load law: radiation through beam and optics, frame force), then a heated film's table
    (k[HEAT] its start, 0: none). world: the state ends with the
    sail's world line (a run of a case with integrated_trajectory; the analyses' states are the chain's alone)."""
    p = model.params
    k = np.zeros(N_CONSTANTS)
    k[N], k[MASS], k[INERTIA], k[HALF] = model.n, model.mass, model.inertia, model.half_length
    k[K_T], k[C_T] = model.torsional_stiffness, model.torsional_damping
    k[K_S], k[C_S], k[TENSION] = model.axial_stiffness, model.axial_damping, model.tension
    k[EXTENSIBLE] = float(model.extensible)
    k[REST_TURN] = p.rest_turn  # the springs' rest angle between neighbours (a sail made curved)
    k[FRAME] = -p.slice_mass * p.nominal_acceleration  # −m g₀ on each slice (the payload's is scaled from it)
    # the sail's world line in the state (model/world_line.py): two more coordinates after the chain's, and g₀/c
    k[WORLD], k[WORLD_RATE] = float(world), world_line.rate_constant(p)
    k[PAY_SLICE] = -1.0  # a payload (model/payload.py): its composite slice j, M, J_c, ρ_c, ρ in slice j's axes
    attached = payload.attachment(p)
    if attached is not None:
        k[PAY_SLICE], k[PAY_MASS], k[PAY_INERTIA] = attached.slice_index, attached.mass, attached.inertia
        k[PAY_CE], k[PAY_CP] = attached.centre_along, attached.centre_across
        k[PAY_RE], k[PAY_RP] = attached.along, attached.across
    packed = terms.pack(p, "chain")
    if not p.heated:
        return np.concatenate([k, packed])
    k[HEAT] = N_CONSTANTS + packed.size  # the heated film's table (model/heating.py) after the packed terms
    return np.concatenate([k, packed, heating.table(p)])
