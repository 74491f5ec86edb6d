"""Optical tables with a wavelength axis: linear interpolation in λ against RCWA at a wavelength between two
grid wavelengths (its error and its Δλ² convergence), the material's dispersion at each wavelength, the file
(version 2 beside version 1), and the range refused outside."""

import math

import numpy as np
import pytest

from lightsail_mbs import ParameterError
from lightsail_mbs.model import optics, rcwa
from lightsail_mbs.model.optics_spectrum import SpectralTable, grating_spectrum, read_spectrum

HARMONICS = 5  # a small RCWA: the tables here are about the interpolation in λ, not RCWA's convergence
SMALL = dict(harmonics=HARMONICS, theta_max=math.radians(10.0), step=math.radians(2.5), tolerance=0.0, grade=0)


def silicon_grating(wavelength: float) -> rcwa.Grating:
    """One Si bar (Green 2008's dispersive index, evaluated at the wavelength), fill 0.4, period 1.8 µm."""
    bar = rcwa.Bar(0.3, 0.7, rcwa.refractive_index("Si", wavelength))
    return rcwa.Grating(wavelength, 1.8e-6, (rcwa.Layer(0.4e-6, 1.0, (bar,)),), "Si bar")


def spectrum(grid, laser=1.2e-6, **settings):
    return grating_spectrum([silicon_grating(lam) for lam in grid], laser, cache_dir=False, **(SMALL | settings))


def node_error(table: optics.OpticalTable, direct: optics.OpticalTable) -> float:
    """max |c − c_RCWA| over the nodes, c_n and c_t."""
    np.testing.assert_array_equal(table.theta, direct.theta)
    return float(max(np.abs(table.c_n - direct.c_n).max(), np.abs(table.c_t - direct.c_t).max()))


def test_linear_in_wavelength_against_rcwa_between_grid_wavelengths():
    """λ* = 1.25 µm: on the grid 1.22, 1.26, 1.30 µm (w = 3/4) and on 1.22, 1.24, … 1.30 µm (w = 1/2), below the
    first Rayleigh anomaly (|θ| ≤ 10°) and above the Si bar's resonance near 1.17 µm, where the coefficients are
    smooth in λ: the linear interpolant's error w(1 − w)Δλ²/2 |∂²c/∂λ²| is 3 times smaller on the finer grid,
    and on the coarse grid is that formula with ∂²c/∂λ² from the second difference of the coarse tables (to
    its own O(Δλ) accuracy)."""
    target = 1.25e-6
    direct = optics.grating_table(silicon_grating(target), "TE", cache_dir=False, **SMALL)
    coarse = spectrum([1.22e-6, 1.26e-6, 1.30e-6], laser=1.26e-6)
    fine = spectrum(np.linspace(1.22e-6, 1.30e-6, 5), laser=1.26e-6)
    e_coarse, e_fine = node_error(coarse.at(target), direct), node_error(fine.at(target), direct)
    assert e_coarse < 0.01  # about 1 % of c_n ≈ 0.44 (measured 4.7e-3; 1.6e-3 on the finer grid)
    assert 2.0 < e_coarse / e_fine < 4.5  # 3 for a smooth c(λ) (measured 3.0)
    t = coarse.tables
    second = max(np.abs(t[0].c_n - 2 * t[1].c_n + t[2].c_n).max(), np.abs(t[0].c_t - 2 * t[1].c_t + t[2].c_t).max())
    predicted = 0.75 * 0.25 / 2 * second  # Δλ² ∂²c/∂λ² ≈ the second difference
    assert 0.5 < e_coarse / predicted < 2.5  # measured 1.5
    # the nearest grid wavelength's table (1.26 µm) is off by much more (measured 0.042)
    assert e_coarse < 0.25 * node_error(coarse.tables[1], direct)


def test_grid_wavelengths_are_their_own_tables_and_materials_disperse():
    s = spectrum([1.1e-6, 1.2e-6, 1.3e-6])
    for lam, table in zip(s.wavelengths, s.tables):
        assert s.at(lam) is table
        assert table.metadata["grating"]["wavelength"] == lam
    indices = [complex(*t.metadata["grating"]["layers"][0]["bars"][0]["index"]) for t in s.tables]
    assert indices[0].real > indices[1].real > indices[2].real  # Si's normal dispersion in the near infrared
    direct = optics.grating_table(silicon_grating(1.2e-6), "TE", cache_dir=False, **SMALL)
    assert s.rest().digest == direct.digest  # the laser's wavelength is a grid wavelength: the plain table
    assert 0 < s.normal_absorptance(1.2e-6) < 1e-4  # Green's κ ≈ 2e-7 absorbs a little


def test_file_round_trip_version_2_beside_version_1(tmp_path):
    s = spectrum([1.1e-6, 1.3e-6], laser=1.17e-6)
    path = s.save(tmp_path / "spectrum.npz")
    back = read_spectrum(path)
    np.testing.assert_array_equal(back.wavelengths, s.wavelengths)
    for a, b in zip(back.tables, s.tables):
        assert a.digest == b.digest
        assert a.extra.keys() == b.extra.keys()
    assert back.at(1.23e-6).digest == s.at(1.23e-6).digest
    # a case reads the file as its table at the laser's wavelength
    assert optics.OpticalTable.load(path).digest == s.rest().digest
    assert optics.read_table(path).normal_at_zero == pytest.approx(s.rest().normal_at_zero, rel=0, abs=0)
    single = s.tables[0].save(tmp_path / "single.npz")
    assert read_spectrum(single, single=True) is None
    with pytest.raises(optics.OpticsFileError, match="no wavelength axis"):
        read_spectrum(single)


def test_a_wavelength_outside_the_range_is_one_clear_error(tmp_path):
    path = spectrum([1.1e-6, 1.3e-6]).save(tmp_path / "s.npz")
    s = read_spectrum(path)
    for lam in (1.0e-6, 1.31e-6):
        with pytest.raises(ParameterError, match=r"wavelength=.* is invalid: allowed 1\.1e-06 … 1\.3e-06 m.*s\.npz"):
            s.at(lam)
    with pytest.raises(ParameterError, match="wavelength"):
        SpectralTable(s.wavelengths, s.tables, 1.4e-6)
