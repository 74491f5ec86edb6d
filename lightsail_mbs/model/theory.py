"""Closed-form quasi-static theory of the paper's Section II (Eqs 4, 7–10), and the time scale t_c of the
finite-amplitude problem (lightsail_mbs.analysis.finite_amplitude).

All functions take a :class:`SailParameters` and return SI values. Tensions are
returned in newtons: the paper's per-width value multiplied by the width W.
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import relativity
from lightsail_mbs.model.parameters import SailParameters


def at_start(p: SailParameters) -> SailParameters:
    """The case as its sail meets the beam at the run's start. With initial_beta β₀ > 0 the sail recedes at
    β₀c and its rest frame sees the intensity I₀ D₀, D₀ = (1 − β₀)/(1 + β₀) (the Doppler term's factor at
    τ = 0, :mod:`lightsail_mbs.model.terms.doppler`), so the closed forms of its start (Eqs 4, 8, 10) are those
    of the case at I₀ D₀ and β₀ = 0 (the beam dims further during the run); without β₀, the case itself."""
    if p.initial_beta == 0:
        return p
    return p.replace(intensity=p.intensity * float(relativity.intensity_factor(p.initial_beta)), initial_beta=0.0)


def radiation_pressure(p: SailParameters) -> float:
    """2 I₀ / c: pressure on a flat perfect reflector at normal incidence (Pa)."""
    return 2.0 * p.intensity / SPEED_OF_LIGHT


def nominal_acceleration(p: SailParameters) -> float:
    """g₀ ≈ 2 I₀ / (c ρ h): first-order term of Eq. (4) (m/s²)."""
    return p.nominal_acceleration


def perturbed_acceleration(p: SailParameters) -> float:
    """Eq. (4) with its second-order term: g₀ [1 − 2π²ν²(a₀/L)²] (the printed 'n' is the mode ν)."""
    return p.nominal_acceleration * (1.0 - 2.0 * np.pi**2 * p.defect_mode**2 * (p.defect_amplitude / p.length) ** 2)


def critical_modulus(p: SailParameters, x0) -> np.ndarray:
    """E_cr(x₀) = −(3/2)(2I₀/c) a₀ L² / (π² ν² h³) · sin(2πνx₀/L), Eq. (7) (Pa)."""
    return -critical_modulus_max(p) * np.sin(2.0 * np.pi * p.defect_mode * np.asarray(x0, float) / p.length)


def critical_modulus_max(p: SailParameters) -> float:
    """E_cr,max = (3/2)(2I₀/c) a₀ L² / (π² ν² h³), Eq. (8) (Pa)."""
    return (
        1.5 * radiation_pressure(p) * p.defect_amplitude * p.length**2 / (np.pi**2 * p.defect_mode**2 * p.thickness**3)
    )


def critical_tension(p: SailParameters, x0) -> np.ndarray:
    """T_cr(x₀) = −(1/2)(2I₀/c) a₀ sin(2πνx₀/L) · W, Eq. (9) (N)."""
    return -critical_tension_max(p) * np.sin(2.0 * np.pi * p.defect_mode * np.asarray(x0, float) / p.length)


def critical_tension_max(p: SailParameters) -> float:
    """T_cr,max = (1/2)(2I₀/c) a₀ · W, Eq. (10) (N)."""
    return 0.5 * radiation_pressure(p) * p.defect_amplitude * p.width


def summary(p: SailParameters) -> dict:
    """All closed-form numbers of Section II for one case; for a sheet, its tiles' instead of the slices'
    (tile size, mass, plate bending rigidity D = E h³/12 at ν_p = 0, membrane modulus E_m) and the edge
    tension scale per metre of edge."""
    numbers = {
        "g0": nominal_acceleration(p),
        "g0_perturbed": perturbed_acceleration(p),
        "radiation_pressure": radiation_pressure(p),
        "e_cr_max": critical_modulus_max(p),
        "t_cr_max": critical_tension_max(p),
    }
    if p.model == "sheet":
        from lightsail_mbs.model.sheet import Tiles

        tiles = Tiles.of(p)
        return {
            **numbers,
            "t_cr_max_per_metre": critical_tension_max(p) / p.width,
            "tile_length": tiles.a,
            "tile_width": tiles.b,
            "tile_mass": tiles.mass,
            "bending_rigidity": tiles.bending_rigidity,
            "membrane_modulus": tiles.membrane_modulus,
        }
    return {
        **numbers,
        "slice_length": p.slice_length,
        "slice_mass": p.slice_mass,
        "torsional_stiffness": p.torsional_stiffness,
        "axial_stiffness": p.axial_stiffness if p.model == "tnt" else None,
    }


def wavenumber(p: SailParameters) -> float:
    """k = 2πν/L (1/m)."""
    return 2.0 * math.pi * p.defect_mode / p.length


def time_scale(p: SailParameters) -> float:
    """t_c = 1/(k √(g₀ a₀)) (s): the time the second-order load needs to move the defect by a₀."""
    if p.defect_amplitude <= 0 or p.nominal_acceleration <= 0:
        raise ParameterError("amplitude and intensity must be > 0 for a finite-amplitude time scale")
    return 1.0 / (wavenumber(p) * math.sqrt(p.nominal_acceleration * p.defect_amplitude))


# The stiffness that holds each model's defect in check and its critical value: what a stability map,
# a bisection or the finite-amplitude scaling sweeps. (The rigid model has none.)
STIFFNESS = {"torsion": ("youngs_modulus", critical_modulus_max), "tnt": ("tension", critical_tension_max)}
