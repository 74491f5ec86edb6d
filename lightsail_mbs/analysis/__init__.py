"""Analysis of Results: failure and amplitude, energy, frequencies, linear and finite-amplitude
stability, statics. Analysis reads a Result (or a chain state); what it needs of a solver's equations
(linearisation, statics, eigenfrequencies, the chain's equations of motion) it asks through the solver's
declared capabilities (solvers.contract), never a solver's module.

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
