"""Linear stability (analysis.linear_stability): the linearised flat sail of both solvers — the load does not
shift the spectrum at first order, it acts along the sail."""

import numpy as np
import pytest

from lightsail_mbs import SailParameters, paper_case
from lightsail_mbs.analysis import linear_stability as st

LINEAR_CASES = {
    "torsion-stable": paper_case("torsion-stable", n=12),
    "torsion-soft": paper_case("torsion-soft", n=12),
    "tnt-inextensible": paper_case("tnt-stable", n=12, axial_springs=False),
    "tnt-extensible": paper_case("tnt-stable", n=8),
    "rigid": paper_case("rigid", n=12),
}


def elastic_shift(lit, dark):
    """Largest |Δω²|/ω² over the modes with ω² > 0 (the rigid-body zeros compared absolutely elsewhere)."""
    w2 = dark.omega_squared
    keep = w2 > 1e-9 * max(w2.max(), 1e-300)
    if not keep.any():
        return 0.0
    return float(np.max(np.abs(lit.omega_squared[keep] - w2[keep]) / w2[keep]))


@pytest.mark.parametrize("name", LINEAR_CASES)
def test_reduced_linear_spectrum_with_load_equals_unloaded(name):
    """The load enters the flat-state Jacobian only through the axial rows: spectrum unchanged,
    to far below the g₀k it would shift it by if it acted transversely at first order."""
    p = LINEAR_CASES[name]
    lit, dark = st.linear_spectrum(p, "reduced"), st.linear_spectrum(st.unlit(p), "reduced")
    assert elastic_shift(lit, dark) < 1e-6
    scale = max(st.load_rate_scale(p), np.abs(dark.omega_squared).max())
    assert np.max(np.abs(lit.omega_squared - dark.omega_squared)) < 1e-9 * scale
    assert lit.max_growth_rate < 1e-6 * np.sqrt(st.load_rate_scale(p))


@pytest.mark.parametrize("name", ["torsion-stable", "torsion-soft", "tnt-inextensible", "rigid"])
def test_exudyn_linear_spectrum_with_load_equals_unloaded_and_reduced(name):
    p = LINEAR_CASES[name]
    lit, dark = st.linear_spectrum(p, "exudyn"), st.linear_spectrum(st.unlit(p), "exudyn")
    assert elastic_shift(lit, dark) < 1e-6
    scale = max(st.load_rate_scale(p), np.abs(dark.omega_squared).max())
    assert np.max(np.abs(lit.omega_squared - dark.omega_squared)) < 1e-6 * scale
    reduced = st.linear_spectrum(st.unlit(p), "reduced")
    assert elastic_shift(dark, reduced) < 1e-6  # the two solvers' unloaded chains agree


@pytest.mark.parametrize("name", ["torsion-soft", "rigid"])
def test_load_acts_along_the_sail_at_first_order(name):
    """It is there, but axial: ∂ẍ₁/∂θ_k = −g₀/n (the whole chain's x-force −f₀Σθ over its mass),
    while the transverse rows do not see it. For the rigid chain, whose spectrum is all zeros with and
    without the load, this is the check that can fail."""
    p = LINEAR_CASES[name]
    jac, dark = st.jacobian(p), st.jacobian(st.unlit(p))
    dof = p.n + 2
    np.testing.assert_allclose(jac[dof, 2:dof], -p.nominal_acceleration / p.n, rtol=1e-6)
    transverse = np.abs(jac[dof + 1 :, :dof] - dark[dof + 1 :, :dof]).max()
    assert transverse < 1e-9 * p.nominal_acceleration


def test_exudyn_own_forward_difference_jacobian_is_noisy_with_load():
    """Exudyn's forward-difference Jacobian of the lit tree cancels f₀-sized load and frame terms:
    its soft bending frequencies move by ≫ 1e-6 (numerical), the central-difference load stiffness
    does not — why mass_stiffness adds the load Jacobian itself."""
    p = SailParameters(n=8, youngs_modulus=4.5e11)
    dark = st.linear_spectrum(st.unlit(p), "exudyn")
    noisy = st.spectrum_of_system(*st.mass_stiffness(p, load="solver"))
    assert elastic_shift(noisy, dark) > 1e-4
    assert elastic_shift(st.linear_spectrum(p, "exudyn"), dark) < 1e-6


@pytest.mark.parametrize("name", ["rigid", "torsion-soft", "tnt-inextensible"])
def test_exudyn_load_stiffness_is_the_axial_first_order_load(name):
    """Exudyn's linearisation: K(lit) − K(unlit) = −∂Q_load/∂q is f₀·(n − j) in the axial row X against the
    j-th relative angle (the x-force −f₀Σθ_k, θ_k the sum of the relative angles up to k) and zero in every
    other row, to 1e-9 f₀ (central differences)."""
    from lightsail_mbs.solvers.exudyn.tree import ChainLayout

    p = LINEAR_CASES[name]
    _, lit = st.mass_stiffness(p)
    _, dark = st.mass_stiffness(st.unlit(p))
    load = (lit - dark) / p.flat_force
    angles = ChainLayout.of(p).angle_index
    expected = np.zeros_like(load)
    expected[0, angles] = p.n - np.arange(p.n)
    np.testing.assert_allclose(load, expected, rtol=0, atol=1e-9 * p.n)
