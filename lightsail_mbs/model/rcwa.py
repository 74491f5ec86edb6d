"""The diffraction orders of a 1-D grating by RCWA, the force coefficients they give, and the thin-film
formulas that check them.

The gratings themselves (geometry, materials, the named designs) are :mod:`lightsail_mbs.model.grating`;
their names are importable from here too.

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
import math
import time
from dataclasses import dataclass, field

import numpy as np

from lightsail_mbs.base.validation import ParameterError, check, finite
from lightsail_mbs.model.grating import (
    GRATINGS,
    MATERIAL_ALIASES,
    MAX_RASTER,
    N_SI,
    N_SIO2,
    WAVELENGTH,
    Bar,
    Grating,
    Layer,
    refractive_index,
)

__all__ = [
    "BACKENDS",
    "GRATINGS",
    "MATERIAL_ALIASES",
    "MAX_RASTER",
    "N_SI",
    "N_SIO2",
    "POLARIZATIONS",
    "WAVELENGTH",
    "Bar",
    "Grating",
    "Layer",
    "Orders",
    "abeles_rt",
    "airy_rt",
    "force_coefficients",
    "orders",
    "refractive_index",
]

BACKENDS = ("meent", "grcwa")
POLARIZATIONS = ("TE", "TM")


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
