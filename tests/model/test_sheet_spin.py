"""The spinning sheet (model.sheet_spin): the case fields, the spun equilibrium against the spinning disc's
closed-form stress, and the free symmetric top's closed form against Euler's equations."""

import math

import numpy as np
import pytest

from lightsail_mbs import SailParameters
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import sheet, sheet_spin

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
@pytest.mark.parametrize("defect", [0.0, 1e-3])
def test_the_spun_state_is_an_equilibrium_in_rigid_rotation(planform, n, ny, defect):
    """The connectors' loads plus the centrifugal loads vanish in the initial shape (up to the net moment a
    non-principal spin axis leaves), for every planform; a defect keeps the residual it had unspun."""
    p = SailParameters(planform=planform, n=n, ny=ny, **dict(UNLIT, defect_amplitude=defect))
    spun = p.replace(spin_rate=50.0)
    centres, quaternions = sheet.initial_quaternions(p)
    before = sheet.static_loads(p, sheet.connectors(p), centres, quaternions)
    after = sheet.static_loads(spun, sheet.connectors(spun), centres, quaternions)
    centrifugal = sheet_spin.centrifugal_loads(spun, centres, quaternions)
    residual = after + centrifugal - before
    scale = np.abs(centrifugal[:, :3]).max()
    assert np.abs(residual[:, :3]).max() < 1e-8 * scale
    v, omega = sheet_spin.spin_velocities(spun, centres)
    np.testing.assert_allclose(omega, np.tile([0.0, 0.0, 50.0], (len(centres), 1)))
    cm = sheet_spin.spin_centre(spun, centres)
    assert np.allclose(np.sum(v * (centres - cm), axis=1), 0.0, atol=1e-12)


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
