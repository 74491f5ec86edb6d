"""The turning-frame modal fit of a spinning sheet's run (analysis.turning_modes): the matrix pencil finds
the frequencies of sums of damped sinusoids, the ring harmonics keep each nodal-diameter count apart
whatever the sheet's in-plane turning, and Exudyn's run of a spinning membrane disc has the in-house
turning-frame spectrum's frequencies."""

import math

import numpy as np
import pytest

from lightsail_mbs import RunSettings, SailParameters, solve
from lightsail_mbs.analysis import spin_spectrum, turning_modes
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import planforms, sheet_spin

SPIN = 100.0
DISC = SailParameters(model="sheet", planform="disc", n=9, ny=12, intensity=0.0, defect_amplitude=0.0)


def test_the_matrix_pencil_finds_the_frequencies_and_growth_rates_of_damped_sinusoids():
    """Three channels of four damped sinusoids at Lamb & Southwell's (n, 0) frequencies (n = 1…4) with
    random amplitudes and phases: the poles' ω and Re λ to 1e-9 relative, with none left over."""
    rng = np.random.default_rng(3)
    omega = SPIN * np.array([sheet_spin.membrane_disc_frequency(n, 0) for n in range(1, 5)])
    sigma = -np.array([0.0, 0.1, 0.5, 1.0])
    t = np.arange(1200) * 4e-4
    amplitude = rng.uniform(0.2, 1.0, (3, 4))
    phase = rng.uniform(0, 2 * np.pi, (3, 4))
    y = np.einsum("cm,cmt->ct", amplitude, np.exp(sigma[:, None] * t) * np.cos(omega[:, None] * t + phase[..., None]))
    rates, weights = turning_modes.matrix_pencil(y, 4e-4, threshold=1e-10)
    upper = rates[rates.imag > 0]
    upper = upper[np.argsort(upper.imag)]
    assert rates.size == 8 and weights.min() > 0.1
    assert np.allclose(upper.imag, omega, rtol=1e-9, atol=0)
    assert np.allclose(upper.real, sigma, rtol=0, atol=1e-9 * SPIN)
    with pytest.raises(ParameterError, match="dt"):
        turning_modes.matrix_pencil(y, 0.0)


def test_ring_harmonics_keep_the_nodal_diameters_apart_in_a_turning_sheet():
    """Standing modes w = (r/R)^(n+2s) cos(n(θ − φ)) cos(ω t) of a 49-tile disc (ω from the closed form)
    whose tiles also turn at Ω in the plane, as in an inertial-frame run: each n's fit holds exactly its
    own modes' frequencies (to 1e-9), and nothing of another n."""
    mesh = planforms.mesh_of(DISC)
    rel = mesh.centres - mesh.centres.mean(axis=0)
    radius, theta = np.hypot(rel[:, 0], rel[:, 1]), np.arctan2(rel[:, 1], rel[:, 0])
    t = np.arange(1601) * 4e-4
    modes = ((1, 0, 0.3), (2, 0, 1.1), (0, 1, 0.0), (2, 1, 2.0), (3, 0, 0.7))
    w = sum(
        (radius / radius.max())[None] ** (n + 2 * s)
        * np.cos(n * (theta - phi))[None]
        * np.cos(SPIN * sheet_spin.membrane_disc_frequency(n, s) * t)[:, None]
        for n, s, phi in modes
    )
    turned = theta[None] + SPIN * t[:, None]
    centres = np.stack([radius * np.cos(turned) + 0.5, radius * np.sin(turned) + 0.5, w], axis=-1)
    found = turning_modes.measured_modes(DISC, t, centres, 3)
    for n in range(4):
        expected = sorted(SPIN * sheet_spin.membrane_disc_frequency(m, s) for m, s, _ in modes if m == n)
        strong = sorted(m.frequency for m in found if m.diameters == n and m.share > 1e-6)
        assert strong == pytest.approx(expected, rel=1e-9)
    other = np.abs(turning_modes.ring_harmonics(DISC, centres, 4)).max()
    assert other < 1e-12 * np.abs(turning_modes.ring_harmonics(DISC, centres, 2)).max()
    with pytest.raises(ParameterError, match="uniform"):
        turning_modes.measured_modes(DISC, t**2, centres, 4)


@pytest.mark.slow
def test_exudyns_spinning_membrane_disc_has_the_turning_frame_spectrums_frequencies():
    """The disc of 49 tiles (E = 1e9 Pa, Ω = 100 rad/s, unlit) from random tile offsets of 1 µm along ẑ,
    Exudyn in the inertial frame for 10 turns (h = 1e-4 s, ρ∞ = 1): every transverse mode below 3.2 Ω of
    the in-house turning-frame spectrum is a pole of the run's deflection within 5e-4 (validation/
    spin_exudyn_modes.md: ~1e-4, the fit's floor), none growing or decaying faster than 2e-3 Ω."""
    p = DISC.replace(youngs_modulus=1e9, spin_rate=SPIN)
    settings = RunSettings(t_final=0.64, output_interval=4e-4, stop_at_failure=False)
    options = dict(step_size=1e-4, spectral_radius=1.0, newton_rel_tol=1e-12, perturbation=1e-6)
    run = solve(p, "exudyn", settings, uncertainty=False, **options)
    found = turning_modes.measured_modes(p, run.time, run.tile_centres, 5, threshold=1e-8)
    reference = [m for m in spin_spectrum.transverse_modes(p, 3.2 * SPIN) if m.frequency > 0]
    assert run.error is None and len(reference) >= 8 and math.isclose(run.time[-1], 0.64)
    for mode in reference:
        near = min((m for m in found if m.diameters == mode.diameters), key=lambda m: abs(m.frequency - mode.frequency))
        assert near.frequency == pytest.approx(mode.frequency, rel=5e-4)
        assert abs(near.growth_rate) < 2e-3 * SPIN
