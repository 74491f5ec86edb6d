"""Film roughness: a physical height spectrum, sampled as seeded random fields that do not depend on the grid.

**The spectrum** (K-correlation or "ABC" model; Palasantzas, Phys. Rev. B 48, 14472 (1993); the ABC form of
Church and Takacs, as in NIST SCATMECH's ``ABC_PSD_Function``). The film is an isotropic random surface
h(x, y) of RMS height σ (m), correlation length ξ (m) and Hurst exponent H (0 < H ≤ 1), with the 2-D
power spectral density (PSD conventions of Jacobs, Junge and Pastewka, Surf. Topogr.: Metrol. Prop. 5,
013001 (2017): ⟨h²⟩ = ∫ C d²q over the whole wavevector plane, q in rad/m)

    C₂(q) = (H σ² ξ² / π) (1 + (qξ)²)^(−1−H),                           ∫ C₂(|q|) d²q = σ².

A line scan of it (the chain's profile h(x)) has the two-sided 1-D PSD C₁(q) = ∫ C₂(√(q² + q_y²)) dq_y,

    C₁(q) = σ² ξ H Γ(H + ½) / (√π Γ(H + 1)) · (1 + (qξ)²)^(−(1+2H)/2),   ∫ C₁ dq (all q) = σ².

Flat (white) for q ≪ 1/ξ, self-affine C₁ ∝ q^(−1−2H) for q ≫ 1/ξ. The variance at |q| ≤ Q is σ² F(Q) with
F(Q) = k ∫₀^atan(Qξ) cos^(2H−1)θ dθ, k = 2HΓ(H + ½)/(√π Γ(H + 1)) (F = (2/π) atan(Qξ) for H = ½), evaluated
here by Gauss–Legendre quadrature: up to qξ = 1 directly, beyond it as the tail 1 − F (the integrable end point
θ = π/2 of H < ½ by its leading terms in closed form), so that F and 1 − F both hold to round-off.

**The fields.** On a sail of length L (and width W) the film is a Fourier series of period Λ = 2L (Λ_y = 2W):
wavenumbers q_j = 2πj/Λ = πj/L, the wavelengths 2L/j of the chain's half-integer modes ν = j/2. Mode j has
the coefficients (a_j, b_j) = √v_j (g₁, g₂), h(x) = Σ_j a_j cos(q_j x) + b_j sin(q_j x), with g₁, g₂ independent
standard normal numbers drawn from a stream keyed by (seed, j) alone, and v_j the PSD integrated over the mode's
bin, v_j = 2 ∫ C₁ dq over (j − ½)π/L ≤ q ≤ (j + ½)π/L (both signs of q). A chain of n slices carries
j = 1 … n (up to its Nyquist wavenumber π n/L); a finer grid keeps every coefficient of a coarser one and adds
the shorter waves. The heights are real, of zero mean in the ensemble (no q = 0 mode), and their variance at
every point is Σ_j v_j = σ² [F((n + ½)π/L) − F(π/(2L))]: the PSD integrated over the wavenumbers carried.
The sheet's surface is the same in 2-D: modes (j_x, j_y) over the half-plane, |j_x| ≤ n_x, |j_y| ≤ n_y, each
with the 2-D PSD integrated over its bin (8 × 8-point Gauss–Legendre) for both signs of the wavevector.

**The reference film** (REFERENCE_FILM, docs/film.md): σ = 1 nm, ξ = 0.1 m, H = 0.5. The RMS lies within the
0.1–2 nm that AFM reports for free-standing and thin films on µm scans; H = 0.5 is graphene's measured
height–height exponent 2H = 1, near the q^(−3.15) 2-D spectrum of suspended graphene (H ≈ 0.6). No cited
measurement covers the centimetre-to-metre waves a sail carries: ξ = 0.1 m is a stated assumption that puts
most of the 1 nm in the band of a 1 m sail (0.91 nm RMS at n = 30).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lightsail_mbs.base.validation import ParameterError, check, finite

_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(40)  # the 1-D cumulative integrals (smooth integrands)
_NODES_2D, _WEIGHTS_2D = np.polynomial.legendre.leggauss(8)  # each 2-D mode's bin, per direction
# the random streams of line scans and of surfaces: keys (seed, 1, j) and (seed, 2, j_x, j_y)
_CHAIN_STREAM, _SHEET_STREAM = 1, 2
MAX_SEED = 2**63 - 1


@dataclass(frozen=True)
class Film:
    """A film's roughness spectrum: RMS height σ (m), correlation length ξ (m), Hurst exponent H (module docstring)."""

    rms: float  # σ, m: RMS height of the whole film (all wavelengths)
    correlation_length: float  # ξ, m: the long-wave roll-off of the self-affine spectrum
    hurst: float  # H, 0 < H ≤ 1: C₁ ∝ q^(−1−2H) at q ≫ 1/ξ

    def __post_init__(self):
        rms = finite("rms", self.rms)
        check("rms", self.rms, rms >= 0, "≥ 0 (m; 0 is a flat film)")
        xi = finite("correlation_length", self.correlation_length)
        check("correlation_length", self.correlation_length, xi > 0, "> 0 (m)")
        hurst = finite("hurst", self.hurst)
        check("hurst", self.hurst, 0 < hurst <= 1, "0 < H ≤ 1")

    def describe(self) -> str:
        """One line: the film's σ, ξ and H."""
        return f"RMS σ = {self.rms:.3g} m, correlation length ξ = {self.correlation_length:.3g} m, H = {self.hurst:g}"

    def _k(self) -> float:
        h = self.hurst
        return 2.0 * h * math.gamma(h + 0.5) / (math.sqrt(math.pi) * math.gamma(h + 1.0))

    def psd_2d(self, q):
        """C₂(|q|), m⁴: the isotropic 2-D PSD; ∫ C₂ d²q = σ²."""
        xi, h = self.correlation_length, self.hurst
        return h * self.rms**2 * xi**2 / math.pi * (1.0 + (np.asarray(q, float) * xi) ** 2) ** (-1.0 - h)

    def psd_1d(self, q):
        """C₁(q), m³: the two-sided PSD of a line scan; ∫ C₁ dq over −∞ < q < ∞ equals σ²."""
        xi, h = self.correlation_length, self.hurst
        return 0.5 * self._k() * self.rms**2 * xi * (1.0 + (np.asarray(q, float) * xi) ** 2) ** (-0.5 - h)

    def cumulative(self, q):
        """F(q): the fraction of σ² a line scan carries at wavenumbers |q'| ≤ q (q ≥ 0)."""
        head, tail = self._head_tail(q)
        return np.where(np.isnan(head), 1.0 - tail, head)

    def band_variance(self, q_low, q_high):
        """2 ∫ C₁ dq over q_low ≤ q ≤ q_high (m², both signs of q; 0 ≤ q_low ≤ q_high ≤ inf)."""
        lo, hi = np.broadcast_arrays(np.asarray(q_low, float), np.asarray(q_high, float))
        head_lo, tail_lo = self._head_tail(lo)
        head_hi, tail_hi = self._head_tail(hi)
        from_tails = tail_lo - tail_hi  # both beyond 1/ξ: the difference of two small tails, without cancellation
        from_heads = np.where(np.isnan(head_hi), 1.0 - tail_hi, head_hi) - head_lo
        return self.rms**2 * np.where(np.isnan(head_lo), from_tails, from_heads)

    def _head_tail(self, q):
        """(F(q) where qξ ≤ 1 else NaN, 1 − F(q) where qξ > 1 else NaN), each by quadrature without cancellation."""
        q = np.asarray(q, float)
        if np.any(q < 0) or np.any(np.isnan(q)):
            raise ParameterError("q is invalid: allowed wavenumbers ≥ 0 (rad/m), no NaN")
        h, k = self.hurst, self._k()
        u = q * self.correlation_length
        near = u <= 1.0
        theta = np.arctan(np.where(near, u, 0.0))[..., None] * 0.5 * (1.0 + _NODES)  # ∫₀^θ cos^(2H−1)
        head = k * 0.5 * np.arctan(np.where(near, u, 0.0)) * (np.cos(theta) ** (2 * h - 1) @ _WEIGHTS)
        # ∫₀^φ₀ sin^(2H−1)φ dφ = ∫₀^φ₀ φ^(2H−1) s(φ) dφ, s = (sin φ/φ)^(2H−1) = 1 + c φ² + O(φ⁴), c = (1 − 2H)/6:
        # the first two terms exactly, the rest with φ = φ₀ t^(1/2H), an integrand ~ t^(2/H) by quadrature
        with np.errstate(divide="ignore"):
            phi0 = np.arctan(1.0 / np.where(near, 2.0, u))
        c = (1.0 - 2.0 * h) / 6.0
        phi = phi0[..., None] * (0.5 * (1.0 + _NODES)) ** (0.5 / h)
        rest = (np.sinc(phi / np.pi) ** (2 * h - 1) - 1.0 - c * phi**2) @ _WEIGHTS * 0.5 / (2 * h)
        tail = k * phi0 ** (2 * h) * (1.0 / (2 * h) + c * phi0**2 / (2 * h + 2) + rest)
        return np.where(near, head, np.nan), np.where(near, np.nan, tail)


REFERENCE_FILM = Film(rms=1e-9, correlation_length=0.1, hurst=0.5)


def of_case(p) -> Film | None:
    """The film of a case (SailParameters.film_rms, film_correlation_length, film_hurst, film_seed), checked,
    each error naming the case's field; None when film_rms is 0 (no film)."""
    seed = p.film_seed
    check("film_seed", seed, isinstance(seed, int) and not isinstance(seed, bool) and seed >= 0, "an integer ≥ 0")
    try:
        spectrum = Film(p.film_rms, p.film_correlation_length, p.film_hurst)
    except ParameterError as exc:
        raise ParameterError(f"film_{exc}") from None
    return spectrum if spectrum.rms > 0 else None


def parse_film(text: str) -> Film:
    """A film from "σ[,ξ[,H]]" (m, m, –); the values left out are the reference film's."""
    fields = [f.strip() for f in str(text).split(",")]
    ref = (REFERENCE_FILM.rms, REFERENCE_FILM.correlation_length, REFERENCE_FILM.hurst)
    if not 1 <= len(fields) <= 3 or not all(fields):
        raise ParameterError(f"film={text!r} is invalid: allowed 'rms[,correlation_length[,hurst]]' (m, m, –)")
    try:
        values = [float(f) for f in fields]
    except ValueError:
        raise ParameterError(f"film={text!r} is invalid: allowed 'rms[,correlation_length[,hurst]]' numbers") from None
    return Film(*values, *ref[len(values) :])


def _length(name: str, value) -> float:
    v = finite(name, value)
    check(name, value, v > 0, "> 0 (m)")
    return v


def _count(name: str, value, least: int) -> int:
    ok = isinstance(value, (int, np.integer)) and not isinstance(value, bool) and value >= least
    check(name, value, ok, f"an integer ≥ {least}")
    return int(value)


def _seed(seed) -> int:
    ok = isinstance(seed, (int, np.integer)) and not isinstance(seed, bool) and 0 <= seed <= MAX_SEED
    check("seed", seed, ok, f"an integer 0 ≤ seed ≤ {MAX_SEED}")
    return int(seed)


def _blocks(size: int, block: int = 2048):
    """Slices of at most `block` points: the mode sums' memory bounded whatever the grid."""
    return [slice(i, min(i + block, size)) for i in range(0, size, block)]


def _mix(z: np.ndarray) -> np.ndarray:
    """SplitMix64's finaliser on uint64 words (a bijection with full avalanche)."""
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return z ^ (z >> np.uint64(31))


def keyed_normals(seed: int, *key) -> tuple[np.ndarray, np.ndarray]:
    """Two independent standard normal numbers for every key (seed, k₁, k₂, …; k integer arrays ≥ 0, broadcast):
    a counter-based stream (SplitMix64 hashing, Box–Muller), the same for a key whatever else is drawn."""
    golden = np.uint64(0x9E3779B97F4A7C15)
    words = np.broadcast_arrays(*[np.atleast_1d(np.asarray(k, dtype=np.uint64)) for k in key])
    z = _mix(np.full(words[0].shape, np.uint64(_seed(seed))) + golden)
    for w in words:
        z = _mix((z + golden) ^ w)
    u1, u2 = ((((_mix(z ^ np.uint64(d)) >> np.uint64(11)).astype(float) + 0.5) * 2.0**-53) for d in (1, 2))
    r = np.sqrt(-2.0 * np.log(u1))
    return r * np.cos(2 * np.pi * u2), r * np.sin(2 * np.pi * u2)


# ---- the chain: a line scan ---------------------------------------------------------------------------------


def chain_modes(film: Film, length: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    """(q_j, v_j), j = 1 … n: the wavenumbers (rad/m) a chain of n slices on length L carries, and the film's
    variance in each (m², the PSD over the mode's bin, both signs of q)."""
    L, n = _length("length", length), _count("n", n, 2)
    dq = np.pi / L
    j = np.arange(1, n + 1)
    return j * dq, film.band_variance((j - 0.5) * dq, (j + 0.5) * dq)


def carried_variance(film: Film, length: float, n: int) -> float:
    """Σ_j v_j (m²): the film's height variance on a chain of n slices (module docstring)."""
    return float(np.sum(chain_modes(film, length, n)[1]))


@dataclass(frozen=True)
class FilmProfile:
    """h(x) = Σ_j a_j cos(q_j x) + b_j sin(q_j x): one film's line scan (m), x in m from the sail's end."""

    wavenumber: np.ndarray  # q_j, rad/m
    cosine: np.ndarray  # a_j, m
    sine: np.ndarray  # b_j, m

    def _sum(self, x, a, b):
        x = np.asarray(x, float)
        xs, out = x.reshape(-1), np.empty(x.size)
        for block in _blocks(xs.size):
            phase = np.multiply.outer(xs[block], self.wavenumber)
            out[block] = np.cos(phase) @ a + np.sin(phase) @ b
        return out.reshape(x.shape) if x.ndim else float(out[0])

    def __call__(self, x):
        return self._sum(x, self.cosine, self.sine)

    def slope(self, x):
        """dh/dx."""
        return self._sum(x, self.wavenumber * self.sine, -self.wavenumber * self.cosine)


def film_profile(film: Film, length: float, n: int, seed: int) -> FilmProfile:
    """The film's line scan carried by a chain of n slices on length L: modes j = 1 … n, keyed by (seed, j)."""
    q, v = chain_modes(film, length, n)
    g1, g2 = keyed_normals(seed, _CHAIN_STREAM, np.arange(1, q.size + 1))
    return FilmProfile(q, np.sqrt(v) * g1, np.sqrt(v) * g2)


@dataclass(frozen=True)
class ChainFilm:
    """The film on a chain of n slices of length l = L/n: heights (m) and slice angles (rad)."""

    hinge_x: np.ndarray  # (n+1,) x_k = k l
    hinge_heights: np.ndarray  # (n+1,) h(x_k)
    centre_x: np.ndarray  # (n,) (k + ½) l
    centre_heights: np.ndarray  # (n,) h at the slice centres (the chords' midpoints differ by l²h''/8)
    angles: np.ndarray  # (n,) θ_k = atan((h_{k+1} − h_k)/l): the chord from hinge k to hinge k+1


def profile(film: Film, length: float, n: int, seed: int) -> ChainFilm:
    """The film at a chain's hinges and slice centres, and its slices' angles (hinges at x = k l: their chords
    exceed l by l θ²/2, ~1e-17 m for nm films; shapes' exact-chord construction takes film_profile instead)."""
    h = film_profile(film, length, n, seed)
    l = float(length) / n
    xk, xc = np.arange(n + 1) * l, (np.arange(n) + 0.5) * l
    hk = h(xk)
    return ChainFilm(xk, hk, xc, h(xc), np.arctan(np.diff(hk) / l))


def mode_seed(film: Film, length: float, wavelength: float) -> float:
    """The RMS amplitude (m) the film puts into a sine of the given wavelength on a sail of length L: √(2 v) with
    v the film's variance over the bin of width π/L at q = 2π/λ (a chain's mode j = 2L/λ). An estimate without a
    grid: the least-squares amplitude along sin(qx + φ) on 0 ≤ x ≤ L (projected_seed) also picks up the neighbouring
    wavenumbers, 0.76–1.19 times this for the reference film (docs/film.md)."""
    L, lam = _length("length", length), _length("wavelength", wavelength)
    q, dq = 2 * np.pi / lam, np.pi / L
    return float(np.sqrt(2.0 * film.band_variance(max(q - 0.5 * dq, 0.0), q + 0.5 * dq)))


# ---- the sheet: an isotropic surface ------------------------------------------------------------------------


def _bin_variance_2d(film: Film, qx: np.ndarray, qy: np.ndarray, dqx: float, dqy: float) -> np.ndarray:
    """(Jy, Jx): 2 ∫ C₂ d²q over the bins of size dqx × dqy centred on (qx_i, qy_j) (both signs of the wavevector)."""
    ox = np.asarray(qx, float)[:, None, None] + 0.5 * dqx * _NODES_2D[:, None]  # (Jx, 8, 1)
    w = np.multiply.outer(_WEIGHTS_2D, _WEIGHTS_2D) * 0.25 * dqx * dqy
    rows = [np.sum(film.psd_2d(np.hypot(ox, row + 0.5 * dqy * _NODES_2D)) * w, axis=(-2, -1)) for row in qy]
    return 2.0 * np.array(rows)  # (Jy, Jx), one row of wavevectors at a time


def sheet_modes(film: Film, length: float, width: float, nx: int, ny: int):
    """(qx (nx+1,), qy (2ny+1,), v (2ny+1, nx+1)): the wavevectors a sheet of nx × ny tiles carries (q_x = πj_x/L,
    q_y = πj_y/W, 0 ≤ j_x ≤ nx, −ny ≤ j_y ≤ ny) and the film's variance in each over the half-plane (zero on the
    other half and at q = 0), m²."""
    L, W = _length("length", length), _length("width", width)
    nx, ny = _count("nx", nx, 2), _count("ny", ny, 1)
    jx, jy = np.arange(nx + 1), np.arange(-ny, ny + 1)
    qx, qy = jx * np.pi / L, jy * np.pi / W
    v = _bin_variance_2d(film, qx, qy, np.pi / L, np.pi / W)
    upper = (jx[None, :] > 0) | ((jx[None, :] == 0) & (jy[:, None] > 0))
    return qx, qy, np.where(upper, v, 0.0)


def sheet_variance(film: Film, length: float, width: float, nx: int, ny: int) -> float:
    """The film's height variance on a sheet of nx × ny tiles (m²): Σ over the carried wavevectors."""
    return float(np.sum(sheet_modes(film, length, width, nx, ny)[2]))


@dataclass(frozen=True)
class FilmSurface:
    """h(x, y) = Re Σ c_jk exp(i(q_x,k x + q_y,j y)): one film's surface (m) over the sail, x, y from its corner."""

    qx: np.ndarray  # (Jx,) rad/m
    qy: np.ndarray  # (Jy,) rad/m
    coefficients: np.ndarray  # (Jy, Jx) complex, m: a − i b of the mode a cos + b sin

    def _sum(self, x, y, c):
        x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
        xs, ys, out = x.reshape(-1), y.reshape(-1), np.empty(x.size)  # 2-D products: a stacked matmul is far slower
        for block in _blocks(xs.size):
            ex, ey = (
                np.exp(1j * np.multiply.outer(xs[block], self.qx)),
                np.exp(1j * np.multiply.outer(ys[block], self.qy)),
            )
            out[block] = np.real(np.sum((ey @ c) * ex, axis=-1))
        return out.reshape(x.shape) if x.ndim else float(out[0])

    def on_grid(self, x, y) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(h, ∂h/∂x, ∂h/∂y) on the grid of the coordinates x (nx,) and y (ny,), arrays (ny, nx)."""
        ex = np.exp(1j * np.multiply.outer(np.asarray(x, float), self.qx))
        ey = np.exp(1j * np.multiply.outer(np.asarray(y, float), self.qy))
        c = self.coefficients
        return tuple(np.real(ey @ m @ ex.T) for m in (c, 1j * self.qx[None, :] * c, 1j * self.qy[:, None] * c))

    def __call__(self, x, y):
        return self._sum(x, y, self.coefficients)

    def slope_x(self, x, y):
        """∂h/∂x."""
        return self._sum(x, y, 1j * self.qx[None, :] * self.coefficients)

    def slope_y(self, x, y):
        """∂h/∂y."""
        return self._sum(x, y, 1j * self.qy[:, None] * self.coefficients)


def film_surface(film: Film, length: float, width: float, nx: int, ny: int, seed: int) -> FilmSurface:
    """The film's surface carried by a sheet of nx × ny tiles: wavevectors keyed by (seed, j_x, j_y)."""
    qx, qy, v = sheet_modes(film, length, width, nx, ny)
    jx = np.arange(qx.size)[None, :]
    jy = np.arange(-(qy.size // 2), qy.size // 2 + 1)[:, None]
    g1, g2 = keyed_normals(seed, _SHEET_STREAM, jx, np.where(jy >= 0, 2 * jy, -2 * jy - 1))  # j_y zig-zagged ≥ 0
    return FilmSurface(qx, qy, np.sqrt(v) * (g1 - 1j * g2))


@dataclass(frozen=True)
class SheetFilm:
    """The film at a sheet's tile centres; arrays (ny, nx), so that .ravel() is in tile order k = j·nx + i."""

    x: np.ndarray  # (nx,) (i + ½) L/nx
    y: np.ndarray  # (ny,) (j + ½) W/ny
    heights: np.ndarray  # h, m
    slope_x: np.ndarray  # ∂h/∂x
    slope_y: np.ndarray  # ∂h/∂y


def surface(film: Film, length: float, width: float, nx: int, ny: int, seed: int) -> SheetFilm:
    """Heights and slopes of the film at the tile centres of a sheet of nx × ny tiles."""
    s = film_surface(film, length, width, nx, ny, seed)
    x, y = (np.arange(nx) + 0.5) * float(length) / nx, (np.arange(ny) + 0.5) * float(width) / ny
    return SheetFilm(x, y, *s.on_grid(x, y))


# ---- the seed of a mode -------------------------------------------------------------------------------------


def projected_seed(film: Film, length: float, mode, width: float | None = None) -> float:
    """The RMS (m) over films of c = Σ φ h / Σ φ², the film's least-squares amplitude along a mode shape φ given at
    the slice centres (shape (n,), a chain on length L) or at the tile centres (shape (ny, nx), a sheet of width W):
    the seed a growing mode of that shape starts from, from the film's exact covariance on the grid."""
    phi = np.asarray(mode, float)
    norm = float(np.sum(phi * phi))
    if phi.ndim not in (1, 2) or not np.all(np.isfinite(phi)) or norm == 0:
        raise ParameterError(f"mode of shape {phi.shape} is invalid: allowed a finite non-zero array (n,) or (ny, nx)")
    if phi.ndim == 1:
        q, v = chain_modes(film, length, phi.size)
        x = (np.arange(phi.size) + 0.5) * float(length) / phi.size
        power = np.abs(np.exp(1j * np.multiply.outer(q, x)) @ phi) ** 2
        return float(np.sqrt(np.sum(v * power)) / norm)
    check("width", width, width is not None, "the sheet's width (m) for a 2-D mode")
    ny, nx = phi.shape
    qx, qy, v = sheet_modes(film, length, width, nx, ny)
    ex = np.exp(1j * np.multiply.outer((np.arange(nx) + 0.5) * float(length) / nx, qx))
    ey = np.exp(1j * np.multiply.outer((np.arange(ny) + 0.5) * float(width) / ny, qy))
    return float(np.sqrt(np.sum(v * np.abs(ey.T @ phi @ ex) ** 2)) / norm)
