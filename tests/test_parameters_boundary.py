"""Boundary conditions and tip load of SailParameters (validation fields, paper Appendices A–B)."""
import math

import pytest

from lightsail_mbs.model.parameters import ParameterError, SailParameters


def test_defaults_keep_the_free_sail_and_its_dict():
    p = SailParameters()
    assert p.boundary == "free" and p.tip_load == 0.0 and p.tip_load_time_constant == 0.0
    d = p.to_dict()
    assert not {"boundary", "tip_load", "tip_load_time_constant"} & set(d)   # sweep keys unchanged
    assert SailParameters.from_dict(d) == p


def test_non_default_fields_round_trip():
    p = SailParameters(boundary="cantilever", tip_load=100.0, tip_load_time_constant=0.3)
    d = p.to_dict()
    assert d["boundary"] == "cantilever" and d["tip_load"] == 100.0
    assert SailParameters.from_dict(d) == p


def test_tip_force_is_equation_43():
    p = SailParameters(tip_load=100.0, tip_load_time_constant=0.3)
    assert p.tip_force(0.0) == 0.0
    assert p.tip_force(0.3) == pytest.approx(100.0 * (1 - math.exp(-1)), rel=1e-15)
    assert SailParameters(tip_load=-5.0).tip_force(0.0) == -5.0          # τ = 0: full load at once


@pytest.mark.parametrize("changes, name", [
    (dict(boundary="clamped"), "boundary"),
    (dict(tip_load=math.nan), "tip_load"),
    (dict(tip_load_time_constant=-1.0), "tip_load_time_constant"),
])
def test_bad_values_name_the_parameter(changes, name):
    with pytest.raises(ParameterError, match=name):
        SailParameters(**changes)
