"""The heated film inside a run (model/heating.py, case field heated) against physics: the table the kernels read
against an independent evaluation of radiative equilibrium and the framed chain's tension law; a flat heated
chain in both solvers carries exactly the tension N(τ) = N₀ − E h W α_T ⟨ΔT(τ)⟩ of the moment and stays at rest;
and the two solvers agree on a heated, Doppler-shifted chain run to failure, with heat and Doppler both inside
the run."""

import numpy as np
import pytest

from lightsail_mbs import ParameterError, RunSettings, solve
from lightsail_mbs.model import expansion, heating, materials, relativity, theory, thermal
from lightsail_mbs.paper.journey import PARKIN_PAYLOAD, parkin_power, starshot_case
from lightsail_mbs.studies.journey import lab_peak_intensity

BETA = 0.15


def heated(n=10, **changes):
    """The Starshot-class chain (docs/journey.md) lit by Parkin's power from β = 0.15 with its carried payload,
    heated inside the run, its world line in the state."""
    p = starshot_case(n)
    fields = dict(intensity=lab_peak_intensity(p, parkin_power(p)), carried_mass=PARKIN_PAYLOAD, heated=True)
    return p.replace(**{**fields, "integrated_trajectory": True, "initial_beta": BETA, **changes})


def independent_tension(p, factor):
    """N₀ − E h W α_T ⟨ΔT⟩ of radiative equilibrium at I₀ D (uniform beam): model.thermal and model.expansion."""
    film = materials.get(p.material)
    temperature = thermal.equilibrium_temperature(film.absorptance.value * p.intensity * factor, film.emissivity)
    rise = float(temperature) - heating.REFERENCE_TEMPERATURE
    return p.tension - expansion.chain_tension_relief(p, film.thermal_expansion.value, rise), float(temperature)


def test_the_table_is_the_equilibrium_and_the_framed_tension():
    p = heated()
    table = heating.table(p)
    rng = np.random.default_rng(3)
    start = float(relativity.intensity_factor(BETA))
    factors = np.concatenate([[start], start * np.exp(-rng.uniform(0, 7, 20))])
    read = heating.at(table, p.n, factors)
    for factor, tension, mean in zip(factors, read["tension"], read["temperature_mean"]):
        expected, temperature = independent_tension(p, factor)
        assert mean == pytest.approx(temperature, rel=2e-7)  # linear in ln D between 2049 points
        assert tension == pytest.approx(expected, abs=2e-7 * p.tension)
    assert read["tension"][0] == pytest.approx(independent_tension(p, start)[0], rel=1e-12)
    with pytest.raises(ParameterError, match="heated=True is invalid: allowed off without a material"):
        heated(material=None)
    with pytest.raises(ParameterError, match="heat_absorptance=1e-05 is invalid: allowed None unless heated"):
        heated(heated=False, heat_absorptance=1e-5)


@pytest.mark.parametrize("solver", ["reduced", "exudyn"])
def test_a_flat_heated_chain_carries_the_tension_of_the_moment(solver):
    """No defect, uniform beam: the chain starts in its heated equilibrium and stays there (the frame's length,
    z = N₀/k_s per spring) while the tension follows N(D(τ)); the reduced solver's joint forces and Exudyn's
    generalized spring forces are N of the closed-form D(τ) at each moment, to 1e-9 of N₀."""
    p = heated(defect_amplitude=0.0, integrated_trajectory=False, tension=60.0)
    z = heating.initial_extension(p)
    np.testing.assert_allclose(z, p.tension / p.axial_stiffness, rtol=1e-12)
    rate = 2.0 * float(relativity.intensity_factor(BETA)) * p.trajectory_acceleration / 2.99792458e8
    table = heating.table(p)
    for time in (0.0, 10.0, 300.0):
        factor = float(relativity.intensity_factor(BETA)) / (1.0 + rate * time)
        expected = float(heating.at(table, p.n, [factor])["tension"][0])
        assert expected == pytest.approx(independent_tension(p, factor)[0], abs=2e-7 * p.tension)
        if solver == "reduced":
            from lightsail_mbs.solvers.reduced.dynamics import ChainDynamics
            from lightsail_mbs.solvers.reduced.kinematics import ChainModel

            model = ChainModel.from_params(p)
            q = model.pack(0.0, 0.0, np.zeros(p.n), z)
            dynamics = ChainDynamics(model)
            y = np.concatenate([q, np.zeros_like(q)])
            forces = dynamics.joint_forces(y, time)
            np.testing.assert_allclose(-forces[:, 0], expected, rtol=0, atol=1e-9 * p.tension)  # slice i pulls i+1 back
            assert np.abs(dynamics.rhs(time, y)[q.size :]).max() < 1e-9
        else:
            from lightsail_mbs.solvers.exudyn.tree import ChainLayout, generalized_force

            layout = ChainLayout.of(p)
            q = np.zeros(layout.size)
            q[layout.stretch_index] = z
            Q = generalized_force(p, layout)(q, None, time)
            # the spring's own pull −k_s z (joint P control) balances the user function's k_s z_th + N
            np.testing.assert_allclose(Q[layout.stretch_index], p.axial_stiffness * z, rtol=1e-9)


def test_both_solvers_agree_on_a_heated_doppler_shifted_chain_to_failure():
    """Pre-tensioned so that heating leaves half the critical tension at β = 0.15; heat and Doppler inside the run
    (the beam dims, the film cools and the tension rises with it). Both solvers fail within 1e-3 of each other
    (measured 5e-6 at the defaults)."""
    p = heated()
    start = float(relativity.intensity_factor(BETA))
    relieved = heating.at(heating.table(p), p.n, [start])["tension"][0]
    critical = expansion.critical(p, p.intensity * start)
    p = p.replace(tension=p.tension - relieved + 0.5 * critical)
    t_c = theory.time_scale(theory.at_start(p.replace(heated=False, tension=0.5 * critical)))
    settings = RunSettings(t_final=20.0 * t_c)
    times = {s: solve(p, s, settings, uncertainty=False).failure_time for s in ("reduced", "exudyn")}
    assert times["reduced"] is not None and times["exudyn"] == pytest.approx(times["reduced"], rel=1e-3)
