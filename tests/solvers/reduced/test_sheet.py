"""The in-house sheet solver: equilibria it must keep, the chain it must reduce to, the linearised
unlit sheet it must not make unstable, plates and membranes against Kirchhoff and string theory, and
its Radau's convergence."""

import math

import numpy as np
import pytest

from lightsail_mbs import RunSettings, SailParameters, solve
from lightsail_mbs.model import plate_theory, sheet, theory
from lightsail_mbs.solvers.reduced import sheet as reduced_sheet
from tests.helpers import plate

SOFT = dict(model="sheet", youngs_modulus=4.5e9)


def accelerations(p):
    model = reduced_sheet.SheetModel(p)
    return model.rhs(0.0, model.y0()).reshape(-1, reduced_sheet.STATE)[:, 7:]


def test_flat_unlit_sheet_is_at_rest_exactly():
    assert not accelerations(SailParameters(n=4, ny=3, defect_amplitude=0.0, intensity=0.0, **SOFT)).any()


def test_edge_tension_prestress_is_an_equilibrium():
    """The isotropic pre-stress plus the follower edge tension leave the flat free sheet at rest."""
    p = SailParameters(n=5, ny=4, defect_amplitude=0.0, intensity=0.0, edge_tension=0.3, **SOFT)
    a = accelerations(p)
    t = sheet.Tiles.of(p)
    assert np.max(np.abs(a[:, :3])) < 1e-9 * 0.3 * t.b / t.mass
    assert np.max(np.abs(a[:, 3:])) < 1e-9 * 0.3 * t.b * t.a / t.inertia.min()


def test_stress_free_doubly_curved_sheet_is_at_rest():
    """Bending and membrane springs at rest in the initial shape: the unlit sheet is an exact equilibrium."""
    p = SailParameters(n=6, ny=5, defect_mode_y=1.0, intensity=0.0, bending_reference="initial", **SOFT)
    a = accelerations(p)
    lit = p.replace(intensity=1e8).nominal_acceleration * (2 * math.pi * p.defect_amplitude) ** 2  # g₀ (k a₀)²
    assert np.max(np.abs(a[:, :3])) < 1e-6 * lit


def growth_rates(p) -> np.ndarray:
    """Eigenvalues of the first-order linearisation in the 6N generalised coordinates, by real part."""
    model = reduced_sheet.SheetModel(p)
    y = model.y0()
    J = model.jacobian(0.0, y).toarray()
    X, V = model.position_indices, model.velocity_indices
    K = J[np.ix_(V, X)] @ model.kinematics(y).toarray()
    n = K.shape[0]
    A = np.block([[np.zeros((n, n)), np.eye(n)], [K, J[np.ix_(V, V)]]])
    w = np.linalg.eigvals(A)
    return w[np.argsort(-w.real)]


def test_unlit_stress_free_shell_does_not_grow():
    """A doubly curved sheet at rest in its own shape with a stiff membrane (E_m = E, the paper's scale) is
    an elastic equilibrium: its linearised growth rates stay near 0 (< 0.05/s; the drilling springs' former
    stiffness gave 15/s through the connector law's non-potential moments: model.sheet docstring)."""
    p = SailParameters(
        n=6, ny=6, defect_mode_y=1.5, intensity=0.0, bending_reference="initial", model="sheet", youngs_modulus=4.9e12
    )
    assert growth_rates(p)[0].real < 0.05


def test_newton_at_the_round_off_floor_of_a_prestressed_sheet_converges():
    """An unlit doubly curved sheet held in equilibrium under 8 T_cr,max by connector rest offsets
    (initial_equilibrium): its internal forces are large and in balance, and simplified Newton's
    increments stagnate at ~1e-9 of the tolerance with contraction rates of 0.9–1. Those increments are
    converged, not diverging: the run takes a few dozen steps (43,000, 87 % rejected, with the rate test
    alone) and stays in its equilibrium."""
    from lightsail_mbs.studies.sheet import with_ratio

    p = SailParameters(n=6, ny=6, defect_mode_y=1.5, initial_equilibrium=True, membrane_modulus=4.5e9, **SOFT)
    p = with_ratio(p, "edge_tension", 8.0).replace(intensity=0.0)
    r = solve(p, "reduced", RunSettings(t_final=0.1), uncertainty=False)
    assert r.error is None and r.info["steps"] < 200 and r.info["rejected_steps"] < 20
    assert abs(r.max_amplitude_ratio - 1.0) < 1e-9


def test_sheet_with_one_defect_across_is_the_chain():
    """1-D sine across the width, free side edges: the soft sail fails within 0.1 % of the torsion chain
    (the stiff sail over 6 s is the slow test below; both at full length: validation/sheet_chain_limit.py)."""
    p = SailParameters(n=30, ny=2, **SOFT)
    settings = RunSettings(t_final=3.0)
    strip = solve(sheet.as_strip(p), "reduced", settings)
    tiles = solve(p, "reduced", settings)
    assert tiles.failure_time == pytest.approx(strip.failure_time, rel=1e-3)


def test_simply_supported_plate_statics_and_modes_on_a_coarse_grid():
    """9 × 9 tiles: the centre deflection within 0.2 % of Navier, the first four frequencies within 2.5 %
    (grid error, shrinking with refinement: the slow tests hold 19 × 19 to 1 %)."""
    p = plate("simply_supported")
    w = reduced_sheet.static_centres(p)[40, 2]
    assert w == pytest.approx(plate_theory.centre_deflection(p), rel=2e-3)
    omega = reduced_sheet.eigenfrequencies(p.replace(pressure=0.0), 4)
    exact = [plate_theory.plate_frequency(p, m, n) for m, n in plate_theory.lowest_modes(4)]
    np.testing.assert_allclose(omega, exact, rtol=0.025)
    assert np.all(omega < exact)  # the tiles' discretisation errs soft


def test_tensioned_membrane_modes_on_a_coarse_grid():
    p = SailParameters(
        model="sheet",
        n=9,
        ny=9,
        youngs_modulus=4.5e9,
        bending=False,
        edge_tension=1.0,
        intensity=0.0,
        defect_amplitude=0.0,
        boundary="simply_supported",
    )
    omega = reduced_sheet.eigenfrequencies(p, 4)
    exact = [plate_theory.membrane_frequency(p, m, n) for m, n in plate_theory.lowest_modes(4)]
    np.testing.assert_allclose(omega, exact, rtol=0.01)


def test_rtol_convergence_of_the_deflections():
    """A 6 × 5 doubly sinusoidal sheet over 0.5 s: rtol 1e-7 and 1e-9 agree to 1e-5 a₀ in every tile."""
    p = SailParameters(n=6, ny=5, defect_mode_y=1.0, **SOFT)
    settings = RunSettings(t_final=0.5, output_interval=0.05)
    a, b = (solve(p, "reduced", settings, rtol=r) for r in (1e-7, 1e-9))
    assert np.max(np.abs(a.deflection() - b.deflection())) < 1e-5 * p.defect_amplitude
    assert a.info["steps"] < b.info["steps"]


def test_bad_options_are_named():
    p = SailParameters(n=4, ny=3, **SOFT)
    with pytest.raises(Exception, match="method"):
        solve(p, "reduced", RunSettings(t_final=0.1), method="DOP853")
    with pytest.raises(Exception, match="rtol"):
        solve(p, "reduced", RunSettings(t_final=0.1), rtol=2.0)


def test_stability_scale_is_the_papers():
    """The strip's E_cr,max and T_cr,max per metre, the units of every sheet stability result."""
    p = SailParameters(n=12, ny=12, **SOFT)
    assert theory.critical_modulus_max(p) == pytest.approx(4.506e11, rel=1e-3)
    assert plate_theory.critical_tension_per_width(p) == pytest.approx(3.336e-6, rel=1e-3)
    assert math.isclose(plate_theory.critical_tension_per_width(p.replace(width=2.0)), 3.336e-6, rel_tol=1e-3)


@pytest.mark.slow
def test_stiff_sheet_survives_with_the_chains_amplitude_ratio():
    """The stiff sail (E = 4.5e13 Pa = E_m), 1-D sine across the width, 30 × 1 tiles, 6 s: survives, and its
    largest amplitude ratio is the reduced torsion chain's within 1 % (measured: to 1e-5)."""
    p = SailParameters(model="sheet", n=30, ny=1, youngs_modulus=4.5e13)
    settings = RunSettings(t_final=6.0)
    chain = solve(SailParameters(model="torsion", n=30, youngs_modulus=4.5e13), "reduced", settings)
    tiles = solve(p, "reduced", settings)
    assert not tiles.failed and not chain.failed
    assert tiles.max_amplitude_ratio == pytest.approx(chain.max_amplitude_ratio, rel=1e-2)


@pytest.mark.slow
@pytest.mark.parametrize("boundary", ["simply_supported", "clamped"])
def test_plate_statics_within_two_percent_at_39_and_modes_within_one_percent_at_19(boundary):
    """Kirchhoff plates under uniform pressure: centre deflection within 2 % of Timoshenko's at 39 × 39 and
    closer than at 19 × 19; the simply supported plate's first four frequencies within 1 % at 19 × 19."""
    p = plate(boundary, tiles=39)
    exact = plate_theory.centre_deflection(p)
    fine = reduced_sheet.static_centres(p)[19 * 39 + 19, 2]
    coarse = reduced_sheet.static_centres(p.replace(n=19, ny=19))[9 * 19 + 9, 2]
    assert fine == pytest.approx(exact, rel=0.02)
    assert abs(fine - exact) < abs(coarse - exact)
    if boundary == "simply_supported":
        q = p.replace(n=19, ny=19, pressure=0.0)
        omega = reduced_sheet.eigenfrequencies(q, 4)
        modes = [plate_theory.plate_frequency(q, m, n) for m, n in plate_theory.lowest_modes(4)]
        np.testing.assert_allclose(omega, modes, rtol=0.01)


@pytest.mark.parametrize("single", [False, True])
def test_complex_solve_products_are_the_real_matrices_products(single):
    """The complex system's A_X, B copies (made once per Jacobian) give bit for bit the products of the real
    matrices with a complex vector, and the reduced LU solves (μ I − J) x = f of the full system: in double
    precision to 1e-9 of μ x_V, with the LU in single precision (the solver's default) to 1e-5 (float32's
    ε = 6e-8 times the matrix's condition), the first block row, formed in double, to round-off."""
    from lightsail_mbs.solvers.reduced.sheet_radau import MU_COMPLEX, ReducedLU, ReducedSystem

    model = reduced_sheet.SheetModel(SailParameters(n=4, ny=3, **SOFT))
    y = model.y0()
    J = model.jacobian(0.0, y)
    system = ReducedSystem(J, model.kinematics(y), model.position_indices, model.velocity_indices)
    f = np.array([1.0, 1.0j]) @ np.random.default_rng(1).normal(size=(2, model.n))
    AX, B = system.products(True)
    assert np.array_equal(AX @ f[system.X], system.AX @ f[system.X])
    assert np.array_equal(B @ f[system.V], system.B @ f[system.V])
    mu = MU_COMPLEX / 1e-3
    x = ReducedLU(system, mu, single).solve(f)
    x_x, x_v, f_x, f_v = x[system.X], x[system.V], f[system.X], f[system.V]
    # the system it solves (sheet_radau's docstring): μ x_X − B x_V = f_X, μ x_V − A_X x_X − A_V x_V = f_V
    assert np.max(np.abs(mu * x_x - system.B @ x_v - f_x)) < 1e-12 * np.max(np.abs(f))
    residual = np.max(np.abs(mu * x_v - system.AX @ x_x - system.AV @ x_v - f_v)) / np.max(np.abs(mu * x_v))
    assert residual < (1e-5 if single else 1e-9)


def test_single_precision_lu_falls_back_to_double_on_a_zero_pivot():
    """A reduced matrix whose single-precision elimination meets a pivot of exactly 0 (2²⁴ + 1 rounds to 2²⁴:
    the second pivot 2²⁴ − 2²⁴·2²⁴/2²⁴; in double 2²⁴/(2²⁴ + 1)) is factored in double, and solves to 1e-9."""
    import types

    import scipy.sparse as sp
    from scipy.sparse.linalg import splu

    from lightsail_mbs.solvers.reduced import block_lu
    from lightsail_mbs.solvers.reduced.sheet_radau import ReducedLU

    n, big, mu = 12, 2.0**24, 1.0
    S = sp.lil_matrix(np.eye(n))
    S[0, 0], S[0, 6], S[6, 0], S[6, 6] = big + 1.0, big, big, big
    S = S.tocsc()
    with pytest.raises(RuntimeError, match="singular"):
        splu(S.astype(np.float32), permc_spec="NATURAL", diag_pivot_thresh=0.0, options=dict(SymmetricMode=True))
    K = (mu * (mu * sp.identity(n) - S)).tocsc()  # S = μ I − A_V − K/μ with A_V = 0
    pattern = block_lu.BlockPattern(block_lu.body_graph(abs(K) + sp.identity(n)))
    system = types.SimpleNamespace(
        identity=sp.identity(n, format="csc"),
        AV=sp.csc_matrix((n, n)),
        K=K,
        pattern=pattern,
        order=(6 * pattern.order[:, None] + np.arange(6)).ravel(),
        X=np.arange(0),
        V=np.arange(n),
        n=n,
        products=lambda complex_: (sp.csr_matrix((n, 0)), sp.csr_matrix((0, n))),
    )
    lu = ReducedLU(system, mu, single=True)
    assert lu.dtype == np.float64
    f = np.random.default_rng(2).normal(size=n)
    x = lu.solve(f)
    assert np.max(np.abs(S @ x - f)) < 1e-9 * np.max(np.abs(S @ x))
