"""The relativistic beam on a flat sail: Doppler factors, the sail-frame (proper) acceleration, and the
trajectory of a sail under constant beam power, in closed form.

**Doppler.** A sail receding from the laser at speed βc sees, in its instantaneous rest frame, the beam's
wavelength stretched and its intensity lowered (a plane wave along the motion; Einstein 1905 §8, or
Kulkarni, Lubin & Zhang, Astron. J. 155, 155 (2018), Eq. 7):

    λ' = λ √((1 + β)/(1 − β)),        I' = I (1 − β)/(1 + β).

The intensity factor is the square of the frequency factor D = √((1 − β)/(1 + β)): one D for each photon's
energy, one for the rate at which photons arrive.

**Proper acceleration.** In its rest frame the flat sail of reflectivity R and absorptivity α (transmissivity
1 − R − α) takes the momentum flux (2R + α) I'/c per area (the paper's Eq. 11 at normal incidence; the
absorbed power is re-radiated alike from both faces when ε_f = ε_b and so adds no thrust). A craft of rest
mass m intercepting the lab-frame beam power P = I A therefore has the proper acceleration

    g₀(β) = (2R + α) P (1 − β) / (m c (1 + β)).

**Trajectory.** For straight-line motion the proper acceleration is d(γv)/dt (lab time t), so with
u = γβ and K = m c² / ((2R + α) P)

    du/dt = (1/K) (1 − β)/(1 + β),      β = u/√(1 + u²).

With du = γ³ dβ and γ² = 1/((1 − β)(1 + β)) this separates:

    t(β)/K = ∫₀^β (1 + b)^(−1/2) (1 − b)^(−5/2) db.

Since d/db[(1 + b)^(1/2)(1 − b)^(−3/2)] = (2 + b)(1 + b)^(−1/2)(1 − b)^(−5/2) and
d/db[(1 + b)^(1/2)(1 − b)^(−1/2)] = (1 − b)(1 + b)^(−1/2)(1 − b)^(−5/2), the integrand is one third of
their sum, so

    t(β) = K [F(β) − F(0)],     F(b) = (2 − b) √(1 + b) / (3 (1 − b)^(3/2)),   F(0) = 2/3,

and t ≈ K β for β ≪ 1 (the Newtonian v = (2R + α)P t/(m c)). The distance follows from dx = cβ dt, with
b = 1 − (1 − b) and the second derivative above: x(β) = c K [F(β) − F(0) − (√((1 + β)/(1 − β)) − 1)].
β(t) inverts the increasing t(β) by Brent's method on [0, 1) (:func:`beta_at`).
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.base.validation import check, finite


def _beta(beta) -> np.ndarray:
    b = np.asarray(beta, float)
    check("beta", beta, bool(np.all((b >= 0) & (b < 1))), "0 ≤ β < 1")
    return b


def intensity_factor(beta):
    """I'/I = (1 − β)/(1 + β): the beam's intensity in the rest frame of a sail receding at βc."""
    b = _beta(beta)
    return (1.0 - b) / (1.0 + b)


def wavelength_factor(beta):
    """λ'/λ = √((1 + β)/(1 − β)): the beam's wavelength in the sail's rest frame."""
    b = _beta(beta)
    return np.sqrt((1.0 + b) / (1.0 - b))


def lorentz_factor(beta):
    """γ = 1/√(1 − β²)."""
    b = _beta(beta)
    return 1.0 / np.sqrt((1.0 - b) * (1.0 + b))


def momentum_coefficient(reflectivity: float, absorptivity: float) -> float:
    """2R + α: the momentum the flat sail takes per unit of incident momentum (Eq. 11 at normal incidence)."""
    return 2.0 * reflectivity + absorptivity


def proper_acceleration(beta, power: float, mass: float, reflectivity: float = 1.0, absorptivity: float = 0.0):
    """g₀(β) = (2R + α) P (1 − β) / (m c (1 + β)) (m/s²): the sail-frame acceleration of a flat craft of rest
    mass m intercepting the lab-frame beam power P."""
    return momentum_coefficient(reflectivity, absorptivity) * power / (mass * SPEED_OF_LIGHT) * intensity_factor(beta)


class Trajectory:
    """The flat craft of constant rest mass m under constant intercepted power P from rest (module docstring):
    t(β), x(β), β(t) and the right-hand side of du/dt (u = γβ), all in closed form. coefficient: the momentum
    the sail takes per unit of incident momentum at normal incidence (2R + α, :func:`momentum_coefficient`;
    c_n(0) of an optical table)."""

    def __init__(self, power: float, mass: float, coefficient: float = 2.0):
        for name, value in (("power", power), ("mass", mass), ("coefficient", coefficient)):
            check(name, value, finite(name, value) > 0, "> 0")
        self.power, self.mass, self.coefficient = float(power), float(mass), float(coefficient)
        self.time_constant = self.mass * SPEED_OF_LIGHT**2 / (self.coefficient * self.power)  # K, s

    @staticmethod
    def _primitive(b):
        return (2.0 - b) * np.sqrt(1.0 + b) / (3.0 * (1.0 - b) ** 1.5)

    def time(self, beta):
        """t(β) (s): the lab time to reach β from rest. F(β) − 2/3 with its numerator rationalised,
        (2 − b)√(1 + b) − 2(1 − b)^(3/2) = b(12 − 15b + 5b²)/((2 − b)√(1 + b) + 2(1 − b)^(3/2)), so that small
        β keeps every digit."""
        b = _beta(beta)
        q = (1.0 - b) ** 1.5
        return (
            self.time_constant
            * b
            * (12.0 - 15.0 * b + 5.0 * b * b)
            / (3.0 * q * ((2.0 - b) * np.sqrt(1.0 + b) + 2.0 * q))
        )

    def distance(self, beta):
        """x(β) (m): the distance covered (lab frame) on reaching β."""
        b = _beta(beta)
        return (
            SPEED_OF_LIGHT
            * self.time_constant
            * (self._primitive(b) - 2.0 / 3.0 - (np.sqrt((1.0 + b) / (1.0 - b)) - 1.0))
        )

    def beta_at(self, time: float) -> float:
        """β(t): the root of t(β) = time on [0, 1) (Brent's method, to round-off in β)."""
        from scipy.optimize import brentq  # here: the physics terms import this module, and runs load no scipy.optimize

        t = finite("time", time)
        check("time", time, t >= 0, "≥ 0")
        if t == 0:
            return 0.0
        # t(β) ≥ K β, so β ≤ t/K; and t(β) grows without bound as β → 1
        high = min(t / self.time_constant, np.nextafter(1.0, 0.0))
        if float(self.time(high)) <= t:  # β rounds to the largest float below 1
            return float(high)
        return brentq(lambda b: float(self.time(b)) - t, 0.0, high, xtol=1e-16, rtol=4 * np.finfo(float).eps)

    def rate(self, beta):
        """du/dt = (1 − β)/(K (1 + β)) (1/s): the right-hand side of the equation of motion in u = γβ."""
        return intensity_factor(beta) / self.time_constant

    def proper_acceleration(self, beta):
        """g₀(β) = c du/dt (m/s²)."""
        return SPEED_OF_LIGHT * self.rate(beta)

    def proper_time(self, beta):
        """τ(β) (s): the sail's own time to reach β. dτ = dt/γ = K (1 + β)/(1 − β) γ² dβ = K dβ/(1 − β)², so
        τ = K β/(1 − β)."""
        b = _beta(beta)
        return self.time_constant * b / (1.0 - b)

    def beta_at_proper_time(self, tau):
        """β(τ) = τ/(K + τ): the speed after the proper time τ ≥ 0 from rest (the inverse of :meth:`proper_time`)."""
        t = np.asarray(tau, float)
        check("tau", tau, bool(np.all(t >= 0)), "≥ 0 (s)")
        return t / (self.time_constant + t)


def speed_from_u(u):
    """β = u/√(1 + u²) for u = γβ."""
    u = np.asarray(u, float)
    return u / np.sqrt(1.0 + u * u)


class VaryingTrajectory:
    """The flat craft of :class:`Trajectory` whose momentum coefficient changes along the way: c_n(0) of an
    optical table with a wavelength axis, read at the sail-frame wavelength λ' = λ₀ √((1 + β)/(1 − β)).

    With K(β) = m c²/(c_n(β) P) the equation of motion du/dt = (1 − β)/(K(β)(1 + β)) separates as for a
    constant coefficient (module docstring), now with K under the integrals:

        t(β) = ∫₀^β K(b) (1 + b)^(−1/2) (1 − b)^(−5/2) db,    τ(β) = ∫₀^β K(b) (1 − b)^(−2) db,
        x(β) = c ∫₀^β b K(b) (1 + b)^(−1/2) (1 − b)^(−5/2) db,

    by adaptive Gauss–Kronrod quadrature (scipy's quad, relative tolerance 1e-13) split at `kinks` (the speeds
    where c_n(β) has a kink: a grid wavelength of a table linear in λ). coefficient: c_n as a function of β."""

    def __init__(self, power: float, mass: float, coefficient, kinks=()):
        for name, value in (("power", power), ("mass", mass)):
            check(name, value, finite(name, value) > 0, "> 0")
        self.power, self.mass, self.coefficient = float(power), float(mass), coefficient
        self.kinks = sorted(float(k) for k in kinks)
        check("coefficient", float(coefficient(0.0)), float(coefficient(0.0)) > 0, "c_n(0) > 0 at rest")

    def constant(self, beta: float) -> float:
        """K(β) = m c²/(c_n(β) P) (s)."""
        return self.mass * SPEED_OF_LIGHT**2 / (float(self.coefficient(beta)) * self.power)

    def _integral(self, beta, weight) -> float:
        from scipy.integrate import quad  # here, as beta_at's brentq

        b = float(_beta(beta))
        points = [k for k in self.kinks if 0.0 < k < b]
        pieces = zip([0.0, *points], [*points, b])
        return float(
            sum(
                quad(lambda x: self.constant(x) * weight(x), lo, hi, epsabs=0.0, epsrel=1e-13, limit=200)[0]
                for lo, hi in pieces
            )
        )

    def time(self, beta) -> float:
        """t(β) (s), lab time from rest."""
        return self._integral(beta, lambda b: (1.0 + b) ** -0.5 * (1.0 - b) ** -2.5)

    def proper_time(self, beta) -> float:
        """τ(β) (s), the sail's own time from rest."""
        return self._integral(beta, lambda b: (1.0 - b) ** -2)

    def distance(self, beta) -> float:
        """x(β) (m), lab frame."""
        return SPEED_OF_LIGHT * self._integral(beta, lambda b: b * (1.0 + b) ** -0.5 * (1.0 - b) ** -2.5)

    def proper_acceleration(self, beta) -> float:
        """g₀(β) = c (1 − β)/(K(β)(1 + β)) (m/s²)."""
        return SPEED_OF_LIGHT * float(intensity_factor(beta)) / self.constant(float(beta))
