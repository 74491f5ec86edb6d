"""What each field of the case (:class:`~lightsail_mbs.model.parameters.SailParameters`) means: its group,
unit, help text, allowed values, the field its default follows, and the model family it belongs to.

One table, FIELDS, in the order of the class's fields; the command-line case options, the case files'
keys and their error messages are generated from it (tests/model/test_parameters.py checks that it names
every field of the class and nothing else). The defaults themselves are the class's.
"""

from __future__ import annotations

import difflib
from typing import NamedTuple

from lightsail_mbs.base.validation import number  # noqa: F401 - re-exported
from lightsail_mbs.model import planforms
from lightsail_mbs.model.materials import MATERIALS

MODELS = ("rigid", "torsion", "tnt", "sheet")
CHAIN_MODELS = ("rigid", "torsion", "tnt")
# Supports of the chain's ends (validations, paper Appendices A–B): "free" (the sail, both ends free),
# "cantilever" (slice 1 clamped at its initial pose, Appendix A), "pinned" (hinge 0 pinned, hinge n on a
# roller along x that lets the end tension T through: a string or simply supported beam, Appendix B).
BOUNDARIES = ("free", "cantilever", "pinned")
# Supports of the sheet's four edges (the plate and membrane validations): "free" (the sail),
# "simply_supported" (w = 0 along every edge, no bending moment), "clamped" (w = 0 and no rotation).
SHEET_BOUNDARIES = ("free", "simply_supported", "clamped")
MEMBRANE_REFERENCES = ("initial", "flat")
BENDING_REFERENCES = ("flat", "initial")
# How the slices carry an optical table: all alike, or the right half turned over (t → −t; model/optics.py).
OPTICS_LAYOUTS = ("uniform", "mirrored-halves")
# Smallest non-zero defect amplitude, as a fraction of L: the solvers scale their tolerances with a₀, and the
# reduced solver's first-step estimate underflows for a₀ ≲ 1e-200 m. (Physically, anything below ~1e-12 L is
# round-off already: shapes.defect_warnings says so.)
MIN_DEFECT_FRACTION = 1e-100


class FieldInfo(NamedTuple):
    group: str  # the section of the case the field belongs to (SECTIONS: a case file's table, a CLI option group)
    unit: str  # SI unit, "" for a number without one
    help: str  # what the field is, for a user
    allowed: str  # the values allowed, as the error messages state them ("" for True/False)
    follows: str | None = None  # the default when it follows other fields ("the sail's middle L/2")
    models: tuple[str, ...] = MODELS  # the models that use it; under any other model it keeps its default
    instead: str = ""  # what the other models use in its place, for the error message

    @property
    def family(self) -> str:
        """ "all", "chain" or "sheet": the model family that uses the field (a tnt-only field is a chain's)."""
        if set(self.models) == set(MODELS):
            return "all"
        return "sheet" if self.models == ("sheet",) else "chain"

    def unused_text(self, default: str) -> str:
        """The one line allowed for the field under a model that does not use it: its default."""
        which = f"={self.models[0]!r}" if len(self.models) == 1 else f" is one of {', '.join(self.models)}"
        return f"{default} unless model{which}" + (f" ({self.instead})" if self.instead else "")


def close_match(key: str, names) -> str:
    """ " (did you mean NAME?)" for the name nearest a misspelt key, or "" when none is near."""
    match = difflib.get_close_matches(key, list(names), n=1)
    return f" (did you mean {match[0]}?)" if match else ""


def _choices(values) -> str:
    return "one of " + ", ".join(values)


# The case's sections: name (a case file's table) -> title (the command line's option group).
SECTIONS = {
    "sail": "sail",
    "material": "material",
    "defect": "defect",
    "film": "film roughness",
    "beam": "beam",
    "optics": "optics table",
    "damping": "damping",
    "supports": "supports and loads",
    "payload": "payload",
    "sheet": "sheet (--model sheet)",
    "spin": "spin (--model sheet)",
}
SAIL, MATERIAL, DEFECT, FILM, BEAM, OPTICS, DAMPING, SUPPORTS, PAYLOAD, SHEET, SPIN = SECTIONS
TNT, CHAINS, SHEETS = ("tnt",), CHAIN_MODELS, ("sheet",)
FIELDS = {
    "model": FieldInfo(
        SAIL, "", "model family: chains of n slices (rigid, torsion, tnt) or a sheet of n × ny tiles", _choices(MODELS)
    ),
    "n": FieldInfo(SAIL, "", "number of slices (sheet: tiles along L)", "an integer 2 ≤ n ≤ 5000 (≤ 500 for a sheet)"),
    "length": FieldInfo(SAIL, "m", "sail length L", "> 0"),
    "width": FieldInfo(SAIL, "m", "sail width W", "> 0"),
    "thickness": FieldInfo(SAIL, "m", "film thickness h", "> 0"),
    "density": FieldInfo(MATERIAL, "kg/m³", "film density ρ", "> 0"),
    "youngs_modulus": FieldInfo(MATERIAL, "Pa", "Young's modulus E", "≥ 0 (> 0 for the tnt model with axial springs)"),
    "tension": FieldInfo(
        SUPPORTS,
        "N",
        "boundary tension T of the TnT chain (the paper's per-width value × W)",
        "≥ 0",
        models=TNT,
        instead="a sheet's is edge_tension, N per metre of edge",
    ),
    "intensity": FieldInfo(BEAM, "W/m²", "laser intensity I₀ (on the beam axis for a Gaussian beam)", "≥ 0"),
    "defect_amplitude": FieldInfo(DEFECT, "m", "initial defect amplitude a₀", "0 or 1e-100 L ≤ a₀ < L/(2πν)"),
    "defect_mode": FieldInfo(DEFECT, "", "defect mode number ν: wavelengths of the sine defect over L (Eq. 1)", "> 0"),
    "defect_seed": FieldInfo(
        DEFECT,
        "",
        "an integer: a seeded random multi-mode defect of amplitude a₀ (modes ν = 1/2 … K/2)",
        "an integer ≥ 0",
        follows="the sine of defect_mode",
    ),
    "defect_mode_count": FieldInfo(DEFECT, "", "multi-mode defect: modes ν_k = k/2, k = 1…K", "an integer 1 ≤ K ≤ 200"),
    "defect_spectrum": FieldInfo(DEFECT, "", "multi-mode defect: mean amplitude ∝ ν_k^(−β), the exponent β", "finite"),
    "roughness": FieldInfo(
        DEFECT, "m", "seeded roughness at every wavelength the slices carry", "0 ≤ … < L/(2πn)", models=CHAINS
    )._replace(instead="a sheet's film: film_rms"),
    "roughness_seed": FieldInfo(DEFECT, "", "seed of the roughness", "an integer ≥ 0", models=CHAINS),
    "film_rms": FieldInfo(
        FILM,
        "m",
        "RMS of the film's roughness (K-correlation spectrum, model.film; 0: none), added to the defect",
        "≥ 0",
    ),
    "film_correlation_length": FieldInfo(FILM, "m", "the film spectrum's correlation length ξ", "> 0"),
    "film_hurst": FieldInfo(FILM, "", "the film spectrum's Hurst exponent H", "0 < H ≤ 1"),
    "film_seed": FieldInfo(FILM, "", "seed of the film's modes", "an integer ≥ 0"),
    "beam_waist": FieldInfo(BEAM, "m", "Gaussian beam waist w: I₀ exp(−2(x − x_c)²/w²); inf: a uniform beam", "> 0"),
    "beam_centre": FieldInfo(BEAM, "m", "Gaussian beam axis x_c", "finite", follows="the sail's middle L/2"),
    "reflectivity": FieldInfo(BEAM, "", "specular reflectivity R (the paper: 1)", "0 ≤ R ≤ 1, R + α ≤ 1"),
    "absorptivity": FieldInfo(BEAM, "", "absorptivity α (transmissivity 1 − R − α)", "0 ≤ α ≤ 1 − R"),
    "bending": FieldInfo(
        SAIL,
        "",
        "torsional springs k_T = EI/l on or off",
        "",
        follows="on for torsion and sheet, off for rigid and tnt",
    ),
    "axial_springs": FieldInfo(
        SAIL,
        "",
        "tnt: extensible slices with k_s = (n−1)EhW/L, or their rigid (inextensible) limit",
        "",
        models=CHAINS,
    ),
    "torsional_damping": FieldInfo(
        DAMPING,
        "N·m·s/rad",
        "torsional damping c_T",
        "≥ 0",
        models=CHAINS,
        instead="a sheet's damping: stiffness_damping",
    ),
    "axial_damping": FieldInfo(
        DAMPING, "N·s/m", "axial damping c_s", "≥ 0", models=CHAINS, instead="a sheet's damping: stiffness_damping"
    ),
    "stiffness_damping": FieldInfo(
        DAMPING, "s", "material damping β: c = β k on every spring; loss factor η at ω: β = η/ω", "≥ 0"
    ),
    "boundary": FieldInfo(
        SUPPORTS,
        "",
        "supports: a chain's ends or a sheet's four edges (the validations; free: the sail)",
        f"chain: {_choices(BOUNDARIES)}; sheet: {_choices(SHEET_BOUNDARIES)}",
    ),
    "tip_load": FieldInfo(
        SUPPORTS, "N", "transverse (+y) dead load P₀ at the centre of slice n (Eq. 43)", "finite", models=CHAINS
    ),
    "tip_load_time_constant": FieldInfo(
        SUPPORTS, "s", "ramp of the tip load, P(t) = P₀(1 − e^(−t/τ)); 0: P₀ from t = 0", "≥ 0", models=CHAINS
    ),
    "body_force": FieldInfo(
        SUPPORTS,
        "N/kg",
        "uniform in-plane body force per unit mass along the sail's length x, on every slice or tile (a test load)",
        "finite; 0 with a payload",
    ),
    "ny": FieldInfo(SHEET, "", "tiles across the width W", "an integer 1 ≤ ny ≤ 500", models=SHEETS),
    "defect_mode_y": FieldInfo(
        SHEET,
        "",
        "defect mode ν_y across the width: w = a₀ sin(2πνx/L) sin(2πν_y y/W)",
        "> 0",
        follows="uniform across W",
        models=SHEETS,
    ),
    "membrane_modulus": FieldInfo(
        SHEET, "Pa", "in-plane (membrane) modulus E_m", "> 0", follows="E (youngs_modulus)", models=SHEETS
    ),
    "edge_tension": FieldInfo(
        SHEET,
        "N/m",
        "follower tension on all four edges, per metre of edge (and the pre-stress)",
        "≥ 0",
        models=SHEETS,
    ),
    "beam_centre_y": FieldInfo(SHEET, "m", "Gaussian beam axis y_c", "finite", follows="W/2", models=SHEETS),
    "pressure": FieldInfo(
        SHEET, "Pa", "dead pressure p along the beam (+z), the plate validations", "finite", models=SHEETS
    ),
    "membrane_damping": FieldInfo(
        SHEET,
        "s",
        "damping β_m k on the stiff in-plane springs",
        "≥ 0",
        follows="critical for the top in-plane mode",
        models=SHEETS,
    ),
    "membrane_reference": FieldInfo(
        SHEET,
        "",
        "in-plane springs at rest in the initial (defect) or the flat shape",
        _choices(MEMBRANE_REFERENCES),
        models=SHEETS,
    ),
    "bending_reference": FieldInfo(
        SHEET,
        "",
        "bending springs at rest flat (the paper: an elastically loaded defect) or in the initial shape "
        "(a stress-free, manufactured defect)",
        _choices(BENDING_REFERENCES),
        models=SHEETS,
    ),
    "initial_equilibrium": FieldInfo(
        SHEET,
        "",
        "correct the springs' rest state so that the unlit sheet (edge tension included) rests in its initial shape",
        "",
        models=SHEETS,
    ),
    "planform": FieldInfo(
        SHEET,
        "",
        "the sheet's outline and tiles: "
        + "; ".join(f"{name}: {form.help}" for name, form in planforms.PLANFORMS.items()),
        _choices(planforms.PLANFORMS),
        models=SHEETS,
    ),
    "spin_rate": FieldInfo(
        SPIN,
        "rad/s",
        "initial spin Ω about the sail's normal through its centre, from the spun equilibrium (the unlit flat "
        "sail rests in its rotating frame)",
        "finite; 0 unless boundary='free'",
        models=SHEETS,
    ),
    "spin_tilt": FieldInfo(
        SPIN,
        "rad",
        "the initial angular velocity turned from the sail's normal towards +x by this angle (a nutating spin)",
        "|tilt| < π/2; 0 unless spin_rate ≠ 0",
        models=SHEETS,
    ),
    "billow_radius": FieldInfo(
        SAIL,
        "m",
        "initial circular arc (chain) or spherical cap (sheet) of radius R_c: > 0 concave to the laser, < 0 "
        "convex; inf: flat",
        "|R_c| ≥ l/(2 sin(π/2n)) (chain), ≥ 2/π × the farthest corner's distance from the middle (sheet)",
    ),
    "optics": FieldInfo(
        OPTICS,
        "",
        "the slices' force law from a table: 'mirror' or a table file (lightsail-mbs optics … --out)",
        "'mirror' or a path",
        follows="the R/α law",
        models=CHAINS,
        instead="a sheet's tiles: reflectivity, absorptivity",
    ),
    "optics_layout": FieldInfo(
        OPTICS,
        "",
        "which slices carry the table turned over (mirrored-halves: the right half)",
        _choices(OPTICS_LAYOUTS),
        models=CHAINS,
    ),
    "payload_mass": FieldInfo(
        PAYLOAD, "kg", "payload mass m_p on a rigid stem from the sail's middle (sheet: or on tethers)", "≥ 0"
    ),
    "payload_inertia": FieldInfo(PAYLOAD, "kg·m²", "the payload's own inertia J_p", "≥ 0"),
    "payload_stem": FieldInfo(
        PAYLOAD,
        "m",
        "stem length d from the sail's middle towards the laser (sheet tethers: the payload's distance there)",
        "≥ 0",
    ),
    "billow_rest": FieldInfo(
        SAIL,
        "",
        "springs at rest on the billowed arc or cap (a sail made curved: a chain's torsion springs, a sheet's "
        "springs whose reference is flat); off: at rest flat",
        "",
    ),
    "initial_tilt": FieldInfo(
        SUPPORTS,
        "rad",
        "the initial shape turned about the craft's centre of mass: a chain counter-clockwise, a sheet about y "
        "(its x axis towards the beam, +z)",
        "|tilt| < π/2",
    ),
    "material": FieldInfo(
        MATERIAL,
        "",
        "the film from the materials table: fills density and youngs_modulus (explicit values override)",
        _choices(MATERIALS),
        follows="none: density and youngs_modulus as given",
    ),
    "velocity_terms": FieldInfo(
        BEAM,
        "",
        "the first-order velocity-dependent radiation load: Doppler and aberration of each slice's or tile's own "
        "velocity in the sail's frame (a damping of rate 2g₀/c on a mirror's normal velocity)",
        "",
    ),
    "initial_beta": FieldInfo(
        BEAM,
        "",
        "the sail's speed along the beam at t = 0, β₀ (a fraction of c); > 0: the beam's loads follow the "
        "Doppler factor (1 − β)/(1 + β) of the speed β(t) along the constant-power trajectory from β₀ "
        "(intensity: the lab frame's); 0: at rest, no Doppler term",
        "0 ≤ β₀ < 1; 0 with supports (boundary other than free) or an optical table",
    ),
    "heated": FieldInfo(
        MATERIAL,
        "",
        "the film heated by the beam inside the run: its quasi-steady temperature at the sail-frame intensity of "
        "each moment, and the tension a rigid frame leaves it, N₀ − E h W α_T ⟨ΔT⟩, with the springs' rest lengths "
        "following T (model/heating.py); needs material",
        "",
        models=TNT,
    ),
    "heat_absorptance": FieldInfo(
        MATERIAL,
        "",
        "with heated: the film's absorptance at the laser's wavelength, at every wavelength",
        "0 ≤ A ≤ 1",
        follows="the material's; with an absorbing optical table that has a wavelength axis, its 1 − R − T at λ'",
        models=TNT,
    ),
    "carried_mass": FieldInfo(
        PAYLOAD,
        "kg",
        "mass the craft carries that is no body of the model (held by the frame): it slows the trajectory the "
        "Doppler factor follows, not the sail's own frame",
        "≥ 0",
        models=CHAINS,
    ),
    "integrated_trajectory": FieldInfo(
        BEAM,
        "",
        "the sail's motion along the beam as part of the run's state (its lab time, distance and 4-velocity, "
        "integrated with the shape): the beam's loads follow the Doppler factor of that state; off: the closed "
        "form of the constant-power trajectory (model/world_line.py); only with boundary free",
        "",
        models=CHAINS,
    ),
    "payload_tethers": FieldInfo(
        PAYLOAD,
        "",
        "tethers from the rim to the payload, elastic cables slack in compression (model.sheet_payload); 0: the stem",
        "0 or an integer 3 ≤ tethers ≤ the rim's edges; 0 without a payload",
        models=SHEETS,
    ),
    "tether_stiffness": FieldInfo(
        PAYLOAD, "N/m", "axial stiffness k of each tether", "> 0 with tethers, else 0", models=SHEETS
    ),
    "initial_tilt_y": FieldInfo(
        SUPPORTS,
        "rad",
        "the initial shape turned about x through the craft's centre of mass (its y axis towards the beam, +z)",
        "|tilt| < π/2",
        models=SHEETS,
    ),
    "grating": FieldInfo(
        OPTICS,
        "",
        "gratings on the tiles: in-plane and normal optical pressures by sectors of the sail, from a layout file "
        "(TOML; model/sheet_grating.py)",
        "None or the path of a layout file",
        follows="none: the film's specular law alone",
        models=SHEETS,
    ),
    "spin_equilibrium": FieldInfo(
        SPIN,
        "",
        "start the spinning sheet in its static equilibrium in the turning frame (connectors and bending against "
        "the centrifugal forces, the shape free to deform from the initial one; solvers.reduced.sheet_relax); "
        "only with spin_rate ≠ 0 and spin_tilt = 0",
        "",
        models=SHEETS,
    ),
}
