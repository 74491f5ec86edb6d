"""FlexSailSim's metagrating pressures on the sheet (lightsail_mbs.paper.flexsail_grating): the committed fit is
their tables' (when the files are at hand), our RCWA of their bars reproduces it and fixes the sign of the tilt,
the pizza's layout pushes outward with the film's mean normal pressure, and a short grating run of both solvers
agrees."""

import math
import os
from pathlib import Path

import numpy as np
import pytest

from lightsail_mbs.model import sheet_grating
from lightsail_mbs.paper import flexsail, flexsail_grating

TABLES = Path(os.environ.get("FLEXSAILSIM_TABLES", "/nonexistent"))  # a folder holding their two .mat files


@pytest.mark.skipif(not (TABLES / Path(flexsail_grating.TABLES.format("TE")).name).exists(), reason="no tables")
def test_the_committed_laws_are_their_tables_fit():
    """COEFFICIENTS (±3°, quadratic) and WIDE (±6°, degree 8, the exact direction cosines) are their tables' fits:
    the refit's coefficients (quadratic) or values over the window (WIDE: to 1e-6 I/c), and their largest
    residuals against the tables' rows within their windows are the ones stated: ≤ 0.0055 and ≤ 0.0018 I/c."""
    fitted = flexsail_grating.fit(TABLES)
    for region, laws in flexsail_grating.COEFFICIENTS.items():
        np.testing.assert_allclose(np.array(fitted[region]), np.array(laws), atol=6e-5)
    window, degree = flexsail_grating.WIDE_WINDOW, flexsail_grating.WIDE_DEGREE
    wide = flexsail_grating.fit(TABLES, window, degree, exact=True)
    for region, laws in flexsail_grating.WIDE.items():
        for (reading, w, d, table), bound in (
            ((False, 3.0, 2, flexsail_grating.COEFFICIENTS), 0.0055),
            ((True, window, degree, flexsail_grating.WIDE), 0.0018),
        ):
            u1, u2, *pressures = flexsail_grating.table_rows(TABLES, region, w, reading)
            basis = sheet_grating.monomials(u1, u2, d)
            for law, pressure in zip(table[region], pressures):
                assert np.abs(basis @ np.array(law) - pressure).max() <= bound
        u1, u2, *_ = flexsail_grating.table_rows(TABLES, region, window, True)
        basis = sheet_grating.monomials(u1, u2, degree)
        for law, refit in zip(laws, wide[region]):
            np.testing.assert_allclose(basis @ np.array(law), basis @ np.array(refit), rtol=0, atol=1e-6)


def test_our_rcwa_of_their_bars_reproduces_their_pressures_and_the_tilts_sign():
    """At normal incidence our RCWA is their published (0°, 0°) rows to 2e-3; across ±2° and at ±5° (the TM
    region near its resonance at 6.5-7.5°) it is the ±6° law (WIDE, with TILT_SIGN) to 0.015 (measured: 0.013 at
    TE +5°), and 0.03 or more
    away from that law read with the other sign; the ±3° quadratic carried to ±5° is 0.04 or more off the TM law."""
    rows = flexsail_grating.rcwa_rows(angles=(-5, -2, 0, 2, 5))
    laws = flexsail_grating.region_laws(wide=True)
    quadratic = flexsail_grating.region_laws()
    for row in rows:
        columns = [row[f"{what}: our RCWA / their tables / the ±3° fit (I/c)"] for what in ("in-plane", "normal")]
        ours, theirs, fit3 = (np.array([float(c.split(" / ")[i]) for c in columns]) for i in range(3))
        if row["θ (°)"] == 0:
            assert np.allclose(ours, theirs, atol=2e-3)
            continue
        assert np.allclose(ours, theirs, atol=0.015)
        u = math.sin(math.radians(row["θ (°)"]))
        other = [flexsail_grating.law_at(law, -u) for law in laws[row["region"]]]
        assert max(abs(a - b) for a, b in zip(ours, other)) > 0.03
        assert np.allclose(fit3, [flexsail_grating.law_at(law, u) for law in quadratic[row["region"]]], atol=1e-4)
        if row["region"] == "TM" and abs(row["θ (°)"]) == 5:
            assert np.abs(fit3 - theirs).max() > 0.04


def test_the_films_normal_law_is_its_cos_theta():
    """film_law: c̄ (1 − u₁² − u₂²)^½ to degree 2 and 8, against the closed form over |u| ≤ sin 6°: the
    remainder of the binomial series, ≤ c̄ r^(d+2) (r² = u₁² + u₂²)."""
    rng = np.random.default_rng(3)
    u = rng.uniform(-1, 1, (200, 2)) * math.sin(math.radians(6.0))
    r2 = (u**2).sum(axis=1)
    for degree in (2, 8):
        law = flexsail_grating.film_law(0.4, degree)
        values = sheet_grating.monomials(u[:, 0], u[:, 1], degree) @ law
        error = np.abs(values - 0.4 * np.sqrt(1 - r2))
        assert np.all(error <= 0.4 * r2 ** (degree / 2 + 1) + 1e-15)  # and the rounding of c̄
        assert error.max() > 0.4 * 1e-3 * np.max(r2) ** (degree / 2 + 1)  # the remainder is there, not rounding


def test_the_pizza_pushes_outward_with_the_films_mean_thrust(tmp_path):
    """Each sector's grating vector points along its middle (outward); the sectors' normal pressures at normal
    incidence, weighted by their areas (TE 1/3), are the film's c̄_n to 1e-3; each sector's total normal
    pressure is its table's."""
    mean = flexsail.film()["normal_pressure"]
    path = flexsail_grating.layout(tmp_path, "tables", mean)
    sectors = sheet_grating.read(path)
    excess = 0.0
    for (start, end, direction, (along, across, normal)), (*_, region) in zip(sectors, flexsail_grating.SECTORS):
        assert direction == 0.5 * (start + end)
        assert along[0] > 0.1 and not any(across)
        excess += (end - start) / 360 * normal[0]
        assert math.isclose(normal[0] + mean, flexsail_grating.COEFFICIENTS[region][1][0])
    assert abs(excess) < 1e-3 * mean
    p = flexsail.case(grating=path)
    assert p.grating == path
    wide = sheet_grating.read(flexsail_grating.layout(tmp_path, "wide", mean))
    film = flexsail_grating.film_law(mean, flexsail_grating.WIDE_DEGREE)
    for (*_, (along, across, normal)), (*_, region) in zip(wide, flexsail_grating.SECTORS):
        assert not any(across)
        laws = flexsail_grating.region_laws(wide=True)[region]
        np.testing.assert_allclose(np.array(normal) + film, laws[1], rtol=1e-12, atol=1e-12)
        np.testing.assert_array_equal(along, laws[0])


def test_a_short_grating_run_of_both_solvers_agrees(tmp_path):
    spec = {k: v[:4] + (0.005,) + v[5:] for k, v in flexsail_grating.RUNS.items()}
    a = flexsail.run("17 tiles, grating", tmp_path, spec["17 tiles, grating"], lambda line: None)
    b = flexsail.run("17 tiles, grating, Exudyn", tmp_path, spec["17 tiles, grating, Exudyn"], lambda line: None)
    plain = flexsail.run(
        "17 tiles", tmp_path, flexsail.RUNS["17 tiles"][:4] + (0.005, {"rtol": 1e-4}), lambda line: None
    )
    assert a["verdict"] == b["verdict"] == "rides"
    c = flexsail.compare(a, b, 0.005)
    assert c["lateral"][1] < 1e-5 and c["tilt"][1] < 1e-3
    changed = np.abs(a["lateral"][-1] - plain["lateral"][-1]).max()
    assert changed > 100 * c["lateral"][0]  # the grating's change is far above the solvers' difference
