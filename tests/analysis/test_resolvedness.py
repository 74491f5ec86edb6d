"""Resolvedness in n (analysis.resolvedness): a run whose fastest-growing wave sits at the grid scale is called
ill-posed in n and says so in one warning; bending or tension that cuts the short waves off makes a case well
posed; the verdict follows the continuum's cut-off wavelength λ* = 2π √(2EI/P) on seeded random cases either side
of it, and its compression estimate is the trough compression p a₀ W of the sine defect."""

import json
import math

import numpy as np
import pytest

from lightsail_mbs import RunSettings, SailParameters, paper_case, paper_settings, solve
from lightsail_mbs.analysis import resolvedness
from lightsail_mbs.cli import main
from lightsail_mbs.model import theory

STARSHOT = dict(
    model="torsion", length=3.2, width=3.2, thickness=100e-9, density=2200.0, youngs_modulus=70e9,
    intensity=1e10, defect_amplitude=1e-6,
)  # fmt: skip
STARSHOT_CLI = (
    "--model torsion --length 3.2 --width 3.2 --thickness 100e-9 --density 2200 --modulus 70e9 --intensity 1e10 "
    "--defect-amplitude 1e-6 --solver reduced --n 30"
).split()


def cutoff_slices(p: SailParameters) -> float:
    """λ*/l of the torsion sail's sine defect in the continuum: compression p a₀ W in the trough, bending EI, so
    λ* = 2π √(2EI/(p a₀ W)) = L √(E/E_cr,max)/ν (Eq. 8)."""
    return p.n * math.sqrt(p.youngs_modulus / theory.critical_modulus_max(p)) / p.defect_mode


def test_dominant_wavelength_of_a_zigzag_and_of_a_sine():
    n = 40
    assert resolvedness.dominant_wavelength((-1.0) ** np.arange(n)) == pytest.approx(2.0)
    assert resolvedness.dominant_wavelength(np.sin(2 * np.pi * np.arange(n) / 10.0)) == pytest.approx(10.0, rel=0.02)


def test_starshot_uniform_beam_is_ill_posed_and_says_so_in_simulate(capsys):
    """The must-show case at n = 30: E/E_cr,max ≈ 1.5e-6, the fastest growth at two slices per wavelength and
    doubling with n; `simulate` prints the one-line verdict with its numbers."""
    assert main(["simulate", *STARSHOT_CLI, "--t-final", "0.02", "--no-uncertainty", "--quiet"]) == 0
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if "ill-posed in n" in line]
    assert len(lines) == 1
    line = lines[0]
    for words in ("depends on n and on noise", "no continuum limit", "bending stiffness", "tension", "cut-off"):
        assert words in line
    assert "2 slices per wavelength" in line and "E/E_cr,max = 1.5e-06" in line
    verdict = resolvedness.assess(SailParameters(**STARSHOT, n=30))
    assert verdict.well_posed is False and verdict.rate_ratio == pytest.approx(2.0, abs=0.15)
    # bending cuts the growth off at the continuum's λ* = L √(E/E_cr,max)/ν (2.6 mm), far below l = 0.107 m
    p = SailParameters(**STARSHOT, n=30)
    assert verdict.cutoff_wavelength == pytest.approx(cutoff_slices(p) * p.slice_length, rel=0.1)


@pytest.mark.parametrize("name", ["torsion-soft", "torsion-stable", "tnt-stable"])
def test_paper_cases_with_bending_or_tension_are_well_posed(name):
    result = solve(paper_case(name), "reduced", paper_settings(name, t_final=0.05), uncertainty=False)
    assert not any("ill-posed" in w or "not resolved" in w for w in result.warnings)
    record = result.info["resolvedness"]
    assert record["assessed"] and record["well_posed"] is True and record["resolved"] is True


def test_well_posed_but_unresolved_chain_says_so():
    """The torsion sail at E = 0.001 E_cr,max (ν = 3/2): bending cuts the growth off at λ* ≈ L √(E/E_cr,max)/ν
    ≈ 2 cm, so at n = 120 (slices of 8 mm) the fastest wave is at the grid scale and its rate still moves by far
    more than UNRESOLVED_RATE_CHANGE between n and 2n, though it no longer doubles: well posed, not resolved,
    and the run says so in one line."""
    base = paper_case("torsion-soft")
    p = base.replace(n=120, youngs_modulus=1e-3 * theory.critical_modulus_max(base))
    verdict = resolvedness.assess(p)
    assert verdict.well_posed is True and verdict.resolved is False
    assert verdict.relative_n_error > resolvedness.UNRESOLVED_RATE_CHANGE
    assert verdict.slices_per_wavelength < 4
    line = verdict.warning()
    assert line.startswith("not resolved in n") and f"n = {2 * p.n}" in line and "\n" not in line


@pytest.mark.parametrize("name", ["rigid", "tnt-soft"])
def test_paper_cases_without_bending_are_ill_posed(name):
    """No bending, and (membrane) a tension of 0.01 T_cr,max that cannot outweigh the trough compression: every
    wavelength down to the slice grows, faster the shorter (docs/convergence.md: their failure times keep
    falling with n)."""
    result = solve(paper_case(name), "reduced", paper_settings(name, t_final=1e-4), uncertainty=False)
    assert sum("ill-posed in n" in w for w in result.warnings) == 1
    assert "no bending stiffness" in result.warnings[-1]
    assert ("as the tnt model has" in result.warnings[-1]) == (name == "rigid")  # only tnt takes --tension
    assert result.info["resolvedness"]["rate_ratio"] > 1.9


def test_seeded_random_torsion_sails_either_side_of_the_cutoff():
    """E/E_cr,max and n drawn at random (seeded) so that the continuum's λ*/l is below 1 or above 4: the chain
    that cannot carry λ* is ill-posed at that n, the one that does is well posed."""
    rng = np.random.default_rng(24)
    base = paper_case("torsion-soft")
    for _ in range(3):
        n = int(rng.choice([20, 30, 40]))
        p = base.replace(n=n)
        below = p.replace(youngs_modulus=theory.critical_modulus_max(p) * (1.5 / n) ** 2 * rng.uniform(1e-4, 0.9))
        above = p.replace(youngs_modulus=theory.critical_modulus_max(p) * (1.5 * 4 / n) ** 2 * rng.uniform(1.1, 50))
        assert cutoff_slices(below) < 1 < 4 < cutoff_slices(above)
        assert resolvedness.assess(below).well_posed is False
        assert resolvedness.assess(above).well_posed is True


def test_seeded_random_membranes_either_side_of_the_trough_compression():
    """The inextensible membrane without bending: tension below 1.5 T_cr,max leaves part of the trough compressed
    (p a₀ W = 2 T_cr,max there), so it is ill-posed; above 2.5 T_cr,max nothing is compressed and it is well
    posed. The stabilising tension the verdict estimates is that compression, 2 T_cr,max."""
    rng = np.random.default_rng(7)
    p = paper_case("tnt-soft", axial_springs=False, n=int(rng.choice([20, 30, 40])))
    t_cr = theory.critical_tension_max(p)
    low = resolvedness.assess(p.replace(tension=t_cr * rng.uniform(0.01, 1.5)))
    high = resolvedness.assess(p.replace(tension=t_cr * rng.uniform(2.5, 100)))
    assert low.well_posed is False and high.well_posed is True
    assert low.stabilising_tension == pytest.approx(2 * t_cr, rel=0.15)


def test_extensible_membrane_is_assessed_in_its_inextensible_limit():
    p = paper_case("tnt-soft")
    assert resolvedness.assess(p).to_dict() == resolvedness.assess(p.replace(axial_springs=False)).to_dict()


@pytest.mark.parametrize(
    "params, why",
    [
        (SailParameters(model="sheet", n=6, ny=6, youngs_modulus=4.5e9), "sheets"),
        (paper_case("torsion-soft", boundary="cantilever", intensity=0.0), "supported"),
        (paper_case("torsion-soft", n=resolvedness.MAX_SLICES + 1), "above n"),
    ],
)
def test_what_is_not_assessed_says_why(params, why):
    verdict = resolvedness.assess(params)
    assert not verdict.assessed and verdict.well_posed is None and why in verdict.reason
    assert verdict.warning() is None


def test_soft_sail_n_error_estimate_covers_its_distance_to_the_converged_answer():
    """Well posed: δt_f = t_f abs(σ(n) − σ(2n))/σ(2n) from the fastest growth rate's discretisation error. At
    n = 30 it covers the n = 30 → converged difference (converged: the run at n = 960, within 1e-4 s of the
    limit of docs/convergence.md)."""
    settings = RunSettings(t_final=3.0)
    coarse = solve(paper_case("torsion-soft"), "reduced", settings, uncertainty=False)
    fine = solve(paper_case("torsion-soft", n=960), "reduced", settings, uncertainty=False)
    record = coarse.info["resolvedness"]
    assert record["well_posed"] and fine.info["resolvedness"]["assessed"] is False
    difference = abs(fine.failure_time - coarse.failure_time)
    assert 0.05 < difference < record["failure_time_n_error"] < 3 * difference


def test_a_receding_sail_is_judged_at_its_doppler_dimmed_start(capsys):
    """β₀ = 0.1: the sail's frame sees I₀ (1 − β₀)/(1 + β₀) = (9/11) I₀ at the start, so g₀ and E_cr,max (Eqs 4,
    8) are 9/11 of the sail at rest's and E/E_cr,max is 11/9 of it, in `theory` and in the run's verdict; the
    verdict's growth rate, from the dimmed load, is that of the case lit at (9/11) I₀."""
    rest, moving = SailParameters(youngs_modulus=4.5e9), SailParameters(youngs_modulus=4.5e9, initial_beta=0.1)
    dimmed = rest.replace(intensity=rest.intensity * 9 / 11)
    ratio = resolvedness.stiffness_ratios(moving)["E/E_cr,max"]
    assert ratio == pytest.approx(resolvedness.stiffness_ratios(rest)["E/E_cr,max"] * 11 / 9, rel=1e-12)
    assert resolvedness.assess(moving).growth_rate == pytest.approx(resolvedness.assess(dimmed).growth_rate, rel=1e-9)
    printed = []
    for args in ([], ["--initial-beta", "0.1"]):
        assert main(["theory", "--modulus", "4.5e9", "--json", *args]) == 0
        printed.append(json.loads(capsys.readouterr().out))
    assert printed[1]["g0"] == pytest.approx(printed[0]["g0"] * 9 / 11, rel=1e-12)
    assert printed[1]["e_cr_max"] == pytest.approx(printed[0]["e_cr_max"] * 9 / 11, rel=1e-12)
    assert printed[1]["e_over_e_cr_max"] == pytest.approx(ratio, rel=1e-12)
    assert printed[1]["intensity_at_start"] == pytest.approx(1e8 * 9 / 11, rel=1e-12)
    assert "Doppler" in printed[1]["paper_prediction"] and "initial_beta" not in printed[0]


def test_a_heated_chain_is_assessed_at_the_tension_its_film_starts_with():
    """The heated TnT chain is judged with the end tension N(0) = N₀ − E h W α_T ⟨ΔT(0)⟩ its film has at the
    start (radiative equilibrium and the frame's relief, evaluated independently by tests/model/test_heating.py);
    a film the heat leaves in compression is not assessed, with the reason."""
    from lightsail_mbs.model import relativity
    from tests.model.test_heating import BETA, heated, independent_tension

    p = heated(tension=60.0)
    verdict = resolvedness.assess(p)
    assert verdict.assessed and verdict.well_posed
    cold = resolvedness.stiffness_ratios(p.replace(heated=False))["T/T_cr,max"]
    start, _ = independent_tension(p, float(relativity.intensity_factor(BETA)))
    assert 0 < start < 0.5 * p.tension
    assert verdict.stiffness_ratios["T/T_cr,max"] / cold == pytest.approx(start / p.tension, rel=1e-6)
    with pytest.raises(ValueError, match=r"the heated film starts in compression \(end tension -"):
        resolvedness.assess(heated(tension=10.0))
