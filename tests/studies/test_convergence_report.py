"""validation/convergence_n.py's summary compares the paper's n with the study's limit, and with nothing when the
study gives no limit (not converging, ill-posed or not): the finest answer of a non-monotone sequence is no limit."""

from types import SimpleNamespace

from lightsail_mbs.studies.convergence import PowerLawFit
from tests.helpers import validation_script


def study(fit, values=(1.004, 1.0, 1.001, 1.0009), ill_posed=False):
    rows = [
        SimpleNamespace(n=n, value=v, kind="max_amplitude_ratio")
        for n, v in zip((15, 30, 60, 120), values, strict=True)
    ]
    return SimpleNamespace(
        rows=rows, fit=fit, ill_posed=ill_posed, empirical_n_for_one_percent=None, tolerance_noise=0.0
    )


def paper_error(row: str) -> str:
    return [cell.strip() for cell in row.strip("|").split("|")][6]


def test_the_paper_n_is_compared_with_the_limit_only():
    summary_row = validation_script("convergence_n").summary_row
    refused = PowerLawFit(None, None, None, "not converging (not monotone in n: 1, 1, 1.001, 1.001)")
    assert paper_error(summary_row("stable", study(refused), 30)) == "—"
    fitted = PowerLawFit(1.25, 1.0, 50.0, "power law")
    assert paper_error(summary_row("fitted", study(fitted), 30)) == "-20.0%"
    noise = PowerLawFit(1.0009, None, None, "converged to the tolerance noise")
    assert paper_error(summary_row("noise", study(noise), 30)) == "-0.1%"
