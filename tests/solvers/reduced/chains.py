"""Small chains of every model and random states, shared by the reduced solver's kinematics and
dynamics tests."""

import numpy as np

from lightsail_mbs import SailParameters
from lightsail_mbs.solvers.reduced.kinematics import ChainModel

rng = np.random.default_rng(2024)

TORSION = SailParameters(n=6, youngs_modulus=4.5e9, intensity=1e9, torsional_damping=2e-9)
TNT = SailParameters(
    model="tnt",
    n=5,
    tension=1e-3,
    youngs_modulus=1e11,
    bending=True,
    intensity=1e9,
    torsional_damping=1e-9,
    axial_damping=1e-2,
)
TNT_RIGID = SailParameters(model="tnt", n=6, tension=1e-3, axial_springs=False, intensity=1e9)
RIGID = SailParameters(model="rigid", n=7, intensity=1e11)
GAUSSIAN = SailParameters(n=9, intensity=1e9, beam_waist=0.3, reflectivity=0.8, absorptivity=0.1)
MODELS = [TORSION, TNT, TNT_RIGID, RIGID]
IDS = ["torsion", "tnt-extensible", "tnt-inextensible", "rigid"]


def random_state(model: ChainModel, spread=0.4):
    q = rng.normal(size=model.dof) * spread
    qd = rng.normal(size=model.dof) * 3.0
    if model.extensible:
        q[model.n + 2 :] *= 1e-2
        qd[model.n + 2 :] *= 1e-2
    return q, qd
