"""Thermal expansion and the tension it costs a framed sail, against the paper's stabilising criteria.

**Strain.** A film heated from the temperature T_ref at which it was made (or tensioned) to T expands by the
thermal strain ε_th = α_T (T − T_ref) in every in-plane direction.

**The TnT chain between supports** (the paper's membrane, Sec. II and IV.C, held at its ends by a frame that
does not expand): its n slices are springs in series of stiffness k = E h W/l each (l = L/n). Heated to T_i, a
slice's rest length grows to l(1 + α_T ΔT_i); the frame keeps the total length, so the tension N in every
slice obeys Σ (N/k + l α_T ΔT_i) = Σ N₀/k (the pre-tension's stretch), i.e.

    N = N₀ − E h W α_T ⟨ΔT⟩,      ⟨ΔT⟩ the slices' mean (by length) temperature rise.

**The framed sheet** (a square or disc held at its edge by a rigid frame, plane stress, ν the Poisson ratio):
an equibiaxial thermal strain under zero total strain takes the in-plane force per metre E h α_T ΔT/(1 − ν),

    N' = N'₀ − E h α_T ⟨ΔT⟩/(1 − ν)   (N/m).

A frame that expands itself with α_frame (at its own temperature rise) relieves only the difference
(α_T ΔT − α_frame ΔT_frame); the frame here is rigid.

**Margin.** The paper's criteria at the sail-frame intensity I' (:mod:`lightsail_mbs.model.theory`): the TnT
chain holds its defect while N ≥ T_cr,max = ½ (2I'/c) a₀ W (Eq. 10), the sheet while N' ≥ T_cr,max/W, the
torsion chain while E ≥ E_cr,max (Eq. 8). The margin is N/T_cr,max (or E/E_cr,max): the verdict is stable while
it is ≥ 1. A negative N is a slack film: no tension holds the defect.
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.model import theory
from lightsail_mbs.model.parameters import SailParameters


def thermal_strain(expansion: float, temperature, reference: float):
    """ε_th = α_T (T − T_ref)."""
    return expansion * (np.asarray(temperature, float) - reference)


def heated_case(p: SailParameters, strain: float) -> SailParameters:
    """The free chain heated uniformly to the thermal strain ε_th = α_T ΔT: every length of the sail (L, W, h,
    a₀, the roughness, the film's lengths, the payload's stem, the billow radius) grows by s = 1 + ε_th about
    the sail's middle, and the density falls by s³ (the mass is kept); the beam is the beam's (its waist and
    axis stay where they are). Its shape is the cold one scaled by s, and the paper's E_cr,max ∝ I' a₀ L²/h³
    (Eq. 8) is unchanged by the scaling: uniform expansion alone does not move a free sail's criterion. A framed
    sail is not scaled (the frame holds its length: :func:`remaining_tension`)."""
    s = 1.0 + strain
    changes = {name: getattr(p, name) * s for name in ("length", "width", "thickness", "defect_amplitude")}
    changes["beam_centre"] = p.beam_centre + 0.5 * (s - 1.0) * p.length
    changes.update(density=p.density / s**3, roughness=p.roughness * s, film_rms=p.film_rms * s)
    changes.update(payload_stem=p.payload_stem * s, film_correlation_length=p.film_correlation_length * s)
    if p.payload_inertia:  # J = m r²: the payload's own size grows by s too
        changes["payload_inertia"] = p.payload_inertia * s**2
    if p.billow_radius != float("inf"):
        changes["billow_radius"] = p.billow_radius * s
    return p.replace(**changes)


def chain_tension_relief(p: SailParameters, expansion: float, mean_rise: float) -> float:
    """E h W α_T ⟨ΔT⟩ (N): the tension a TnT chain between rigid supports loses when heated by ⟨ΔT⟩."""
    return p.youngs_modulus * p.thickness * p.width * expansion * mean_rise


def sheet_tension_relief(p: SailParameters, expansion: float, poisson: float, mean_rise: float) -> float:
    """E_m h α_T ⟨ΔT⟩/(1 − ν) (N/m): the edge tension per metre a framed sheet loses (equibiaxial plane stress;
    E_m the sheet's in-plane modulus)."""
    modulus = p.youngs_modulus if p.membrane_modulus is None else p.membrane_modulus
    return modulus * p.thickness * expansion * mean_rise / (1.0 - poisson)


def remaining_tension(p: SailParameters, expansion: float, poisson: float, mean_rise: float) -> float | None:
    """The tension that holds the defect after heating: N (N) for the TnT chain, N' (N/m) for the sheet,
    None for the models without one (rigid, torsion)."""
    if p.model == "tnt":
        return p.tension - chain_tension_relief(p, expansion, mean_rise)
    if p.model == "sheet":
        return p.edge_tension - sheet_tension_relief(p, expansion, poisson, mean_rise)
    return None


def critical(p: SailParameters, sail_intensity: float) -> float | None:
    """The critical value of the stiffness that holds the defect at the sail-frame intensity I': T_cr,max (N,
    tnt, Eq. 10), T_cr,max/W (N/m, sheet), E_cr,max (Pa, torsion, Eq. 8); None for the rigid model or without a
    defect or load (no criterion)."""
    if p.model == "rigid" or p.defect_amplitude == 0 or sail_intensity == 0:
        return None
    case = p.replace(intensity=sail_intensity)
    if p.model == "torsion":
        return theory.critical_modulus_max(case)
    value = theory.critical_tension_max(case)
    return value / p.width if p.model == "sheet" else value


def margin(p: SailParameters, sail_intensity: float, tension: float | None) -> float | None:
    """The stabilising stiffness over its critical value (:func:`critical`): N/T_cr,max (tnt),
    N'/(T_cr,max/W) (sheet), E/E_cr,max (torsion); None where there is no criterion."""
    limit = critical(p, sail_intensity)
    if limit is None:
        return None
    return (p.youngs_modulus if p.model == "torsion" else tension) / limit
