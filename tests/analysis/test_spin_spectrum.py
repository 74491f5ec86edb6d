"""The spinning sheet's linearisation in its turning frame (solvers.reduced.sheet_rotating through
analysis.spin_spectrum): it reduces to the resting linearisation without spin, a spinning free membrane disc
has Lamb & Southwell's transverse frequencies, and the spectrum's growth rate is the time-domain run's."""

import numpy as np
import pytest

from lightsail_mbs import RunSettings, SailParameters, solve
from lightsail_mbs.analysis import sheet_spectrum, spin_spectrum
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import failure, sheet, sheet_spin
from lightsail_mbs.solvers.reduced.sheet import SheetModel

SOFT = dict(model="sheet", planform="rectangle", n=6, ny=6, youngs_modulus=4.5e9, defect_mode_y=1.5)


def test_without_spin_the_turning_frame_is_the_resting_linearisation():
    p = SailParameters(**SOFT)
    rest = sheet_spectrum.linearisation(p)
    turning = spin_spectrum.rotating_linearisation(p)
    assert abs(rest - turning).max() < 1e-8 * abs(rest).max()
    with pytest.raises(ParameterError, match="boundary"):
        spin_spectrum.rotating_linearisation(p.replace(boundary="clamped"))


@pytest.mark.parametrize("n", [0, 1, 2, 3])
def test_the_closed_form_solves_the_spinning_membrane_equation(n):
    """W = Σ a_j x^(n+2j) from the recursion with membrane_disc_frequency's ω/Ω ends at x^(n+2s) and solves
    (3 + ν)[(1 − x²)W'' + (1/x − 3x)W' − n²W/x²] + (1 + 3ν)n²W + 8(ω/Ω)²W = 0 (model.sheet_spin's docstring)."""
    nu, s = 0.25, 2
    k = sheet_spin.membrane_disc_frequency(n, s, nu) ** 2
    a = [1.0]
    for j in range(s):
        m = n + 2 * j
        a.append(
            a[-1] * ((3 + nu) * (m * m + 2 * m) - (1 + 3 * nu) * n * n - 8 * k) / ((3 + nu) * ((m + 2) ** 2 - n * n))
        )
    W = np.polynomial.Polynomial(np.concatenate([[0.0] * n, *[[c, 0.0] for c in a]]))
    x = np.linspace(0.1, 1.0, 7)
    d1, d2 = W.deriv(1)(x), W.deriv(2)(x)
    residual = (3 + nu) * ((1 - x**2) * d2 + (1 / x - 3 * x) * d1 - n * n * W(x) / x**2) + (
        (1 + 3 * nu) * n * n + 8 * k
    ) * W(x)
    assert np.abs(residual).max() < 1e-10 * np.abs(W(x)).max()
    assert sheet_spin.membrane_disc_frequency(1, 0) == pytest.approx(1.0)  # the rigid tilt turns at Ω


def test_a_spinning_membrane_disc_has_lamb_and_southwells_frequencies():
    """A free disc of 49 tiles (bending ~1e-8 of the centrifugal stiffness) at Ω = 100 rad/s: the transverse
    modes below 3.2 Ω in its turning frame are those of the closed form, each within 7 % (validation/
    spin_spectrum.py refines the mesh to 0.5 %), the rigid tilt at Ω to 1e-6; none grows faster than 2e-3 Ω."""
    p = SailParameters(model="sheet", planform="disc", n=9, ny=12, intensity=0.0, defect_amplitude=0.0)
    modes = spin_spectrum.transverse_modes(p.replace(youngs_modulus=1e9, spin_rate=100.0), 320.0)
    found = {(m.diameters, m.circles): m for m in modes}
    assert set(found) >= {(0, 0), (1, 0), (2, 0), (0, 1), (3, 0), (1, 1), (4, 0)}
    for (n, s), mode in found.items():
        exact = sheet_spin.membrane_disc_frequency(n, s)
        assert mode.frequency / 100.0 == pytest.approx(exact, rel=0.07, abs=1e-9)
        assert mode.growth_rate < 2e-3 * 100.0
    assert found[(1, 0)].frequency == pytest.approx(100.0, rel=1e-6)


@pytest.mark.slow
@pytest.mark.parametrize("solver, options", [("reduced", {}), ("exudyn", {"step_size": 1e-3})])
def test_the_spectrum_gives_the_growth_rate_of_a_spinning_curved_sheet(solver, options):
    """The paper's soft sail (6 × 6 tiles, a₀ = 10 µm) spun at 10 rad/s, unlit, in the exact spun equilibrium of
    its curved shape (initial_equilibrium: some tiles compressed): the fastest Re λ of the turning-frame
    spectrum (a mode mostly of the tiles' tilts) is the growth rate of each solver's amplitude departure
    within 2 %; without spin the same sail does not grow."""
    p = SailParameters(**SOFT, intensity=0.0, initial_equilibrium=True).replace(spin_rate=10.0)
    spectrum = spin_spectrum.rotating_spectrum(p)
    run = solve(p, solver, RunSettings(t_final=1.0, output_interval=0.02), uncertainty=False, **options)
    departure = np.abs(failure.plane_amplitude(run.tile_centres) - failure.plane_amplitude(run.tile_centres[0]))
    late = np.asarray(run.time) >= 0.5
    measured = np.polyfit(np.asarray(run.time)[late], np.log(departure[late]), 1)[0]
    assert run.error is None and spectrum.growth_rate > 1.0 and spectrum.tilt_share > 0.5
    assert measured == pytest.approx(spectrum.growth_rate, rel=0.02)
    assert spin_spectrum.rotating_spectrum(p.replace(spin_rate=0.0)).growth_rate < 1e-6


@pytest.mark.parametrize("n", [5, 6, 8])
def test_a_curved_spinning_sheet_in_the_flat_sheets_stress_has_no_tilt_instability(n):
    """The soft sail (a₀ = 10 µm, doubly sinusoidal) spun at 10 rad/s, unlit: with the flat sheet's centrifugal
    stress (the default) every tile is in tension and no deformation grows (faster than 1e-6 Ω); in the
    exact spun equilibrium of its curved shape (initial_equilibrium) the stress is redistributed so that
    some tiles are compressed, and a mode of the tiles' tilts grows at over Ω (model.sheet_spin)."""
    p = SailParameters(**dict(SOFT, n=n, ny=n), intensity=0.0).replace(spin_rate=10.0)
    centres, quaternions = sheet.initial_quaternions(p)
    for exact in (False, True):
        q = p.replace(initial_equilibrium=exact)
        least = sheet_spin.tile_membrane_forces(q, sheet.connectors(q), centres, quaternions)[:, 0].min()
        spectrum = spin_spectrum.rotating_spectrum(q)
        if exact:
            assert least < 0.0 and spectrum.growth_rate > p.spin_rate and spectrum.tilt_share > 0.5
        else:
            assert least > 0.0 and spectrum.growth_rate < 1e-6 * p.spin_rate


def test_the_critical_spin_brackets_the_last_crossing_of_the_threshold(monkeypatch):
    """A growth rate that falls below the threshold at 0.5 rad/s, rises above it again between 1.0 and
    1.3 rad/s and stays below after: the bracket holds 1.3 rad/s, at most `width` wide; a rate stable from
    the lowest spin gives (0, low), one unstable at the highest (high, inf)."""
    threshold = np.log(2.0) / spin_spectrum.RUN_LENGTH
    bumps = {"rate": lambda w: threshold * (2.0 - 2.0 * w if w < 1.0 else (1.5 if w < 1.3 else 0.5))}

    class Fake:
        def __init__(self, spin):
            self.growth_rate = bumps["rate"](spin)

    monkeypatch.setattr(spin_spectrum, "rotating_spectrum", lambda q: Fake(q.spin_rate))
    p = SailParameters(**SOFT)
    below, above = spin_spectrum.critical_spin(p, (0.1, 10.0), steps=20, width=1.01)
    assert below < 1.3 <= above and above / below <= 1.01
    bumps["rate"] = lambda w: 0.5 * threshold
    assert spin_spectrum.critical_spin(p, (0.1, 10.0)) == (0.0, 0.1)
    bumps["rate"] = lambda w: threshold
    assert spin_spectrum.critical_spin(p, (0.1, 10.0)) == (10.0, np.inf)
    with pytest.raises(ParameterError, match="spins"):
        spin_spectrum.critical_spin(p, (1.0, 0.5))


STEM_CAP = dict(billow_radius=1.0, billow_rest=True, payload_mass=7.85e-4, payload_stem=2.0, intensity=1e8)


def test_a_payload_is_one_more_body_of_the_turning_frames_linearisation():
    """The disc on its cap with a stem payload: without spin the turning frame's L is the resting one (the payload
    its 14th body, after the 13 tiles); the deformation spectrum is the complement of the craft's six rigid motions."""
    p = SailParameters(model="sheet", planform="disc", n=5, ny=6, **STEM_CAP)
    rest = sheet_spectrum.linearisation(p)
    turning = spin_spectrum.rotating_linearisation(p)
    assert turning.shape == (12 * 14, 12 * 14)
    assert abs(rest - turning).max() < 1e-8 * abs(rest).max()
    spectrum = spin_spectrum.rotating_spectrum(p.replace(spin_rate=40.0))
    assert spectrum.eigenvalues.size == 2 * (6 * 14 - 6)


def test_taut_tethers_linearise_and_slack_ones_are_refused():
    """Six tethers: lit, they start taut (pre-stretched by the payload's share m_p g₀) and couple the payload to
    their rim tiles in L; unlit they carry nothing (ℓ = ℓ₀, the law's kink) and the linearisation is refused."""
    p = SailParameters(model="sheet", planform="disc", n=5, ny=6, **STEM_CAP, payload_tethers=6, tether_stiffness=1e3)
    L = spin_spectrum.rotating_linearisation(p.replace(spin_rate=40.0)).tocsr()
    payload = 13  # body index: after the 13 tiles
    rows = L[6 * 14 + 6 * payload : 6 * 14 + 6 * payload + 3, : 6 * 14].toarray().reshape(3, 14, 6)
    coupled = np.nonzero(np.abs(rows).sum(axis=(0, 2)))[0]
    model_tiles = set(SheetModel(p).tethers[0].tolist())
    assert set(coupled) == model_tiles | {payload}
    with pytest.raises(ParameterError, match="payload_tethers"):
        spin_spectrum.rotating_linearisation(p.replace(intensity=0.0, spin_rate=40.0))


def test_the_kinetic_metric_holds_the_crafts_own_mass_and_inertia():
    """The spin map's craft (a polar disc of 25 tiles of different masses and inertia tensors, a stem payload):
    in spin_spectrum's metric the craft's rigid translations carry its mass M_s + m_p (M_s = ρh πL²/4) and its
    spin about the axis the criterion's axial inertia ρh ∫ r² dA on the cap, to the tiles' discretisation (1 %)."""
    from lightsail_mbs.analysis.ride3d_criterion import cap_criterion
    from lightsail_mbs.paper import spinning_maps as maps

    p = maps.BASE.replace(payload_stem=2.0)
    _, centres, quaternions, _ = spin_spectrum._start(p)
    half, inverse = spin_spectrum.mass_metric(p)
    z = half @ sheet_spectrum.rigid_motions(centres, quaternions)  # the spin column turns about the axis
    gram = z.T @ z
    criterion = cap_criterion(p, maps.SAIL_MASS, 2.0)
    np.testing.assert_allclose(np.diag(gram)[:3], criterion.mass, rtol=1e-12)
    assert gram[5, 5] == pytest.approx(criterion.axial_inertia, rel=0.015)
    assert abs(inverse @ half - np.eye(half.shape[0])).max() < 1e-12


@pytest.mark.slow
def test_rigid_modes_of_the_lit_spinning_cap_are_the_rigid_criterions():
    """The spin map's craft (d = 1.15 d*) at 40 rad/s about its lit spun equilibrium, where the cap keeps its
    sphere: eight of the twelve rigid modes are the criterion's roots s seen from the turning frame (s − iΩ and
    their conjugates) within 0.5 % (validation/spin_spectrum_rigid.md: 0.33 %); the other four (the axial
    translation and the spin, null for a rigid craft) stay below 0.02 Ω: the spin's ±0.63/s is the relaxation's
    spin deficit (the craft turns 5e-3 rad/s slower than the frame), not the craft's."""
    from scipy.optimize import linear_sum_assignment

    from lightsail_mbs.analysis.ride3d_criterion import cap_criterion
    from lightsail_mbs.paper import spinning_maps as maps

    p = maps.BASE.replace(billow_radius=1.0, spin_rate=40.0)
    d = 1.15 * maps.d_star(p)
    p = p.replace(payload_stem=d)
    values = spin_spectrum.rigid_modes(p, state=spin_spectrum.lit_state(p))
    roots = cap_criterion(p, maps.SAIL_MASS, d).roots - 40.0j
    target = np.r_[roots, np.conj(roots)]
    rows, cols = linear_sum_assignment(np.abs(values[:, None] - target[None, :]))
    np.testing.assert_allclose(values[rows], target[cols], rtol=5e-3)
    assert np.abs(np.delete(values, rows)).max() < 0.02 * 40.0
