"""The derived quantities of a case (paper Sec. III): the slices' length, mass, inertia and stiffnesses, the
dampers, the beam's mean intensity; the radiation force and the acceleration are
:class:`~lightsail_mbs.model.parameters.SailParameters`' own.

Slice length l = L/n, slice mass m = ρ h W l, centroidal inertia J = m l²/12, bending stiffness
k_T = E I / l with I = W h³/12 (Sec. III.B), axial stiffness k_s = (n − 1) E h W / L (Sec. III.C).
"""

from __future__ import annotations

import math


class DerivedQuantities:
    """The derived quantities of SailParameters (a base class of it: it reads the case's fields)."""

    @property
    def slice_length(self) -> float:
        """l = L / n."""
        return self.length / self.n

    @property
    def slice_mass(self) -> float:
        """m = ρ h W l."""
        return self.density * self.thickness * self.width * self.slice_length

    @property
    def sail_area(self) -> float:
        """A: L W, or a sheet's mesh area (its tiles' areas summed: πL²/4 for the disc)."""
        if self.model == "sheet" and self.planform != "rectangle":
            from lightsail_mbs.model import planforms

            return float(planforms.mesh_of(self).areas.sum())
        return self.length * self.width

    @property
    def slice_inertia(self) -> float:
        """J = m l² / 12 about the slice centre."""
        return self.slice_mass * self.slice_length**2 / 12.0

    @property
    def second_moment_of_area(self) -> float:
        """I = W h³ / 12."""
        return self.width * self.thickness**3 / 12.0

    @property
    def torsional_stiffness(self) -> float:
        """k_T = E I / l (0 for the rigid model or with bending off)."""
        if self.model == "rigid" or not self.bending:
            return 0.0
        return self.youngs_modulus * self.second_moment_of_area / self.slice_length

    @property
    def rest_turn(self) -> float:
        """δ = θ_{k+1} − θ_k of the unstressed sail: −2 asin(l/(2R_c)) when the springs are at rest on the billowed
        arc (billow_rest), else 0 (flat); the torsion springs act on θ_{k+1} − θ_k − δ."""
        if not self.billow_rest:
            return 0.0
        return -2.0 * math.asin(self.slice_length / (2.0 * float(self.billow_radius)))

    @property
    def axial_stiffness(self) -> float:
        """k_s = (n − 1) E h W / L (TnT only; inf in the inextensible limit)."""
        if self.model != "tnt":
            return math.inf
        if not self.axial_springs:
            return math.inf
        return (self.n - 1) * self.youngs_modulus * self.thickness * self.width / self.length

    @property
    def total_torsional_damping(self) -> float:
        """c_T + β k_T (N·m·s/rad) on the relative rate θ̇_j − θ̇_{j−1} of each interior hinge (0: rigid)."""
        if self.model == "rigid":
            return 0.0
        return self.torsional_damping + self.stiffness_damping * self.torsional_stiffness

    @property
    def total_axial_damping(self) -> float:
        """c_s + β k_s (N·s/m) on each axial spring rate ż_j (0 without axial springs)."""
        if not self.extensible:
            return 0.0
        return self.axial_damping + self.stiffness_damping * self.axial_stiffness

    @property
    def extensible(self) -> bool:
        """True when the chain has axial spring coordinates z₁…z_{n−1}."""
        return self.model == "tnt" and self.axial_springs

    @property
    def displacement_scale(self) -> float:
        """Typical transverse displacement for solver tolerances: a₀, or 1e-6 L for a flat sail."""
        return self.defect_amplitude if self.defect_amplitude > 0 else 1e-6 * self.length

    @property
    def uniform_beam(self) -> bool:
        return math.isinf(self.beam_waist)

    @property
    def mean_intensity(self) -> float:
        """Ī: the beam intensity averaged over the flat sail 0 ≤ x ≤ L (and 0 ≤ y ≤ W for a sheet, whose
        Gaussian beam is round; over the tiles of a sheet of another planform, model.planforms.mean_intensity;
        I₀ for the uniform beam)."""
        if self.uniform_beam:
            return self.intensity
        if self.model == "sheet" and self.planform != "rectangle":  # the mesh's own mean
            from lightsail_mbs.model import planforms

            return planforms.mean_intensity(self)
        mean = self.intensity * _gaussian_mean(self.beam_waist, self.beam_centre, self.length)
        if self.model == "sheet":  # the sheet's beam is round: I₀ exp(−2((x − x_c)² + (y − y_c)²)/w²)
            mean *= _gaussian_mean(self.beam_waist, self.sheet_beam_centre_y, self.width)
        return mean

    @property
    def normal_momentum(self) -> float:
        """c_n(0): the momentum the flat sail takes from the light, per photon momentum incident on it —
        2R + α for the R/α facet (2 for the paper's mirror), the table's c_n(0) with an optical table."""
        if self.optics is None:
            return 2.0 * self.reflectivity + self.absorptivity
        return self.optical_table().normal_at_zero

    @property
    def sheet_beam_centre_y(self) -> float:
        """y_c of the sheet's Gaussian beam (m): beam_centre_y, or W/2 when it is None."""
        return 0.5 * self.width if self.beam_centre_y is None else float(self.beam_centre_y)

    def tip_force(self, t):
        """P(t) = P₀(1 − e^(−t/τ)) (paper Eq. 43; P₀ for τ = 0), N."""
        if self.tip_load_time_constant == 0:
            return self.tip_load
        return self.tip_load * -math.expm1(-t / self.tip_load_time_constant)


def _gaussian_mean(waist: float, centre: float, span: float) -> float:
    """(1/span) ∫₀^span exp(−2(s − centre)²/waist²) ds."""
    r = math.sqrt(2.0) / waist
    return math.sqrt(math.pi / 8.0) * waist / span * (math.erf(r * (span - centre)) + math.erf(r * centre))
