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
