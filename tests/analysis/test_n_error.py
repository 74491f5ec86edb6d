"""The n-error of a single run (analysis.n_error): twins at n/2 and n/4, folded into the ± where the case is well
posed in n; an ill-posed run keeps its verdict and prints no n-error; the paper's soft sail at n = 30 prints a ±
that covers its distance to the converged answer."""

import numpy as np
import pytest

from lightsail_mbs import RunSettings, SailParameters, paper_case, paper_settings, solve
from lightsail_mbs.analysis import n_error
from lightsail_mbs.cli import main
from lightsail_mbs.result import Result

STARSHOT_CLI = (
    "--model torsion --length 3.2 --width 3.2 --thickness 100e-9 --density 2200 --modulus 70e9 --intensity 1e10 "
    "--defect-amplitude 1e-6 --solver reduced --n 30 --t-final 0.02 --quiet"
).split()


@pytest.mark.parametrize("order", [0.9, 1.0, 2.0, 4.0])
def test_estimate_covers_a_power_law_sequence(order):
    """q(n) = q_∞ + C n^(−p) from n = 8 to 512: E_n ≥ abs(q(n) − q_∞) at every n for orders from 0.9 (slower than
    the first order the rule assumes) to 4, and overstates it by at most SAFETY 2^p (2^p − 1)."""
    limit, c = 2.0, 3.0
    q = {n: limit + c * n**-order for n in (8, 16, 32, 64, 128, 256, 512)}
    for n in (32, 64, 128, 256, 512):
        error = abs(q[n] - limit)
        estimate = n_error.estimate(q[n], q[n // 2], q[n // 4])
        assert estimate >= error
        assert estimate <= n_error.SAFETY * 2**order * (2**order - 1) * error * (1 + 1e-9)


def test_estimate_of_a_sequence_that_is_not_monotone_takes_the_larger_change():
    """The soft sail's pre-asymptotic stretch: q(n/4), q(n/2), q(n) = 2.11, 2.18, 2.21 s at n = 30, 60, 120 shrink
    at first order or faster (the last change alone, doubled); 2.23, 2.03, 2.11 s at n = 7, 15, 30 do not."""
    assert n_error.estimate(2.21, 2.18, 2.11) == pytest.approx(2 * 0.03)
    assert n_error.estimate(2.11, 2.03, 2.23) == pytest.approx(2 * 0.20)
    assert n_error.estimate(2.11, 2.03) == pytest.approx(2 * 0.08)  # no twin at n/4: the last change alone


def test_estimate_distrusts_a_collapse_and_a_clipped_ratio():
    """A last change far below any power law's (a seeded torsion case: 0.74061, 0.75629, 0.75630 s at n = 23, 47,
    95, then 0.75449 s at 190) and an amplitude ratio of exactly 1 take the larger change."""
    assert n_error.estimate(0.75630, 0.75629, 0.74061) == pytest.approx(2 * 0.01568)
    assert n_error.estimate(1.0, 1.0002, 1.0042, ratio=True) == pytest.approx(2 * 0.004)
    assert n_error.estimate(1.0001, 1.0002, 1.0042, ratio=True) == pytest.approx(2 * 0.0001)


def recurring_history(recurrence: float, dip: float = 0.08):
    """(time, amplitude) of a tension-stabilised sail's amplitude: from a(0) = 1 down to `dip` at half the run and
    back up to `recurrence` at its end (piecewise linear, 401 samples)."""
    time = np.linspace(0.0, 1.0, 401)
    return time, np.interp(time, [0.0, 0.5, 1.0], [1.0, dip, recurrence])


def test_recurrence_rise_bounds_a_clipped_ratio():
    """Recurrences that stay below the initial amplitude at n/2 and n (0.977, 0.9995) give the answer 1 twice, so
    the change of the answers is 0; the recurrences' own change, doubled, may lift them above 1:
    0.9995 + 2 · 0.0225 − 1."""
    ratio_n, ratio_half = 1.0, 1.0
    assert n_error.estimate(ratio_n, ratio_half, ratio=True) == 0.0
    rise = n_error.recurrence_rise(*recurring_history(0.9995), *recurring_history(0.977))
    assert rise == pytest.approx(0.9995 + 2 * 0.0225 - 1.0)


def test_recurrence_rise_ignores_recurrences_far_below_the_answer():
    """A recurrence to 0.5 (0.3 at n/2) cannot reach the answer 1 within twice its change: no rise. A history
    that only rises is its own recurrence: R(t) is its running maximum, and the rise twice the change at the end."""
    assert n_error.recurrence_rise(*recurring_history(0.5), *recurring_history(0.3)) == 0.0
    time = np.linspace(0.0, 1.0, 101)
    assert n_error.recurrence_rise(time, 1.0 + 0.1 * time, time, 1.0 + 0.08 * time) == pytest.approx(2 * 0.02)


def test_surviving_chain_whose_recurrence_passes_its_initial_amplitude_at_2n():
    """An extensible TnT chain at T = 5 T_cr,max (seeded case 18 of validation/accuracy.md, where the rule was
    found): its amplitude falls to 0.08 a(0) and recurs to 0.9995 a(0) at n = 91 (0.977 at n = 45), so the
    answer is 1 at both and their change 0; at n = 182, sampled 4× finer, the recurrence passes a(0) (1.0146).
    The ± holds the rise of the recurrences and covers it."""
    p = SailParameters(
        model="tnt", axial_springs=True, n=91, defect_mode=3, thickness=0.406e-6, density=2680, intensity=2.77e9,
        defect_amplitude=3.84e-5, youngs_modulus=5.28e9, tension=1.81e-3,
    )  # fmt: skip
    settings = RunSettings(t_final=0.2625, output_interval=0.2625 / 400)
    result = solve(p, "reduced", settings)
    record = result.uncertainty["n_error"]
    assert result.max_amplitude_ratio == 1.0 and record["twins"]["45"]["value"] == 1.0
    assert record["value"] == record["recurrence_rise"] > 0
    fine = solve(
        p.replace(n=182), "reduced", RunSettings(t_final=0.2625, output_interval=0.2625 / 1600), uncertainty=False
    )
    assert fine.max_amplitude_ratio > 1.01
    assert abs(fine.max_amplitude_ratio - result.max_amplitude_ratio) <= result.max_amplitude_ratio_uncertainty


def test_twin_sizes_carry_the_defect():
    """The twin at n/4 only with 8 slices per defect wavelength (ν = 1.5: from 12 slices), none below 4 slices."""
    p = paper_case("torsion-soft")
    assert n_error.twin_sizes(p.replace(n=120)) == [60, 30]
    assert n_error.twin_sizes(p.replace(n=30)) == [15]
    assert n_error.twin_sizes(p.replace(n=7)) == []


def test_soft_sail_at_n30_prints_a_plus_minus_that_covers_the_converged_answer(tmp_path):
    """The must-show case: the paper's soft torsion sail at n = 30 (reduced solver) is well posed; its printed ±
    holds the n-error from its twin at n = 15 and covers the distance to the answer at n = 960, which
    `converge` puts within 1e-4 s of its limit (docs/convergence.md)."""
    p, settings = paper_case("torsion-soft"), paper_settings("torsion-soft")
    result = solve(p, "reduced", settings)
    record = result.uncertainty["n_error"]
    assert record["estimated"] and set(record["twins"]) == {"15"}
    assert result.uncertainty["uncertainty"] == pytest.approx(
        result.uncertainty["uncertainty_numerics"] + record["value"]
    )
    fine = solve(p.replace(n=960), "reduced", settings, uncertainty=False)
    assert abs(result.failure_time - fine.failure_time) > 0.04  # n = 30 is 5 % early
    assert abs(result.failure_time - fine.failure_time) <= result.failure_time_uncertainty
    assert "of which n-error" in result.answer_text() and "from a twin at n = 15" in result.answer_text()
    # saved and read back (what `info` prints), the same line
    assert Result.load(result.save(tmp_path / "soft")).answer_text() == result.answer_text()


def test_ill_posed_run_keeps_its_verdict_and_prints_no_n_error(capsys):
    """The uniform-beam Starshot-like sail at n = 30 is ill-posed in n: its line says so and holds no n-error
    digits; the ± is the numerics' alone."""
    assert main(["simulate", *STARSHOT_CLI]) == 0
    captured = capsys.readouterr()
    line = captured.out.splitlines()[0]
    assert "(no n-error: ill-posed in n)" in line and "of which n-error" not in line
    assert sum("ill-posed in n: the fastest-growing wave" in w for w in captured.err.splitlines()) == 1


def test_sheet_says_why_it_has_no_n_error():
    sheet = SailParameters(model="sheet", n=4, ny=4, youngs_modulus=4.5e9)
    result = solve(sheet, "reduced", RunSettings(t_final=0.05))
    assert "n-error not estimated: not assessed for sheets" in result.answer_text()
    assert "n_error" in result.uncertainty and "uncertainty_numerics" not in result.uncertainty
