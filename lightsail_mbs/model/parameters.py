"""The case: one validated, immutable parameter set per simulation (SI units throughout).

Paper: Sections III–IV. Derived quantities follow the paper's definitions:
slice length l = L/n, slice mass m = ρ h W l, centroidal inertia J = m l²/12,
bending stiffness k_T = E I / l with I = W h³/12 (Sec. III.B),
axial stiffness k_s = (n − 1) E h W / L (Sec. III.C).

Two model families share this one parameter class. The chains ("rigid", "torsion", "tnt") are the
paper's strip of n slices. The "sheet" is the sail cut into n × ny rigid tiles moving in 3-D
(:mod:`lightsail_mbs.model.sheet`); its own fields (ny, defect_mode_y, membrane_modulus,
edge_tension, beam_center_y, pressure, membrane_damping, membrane_reference, bending_reference,
initial_equilibrium) are listed in
SHEET_DEFAULTS, rejected away from their defaults for a chain, and left out of :meth:`to_dict` at
their defaults, so the record (and the store key) of every chain case is what it was before the
sheet existed.
"""

from __future__ import annotations

import dataclasses
import math
import numbers
from dataclasses import dataclass

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.base.validation import ParameterError, check, finite

MODELS = ("rigid", "torsion", "tnt", "sheet")
CHAIN_MODELS = ("rigid", "torsion", "tnt")
# Supports of the chain's ends (validations, paper Appendices A–B): "free" (the sail, both ends free),
# "cantilever" (slice 1 clamped at its initial pose, Appendix A), "pinned" (hinge 0 pinned, hinge n on a
# roller along x that lets the end tension T through: a string or simply supported beam, Appendix B).
BOUNDARIES = ("free", "cantilever", "pinned")
# Supports of the sheet's four edges (the plate and membrane validations): "free" (the sail),
# "simply_supported" (w = 0 along every edge, no bending moment), "clamped" (w = 0 and no rotation).
SHEET_BOUNDARIES = ("free", "simply_supported", "clamped")
# Fields of the validations that to_dict omits at their defaults (a free, unloaded sail), so that the
# record of a sail lists only what describes it.
VALIDATION_DEFAULTS = {"boundary": "free", "tip_load": 0.0, "tip_load_time_constant": 0.0}
# The sheet's own fields at their defaults: omitted by to_dict, and the only values a chain accepts.
SHEET_DEFAULTS = {
    "ny": 1,
    "defect_mode_y": None,
    "membrane_modulus": None,
    "edge_tension": 0.0,
    "beam_center_y": None,
    "pressure": 0.0,
    "membrane_damping": None,
    "membrane_reference": "initial",
    "bending_reference": "flat",
    "initial_equilibrium": False,
}
MEMBRANE_REFERENCES = ("initial", "flat")
BENDING_REFERENCES = ("flat", "initial")
# Fields added after the store's keys were first written, omitted by to_dict at their defaults so that the
# record (and store key) of every case that does not use them stays what it was.
LATER_DEFAULTS = {
    "billow_radius": math.inf,
    "optics": None,
    "optics_layout": "uniform",
    "payload_mass": 0.0,
    "payload_inertia": 0.0,
    "payload_stem": 0.0,
    "billow_rest": False,
    "initial_tilt": 0.0,
    "roughness": 0.0,
    "roughness_seed": 0,
}
# How the slices carry an optical table: all alike, or the right half turned over (t → −t; model/optics.py).
OPTICS_LAYOUTS = ("uniform", "mirrored-halves")
# Names under which saved runs and store records written before the current field names hold them.
LEGACY_NAMES = {"amplitude": "defect_amplitude", "mode": "defect_mode", "defect_modes": "defect_mode_count"}
# Smallest non-zero defect amplitude, as a fraction of L: the solvers scale their tolerances with a₀, and the
# reduced solver's first-step estimate underflows for a₀ ≲ 1e-200 m. (Physically, anything below ~1e-12 L is
# round-off already: shapes.defect_warnings says so.)
MIN_DEFECT_FRACTION = 1e-100
# Run control that saved runs of that format kept with the case (now solvers.settings.RunSettings).
RUN_FIELDS = ("t_final", "output_interval", "stop_at_failure", "failure_ratio")


def _as_float(value) -> float:
    """float(value), NaN where that fails (an int beyond the float range)."""
    try:
        return float(value)
    except (TypeError, ValueError, OverflowError):
        return math.nan


@dataclass(frozen=True)
class SailParameters:
    """One lightsail case: the sail, its supports, its defect and the beam (SI units).

    Defaults: the paper's torsion study (Sec. IV.B, Fig. 6). Run control (duration, sampling, stop
    rule) is a separate :class:`~lightsail_mbs.solvers.settings.RunSettings`. Every field is checked
    on construction; a bad value raises :class:`ParameterError` naming the field and its range.
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
    beam_waist: float = math.inf  # w, m: Gaussian beam I₀ exp(−2(x − x_c)²/w²); inf = uniform (paper)
    beam_center: float | None = None  # x_c, m; None: the sail's middle L/2
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
    # ---- the sheet (model="sheet": n × ny tiles; model.sheet) -------------------------------------
    ny: int = 1  # tiles across the width W (n tiles along L)
    defect_mode_y: float | None = None  # ν_y: w = a₀ sin(2πνx/L) sin(2πν_y y/W); None: uniform across W
    membrane_modulus: float | None = None  # E_m, Pa, of the in-plane (membrane) springs; None: E
    edge_tension: float = 0.0  # T, N per metre of edge: follower tension on all four edges + pre-stress
    beam_center_y: float | None = None  # y_c, m, of the Gaussian beam; None: W/2
    pressure: float = 0.0  # p, Pa: dead pressure along the beam (+z) (the plate validations)
    membrane_damping: float | None = None  # β_m, s: damping β_m k on the stiff springs; None: critical
    membrane_reference: str = "initial"  # in-plane springs at rest in the "initial" (defect) or "flat" shape
    bending_reference: str = "flat"  # bending springs at rest "flat" (the paper: an elastically loaded defect)
    #                                  or in the "initial" shape (a stress-free, manufactured defect)
    initial_equilibrium: bool = False  # True: the springs' rest state is corrected so that the unlit sheet
    #                                    (edge tension included) is at rest in the initial shape (model.sheet)
    billow_radius: float = math.inf  # R_c, m: initial circular arc (shapes.py); > 0 concave to the laser; inf: flat
    optics: str | None = None  # the slices' force law from a table: None (R, α above), "mirror", or a table file
    optics_layout: str = "uniform"  # one of OPTICS_LAYOUTS: which slices carry the table turned over
    payload_mass: float = 0.0  # m_p, kg: a payload on a rigid stem from the sail's middle (model/payload.py)
    payload_inertia: float = 0.0  # J_p, kg·m²: its inertia about its own centre
    payload_stem: float = 0.0  # d, m: the stem's length from the sail's middle towards the laser (−ŷ)
    billow_rest: bool = False  # torsion springs at rest on the billowed arc (a sail made curved); False: flat
    initial_tilt: float = 0.0  # rad: the initial shape turned counter-clockwise about the craft's centre of mass

    def __post_init__(self):
        check("model", self.model, self.model in MODELS, f"one of {', '.join(MODELS)}")
        check(
            "n",
            self.n,
            isinstance(self.n, int) and not isinstance(self.n, bool) and 2 <= self.n <= 5000,
            "an integer 2 ≤ n ≤ 5000",
        )
        for name in ("length", "width", "thickness", "density"):
            v = finite(name, getattr(self, name))
            check(name, v, v > 0, "> 0")
        for name in (
            "youngs_modulus",
            "tension",
            "intensity",
            "defect_amplitude",
            "torsional_damping",
            "axial_damping",
            "stiffness_damping",
        ):
            v = finite(name, getattr(self, name))
            check(name, v, v >= 0, "≥ 0")
        check(
            "youngs_modulus",
            self.youngs_modulus,
            self.youngs_modulus > 0 or not (self.model == "tnt" and self.axial_springs),
            "> 0 for the tnt model with axial springs",
        )
        check(
            "defect_seed",
            self.defect_seed,
            self.defect_seed is None
            or (isinstance(self.defect_seed, int) and not isinstance(self.defect_seed, bool) and self.defect_seed >= 0),
            "None or an integer ≥ 0",
        )
        check(
            "defect_mode_count",
            self.defect_mode_count,
            isinstance(self.defect_mode_count, int)
            and not isinstance(self.defect_mode_count, bool)
            and 1 <= self.defect_mode_count <= 200,
            "an integer 1 ≤ K ≤ 200",
        )
        finite("defect_spectrum", self.defect_spectrum)
        v = finite("roughness", self.roughness)
        check(
            "roughness",
            v,
            0 <= v < self.length / (2 * math.pi * self.n),
            f"0 ≤ roughness < L/(2πn) = "
            f"{self.length / (2 * math.pi * self.n):.3g} m (slopes of its shortest waves below 45°)",
        )
        check(
            "roughness_seed",
            self.roughness_seed,
            isinstance(self.roughness_seed, int)
            and not isinstance(self.roughness_seed, bool)
            and self.roughness_seed >= 0,
            "an integer ≥ 0",
        )
        waist = self.beam_waist
        check(
            "beam_waist",
            waist,
            not isinstance(waist, bool) and isinstance(waist, numbers.Real) and _as_float(waist) > 0,
            "> 0 (inf for a uniform beam)",
        )
        if self.beam_center is None:
            object.__setattr__(self, "beam_center", 0.5 * self.length)
        finite("beam_center", self.beam_center)
        for name in ("reflectivity", "absorptivity"):
            v = finite(name, getattr(self, name))
            check(name, v, 0 <= v <= 1, "0 ≤ value ≤ 1")
        check(
            "absorptivity",
            self.absorptivity,
            self.reflectivity + self.absorptivity <= 1,
            f"≤ 1 − reflectivity = {1 - self.reflectivity:g} (R + α + transmissivity = 1)",
        )
        check(
            "reflectivity",
            self.reflectivity,
            2 * self.reflectivity + self.absorptivity > 0,
            "> 0 or absorptivity > 0 (a transparent sail feels no load)",
        )
        v = finite("defect_mode", self.defect_mode)
        check("defect_mode", v, v > 0, "> 0 (whole or half integers in the paper)")
        check(
            "tension",
            self.tension,
            self.tension == 0 or self.model == "tnt",
            "0 unless model='tnt' (boundary tension exists only in the TnT model; a sheet's is edge_tension, N/m)",
        )
        finite("tip_load", self.tip_load)
        v = finite("tip_load_time_constant", self.tip_load_time_constant)
        check("tip_load_time_constant", v, v >= 0, "≥ 0 (0: the full load from t = 0)")
        ok_type = isinstance(self.billow_radius, (int, float)) and not isinstance(self.billow_radius, bool)
        R = float(self.billow_radius) if ok_type else math.nan
        r_min = self.slice_length / (2.0 * math.sin(math.pi / (2 * self.n)))
        check(
            "billow_radius",
            self.billow_radius,
            not math.isnan(R) and abs(R) >= r_min,
            f"|R_c| ≥ {r_min:.4g} m (the arc of n chords of length l subtends at most 180°), > 0 concave to the "
            "laser, < 0 convex, inf for a flat sail",
        )
        check(
            "billow_radius",
            self.billow_radius,
            math.isinf(R) or self.boundary == "free",
            "inf (flat) unless boundary='free' (the supports hold a flat chain)",
        )
        self._check_optics()
        self._check_payload()
        check("billow_rest", self.billow_rest, isinstance(self.billow_rest, bool), "True or False")
        v = finite("initial_tilt", self.initial_tilt)
        check("initial_tilt", v, abs(v) < math.pi / 2, "|tilt| < π/2 rad")
        check("initial_tilt", v, v == 0 or self.boundary == "free", "0 unless boundary='free'")
        check(
            "billow_rest",
            self.billow_rest,
            not self.billow_rest or not math.isinf(float(self.billow_radius)),
            "False for a flat sail (billow_radius = inf)",
        )
        self._check_sheet_fields()
        if self.bending is None:
            object.__setattr__(self, "bending", self.model in ("torsion", "sheet"))
        check("bending", self.bending, isinstance(self.bending, bool), "True, False or None")
        check(
            "defect_amplitude",
            self.defect_amplitude,
            self.defect_amplitude == 0 or self.defect_amplitude >= MIN_DEFECT_FRACTION * self.length,
            f"0 or ≥ {MIN_DEFECT_FRACTION:g} L = {MIN_DEFECT_FRACTION * self.length:.3g} m (the solvers' "
            "tolerances scale with a₀; below this they underflow)",
        )
        check(
            "defect_amplitude",
            self.defect_amplitude,
            self.defect_amplitude < self.length / (2 * math.pi * self.defect_mode),
            f"< L/(2πν) = {self.length / (2 * math.pi * self.defect_mode):.3g} m (a sine steeper than 45° "
            "is outside the model)",
        )

    def _check_sheet_fields(self) -> None:
        """The sheet's fields: at their defaults for a chain; in range for a sheet."""
        if self.model != "sheet":
            for name, default in SHEET_DEFAULTS.items():
                check(name, getattr(self, name), getattr(self, name) == default, f"{default!r} unless model='sheet'")
            check("boundary", self.boundary, self.boundary in BOUNDARIES, f"one of {', '.join(BOUNDARIES)}")
            return
        check(
            "ny",
            self.ny,
            isinstance(self.ny, int) and not isinstance(self.ny, bool) and 1 <= self.ny <= 500,
            "an integer 1 ≤ ny ≤ 500",
        )
        check("n", self.n, self.n <= 500, "an integer 2 ≤ n ≤ 500 for a sheet (n × ny tiles)")
        check(
            "boundary",
            self.boundary,
            self.boundary in SHEET_BOUNDARIES,
            f"one of {', '.join(SHEET_BOUNDARIES)} for a sheet",
        )
        check("tip_load", self.tip_load, self.tip_load == 0, "0 for a sheet (a chain validation)")
        check("billow_radius", self.billow_radius, self.billow_radius == math.inf, "inf (flat) for a sheet")
        check("billow_rest", self.billow_rest, self.billow_rest is False, "False for a sheet")
        check("initial_tilt", self.initial_tilt, self.initial_tilt == 0, "0 for a sheet")
        check("optics", self.optics, self.optics is None, "None for a sheet (its tiles: reflectivity, absorptivity)")
        check("payload_mass", self.payload_mass, self.payload_mass == 0, "0 for a sheet")
        for name in ("torsional_damping", "axial_damping"):
            check(name, getattr(self, name), getattr(self, name) == 0, "0 for a sheet (its damping: stiffness_damping)")
        if self.defect_mode_y is not None:
            v = finite("defect_mode_y", self.defect_mode_y)
            check("defect_mode_y", v, v > 0, "None (uniform across the width) or > 0")
            check(
                "defect_amplitude",
                self.defect_amplitude,
                self.defect_amplitude < self.width / (2 * math.pi * v),
                f"< W/(2πν_y) = {self.width / (2 * math.pi * v):.3g} m (a sine steeper than 45° is outside the model)",
            )
        for name in ("edge_tension", "pressure"):
            finite(name, getattr(self, name))
        check("edge_tension", self.edge_tension, self.edge_tension >= 0, "≥ 0 (N per metre of edge)")
        if self.membrane_modulus is not None:
            v = finite("membrane_modulus", self.membrane_modulus)
            check("membrane_modulus", v, v > 0, "> 0 or None (= youngs_modulus)")
        else:
            check(
                "membrane_modulus",
                self.membrane_modulus,
                self.youngs_modulus > 0,
                "> 0 when youngs_modulus = 0 (the in-plane springs hold the tiles together)",
            )
        if self.membrane_damping is not None:
            v = finite("membrane_damping", self.membrane_damping)
            check("membrane_damping", v, v >= 0, "≥ 0 s or None (critical for the top in-plane mode)")
        if self.beam_center_y is not None:
            finite("beam_center_y", self.beam_center_y)
        check(
            "membrane_reference",
            self.membrane_reference,
            self.membrane_reference in MEMBRANE_REFERENCES,
            f"one of {', '.join(MEMBRANE_REFERENCES)}",
        )
        check(
            "bending_reference",
            self.bending_reference,
            self.bending_reference in BENDING_REFERENCES,
            f"one of {', '.join(BENDING_REFERENCES)}",
        )
        check(
            "initial_equilibrium", self.initial_equilibrium, isinstance(self.initial_equilibrium, bool), "True or False"
        )

    def _check_optics(self) -> None:
        check("optics_layout", self.optics_layout, self.optics_layout in OPTICS_LAYOUTS, " or ".join(OPTICS_LAYOUTS))
        if self.optics is None:
            check("optics_layout", self.optics_layout, self.optics_layout == "uniform", "'uniform' without optics")
            return
        allowed = "None, 'mirror' or the path of an optical table file (.npz, from lightsail-mbs optics … --out)"
        check("optics", self.optics, isinstance(self.optics, str) and self.optics != "", allowed)
        for name in ("reflectivity", "absorptivity"):
            check(name, getattr(self, name), getattr(self, name) == (name == "reflectivity"), "its default with optics")
        self.optical_table()  # reads the file now: a bad one is refused before any solving

    def _check_payload(self) -> None:
        for name in ("payload_mass", "payload_inertia", "payload_stem"):
            v = finite(name, getattr(self, name))
            check(name, v, v >= 0, "≥ 0")
        if self.payload_mass == 0:
            for name in ("payload_inertia", "payload_stem"):
                check(name, getattr(self, name), getattr(self, name) == 0, "0 without a payload (payload_mass = 0)")
            return
        check("payload_mass", self.payload_mass, self.boundary == "free", "0 unless boundary='free'")
        check("payload_mass", self.payload_mass, self.n >= 3, "0 for n < 3 (the payload slice is not an end slice)")
        check(
            "payload_mass",
            self.payload_mass,
            not (self.model == "tnt" and self.axial_springs),
            "0 for the extensible TnT chain (axial_springs=False: its inextensible limit carries one)",
        )

    def optical_table(self):
        """The slices' force law as a :class:`~lightsail_mbs.model.optics.OpticalTable`: the file `optics`
        (read once per path and modification time), the built-in mirror for 'mirror', and for None the
        built-in mirror or facet of reflectivity and absorptivity."""
        from lightsail_mbs.model import optics

        if self.optics is None:
            return optics.for_case(self)
        if self.optics == "mirror":
            return optics.mirror()
        try:
            return optics.read_table(self.optics)
        except optics.OpticsFileError as exc:
            raise ParameterError(f"optics={self.optics!r} is invalid: {exc}") from None

    @property
    def optics_file(self) -> bool:
        """Whether the force law comes from a table file (``optics`` is a path)."""
        return self.optics not in (None, "mirror")

    @property
    def optics_digest(self) -> str | None:
        """The digest of the table file's content (OpticalTable.digest) when ``optics`` is a path, else None:
        what identifies the case's force law, since the file at a path can be rewritten."""
        return self.optical_table().digest if self.optics_file else None

    # ---- derived quantities (paper Sec. III) -------------------------------------------------
    @property
    def slice_length(self) -> float:
        """l = L / n."""
        return self.length / self.n

    @property
    def slice_mass(self) -> float:
        """m = ρ h W l."""
        return self.density * self.thickness * self.width * self.slice_length

    @property
    def slice_inertia(self) -> float:
        """J = m l² / 12 about the slice centre."""
        return self.slice_mass * self.slice_length**2 / 12.0

    @property
    def second_moment_of_area(self) -> float:
        """I = W h³ / 12."""
        return self.width * self.thickness**3 / 12.0

    @property
    def torsional_stiffness(self) -> float:
        """k_T = E I / l (0 for the rigid model or with bending off)."""
        if self.model == "rigid" or not self.bending:
            return 0.0
        return self.youngs_modulus * self.second_moment_of_area / self.slice_length

    @property
    def rest_turn(self) -> float:
        """δ = θ_{k+1} − θ_k of the unstressed sail: −2 asin(l/(2R_c)) when the springs are at rest on the billowed
        arc (billow_rest), else 0 (flat); the torsion springs act on θ_{k+1} − θ_k − δ."""
        if not self.billow_rest:
            return 0.0
        return -2.0 * math.asin(self.slice_length / (2.0 * float(self.billow_radius)))

    @property
    def axial_stiffness(self) -> float:
        """k_s = (n − 1) E h W / L (TnT only; inf in the inextensible limit)."""
        if self.model != "tnt":
            return math.inf
        if not self.axial_springs:
            return math.inf
        return (self.n - 1) * self.youngs_modulus * self.thickness * self.width / self.length

    @property
    def total_torsional_damping(self) -> float:
        """c_T + β k_T (N·m·s/rad) on the relative rate θ̇_j − θ̇_{j−1} of each interior hinge (0: rigid)."""
        if self.model == "rigid":
            return 0.0
        return self.torsional_damping + self.stiffness_damping * self.torsional_stiffness

    @property
    def total_axial_damping(self) -> float:
        """c_s + β k_s (N·s/m) on each axial spring rate ż_j (0 without axial springs)."""
        if not self.extensible:
            return 0.0
        return self.axial_damping + self.stiffness_damping * self.axial_stiffness

    @property
    def extensible(self) -> bool:
        """True when the chain has axial spring coordinates z₁…z_{n−1}."""
        return self.model == "tnt" and self.axial_springs

    @property
    def displacement_scale(self) -> float:
        """Typical transverse displacement for solver tolerances: a₀, or 1e-6 L for a flat sail."""
        return self.defect_amplitude if self.defect_amplitude > 0 else 1e-6 * self.length

    @property
    def flat_force(self) -> float:
        """f₀ = (2 I₀ / c) l W: radiation force on a flat slice (Eq. 11)."""
        return 2.0 * self.intensity / SPEED_OF_LIGHT * self.slice_length * self.width

    @property
    def uniform_beam(self) -> bool:
        return math.isinf(self.beam_waist)

    @property
    def mean_intensity(self) -> float:
        """Ī: the beam intensity averaged over the flat sail 0 ≤ x ≤ L (and 0 ≤ y ≤ W for a sheet, whose
        Gaussian beam is round; I₀ for the uniform beam)."""
        if self.uniform_beam:
            return self.intensity
        mean = self.intensity * _gaussian_mean(self.beam_waist, self.beam_center, self.length)
        if self.model == "sheet":  # the sheet's beam is round: I₀ exp(−2((x − x_c)² + (y − y_c)²)/w²)
            mean *= _gaussian_mean(self.beam_waist, self.sheet_beam_center_y, self.width)
        return mean

    @property
    def normal_momentum(self) -> float:
        """c_n(0): the momentum the flat sail takes from the light, per photon momentum incident on it —
        2R + α for the R/α facet (2 for the paper's mirror), the table's c_n(0) with an optical table."""
        if self.optics is None:
            return 2.0 * self.reflectivity + self.absorptivity
        return self.optical_table().normal_at_zero

    @property
    def nominal_acceleration(self) -> float:
        """g₀ = (2R + α) Ī / (c ρ h): the flat sail's acceleration (Eq. 4, first order, for R = 1,
        α = 0 and a uniform beam: 2 I₀ / (c ρ h)); with an optical table, c_n(0) Ī / (c ρ h); with a payload
        of mass m_p, times M_sail/(M_sail + m_p) (the whole craft accelerates)."""
        momentum = self.normal_momentum
        if self.payload_mass > 0:  # the whole craft accelerates: c_n(0) Ī L W / (c (M_sail + m_p))
            sail = self.density * self.thickness * self.length * self.width
            return (
                momentum
                * self.mean_intensity
                / (SPEED_OF_LIGHT * self.density * self.thickness)
                * (sail / (sail + self.payload_mass))
            )
        return momentum * self.mean_intensity / (SPEED_OF_LIGHT * self.density * self.thickness)

    @property
    def sheet_beam_center_y(self) -> float:
        """y_c of the sheet's Gaussian beam (m): beam_center_y, or W/2 when it is None."""
        return 0.5 * self.width if self.beam_center_y is None else float(self.beam_center_y)

    def replace(self, **changes) -> SailParameters:
        """A copy with some fields changed (validated again)."""
        if "model" in changes and "bending" not in changes:
            changes["bending"] = None
        return dataclasses.replace(self, **changes)

    def tip_force(self, t):
        """P(t) = P₀(1 − e^(−t/τ)) (paper Eq. 43; P₀ for τ = 0), N."""
        if self.tip_load_time_constant == 0:
            return self.tip_load
        return self.tip_load * -math.expm1(-t / self.tip_load_time_constant)

    def to_dict(self) -> dict:
        """The fields as a dict (the validation fields, the later ones and the sheet's fields omitted at their
        defaults)."""
        d = dataclasses.asdict(self)
        for name, default in {**VALIDATION_DEFAULTS, **LATER_DEFAULTS, **SHEET_DEFAULTS}.items():
            if d[name] == default:
                del d[name]
        return d

    @classmethod
    def from_dict(cls, d: dict) -> SailParameters:
        """The case of a dict from to_dict; the names of older saved runs (LEGACY_NAMES) are read too
        and their run-control entries (RUN_FIELDS) skipped. An unknown key raises ParameterError."""
        names = {f.name for f in dataclasses.fields(cls)}
        known = {}
        for key, value in d.items():
            key = LEGACY_NAMES.get(key, key)
            if key in RUN_FIELDS:
                continue
            check("parameters", key, key in names, f"field names of SailParameters ({', '.join(sorted(names))})")
            known[key] = value
        return cls(**known)


def _gaussian_mean(waist: float, center: float, span: float) -> float:
    """(1/span) ∫₀^span exp(−2(s − center)²/waist²) ds."""
    r = math.sqrt(2.0) / waist
    return math.sqrt(math.pi / 8.0) * waist / span * (math.erf(r * (span - center)) + math.erf(r * center))


def paper_case(name: str, **changes) -> SailParameters:
    """The paper's cases by name (Sec. IV): 'rigid' (Fig. 5), 'torsion-stable' (Fig. 6),
    'torsion-soft' (Fig. 7), 'tnt-stable' (Fig. 10), 'tnt-soft' (Fig. 11). Their runs:
    :func:`lightsail_mbs.solvers.settings.paper_settings`."""
    if name not in PAPER_CASES:
        raise ParameterError(f"case={name!r} is invalid: allowed one of {', '.join(PAPER_CASES)}")
    return SailParameters(**{**PAPER_CASES[name], **changes})


# The paper gives no E for its TnT runs; 1e11 Pa (a stiff polymer/ceramic film, k_s ≈ 2.9e6 N/m at n = 30)
TNT_DEFAULT_MODULUS = 1e11
PAPER_CASES = {
    "rigid": dict(model="rigid", n=40, intensity=1e11, defect_amplitude=1e-3, defect_mode=1.5),
    "torsion-stable": dict(model="torsion", youngs_modulus=4.5e13),
    "torsion-soft": dict(model="torsion", youngs_modulus=4.5e9),
    "tnt-stable": dict(model="tnt", tension=3.34e-3, youngs_modulus=TNT_DEFAULT_MODULUS),
    "tnt-soft": dict(model="tnt", tension=3.34e-8, youngs_modulus=TNT_DEFAULT_MODULUS),
}
