"""Film roughness: the spectrum's normalisation, grid-independent seeded fields, their statistics, the seed of a mode.

The statistical tests run a fixed set of seeds (0 … S−1) and accept a sample mean within 4 standard errors of
its expectation, the standard error computed exactly from the film's covariance on the grid where it can be
(a Gaussian field: Var(h_a h_b) sums of products of covariances), else from the spread over the seeds."""

import math
import re
from pathlib import Path

import numpy as np
import pytest

from lightsail_mbs.model import film as F
from lightsail_mbs.model.parameters import ParameterError

REF = F.REFERENCE_FILM
DOCS = Path(__file__).resolve().parents[2] / "docs" / "film.md"


def fourier_coefficients(h, period, count):
    """(a_j, b_j), j = 1 … count, of h(x) = Σ a_j cos(2πjx/P) + b_j sin(2πjx/P), from h on one whole period."""
    m = 4096
    c = np.fft.rfft(h(np.arange(m) * period / m)) * 2.0 / m
    return c.real[1 : count + 1], -c.imag[1 : count + 1]


# ---- the spectrum ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("hurst", [0.05, 0.3, 0.5, 0.8, 1.0])
def test_psd_integrates_to_the_rms_and_its_cumulative_is_its_integral(hurst):
    film = F.Film(rms=2e-9, correlation_length=0.04, hurst=hurst)
    q = np.linspace(0.0, 400.0, 400_001)
    integral = 2.0 * np.concatenate([[0.0], np.cumsum(0.5 * (film.psd_1d(q[1:]) + film.psd_1d(q[:-1])) * np.diff(q))])
    for i in (1000, 25_000, 100_000, 400_000):  # qξ = 0.04 … 16: either side of the roll-off
        assert film.cumulative(q[i]) == pytest.approx(integral[i] / film.rms**2, rel=1e-9)
        assert film.band_variance(0.0, q[i]) == pytest.approx(integral[i], rel=1e-9)
    assert film.cumulative(np.inf) == 1.0
    # the two quadratures meet at qξ = 1
    assert film.cumulative(25.0 * (1 - 1e-12)) == pytest.approx(film.cumulative(25.0 * (1 + 1e-12)), abs=1e-12)
    # a band far in the tail: the difference of two small tails
    tail = film.band_variance(1e5, 2e5)
    q_far = np.linspace(1e5, 2e5, 200_001)
    assert tail == pytest.approx(2.0 * np.trapezoid(film.psd_1d(q_far), q_far), rel=1e-8)


def test_half_hurst_has_the_closed_form():
    q = np.array([0.0, 1.0, 9.99, 10.0, 10.01, 300.0, 1e6])
    np.testing.assert_allclose(REF.cumulative(q), 2.0 / np.pi * np.arctan(0.1 * q), rtol=1e-14, atol=1e-16)


@pytest.mark.parametrize("hurst", [0.2, 0.5, 1.0])
def test_line_scan_psd_is_the_isotropic_surface_psd_integrated_across(hurst):
    film = F.Film(rms=1e-9, correlation_length=0.02, hurst=hurst)
    u = np.linspace(-60.0, 60.0, 1_200_001)  # q_y ξ = tan u (a change of variable that reaches q_y = ±∞)
    for qx in (0.0, 30.0, 500.0):
        qy = np.tan(np.clip(u, -np.pi / 2 + 1e-9, np.pi / 2 - 1e-9) * np.pi / 120.0) / 0.02
        dqy = np.gradient(qy, u)
        across = np.trapezoid(film.psd_2d(np.hypot(qx, qy)) * dqy, u)
        assert across == pytest.approx(film.psd_1d(qx), rel=1e-6)


# ---- the same film on every grid ------------------------------------------------------------------------------


def test_same_film_on_finer_chains_keeps_its_long_waves():
    """n-independence: the modes n = 30, 60, 120 share are identical to round-off; each grid adds its short waves."""
    L, seed = 1.0, 11
    coeffs = {n: fourier_coefficients(F.film_profile(REF, L, n, seed), 2 * L, 200) for n in (30, 60, 120)}
    scale = REF.rms
    for n_coarse, n_fine in ((30, 60), (30, 120), (60, 120)):
        for part in (0, 1):
            np.testing.assert_allclose(
                coeffs[n_fine][part][:n_coarse], coeffs[n_coarse][part][:n_coarse], atol=1e-12 * scale
            )
    for n in (30, 60, 120):
        a, b = coeffs[n]
        assert np.all(np.abs(a[n:]) < 1e-12 * scale) and np.all(np.abs(b[n:]) < 1e-12 * scale)  # nothing beyond π n/L
        assert np.all(np.hypot(a[:n], b[:n]) > 0) and np.hypot(a[:n], b[:n]).max() > 1e-3 * scale  # not trivially 0
    # the short waves the finer grid adds are real: 30 < j ≤ 120 carry the film's variance there
    added = np.sum(coeffs[120][0][30:] ** 2 + coeffs[120][1][30:] ** 2) / 2
    assert added > 0
    # the heights on the grids: the hinge and centre values are the profile's, and differ between grids
    chains = {n: F.profile(REF, L, n, seed) for n in (30, 60, 120)}
    h = F.film_profile(REF, L, 120, seed)
    np.testing.assert_array_equal(chains[120].centre_heights, h(chains[120].centre_x))
    np.testing.assert_allclose(chains[120].hinge_heights[::4], chains[30].hinge_heights, atol=3 * REF.rms)


def test_same_film_on_finer_sheets_keeps_its_long_waves():
    L, W, seed = 1.0, 0.5, 5
    m = 128
    x, y = np.meshgrid(np.arange(m) * 2 * L / m, np.arange(m) * 2 * W / m)
    spectra = {}
    for nx, ny in ((8, 4), (16, 8), (32, 16)):
        c = np.fft.fft2(F.film_surface(REF, L, W, nx, ny, seed)(x, y)) / m**2
        spectra[nx] = c
    for coarse, fine in ((8, 16), (8, 32), (16, 32)):
        jy = np.r_[0 : coarse // 2 + 1, -(coarse // 2) : 0]  # the j_y ≤ ny = nx/2 of the coarse grid, both signs
        np.testing.assert_allclose(
            spectra[fine][np.ix_(jy, np.arange(coarse + 1))],
            spectra[coarse][np.ix_(jy, np.arange(coarse + 1))],
            atol=1e-13 * REF.rms,
        )
    assert np.abs(spectra[8][0:5, 0:9]).max() > 1e-3 * REF.rms
    assert np.abs(spectra[8][:, 9 : m - 8]).max() < 1e-13 * REF.rms  # nothing beyond the coarse grid's Nyquist in x


# ---- statistics over seeds -------------------------------------------------------------------------------------


def covariance(film, length, n):
    """R(x_a − x_b) of the film on the slice centres of a chain, from its modes."""
    q, v = F.chain_modes(film, length, n)
    x = (np.arange(n) + 0.5) * length / n
    return np.cos(np.multiply.outer(x, q)) @ (v[:, None] * np.cos(np.multiply.outer(q, x))) + np.sin(
        np.multiply.outer(x, q)
    ) @ (v[:, None] * np.sin(np.multiply.outer(q, x)))


@pytest.mark.parametrize(
    "film", [REF, F.Film(rms=3e-9, correlation_length=0.002, hurst=0.8)], ids=["reference", "short-xi"]
)
def test_variance_over_seeds_is_the_integrated_psd(film):
    L, n, seeds = 1.0, 40, range(300)
    expected = F.carried_variance(film, L, n)
    assert expected == pytest.approx(film.band_variance(0.5 * np.pi / L, (n + 0.5) * np.pi / L), rel=1e-12)
    heights = np.array([F.profile(film, L, n, s).centre_heights for s in seeds])
    sample = np.mean(heights**2)
    R = covariance(film, L, n)
    assert np.allclose(np.diag(R), expected, rtol=1e-12)  # every point carries the whole band
    stderr = math.sqrt(2.0 * np.sum(R**2) / n**2 / len(seeds))  # Var(mean h²) of a Gaussian field
    assert abs(sample - expected) < 4 * stderr, (sample, expected, stderr)
    assert stderr < 0.15 * expected  # the test can tell a wrong variance
    assert abs(np.mean(heights)) < 4 * math.sqrt(np.sum(R) / n**2 / len(seeds))  # zero mean


def test_surface_variance_over_seeds_is_the_integrated_psd():
    film, L, W, nx, ny = F.Film(rms=1e-9, correlation_length=0.05, hurst=0.7), 1.0, 1.0, 12, 12
    qx, qy, v = F.sheet_modes(film, L, W, nx, ny)
    x, y = (np.arange(nx) + 0.5) * L / nx, (np.arange(ny) + 0.5) * W / ny
    gx, gy = (g.ravel() for g in np.meshgrid(x, y))
    dx, dy = np.subtract.outer(gx, gx), np.subtract.outer(gy, gy)
    R = sum(v[j, i] * np.cos(qx[i] * dx + qy[j] * dy) for j, i in zip(*np.nonzero(v)))
    expected = F.sheet_variance(film, L, W, nx, ny)
    assert np.allclose(np.diag(R), expected)
    seeds = range(150)
    sample = np.mean([np.mean(F.surface(film, L, W, nx, ny, s).heights ** 2) for s in seeds])
    stderr = math.sqrt(2.0 * np.sum(R**2) / R.shape[0] ** 2 / len(seeds))
    assert abs(sample - expected) < 4 * stderr, (sample, expected, stderr)
    assert stderr < 0.15 * expected


def test_surface_is_isotropic_in_the_mean():
    """The structure functions D(r) = ⟨(h(p + r) − h(p))²⟩ along x and along y agree, sample and expectation."""
    film = F.Film(rms=1e-9, correlation_length=0.05, hurst=0.7)
    for L, W, nx, ny in ((1.0, 1.0, 16, 16), (1.0, 0.5, 16, 8)):  # square tiles; a square and an oblong sheet
        qx, qy, v = F.sheet_modes(film, L, W, nx, ny)
        lags = (1, 2, 4)
        a = L / nx
        exact_x = [2 * np.sum(v * (1 - np.cos(qx[None, :] * k * a))) for k in lags]
        exact_y = [2 * np.sum(v * (1 - np.cos(qy[:, None] * k * a))) for k in lags]
        np.testing.assert_allclose(exact_x, exact_y, rtol=0.02)
        per_seed = []
        for s in range(120):
            h = F.surface(film, L, W, nx, ny, s).heights
            per_seed.append(
                [np.mean((h[:, k:] - h[:, :-k]) ** 2) for k in lags]
                + [np.mean((h[k:, :] - h[:-k, :]) ** 2) for k in lags]
            )
        per_seed = np.array(per_seed)
        mean, stderr = per_seed.mean(axis=0), per_seed.std(axis=0, ddof=1) / math.sqrt(len(per_seed))
        diff = per_seed[:, :3] - per_seed[:, 3:]
        assert np.all(np.abs(diff.mean(axis=0)) < 4 * diff.std(axis=0, ddof=1) / math.sqrt(len(diff)))
        assert np.all(np.abs(mean - np.r_[exact_x, exact_y]) < 4 * stderr)
        assert np.all(stderr < 0.1 * mean)


def test_rms_converges_as_the_grid_refines():
    for hurst in (0.5, 0.8):
        film = F.Film(rms=1e-9, correlation_length=0.1, hurst=hurst)
        ns = [30, 60, 120, 240, 480, 960]
        var = np.array([F.carried_variance(film, 1.0, n) for n in ns])
        limit = film.band_variance(0.5 * np.pi, np.inf)
        gap = limit - var
        assert np.all(np.diff(var) > 0) and np.all(gap > 0)
        # the part beyond the grid's Nyquist wavenumber falls as q^(−2H) once qξ ≫ 1
        np.testing.assert_allclose(gap[1:] / gap[:-1], 2.0 ** (-2 * hurst), rtol=0.03)
        assert limit < film.rms**2


def test_reference_film_band_rms_is_what_the_docs_say():
    table = r"^\| *(\d+|∞) *\| *([0-9.]+) *\| *([0-9.]+|–) *\|"
    rows = re.findall(table, DOCS.read_text(encoding="utf-8"), re.M)
    assert len(rows) >= 4 and rows[-1][0] == "∞"
    for n, rms_nm, seed_nm in rows:
        if n == "∞":
            carried = REF.band_variance(0.5 * np.pi, np.inf)
            assert seed_nm == "–"
        else:
            carried = F.carried_variance(REF, 1.0, int(n))
            # the seed of the grid's shortest wave, λ = 2l
            assert float(seed_nm) == pytest.approx(F.mode_seed(REF, 1.0, 2.0 / int(n)) * 1e9, abs=0.0005)
        assert float(rms_nm) == pytest.approx(math.sqrt(carried) * 1e9, abs=0.0005)


# ---- the seed of a mode ----------------------------------------------------------------------------------------


def test_projected_seed_is_the_rms_of_the_projection_over_seeds():
    L, n = 1.0, 40
    x = (np.arange(n) + 0.5) * L / n
    shape = np.sin(3 * np.pi * x / L) * np.exp(-((x - 0.4) ** 2) / 0.1)  # any shape the linear spectrum may give
    seeds = range(400)
    c = np.array([shape @ F.profile(REF, L, n, s).centre_heights / (shape @ shape) for s in seeds])
    r = F.projected_seed(REF, L, shape)
    assert abs(np.mean(c**2) - r**2) < 4 * math.sqrt(2.0 / len(seeds)) * r**2
    # the sheet: a doubly sinusoidal mode
    Ls, W, nx, ny = 1.0, 1.0, 10, 10
    xs, ys = (np.arange(nx) + 0.5) / nx, (np.arange(ny) + 0.5) / ny
    phi = np.outer(np.sin(3 * np.pi * ys), np.sin(3 * np.pi * xs))
    c2 = np.array([np.sum(phi * F.surface(REF, Ls, W, nx, ny, s).heights) / np.sum(phi**2) for s in range(200)])
    r2 = F.projected_seed(REF, Ls, phi, width=W)
    assert abs(np.mean(c2**2) - r2**2) < 4 * math.sqrt(2.0 / 200) * r2**2


def test_mode_seed_of_a_sine_and_its_self_affine_tail():
    L = 1.0
    white = F.Film(rms=1e-9, correlation_length=1e-5, hurst=0.5)  # flat over the sail's band: no leakage bias
    for film, tolerance in ((white, 0.01), (REF, 0.15)):
        for j in (10, 25):
            x = (np.arange(240) + 0.5) * L / 240
            exact = F.projected_seed(film, L, np.sin(np.pi * j * x / L))
            assert F.mode_seed(film, L, 2 * L / j) == pytest.approx(exact, rel=tolerance)
    # q ≫ 1/ξ: C₁ ∝ q^(−1−2H), so the seed of a bin of fixed width falls as q^(−1/2−H)
    for hurst in (0.5, 0.9):
        film = F.Film(rms=1e-9, correlation_length=0.1, hurst=hurst)
        ratio = F.mode_seed(film, L, 0.005) / F.mode_seed(film, L, 0.01)
        assert ratio == pytest.approx(2.0 ** (-0.5 - hurst), rel=0.01)
    assert F.mode_seed(F.Film(0.0, 0.1, 0.5), L, 0.1) == 0.0


# ---- geometry of the fields ------------------------------------------------------------------------------------


def test_slopes_and_angles_are_those_of_the_heights():
    h = F.film_profile(REF, 1.0, 50, 3)
    x, dx = np.linspace(0.1, 0.9, 7), 1e-6
    np.testing.assert_allclose(h.slope(x), (h(x + dx) - h(x - dx)) / (2 * dx), rtol=1e-6, atol=1e-16)
    c = F.profile(REF, 1.0, 50, 3)
    np.testing.assert_allclose(np.tan(c.angles), np.diff(c.hinge_heights) / 0.02, rtol=1e-12)
    assert c.hinge_heights.shape == (51,) and c.centre_heights.shape == c.angles.shape == (50,)
    s = F.film_surface(REF, 1.0, 0.8, 12, 9, 4)
    px, py = np.array([0.2, 0.5, 0.7]), np.array([0.1, 0.4, 0.6])
    np.testing.assert_allclose(s.slope_x(px, py), (s(px + dx, py) - s(px - dx, py)) / (2 * dx), rtol=1e-6, atol=1e-16)
    np.testing.assert_allclose(s.slope_y(px, py), (s(px, py + dx) - s(px, py - dx)) / (2 * dx), rtol=1e-6, atol=1e-16)
    sheet = F.surface(REF, 1.0, 0.8, 12, 9, 4)
    assert sheet.heights.shape == (9, 12)
    gx, gy = np.meshgrid(sheet.x, sheet.y)
    for on_grid, pointwise in ((sheet.heights, s), (sheet.slope_x, s.slope_x), (sheet.slope_y, s.slope_y)):
        np.testing.assert_allclose(on_grid, pointwise(gx, gy), rtol=1e-10, atol=1e-10 * np.abs(on_grid).max())


def test_keyed_normals_are_standard_and_depend_on_the_key_alone():
    g1, g2 = F.keyed_normals(7, 1, np.arange(100_000))
    for g in (g1, g2):
        assert abs(g.mean()) < 4 / math.sqrt(g.size) and abs(g.var() - 1) < 4 * math.sqrt(2 / g.size)
    assert abs(np.mean(g1 * g2)) < 4 / math.sqrt(g1.size) and abs(np.mean(g1[1:] * g1[:-1])) < 4 / math.sqrt(g1.size)
    one = F.keyed_normals(7, 1, np.array([12345]))
    assert one[0][0] == g1[12345] and one[1][0] == g2[12345]
    other = F.keyed_normals(8, 1, np.arange(100_000))[0]
    assert abs(np.mean(g1 * other)) < 4 / math.sqrt(g1.size)


# ---- bad parameters ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: F.Film(rms=-1e-9, correlation_length=0.1, hurst=0.5), "rms"),
        (lambda: F.Film(rms=math.nan, correlation_length=0.1, hurst=0.5), "rms"),
        (lambda: F.Film(rms=1e-9, correlation_length=0.0, hurst=0.5), "correlation_length"),
        (lambda: F.Film(rms=1e-9, correlation_length=-0.1, hurst=0.5), "correlation_length"),
        (lambda: F.Film(rms=1e-9, correlation_length=0.1, hurst=0.0), "hurst"),
        (lambda: F.Film(rms=1e-9, correlation_length=0.1, hurst=1.5), "hurst"),
        (lambda: F.Film(rms=1e-9, correlation_length=0.1, hurst="0.5"), "hurst"),
        (lambda: F.profile(REF, 1.0, 1, 0), "n"),
        (lambda: F.profile(REF, 1.0, 30.0, 0), "n"),
        (lambda: F.profile(REF, 0.0, 30, 0), "length"),
        (lambda: F.profile(REF, 1.0, 30, -1), "seed"),
        (lambda: F.surface(REF, 1.0, 1.0, 1, 4, 0), "nx"),
        (lambda: F.surface(REF, 1.0, 1.0, 4, 0, 0), "ny"),
        (lambda: F.surface(REF, 1.0, -1.0, 4, 4, 0), "width"),
        (lambda: F.mode_seed(REF, 1.0, 0.0), "wavelength"),
        (lambda: F.projected_seed(REF, 1.0, np.zeros(10)), "mode"),
        (lambda: F.projected_seed(REF, 1.0, np.ones((3, 4))), "width"),
        (lambda: F.parse_film("1e-9,abc"), "film"),
        (lambda: F.parse_film("1e-9,0.1,0.5,2"), "film"),
        (lambda: F.parse_film("1e-9,0.1,2"), "hurst"),
    ],
)
def test_bad_parameters_raise_one_line_naming_them(call, name):
    with pytest.raises(ParameterError) as err:
        call()
    message = str(err.value)
    assert "\n" not in message and message.startswith(name) and "allowed" in message


def test_parse_film_fills_in_the_reference():
    assert F.parse_film("2e-9") == F.Film(2e-9, REF.correlation_length, REF.hurst)
    assert F.parse_film("2e-9, 0.01, 0.8") == F.Film(2e-9, 0.01, 0.8)
    assert "1e-09 m" in REF.describe() and "0.1 m" in REF.describe()
