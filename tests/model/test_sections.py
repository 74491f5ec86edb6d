"""The case as sections (lightsail_mbs.model.sections): each section is a record checked on its own with the
case's own messages, a case is built from its sections, and the one rule of model-family support refuses
every field that the case's model does not use, in the line its declaration (FieldInfo.models) generates."""

import dataclasses

import pytest

from lightsail_mbs import ParameterError, SailParameters
from lightsail_mbs.base.validation import shown
from lightsail_mbs.model.fields import FIELDS, MODELS, SECTIONS
from lightsail_mbs.model.parameters import DEFAULTS, SECTION_RECORDS
from lightsail_mbs.model.sections import shown_default
from tests.model.grating_layouts import PIZZA, write

SHEET = SailParameters(model="sheet", n=4, ny=3, edge_tension=1e-3, beam_waist=0.6, beam_centre_y=0.4)
TNT = SailParameters(model="tnt", tension=1e-3, youngs_modulus=1e11, payload_mass=0.0, torsional_damping=1e-9)


def test_the_sections_hold_every_field_once_in_the_field_tables_group():
    fields = [f.name for record in SECTION_RECORDS.values() for f in dataclasses.fields(record)]
    assert sorted(fields) == sorted(FIELDS) and list(SECTION_RECORDS) == list(SECTIONS)
    for name, record in SECTION_RECORDS.items():
        assert all(FIELDS[f.name].group == name for f in dataclasses.fields(record))
        assert record().name == name  # its defaults are valid on their own


@pytest.mark.parametrize("case", [SailParameters(), TNT, SHEET], ids=["torsion", "tnt", "sheet"])
def test_a_case_is_its_sections(case):
    parts = [case.section(name) for name in SECTIONS]
    assert SailParameters.from_sections(*parts) == case
    assert SailParameters.from_sections(case.section("sail"), case.section("material")).n == case.n
    assert SailParameters.from_sections(case.section("beam"), intensity=2e8).intensity == 2e8
    with pytest.raises(ParameterError, match="one record per section"):
        SailParameters.from_sections(case.section("beam"), case.section("beam"))
    with pytest.raises(ParameterError, match="section='hull' is invalid: allowed one of sail, material"):
        case.section("hull")
    with pytest.raises(ParameterError, match="allowed section records"):
        SailParameters.from_sections({"n": 3})


def test_a_followed_default_follows_the_case_its_section_joins():
    """The beam section of the 1 m sail, joined to the sail section of a 2 m one, centres the beam on the 2 m
    sail (x_c = L/2 = 1 m) as a case file would; a beam axis set away from the middle stays where it was set."""
    long_sail = SailParameters(length=2.0).section("sail")
    assert SailParameters.from_sections(long_sail, SailParameters().section("beam")).beam_centre == 1.0
    offset = SailParameters(beam_centre=0.3).section("beam")
    assert SailParameters.from_sections(long_sail, offset).beam_centre == 0.3
    rigid = SailParameters.from_sections(SailParameters(model="rigid").section("sail"), model="torsion")
    assert rigid.bending  # bending follows the model it joins: on for torsion


@pytest.mark.parametrize(
    "section, changes",
    [
        ("sail", dict(n=1)),
        ("sail", dict(thickness=-1e-6)),
        ("material", dict(density=0.0)),
        ("material", dict(material="unobtainium")),
        ("defect", dict(defect_mode_count=0)),
        ("film", dict(film_hurst=2.0)),
        ("beam", dict(absorptivity=0.5, reflectivity=0.8)),
        ("optics", dict(optics_layout="mirrored-halves")),
        ("damping", dict(stiffness_damping=-1.0)),
        ("supports", dict(tip_load_time_constant=-1.0)),
        ("payload", dict(payload_stem=0.1)),
        ("sheet", dict(ny=0)),
        ("spin", dict(spin_tilt=0.1)),
    ],
)
def test_each_section_is_checked_on_its_own_with_the_cases_message(section, changes):
    with pytest.raises(ParameterError) as alone:
        SECTION_RECORDS[section](**changes)
    with pytest.raises(ParameterError) as whole:
        SailParameters(model="sheet" if section in ("sheet", "spin") else "torsion", **changes)
    assert str(alone.value) == str(whole.value) and str(alone.value).startswith(next(iter(changes)))


# A value other than the default for every field that some model does not use; the fields whose own section
# refuses the value first (a layout without a table, a payload's inertia without its mass, a tilt without spin)
# name the field in their section's line.
UNUSED = {
    "tension": 1e-3,
    "axial_springs": False,
    "torsional_damping": 1e-6,
    "axial_damping": 1e-6,
    "tip_load": 1.0,
    "tip_load_time_constant": 0.1,
    "roughness": 1e-6,
    "roughness_seed": 3,
    "optics": "mirror",
    "optics_layout": "mirrored-halves",
    "payload_tethers": 3,
    "tether_stiffness": 1.0,
    "initial_tilt_y": 0.1,
    "ny": 3,
    "defect_mode_y": 0.5,
    "membrane_modulus": 1e9,
    "edge_tension": 1e-3,
    "beam_centre_y": 0.3,
    "pressure": 1.0,
    "membrane_damping": 0.1,
    "membrane_reference": "flat",
    "bending_reference": "initial",
    "initial_equilibrium": True,
    "planform": "disc",
    "spin_rate": 1.0,
    "spin_tilt": 0.1,
    "spin_equilibrium": True,
    "integrated_trajectory": True,
    "heated": True,
    "heat_absorptance": 1e-5,
    "carried_mass": 1e-3,
    "grating": write("pizza", PIZZA),
}
REFUSED_BY_THEIR_SECTION = {"optics_layout", "payload_tethers", "tether_stiffness", "spin_tilt", "spin_equilibrium"}
COMPANIONS = {
    "optics_layout": {"optics": "mirror"},
    "spin_tilt": {"spin_rate": 1.0},
    "spin_equilibrium": {"spin_rate": 1.0},
    "planform": {"ny": 8},
    "heated": {"material": "silicon-nitride"},
    "heat_absorptance": {"material": "silicon-nitride", "heated": True},
    "payload_tethers": {"payload_mass": 1e-3, "payload_stem": 0.1, "tether_stiffness": 1.0},
    "tether_stiffness": {"payload_mass": 1e-3, "payload_stem": 0.1, "payload_tethers": 3},
}


def test_every_field_a_model_does_not_use_is_refused_in_the_line_its_declaration_generates():
    assert set(UNUSED) == {name for name, info in FIELDS.items() if set(info.models) != set(MODELS)}
    for name, value in UNUSED.items():
        info = FIELDS[name]
        for model in (m for m in MODELS if m not in info.models):
            with pytest.raises(ParameterError) as err:
                SailParameters(model=model, **{name: value})
            expected = (
                f"{name}={shown(value)} is invalid: allowed {info.unused_text(shown_default(info, DEFAULTS[name]))}"
            )
            assert "allowed None" not in str(err.value) and "allowed True" not in str(err.value)
            assert str(err.value) == expected or (name in REFUSED_BY_THEIR_SECTION and str(err.value).startswith(name))
        SailParameters(**{"model": info.models[0], **COMPANIONS.get(name, {}), name: value})  # its models take it


def test_the_generated_line_says_which_models_use_the_field_and_what_the_others_use():
    with pytest.raises(ParameterError, match=r"tension=1.0 is invalid: allowed 0.0 unless model='tnt' \(a sheet's"):
        SailParameters(model="sheet", tension=1.0)
    with pytest.raises(ParameterError, match="ny=3 is invalid: allowed 1 unless model='sheet'$"):
        SailParameters(ny=3)
    with pytest.raises(ParameterError, match="allowed its default, the R/α law, unless model is one of rigid, torsion"):
        SailParameters(model="sheet", optics="mirror")
    with pytest.raises(ParameterError, match="allowed on unless model is one of rigid, torsion, tnt"):
        SailParameters(model="sheet", axial_springs=False)
