"""The materials table: every value sourced and physical, --material fills the case under explicit values, an
unknown name is one line listing the names."""

import math

import pytest

from lightsail_mbs import ParameterError, SailParameters
from lightsail_mbs.cli import build_parser
from lightsail_mbs.cli.options import params_from_args
from lightsail_mbs.model import materials

REQUIRED = {"silicon-nitride", "silicon", "silica", "mos2", "aluminium", "kapton"}


def parsed(*args):
    return build_parser().parse_args([str(a) for a in args])


def test_every_value_has_a_source_and_lies_in_its_physical_range():
    assert REQUIRED <= set(materials.MATERIALS)
    for m in materials.MATERIALS.values():
        for prop in materials.PROPERTIES:
            v = getattr(m, prop)
            assert v.source in materials.REFERENCES, (m.name, prop)
            assert math.isfinite(v.value) and v.value > 0, (m.name, prop)
        assert 0 < m.poisson_ratio.value < 0.5
        assert m.emissivity_front.value <= 1 and m.emissivity_back.value <= 1 and m.absorptance.value < 1
        assert 300 < m.limit_temperature.value < 3000
        if any(getattr(m, p).source == "estimate" for p in materials.PROPERTIES):
            assert m.note, f"{m.name}: an estimate must say what it is based on"


def test_the_docs_table_names_every_material_and_source():
    table = materials.markdown_table()
    for name in materials.MATERIALS:
        assert f"`{name}`" in table
    assert table.count("\n") == len(materials.MATERIALS) + 1


def test_material_fills_density_and_modulus_and_explicit_options_override(tmp_path):
    sin = materials.get("silicon-nitride")
    p = params_from_args(parsed("theory", "--material", "silicon-nitride"))
    assert (p.density, p.youngs_modulus, p.material) == (sin.density.value, sin.youngs_modulus.value, sin.name)
    p = params_from_args(parsed("theory", "--material", "silicon-nitride", "--density", 2500))
    assert p.density == 2500 and p.youngs_modulus == sin.youngs_modulus.value
    # a case file naming a material: its own entries over the material's, the options over both
    path = SailParameters(material="kapton", density=1000.0).to_toml(tmp_path / "k.toml")
    p = params_from_args(parsed("theory", path))
    assert p.density == 1000.0  # the file's own (it was written with density 1000)
    p = params_from_args(parsed("theory", path, "--material", "silica"))
    assert p.density == materials.get("silica").density.value  # the option's material over the file


def test_an_unknown_material_is_one_line_listing_the_names():
    with pytest.raises(ParameterError) as info:
        SailParameters(material="unobtainium")
    text = str(info.value)
    assert "\n" not in text and "material='unobtainium'" in text
    assert all(name in text for name in REQUIRED)
    with pytest.raises(ParameterError, match="material="):
        params_from_args(parsed("theory", "--material", "unobtainium"))


def test_the_docs_page_shows_the_table_of_the_code():
    from pathlib import Path

    page = (Path(__file__).parents[2] / "docs" / "materials.md").read_text(encoding="utf-8")
    assert materials.markdown_table() in page
