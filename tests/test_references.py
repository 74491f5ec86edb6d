"""The regression net: every headline number of the docs recomputed and held to its dated reference
(tests/references.py: value, tolerance from its measured uncertainty, date, command), and the docs checked to
print each one as it is.

The short runs (well under a second each) are in the default suite; the longer ones (Exudyn over 6 s of
the stable torsion sail and of the extensible membrane, the membrane's trends, the Monte Carlo table) and
every row of the committed Fig. 9 and Fig. 12 maps are marked slow.
"""

import csv
import functools
import math
import re
from pathlib import Path

import numpy as np
import pytest

import lightsail_mbs
from lightsail_mbs import RunSettings, SailParameters, paper_case, paper_settings
from lightsail_mbs.analysis import finite_amplitude as fa
from lightsail_mbs.analysis import linear_stability
from lightsail_mbs.analysis.frequencies import angle_frequency
from lightsail_mbs.model import theory
from tests.references import REFERENCES, Boundary, Value, assert_boundary, assert_held

ROOT = Path(__file__).resolve().parents[1]
# the references are the answers of single runs; their error bars are measured as references.py says
solve = functools.partial(lightsail_mbs.solve, uncertainty=False)
SIX_SECONDS = RunSettings(t_final=6.0)
MEMBRANE = paper_case("tnt-stable", axial_springs=False)  # the membrane as the pipelines run it
SOFT_MEMBRANE = MEMBRANE.replace(tension=3.34e-8)


def six_second_failure(p: SailParameters) -> bool:
    r = solve(p, "reduced", SIX_SECONDS)
    assert r.error is None, r.error
    return r.failed


# ---- the docs print what the references hold -------------------------------------------------------
def quotes():
    for name, ref in REFERENCES.items():
        for quote in ref.docs:
            yield pytest.param(name, quote, id=f"{name}-{quote.file}")


@pytest.mark.parametrize("name, quote", list(quotes()))
def test_docs_print_the_reference(name, quote):
    """The quoted text is in the file, and the number it prints is the reference rounded as printed (for a
    boundary: within the bracket the printed number is the middle of)."""
    assert quote.text in (ROOT / quote.file).read_text(), f"{quote.file} no longer says {quote.text!r}"
    ref = REFERENCES[name]
    printed = [float(x) for x in quote.printed.split(",")]
    if isinstance(ref, Boundary):
        middle = math.sqrt(ref.failed * ref.stable)
        assert all(abs(math.log(x / middle)) <= 0.5 * math.log(quote.bracket) + 1e-3 for x in printed)
        return
    digits = [len(x.strip().split(".")[1]) if "." in x else 0 for x in quote.printed.split(",")]
    values = np.atleast_1d(ref.value) * quote.scale
    if len(printed) == 1 and values.size > 1:
        values = values[:1]
    for shown, decimals, value in zip(printed, digits, values):
        half_unit = 0.5 * 10.0**-decimals
        assert abs(shown - value) <= half_unit + ref.tolerance * quote.scale + 1e-12, (name, shown, value)


def test_every_reference_is_dated_and_explained():
    for name, ref in REFERENCES.items():
        assert re.fullmatch(r"\d{4}-\d{2}-\d{2}", ref.measured), name
        assert ref.command and ref.uncertainty, name
        if isinstance(ref, Value) and ref.unit == "runs":
            assert ref.tolerance == 0.5, name  # counts of runs are held exactly
        elif isinstance(ref, Value):
            assert 0 < ref.tolerance < 0.01 * np.abs(np.atleast_1d(ref.value)).min(), name  # no wide windows
        else:
            assert 1 < ref.stable / ref.failed < 1.02, name


# ---- Figs 6–7: the torsion sail ---------------------------------------------------------------------
def test_soft_torsion_failure_time_reduced():
    assert_held(
        "soft_torsion_failure_time_reduced",
        solve(paper_case("torsion-soft"), "reduced", paper_settings("torsion-soft")).failure_time,
    )


def test_soft_torsion_failure_time_exudyn():
    assert_held(
        "soft_torsion_failure_time_exudyn",
        solve(paper_case("torsion-soft"), "exudyn", paper_settings("torsion-soft")).failure_time,
    )


@pytest.mark.parametrize("solver", ["reduced", "exudyn"])
def test_soft_torsion_reported_failure_time(solver):
    """The answer `simulate` prints: the base run's, as a sweep gets it, with its error bar."""
    reported = lightsail_mbs.solve(paper_case("torsion-soft"), solver, paper_settings("torsion-soft"))
    assert reported.uncertainty["reported"] == "base"
    assert_held(f"soft_torsion_failure_time_{solver}", reported.failure_time)


def test_stable_torsion_frequency_and_amplitude():
    r = solve(paper_case("torsion-stable"), "reduced", paper_settings("torsion-stable"))
    assert r.error is None and not r.failed
    assert_held("stable_torsion_frequency", angle_frequency(r))
    assert_held("stable_torsion_max_amplitude_ratio", r.max_amplitude_ratio)


@pytest.mark.slow
def test_stable_torsion_frequency_and_amplitude_exudyn():
    r = solve(paper_case("torsion-stable"), "exudyn", paper_settings("torsion-stable"))
    assert_held("stable_torsion_frequency", angle_frequency(r))
    assert_held("stable_torsion_max_amplitude_ratio", r.max_amplitude_ratio)


def test_torsion_free_free_frequencies():
    spectrum = linear_stability.linear_spectrum(linear_stability.unlit(paper_case("torsion-stable")), "reduced")
    w2 = np.sort(spectrum.omega_squared)
    elastic = w2[w2 > 1e-9 * w2.max()]
    assert_held("torsion_free_free_frequencies", np.sqrt(elastic[:3]) / (2 * np.pi))


# ---- Fig. 5: the rigid sail -------------------------------------------------------------------------
def test_rigid_failure_time_reduced():
    r = solve(paper_case("rigid", defect_mode=1.5), "reduced", paper_settings("rigid"))
    assert_held("rigid_nu_1_5_failure_time_reduced", r.failure_time)


def test_rigid_failure_time_exudyn():
    r = solve(paper_case("rigid", defect_mode=1.5), "exudyn", paper_settings("rigid"))
    assert_held("rigid_nu_1_5_failure_time_exudyn", r.failure_time)


def test_rigid_failure_times_of_every_mode():
    modes = [1.0 + 0.5 * k for k in range(9)]
    times = [
        solve(paper_case("rigid", defect_mode=nu), "reduced", paper_settings("rigid")).failure_time for nu in modes
    ]
    assert_held("rigid_failure_times_reduced", times)


# ---- Figs 10–11 and 21–23: the membrane -------------------------------------------------------------
def test_membrane_stable_frequency_and_soft_failure():
    stable = solve(MEMBRANE, "reduced", SIX_SECONDS)
    assert stable.error is None and not stable.failed
    assert_held("membrane_stable_frequency", angle_frequency(stable))
    assert_held("membrane_soft_failure_time", solve(SOFT_MEMBRANE, "reduced", SIX_SECONDS).failure_time)


@pytest.mark.parametrize(
    "name, changes",
    [
        ("membrane_failure_time_nu_1", dict(defect_mode=1.0)),
        ("membrane_failure_time_nu_2", dict(defect_mode=2.0)),
        ("membrane_failure_time_h_0_01um", dict(thickness=1e-8)),
        ("membrane_failure_time_h_0_1um", dict(thickness=1e-7)),
    ],
)
def test_membrane_failure_times(name, changes):
    assert_held(name, solve(SOFT_MEMBRANE.replace(**changes), "reduced", SIX_SECONDS).failure_time)


def test_extensible_membrane_failure_time_reduced():
    held_run = solve(paper_case("tnt-soft"), "reduced", paper_settings("tnt-soft"))
    assert_held("membrane_extensible_soft_failure_time_reduced", held_run.failure_time)


@pytest.mark.slow
def test_extensible_membrane_failure_time_exudyn():
    held_run = solve(paper_case("tnt-soft"), "exudyn", paper_settings("tnt-soft"))
    assert_held("membrane_extensible_soft_failure_time_exudyn", held_run.failure_time)


# ---- the critical ratios and the maps' boundaries ----------------------------------------------------
def test_torsion_critical_ratio():
    p = paper_case("torsion-stable")
    assert_boundary("torsion_critical_ratio", lambda r: fa.failure_tau(fa.with_ratio(p, r), 8.0) is not None)


def test_membrane_critical_ratio():
    assert_boundary("membrane_critical_ratio", lambda r: fa.failure_tau(fa.with_ratio(MEMBRANE, r), 8.0) is not None)


def test_fig9_boundary_at_1um():
    p = SailParameters(model="torsion", defect_mode=1.5, n=30, thickness=1e-6)
    assert_boundary("fig9_boundary_1um", lambda r: six_second_failure(fa.with_ratio(p, r)))


def test_fig9_boundary_at_3_16um():
    p = SailParameters(model="torsion", defect_mode=1.5, n=30, thickness=10**-5.5)
    assert_boundary("fig9_boundary_3_16um", lambda r: six_second_failure(fa.with_ratio(p, r)))


@pytest.mark.parametrize("name, mode", [("fig12_boundary_1um_nu_1_5", 1.5), ("fig12_boundary_1um_nu_1", 1.0)])
def test_fig12_boundaries_at_1um(name, mode):
    p = MEMBRANE.replace(n=30, thickness=1e-6, defect_mode=mode)
    assert_boundary(name, lambda r: six_second_failure(fa.with_ratio(p, r)))


def test_fig12_boundary_at_1um_mode_2():
    p = MEMBRANE.replace(n=30, thickness=1e-6, defect_mode=2.0)
    assert_boundary("fig12_boundary_1um_nu_2", lambda r: six_second_failure(fa.with_ratio(p, r)))


def committed_map_rows():
    """Every converged 6 s row of the committed maps: (figure, base case, row)."""
    for figure, base in (
        ("fig9", SailParameters(model="torsion", defect_mode=1.5, n=30)),
        ("fig12", paper_case("tnt-stable", n=30, axial_springs=False)),
    ):
        with open(ROOT / "scenarios" / "figures" / f"{figure}_boundaries.csv", newline="") as handle:
            for row in csv.DictReader(handle):
                h, mode = float(row["thickness_m"]), float(row["mode"])
                yield pytest.param(figure, base, row, id=f"{figure}-h{h:.3g}-nu{mode:g}")


@pytest.mark.slow
@pytest.mark.parametrize("figure, base, row", list(committed_map_rows()))
def test_committed_map_rows_hold(figure, base, row):
    """Each bracket of the committed Fig. 9/12 maps (6 s runs): its failed end fails, its stable end
    survives; an unbracketed row's sail survives even with 1e-3 of the analytic stiffness."""
    p = base.replace(thickness=float(row["thickness_m"]), defect_mode=float(row["mode"]))
    field = "youngs_modulus" if figure == "fig9" else "tension"
    analytic = theory.critical_modulus_max(p) if figure == "fig9" else theory.critical_tension_max(p)
    assert float(row["analytic"]) == pytest.approx(analytic, rel=1e-12)
    if row["status"] == "unbracketed":
        assert not six_second_failure(p.replace(**{field: 1e-3 * analytic}))
        return
    assert six_second_failure(p.replace(**{field: float(row["unstable_value"])}))
    assert not six_second_failure(p.replace(**{field: float(row["stable_value"])}))


# ---- beyond the paper -----------------------------------------------------------------------------
def test_gaussian_beam_cups_the_sail():
    settings = RunSettings(t_final=0.01, output_interval=1e-5)
    assert_held(
        "gaussian_cupping_time_w_1m",
        solve(paper_case("torsion-stable", beam_waist=1.0), "reduced", settings).failure_time,
    )


def test_gaussian_beams_cup_the_sail_faster_the_narrower():
    settings = RunSettings(t_final=0.01, output_interval=1e-5)
    runs = [solve(paper_case("torsion-stable", beam_waist=w), "reduced", settings) for w in (2.0, 1.0, 0.5)]
    assert_held("gaussian_cupping_times", [r.failure_time for r in runs])


@pytest.mark.slow
def test_membrane_trends():
    """Figs 18–20: the stable membrane's frequency against T, h and ν; Fig. 23: the failure time against h."""

    def slope(xs, ys):
        return float(np.polyfit(np.log(xs), np.log(ys), 1)[0])

    def frequency(**changes):
        r = solve(MEMBRANE.replace(**changes), "reduced", SIX_SECONDS)
        assert r.error is None and not r.failed
        return angle_frequency(r)

    tensions, thicknesses, modes = [3.34e-5, 3.34e-4, 3.34e-3, 3.34e-2], [1e-8, 1e-7, 1e-6, 1e-5], [1.0, 1.5, 2.0]
    slopes = [
        slope(tensions, [frequency(tension=t) for t in tensions]),
        slope(thicknesses, [frequency(thickness=h) for h in thicknesses]),
        slope(modes, [frequency(defect_mode=nu) for nu in modes]),
    ]
    assert_held("membrane_frequency_exponents", slopes)
    times = [solve(SOFT_MEMBRANE.replace(thickness=h), "reduced", SIX_SECONDS).failure_time for h in thicknesses[:3]]
    assert_held("membrane_failure_time_thickness_exponent", slope(thicknesses[:3], times))


@pytest.mark.slow
def test_montecarlo_table(tmp_path):
    """The Monte Carlo table of the docs: 50 seeded multi-mode defects at each of four moduli."""
    from lightsail_mbs.studies import montecarlo

    base = SailParameters(model="torsion", defect_seed=0)
    rows = montecarlo.run(
        base, "youngs_modulus", [4.5e10, 4.5e11, 4.5e12, 4.5e13], 50, tmp_path, solver="reduced", progress=False
    )
    assert_held("montecarlo_failures", [r.failures for r in rows])
    assert_held("montecarlo_median_failure_times", [r.failure_time_median for r in rows[:3]])


def test_partial_reflector_fails_later():
    p = paper_case("torsion-soft", reflectivity=0.9, absorptivity=0.1)
    assert_held("partial_reflector_failure_time", solve(p, "reduced", SIX_SECONDS).failure_time)
