"""Plate and membrane closed forms: Navier's series against Timoshenko's tables, frequencies by hand."""

import math

import pytest

from lightsail_mbs.model import plate_theory
from tests.helpers import plate


def test_navier_series_gives_the_tabulated_centre_deflection():
    """Timoshenko & Woinowsky-Krieger Table 8: w = 0.00406 q a⁴/D at the centre of the square; a 2:1
    rectangle 0.01013 q b⁴/D (b the short side)."""
    assert plate_theory.navier_deflection(1.0, 1.0, 1.0, 1.0, 0.5, 0.5) == pytest.approx(0.00406, abs=5e-6)
    assert plate_theory.navier_deflection(1.0, 1.0, 2.0, 1.0, 1.0, 0.5) == pytest.approx(0.01013, abs=5e-5)
    # converged: more terms change nothing at 1e-7
    a = plate_theory.navier_deflection(1.0, 1.0, 1.0, 1.0, 0.5, 0.5, terms=201)
    assert plate_theory.navier_deflection(1.0, 1.0, 1.0, 1.0, 0.5, 0.5, terms=801) == pytest.approx(a, rel=1e-7)


def test_frequencies_and_centre_deflections_of_a_sheet_case():
    p = plate("clamped", edge_tension=2.0)
    D = 1.2e9 * 1e-6 / 12
    assert plate_theory.bending_rigidity(p) == pytest.approx(D)
    assert plate_theory.centre_deflection(p) == pytest.approx(0.00126532 * 0.01 / D)
    assert plate_theory.plate_frequency(p, 1, 2) == pytest.approx(math.pi**2 * 5 * math.sqrt(D / 10.0))
    assert plate_theory.membrane_frequency(p, 2, 2) == pytest.approx(math.pi * math.sqrt(2 / 10.0) * math.sqrt(8))
    assert plate_theory.lowest_modes(4) == [(1, 1), (1, 2), (2, 1), (2, 2)]
    assert plate_theory.lowest_modes(2, length=2.0) == [(1, 1), (2, 1)]
