"""Closed forms of Section II against hand evaluation of Eqs (4), (7)–(10)."""

import numpy as np
import pytest

from lightsail_mbs import SailParameters
from lightsail_mbs.model import theory

C = 299_792_458.0


def paper_torsion():
    return SailParameters(thickness=1e-6, density=1000.0, intensity=1e8, defect_amplitude=1e-5, defect_mode=1.5)


def test_paper_critical_values():
    p = paper_torsion()
    # paper Sec. IV.B/C: E_cr,max = 4.5e11 Pa and T_cr,max = 3.34e-6 N for h = 1 µm, ν = 3/2
    assert theory.critical_modulus_max(p) == pytest.approx(4.5e11, rel=0.01)
    assert theory.critical_tension_max(p.replace(model="tnt")) == pytest.approx(3.34e-6, rel=0.01)
    assert theory.nominal_acceleration(p) == pytest.approx(2e8 / (C * 1000 * 1e-6))


def test_scalings():
    p = paper_torsion()
    e = theory.critical_modulus_max(p)
    assert theory.critical_modulus_max(p.replace(thickness=2e-6)) == pytest.approx(e / 8)
    assert theory.critical_modulus_max(p.replace(defect_mode=3.0)) == pytest.approx(e / 4)
    assert theory.critical_modulus_max(p.replace(defect_amplitude=2e-5)) == pytest.approx(2 * e)
    t = theory.critical_tension_max(p)
    assert theory.critical_tension_max(p.replace(width=2.0)) == pytest.approx(2 * t)
    assert theory.critical_tension_max(p.replace(thickness=1e-8)) == pytest.approx(t)


def test_local_critical_values_peak_at_troughs():
    p = paper_torsion()
    x = np.linspace(0, 1, 2001)
    e = theory.critical_modulus(p, x)
    # maximum of Eq. (7) where the sine has its trough, value E_cr,max
    assert e.max() == pytest.approx(theory.critical_modulus_max(p), rel=1e-6)
    assert np.sin(3 * np.pi * x[np.argmax(e)]) == pytest.approx(-1.0, abs=1e-5)
    assert theory.critical_tension(p, x).max() == pytest.approx(theory.critical_tension_max(p), rel=1e-6)


def test_perturbed_acceleration_second_order():
    p = paper_torsion().replace(defect_amplitude=1e-3)
    ratio = theory.perturbed_acceleration(p) / theory.nominal_acceleration(p)
    assert ratio == pytest.approx(1 - 2 * np.pi**2 * 1.5**2 * 1e-6)
