"""Checks of input values: a bad value raises :class:`ParameterError` with one line naming the parameter,
its value and what is allowed."""

from __future__ import annotations

import math
import numbers


class ParameterError(ValueError):
    """A parameter is outside its allowed range; the message names it, its value and the range."""


def check(name: str, value, ok: bool, allowed: str) -> None:
    if not ok:
        raise ParameterError(f"{name}={value!r} is invalid: allowed {allowed}")


def finite(name: str, value) -> float:
    """value as a float; ParameterError unless it is a real number (not a bool or a string), finite."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ParameterError(f"{name}={value!r} is invalid: allowed a finite real number")
    try:
        v = float(value)
    except (TypeError, ValueError, OverflowError):
        raise ParameterError(f"{name}={value!r} is invalid: allowed a finite real number") from None
    check(name, value, math.isfinite(v), "a finite real number (no NaN or inf)")
    return v
