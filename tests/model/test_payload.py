"""A payload on a rigid stem: its attachment, the reduced kernel against a dense Lagrangian in which the
payload is a body of its own, and the two solvers on one run."""

import math

import numpy as np
import pytest

from lightsail_mbs import ParameterError, RunSettings, SailParameters, solve
from lightsail_mbs.model import payload
from lightsail_mbs.solvers.reduced.dynamics import ChainDynamics
from lightsail_mbs.solvers.reduced.kinematics import (
    ChainModel,
    centre_jacobian,
    centres,
    generalized_forces,
    velocity_terms,
)

rng = np.random.default_rng(3)


def dense_accelerations(p, q, qd):
    """q̈ = M⁻¹(Q − c) with the payload a separate point body with inertia J_p on slice j's angle: its
    Jacobian by central differences of payload.position, its J̇q̇ by a second difference along q̇ (none of
    the kernel's algebra)."""
    model = ChainModel.from_params(p)
    j = payload.attachment(p).slice_index
    g = p.nominal_acceleration

    def where(qq):
        x, y = centres(model, qq)
        return np.array(payload.position(p, x, y, qq[2 : p.n + 2]))

    eps = 1e-6
    jp = np.column_stack([(where(q + eps * e) - where(q - eps * e)) / (2 * eps) for e in np.eye(q.size)])
    h = 1e-4 / np.linalg.norm(qd)
    hp = (where(q + h * qd) - 2 * where(q) + where(q - h * qd)) / h**2
    jac = centre_jacobian(model, q)
    mass = p.slice_mass * np.einsum("jai,jak->ik", jac, jac) + p.payload_mass * jp.T @ jp
    idx = np.arange(2, p.n + 2)
    mass[idx, idx] += p.slice_inertia
    mass[2 + j, 2 + j] += p.payload_inertia
    # the sail's own generalized forces (light, frame force −m g₀, springs, end tension), then the payload's
    forces = generalized_forces(model, q, qd) + jp.T @ np.array([0.0, -p.payload_mass * g])
    c = velocity_terms(model, q, qd) + p.payload_mass * jp.T @ hp
    return np.linalg.solve(mass, forces - c)


@pytest.mark.parametrize("n", [7, 8])
@pytest.mark.parametrize(
    "extra",
    [
        dict(payload_mass=2e-4, payload_stem=0.3),
        dict(payload_mass=1e-3, payload_stem=0.7, payload_inertia=1e-6, billow_radius=1.5),
        dict(payload_mass=5e-4, payload_stem=2.0, model="tnt", tension=1e-3, axial_springs=False),
    ],
)
def test_kernel_equals_the_dense_lagrangian(n, extra):
    p = SailParameters(n=n, youngs_modulus=4.5e11, beam_waist=1.5, beam_centre=0.45, **extra)
    q = np.concatenate([[0.01, -0.02], 0.2 * rng.standard_normal(n)])
    qd = np.concatenate([[0.1, 0.2], 0.3 * rng.standard_normal(n)])
    kernel = ChainDynamics(ChainModel.from_params(p)).accelerations(q, qd)
    dense = dense_accelerations(p, q, qd)
    assert np.max(np.abs(kernel - dense)) <= 1e-6 * np.max(np.abs(dense))
    light = p.replace(payload_mass=1e-300, payload_inertia=0.0)
    plain = p.replace(payload_mass=0.0, payload_stem=0.0, payload_inertia=0.0)
    light, plain = (ChainDynamics(ChainModel.from_params(c)).accelerations(q, qd) for c in (light, plain))
    assert np.max(np.abs(light - plain)) <= 1e-12 * np.max(np.abs(plain))  # the general sweep → the plain one


def test_attachment_and_frame_acceleration():
    p = SailParameters(n=9, payload_mass=1e-3, payload_stem=0.5, billow_radius=2.0, defect_amplitude=0.0)
    a = payload.attachment(p)
    assert a.slice_index == 4 and a.mass == pytest.approx(p.slice_mass + 1e-3, rel=1e-15)
    from lightsail_mbs.model.shapes import initial_state

    s = initial_state(p)
    xp, yp = payload.position(p, s.x, s.y, s.theta)
    assert xp == pytest.approx(s.x[4], abs=1e-15) and yp == pytest.approx(s.y[4] - 0.5, abs=1e-15)  # along −ŷ
    sail = p.density * p.thickness * p.length * p.width
    assert p.nominal_acceleration == pytest.approx(SailParameters().nominal_acceleration * sail / (sail + 1e-3))
    even = SailParameters(n=8, payload_mass=1e-3, payload_stem=0.5, defect_amplitude=0.0)
    s = initial_state(even)
    xp, yp = payload.position(even, s.x, s.y, s.theta)
    assert xp == pytest.approx(0.5, abs=1e-15) and yp == pytest.approx(-0.5, abs=1e-15)
    for bad, name in [
        (dict(payload_mass=-1.0), "payload_mass"),
        (dict(payload_stem=1.0), "payload_stem"),
        (dict(payload_mass=1e-3, model="tnt", tension=1e-3), "payload_mass"),
        (dict(payload_mass=1e-3, boundary="cantilever"), "payload_mass"),
    ]:
        with pytest.raises(ParameterError, match=name):
            SailParameters(**bad)


def test_the_frame_acceleration_holds_the_craft_s_centre_of_mass():
    """At rest and flat, the light on the sail equals (M_sail + m_p) g₀: the centre of mass of sail and payload
    does not accelerate, though the payload's weight bends the sail (and its middle moves)."""
    p = SailParameters(n=9, payload_mass=1e-3, payload_stem=0.5, defect_amplitude=0.0)
    model = ChainModel.from_params(p)
    q = np.zeros(model.dof)
    q[0] = -0.5 * p.slice_length  # hinge 0 at x = 0: slice 1's centre
    qdd = ChainDynamics(model).accelerations(q, np.zeros_like(q))

    def where(qq):
        x, y = centres(model, qq)
        return np.array(payload.position(p, x, y, qq[2:]))

    jp = np.column_stack([(where(q + 1e-7 * e) - where(q - 1e-7 * e)) / 2e-7 for e in np.eye(q.size)])
    centre = p.slice_mass * np.einsum("jai,i->a", centre_jacobian(model, q), qdd) + p.payload_mass * jp @ qdd
    weight = p.payload_mass * p.nominal_acceleration
    assert np.max(np.abs(centre)) < 1e-7 * weight
    assert np.max(np.abs(qdd[2:])) > 1.0  # the sail bends around the stem


def test_both_solvers_agree_with_a_payload():
    p = SailParameters(
        n=9,
        youngs_modulus=4.5e12,
        payload_mass=2e-3,
        payload_stem=0.4,
        payload_inertia=1e-6,
        billow_radius=2.0,
        beam_waist=1.0,
    )
    settings = RunSettings(t_final=0.02, output_interval=1e-3, stop_at_failure=False)
    reduced = solve(p, "reduced", settings, rtol=1e-10, method="DOP853")
    exudyn = solve(p, "exudyn", settings, step_size=2e-5)
    assert reduced.error is None and exudyn.error is None
    bare = solve(p.replace(payload_mass=0.0, payload_stem=0.0, payload_inertia=0.0), "reduced", settings)
    moved = np.max(np.abs(reduced.theta - reduced.theta[0]))
    assert np.max(np.abs(bare.theta - reduced.theta)) > 0.1 * moved  # the payload's weight folds the sail
    assert np.max(np.abs(exudyn.theta - reduced.theta)) < 1e-5 * moved  # measured 1.0e-6 (2.9e-7 at h = 1e-5 s)
    assert math.isfinite(float(exudyn.y[-1, 0]))
