"""Checks of input values: a bad value raises :class:`ParameterError` with one line naming the parameter,
its value and what is allowed."""

from __future__ import annotations

import math
import numbers


class ParameterError(ValueError):
    """A parameter is outside its allowed range; the message names it, its value and the range."""


def check(name: str, value, ok: bool, allowed: str) -> None:
    if not ok:
        raise ParameterError(f"{name}={shown(value)} is invalid: allowed {allowed}")


def shown(value) -> str:
    """A value in an error message: a float as a user reads it (number), anything else as its repr."""
    return number(value) if isinstance(value, float) else repr(value)


def number(value) -> str:
    """A number as a user reads it: the shortest text that reads back to the same float, in scientific
    notation when large or small (4.5e+13, 1e-06, not 45000000000000.0); other values as str()."""
    if isinstance(value, bool) or not isinstance(value, float):
        return str(value)
    if value == 0 or not math.isfinite(value) or 1e-4 <= abs(value) < 1e6:
        return repr(float(value))
    for digits in range(17):
        text = f"{value:.{digits}e}"
        if float(text) == value:
            return text
    return repr(value)


def finite(name: str, value) -> float:
    """value as a float; ParameterError unless it is a real number (not a bool or a string), finite."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ParameterError(f"{name}={shown(value)} is invalid: allowed a finite real number")
    try:
        v = float(value)
    except (TypeError, ValueError, OverflowError):
        raise ParameterError(f"{name}={shown(value)} is invalid: allowed a finite real number") from None
    check(name, value, math.isfinite(v), "a finite real number (no NaN or inf)")
    return v
