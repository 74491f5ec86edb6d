"""Analysis of Results: failure and amplitude, energy, frequencies, linear and finite-amplitude
stability, statics. Analysis reads a Result (or a chain state); the exceptions that still build a
solver's system from its internals (linear_stability, statics, finite_amplitude) are listed in the
import contract (pyproject.toml).

The failure rule and the energy functions (model.failure, model.energy) are also reachable from here
(``analysis.amplitude``, ``analysis.failure_time``, ``analysis.mechanical_energy``, …).
"""

from lightsail_mbs.analysis.energy import dissipated_energy, dissipated_power, mechanical_energy
from lightsail_mbs.analysis.failure import (
    amplitude,
    fails_at_trough,
    failure_time,
    hinge_heights,
    line_offsets,
    plane_amplitude,
    plane_offsets,
)

__all__ = [
    "amplitude",
    "dissipated_energy",
    "dissipated_power",
    "failure_time",
    "fails_at_trough",
    "hinge_heights",
    "line_offsets",
    "mechanical_energy",
    "plane_amplitude",
    "plane_offsets",
]
