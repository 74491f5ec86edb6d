"""The case's sections: the sail, its material, defect, film, beam, optics table, damping, supports and loads,
payload, and the sheet's own fields and spin — each field in the section its
:data:`~lightsail_mbs.model.fields.FIELDS` entry names (``group``).

Each section's range checks are a function of that section's fields alone (CHECKS): they validate a
section record on its own (:func:`records`, e.g. ``case.section("beam")``) and, as a whole, the case
(:class:`~lightsail_mbs.model.parameters.SailParameters`), whose own ``__post_init__`` adds only the rules
that join sections. Which models use each field is declared in its FieldInfo (``models``); one rule,
:func:`check_unused_at_defaults`, keeps every field the case's model does not use at its default.
"""

from __future__ import annotations

import dataclasses
import inspect
import math
import numbers
from collections.abc import Callable

from lightsail_mbs.base.validation import ParameterError, check, finite
from lightsail_mbs.model import film, materials, planforms, sheet_grating
from lightsail_mbs.model.fields import (
    BENDING_REFERENCES,
    BOUNDARIES,
    FIELDS,
    MEMBRANE_REFERENCES,
    MODELS,
    OPTICS_LAYOUTS,
    SECTIONS,
    SHEET_BOUNDARIES,
    close_match,
    number,
)
from lightsail_mbs.model.records import RUN_FIELDS

CHECKS: dict[str, Callable] = {}  # section name -> its range checks, a function of an object with its fields


def integer(value, low: int, high: float = math.inf) -> bool:
    """Whether value is an int (not a bool) with low ≤ value ≤ high."""
    return isinstance(value, int) and not isinstance(value, bool) and low <= value <= high


def as_float(value) -> float:
    """float(value), NaN where that fails (not a number, or an int beyond the float range)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        return math.nan
    try:
        return float(value)
    except (TypeError, ValueError, OverflowError):
        return math.nan


def _section(name: str):
    def register(function):
        CHECKS[name] = function
        return function

    return register


def _at_least(s, names, low: float = 0.0, strict: bool = False) -> None:
    for name in names:
        v = finite(name, getattr(s, name))
        check(name, v, v > low if strict else v >= low, f"> {low:g}" if strict else f"≥ {low:g}")


def _flags(s, names) -> None:
    for name in names:
        check(name, getattr(s, name), isinstance(getattr(s, name), bool), "True or False")


@_section("sail")
def _sail(s) -> None:
    check("model", s.model, s.model in MODELS, f"one of {', '.join(MODELS)}")
    check("n", s.n, integer(s.n, 2, 5000), "an integer 2 ≤ n ≤ 5000")
    _at_least(s, ("length", "width", "thickness"), strict=True)
    check("bending", s.bending, s.bending is None or isinstance(s.bending, bool), "True, False or None")
    _flags(s, ("billow_rest",))
    check(
        "billow_rest",
        s.billow_rest,
        not s.billow_rest or not math.isinf(as_float(s.billow_radius)),
        "False for a flat sail (billow_radius = inf)",
    )


@_section("material")
def _material(s) -> None:
    _at_least(s, ("density",), strict=True)
    _at_least(s, ("youngs_modulus",))
    if s.material is not None:
        materials.get(s.material)  # one line naming the allowed materials
    _flags(s, ("heated",))
    if s.heat_absorptance is not None:
        v = finite("heat_absorptance", s.heat_absorptance)
        check("heat_absorptance", v, 0 <= v <= 1, "0 ≤ A ≤ 1")


@_section("defect")
def _defect(s) -> None:
    _at_least(s, ("defect_amplitude",))
    seed = s.defect_seed
    check("defect_seed", seed, seed is None or integer(seed, 0), "None or an integer ≥ 0")
    check("defect_mode_count", s.defect_mode_count, integer(s.defect_mode_count, 1, 200), "an integer 1 ≤ K ≤ 200")
    finite("defect_spectrum", s.defect_spectrum)
    finite("roughness", s.roughness)
    check("roughness_seed", s.roughness_seed, integer(s.roughness_seed, 0), "an integer ≥ 0")
    v = finite("defect_mode", s.defect_mode)
    check("defect_mode", v, v > 0, "> 0 (whole or half integers in the paper)")


@_section("film")
def _film(s) -> None:
    film.of_case(s)  # the film's fields, each checked by the film model


@_section("beam")
def _beam(s) -> None:
    _at_least(s, ("intensity",))
    waist = s.beam_waist
    check("beam_waist", waist, as_float(waist) > 0, "> 0 (inf for a uniform beam)")
    if s.beam_centre is not None:
        finite("beam_centre", s.beam_centre)
    for name in ("reflectivity", "absorptivity"):
        v = finite(name, getattr(s, name))
        check(name, v, 0 <= v <= 1, "0 ≤ value ≤ 1")
    check(
        "absorptivity",
        s.absorptivity,
        s.reflectivity + s.absorptivity <= 1,
        f"≤ 1 − reflectivity = {1 - s.reflectivity:g} (R + α + transmissivity = 1)",
    )
    check(
        "reflectivity",
        s.reflectivity,
        2 * s.reflectivity + s.absorptivity > 0,
        "> 0 or absorptivity > 0 (a transparent sail feels no load)",
    )
    _flags(s, ("velocity_terms", "integrated_trajectory"))
    v = finite("initial_beta", s.initial_beta)
    check("initial_beta", v, 0 <= v < 1, "0 ≤ β₀ < 1 (the sail's speed along the beam, a fraction of c)")


@_section("optics")
def _optics(s) -> None:
    check("optics_layout", s.optics_layout, s.optics_layout in OPTICS_LAYOUTS, " or ".join(OPTICS_LAYOUTS))
    if s.grating is not None:
        check("grating", s.grating, isinstance(s.grating, str) and s.grating != "", "None or a layout file's path")
        sheet_grating.read(s.grating)  # reads the file now: a bad one is refused before any solving
    if s.optics is None:
        check("optics_layout", s.optics_layout, s.optics_layout == "uniform", "'uniform' without optics")
        return
    allowed = "None, 'mirror' or the path of an optical table file (.npz, from lightsail-mbs optics … --out)"
    check("optics", s.optics, isinstance(s.optics, str) and s.optics != "", allowed)
    table_of(s.optics)  # reads the file now: a bad one is refused before any solving


@_section("damping")
def _damping(s) -> None:
    _at_least(s, ("torsional_damping", "axial_damping", "stiffness_damping"))


@_section("supports")
def _supports(s) -> None:
    every = (*BOUNDARIES, *(b for b in SHEET_BOUNDARIES if b not in BOUNDARIES))
    check("boundary", s.boundary, s.boundary in every, f"one of {', '.join(every)}")
    _at_least(s, ("tension",))
    finite("tip_load", s.tip_load)
    v = finite("tip_load_time_constant", s.tip_load_time_constant)
    check("tip_load_time_constant", v, v >= 0, "≥ 0 (0: the full load from t = 0)")
    finite("body_force", s.body_force)
    for name in ("initial_tilt", "initial_tilt_y"):
        v = finite(name, getattr(s, name))
        check(name, v, abs(v) < math.pi / 2, "|tilt| < π/2 rad")


@_section("payload")
def _payload(s) -> None:
    _at_least(s, ("payload_mass", "payload_inertia", "payload_stem", "carried_mass", "tether_stiffness"))
    tethers = s.payload_tethers
    check("payload_tethers", tethers, integer(tethers, 0, 10**6) and tethers != 1 and tethers != 2, "0 or ≥ 3")
    if s.payload_mass == 0:
        for name in ("payload_inertia", "payload_stem", "payload_tethers"):
            check(name, getattr(s, name), getattr(s, name) == 0, "0 without a payload (payload_mass = 0)")
    check("tether_stiffness", s.tether_stiffness, (s.tether_stiffness > 0) == (tethers > 0), "> 0 with tethers, else 0")


@_section("sheet")
def _sheet(s) -> None:
    check("ny", s.ny, integer(s.ny, 1, 500), "an integer 1 ≤ ny ≤ 500")
    names = planforms.PLANFORMS
    check("planform", s.planform, s.planform in names, "one of " + ", ".join(names))
    if s.defect_mode_y is not None:
        v = finite("defect_mode_y", s.defect_mode_y)
        check("defect_mode_y", v, v > 0, "None (uniform across the width) or > 0")
    finite("pressure", s.pressure)
    v = finite("edge_tension", s.edge_tension)
    check("edge_tension", v, v >= 0, "≥ 0 (N per metre of edge)")
    if s.membrane_modulus is not None:
        v = finite("membrane_modulus", s.membrane_modulus)
        check("membrane_modulus", v, v > 0, "> 0 or None (= youngs_modulus)")
    if s.membrane_damping is not None:
        v = finite("membrane_damping", s.membrane_damping)
        check("membrane_damping", v, v >= 0, "≥ 0 s or None (critical for the top in-plane mode)")
    if s.beam_centre_y is not None:
        finite("beam_centre_y", s.beam_centre_y)
    references = (("membrane_reference", MEMBRANE_REFERENCES), ("bending_reference", BENDING_REFERENCES))
    for name, allowed in references:
        check(name, getattr(s, name), getattr(s, name) in allowed, f"one of {', '.join(allowed)}")
    _flags(s, ("initial_equilibrium",))


@_section("spin")
def _spin(s) -> None:
    spin, tilt = finite("spin_rate", s.spin_rate), finite("spin_tilt", s.spin_tilt)
    check("spin_tilt", tilt, abs(tilt) < math.pi / 2 and (tilt == 0 or spin != 0), "|β| < π/2, 0 unless spinning")
    _flags(s, ("spin_equilibrium",))
    steady = spin != 0 and tilt == 0  # a spin about the normal: a steady state in its turning frame
    check("spin_equilibrium", s.spin_equilibrium, not s.spin_equilibrium or steady, "False unless spinning, β = 0")


def payload_problems(case) -> list:
    """[(field, value, allowed)]: why a sheet's payload tethers cannot be attached (empty if they can)."""
    tethers = case.payload_tethers
    if tethers == 0:
        return []
    edges = len(planforms.mesh_of(case).boundary_tile)
    if tethers > edges:
        return [("payload_tethers", tethers, f"≤ {edges} (the rim's boundary edges)")]
    if case.payload_stem <= 0:
        return [("payload_stem", case.payload_stem, "> 0 with tethers (the payload hangs behind the rim)")]
    return []


def check_sections(case) -> None:
    """Every section's range checks on the case (in the order of SECTIONS)."""
    for name in SECTIONS:
        CHECKS[name](case)


def check_unused_at_defaults(case, defaults: dict) -> None:
    """The one rule of model-family support: each field whose FieldInfo.models leaves out the case's model
    keeps its default (defaults: field name -> default), the one line generated from the declaration."""
    for name, info in FIELDS.items():
        if case.model not in info.models:
            value, default = getattr(case, name), defaults[name]
            check(name, value, value == default, info.unused_text(shown_default(info, default)))


def shown_default(info, default) -> str:
    """A default as the error messages state it: a number as a user reads it, on/off for a switch, and for
    None, which neither a case file nor an option can spell, what it follows (FieldInfo.follows)."""
    if default is None:
        return f"its default, {info.follows}," if info.follows else "unset"
    if isinstance(default, bool):
        return "on" if default else "off"
    return number(default) if isinstance(default, float) else repr(default)


def table_of(optics: str):
    """The OpticalTable of a case's ``optics`` entry ("mirror" or a table file's path), read once per path
    and modification time; ParameterError naming the field for a bad file."""
    from lightsail_mbs.model import optics as tables

    if optics == "mirror":
        return tables.mirror()
    try:
        return tables.read_table(optics)
    except tables.OpticsFileError as exc:
        raise ParameterError(f"optics={optics!r} is invalid: {exc}") from None


def records(case_class) -> dict[str, type]:
    """One frozen record class per section (name -> class), its fields those of case_class in that
    section with the same defaults, checked on construction by the section's CHECKS."""
    grouped: dict[str, list] = {name: [] for name in SECTIONS}
    for f in dataclasses.fields(case_class):
        grouped[FIELDS[f.name].group].append((f.name, f.type, dataclasses.field(default=f.default)))
    return {
        name: dataclasses.make_dataclass(
            name.title() + "Section",
            specs,
            frozen=True,
            namespace={"__post_init__": CHECKS[name], "name": name, "__module__": __name__},
        )
        for name, specs in grouped.items()
    }


class UnknownFieldError(ParameterError, TypeError):
    """A keyword the case does not have (a TypeError too, as Python's own for an unexpected keyword)."""


def checked_init(init: Callable) -> Callable:
    """The case's generated __init__, refusing a keyword that is no field with one ParameterError line naming
    it and the nearest field (the fields: :data:`lightsail_mbs.model.fields.FIELDS`)."""

    def __init__(self, *args, **values):
        for key in values:
            if key in RUN_FIELDS:
                raise UnknownFieldError(f"{key} is a run setting, not a case field: give it to RunSettings")
            if key not in FIELDS:
                raise UnknownFieldError(
                    f"unknown case field {key}{close_match(key, FIELDS)}: allowed the fields of model.fields.FIELDS"
                )
        init(self, *args, **values)

    __init__.__doc__ = init.__doc__
    __init__.__signature__ = inspect.signature(init)
    return __init__
