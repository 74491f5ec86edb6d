"""Beam riding of the rigid curved sail: the force through the centre of curvature, the closed-form
criterion against the discrete body's linearisation, and both against nonlinear rigid-body runs."""

import math

import numpy as np
import pytest

from lightsail_mbs import ParameterError, SailParameters
from lightsail_mbs.analysis import beam_riding as br
from lightsail_mbs.model import optics


def case(radius=2.0, waist=1.0, n=30, **changes):
    return SailParameters(model="rigid", n=n, defect_amplitude=0.0, beam_waist=waist, billow_radius=radius, **changes)


def sail_mass(p):
    return p.slice_mass * p.n


@pytest.mark.parametrize("radius", [2.0, -1.5])
def test_mirror_force_passes_through_the_centre_of_curvature(radius):
    rng = np.random.default_rng(1)
    p = case(radius, waist=0.6, beam_centre=0.35)
    sail = br.RigidSail(p, 1e-3, 4.0)
    gx, gy = sail.centre_of_mass
    for _ in range(5):
        X, phi = rng.uniform(0.0, 1.0), rng.uniform(-0.4, 0.4)
        fx, fy, moment = sail.loads(X, phi)
        c, s = math.cos(phi), math.sin(phi)
        cx, cy = 0.5 - gx, -radius - gy  # C from G in the initial pose, turned with the body
        about_c = moment - ((c * cx - s * cy) * fy - (s * cx + c * cy) * fx)
        assert abs(about_c) < 1e-14 * math.hypot(fx, fy) * p.length


def test_an_absorbing_sail_has_a_moment_about_c():
    """The reduction needs forces along the normals: absorption pushes along the beam, off the radius."""
    p = case(2.0, waist=0.6, reflectivity=0.5, absorptivity=0.5)
    sail = br.RigidSail(p, 1e-3, 4.0)
    gx, gy = sail.centre_of_mass
    fx, fy, moment = sail.loads(0.3, 0.2)
    cx, cy = 0.5 - gx, -2.0 - gy
    c, s = math.cos(0.2), math.sin(0.2)
    assert abs(moment - ((c * cx - s * cy) * fy - (s * cx + c * cy) * fx)) > 1e-3 * math.hypot(fx, fy)


@pytest.mark.parametrize("radius, waist", [(2.0, 1.0), (1.0, 0.5), (4.0, 2.0), (-1.5, 1.0)])
def test_closed_form_equals_the_discrete_body(radius, waist):
    """The exact-arc closed form against central differences of the n = 90 chain locked rigid."""
    p = case(radius, waist, n=90)
    mp = sail_mass(p)
    for d in (0.5 * abs(radius), 1.7 * abs(radius), 4 * abs(radius)):
        cf = br.criterion(p, mp, d)
        lin = br.linearised(br.RigidSail(p, mp, d))
        assert lin.S == pytest.approx(cf.S, rel=2e-4)
        assert lin.P == pytest.approx(cf.P, rel=2e-4, abs=1e-3 * cf.S**2)
        assert np.max(np.abs(lin.residual)) < 1e-12 * abs(cf.S)  # symmetric: an equilibrium on the axis
        # the stiffness per unit mass and inertia, entry by entry
        K = np.array(
            [
                [cf.k / cf.mass, (cf.k * cf.D + cf.edge_force) / cf.mass],
                [cf.k * cf.D / cf.inertia, (cf.k * cf.D**2 + cf.D * (cf.edge_force - cf.axial_force)) / cf.inertia],
            ]
        )
        np.testing.assert_allclose(lin.K, K, rtol=2e-4, atol=1e-4 * np.abs(K).max())


def test_static_boundary_is_the_centre_of_mass_on_the_centre_of_curvature():
    p = case(2.0, 1.0)
    mp = 0.5 * sail_mass(p)
    d_star = br.criterion(p, mp, 1.0).static_boundary
    psi = p.length / 4.0
    y_s = -2.0 + 2.0 * math.sin(psi) / psi
    assert d_star == pytest.approx(2.0 * (1 + sail_mass(p) / mp) + sail_mass(p) / mp * y_s, rel=1e-14)
    assert br.criterion(p, mp, d_star).D == pytest.approx(0.0, abs=1e-12)
    assert not br.criterion(p, mp, 0.99 * d_star).stable and br.criterion(p, mp, 0.99 * d_star).P < 0
    assert br.criterion(p, mp, 1.01 * d_star).P > 0


def test_boundaries_and_the_flutter_band():
    """A wide beam (w = L): stable just above d*, flutter in a band, stable again for long stems; a narrow beam
    (w = L/2): no flutter band."""
    mp = sail_mass(case())
    wide = br.boundaries(case(2.0, 1.0), mp, 0.5, 200.0)
    assert [kind for _, kind, _ in wide] == ["static", "flutter", "flutter"]
    assert [stable for *_, stable in wide] == [True, False, True]
    (d_star, *_), (f1, *_), (f2, *_) = wide
    assert d_star < f1 < f2
    narrow = br.boundaries(case(2.0, 0.5), mp, 0.5, 200.0)
    assert [kind for _, kind, _ in narrow] == ["static"]
    # the boundaries scale with R (all lengths of the criterion do, at fixed L/R only approximately)
    assert br.boundaries(case(4.0, 1.0), mp, 0.5, 400.0)[0][0] == pytest.approx(2 * d_star, rel=2e-2)


@pytest.mark.parametrize("radius", [math.inf, -2.0])
def test_flat_and_convex_sails_never_ride(radius):
    p = SailParameters(model="rigid", n=30, defect_amplitude=0.0, beam_waist=1.0, billow_radius=radius)
    for d in (-3.0, 0.0, 0.5, 2.0, 5.0, 20.0, 100.0):
        lin = br.linearised(br.RigidSail(p, sail_mass(p), d))
        assert not lin.stable and lin.growth_rate > 0
    if math.isinf(radius):
        with pytest.raises(ParameterError, match="billow_radius"):
            br.criterion(p, 1e-3, 1.0)


@pytest.mark.parametrize(
    "d, kind",
    [(3.0, "static"), (8.0, "flutter")],  # below d* = 3.98 m; inside the flutter band 4.40 … 13.17 m
)
def test_unstable_runs_grow_at_the_linear_rate(d, kind):
    p = case(2.0, 1.0)
    sail = br.RigidSail(p, sail_mass(p), d)
    lin = br.linearised(sail)
    cf = br.criterion(p, sail_mass(p), d)
    assert (cf.P < 0) == (kind == "static") and (cf.discriminant < 0) == (kind == "flutter")
    run = br.ride(sail, 30.0, offset=1e-6)
    assert run.verdict == "drifts out"
    assert run.growth_rate(start=1.0) == pytest.approx(lin.growth_rate, rel=0.05)
    assert lin.growth_rate == pytest.approx(cf.growth_rate, rel=5e-3)


@pytest.mark.parametrize("d", [4.2, 20.0])
def test_stable_runs_ride_with_a_bounded_oscillation(d):
    p = case(2.0, 1.0)
    sail = br.RigidSail(p, sail_mass(p), d)
    assert br.criterion(p, sail_mass(p), d).stable
    run = br.ride(sail, 30.0, offset=1e-3, tilt=1e-3)
    assert run.verdict == "rides" and run.decided_at is None
    assert run.envelope_growth() < 1.2 and np.max(np.abs(run.lateral)) < 0.05
    # it oscillates about the axis at the linear frequencies: the run's spectrum peaks at one of them
    omega = np.sqrt(br.linearised(sail).eigenvalues.real)
    spectrum = np.abs(np.fft.rfft(run.lateral - run.lateral.mean()))
    peak = 2 * np.pi * np.fft.rfftfreq(run.time.size, run.time[1] - run.time[0])[np.argmax(spectrum)]
    assert np.min(np.abs(omega - peak)) < 2 * np.pi / 30.0  # one frequency bin


def test_tumbling_ends_the_run_at_the_edge_of_the_table():
    """A flat sail with a mirror table bounded at ±30°, in a Gaussian beam it may drift far out of: it turns out
    of the table before it leaves."""
    theta = optics.node_grid(math.radians(30), math.radians(1))
    table = optics.OpticalTable.from_samples(theta, 2 * np.cos(theta) ** 2, 0 * theta, metadata={"kind": "test"})
    p = SailParameters(model="rigid", n=20, defect_amplitude=0.0, beam_waist=1.0)
    run = br.ride(br.RigidSail(p, sail_mass(p), -2.0, table=table), 60.0, tilt=0.05, drift_factor=100)
    assert run.verdict == "tumbles" and run.decided_at < 60.0
    assert math.radians(20) < abs(run.tilt[-1]) <= math.radians(30)


def test_inputs_are_validated():
    p = case()
    with pytest.raises(ParameterError, match="payload_mass"):
        br.RigidSail(p, -1.0, 1.0)
    with pytest.raises(ParameterError, match="mirrored"):
        br.RigidSail(p, 1e-3, 1.0, mirrored=np.zeros(3, bool))
    with pytest.raises(ParameterError, match="t_final"):
        br.ride(br.RigidSail(p, 1e-3, 1.0), 0.0)


# ---- the flexible sail ---------------------------------------------------------------------------------
def flexible_case(**changes):
    base = dict(n=10, youngs_modulus=1e19, billow_radius=2.0, billow_rest=True, beam_waist=0.5, beam_centre=0.49)
    base.update(defect_amplitude=0.0, payload_mass=1e-3, payload_stem=6.0, stiffness_damping=1e-4)
    return SailParameters(**{**base, **changes})


def test_flexible_ride_reads_a_rigid_motion_exactly():
    """Slices moved rigidly (turned by φ(t) about a point and shifted by X(t)): the tilt is φ, the deformation
    zero, the lateral position the shift of the craft's centre of mass (payload included); a shape change is
    read as deformation and the verdicts follow their thresholds."""
    from lightsail_mbs import Result, RunSettings
    from lightsail_mbs.model import payload, shapes

    p = flexible_case()
    s0 = shapes.initial_state(p)
    t = np.linspace(0, 1, 11)
    phi, shift = 0.03 * np.sin(3 * t), 0.02 * t
    c, s = np.cos(phi)[:, None], np.sin(phi)[:, None]
    x = c * (s0.x - 0.5) - s * s0.y + 0.5 + shift[:, None]
    y = s * (s0.x - 0.5) + c * s0.y
    theta = s0.theta[None, :] + phi[:, None]
    zero = np.zeros_like(x)
    r = Result.from_trajectory(p, "synthetic", t, x, y, theta, zero, zero, zero, settings=RunSettings(t_final=1.0))
    f = br.flexible_ride(r)
    np.testing.assert_allclose(f.tilt, phi, atol=1e-13)
    assert f.deformation.max() < 1e-13 and f.verdict == "rides"
    m, mp = p.slice_mass, p.payload_mass
    xp, _ = payload.position(p, x, y, theta)
    expected = (m * x.sum(axis=1) + mp * xp) / (m * p.n + mp) - p.beam_centre
    np.testing.assert_allclose(f.lateral, expected, atol=1e-15)
    assert abs(f.lateral[0] - 0.01) < 2e-3  # the payload under the middle: the craft starts 1 cm off the axis
    bent = y.copy()
    bent[6:, 0] += 0.02  # the first slice lifted by 2 cm from t = 0.6 s
    f = br.flexible_ride(
        Result.from_trajectory(p, "synthetic", t, x, bent, theta, zero, zero, zero, settings=RunSettings(t_final=1.0))
    )
    assert f.verdict == "crumples" and f.decided_at == pytest.approx(0.6)


def test_a_sail_made_curved_rests_unlit():
    """Springs at rest on the billowed arc: unlit, the curved sail stays as it is in both solvers; with the
    springs at rest flat it springs back."""
    from lightsail_mbs import RunSettings, solve

    settings = RunSettings(t_final=0.01, output_interval=1e-3, stop_at_failure=False)
    p = flexible_case(intensity=0.0, payload_mass=0.0, payload_stem=0.0, youngs_modulus=1e15)
    for solver in ("reduced", "exudyn"):
        r = solve(p, solver, settings)
        assert np.max(np.abs(r.theta - r.theta[0])) < 1e-12
    flat = solve(p.replace(billow_rest=False), "reduced", settings)
    assert np.max(np.abs(flat.theta - flat.theta[0])) > 1e-4


@pytest.mark.parametrize("t_final", [0.2, pytest.param(1.0, marks=pytest.mark.slow)])
def test_both_solvers_agree_on_a_flexible_riding_run(t_final):
    """The riding sail of scenarios/flexible_beam_riding.py: lateral position and tilt within 1e-3 relative
    (measured at 1 s: 1e-7 and 2e-6 with Exudyn at h = 5e-5 s)."""
    from lightsail_mbs import RunSettings, solve

    settings = RunSettings(t_final=t_final, output_interval=0.01, stop_at_failure=False)
    a = br.flexible_ride(solve(flexible_case(), "reduced", settings, rtol=1e-10))
    b = br.flexible_ride(solve(flexible_case(), "exudyn", settings, step_size=1e-4))
    assert a.verdict == b.verdict == "rides"
    for name in ("lateral", "tilt"):
        u, v = getattr(a, name)[-1], getattr(b, name)[-1]
        assert abs(u - v) <= 1e-3 * abs(u), name


def test_a_tilted_start_turns_the_craft_about_its_centre_of_mass():
    """initial_tilt turns the shape and the stem rigidly about the craft's centre of mass; flexible_ride reports
    the tilt from the untilted pose; the two solvers start from the same tilted state and agree on it."""
    from lightsail_mbs import RunSettings, solve
    from lightsail_mbs.model import payload, shapes

    flat, tilted = flexible_case(), flexible_case(initial_tilt=0.05)
    a, b = shapes.initial_state(flat), shapes.initial_state(tilted)
    np.testing.assert_allclose(b.theta - a.theta, 0.05, atol=1e-15)
    m, mp = flat.slice_mass, flat.payload_mass

    def centre(p, st):
        px, py = payload.position(p, st.x, st.y, st.theta)
        return (m * st.x.sum() + mp * px) / (m * p.n + mp), (m * st.y.sum() + mp * py) / (m * p.n + mp)

    np.testing.assert_allclose(centre(tilted, b), centre(flat, a), atol=1e-14)
    (ax, ay), (bx, by) = payload.position(flat, a.x, a.y, a.theta), payload.position(tilted, b.x, b.y, b.theta)
    gx, gy = centre(flat, a)
    assert math.atan2(by - gy, bx - gx) - math.atan2(ay - gy, ax - gx) == pytest.approx(0.05, abs=1e-12)
    settings = RunSettings(t_final=0.05, output_interval=0.01, stop_at_failure=False)
    r = br.flexible_ride(solve(tilted, "reduced", settings, rtol=1e-10))
    e = br.flexible_ride(solve(tilted, "exudyn", settings, step_size=1e-4))
    assert r.tilt[0] == pytest.approx(0.05, abs=1e-12)
    for name in ("lateral", "tilt"):
        u, v = getattr(r, name)[-1], getattr(e, name)[-1]
        assert abs(u - v) < 1e-3 * abs(u), name  # measured: tilt 5e-5 (Exudyn's h = 1e-4 s damps the first wobble)
