"""The film on the sheet (model.sheet_shapes with SailParameters.film_*): the surface a sheet of ny ≥ 2 tiles
across starts from, and the line scan a strip of one tile across carries."""

import numpy as np
import pytest

from lightsail_mbs import SailParameters
from lightsail_mbs.model import film, shapes, sheet

SOFT = dict(model="sheet", youngs_modulus=4.5e9)
REF = film.REFERENCE_FILM


def filmed(p, seed=0, rms=REF.rms):
    return p.replace(film_rms=rms, film_correlation_length=REF.correlation_length, film_hurst=REF.hurst, film_seed=seed)


@pytest.mark.parametrize("defect", [{}, {"defect_mode_y": 1.5}, {"defect_amplitude": 0.0}])
def test_a_sheet_starts_off_its_ideal_shape_by_the_films_carried_rms(defect):
    """Over 20 films the tile centres move off the ideal (1-D, doubly sinusoidal or flat) shape by the RMS the
    12 × 12 grid carries (film.sheet_variance), and each tile turns by the film's slope."""
    p = SailParameters(n=12, ny=12, **SOFT, **defect)
    ideal, q_ideal = sheet.initial_quaternions(p)
    squares, tilts = [], []
    for seed in range(20):
        centres, q = sheet.initial_quaternions(filmed(p, seed))
        squares.append(np.mean((centres[:, 2] - ideal[:, 2]) ** 2))
        normal, normal_ideal = sheet.quaternion_rotation(q)[:, :, 2], sheet.quaternion_rotation(q_ideal)[:, :, 2]
        s = film.surface(REF, p.length, p.width, p.n, p.ny, seed)
        expected = -np.column_stack([s.slope_x.ravel(), s.slope_y.ravel()])
        tilts.append(np.max(np.abs(normal[:, :2] - normal_ideal[:, :2] - expected)) / np.max(np.abs(expected)))
    carried = np.sqrt(film.sheet_variance(REF, p.length, p.width, p.n, p.ny))
    assert np.sqrt(np.mean(squares)) == pytest.approx(carried, rel=0.15)
    assert max(tilts) < 1e-3  # the film's slope, to the defect's second order
    np.testing.assert_array_equal(np.isfinite(centres), True)


def test_the_film_moves_the_tiles_in_proportion_to_its_rms():
    p = SailParameters(n=8, ny=6, **SOFT)
    ideal = sheet.initial_quaternions(p)[0][:, 2]
    small, large = (sheet.initial_quaternions(filmed(p, rms=rms))[0][:, 2] - ideal for rms in (1e-9, 1e-8))
    np.testing.assert_allclose(large, 10 * small, rtol=1e-6, atol=1e-6 * np.max(np.abs(large)))


def test_a_strip_sees_the_chains_line_scan():
    """A strip of one tile across carries one body across its width, as the chain does, so it carries the
    film's line scan along x: it starts exactly as the torsion chain of the same sail and film (as_strip),
    whose RMS (film.carried_variance) exceeds the surface a one-tile grid would carry across."""
    p = filmed(SailParameters(n=30, ny=1, **SOFT), seed=3)
    centres, q = sheet.initial_quaternions(p)
    chain = shapes.initial_state(sheet.as_strip(p))
    np.testing.assert_array_equal(centres[:, 2], chain.y)
    np.testing.assert_array_equal(centres[:, 0], chain.x)
    np.testing.assert_allclose(2 * np.arctan2(-q[:, 2], q[:, 0]), chain.theta, rtol=1e-12, atol=1e-18)
    assert sheet.as_strip(p).film_seed == 3 and sheet.as_strip(p).film_rms == REF.rms
    moved = centres[:, 2] - sheet.initial_quaternions(p.replace(film_rms=0.0))[0][:, 2]
    scan = film.profile(REF, p.length, p.n, p.film_seed).hinge_heights  # the slices lie along the scan's chords
    np.testing.assert_allclose(moved, 0.5 * (scan[:-1] + scan[1:]), atol=1e-3 * REF.rms)
    assert film.carried_variance(REF, p.length, p.n) > 2 * film.sheet_variance(REF, p.length, p.width, p.n, 1)


def test_a_filmed_flat_sheet_has_its_membrane_at_rest_in_the_filmed_shape():
    """Without a defect the film alone makes the initial shape: the in-plane springs rest there (Connectors.gap
    set), as they do for a defect."""
    p = filmed(SailParameters(n=6, ny=6, defect_amplitude=0.0, **SOFT), rms=1e-7)
    assert np.any(sheet.connectors(p).gap != 0)
    assert not np.any(sheet.connectors(p.replace(film_rms=0.0)).gap != 0)
