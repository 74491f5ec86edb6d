"""The case as a record: the dict of :meth:`SailParameters.to_dict` / :meth:`~SailParameters.from_dict` that saved
runs and the store's keys are made of, kept stable as fields are added.

Fields added after the store's keys were first written (the validations', the later ones and the sheet's)
are left out of the record at their defaults, so the record (and the store key) of every case that does
not use them is what it was before they existed; records of older versions are read under their old
names (LEGACY_NAMES), their run-control entries (RUN_FIELDS) skipped, and the store's keys keep the old names
(:func:`stored`). The validation of the case does not read these tables: which model uses which field is
declared in :data:`lightsail_mbs.model.fields.FIELDS`.
"""

from __future__ import annotations

import math

# Fields of the validations that to_dict omits at their defaults (a free, unloaded sail), so that the
# record of a sail lists only what describes it.
VALIDATION_DEFAULTS = {"boundary": "free", "tip_load": 0.0, "tip_load_time_constant": 0.0}
# The sheet's own fields, omitted by to_dict at their defaults.
SHEET_DEFAULTS = {
    "ny": 1,
    "defect_mode_y": None,
    "membrane_modulus": None,
    "edge_tension": 0.0,
    "beam_centre_y": None,
    "pressure": 0.0,
    "membrane_damping": None,
    "membrane_reference": "initial",
    "bending_reference": "flat",
    "initial_equilibrium": False,
    "planform": "rectangle",
    "spin_rate": 0.0,
    "spin_tilt": 0.0,
}
# Fields added after the store's keys were first written, omitted by to_dict at their defaults so that the
# record (and store key) of every case that does not use them stays what it was.
LATER_DEFAULTS = {
    "billow_radius": math.inf,
    "optics": None,
    "optics_layout": "uniform",
    "body_force": 0.0,
    "payload_mass": 0.0,
    "payload_inertia": 0.0,
    "payload_stem": 0.0,
    "billow_rest": False,
    "initial_tilt": 0.0,
    "roughness": 0.0,
    "roughness_seed": 0,
    "film_rms": 0.0,
    "film_correlation_length": 0.1,
    "film_hurst": 0.5,
    "film_seed": 0,
    "material": None,
    "velocity_terms": False,
    "initial_beta": 0.0,
    "heated": False,
    "heat_absorptance": None,
    "carried_mass": 0.0,
    "integrated_trajectory": False,
    "payload_tethers": 0,
    "tether_stiffness": 0.0,
    "initial_tilt_y": 0.0,
    "grating": None,
    "spin_equilibrium": False,
}
# Names under which saved runs and store records written before the current field names hold them.
LEGACY_NAMES = {
    "amplitude": "defect_amplitude",
    "mode": "defect_mode",
    "defect_modes": "defect_mode_count",
    "beam_center": "beam_centre",
    "beam_center_y": "beam_centre_y",
}
# Run control that saved runs of that format kept with the case (now solvers.settings.RunSettings).
RUN_FIELDS = ("t_final", "output_interval", "stop_at_failure", "failure_ratio")
STORED_NAMES = {new: old for old, new in LEGACY_NAMES.items()}  # field name -> its name in the store's keys
OMITTED_AT_DEFAULT = {**VALIDATION_DEFAULTS, **LATER_DEFAULTS, **SHEET_DEFAULTS}


def record(fields: dict) -> dict:
    """The record of a case's fields: those of OMITTED_AT_DEFAULT that are at their defaults left out."""
    return {k: v for k, v in fields.items() if k not in OMITTED_AT_DEFAULT or v != OMITTED_AT_DEFAULT[k]}


def stored(fields: dict) -> dict:
    """The record of a case's fields as the store's keys name them: record(fields) under the field names the
    keys were first written with (LEGACY_NAMES reversed), so that a renamed field keeps every key."""
    return {STORED_NAMES.get(k, k): v for k, v in record(fields).items()}


def current_names(d: dict) -> dict:
    """A record under the current field names (LEGACY_NAMES renamed, RUN_FIELDS dropped)."""
    renamed = ((LEGACY_NAMES.get(key, key), value) for key, value in d.items())
    return {key: value for key, value in renamed if key not in RUN_FIELDS}
