"""Studies compose many solves: resumable sweeps and their store, bisection and stability maps,
Monte Carlo over defects, the solver cross-check and the classic validations."""
