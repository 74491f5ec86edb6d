"""The sheet's growth-rate spectrum and its symmetry families: the flat sheet's spectrum against the solver's
eigenfrequencies, stable cases without a growing mode, the group algebra of the projectors, and the family of
known fields."""

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.optimize import linear_sum_assignment

from lightsail_mbs import SailParameters
from lightsail_mbs.analysis import sheet_spectrum as ss
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import sheet, theory
from lightsail_mbs.solvers import contract
from tests.helpers import plate

GRID = 6


def doubly(**changes) -> SailParameters:
    return SailParameters(
        **{"model": "sheet", "n": GRID, "ny": GRID, "youngs_modulus": 4.5e9, "defect_mode_y": 1.5, **changes}
    )


def stiff(ratio: float, **changes) -> SailParameters:
    p = doubly(**changes)
    return p.replace(youngs_modulus=ratio * theory.critical_modulus_max(p))


def test_linearise_is_a_declared_capability_of_the_reduced_sheet_only():
    p = doubly()
    L = contract.lookup("reduced", p).capability("linearise")(p)
    n = 6 * p.n * p.ny
    assert L.shape == (2 * n, 2 * n)
    assert abs(L[:n, n:] - sp.identity(n)).max() == 0 and L[:n, :n].nnz == 0  # ξ̇ = V
    with pytest.raises(ParameterError, match="linearise"):
        contract.lookup("exudyn", p).capability("linearise")


def test_supported_plate_spectrum_is_the_solvers_eigenfrequencies():
    """The flat, unloaded, simply supported plate (its eigenfrequencies are held to Kirchhoff's in
    validation/sheet_plates.py) oscillates without growth at the eigenfrequencies capability's ω: λ = ±iω."""
    p = plate("simply_supported", tiles=GRID)
    s = ss.spectrum(p)
    omega = contract.lookup("reduced", p).capability("eigenfrequencies")(p, count=6)
    lowest = np.sort(np.abs(s.modes.eigenvalues))[::2][:6]  # each ω once
    np.testing.assert_allclose(lowest, omega, rtol=1e-6)
    assert s.growth_rate < 1e-6 * omega[0]  # the membrane damping makes the rest decay


def test_free_sheet_spectrum_drops_exactly_the_rigid_modes():
    """The flat, unloaded free sheet: its deformation frequencies are √eig(−K) without the six rigid-body modes.
    Their ω² are the finite differences' round-off, ≤ 1e-2 of the lowest bending ω² for the paper's stiff sail,
    and couple to the bending modes at that level: removing them moves the bending ω by < 2e-3."""
    p = doubly(defect_amplitude=0.0, intensity=0.0, youngs_modulus=4.5e13)
    L = ss.linearisation(p)
    n = L.shape[0] // 2
    w2 = np.sort(np.linalg.eigvals(-L[n:, :n].toarray()).real)
    assert np.abs(w2[:6]).max() < 1e-2 * w2[6]
    s = ss.spectrum(p)
    assert s.modes.eigenvalues.size == 2 * (n - 6)
    lowest = np.sort(np.abs(s.modes.eigenvalues))[::2][:8]
    np.testing.assert_allclose(lowest, np.sqrt(w2[6:14]), rtol=2e-3)
    assert s.growth_rate < 1e-4 * lowest[0]  # the finite differences' noise


@pytest.mark.parametrize(
    "p",
    [stiff(100.0), doubly(intensity=0.0, bending_reference="initial")],
    ids=["100 E_cr,max", "unlit, stress-free"],
)
def test_stable_sheets_have_no_growing_deformation_mode(p):
    """Far above E_cr,max, and the unlit sheet at rest in its own shape (an elastic equilibrium), grow at no
    rate above round-off: 1e-6/s, a factor 1e-6 below the lowest frequency."""
    s = ss.spectrum(p)
    assert s.growth_rate < 1e-6
    assert np.abs(s.modes.eigenvalues).min() > 1e-3


def test_a_soft_doubly_curved_sheet_grows_in_its_own_family_too():
    """Below E_cr,max the released defect grows, and its own family A1 is among the growing ones."""
    s = ss.spectrum(stiff(0.5))
    assert s.growth_rate > 0.1 and s.family_rates["A1"] > 0.1


def test_projectors_are_orthogonal_idempotent_and_exhaustive():
    p = doubly()
    g = ss.generators(p)
    eye = sp.identity(6 * GRID * GRID)
    for G in g.values():
        assert abs(G @ G - eye).max() == 0  # involutions
    assert abs(g["swap"] @ g["mirror_x"] @ g["swap"] - g["mirror_y"]).max() == 0
    proj = ss.projectors(p)
    for a in ss.FAMILIES:
        assert abs(proj[a] @ proj[a] - proj[a]).max() < 1e-15
        assert abs(proj[a] - proj[a].T).max() == 0
        for b in ss.FAMILIES:
            if a < b:
                assert abs(proj[a] @ proj[b]).max() < 1e-15
    assert abs(sum(proj[f] for f in ss.FAMILIES) - eye).max() < 1e-15
    dims = {f: ss.family_basis(proj[f]).shape[1] for f in ss.FAMILIES}
    assert sum(dims.values()) == 6 * GRID * GRID and dims["E"] == 2 * ss.family_basis(proj["E+-"]).shape[1]


def test_symmetric_defect_and_rigid_motions_are_in_their_families():
    p = doubly()
    centres, _ = sheet.initial_quaternions(p)
    xi = np.zeros((GRID * GRID, 6))
    xi[:, :3] = centres - sheet.flat_centres(p)
    assert ss.family_weights(p, xi.ravel())["A1"][0] == pytest.approx(1.0, abs=1e-15)
    weights = ss.family_weights(p, ss.rigid_basis(p))  # translations x, y, z; rotations about x, y, z
    expected = ["E", "E", "A1", "E", "E", "B2"]
    assert [max(weights, key=lambda f, k=k: weights[f][k]) for k in range(6)] == expected
    assert all(max(w[k] for w in weights.values()) > 1 - 1e-12 for k in range(6))


def test_flat_sheet_commutes_with_the_symmetries_and_its_blocks_are_its_spectrum():
    """Without a defect the linearisation is symmetric (the grid and the connectors are); then every family's
    block holds a share of the whole deformation spectrum and together they hold all of it (E twice), up to the
    rigid modes' round-off coupling (free_sheet test above)."""
    p = doubly(defect_amplitude=0.0)
    assert max(ss.commutator_defects(p, ss.linearisation(p)).values()) < 1e-12
    whole = ss.spectrum(p).modes.eigenvalues
    blocks = ss.family_spectrum(p)
    parts = np.concatenate([blocks[f].eigenvalues for f in ss.FAMILIES] + [blocks["E"].eigenvalues])
    assert parts.size == whole.size
    # the two multisets matched one to one (a sort of nearly equal complex numbers is not robust to round-off)
    rows, cols = linear_sum_assignment(np.abs(whole[:, None] - parts[None, :]))
    np.testing.assert_allclose(parts[cols], whole[rows], rtol=1e-3, atol=2e-6)


def test_deflection_families_of_known_fields():
    p = doubly()
    flat = sheet.flat_centres(p)
    x, y = flat[:, 0] - 0.5, flat[:, 1] - 0.5
    fields = {
        "A1": np.cos(3 * np.pi * x) * np.cos(3 * np.pi * y),
        "A2": np.cos(2 * np.pi * x) - np.cos(2 * np.pi * y),
        "B1": x * y,
        "B2": x * y * (x * x - y * y),
        "E": x * np.cos(np.pi * y) ** 2,
    }
    for family, w in fields.items():
        centres = flat + np.column_stack([0 * w, 0 * w, w])
        parts = ss.deflection_families(p, centres)
        assert parts[family] > 0.1 * np.abs(w).max()
        assert all(parts[f] < 1e-15 for f in ss.FAMILIES if f != family)
    tilt = ss.deflection_families(p, flat + np.column_stack([0 * x, 0 * x, 0.3 * x + 0.1 * y + 2.0]))
    assert max(tilt.values()) < 1e-15  # a rigid tilt and lift is no deformation


def test_families_need_a_square_sheet():
    with pytest.raises(ParameterError, match="n = ny"):
        ss.generators(doubly().replace(ny=GRID + 1))


def test_families_and_the_diagonal_metric_need_the_rectangles_grid():
    """A disc of n = ny rings and sectors with L = W has neither the grid's mirrors nor tiles all alike."""
    disc = SailParameters(model="sheet", planform="disc", n=6, ny=6, youngs_modulus=4.5e9, defect_amplitude=0.0)
    assert np.ptp(sheet.Tiles.of(disc).masses) > 0
    with pytest.raises(ParameterError, match="planform='disc'"):
        ss.spectrum(disc)


def test_run_state_is_the_solvers_state():
    """A run's first sample rebuilt as the solver's state (quaternions from the xyz angles) is its start: the same
    centres, the same rotations, the same growth rates."""
    from lightsail_mbs import RunSettings, solve

    p = stiff(0.5).replace(n=4, ny=4)
    r = solve(p, "reduced", RunSettings(t_final=0.02, output_interval=0.01), uncertainty=False)
    state = ss.run_state(r, 0).reshape(-1, 13)
    centres, q = sheet.initial_quaternions(p)
    np.testing.assert_allclose(state[:, :3], centres - sheet.flat_centres(p), atol=1e-20)
    np.testing.assert_allclose(state[:, 3:7] * np.sign(state[:, 3:4]), q, atol=1e-15)
    rate = ss.spectrum(p).growth_rate  # the finite-difference Jacobian resolves it to ~1e-6
    assert ss.spectrum(p, state.ravel()).growth_rate == pytest.approx(rate, rel=1e-5)
