"""Sail films as data: mechanical, thermal and optical properties with their sources.

Each :class:`Material` holds what the case and the heat balance of a sail need: Young's modulus E, Poisson
ratio ν, density ρ, linear thermal expansion α_T, specific heat c_p, in-plane conductivity k, hemispherical
emissivities of the front (laser-facing) and back faces, the absorptance A of the film at the beam's 1.064 µm,
and a limit temperature T_lim (the temperature the film must stay below: melting, decomposition, or the
failure temperature its source states). Every value carries the key of its source (REFERENCES); values that
are an order of magnitude for a film of the stated kind, not a measurement of it, carry the key ``estimate``
with what they are based on. docs/materials.md lists them all (made from this table,
:func:`markdown_table`).

The emissivity and the absorptance of a film depend on its thickness and structure (a photonic crystal or a
grating changes both); the values here are those of the film the source describes. The absorptance enters
only the heat balance (:mod:`lightsail_mbs.model.thermal`); the case's ``absorptivity`` is the optics'
(the force law's) and is not filled from the material.

``--material NAME`` (the case field ``material``) fills the case's ``density`` and ``youngs_modulus`` from the
table (:func:`fill`); options and case-file entries given explicitly override them.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import NamedTuple

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

from lightsail_mbs.base.validation import ParameterError


class Value(NamedTuple):
    value: float
    source: str  # a key of REFERENCES


REFERENCES = {
    "flexsailsim": "Gao, Kelzenberg & Atwater, FlexSailSim (Starshot-Lightsail/FlexSailSim, "
    "setupMaterialProperties_v17.m), the material table of the flexible-lightsail simulations of "
    "R. Gao et al., Nat. Commun. 15, 4203 (2024); its Si₃N₄ entries cite D. J. Wilson (2009, 2012), "
    "H. Ftouni et al., Phys. Rev. B 92, 125439 (2015), M. Karuza et al. (2013), C. Zhang et al. (2020)",
    "atwater2018": "H. A. Atwater et al., Materials challenges for the Starshot lightsail, Nat. Mater. 17, 861 (2018)",
    "ilic2018": "O. Ilic, C. M. Went & H. A. Atwater, Nanophotonic heterostructures for efficient propulsion and "
    "radiative cooling of relativistic light sails, Nano Lett. 18, 5583 (2018)",
    "brewer2022": "J. Brewer et al., Multiscale photonic emissivity engineering for relativistic lightsail "
    "thermal regulation, Nano Lett. 22, 594 (2022)",
    "hopcroft2010": "M. A. Hopcroft, W. D. Nix & T. W. Kenny, What is the Young's modulus of silicon?, "
    "J. Microelectromech. Syst. 19, 229 (2010) (E along ⟨110⟩)",
    "okada1984": "Y. Okada & Y. Tokumaru, J. Appl. Phys. 56, 314 (1984): α_T of silicon at 300 K",
    "green2008": "M. A. Green, Self-consistent optical parameters of intrinsic silicon at 300 K, Sol. Energy "
    "Mater. Sol. Cells 92, 1305 (2008): absorption coefficient ≈ 10 /cm at 1.06 µm",
    "crc": "CRC Handbook of Chemistry and Physics, 97th ed. (2016): density, heat capacity, conductivity, "
    "melting point at 300 K",
    "corning7980": "Corning HPFS 7980 fused silica, product information (2014): E, ν, ρ, α_T, c_p, k, "
    "annealing point 1042 °C",
    "bertolazzi2011": "S. Bertolazzi, J. Brivio & A. Kis, Stretching and breaking of ultrathin MoS₂, ACS Nano 5, "
    "9703 (2011): E = 270 ± 100 GPa",
    "yan2014": "R. Yan et al., Thermal conductivity of monolayer MoS₂ by Raman spectroscopy, ACS Nano 8, "
    "986 (2014): 34.5 W/(m·K)",
    "rakic1995": "A. D. Rakić, Algorithm for the determination of intrinsic optical constants of metal films: "
    "application to aluminum, Appl. Opt. 34, 4755 (1995): R ≈ 0.94 at 1.06 µm",
    "incropera": "F. P. Incropera et al., Fundamentals of Heat and Mass Transfer, 6th ed., Table A.11: "
    "polished aluminium ε ≈ 0.03–0.04",
    "dupont_kapton": "DuPont, Kapton HN polyimide film, general specifications (2017): E, ν, ρ, α_T, c_p, k, "
    "service temperature up to 400 °C",
    "sheldahl": "Sheldahl, The Red Book (thermal control films): 25 µm Kapton ε ≈ 0.5–0.6",
    "starshot_forum": "Breakthrough Initiatives, Starshot challenges, 'Lightsail | Integrity under thrust' "
    "(breakthroughinitiatives.org): absorption below 1e-9 for optimised dielectrics",
    "mos2_tec2019": "Thermal expansion coefficient of monolayer molybdenum disulfide using micro-Raman spectroscopy, "
    "Nano Lett. 19 (2019), doi:10.1021/acs.nanolett.9b01829: in-plane α_T = (7.6 ± 0.9) and (7.4 ± 0.5) × 1e-6 /K",
    "vasilyeva2015": "I. G. Vasilyeva, I. P. Asanov & L. M. Kulikov, Experiments and consideration about surface "
    "nonstoichiometry of few-layer MoS₂ prepared by chemical vapor deposition, J. Phys. Chem. C (2015): incongruent "
    "evaporation (sulfur loss) in vacuum above 1000 K",
    "estimate": "an order-of-magnitude value for the film described, stated as an assumption (see the note)",
}


@dataclass(frozen=True)
class Material:
    """One film: its properties as (value, source) pairs, SI units."""

    name: str
    description: str
    youngs_modulus: Value  # E, Pa
    poisson_ratio: Value  # ν
    density: Value  # ρ, kg/m³
    thermal_expansion: Value  # α_T, 1/K
    heat_capacity: Value  # c_p, J/(kg·K)
    conductivity: Value  # k, W/(m·K)
    emissivity_front: Value  # ε_f, the laser-facing face
    emissivity_back: Value  # ε_b
    absorptance: Value  # A at 1.064 µm
    limit_temperature: Value  # T_lim, K
    note: str = ""

    def value(self, prop: str) -> float:
        """The property's value (SI)."""
        return getattr(self, prop).value

    @property
    def emissivity(self) -> float:
        """ε_f + ε_b: the total emissivity the two faces radiate with."""
        return self.emissivity_front.value + self.emissivity_back.value


PROPERTIES = {  # property -> (symbol, unit) for the docs' table
    "youngs_modulus": ("E", "GPa"),
    "poisson_ratio": ("ν", ""),
    "density": ("ρ", "kg/m³"),
    "thermal_expansion": ("α_T", "1e-6/K"),
    "heat_capacity": ("c_p", "J/(kg·K)"),
    "conductivity": ("k", "W/(m·K)"),
    "emissivity_front": ("ε_f", ""),
    "emissivity_back": ("ε_b", ""),
    "absorptance": ("A(1.064 µm)", ""),
    "limit_temperature": ("T_lim", "K"),
}
_DISPLAY_SCALE = {"youngs_modulus": 1e-9, "thermal_expansion": 1e6}

DATA_FILE = Path(__file__).with_name("materials.toml")  # the table itself: one [name] table per film


def _read(path: Path) -> dict:
    """The materials of the data file: name -> Material (each property a [value, source] pair)."""
    with path.open("rb") as handle:
        data = tomllib.load(handle)
    table = {}
    for name, entry in data.items():
        values = {prop: Value(float(entry[prop][0]), str(entry[prop][1])) for prop in PROPERTIES}
        table[name] = Material(name, entry["description"], **values, note=entry.get("note", ""))
    return table


MATERIALS = _read(DATA_FILE)


def get(name: str) -> Material:
    """The material of this name; ParameterError (one line, the allowed names) for an unknown one."""
    if name not in MATERIALS:
        raise ParameterError(f"material={name!r} is invalid: allowed one of {', '.join(MATERIALS)}")
    return MATERIALS[name]


# the case's fields a material fills, and the material's property each comes from
CASE_FIELDS = {"density": "density", "youngs_modulus": "youngs_modulus"}


def case_fields(name: str) -> dict:
    """The case fields the material sets (CASE_FIELDS), as a dict of values."""
    material = get(name)
    return {field: material.value(prop) for field, prop in CASE_FIELDS.items()}


def fill(fields: dict, source: dict | None = None) -> dict:
    """The case fields with the material's filled in: the material named in fields (or else in source) sets
    CASE_FIELDS under the explicit entries of fields; entries of source (a case file) apply beneath the
    material when fields names it and above it when the source names it."""
    source = source or {}
    if fields.get("material") is not None:
        return {**source, **case_fields(fields["material"]), **fields}
    if source.get("material") is not None:
        return {**case_fields(source["material"]), **source, **fields}
    return {**source, **fields}


def markdown_table() -> str:
    """The table of every material's values, each with its source key (docs/materials.md)."""
    head = "| material | " + " | ".join(f"{s} ({u})" if u else s for s, u in PROPERTIES.values()) + " |"
    rows = [head, "|" + "---|" * (len(PROPERTIES) + 1)]
    for m in MATERIALS.values():
        cells = []
        for prop in PROPERTIES:
            v = getattr(m, prop)
            cells.append(f"{v.value * _DISPLAY_SCALE.get(prop, 1.0):.4g} [{v.source}]")
        rows.append(f"| `{m.name}` | " + " | ".join(cells) + " |")
    return "\n".join(rows)
