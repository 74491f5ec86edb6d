"""Both solvers on Doppler-shifted chains run to failure (lightsail_mbs.paper.doppler): the paper's soft torsion sail
at 1e13 W/m² from β₀ = 0.1, where the sail-frame intensity falls by 0.27 % during the run, and the journey's heated,
tension-relieved Starshot-class snapshot from β₀ = 0.15. Their failure times agree within 1e-3 (or their combined
±), and so does the delay the Doppler term causes against the run at the constant intensity of the start."""

import pytest

from lightsail_mbs.paper.doppler import CASES, agreement, measure_case


@pytest.mark.parametrize("name", CASES)
def test_both_solvers_agree_on_a_doppler_shifted_chain_run_to_failure(name):
    rows = measure_case(name)
    assert all(r["failure_time"] is not None and r["constant_failure_time"] is not None for r in rows)
    agree = agreement(rows)
    assert agree["difference"] <= max(1e-3, agree["combined"])
    assert all(r["shift"] > 0 for r in rows)  # the beam dims: the shape grows more slowly and fails later
    shifts = [r["shift"] for r in rows]
    spread = sum(r["uncertainty"] + r["constant_uncertainty"] for r in rows) / rows[0]["failure_time"]
    assert abs(shifts[0] - shifts[1]) <= max(1e-2 * shifts[0], spread)


def test_the_soft_sails_delay_is_that_of_a_growth_rate_following_the_dimmed_beam():
    """At 1e13 W/m² the soft sail is far above critical (σ ∝ √I'): the delay is about r t_f/4 (0.88 of it: the
    estimate ignores the approach to failure), and it is resolved: over 20 times the solvers' combined ±."""
    rows = measure_case(next(iter(CASES)))
    for r in rows:
        assert 0.8 * r["estimate"] < r["shift"] < r["estimate"]
        assert r["dimming"] > 2e-3  # the run sees the beam dim by more than 0.2 %
    assert rows[0]["shift"] > 20 * agreement(rows)["combined"]
