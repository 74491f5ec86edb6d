"""The compiled O(n) joint-force recursion (ChainDynamics) against the dense Lagrangian solution M⁻¹(Q − c),
and its linear cost in n."""

import numpy as np
import pytest

from lightsail_mbs import SailParameters
from lightsail_mbs.solvers.reduced.dynamics import ChainDynamics
from lightsail_mbs.solvers.reduced.kinematics import ChainModel, dense_accelerations
from tests.solvers.reduced.chains import GAUSSIAN, IDS, MODELS, random_state


# ---- O(n) accelerations ---------------------------------------------------------------------
@pytest.mark.parametrize("p", MODELS + [GAUSSIAN], ids=IDS + ["gaussian-beam"])
def test_recursive_accelerations_equal_dense_solution(p):
    """The compiled O(n) joint-force solution equals M⁻¹(Q − c) (with the shared load model of
    loads.py), one state and a batch of states."""
    model = ChainModel.from_params(p)
    dyn = ChainDynamics(model)
    states = [random_state(model) for _ in range(4)]
    dense = np.stack([dense_accelerations(model, q, qd) for q, qd in states], axis=1)
    scale = np.abs(dense).max()
    batch = dyn.accelerations(np.stack([s[0] for s in states], 1), np.stack([s[1] for s in states], 1))
    np.testing.assert_allclose(batch, dense, rtol=0, atol=1e-11 * scale)
    stacked = dyn.rhs(0.0, np.concatenate([np.stack([s[0] for s in states], 1), np.stack([s[1] for s in states], 1)]))
    np.testing.assert_allclose(stacked[model.dof :], dense, rtol=0, atol=1e-11 * scale)
    for k, (q, qd) in enumerate(states):
        single = dyn.rhs(0.0, np.concatenate([q, qd]))[model.dof :]
        np.testing.assert_allclose(single, dense[:, k], rtol=0, atol=1e-11 * scale)


def test_rhs_cost_grows_linearly_with_n():
    """No dense algebra in the right-hand side: 30× more slices cost far less than 30²×."""
    import timeit

    cost = {}
    for n in (100, 3000):
        model = ChainModel.from_params(SailParameters(n=n, defect_amplitude=1e-6))
        dyn = ChainDynamics(model)
        y = np.concatenate(random_state(model, 1e-3))
        cost[n] = min(timeit.repeat(lambda dyn=dyn, y=y: dyn.rhs(0.0, y), number=20, repeat=5))
    assert cost[3000] / cost[100] < 30 * 3
