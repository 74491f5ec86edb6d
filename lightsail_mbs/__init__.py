"""lightsail-mbs: does a laser-driven lightsail keep its shape under the beam, or crumple?

Data flows one way: case (SailParameters) → initial shape → solver (exudyn | reduced, with RunSettings)
→ Result → analysis → studies, reports, figures, frames.
"""

from lightsail_mbs.model.parameters import ParameterError, SailParameters, paper_case
from lightsail_mbs.result import Result
from lightsail_mbs.solvers import solve
from lightsail_mbs.solvers.settings import RunSettings, paper_settings

__all__ = ["ParameterError", "SailParameters", "RunSettings", "paper_case", "paper_settings", "Result", "solve"]
__version__ = "0.1.0"
