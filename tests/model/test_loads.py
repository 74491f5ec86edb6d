"""The radiation load: Eq. (11), its optics and beam-profile generalisations."""

import numpy as np
import pytest

from lightsail_mbs import ParameterError, RunSettings, SailParameters, paper_case, solve
from lightsail_mbs.model.loads import (
    frame_force,
    gaussian_intensity,
    intensity,
    net_slice_force,
    net_slice_forces,
    radiation_forces,
)

C = 299_792_458.0
rng = np.random.default_rng(7)


def test_flat_sail_is_balanced_by_frame_force():
    p = SailParameters(n=20)
    fx, fy = net_slice_forces(p, np.linspace(0, 1, 20), np.zeros(20))
    assert not fx.any()
    np.testing.assert_allclose(fy, 0.0, atol=1e-18 * p.flat_force)


OPTICS = {
    "mirror": SailParameters(n=12, intensity=1e9),
    "facet": SailParameters(n=12, intensity=1e9, reflectivity=0.6, absorptivity=0.3),
    "gaussian": SailParameters(n=12, intensity=1e9, beam_waist=0.4, beam_centre=0.3),
    "gaussian-facet": SailParameters(n=12, intensity=1e9, beam_waist=0.5, reflectivity=0.7, absorptivity=0.2),
}


@pytest.mark.parametrize("name", OPTICS)
def test_net_force_is_radiation_plus_frame_force(name):
    """The net force (cancellation done analytically) equals radiation_forces + frame_force at finite
    angles, where the naive sum loses nothing that matters."""
    p = OPTICS[name]
    th = rng.uniform(-0.6, 0.6, p.n)
    x = np.sort(rng.uniform(0, 1, p.n))
    fx, fy = net_slice_forces(p, x, th)
    rx, ry = radiation_forces(p, x, th)
    np.testing.assert_allclose(fx, rx, rtol=1e-13, atol=1e-16 * p.flat_force)
    np.testing.assert_allclose(fy, ry + frame_force(p), rtol=0, atol=1e-14 * p.flat_force)
    assert frame_force(p) == pytest.approx(-p.slice_mass * p.nominal_acceleration, rel=1e-14)


@pytest.mark.parametrize("theta", [1e-3, 1e-5, 1e-8])
def test_net_force_keeps_its_digits_at_small_slopes(theta):
    """Mirror in a uniform beam: f_y = −f₀(1 − cos³θ) = −f₀(3θ²/2 − 7θ⁴/8 + …) to a few ulps, where the
    naive sum f₀cos³θ − m g₀ keeps about 16 + 2 log₁₀θ digits (none at θ = 1e-8)."""
    p = SailParameters(n=10)
    fx, fy = net_slice_forces(p, np.array([0.5]), np.array([theta]))
    series = -p.flat_force * (1.5 * theta**2 - 0.875 * theta**4)
    assert fy[0] == pytest.approx(series, rel=4e-16 + theta**6)
    assert fx[0] == pytest.approx(-p.flat_force * np.cos(theta) ** 2 * np.sin(theta), rel=1e-15)
    naive = radiation_forces(p, np.array([0.5]), np.array([theta]))[1][0] + frame_force(p)
    assert abs(naive - series) > 1e3 * abs(fy[0] - series) or theta > 1e-4


def test_net_force_of_a_facet_at_small_slopes():
    """R/α facet: f_y = −(IA/c)[2R(1 − cos³θ) + α(1 − cos θ)] ≈ −(IA/c)(3R + α/2)θ² to relative θ²."""
    p = OPTICS["facet"]
    theta = 1e-7
    fy = net_slice_forces(p, np.array([0.5]), np.array([theta]))[1][0]
    push = p.intensity * p.slice_length * p.width / C
    assert fy == pytest.approx(-push * (3 * p.reflectivity + 0.5 * p.absorptivity) * theta**2, rel=1e-12)


@pytest.mark.parametrize("name", OPTICS)
def test_compiled_net_force_equals_the_load_model(name):
    """loads.net_slice_force (compiled, called by both solvers) is net_slice_forces slice by slice."""
    p = OPTICS[name]
    th = np.concatenate([rng.uniform(-0.6, 0.6, p.n - 2), [1e-9, -3e-7]])
    x = rng.uniform(0, 1, p.n)
    fx, fy = net_slice_forces(p, x, th)
    area_c = p.slice_length * p.width / C
    for i in range(p.n):
        local = gaussian_intensity(x[i], p.intensity, p.beam_centre, p.beam_waist)
        cx, cy = net_slice_force(
            th[i], np.cos(th[i]), np.sin(th[i]), local, p.mean_intensity, area_c, p.reflectivity, p.absorptivity
        )
        assert cx == pytest.approx(fx[i], rel=1e-15, abs=1e-300)
        assert cy == pytest.approx(fy[i], rel=1e-14, abs=1e-15 * p.flat_force * abs(th[i]) ** 2)


def test_eq11_perfect_reflector():
    p = SailParameters(n=10, intensity=1e9, width=2.0)
    th = rng.uniform(-0.5, 0.5, 10)
    fx, fy = radiation_forces(p, np.zeros(10), th)
    f0 = 2 * 1e9 / C * 0.1 * 2.0
    np.testing.assert_allclose(fx, -f0 * np.cos(th) ** 2 * np.sin(th), rtol=1e-14)
    np.testing.assert_allclose(fy, f0 * np.cos(th) ** 3, rtol=1e-14)


def test_general_optics_path_reduces_to_eq11():
    """R = 1, α = 0 through the general formula (forced by a huge waist) equals Eq. (11)."""
    p = SailParameters(n=10)
    wide = p.replace(beam_waist=1e12)
    th = rng.uniform(-0.5, 0.5, 10)
    x = rng.uniform(0, 1, 10)
    for a, b in zip(radiation_forces(p, x, th), radiation_forces(wide, x, th)):
        np.testing.assert_allclose(b, a, rtol=1e-12)


def test_absorbing_facet_by_hand():
    """A facet at 30° with R = 0.6, α = 0.3: hand-computed components."""
    p = SailParameters(n=4, intensity=1e9, reflectivity=0.6, absorptivity=0.3)
    th = np.deg2rad(30.0)
    fx, fy = radiation_forces(p, np.array([0.5]), np.array([th]))
    area = 0.25 * 1.0
    power = 1e9 * area * np.cos(th)  # intercepted power
    normal_push = 2 * 0.6 * power / C * np.cos(th)  # specular: 2R (P/c) cos θ along n
    absorbed = 0.3 * power / C  # absorbed: α P/c along the beam
    n = np.array([-np.sin(th), np.cos(th)])
    assert fx[0] == pytest.approx(normal_push * n[0], rel=1e-13)
    assert fy[0] == pytest.approx(normal_push * n[1] + absorbed, rel=1e-13)
    # the tangential component (along the slice) comes from absorption only
    t = np.array([np.cos(th), np.sin(th)])
    assert np.dot([fx[0], fy[0]], t) == pytest.approx(absorbed * np.sin(th), rel=1e-12)


def test_frame_force_follows_optics():
    p = SailParameters(reflectivity=0.5, absorptivity=0.5)
    fx, fy = net_slice_forces(p, np.linspace(0, 1, 30), np.zeros(30))
    np.testing.assert_allclose(fy, 0.0, atol=1e-15 * p.flat_force)


def test_gaussian_profile_and_mean():
    p = SailParameters(beam_waist=0.4, beam_centre=0.3)
    x = np.linspace(0, 1, 200001)
    i = intensity(p, x)
    assert i.max() == pytest.approx(p.intensity, rel=1e-9)
    assert intensity(p, np.array([0.3 + 0.4]))[0] == pytest.approx(p.intensity * np.exp(-2))
    assert p.mean_intensity == pytest.approx(np.trapezoid(i, x), rel=1e-9)


def test_wide_gaussian_is_uniform():
    p = SailParameters()
    assert p.replace(beam_waist=1e7).nominal_acceleration == pytest.approx(p.nominal_acceleration, rel=1e-12)


def test_off_centre_beam_torque_sign():
    """Beam centred right of the middle pushes the right half harder: counter-clockwise torque."""
    p = SailParameters(n=40, beam_waist=0.5, beam_centre=0.7)
    x = (np.arange(40) + 0.5) / 40
    fx, fy = net_slice_forces(p, x, np.zeros(40))
    torque = np.sum((x - x.mean()) * fy)
    assert torque > 0
    assert np.sum(net_slice_forces(p.replace(beam_centre=0.3), x, np.zeros(40))[1] * (x - x.mean())) < 0


@pytest.mark.parametrize(
    "changes, name",
    [
        (dict(reflectivity=1.2), "reflectivity"),
        (dict(reflectivity=0.8, absorptivity=0.3), "absorptivity"),
        (dict(beam_waist=0.0), "beam_waist"),
        (dict(beam_centre=float("nan")), "beam_centre"),
        (dict(reflectivity=0.0, absorptivity=0.0), "reflectivity"),
    ],
)
def test_bad_optics(changes, name):
    with pytest.raises(ParameterError, match=name):
        SailParameters(**changes)


def _relative_difference(a, b):
    return np.abs(a.theta - b.theta).max() / np.abs(b.theta).max()


@pytest.mark.parametrize("solver", ["reduced", "exudyn"])
def test_wide_gaussian_run_reproduces_uniform_run(solver):
    """w = 1e8 L: 1 − I/I₀ < 1e-16 on the sail; the runs agree to 1e-9 relative (the 50 ms
    stable run keeps Exudyn's round-off sensitivity, ~1e-7 after 0.3 s of the soft sail, below that)."""
    p, settings = paper_case("torsion-stable"), RunSettings(t_final=0.05)
    assert (
        _relative_difference(
            solve(p.replace(beam_waist=1e8), solver, settings, uncertainty=False),
            solve(p, solver, settings, uncertainty=False),
        )
        <= 1e-9
    )


def test_gaussian_beam_effect_falls_as_inverse_waist_squared():
    """The curvature of I(x) near its axis, 4I₀/w², drives the deviation from the uniform run: ×10 in w,
    ÷100 in the difference (the soft sail over 0.3 s, where it is largest)."""
    p, settings = paper_case("torsion-soft"), RunSettings(t_final=0.3)
    uniform = solve(p, "reduced", settings, rtol=1e-12, uncertainty=False)
    d = [
        _relative_difference(
            solve(p.replace(beam_waist=w), "reduced", settings, rtol=1e-12, uncertainty=False), uniform
        )
        for w in (1e4, 1e5, 1e6)
    ]
    assert 90 < d[0] / d[1] < 110 and 90 < d[1] / d[2] < 110


@pytest.mark.parametrize("solver", ["reduced", "exudyn"])
def test_off_centre_beam_turns_the_sail_counter_clockwise(solver):
    """Beam axis right of the middle: the right half is pushed harder, the flat sail turns θ > 0."""
    p = paper_case("torsion-stable", defect_amplitude=0.0, beam_waist=0.5, beam_centre=0.7)
    settings = RunSettings(t_final=0.05)
    r = solve(p, solver, settings, uncertainty=False)
    assert r.omega[-1].mean() > 0 and r.theta[-1].mean() > 0
    assert solve(p.replace(beam_centre=0.3), solver, settings, uncertainty=False).theta[-1].mean() < 0
