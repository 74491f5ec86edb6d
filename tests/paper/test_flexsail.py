"""FlexSailSim's published case as a sheet (lightsail_mbs.paper.flexsail): the case carries the published numbers,
its pose is FlexSailSim's rotation of the sail, the equivalent film has the metagrating's mass and thrust, the
rigid criterion's flat limit has converged, and a short run of both solvers agrees with each other and with the
rigid disc's motion, and is read back."""

import math

import numpy as np

from lightsail_mbs.model import sheet_pose
from lightsail_mbs.model.sheet_grid import quaternion_rotation
from lightsail_mbs.paper import flexsail


def test_the_case_carries_the_published_numbers():
    p = flexsail.case()
    assert p.planform == "disc" and p.length == p.width == 1.0  # D = 2 × 500 mm
    assert math.isclose(p.spin_rate, 2 * math.pi * 120)
    assert math.isclose(p.intensity, 1e9)  # 1000 W/mm²
    # FlexSailSim's I₀ exp(−r²/Irad²) with Irad = 0.4 √2 R is I₀ exp(−2r²/w²) with w = 0.4 D
    irad = 0.4 * math.sqrt(2) * 0.5
    r = np.linspace(0, 0.5, 7)
    assert np.allclose(np.exp(-(r**2) / irad**2), np.exp(-2 * r**2 / p.beam_waist**2))
    # the sail 0.1 R off the axis in +x and +y: the beam's axis at the middle less 50 mm in both
    assert math.isclose(p.beam_centre, 0.45) and math.isclose(p.beam_centre_y, 0.45)
    assert math.isclose(p.youngs_modulus, 270e9) and math.isclose(p.membrane_modulus, 270e9)
    assert math.isclose(p.density, 2700.0) and p.payload_mass == 0.0
    off = flexsail.case(bending=False)
    assert math.isclose(off.youngs_modulus / p.youngs_modulus, 1e-6) and off.membrane_modulus == p.membrane_modulus


def test_the_pose_is_flexsailsims_rotation_of_the_sail():
    """FlexSailSim turns a node x to Cᵀx with C its 1-2-3 direction cosine matrix of (ψ, θ, φ) = (0, −2°, −2°).
    The sheet composes its two tilts in the other order: the two rotations differ by θφ (1.2e-3 rad) about the
    normal, a spin phase of the round sail, and the normals agree to second order."""
    theta = phi = math.radians(-2.0)
    c = np.array(
        [
            [math.cos(theta), math.sin(theta) * math.sin(phi), -math.sin(theta) * math.cos(phi)],
            [0.0, math.cos(phi), math.sin(phi)],
            [math.sin(theta), -math.cos(theta) * math.sin(phi), math.cos(theta) * math.cos(phi)],
        ]
    )
    q = sheet_pose.tilt_quaternion(flexsail.case())
    ours = quaternion_rotation(q)
    normal, theirs = ours[:, 2], c.T[:, 2]
    assert np.allclose(ours, c.T, atol=1.5 * abs(theta * phi))  # the same tilts to first order
    assert math.acos(min(normal @ theirs, 1.0)) < 0.05 * abs(theta * phi)  # and the same normal to 2nd order
    difference = ours.T @ c.T
    axis = np.array([difference[2, 1] - difference[1, 2], difference[0, 2] - difference[2, 0], 0.0])
    assert abs(math.acos((np.trace(difference) - 1) / 2) - abs(theta * phi)) < 1e-3 * abs(theta * phi)
    assert abs(difference[1, 0] - difference[0, 1]) > 20 * np.linalg.norm(axis)  # about the normal


def test_the_equivalent_film_has_the_metagratings_mass_and_thrust():
    f = flexsail.film()
    # χ = ρ(t_s + h_r (w₁ + w₂)/Λ): TE 2700 (0.2 + 0.4 · 0.8/1.6) µm, TM 2700 (0.2 + 0.4 · 0.72/1.35) µm
    te, tm = 2700 * 0.4e-6, 2700 * (0.2e-6 + 0.4e-6 * 0.72 / 1.35)
    assert math.isclose(f["areal_density"], te / 3 + 2 * tm / 3)
    assert math.isclose(f["mass"], f["areal_density"] * math.pi / 4)
    assert 0.86e-3 < f["mass"] < 0.875e-3
    # the sheet's normal thrust at normal incidence, 2R + α, is the tables' area mean
    assert math.isclose(2 * f["reflectivity"] + f["absorptivity"], (0.71935 + 2 * 0.23503) / 3)
    p = flexsail.case()
    assert math.isclose(p.density * p.thickness, f["areal_density"])
    assert 9e-6 < p.absorptivity < 1e-5


def test_the_rigid_flat_limit_has_converged_and_drifts_out():
    rows = flexsail.rigid_prediction()
    for row in rows:
        coarse, fine = (float(v) for v in row["growth rate at R_c = 1e3 / 1e4 m (1/s)"].split(" / "))
        assert abs(coarse - fine) <= 1e-3 * fine
        assert row["prediction"] == "drifts out"
    assert float(rows[1]["e-folding time (s)"]) > float(rows[0]["e-folding time (s)"])  # spin slows it


def test_a_short_run_of_both_solvers_agrees_and_is_read_back(tmp_path):
    spec = {name: flexsail.RUNS[name][:4] + (0.005,) + flexsail.RUNS[name][5:] for name in flexsail.RUNS}
    lines = []
    a = flexsail.run("17 tiles", tmp_path, spec["17 tiles"], lines.append)
    b = flexsail.run("17 tiles, Exudyn", tmp_path, spec["17 tiles, Exudyn"], lines.append)
    assert a["verdict"] == b["verdict"] == "rides" and len(lines) == 4
    c = flexsail.compare(a, b, 0.005)
    assert c["samples"] == 3
    assert c["lateral"][1] < 1e-6 and c["tilt"][1] < 1e-4 and c["spin_rate"][0] < 1e-4
    # the sheet's first drift is the rigid disc's: its centre moves 0.16 mm in 5 ms, 17 tiles within 3 % of it
    lateral, _ = flexsail.rigid_path(a["lateral"][0], a["tilt"][0], a["time"][1:])
    moved = np.linalg.norm(a["lateral"][-1] - a["lateral"][0])
    assert moved > 1e-4 and np.linalg.norm(a["lateral"][-1] - lateral[-1]) < 0.03 * moved
    again = flexsail.run("17 tiles", tmp_path, spec["17 tiles"], lines.append)  # read back, not rerun
    assert len(lines) == 4 and np.array_equal(again["lateral"], a["lateral"]) and again["cpu"] == a["cpu"]
