"""Static equilibrium of a supported chain under its full tip load, from each solver's own equations.

Each solver solves it through its ``statics`` capability (solvers.contract, rule 9):

* exudyn: the assembled system with its supports and Exudyn's static solver (``mbs.SolveStatic``, Newton
  on the constrained equilibrium) with P = P₀;
* reduced: Newton on the reduced solver's accelerations at rest, q̈_f(q) = 0 on the free coordinates of the
  clamped chain (q̈ = M⁻¹Q at q̇ = 0, so this is Q_f(q) = 0), with the linearised Jacobian of its
  eigenfrequencies as a fixed (chord) Newton matrix; the tip load adds only ≈ P L²/EI relative load
  stiffness, so a few iterations reach round-off.

Meant for the cantilever validation (paper Appendix A): the load is the constant P₀ (τ ignored).
"""

from __future__ import annotations

from lightsail_mbs.model import shapes
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.solvers import contract


def full_load(p: SailParameters) -> SailParameters:
    """The case with its tip load at P₀ from the start (τ = 0), flat and unlit."""
    return p.replace(tip_load_time_constant=0.0, defect_amplitude=0.0, intensity=0.0)


def static_state(p: SailParameters, solver: str = "exudyn") -> shapes.ChainState:
    """Slice centres, angles and extensions of the static equilibrium under P₀ (module docstring)."""
    return contract.lookup(solver, p).capability("statics")(full_load(p))
