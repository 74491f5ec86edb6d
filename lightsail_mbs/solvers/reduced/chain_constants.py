"""The constants of one chain as the float vector the compiled kernels read, and the rows of their workspace.

`constants(model)` packs a ChainModel (kinematics.py) and its case's load law: slice mass and inertia,
springs and dampers, end tension, beam, optics (a packed optical table after the constants), payload and
frame force, at the indices named below. The kernels of dynamics.py, joints.py, newton.py, radau.py
and dop853.py read them by these names.
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.model import loads, optics, payload
from lightsail_mbs.model.parameters import SPEED_OF_LIGHT
from lightsail_mbs.solvers.reduced.kinematics import ChainModel

# layout of the constants vector of one chain (read by the compiled kernels)
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
    INTENSITY,
    AREA_C,
    WAIST,
    CENTER,
    REFL,
    ABSORB,
    MEAN_INTENSITY,
    EXTENSIBLE,
    UNIFORM,
    PAY_SLICE,
    PAY_MASS,
    PAY_INERTIA,
    PAY_CE,
    PAY_CP,
    PAY_RE,
    PAY_RP,
    REST_TURN,
    FRAME,
    FRAME_EXCESS,
    MOMENTUM,
) = range(29)
N_CONSTANTS = 29

# rows of the workspace of one right-hand-side evaluation
(COS, SIN, ARM, ABSCISSA, AX, AY, AL, I_XX, I_XY, I_YY, U_XX, U_XY, U_YY, R_X, R_Y) = range(15)
WORK_ROWS = 15


def constants(model: ChainModel) -> np.ndarray:
    """The chain's constants as the float vector the compiled kernels read (indices above)."""
    p = model.params
    k = np.zeros(N_CONSTANTS)
    k[N], k[MASS], k[INERTIA], k[HALF] = model.n, model.mass, model.inertia, model.half_length
    k[K_T], k[C_T] = model.torsional_stiffness, model.torsional_damping
    k[K_S], k[C_S], k[TENSION] = model.axial_stiffness, model.axial_damping, model.tension
    k[INTENSITY], k[AREA_C] = p.intensity, p.slice_length * p.width / SPEED_OF_LIGHT
    k[WAIST] = 1.0 if p.uniform_beam else p.beam_waist
    k[CENTER], k[REFL], k[ABSORB] = p.beam_center, p.reflectivity, p.absorptivity
    k[MEAN_INTENSITY] = p.mean_intensity  # the net form's frame force is −(2R + α) Ī l W/c
    k[EXTENSIBLE], k[UNIFORM] = float(model.extensible), float(p.uniform_beam)
    k[REST_TURN] = p.rest_turn  # the springs' rest angle between neighbours (a sail made curved)
    k[FRAME] = -p.slice_mass * p.nominal_acceleration  # −m g₀ on each slice (the payload's is scaled from it)
    k[MOMENTUM] = p.normal_momentum
    k[PAY_SLICE] = -1.0  # a payload (model/payload.py): its composite slice j, M, J_c, ρ_c, ρ in slice j's axes
    attached = payload.attachment(p)
    if attached is not None:
        k[PAY_SLICE], k[PAY_MASS], k[PAY_INERTIA] = attached.slice_index, attached.mass, attached.inertia
        k[PAY_CE], k[PAY_CP] = attached.centre_along, attached.centre_across
        k[PAY_RE], k[PAY_RP] = attached.along, attached.across
        k[FRAME_EXCESS] = loads.frame_force_excess(p)  # c_n(0) Ī l W/c − m g₀ (0 without a payload)
    if p.optics is not None:  # an optical table: the slices' flags and the packed table follow the constants
        k = np.concatenate([k, optics.solver_block(p)])
    return k
