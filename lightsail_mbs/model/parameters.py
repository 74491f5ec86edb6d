"""The case: one validated, immutable parameter set per simulation (SI units throughout).

Paper: Sections III–IV; the derived quantities (slice length, mass, inertia, stiffnesses) are those of
:class:`~lightsail_mbs.model.derived.DerivedQuantities`. What each field means, its unit, its allowed
values, its section and the models that use it: :data:`lightsail_mbs.model.fields.FIELDS`; case files:
:mod:`lightsail_mbs.model.casefile`.

The case is composed of sections (the sail, its material, defect, film, beam, optics table, damping,
supports and loads, payload, the sheet's fields and its spin: :mod:`lightsail_mbs.model.sections`), each
checked on its own; :meth:`SailParameters.section` gives one as its own record and
:meth:`SailParameters.from_sections` builds a case from them. The solvers read the flat record. Two model
families share it: the chains ("rigid", "torsion", "tnt") are the paper's strip of n slices; the "sheet"
is the sail cut into n × ny rigid tiles moving in 3-D (:mod:`lightsail_mbs.model.sheet`). A field that
the case's model does not use (FieldInfo.models) stays at its default.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from lightsail_mbs.base.constants import SPEED_OF_LIGHT  # noqa: F401 - re-exported
from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError, check
from lightsail_mbs.model import casefile, materials, planforms, sections
from lightsail_mbs.model.derived import DerivedQuantities
from lightsail_mbs.model.fields import BOUNDARIES, FIELDS, MIN_DEFECT_FRACTION, SHEET_BOUNDARIES
from lightsail_mbs.model.records import LEGACY_NAMES, RUN_FIELDS, current_names, record  # noqa: F401

# The fields an optical table replaces, at the values it requires, and why (model/optics.py).
OPTICS_DEFAULTS = {
    "reflectivity": 1.0,
    "absorptivity": 0.0,
    "velocity_terms": False,
    "initial_beta": 0.0,
    "integrated_trajectory": False,
}
OPTICS_REASONS = {
    "velocity_terms": "the velocity-dependent load is derived for the R/α facet law",
    "initial_beta": (
        "a run holds its table at one wavelength, and the Doppler-shifted light is at another: for a grating at "
        "the sail-frame wavelength along the acceleration, tabulate it with `lightsail-mbs optics grating "
        "--wavelengths …` and run with it and integrated_trajectory (the run reads it at λ' of its state), or "
        "`lightsail-mbs journey --optics TABLE` (each snapshot at its λ'); for the dimming inside a run, a "
        "reflectivity and absorptivity without optics, which hold at every wavelength"
    ),
}
OPTICS_REASONS["integrated_trajectory"] = OPTICS_REASONS["initial_beta"]
# allowed with a table that has a wavelength axis when the run integrates the world line (terms/radiation.py)
IN_RUN_WITH_SPECTRUM = ("initial_beta", "integrated_trajectory")


@dataclass(frozen=True)
class SailParameters(DerivedQuantities):
    """One lightsail case: the sail, its supports, its defect and the beam (SI units).

    Defaults: the paper's torsion study (Sec. IV.B, Fig. 6). Run control (duration, sampling, stop
    rule) is a separate :class:`~lightsail_mbs.solvers.settings.RunSettings`. The fields form sections
    (:meth:`section`, :meth:`from_sections`); every field is checked on construction, by its section and
    the rules that join sections; a bad value raises :class:`ParameterError` naming the field and its range.
    """

    model: str = "torsion"
    n: int = 30  # number of rigid slices
    length: float = 1.0  # L, m
    width: float = 1.0  # W, m
    thickness: float = 1e-6  # h, m
    density: float = 1000.0  # ρ, kg/m³
    youngs_modulus: float = 4.5e13  # E, Pa
    tension: float = 0.0  # T, N (paper's per-width value × W); TnT only
    intensity: float = 1e8  # I₀, W/m²
    defect_amplitude: float = 1e-5  # a₀, m
    defect_mode: float = 1.5  # ν: wavelengths of the sine defect over L (Eq. 1)
    defect_seed: int | None = None  # None: the paper's sine; an int: random multi-mode defect (shapes.py)
    defect_mode_count: int = 10  # multi-mode defect: modes ν_k = k/2, k = 1…K
    defect_spectrum: float = 1.0  # multi-mode defect: mean amplitude ∝ ν_k^(−β)
    roughness: float = 0.0  # m: seeded roughness at every wavelength the chain carries (shapes.roughness_profile)
    roughness_seed: int = 0  # seed of the roughness
    film_rms: float = 0.0  # σ, m: RMS of a physical film roughness (model.film); 0: none
    film_correlation_length: float = 0.1  # ξ, m: the film spectrum's long-wave roll-off
    film_hurst: float = 0.5  # H: the film spectrum's self-affine exponent
    film_seed: int = 0  # seed of the film's modes
    beam_waist: float = math.inf  # w, m: Gaussian beam I₀ exp(−2(x − x_c)²/w²); inf = uniform (paper)
    beam_centre: float | None = None  # x_c, m; None: the sail's middle L/2
    reflectivity: float = 1.0  # R, specular (paper: 1)
    absorptivity: float = 0.0  # α; transmissivity 1 − R − α
    bending: bool | None = None  # torsional springs on? None: on for torsion, off for tnt (paper)
    axial_springs: bool = True  # TnT: extensible slices (k_s); False: rigid (inextensible) limit
    torsional_damping: float = 0.0  # c_T, N·m·s/rad
    axial_damping: float = 0.0  # c_s, N·s/m
    stiffness_damping: float = 0.0  # β, s: material (Rayleigh) damping c = β k added to every spring
    boundary: str = "free"  # end supports, one of BOUNDARIES
    tip_load: float = 0.0  # P₀, N: transverse (+y) dead load at the centre of slice n (Eq. 43)
    tip_load_time_constant: float = 0.0  # τ, s: P(t) = P₀(1 − e^(−t/τ)) (Eq. 43); 0: P₀ from t = 0
    body_force: float = 0.0  # b, N/kg: uniform in-plane body force per unit mass along x (model/terms/body_force.py)
    # ---- the sheet (model="sheet": n × ny tiles; model.sheet) -------------------------------------
    ny: int = 1  # tiles across the width W (n tiles along L)
    defect_mode_y: float | None = None  # ν_y: w = a₀ sin(2πνx/L) sin(2πν_y y/W); None: uniform across W
    membrane_modulus: float | None = None  # E_m, Pa, of the in-plane (membrane) springs; None: E
    edge_tension: float = 0.0  # T, N per metre of edge: follower tension on all four edges + pre-stress
    beam_centre_y: float | None = None  # y_c, m, of the Gaussian beam; None: W/2
    pressure: float = 0.0  # p, Pa: dead pressure along the beam (+z) (the plate validations)
    membrane_damping: float | None = None  # β_m, s: damping β_m k on the stiff springs; None: critical
    membrane_reference: str = "initial"  # in-plane springs at rest in the "initial" (defect) or "flat" shape
    bending_reference: str = "flat"  # bending springs at rest "flat" or in the "initial" (manufactured) shape
    initial_equilibrium: bool = False  # True: the springs' rest state corrected: the unlit sheet rests as it starts
    planform: str = "rectangle"  # the sheet's outline and its tiles: one of model.planforms.PLANFORMS
    spin_rate: float = 0.0  # Ω, rad/s: initial spin about the sail's normal through its centre (model.sheet_spin)
    spin_tilt: float = 0.0  # rad: the initial angular velocity turned from the normal towards +x (nutation)
    billow_radius: float = math.inf  # R_c, m: initial circular arc (shapes.py); > 0 concave to the laser; inf: flat
    optics: str | None = None  # the slices' force law from a table: None (R, α above), "mirror", or a table file
    optics_layout: str = "uniform"  # one of OPTICS_LAYOUTS: which slices carry the table turned over
    payload_mass: float = 0.0  # m_p, kg: a payload on a rigid stem from the sail's middle (model/payload.py)
    payload_inertia: float = 0.0  # J_p, kg·m²: its inertia about its own centre
    payload_stem: float = 0.0  # d, m: the stem's length from the sail's middle towards the laser (−ŷ)
    billow_rest: bool = False  # torsion springs at rest on the billowed arc (a sail made curved); False: flat
    initial_tilt: float = 0.0  # rad: the initial shape turned counter-clockwise about the craft's centre of mass
    material: str | None = None  # the film's name in model.materials (its density and E fill the case: materials.fill)
    velocity_terms: bool = False  # the first-order Doppler and aberration of each body's velocity (terms/velocity.py)
    initial_beta: float = 0.0  # β₀: the sail's speed along the beam at t = 0, a fraction of c (terms/doppler.py)
    heated: bool = False  # the film's quasi-steady temperature and the tension it leaves, inside the run (heating.py)
    heat_absorptance: float | None = None  # A at every wavelength (None: the material's or the table's, heating.py)
    carried_mass: float = 0.0  # kg the craft carries that is no body: it slows only the trajectory (terms/doppler.py)
    integrated_trajectory: bool = False  # the world line integrated in the run's state (model/world_line.py)
    payload_tethers: int = 0  # sheet: tethers from the rim to the payload (model/sheet_payload.py); 0: the stem
    tether_stiffness: float = 0.0  # k, N/m: axial stiffness of each tether (slack in compression)
    initial_tilt_y: float = 0.0  # rad, sheet: the initial shape turned about x, its y axis towards the beam
    grating: str | None = None  # sheet: a grating layout file (model/sheet_grating.py): in-plane optical pressures
    spin_equilibrium: bool = False  # sheet: start spinning in the static equilibrium of the turning frame

    def __post_init__(self):
        sections.check_sections(self)
        sections.check_unused_at_defaults(self, DEFAULTS)
        if self.bending is None:
            object.__setattr__(self, "bending", self.model in ("torsion", "sheet"))
        if self.beam_centre is None:
            object.__setattr__(self, "beam_centre", 0.5 * self.length)
        if self.model == "sheet":
            self._check_sheet()
        else:
            check("boundary", self.boundary, self.boundary in BOUNDARIES, f"one of {', '.join(BOUNDARIES)}")
        self._check_across()

    def _check_across(self) -> None:
        """The rules that join sections: the material and the model, the defect and the roughness against the
        sail's size, the loads, payload, tilt and billow against the supports, the optics table against R/α."""
        check(
            "youngs_modulus",
            self.youngs_modulus,
            self.youngs_modulus > 0 or not self.extensible,
            "> 0 for the tnt model with axial springs",
        )
        limit = self.length / (2 * math.pi * self.n)
        check(
            "roughness",
            self.roughness,
            0 <= self.roughness < limit,
            f"0 ≤ roughness < L/(2πn) = {limit:.3g} m (slopes of its shortest waves below 45°)",
        )
        check(
            "body_force",
            self.body_force,
            self.body_force == 0 or self.payload_mass == 0,
            "0 with a payload (it acts on the sail's bodies)",
        )
        self._check_billow()
        check(
            "initial_beta",
            self.initial_beta,
            self.initial_beta == 0 or self.boundary == "free",
            "0 unless boundary='free' (the trajectory is a free sail's)",
        )
        check("heated", self.heated, not self.heated or self.material is not None, "off without a material")
        check("heated", self.heated, not self.heated or self.extensible, "off unless the TnT chain has axial springs")
        check(
            "heat_absorptance",
            self.heat_absorptance,
            self.heat_absorptance is None or self.heated,
            "None unless heated",
        )
        check(
            "integrated_trajectory",
            self.integrated_trajectory,
            not self.integrated_trajectory or self.boundary == "free",
            "off unless boundary='free' (the trajectory is a free sail's)",
        )
        why = f"False with a grating ({OPTICS_REASONS['velocity_terms']})"
        check("velocity_terms", self.velocity_terms, not (self.velocity_terms and self.grating), why)
        if self.optics is not None:
            for name, default in OPTICS_DEFAULTS.items():
                if name in IN_RUN_WITH_SPECTRUM and self._spectrum_in_run():
                    continue
                check(
                    name,
                    getattr(self, name),
                    getattr(self, name) == default,
                    f"{sections.shown_default(FIELDS[name], default)} with an optical table "
                    f"({OPTICS_REASONS.get(name, 'the table gives the force law')})",
                )
        if self.payload_mass != 0:
            check("payload_mass", self.payload_mass, self.boundary == "free", "0 unless boundary='free'")
            chain = self.model != "sheet"
            check("payload_mass", self.payload_mass, self.n >= 3 or not chain, "0 for n < 3 (not an end slice)")
            check(
                "payload_mass",
                self.payload_mass,
                not self.extensible,
                "0 for the extensible TnT chain (axial_springs=False: its inextensible limit carries one)",
            )
        for name in ("initial_tilt", "initial_tilt_y", "spin_rate"):
            check(
                name,
                getattr(self, name),
                getattr(self, name) == 0 or self.boundary == "free",
                "0 unless boundary='free'",
            )
        a, floor, steep = (
            self.defect_amplitude,
            MIN_DEFECT_FRACTION * self.length,
            self.length / (2 * math.pi * self.defect_mode),
        )
        check(
            "defect_amplitude",
            a,
            a == 0 or a >= floor,
            f"0 or ≥ {MIN_DEFECT_FRACTION:g} L = {floor:.3g} m (the solvers' tolerances scale with a₀; below this "
            "they underflow)",
        )
        check(
            "defect_amplitude",
            a,
            a < steep,
            f"< L/(2πν) = {steep:.3g} m (a sine steeper than 45° is outside the model)",
        )

    def _check_billow(self) -> None:
        R = sections.as_float(self.billow_radius)
        if self.model == "sheet":  # the cap reaches the sail's farthest corner at most 90° from its apex
            reach = 0.5 * (math.hypot(self.length, self.width) if self.planform == "rectangle" else self.length)
            r_min, why = 2.0 * reach / math.pi, "the cap reaches at most 90° from its apex to the farthest corner"
        else:
            r_min = self.slice_length / (2.0 * math.sin(math.pi / (2 * self.n)))
            why = "the arc of n chords of length l subtends at most 180°"
        check(
            "billow_radius",
            self.billow_radius,
            not math.isnan(R) and abs(R) >= r_min,
            f"|R_c| ≥ {r_min:.4g} m ({why}), > 0 concave to the laser, < 0 convex, inf for a flat sail",
        )
        check(
            "billow_radius",
            self.billow_radius,
            math.isinf(R) or self.boundary == "free",
            "inf (flat) unless boundary='free' (the supports hold a flat chain)",
        )

    def _check_sheet(self) -> None:
        """The sheet's rules that join its own section to the sail's: its size, planform, supports, the
        defect across the width and the membrane's modulus."""
        check("n", self.n, self.n <= 500, "an integer 2 ≤ n ≤ 500 for a sheet (n × ny tiles)")
        for name, value, allowed in planforms.problems(self) + sections.payload_problems(self):
            check(name, value, False, allowed)
        check(
            "boundary",
            self.boundary,
            self.boundary in SHEET_BOUNDARIES,
            f"one of {', '.join(SHEET_BOUNDARIES)} for a sheet",
        )
        if self.defect_mode_y is not None:
            steep = self.width / (2 * math.pi * self.defect_mode_y)
            check(
                "defect_amplitude",
                self.defect_amplitude,
                self.defect_amplitude < steep,
                f"< W/(2πν_y) = {steep:.3g} m (a sine steeper than 45° is outside the model)",
            )
        check(
            "membrane_modulus",
            self.membrane_modulus,
            self.membrane_modulus is not None or self.youngs_modulus > 0,
            "> 0 when youngs_modulus = 0 (the in-plane springs hold the tiles together)",
        )

    def optical_table(self):
        """The slices' force law as a :class:`~lightsail_mbs.model.optics.OpticalTable`: the file `optics`
        (read once per path and modification time), the built-in mirror for 'mirror', and for None the
        built-in mirror or facet of reflectivity and absorptivity."""
        if self.optics is None:
            from lightsail_mbs.model import optics

            return optics.for_case(self)
        return sections.table_of(self.optics)

    def section(self, name: str):
        """The case's section name (one of fields.SECTIONS) as its own frozen record
        (:func:`lightsail_mbs.model.sections.records`). A field whose default follows other fields (FieldInfo
        .follows: beam_centre, bending, …) is None there while it holds that default, as in a case file, so
        that it follows the case the record joins (from_sections) rather than the one it came from."""
        check("section", name, name in SECTION_RECORDS, f"one of {', '.join(SECTION_RECORDS)}")
        record_class = SECTION_RECORDS[name]
        followed = type(self)(model=self.model, length=self.length, width=self.width)
        values = {f.name: getattr(self, f.name) for f in dataclasses.fields(record_class)}
        for key, value in values.items():
            if FIELDS[key].follows and value == getattr(followed, key):
                values[key] = None
        return record_class(**values)

    @classmethod
    def from_sections(cls, *records, **fields) -> SailParameters:
        """The case of section records (one per section at most; a section left out keeps its defaults) and
        of fields given by name over them."""
        merged: dict = {}
        kinds = tuple(SECTION_RECORDS.values())
        for part in records:
            check("sections", part, isinstance(part, kinds), "section records (SailParameters.section(name))")
        names = [part.name for part in records]
        for part in records:
            check("sections", names, names.count(part.name) == 1, "one record per section")
            merged.update(dataclasses.asdict(part))
        return cls(**{**merged, **fields})

    @property
    def optics_file(self) -> bool:
        """Whether the force law comes from a table file (``optics`` is a path)."""
        return self.optics not in (None, "mirror")

    @property
    def optics_digest(self) -> str | None:
        """The digest of the table file's content (OpticalTable.digest) when ``optics`` is a path, else None:
        what identifies the case's force law, since the file at a path can be rewritten."""
        return self.optical_table().digest if self.optics_file else None

    @property
    def flat_force(self) -> float:
        """f₀ = (2 I₀ / c) l W: radiation force on a flat slice (Eq. 11)."""
        return 2.0 * self.intensity / SPEED_OF_LIGHT * self.slice_length * self.width

    @property
    def nominal_acceleration(self) -> float:
        """g₀ = (2R + α) Ī / (c ρ h): the flat sail's acceleration (Eq. 4, first order, for R = 1,
        α = 0 and a uniform beam: 2 I₀ / (c ρ h)); with an optical table, c_n(0) Ī / (c ρ h); with a payload
        of mass m_p, times M_sail/(M_sail + m_p) (the whole craft accelerates)."""
        momentum = self.normal_momentum
        if self.payload_mass > 0:  # the whole craft accelerates: c_n(0) Ī A / (c (M_sail + m_p))
            sail = self.density * self.thickness * self.sail_area
            return (
                momentum
                * self.mean_intensity
                / (SPEED_OF_LIGHT * self.density * self.thickness)
                * (sail / (sail + self.payload_mass))
            )
        return momentum * self.mean_intensity / (SPEED_OF_LIGHT * self.density * self.thickness)

    def _spectrum_in_run(self) -> bool:
        """Whether the run reads its optical table at the sail-frame wavelength of its state: a table file with a
        wavelength axis and integrated_trajectory (model/terms/radiation.py)."""
        if not (self.integrated_trajectory and self.optics_file):
            return False
        from lightsail_mbs.model.optics_spectrum import read_spectrum

        return read_spectrum(self.optics, single=True) is not None

    @property
    def trajectory_acceleration(self) -> float:
        """The craft's proper acceleration at rest along its trajectory (the Doppler factor's, terms/doppler.py):
        g₀, times (M_sail + m_p)/(M_sail + m_p + m_carried) with a carried mass the model has no body for."""
        if self.carried_mass == 0:
            return self.nominal_acceleration
        bodies = self.density * self.thickness * self.length * self.width + self.payload_mass
        return self.nominal_acceleration * bodies / (bodies + self.carried_mass)

    def replace(self, **changes) -> SailParameters:
        """A copy with some fields changed (validated again)."""
        if "model" in changes and "bending" not in changes:
            changes["bending"] = None
        return dataclasses.replace(self, **changes)

    @classmethod
    def from_toml(cls, path) -> SailParameters:
        """The case of a case file (:mod:`lightsail_mbs.model.casefile`; its [run] table:
        :func:`run_settings_of_case_file`).
        ParameterError, naming the file and the key, for a bad file or value."""
        return case_of(path, **read_case_file(path)[0])

    def to_toml(self, path, settings=None):
        """Write this case as a case file (:func:`~lightsail_mbs.model.casefile.write_case`), with settings (a
        RunSettings) as its [run] table."""
        return casefile.write_case(path, self, settings)

    def to_dict(self) -> dict:
        """The fields as a dict (the validation fields, the later ones and the sheet's fields omitted at their
        defaults: :func:`lightsail_mbs.model.records.record`)."""
        return record(dataclasses.asdict(self))

    @classmethod
    def from_dict(cls, d: dict) -> SailParameters:
        """The case of a dict from to_dict; the names of older saved runs (LEGACY_NAMES) are read too
        and their run-control entries (RUN_FIELDS) skipped. An unknown key raises ParameterError."""
        names = {f.name for f in dataclasses.fields(cls)}
        for old, name in LEGACY_NAMES.items():
            check(old, d.get(old), old not in d or name not in d, f"one of {old} and {name} (the same field)")
        known = current_names(d)
        for key in known:
            check("parameters", key, key in names, f"field names of SailParameters ({', '.join(sorted(names))})")
        return cls(**known)


SailParameters.__init__ = sections.checked_init(SailParameters.__init__)


DEFAULTS = {f.name: f.default for f in dataclasses.fields(SailParameters)}
SECTION_RECORDS = sections.records(SailParameters)  # section name -> its frozen record class


def read_case_file(path) -> tuple[dict, dict]:
    """(the case's fields, the [run] table) of a case file, names and types checked
    (:func:`lightsail_mbs.model.casefile.read`), a named material's values under the file's own
    (:func:`lightsail_mbs.model.materials.fill`); ParameterError naming the file and the key."""
    fields = {f.name: (f.type, FIELDS[f.name].allowed) for f in dataclasses.fields(SailParameters)}
    try:
        case, run = casefile.read(path, fields)
        return materials.fill(case), run
    except casefile.CaseFileError as exc:
        raise ParameterError(str(exc)) from None
    except ParameterError as exc:
        raise ParameterError(f"{path}: {exc}") from None


def run_settings_of_case_file(path):
    """The RunSettings of a case file's [run] table (the counterpart of SailParameters.to_toml's settings), or
    None when it has none; ParameterError naming the file and the key."""
    run = read_case_file(path)[1]
    if not run:
        return None
    try:
        return RunSettings(**run)
    except ParameterError as exc:
        raise ParameterError(f"{path}: [run] {exc}") from None


def case_of(source, **fields) -> SailParameters:
    """``SailParameters(**fields)``, a ParameterError prefixed with source (the file the fields come from)."""
    try:
        return SailParameters(**fields)
    except ParameterError as exc:
        raise ParameterError(f"{source}: {exc}") from None
