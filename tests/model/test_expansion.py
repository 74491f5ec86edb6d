"""Thermal expansion: the tension a framed chain loses, against the equilibrium of its slices as springs in series
with heated rest lengths; the sheet's equibiaxial relief; the margins against the paper's criteria."""

import numpy as np
import pytest

from lightsail_mbs import SailParameters
from lightsail_mbs.model import expansion, theory


def series_tension(k, rest, total):
    """The tension N of springs in series (stiffnesses k, rest lengths rest) stretched to the length total:
    Σ (rest_i + N/k_i) = total, solved for N by a linear least-squares system of the n + 1 unknowns
    (N and the n stretched lengths) — independent of the closed form."""
    n = len(k)
    A = np.zeros((n + 1, n + 1))
    b = np.zeros(n + 1)
    for i in range(n):  # stretched length_i − N/k_i = rest_i
        A[i, i], A[i, n], b[i] = 1.0, -1.0 / k[i], rest[i]
    A[n, :n], b[n] = 1.0, total
    return np.linalg.solve(A, b)[n]


def test_a_framed_chain_loses_exactly_e_h_w_alpha_mean_rise():
    p = SailParameters(model="tnt", n=20, tension=5.0, youngs_modulus=270e9, thickness=1e-7, width=0.5)
    alpha = 2.3e-6
    l, k = p.length / p.n, p.youngs_modulus * p.thickness * p.width / (p.length / p.n)
    rises = np.random.default_rng(1).uniform(100.0, 900.0, p.n)  # a non-uniform temperature rise
    frame = p.n * (l + p.tension / k)  # the frame holds the pre-tensioned length
    N = series_tension(np.full(p.n, k), l * (1 + alpha * rises), frame)
    closed = expansion.remaining_tension(p, alpha, 0.27, float(np.mean(rises)))
    assert closed == pytest.approx(N, rel=1e-9)
    assert p.tension - closed == pytest.approx(expansion.chain_tension_relief(p, alpha, float(np.mean(rises))))


def test_the_sheets_relief_is_equibiaxial_plane_stress():
    """σ_x = σ_y = σ and ε_x = (σ − νσ)/E − α ΔT = 0 give σ = E α ΔT/(1 − ν): per metre, times h."""
    p = SailParameters(model="sheet", n=4, ny=4, edge_tension=100.0, youngs_modulus=2e11, thickness=1e-7)
    nu, alpha, rise = 0.3, 1e-5, 50.0
    sigma = np.linalg.solve([[1.0, -nu], [-nu, 1.0]], [p.youngs_modulus * alpha * rise] * 2)
    assert p.edge_tension - expansion.remaining_tension(p, alpha, nu, rise) == pytest.approx(sigma[0] * p.thickness)


def test_margins_are_the_papers_ratios_at_the_sail_frame_intensity():
    p = SailParameters(model="tnt", tension=1e-3, defect_amplitude=1e-4)
    intensity = 0.5 * p.intensity
    expected = 2e-4 / theory.critical_tension_max(p.replace(intensity=intensity, tension=0.0))
    assert expansion.margin(p, intensity, 2e-4) == pytest.approx(expected)
    q = SailParameters()  # the torsion default
    assert expansion.margin(q, q.intensity, None) == pytest.approx(q.youngs_modulus / theory.critical_modulus_max(q))
    assert expansion.margin(SailParameters(model="rigid"), 1e8, None) is None
    assert expansion.thermal_strain(2e-6, 1293.0, 293.0) == pytest.approx(2e-3)


@pytest.mark.parametrize("model", ["torsion", "rigid"])
def test_a_free_chain_heated_uniformly_keeps_its_shape_scaled(model):
    """The heated case's initial hinge points are the cold ones times 1 + α_T ΔT (to 1e-12 of L), its mass is the
    cold mass, and E_cr,max (Eq. 8) is unchanged."""
    from lightsail_mbs.model.shapes import hinge_points

    p = SailParameters(model=model, n=24, defect_amplitude=2e-3, defect_mode=2.5)
    hot = expansion.heated_case(p, expansion.thermal_strain(2.3e-6, 1293.0, 293.0))
    s = 1 + 2.3e-6 * 1000.0
    assert np.max(np.abs(hinge_points(hot) - s * hinge_points(p))) < 1e-12 * p.length
    assert hot.density * hot.thickness * hot.length * hot.width == pytest.approx(
        p.density * p.thickness * p.length * p.width, rel=1e-14
    )
    assert theory.critical_modulus_max(hot) == pytest.approx(theory.critical_modulus_max(p), rel=1e-13)
