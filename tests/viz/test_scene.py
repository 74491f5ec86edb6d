"""What a frame shows (viz.scene): hinge curvature and moment, the exaggeration of the drawn deflection.

``run`` (tests/conftest.py) is a synthetic sine growing as e^t over 1 s (tests.helpers.growing_sine), so the
curvature at the hinges is known in closed form.
"""

import math

import numpy as np

from lightsail_mbs.viz.scene import Layout, auto_exaggeration, frame_exaggeration, hinge_values, make_style
from tests.helpers import growing_sine


def test_hinge_curvature_is_the_sines_second_derivative(run):
    """κ_j = Δθ_j / l ≈ w''(x_j) = −a k² sin(k x_j) at the hinges (small slopes, l ≪ wavelength)."""
    p = run.params
    k = 2 * np.pi * p.defect_mode / p.length
    x_hinge = np.arange(1, p.n) * p.slice_length
    for i in (0, -1):
        expected = -p.defect_amplitude * math.exp(run.time[i]) * k * k * np.sin(k * x_hinge)
        kappa = hinge_values(run, i, "curvature")
        assert np.max(np.abs(kappa - expected)) < 0.03 * np.max(np.abs(expected))
    moment = hinge_values(run, 0, "moment")
    np.testing.assert_allclose(moment, p.torsional_stiffness * p.slice_length * hinge_values(run, 0, "curvature"))


def test_auto_exaggeration_draws_initial_amplitude_at_5_percent_of_length(run):
    lay = Layout(800, 400)
    e = auto_exaggeration([run], [np.arange(run.time.size // 2)], lay)  # grows e^0.5: fits at 5 % of L
    drawn = e * run.amplitude[0] / run.params.length
    assert 0.045 < drawn <= 0.05  # rounded down to two significant digits
    long_run = growing_sine(rate=4.0)  # grows e^4 ≈ 55×: failure (×2) at t = ln 2 / 4
    every = np.arange(long_run.time.size)
    style = make_style([long_run], [every], lay)
    assert style.exaggeration == e  # up to failure the sail fits at 5 % of L
    peak = np.abs(long_run.y[-1]).max() / long_run.params.length
    e_last = frame_exaggeration(style, [(long_run, every[-1])])
    assert e_last < e and e_last * peak < lay.sail_half_height  # lowered after failure to stay in the band
    assert frame_exaggeration(style, [(long_run, 0)]) == e
    fixed = make_style([long_run], [every], lay, exaggeration=e)
    assert frame_exaggeration(fixed, [(long_run, every[-1])]) == e  # a given factor is never changed
