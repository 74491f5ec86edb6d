"""Parameters: validation before any solving, derived quantities (paper Sec. III)."""
import math

import pytest

from lightsail_mbs import ParameterError, SailParameters, paper_case


@pytest.mark.parametrize("field, value, words", [
    ("thickness", 0.0, "thickness"),
    ("thickness", -1e-6, "> 0"),
    ("n", 1, "2 ≤ n"),
    ("n", 2.5, "integer"),
    ("density", float("nan"), "finite"),
    ("intensity", float("inf"), "finite"),
    ("model", "membrane", "rigid, torsion, tnt"),
    ("mode", 0.0, "mode"),
    ("mode", -1.5, "> 0"),
    ("amplitude", -1e-5, "≥ 0"),
    ("t_final", 0.0, "t_final"),
    ("failure_ratio", 1.0, "> 1"),
    ("output_interval", 10.0, "output_interval"),
    ("youngs_modulus", -4.5e9, "youngs_modulus"),
    ("torsional_damping", -1.0, "torsional_damping"),
    ("amplitude", 0.2, "45°"),
])
def test_bad_value_names_parameter_and_range(field, value, words):
    with pytest.raises(ParameterError) as err:
        SailParameters(**{field: value})
    assert field in str(err.value) and words in str(err.value)


def test_negative_tension_rejected():
    with pytest.raises(ParameterError, match="tension"):
        SailParameters(model="tnt", tension=-1.0)


def test_tension_only_in_tnt():
    with pytest.raises(ParameterError, match="tnt"):
        SailParameters(model="torsion", tension=1e-3)


def test_derived_quantities_follow_the_paper():
    p = SailParameters(n=30, thickness=1e-6, density=1000.0, youngs_modulus=4.5e9, width=1.0, length=1.0)
    l = 1.0 / 30
    assert p.slice_length == pytest.approx(l)
    assert p.slice_mass == pytest.approx(1000.0 * 1e-6 * l)
    assert p.slice_inertia == pytest.approx(p.slice_mass * l ** 2 / 12)
    assert p.torsional_stiffness == pytest.approx(4.5e9 * 1e-18 / 12 / l)
    # g0 = f0 / m: a flat slice is balanced exactly by the frame force
    assert p.flat_force / p.slice_mass == pytest.approx(p.nominal_acceleration, rel=1e-14)


def test_bending_defaults_per_model_and_axial_stiffness():
    assert SailParameters(model="torsion").torsional_stiffness > 0
    assert SailParameters(model="tnt").torsional_stiffness == 0.0          # paper: k_T = 0 in TnT runs
    assert SailParameters(model="tnt", bending=True).torsional_stiffness > 0
    assert SailParameters(model="rigid").torsional_stiffness == 0.0
    p = SailParameters(model="tnt", n=30, youngs_modulus=1e11, thickness=1e-6)
    assert p.axial_stiffness == pytest.approx(29 * 1e11 * 1e-6)
    assert math.isinf(p.replace(axial_springs=False).axial_stiffness)
    assert p.replace(model="torsion").bending is True


def test_roundtrip_dict_and_paper_cases():
    p = paper_case("tnt-soft")
    assert SailParameters.from_dict(p.to_dict()) == p
    assert paper_case("rigid").n == 40
    with pytest.raises(ParameterError, match="case"):
        paper_case("nope")


def test_sample_interval_default():
    assert SailParameters(t_final=6.0).sample_interval == pytest.approx(1e-3)
    assert SailParameters(t_final=0.01).sample_interval == pytest.approx(1e-5)
