"""The chain's post-step sampler (solvers.exudyn.sampler): a step whose record an interrupt cut between its
appends (Ctrl-C lands between any two bytecodes of the post-step function) is dropped, not indexed."""

import numpy as np

from lightsail_mbs.solvers.exudyn.sampler import Sampler


def test_a_step_record_cut_by_an_interrupt_is_dropped():
    sampler = Sampler.__new__(Sampler)
    sampler.times = np.array([0.0, 0.1, 0.2])
    rate = np.array([1.0, 2.0])
    state = [rate * t for t in (0.0, 0.1, 0.2)]
    sampler.steps_t = [0.0, 0.1, 0.2]  # the third step: t, q and q̇ appended, q̈ not
    sampler.steps_q = list(state)
    sampler.steps_v = [rate, rate, rate]
    sampler.steps_a = [0 * rate, 0 * rate]
    sampler.q, sampler.v = [state[0]], [rate]
    sampler._sample(final=True)
    assert len(sampler.q) == 2 and np.allclose(sampler.q[1], state[1]) and np.allclose(sampler.v[1], rate)
    assert [len(kept) for kept in (sampler.steps_t, sampler.steps_q, sampler.steps_v, sampler.steps_a)] == [1] * 4
