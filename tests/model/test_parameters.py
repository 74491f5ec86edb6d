"""Parameters: validation before any solving, derived quantities (paper Sec. III), supports and tip load
(validation fields, Appendices A–B), material damping, the dict form and the names of older records."""

import math

import pytest
from hypothesis import given

from lightsail_mbs import ParameterError, SailParameters, paper_case
from tests.strategies import EXAMPLES, any_case_kwargs, check_property


@pytest.mark.parametrize(
    "field, value, words",
    [
        ("thickness", 0.0, "thickness"),
        ("thickness", -1e-6, "> 0"),
        ("n", 1, "2 ≤ n"),
        ("n", 2.5, "integer"),
        ("density", float("nan"), "finite"),
        ("intensity", float("inf"), "finite"),
        ("model", "membrane", "rigid, torsion, tnt"),
        ("defect_mode", 0.0, "mode"),
        ("defect_mode", -1.5, "> 0"),
        ("defect_amplitude", -1e-5, "≥ 0"),
        ("youngs_modulus", -4.5e9, "youngs_modulus"),
        ("torsional_damping", -1.0, "torsional_damping"),
        ("defect_amplitude", 0.2, "45°"),
        ("defect_amplitude", 1e-250, "underflow"),
        ("defect_mode_count", 0, "defect_mode_count"),
    ],
)
def test_bad_value_names_parameter_and_range(field, value, words):
    with pytest.raises(ParameterError) as err:
        SailParameters(**{field: value})
    assert field in str(err.value) and words in str(err.value)


def test_run_control_is_not_a_parameter():
    """t_final & co. belong to RunSettings (tests/solvers/test_settings.py)."""
    for name in ("t_final", "output_interval", "stop_at_failure", "failure_ratio"):
        assert not hasattr(SailParameters(), name)
        with pytest.raises(TypeError):
            SailParameters(**{name: 1.0})


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
    assert p.slice_inertia == pytest.approx(p.slice_mass * l**2 / 12)
    assert p.torsional_stiffness == pytest.approx(4.5e9 * 1e-18 / 12 / l)
    # g0 = f0 / m: a flat slice is balanced exactly by the frame force
    assert p.flat_force / p.slice_mass == pytest.approx(p.nominal_acceleration, rel=1e-14)


def test_bending_defaults_per_model_and_axial_stiffness():
    assert SailParameters(model="torsion").torsional_stiffness > 0
    assert SailParameters(model="tnt").torsional_stiffness == 0.0  # paper: k_T = 0 in TnT runs
    assert SailParameters(model="tnt", bending=True).torsional_stiffness > 0
    assert SailParameters(model="rigid").torsional_stiffness == 0.0
    p = SailParameters(model="tnt", n=30, youngs_modulus=1e11, thickness=1e-6)
    assert p.axial_stiffness == pytest.approx(29 * 1e11 * 1e-6)
    assert math.isinf(p.replace(axial_springs=False).axial_stiffness)
    assert p.replace(model="torsion").bending is True


def test_stiffness_damping_adds_beta_k_to_every_damper():
    p = SailParameters(
        model="tnt",
        youngs_modulus=1e9,
        tension=1e-3,
        bending=True,
        torsional_damping=1e-9,
        axial_damping=2.0,
        stiffness_damping=1e-4,
    )
    assert p.total_torsional_damping == pytest.approx(1e-9 + 1e-4 * p.torsional_stiffness, rel=1e-15)
    assert p.total_axial_damping == pytest.approx(2.0 + 1e-4 * p.axial_stiffness, rel=1e-15)
    assert SailParameters(model="rigid", torsional_damping=1.0, stiffness_damping=1.0).total_torsional_damping == 0.0
    assert p.replace(axial_springs=False).total_axial_damping == 0.0
    with pytest.raises(ParameterError, match="stiffness_damping"):
        SailParameters(stiffness_damping=-1e-3)


def test_roundtrip_dict_and_paper_cases():
    p = paper_case("tnt-soft")
    assert SailParameters.from_dict(p.to_dict()) == p
    assert paper_case("rigid").n == 40
    with pytest.raises(ParameterError, match="case"):
        paper_case("nope")


def test_from_dict_reads_the_names_of_older_records():
    """Saved runs and store records written before the renames: amplitude, mode, defect_modes, and run
    control kept with the case (skipped: it is RunSettings now)."""
    p = SailParameters(defect_amplitude=2e-5, defect_mode=2.5, defect_seed=4, defect_mode_count=7)
    old = {
        (
            "amplitude"
            if k == "defect_amplitude"
            else "mode"
            if k == "defect_mode"
            else "defect_modes"
            if k == "defect_mode_count"
            else k
        ): v
        for k, v in p.to_dict().items()
    }
    old.update(t_final=0.3, output_interval=1e-3, stop_at_failure=False, failure_ratio=3.0)
    assert "defect_mode" not in old and "mode" in old
    assert SailParameters.from_dict(old) == p


def test_from_dict_reads_the_beam_axis_under_its_older_spelling():
    p = SailParameters(model="sheet", n=4, ny=3, beam_waist=0.5, beam_centre=0.3, beam_centre_y=0.6)
    old = {LEGACY_SPELLING.get(k, k): v for k, v in p.to_dict().items()}
    assert {"beam_center", "beam_center_y"} <= set(old) and SailParameters.from_dict(old) == p


LEGACY_SPELLING = {"beam_centre": "beam_center", "beam_centre_y": "beam_center_y"}


def test_from_dict_refuses_a_field_under_both_its_names():
    """A record with beam_center and beam_centre names one field twice: refused, not one of them dropped."""
    with pytest.raises(ParameterError, match="one of beam_center and beam_centre"):
        SailParameters.from_dict({"beam_centre": 0.3, "beam_center": 0.4})


def test_from_dict_rejects_an_unknown_key():
    d = {**SailParameters().to_dict(), "colour": "gold"}
    with pytest.raises(ParameterError, match="colour"):
        SailParameters.from_dict(d)


# ---- supports and tip load (paper Appendices A–B) --------------------------------------------
def test_defaults_keep_the_free_sail_and_its_dict():
    p = SailParameters()
    assert p.boundary == "free" and p.tip_load == 0.0 and p.tip_load_time_constant == 0.0
    d = p.to_dict()
    assert not {"boundary", "tip_load", "tip_load_time_constant"} & set(d)  # sweep keys unchanged
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
    assert SailParameters(tip_load=-5.0).tip_force(0.0) == -5.0  # τ = 0: full load at once


@pytest.mark.parametrize(
    "changes, name",
    [
        (dict(boundary="clamped"), "boundary"),
        (dict(tip_load=math.nan), "tip_load"),
        (dict(tip_load_time_constant=-1.0), "tip_load_time_constant"),
    ],
)
def test_bad_support_values_name_the_parameter(changes, name):
    with pytest.raises(ParameterError, match=name):
        SailParameters(**changes)


# ---- the sheet (model="sheet") ---------------------------------------------------------------
def test_chain_records_do_not_change_with_the_sheet_fields():
    """The sheet's fields are left out of to_dict at their defaults, so every chain case keeps its
    record and store key; a chain rejects them away from their defaults."""
    from lightsail_mbs.model.records import SHEET_DEFAULTS

    for p in (SailParameters(), paper_case("tnt-soft"), SailParameters(model="rigid", beam_waist=0.5)):
        assert not set(SHEET_DEFAULTS) & set(p.to_dict())
    for name, value in dict(
        ny=3, defect_mode_y=1.5, membrane_modulus=1e9, edge_tension=1e-6, beam_centre_y=0.2, pressure=1.0
    ).items():
        with pytest.raises(ParameterError, match=f"{name}.*unless model='sheet'"):
            SailParameters(**{name: value})


def test_sheet_fields_round_trip_and_defaults():
    p = SailParameters(model="sheet", n=12, ny=8, defect_mode_y=1.5, membrane_modulus=4.5e9, edge_tension=1e-6)
    d = p.to_dict()
    assert d["ny"] == 8 and d["defect_mode_y"] == 1.5 and "pressure" not in d
    assert SailParameters.from_dict(d) == p
    assert p.bending is True  # plate bending on by default
    assert p.sheet_beam_centre_y == 0.5


@pytest.mark.parametrize(
    "changes, name, words",
    [
        (dict(ny=0), "ny", "1 ≤ ny ≤ 500"),
        (dict(ny=2.0), "ny", "integer"),
        (dict(n=600), "n", "≤ 500"),
        (dict(defect_mode_y=-1.0), "defect_mode_y", "> 0"),
        (dict(defect_mode_y=1.5, width=5e-5), "defect_amplitude", "W/(2πν_y)"),
        (dict(edge_tension=-1.0), "edge_tension", "≥ 0"),
        (dict(membrane_modulus=0.0), "membrane_modulus", "> 0"),
        (dict(youngs_modulus=0.0), "membrane_modulus", "youngs_modulus = 0"),
        (dict(membrane_damping=-1.0), "membrane_damping", "≥ 0"),
        (dict(membrane_reference="curved"), "membrane_reference", "initial, flat"),
        (dict(boundary="pinned"), "boundary", "simply_supported"),
        (dict(tension=1.0), "tension", "edge_tension"),
        (dict(torsional_damping=1.0), "torsional_damping", "stiffness_damping"),
        (dict(beam_centre_y=math.nan), "beam_centre_y", "finite"),
        (dict(optics="mirror"), "optics", "the R/α law, unless model is one of rigid, torsion, tnt"),
        (dict(initial_tilt_y=2.0), "initial_tilt_y", "|tilt| < π/2"),
        (dict(payload_mass=1e-3, payload_stem=0.2, payload_tethers=3), "tether_stiffness", "> 0 with tethers"),
        (dict(billow_radius=0.2), "billow_radius", "90° from its apex"),
    ],
)
def test_bad_sheet_values_name_the_parameter(changes, name, words):
    with pytest.raises(ParameterError) as err:
        SailParameters(model="sheet", **changes)
    assert name in str(err.value) and words in str(err.value)


@pytest.mark.parametrize("examples", EXAMPLES)
def test_any_parameter_set_is_accepted_or_refused_naming_a_field(examples):
    """Property: whatever the values (wrong sign, NaN, inf, wrong type), SailParameters either accepts them
    or raises ParameterError naming one of its fields — never another exception."""

    @given(any_case_kwargs())
    def accepted_or_refused(kwargs):
        try:
            p = SailParameters(**kwargs)
        except ParameterError as exc:
            assert len(str(exc).splitlines()) == 1
            assert any(str(exc).startswith(f"{name}=") or f"{name} " in str(exc) for name in kwargs), str(exc)
        else:
            assert SailParameters.from_dict(p.to_dict()) == p

    check_property(accepted_or_refused, examples)


def test_a_misspelt_field_is_one_line_naming_it_and_the_nearest_field():
    with pytest.raises(ParameterError, match=r"unknown case field beam_center \(did you mean beam_centre\?\)"):
        SailParameters(beam_center=0.4)
    with pytest.raises(ParameterError, match="unknown case field thicknes"):
        SailParameters().replace(thicknes=1e-6)
    assert SailParameters(beam_centre=0.4).beam_centre == 0.4
