"""1-D gratings: their geometry, their materials and the named designs (the orders and forces they give by
RCWA: :mod:`lightsail_mbs.model.rcwa`).

**Geometry.** One period Λ of a grating whose grooves run along the sail's width (z), its grating
vector along the slice tangent t: a stack of layers listed from the side the laser light arrives on,
between vacuum on both sides. Each layer has a thickness, a background refractive index and bars;
a bar is an interval [start, end) in fractions of the period with its own refractive index. A layer
without bars is a uniform film. Refractive indices are n + iκ with κ ≥ 0 absorbing (time dependence
e^(−iωt)); they are given as numbers, as permittivities ε = (n + iκ)², or by the name of a material
in meent's tables (:func:`refractive_index`).
"""

from __future__ import annotations

import cmath
import hashlib
import json
import math
from dataclasses import dataclass

import numpy as np

from lightsail_mbs.base.validation import ParameterError, check, finite

# short names for the materials most lightsail designs use; any other name of meent's tables works too
MATERIAL_ALIASES = {"si": "SI_GREEN-2008", "sio2": "SIO2_MALITSON", "si3n4": "SI3N4_LUKE", "al2o3": "AL2O3_MALITSON-O"}
MAX_RASTER = 100_000  # cells per period that bar edges may need


def refractive_index(spec, wavelength: float | None = None, name: str = "index") -> complex:
    """n + iκ from a number (``3.48``, ``3.48+0.01j``), a permittivity (``eps=12.1``, ``eps=-20+1.5j``) or
    a material name of meent's tables (``Si`` = Green 2008, ``SiO2`` = Malitson 1965, or any name that
    ``meent.list_materials()`` shows), evaluated at the wavelength (m; needed for a material name only).
    κ < 0 (gain) is rejected."""
    if isinstance(spec, (int, float, complex)) and not isinstance(spec, bool):
        n = complex(spec)
    else:
        text = str(spec).strip()
        try:
            if text.lower().startswith("eps="):
                n = cmath.sqrt(complex(text[4:].replace(" ", "")))
                if n.imag < 0 or (n.imag == 0 and n.real < 0):
                    n = -n
            else:
                n = complex(text.replace(" ", ""))
        except ValueError:
            check(name, spec, wavelength is not None, "a number or eps=… here (a material name needs the wavelength)")
            n = _material_index(text, wavelength, name)
    check(name, spec, math.isfinite(n.real) and math.isfinite(n.imag), "a finite number, eps=…, or a material name")
    check(name, spec, n.imag >= 0, "κ = Im n ≥ 0 (absorbing or lossless; n + iκ convention)")
    check(name, spec, n.real > 0 or n.imag > 0, "Re n > 0 or Im n > 0")
    return n


def _material_index(text: str, wavelength: float, name: str) -> complex:
    import meent

    table = meent.read_material_table()
    key = MATERIAL_ALIASES.get(text.lower(), text.upper())
    check(
        name,
        text,
        key in table,
        f"a number, eps=…, or a material: {', '.join(MATERIAL_ALIASES)} or a name that meent.list_materials() "
        "shows (e.g. SI_GREEN-2008, AU_JOHNSON)",
    )
    info = next(m for m in meent.list_materials() if m["name"] == key)
    check(
        "wavelength",
        wavelength,
        info["wl_min"] <= wavelength <= info["wl_max"],
        f"{info['wl_min']:.4g} … {info['wl_max']:.4g} m for the material {text} ({key})",
    )
    # meent's tables return n − iκ (its e^{+iωt} convention): conjugate to n + iκ
    return complex(np.conj(meent.find_nk_index(key, table, wavelength)))


@dataclass(frozen=True)
class Bar:
    """A bar of one layer: [start, end) in fractions of the period, refractive index n + iκ."""

    start: float
    end: float
    index: complex

    def __post_init__(self):
        for attr in ("start", "end"):
            finite(f"bar {attr}", getattr(self, attr))
        check("bar", (self.start, self.end), 0 <= self.start < self.end <= 1, "0 ≤ start < end ≤ 1 (period fractions)")
        for attr in ("start", "end"):  # edges to 1e-12 of the period, so that 1 − (1 − x) is x again
            object.__setattr__(self, attr, round(float(getattr(self, attr)), 12))
        object.__setattr__(self, "index", refractive_index(self.index, name="bar index"))


@dataclass(frozen=True)
class Layer:
    """One layer: thickness (m), background refractive index, and bars (none: a uniform film)."""

    thickness: float
    background: complex
    bars: tuple[Bar, ...] = ()

    def __post_init__(self):
        v = finite("layer thickness", self.thickness)
        check("layer thickness", v, v >= 0, "≥ 0 m")
        object.__setattr__(self, "background", refractive_index(self.background, name="layer background index"))
        object.__setattr__(self, "bars", tuple(self.bars))
        edges = sorted((b.start, b.end) for b in self.bars)
        for (_, e0), (s1, _) in zip(edges, edges[1:]):
            check("bars", edges, s1 >= e0, "non-overlapping intervals within a layer")


@dataclass(frozen=True)
class Grating:
    """A 1-D grating: vacuum wavelength λ and period Λ (m), layers listed from the laser side.

    Parameters
    ----------
    wavelength, period : float
        λ and Λ in metres; orders ±m propagate at normal incidence while mλ/Λ < 1.
    layers : tuple of Layer
        The stack, first layer on the side the laser light arrives on.
    name : str
        A label (not part of the cache key).
    """

    wavelength: float
    period: float
    layers: tuple[Layer, ...]
    name: str = ""

    def __post_init__(self):
        for attr in ("wavelength", "period"):
            v = finite(attr, getattr(self, attr))
            check(attr, v, v > 0, "> 0 m")
        object.__setattr__(self, "layers", tuple(self.layers))
        check("layers", len(self.layers), len(self.layers) >= 1, "at least one layer")
        self.raster_cells()

    # ---- forms -------------------------------------------------------------------------------
    def to_dict(self) -> dict:
        """Plain JSON-able dict; complex indices as [re, im]."""

        def cx(v):
            return [v.real, v.imag]

        return {
            "wavelength": self.wavelength,
            "period": self.period,
            "name": self.name,
            "layers": [
                {
                    "thickness": layer.thickness,
                    "background": cx(layer.background),
                    "bars": [{"start": b.start, "end": b.end, "index": cx(b.index)} for b in layer.bars],
                }
                for layer in self.layers
            ],
        }

    @classmethod
    def from_dict(cls, d: dict) -> Grating:
        def cx(v):
            return complex(*v) if isinstance(v, (list, tuple)) else complex(v)

        layers = tuple(
            Layer(
                layer["thickness"],
                cx(layer["background"]),
                tuple(Bar(b["start"], b["end"], cx(b["index"])) for b in layer["bars"]),
            )
            for layer in d["layers"]
        )
        return cls(d["wavelength"], d["period"], layers, d.get("name", ""))

    def key(self) -> str:
        """SHA-256 (16 hex digits) of the geometry (the name excluded)."""
        d = self.to_dict()
        d.pop("name")
        return hashlib.sha256(json.dumps(d, sort_keys=True).encode()).hexdigest()[:16]

    # ---- variants ----------------------------------------------------------------------------
    def mirrored(self) -> Grating:
        """The grating turned t → −t (every bar x → 1 − x)."""
        layers = tuple(
            Layer(layer.thickness, layer.background, tuple(Bar(1 - b.end, 1 - b.start, b.index) for b in layer.bars))
            for layer in self.layers
        )
        return Grating(self.wavelength, self.period, layers, f"{self.name} (mirrored)")

    def zero_contrast(self) -> Grating:
        """The same stack with every bar given its layer's background index: uniform films."""
        layers = tuple(
            Layer(layer.thickness, layer.background, tuple(Bar(b.start, b.end, layer.background) for b in layer.bars))
            for layer in self.layers
        )
        return Grating(self.wavelength, self.period, layers, f"{self.name} (zero contrast)")

    def filled(self, index: complex) -> Grating:
        """The stack with its patterned layers filled with `index`, bars and gaps alike (zero contrast)."""

        def fill(layer):
            return Layer(layer.thickness, index, tuple(Bar(b.start, b.end, index) for b in layer.bars))

        layers = tuple(fill(layer) if layer.bars else layer for layer in self.layers)
        return Grating(self.wavelength, self.period, layers, f"{self.name} (filled)")

    @property
    def lossless(self) -> bool:
        return all(layer.background.imag == 0 and all(b.index.imag == 0 for b in layer.bars) for layer in self.layers)

    def rayleigh_anomalies(self, theta_max: float = math.pi / 2) -> np.ndarray:
        """Angles θ in (−θ_max, θ_max) at which an order m ≠ 0 grazes the sail: sin θ + mλ/Λ = ±1."""
        ratio = self.wavelength / self.period
        angles = []
        for m in range(1, int(2.0 / ratio) + 1):  # orders ±m graze at sin θ = ±(1 − mλ/Λ)
            a = abs(math.asin(1.0 - m * ratio)) if abs(1.0 - m * ratio) < 1.0 else math.inf
            if a < theta_max and not any(abs(a - b) < 1e-12 for b in angles):  # m and 2Λ/λ − m graze together
                angles.append(a)
        return np.array(sorted({-a for a in angles} | set(angles)))

    # ---- raster ------------------------------------------------------------------------------
    def raster_cells(self) -> int:
        """The coarsest raster (cells per period) whose cell edges include every bar edge."""
        edges = [e for layer in self.layers for b in layer.bars for e in (b.start, b.end)]
        for cells in range(2, MAX_RASTER + 1):
            if all(abs(e * cells - round(e * cells)) < 1e-9 for e in edges):
                return cells
        raise ParameterError(
            f"bars={edges!r} is invalid: allowed bar edges on a raster of at most {MAX_RASTER} cells per period "
            "(round them to 5 decimals)"
        )

    def index_profile(self, layer: Layer, cells: int) -> np.ndarray:
        """Refractive index on `cells` equal cells of one period (bar edges on cell edges)."""
        n = np.full(cells, layer.background, dtype=complex)
        for b in layer.bars:
            n[int(round(b.start * cells)) : int(round(b.end * cells))] = b.index
        return n


# the named designs
WAVELENGTH = 1.2e-6
N_SI = 3.48  # nominal c-Si index in the near infrared (Green 2008 in meent's tables gives 3.52 at 1.2 µm)
N_SIO2 = 1.45  # nominal fused silica (Malitson 1965: 1.448 at 1.2 µm)
GRATINGS = {
    # Own design in the style of Ilic & Atwater, Nat. Photon. 13, 289 (2019) (silicon resonators on silica,
    # two bars of different widths per period: an asymmetric cell that steers light sideways); picked from a
    # random search of 300 cells for a high normal force and a steady sideways force near normal incidence.
    # Areal mass ≈ 2330·0.4e-6·0.36 + 2200·0.3e-6 ≈ 1.0 g/m², the paper's ρh.
    "bigrating": Grating(
        WAVELENGTH,
        1.8e-6,
        (Layer(0.40e-6, 1.0, (Bar(0.05, 0.34, N_SI), Bar(0.47, 0.54, N_SI))), Layer(0.30e-6, N_SIO2)),
        name="Si bigrating on SiO2",
    ),
    # one centred Si bar (fill factor 0.4) on the same film: a mirror-symmetric cell, c_t odd in θ
    "symmetric": Grating(
        WAVELENGTH,
        1.8e-6,
        (Layer(0.40e-6, 1.0, (Bar(0.30, 0.70, N_SI),)), Layer(0.30e-6, N_SIO2)),
        name="symmetric Si grating on SiO2",
    ),
}
