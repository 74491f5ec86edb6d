"""The journey with an optical table that has a wavelength axis: a table flat in λ gives the journey of the
single table; one whose c_n(0) and absorptance change with λ gives the trajectory of du/dt = c_n(λ'(β)) P D/(M c²)
(integrated here independently), the acceleration and the temperature of the table at each snapshot's λ'; a
laser whose sail-frame wavelengths leave the table's range is one line."""

import math

import numpy as np
import pytest

from lightsail_mbs import ParameterError, SailParameters
from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.model import materials, relativity, thermal
from lightsail_mbs.model.optics import OpticalTable, SpectralTable
from lightsail_mbs.studies.journey import Journey, JourneySettings, run_journey

LASER = 1.064e-6
GRID = (1.0e-6, 1.4e-6)  # covers λ' from rest to β = 0.2: 1.064 … 1.303 µm
SETTINGS = JourneySettings(power=4e10, carried_mass=1e-3)


@pytest.fixture(autouse=True)
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("LIGHTSAIL_MBS_CACHE", str(tmp_path / "cache"))


def table(normal: float, absorptance: float, lossless: bool) -> OpticalTable:
    """A grating-like table on ±30°: c_n = c_n(0) cos²θ, c_t = 0.05 cos θ sin θ, 1 − R − T = absorptance."""
    theta = np.linspace(-math.radians(30), math.radians(30), 13)
    c, s = np.cos(theta), np.sin(theta)
    extra = {"A_TE": np.full(theta.size, absorptance), "R_TE": np.full(theta.size, 0.5), "T_TE": 0.5 - absorptance}
    extra["T_TE"] = np.full(theta.size, extra["T_TE"])
    meta = {"kind": "grating", "lossless": lossless}
    return OpticalTable.from_samples(theta, normal * c * c, 0.05 * c * s, (), "TE", meta, extra)


def case(optics: str) -> SailParameters:
    """The framed silicon-nitride strip of tests/studies/test_journey.py with an optical table."""
    fields = {"material": "silicon-nitride", "model": "tnt", "n": 20, "length": 3.6, "width": 3.6}
    fields.update(thickness=2.5e-8, tension=100.0, defect_amplitude=1e-3, optics=optics)
    return SailParameters(**materials.fill(fields))


def test_a_table_flat_in_wavelength_gives_the_single_tables_journey(tmp_path):
    one = table(1.7, 0.0, lossless=True)
    single = one.save(tmp_path / "single.npz")
    flat = SpectralTable(np.array(GRID), (one, one), LASER).save(tmp_path / "flat.npz")
    a = run_journey(case(str(single)), SETTINGS)
    b = run_journey(case(str(flat)), SETTINGS)
    assert not a["optics"]["wavelength_axis"] and b["optics"]["wavelength_axis"]
    assert a["verdict"] == b["verdict"]
    for ra, rb in zip(a["snapshots"], b["snapshots"], strict=True):
        assert (
            rb["normal_momentum"] == pytest.approx(1.7, rel=1e-15)
            and rb["absorptance"] == materials.get("silicon-nitride").absorptance.value
        )
        for key, value in ra.items():
            # the quadrature of the trajectory against its closed form; every other column to the bit
            assert rb[key] == (value if isinstance(value, str) else pytest.approx(value, rel=1e-11, abs=0)), key


def trajectory_by_ode(normal_of_wavelength, mass: float, power: float, target: float):
    """t and τ at β = target from du/dt = c_n(λ'(β)) P D(β)/(M c²), dτ/dt = 1/γ (u = γβ), by scipy's DOP853."""
    from scipy.integrate import solve_ivp

    def rhs(t, y):
        beta = y[0] / math.sqrt(1 + y[0] ** 2)
        lam = LASER * math.sqrt((1 + beta) / (1 - beta))
        return [
            normal_of_wavelength(lam) * power * (1 - beta) / ((1 + beta) * mass * SPEED_OF_LIGHT**2),
            1 / math.sqrt(1 + y[0] ** 2),
        ]

    def reached(t, y):
        return y[0] / math.sqrt(1 + y[0] ** 2) - target

    reached.terminal = True
    sol = solve_ivp(rhs, (0, 1e5), [0.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-16, events=reached)
    return float(sol.t_events[0][0]), float(sol.y_events[0][0][1])


def test_a_wavelength_dependent_table_changes_what_it_should(tmp_path):
    """c_n(0) falls from 1.9 at 1.0 µm to 1.5 at 1.4 µm and the absorptance rises from 1e-5 to 3e-5: each
    snapshot's acceleration and temperature are those of the table at its λ' (linear in λ), and the time to
    0.2c is the ODE's."""
    spectrum = SpectralTable(np.array(GRID), (table(1.9, 1e-5, False), table(1.5, 3e-5, False)), LASER)
    path = spectrum.save(tmp_path / "spectrum.npz")
    p = case(str(path))
    report = run_journey(p, SETTINGS)
    mass = Journey(p, SETTINGS).mass
    sin = materials.get("silicon-nitride")

    def linear(lam, a, b):
        return a + (b - a) * (lam - GRID[0]) / (GRID[1] - GRID[0])

    for row in report["snapshots"]:
        lam = LASER * float(relativity.wavelength_factor(row["beta"]))
        assert row["wavelength"] == pytest.approx(lam, rel=1e-15)
        normal = linear(lam, 1.9, 1.5)
        g0 = normal * SETTINGS.power * float(relativity.intensity_factor(row["beta"])) / (mass * SPEED_OF_LIGHT)
        assert row["acceleration"] == pytest.approx(g0, rel=1e-12)
        absorbed = linear(lam, 1e-5, 3e-5) * row["intensity_sail"]
        T = float(thermal.equilibrium_temperature(absorbed, sin.emissivity))
        assert row["temperature_max"] == pytest.approx(T, rel=1e-12)
    t, tau = trajectory_by_ode(lambda lam: linear(lam, 1.9, 1.5), mass, SETTINGS.power, 0.2)
    last = report["snapshots"][-1]
    assert last["t"] == pytest.approx(t, rel=1e-9) and last["tau"] == pytest.approx(tau, rel=1e-9)
    # against the flat table at the laser's wavelength (c_n(0) = 1.836): the lower c_n(λ') takes longer
    flat = relativity.Trajectory(SETTINGS.power, mass, linear(LASER, 1.9, 1.5))
    assert 1.0 < last["t"] / float(flat.time(0.2)) < 1.836 / 1.5
    assert "sail-frame wavelength" in report["optics"]["text"]


def test_a_laser_whose_sail_frame_wavelengths_leave_the_table_is_one_line(tmp_path):
    one = table(1.7, 0.0, lossless=True)
    path = SpectralTable(np.array(GRID), (one, one), 1.2e-6).save(tmp_path / "s.npz")
    settings = JourneySettings(power=4e10, carried_mass=1e-3, wavelength=1.2e-6)  # 1.2 … 1.47 µm at 0.2c
    with pytest.raises(ParameterError, match=r"wavelength=1\.2e-06 is invalid: .*s\.npz, 1e-06 … 1\.4e-06 m"):
        Journey(case(str(path)), settings)


def test_the_command_says_where_it_read_the_table(tmp_path, capsys):
    import csv

    from lightsail_mbs.cli import main

    spectrum = SpectralTable(np.array(GRID), (table(1.9, 1e-5, False), table(1.5, 3e-5, False)), LASER)
    path = spectrum.save(tmp_path / "spectrum.npz")
    args = ["journey", "--model", "tnt", "--material", "silicon-nitride", "--length", 3.6, "--width", 3.6]
    args += ["--thickness", 2.5e-8, "--tension", 100, "--defect-amplitude", 1e-3, "--power", 4e10, "--optics", path]
    assert main([str(a) for a in [*args, "--carried-mass", 1e-3, "--out", tmp_path / "out", "--quiet"]]) == 0
    assert "optics: the optical table" in capsys.readouterr().out
    with open(tmp_path / "out" / "journey.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    assert float(rows[0]["normal_momentum"]) == pytest.approx(1.836, rel=1e-12)
    assert float(rows[-1]["absorptance"]) > float(rows[0]["absorptance"])
