"""Analysis of Results: failure and amplitude, energy, frequencies, linear and finite-amplitude
stability, statics. Analysis reads a Result (or a chain state), never a solver's internals."""
from lightsail_mbs.analysis.failure import *  # noqa: F401,F403
