"""Energy of a run: kinetic plus elastic energy (Eqs 12, 23, 29) and the heat of the dampers."""

from __future__ import annotations

import numpy as np


def mechanical_energy(result) -> np.ndarray:
    """Kinetic plus elastic energy of a Result over time (J), Eqs (12), (23), (29):

    ½ m Σ(ẋ² + ẏ²) + ½ J Σ θ̇² + ½ k_T Σ(θ_j − θ_{j−1})² + ½ k_s Σ z_j².
    Conserved in free vibration (zero intensity, no damping, no tension).
    """
    p = result.params
    kinetic = 0.5 * p.slice_mass * (result.vx**2 + result.vy**2).sum(axis=1) + 0.5 * p.slice_inertia * (
        result.omega**2
    ).sum(axis=1)
    elastic = 0.5 * p.torsional_stiffness * (np.diff(result.theta, axis=1) ** 2).sum(axis=1)
    if result.z.shape[1]:
        elastic = elastic + 0.5 * p.axial_stiffness * (result.z**2).sum(axis=1)
    return kinetic + elastic


def dissipated_power(result) -> np.ndarray:
    """Heat generated in the dampers over time (W): c_T Σ(θ̇_j − θ̇_{j−1})² + c_s Σ ż_j²,
    with c_T, c_s the SailParameters dampers (explicit c plus material β k)."""
    p = result.params
    power = p.total_torsional_damping * (np.diff(result.omega, axis=1) ** 2).sum(axis=1)
    if result.z_rate.shape[1]:
        power = power + p.total_axial_damping * (result.z_rate**2).sum(axis=1)
    return power


def dissipated_energy(result) -> np.ndarray:
    """D(t) = ∫₀ᵗ P dt (J) by the cumulative Simpson rule on the output samples (error ∝ (ω Δt)⁴ for a
    mode at ω). In free vibration, mechanical_energy + D is constant."""
    power = dissipated_power(result)
    if not np.any(power):  # no dampers: nothing to integrate
        return np.zeros_like(power)
    from scipy.integrate import cumulative_simpson

    return cumulative_simpson(power, x=result.time, initial=0.0)
