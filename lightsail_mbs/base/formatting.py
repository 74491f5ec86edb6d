"""Numbers as a user reads them: a value with the digits its uncertainty supports."""

from __future__ import annotations

import math


def with_uncertainty(value: float | None, uncertainty: float | None, digits: int = 6) -> str:
    """'2.1112 ± 0.0001': the value rounded to the uncertainty's first significant digit (two when it
    starts with 1); without an uncertainty, `digits` significant digits; '± inf' when infinite. A value
    below 1e-3 or from 1e5 on is written in scientific notation with the same rule on its mantissa:
    '(6.29483 ± 0.00004)e-06'."""
    if value is None:
        return "–"
    if uncertainty is None:
        return f"{value:.{digits}g}"
    if not math.isfinite(uncertainty):
        return f"{value:.{digits}g} ± inf"
    if uncertainty <= 0:
        return f"{value:.{digits}g} ± 0"
    if value != 0 and not 1e-3 <= abs(value) < 1e5 and uncertainty < abs(value):
        power = math.floor(math.log10(abs(value)))
        return f"({with_uncertainty(value / 10.0**power, uncertainty / 10.0**power)})e{power:+03d}"
    exponent = math.floor(math.log10(uncertainty))
    if f"{uncertainty:.0e}"[0] == "1":
        exponent -= 1
    decimals = max(0, -exponent)
    step = 10.0**exponent
    shown = math.ceil(uncertainty / step - 1e-9) * step
    if decimals:
        return f"{value:.{decimals}f} ± {shown:.{decimals}f}"
    return f"{round(value / step) * step:.0f} ± {shown:.0f}"


def n_error_clause(record: dict | None, unit: str = "") -> str:
    """A run's n-error record (Result.uncertainty["n_error"], lightsail_mbs.analysis.n_error) as a clause of its
    one-line answer: 'of which n-error 0.16 s, from a twin at n = 15', or why the ± holds none ('no n-error:
    ill-posed in n', 'n-error not estimated: …', 'n-error unbounded: …'); empty without a record."""
    if not record:
        return ""
    if not record["estimated"]:
        if record["reason"].startswith("ill-posed"):
            return "no n-error: ill-posed in n"
        return f"n-error not estimated: {record['reason']}"
    if not math.isfinite(record["value"]):
        verdict = "fails" if record["coarse_failed"] else "survives"
        return f"n-error unbounded: the twin at n = {record['n_coarse']} {verdict}"
    sizes = " and ".join(f"n = {size}" for size in record["twins"])
    twins = "twins" if len(record["twins"]) > 1 else "a twin"
    return f"of which n-error {record['value']:.2g}{unit}, from {twins} at {sizes}"
