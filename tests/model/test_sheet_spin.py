"""The spinning sheet (model.sheet_spin): the case fields, the spun equilibrium against the spinning disc's
closed-form stress, and the free symmetric top's closed form against Euler's equations."""

import math

import numpy as np
import pytest

from lightsail_mbs import SailParameters
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import planforms, sheet, sheet_spin

UNLIT = dict(model="sheet", length=1.0, width=1.0, intensity=0.0, defect_amplitude=0.0)


def test_spin_fields_are_checked_and_left_out_of_the_record_at_zero():
    p = SailParameters(planform="disc", n=5, ny=6, **UNLIT)
    assert "spin_rate" not in p.to_dict() and "spin_tilt" not in p.to_dict()
    spun = p.replace(spin_rate=3.0, spin_tilt=0.1)
    assert spun.to_dict()["spin_rate"] == 3.0 and SailParameters.from_dict(spun.to_dict()) == spun
    with pytest.raises(ParameterError, match="spin_rate"):
        SailParameters(spin_rate=1.0)  # a chain
    with pytest.raises(ParameterError, match="spin_rate"):
        p.replace(boundary="clamped", spin_rate=1.0)
    with pytest.raises(ParameterError, match="spin_tilt"):
        p.replace(spin_tilt=0.1)
    with pytest.raises(ParameterError, match="spin_rate"):
        p.replace(spin_rate=math.nan)


@pytest.mark.parametrize("planform, n, ny", [("rectangle", 6, 4), ("disc", 9, 12), ("hexagon", 6, 1)])
def test_the_flat_spun_state_is_an_equilibrium_in_rigid_rotation(planform, n, ny):
    """The connectors' loads plus the centrifugal loads vanish on the flat sail, for every planform."""
    spun = SailParameters(planform=planform, n=n, ny=ny, **UNLIT).replace(spin_rate=50.0)
    centres, quaternions = sheet.initial_quaternions(spun)
    residual = sheet.static_loads(spun, sheet.connectors(spun), centres, quaternions)
    centrifugal = sheet_spin.centrifugal_loads(spun, centres, quaternions)
    assert np.abs((residual + centrifugal)[:, :3]).max() < 1e-8 * np.abs(centrifugal[:, :3]).max()
    v, omega = sheet_spin.spin_velocities(spun, centres)
    np.testing.assert_allclose(omega, np.tile([0.0, 0.0, 50.0], (len(centres), 1)))
    cm = sheet_spin.spin_centre(spun, centres)
    assert np.allclose(np.sum(v * (centres - cm), axis=1), 0.0, atol=1e-12)


@pytest.mark.parametrize("planform, n, ny", [("rectangle", 6, 4), ("disc", 9, 12), ("hexagon", 6, 1)])
def test_a_curved_spun_sheet_carries_the_flat_stress_and_is_pulled_flat(planform, n, ny):
    """A defect (a₀ = 1 mm, 10 times less) keeps the residual it had unspun plus the pull of the flat sheet's
    centrifugal stress towards flat: in the plane that residual is of second order in the slope, across it
    proportional to a₀, and it does negative work on the defect (the membrane's geometric stiffness). On the
    1-D sine of a rectangle that work is the tension of every x-edge times its slope change,
    −Σ_e F_e (w_b − w_a)²/s_e, to 1e-3."""
    residuals = []
    for amplitude in (1e-3, 1e-4):
        p = SailParameters(planform=planform, n=n, ny=ny, **dict(UNLIT, defect_amplitude=amplitude))
        spun = p.replace(spin_rate=50.0)
        centres, quaternions = sheet.initial_quaternions(p)
        before = sheet.static_loads(p, sheet.connectors(p), centres, quaternions)
        conn = sheet.connectors(spun)
        centrifugal = sheet_spin.centrifugal_loads(spun, centres, quaternions)
        residual = sheet.static_loads(spun, conn, centres, quaternions) + centrifugal - before
        scale = np.abs(centrifugal[:, :3]).max()
        assert np.abs(residual[:, :2]).max() < 2e-3 * scale * (amplitude / 1e-3) ** 2
        residuals.append(residual[:, 2])
        work = residual[:, 2] @ (centres[:, 2] - centres[:, 2].mean())
        assert work < 0.0
    np.testing.assert_allclose(residuals[0], 10.0 * residuals[1], rtol=1e-3, atol=1e-9 * scale)
    if planform == "rectangle":
        m = planforms.mesh_of(p)
        edges = len(m.pairs)
        tension = -(conn.stiffness[:edges, :2] * conn.offset[:edges, :2] * m.direction).sum(axis=1)
        rise = centres[m.pairs[:, 1], 2] - centres[m.pairs[:, 0], 2]
        assert work == pytest.approx(-np.sum(tension * rise**2 / m.span), rel=1e-3)


def test_disc_stress_converges_to_the_closed_form():
    """σ_r and σ_θ across the shared edges of a spinning free disc against the plane-stress closed form with
    ν_p = 0: the largest error (fraction of the centre's stress) within 2 % on the finest of three meshes,
    falling with the mesh."""
    errors = []
    for n, ny in ((9, 12), (17, 24), (33, 48)):
        p = SailParameters(planform="disc", n=n, ny=ny, **UNLIT).replace(spin_rate=100.0)
        conn = sheet.connectors(p)
        errors.append(sheet_spin.disc_stress_errors(p, conn.offset, conn.stiffness)[1:])
    errors = np.array(errors)
    assert np.all(errors[-1] < 0.02)
    assert np.all(np.diff(errors, axis=0) < 0)


def test_free_top_rates_solve_eulers_equations():
    """The closed form's derivative against I₁ω̇₁ = (I₂ − I₃)ω₂ω₃, I₁ω̇₂ = (I₃ − I₁)ω₃ω₁, ω̇₃ = 0."""
    i1, i3 = 2.0, 3.5
    t = np.linspace(0.0, 5.0, 2001)
    w = sheet_spin.free_top_rates(t, 4.0, 0.3, (i1, i3))
    dw = np.gradient(w, t, axis=0, edge_order=2)
    rhs = np.column_stack([-(i3 - i1) * w[:, 1] * w[:, 2] / i1, (i3 - i1) * w[:, 2] * w[:, 0] / i1, 0 * t])
    assert np.abs(dw - rhs)[5:-5].max() < 1e-4 * np.abs(rhs).max()
    np.testing.assert_allclose(w[0], [0.3, 0.0, 4.0])


def test_rigid_inertia_of_the_disc():
    """The tiles as one rigid body: a thin disc's I₃ = ½mR², I₁ = I₂ = ¼mR² + mh²/12 as the mesh refines
    (the polygon has the disc's area)."""
    p = SailParameters(planform="disc", n=33, ny=48, **UNLIT)
    centres, quaternions = sheet.initial_quaternions(p)
    inertia = sheet_spin.rigid_inertia(p, centres, quaternions)
    mass = p.density * p.thickness * math.pi * 0.25
    assert inertia[2, 2] == pytest.approx(0.5 * mass * 0.25, rel=2e-3)
    assert inertia[0, 0] == pytest.approx(inertia[1, 1], rel=1e-12)
