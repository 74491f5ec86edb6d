"""The reduced sheet's run options (solvers.reduced.sheet.run) and the absolute-tolerance scales of its state.

Options: rtol, max_step, perturbation and frame (solvers.reduced.sheet's docstring), and two that change how a
spinning sheet is integrated, both off by default:

* ``rate_scale``: "component" (default: every state entry's error scaled by atol_i + rtol |y_i|, with atol
  from :func:`state_scales`) or "spin": a spinning sheet's tiles' three rates (ω_x, ω_y, ω_z in the tile's
  axes) all take the spin rate |Ω| as their scale, as a vector's components do in a norm relative to the
  vector (a tile turning at Ω whose axis tilts by δα has body rates of Ω δα about its in-plane axes; the
  component scale of ω_x, ω_y is the defect's slope over the instability time, ~1e-7 of Ω for a flat disc).
  No change for a sheet that does not spin.
* ``jacobian``: "coloured" (default: 13 right-hand sides per colour of the tiles' distance-2 colouring) or
  "split": the rows of tiles with more than sheet_jacobian.DENSE_DEGREE neighbours (a polar disc's centre
  tile) are left out of the colouring's conflicts and computed apart (solvers.reduced.sheet_jacobian): the
  same Jacobian to the round-off of its difference quotients, with 7 colours instead of 57 on a 1009-tile
  disc.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import sheet
from lightsail_mbs.model.parameters import SailParameters

DEFAULT_RTOL = 1e-7
DEFAULT_MAX_STEP = 0.01
FRAMES = ("inertial", "turning")
RATE_SCALES = ("component", "spin")
JACOBIANS = ("coloured", "split")
OPTIONS = ("rtol", "max_step", "perturbation", "frame", "rate_scale", "jacobian")


@dataclass(frozen=True)
class RunOptions:
    """A reduced sheet run's options, checked (:func:`checked_options`)."""

    rtol: float
    max_step: float
    perturbation: float
    frame: str
    rate_scale: str = "component"
    jacobian: str = "coloured"


def state_scales(p: SailParameters, rate_scale: str = "component") -> np.ndarray:
    """Absolute-tolerance scales per state component: a₀ for u, the defect slope for q, and both over the
    instability time √(L/g₀) for the rates; a billowed sheet's at least its cap's sag and largest slope (the
    round-off of its tilted springs' forces, ~1e-16 of them, must sit below the tolerance). A spinning sail's
    in-plane motion is its rotation: u_x, u_y and v_x, v_y are scaled by the rim's radius and speed (a tile
    near the axis moves little, but the round-off of its in-plane forces, ~ε k_∥ R, is that of the whole
    sheet's); its ω_z by the spin rate, and with rate_scale "spin" its ω_x and ω_y too (module docstring)."""
    a0 = p.displacement_scale
    mode = p.defect_mode if p.defect_mode_y is None else max(p.defect_mode, p.defect_mode_y)
    slope = max(2 * math.pi * mode * p.defect_amplitude / p.length, a0 / p.length)
    if not math.isinf(p.billow_radius):
        points, normals = sheet.cap(p, sheet.flat_centres(p))
        a0 = max(a0, float(np.ptp(points[:, 2])))
        slope = max(slope, float(np.max(np.hypot(normals[:, 0], normals[:, 1]))))
    tc = math.sqrt(p.length / p.nominal_acceleration) if p.nominal_acceleration > 0 else 1.0
    scales = np.tile(np.r_[[a0] * 3, [slope] * 4, [a0 / tc] * 3, [slope / tc] * 3], (sheet.tile_count(p), 1))
    if p.spin_rate != 0:
        rim = 0.5 * max(p.length, p.width)
        scales[:, 0:2] = np.maximum(scales[:, 0:2], rim)
        scales[:, 7:9] = np.maximum(scales[:, 7:9], abs(p.spin_rate) * rim)
        scales[:, 6] = np.maximum(scales[:, 6], 1.0)
        rates = slice(10, 13) if rate_scale == "spin" else slice(12, 13)
        scales[:, rates] = np.maximum(scales[:, rates], abs(p.spin_rate))
    return scales.ravel()


def checked_options(options: dict, p: SailParameters) -> RunOptions:
    """A run's options (defaults for those not given: the turning frame for a spinning sheet); one line on a
    bad one."""
    unknown = sorted(set(options) - set(OPTIONS))
    if unknown:
        raise ParameterError(f"option {unknown[0]!r} is invalid for a sheet: allowed {', '.join(OPTIONS)}")
    rtol = float(options.get("rtol") or DEFAULT_RTOL)
    if not 0 < rtol < 1:
        raise ParameterError(f"rtol={rtol!r} is invalid: allowed 0 < rtol < 1")
    max_step = float(options.get("max_step") or DEFAULT_MAX_STEP)
    if not (max_step > 0 and math.isfinite(max_step)):
        raise ParameterError(f"max_step={max_step!r} is invalid: allowed a finite value > 0 (s)")
    frame = options.get("frame") or ("turning" if p.spin_rate != 0 else "inertial")
    if frame not in FRAMES:
        raise ParameterError(f"frame={frame!r} is invalid: allowed inertial or turning")
    choices = {}
    for name, allowed in (("rate_scale", RATE_SCALES), ("jacobian", JACOBIANS)):
        choices[name] = options.get(name) or allowed[0]
        if choices[name] not in allowed:
            raise ParameterError(f"{name}={choices[name]!r} is invalid: allowed {' or '.join(allowed)}")
    return RunOptions(rtol, max_step, float(options.get("perturbation") or 0.0), frame, **choices)
