"""lightsail-mbs: does a laser-driven lightsail keep its shape under the beam, or crumple?

Data flows one way: SailParameters → initial shape → solver (exudyn | reduced) → Result
→ analysis → reports, maps, frames.
"""
from lightsail_mbs.model.parameters import ParameterError, SailParameters, paper_case
from lightsail_mbs.result import Result
from lightsail_mbs.solvers import solve

__all__ = ["ParameterError", "SailParameters", "paper_case", "Result", "solve"]
__version__ = "0.1.0"
