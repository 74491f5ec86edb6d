"""1-D gratings, their diffraction orders by RCWA, and the thin-film formulas that check them.

**Geometry.** One period Λ of a grating whose grooves run along the sail's width (z), its grating
vector along the slice tangent t: a stack of layers listed from the side the laser light arrives on,
between vacuum on both sides. Each layer has a thickness, a background refractive index and bars;
a bar is an interval [start, end) in fractions of the period with its own refractive index. A layer
without bars is a uniform film. Refractive indices are n + iκ with κ ≥ 0 absorbing (time dependence
e^(−iωt)); they are given as numbers, as permittivities ε = (n + iκ)², or by the name of a material
in meent's tables (:func:`refractive_index`).

**Incidence.** A plane wave of vacuum wavelength λ in the plane of the grating vector and the
normal (planar mounting), at the signed angle θ from the normal, with tangential wavevector
k₀ sin θ along +t. TE: E along the grooves; TM: H along the grooves. The two decouple in this
mounting, so an unpolarised (or circularly polarised) beam sees the mean of their efficiencies.

**Orders.** Order m leaves with tangential direction cosine σ_m = sin θ + mλ/Λ; it propagates if
|σ_m| < 1, at cos θ_m = √(1 − σ_m²). R_m and T_m are the reflected and transmitted fractions of the
incident power crossing the sail plane (Poynting flux normal to the plane), so ΣR_m + ΣT_m = 1 for a
lossless grating; evanescent orders carry none. Orders (:func:`orders`) come from meent (numpy
backend; exact Fourier series of the bar profile, ``fourier_type=1``; Li's factorisation rules for TM)
or, as a cross-check, from grcwa (a 1-D grating as a 2-D lattice with a negligible second period;
grcwa is optional: ``pip install grcwa``). meent's time dependence is e^(+iωt): it is handed the
complex conjugate of every index.

**Momentum balance** (:func:`force_coefficients`; per unit sail area, per period). The incident
light crosses the plane with power I cos θ and momentum flux (I cos θ / c) ŷ, ŷ = cos θ n + sin θ t
the beam direction; order m leaves with the fraction R_m or T_m of that power along
σ_m t ∓ cos θ_m n (reflected: back through the laser side, −n; transmitted: +n); absorbed light stays.
Force = momentum in − momentum out, f = (I A / c) [c_n n + c_t t]:

    c_n = cos θ [cos θ + Σ_m R_m cos θ_m − Σ_m T_m cos θ_m],
    c_t = cos θ [sin θ − Σ_m (R_m + T_m) σ_m].

Checks by hand: a mirror (R₀ = 1, σ₀ = sin θ) gives c_n = 2 cos²θ, c_t = 0 (Eq. 11); a facet with
specular R₀ = R, T₀ = 1 − R − α gives c_n = (2R + α) cos²θ, c_t = α cos θ sin θ (model/loads.py).

**Thin films** (:func:`airy_rt`, :func:`abeles_rt`): R and T of one uniform film by Airy's sum of
Fresnel coefficients, and of a stack by the characteristic (Abelès) matrix; written independently
of the RCWA codes, they are what a grating of zero index contrast must reproduce.
"""

from __future__ import annotations

import cmath
import hashlib
import json
import math
import time
from dataclasses import dataclass, field

import numpy as np

from lightsail_mbs.base.validation import ParameterError, check, finite

BACKENDS = ("meent", "grcwa")
POLARIZATIONS = ("TE", "TM")
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


@dataclass
class Orders:
    """The diffraction orders of one incidence θ: m, σ_m = sin θ + mλ/Λ, efficiencies R_m and T_m."""

    theta: float
    polarization: str
    m: np.ndarray
    sigma: np.ndarray
    reflected: np.ndarray
    transmitted: np.ndarray
    info: dict = field(default_factory=dict)

    @property
    def absorbed(self) -> float:
        """1 − ΣR_m − ΣT_m: the absorbed fraction (0 to round-off for a lossless grating)."""
        return float(1.0 - self.reflected.sum() - self.transmitted.sum())


def _meent_orders(g: Grating, theta: float, pol: str, harmonics: int) -> Orders:
    import meent

    cells = g.raster_cells()
    ucell = np.conj(np.stack([g.index_profile(layer, cells)[None, :] for layer in g.layers]))
    if not np.any(ucell.imag):
        ucell = ucell.real
    mee = meent.call_mee(
        backend=0,
        pol=0 if pol == "TE" else 1,
        n_top=1.0,
        n_bot=1.0,
        theta=theta,
        fto=[harmonics, 0],
        period=[g.period, g.period],
        wavelength=g.wavelength,
        thickness=[layer.thickness for layer in g.layers],
        ucell=ucell,
        fourier_type=1,
        type_complex=np.complex128,
    )
    res = mee.conv_solve().res
    m = np.arange(-harmonics, harmonics + 1)
    sigma = math.sin(theta) + m * g.wavelength / g.period
    return Orders(
        theta,
        pol,
        m,
        sigma,
        np.asarray(res.de_ri).ravel().real,
        np.asarray(res.de_ti).ravel().real,
        dict(backend="meent", harmonics=harmonics, cells=cells),
    )


def _grcwa_orders(g: Grating, theta: float, pol: str, harmonics: int) -> Orders:
    try:
        import grcwa
    except ImportError:
        raise ParameterError("backend='grcwa' is invalid: allowed with grcwa installed (pip install grcwa)") from None
    grcwa.set_backend("numpy")
    # lengths in units of the period; a tiny second lattice period keeps only the orders along the grating vector
    obj = grcwa.obj(2 * harmonics + 1, [1.0, 0.0], [0.0, 1e-4], g.period / g.wavelength, theta, 0.0, verbose=0)
    obj.Add_LayerUniform(0.0, 1.0)
    base = g.raster_cells()
    cells = base * math.ceil(max(base, 8 * harmonics + 8) / base)
    patterned = []
    for layer in g.layers:
        if layer.bars:
            obj.Add_LayerGrid(layer.thickness / g.period, cells, 1)
            patterned.append(g.index_profile(layer, cells) ** 2)
        else:
            obj.Add_LayerUniform(layer.thickness / g.period, layer.background**2)
    obj.Add_LayerUniform(0.0, 1.0)
    obj.Init_Setup(Gmethod=0)
    if patterned:
        obj.GridLayer_geteps(np.concatenate(patterned))
    if pol == "TE":
        obj.MakeExcitationPlanewave(0.0, 0.0, 1.0, 0.0, order=0)
    else:
        obj.MakeExcitationPlanewave(1.0, 0.0, 0.0, 0.0, order=0)
    R, T = obj.RT_Solve(normalize=1, byorder=1)
    if np.any(obj.G[:, 1] != 0):
        raise ParameterError(f"harmonics={harmonics} is invalid for grcwa: allowed fewer (orders off the grating line)")
    m = np.asarray(obj.G[:, 0])
    order = np.argsort(m)
    sigma = math.sin(theta) + m[order] * g.wavelength / g.period
    return Orders(
        theta,
        pol,
        m[order],
        sigma,
        np.real(R)[order],
        np.real(T)[order],
        dict(backend="grcwa", harmonics=int(obj.nG), cells=cells),
    )


def orders(g: Grating, theta: float, polarization: str = "TE", harmonics: int = 20, backend: str = "meent") -> Orders:
    """The diffraction orders of `g` at incidence θ (rad), orders −harmonics…harmonics kept in the RCWA."""
    check("polarization", polarization, polarization in POLARIZATIONS, " or ".join(POLARIZATIONS))
    check("backend", backend, backend in BACKENDS, " or ".join(BACKENDS))
    check("harmonics", harmonics, isinstance(harmonics, int) and 1 <= harmonics <= 2000, "an integer 1 … 2000")
    v = finite("theta", theta)
    check("theta", v, abs(v) < math.pi / 2, "|θ| < π/2 rad")
    t0 = time.process_time()
    # one BLAS thread: the small dense eigenproblems of RCWA run several times slower multithreaded
    from threadpoolctl import threadpool_limits  # not a build requirement: the solver kernels compile without it

    with threadpool_limits(1):
        out = (_meent_orders if backend == "meent" else _grcwa_orders)(g, v, polarization, harmonics)
    propagating = np.abs(out.sigma) < 1.0
    out.reflected = np.where(propagating, out.reflected, 0.0)
    out.transmitted = np.where(propagating, out.transmitted, 0.0)
    out.info["cpu_seconds"] = time.process_time() - t0
    return out


def force_coefficients(o: Orders) -> tuple[float, float]:
    """(c_n, c_t) of one incidence by momentum balance (module docstring)."""
    c, s = math.cos(o.theta), math.sin(o.theta)
    prop = np.abs(o.sigma) < 1.0
    cos_m = np.sqrt(np.clip(1.0 - o.sigma[prop] ** 2, 0.0, None))
    r, t, sig = o.reflected[prop], o.transmitted[prop], o.sigma[prop]
    c_n = c * (c + float(np.dot(r, cos_m)) - float(np.dot(t, cos_m)))
    c_t = c * (s - float(np.dot(r + t, sig)))
    return c_n, c_t


# ---- thin films: the independent reference ------------------------------------------------------
def airy_rt(index: complex, thickness: float, wavelength: float, theta: float, polarization: str):
    """(R, T) of one film (index n + iκ, thickness d) in vacuum at incidence θ, by Airy's sum.

    Snell: sin θ₂ = sin θ / n, cos θ₂ = √(1 − sin²θ₂) (principal root); Fresnel amplitude coefficients
    (TE: r₁₂ = (cos θ − n cos θ₂)/(cos θ + n cos θ₂), t₁₂ = 2 cos θ/(cos θ + n cos θ₂); TM:
    r₁₂ = (n cos θ − cos θ₂)/(n cos θ + cos θ₂), t₁₂ = 2 cos θ/(n cos θ + cos θ₂); r₂₃ = −r₁₂ and t₂₃ from
    the film to vacuum), phase β = 2π n d cos θ₂/λ, then the multiple-beam sums
    r = (r₁₂ + r₂₃ e^(2iβ))/(1 + r₁₂ r₂₃ e^(2iβ)), t = t₁₂ t₂₃ e^(iβ)/(1 + r₁₂ r₂₃ e^(2iβ)), R = |r|², T = |t|²
    (the same medium on both sides, so T needs no admittance ratio).
    """
    n = complex(index)
    c1 = math.cos(theta)
    c2 = cmath.sqrt(1.0 - (math.sin(theta) / n) ** 2)
    if polarization == "TE":
        r12 = (c1 - n * c2) / (c1 + n * c2)
        t12 = 2 * c1 / (c1 + n * c2)
        r23 = (n * c2 - c1) / (n * c2 + c1)
        t23 = 2 * n * c2 / (n * c2 + c1)
    else:
        r12 = (n * c1 - c2) / (n * c1 + c2)
        t12 = 2 * c1 / (n * c1 + c2)
        r23 = (c2 - n * c1) / (c2 + n * c1)
        t23 = 2 * n * c2 / (c2 + n * c1)
    beta = 2 * math.pi * n * thickness * c2 / wavelength
    ph = cmath.exp(2j * beta)
    r = (r12 + r23 * ph) / (1 + r12 * r23 * ph)
    t = t12 * t23 * cmath.exp(1j * beta) / (1 + r12 * r23 * ph)
    return abs(r) ** 2, abs(t) ** 2


def abeles_rt(indices, thicknesses, wavelength: float, theta: float, polarization: str):
    """(R, T) of a stack of uniform films in vacuum by the characteristic (Abelès) matrix.

    Film j: cos θ_j = √(1 − sin²θ/n_j²), phase δ_j = 2π n_j d_j cos θ_j/λ, admittance η_j = n_j cos θ_j (TE)
    or n_j/cos θ_j (TM); M = Π_j [[cos δ_j, −i sin δ_j/η_j], [−i η_j sin δ_j, cos δ_j]];
    with η₀ the vacuum's: r = (η₀M₁₁ + η₀²M₁₂ − M₂₁ − η₀M₂₂)/Δ, t = 2η₀/Δ, Δ = η₀M₁₁ + η₀²M₁₂ + M₂₁ + η₀M₂₂.
    """
    s = math.sin(theta)
    eta0 = math.cos(theta) if polarization == "TE" else 1.0 / math.cos(theta)
    M = np.eye(2, dtype=complex)
    for n, d in zip(indices, thicknesses):
        n = complex(n)
        cos_j = cmath.sqrt(1 - (s / n) ** 2)
        eta = n * cos_j if polarization == "TE" else n / cos_j
        delta = 2 * math.pi * n * d * cos_j / wavelength
        M = M @ np.array(
            [[cmath.cos(delta), -1j * cmath.sin(delta) / eta], [-1j * eta * cmath.sin(delta), cmath.cos(delta)]]
        )
    den = eta0 * M[0, 0] + eta0 * eta0 * M[0, 1] + M[1, 0] + eta0 * M[1, 1]
    r = (eta0 * M[0, 0] + eta0 * eta0 * M[0, 1] - M[1, 0] - eta0 * M[1, 1]) / den
    t = 2 * eta0 / den
    return abs(r) ** 2, abs(t) ** 2


# ---- named gratings -------------------------------------------------------------------------------
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
