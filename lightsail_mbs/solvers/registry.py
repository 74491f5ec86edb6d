"""The registered solvers: each engine's declaration for each model family it runs (solvers.contract).

A new engine is a folder under ``lightsail_mbs/solvers/`` with a ``run`` that keeps the contract, and its
``register(Solver(...))`` here. Capabilities and default options are named as "function" (of the
solver's module) or "module:function" (of a module of its package: each engine's ``capabilities.py``).
The declarations import nothing of the engines (Exudyn, numba): the modules are imported when a run or a
capability first needs them.
"""

from __future__ import annotations

from lightsail_mbs.solvers.contract import (
    Option,
    Solver,
    fraction,
    non_negative,
    one_of,
    positive,
    positive_or_per_entry,
    register,
    unit_interval,
    whole_positive,
)

PERTURBATION = Option("perturbation", non_negative, "a finite value ≥ 0 (m)", "perturbation", "seeded start (m)")
SHEET_CAPABILITIES = {"statics": "static_centres", "eigenfrequencies": "eigenfrequencies"}
CHAIN_DEFAULTS, SHEET_DEFAULTS = "capabilities:chain_defaults", "capabilities:sheet_defaults"

# Exudyn: the chain as one ObjectKinematicTree, the sheet as rigid tiles and connectors
STEP = Option("step_size", positive, "a finite step > 0 (s)", "step", "a fixed generalized-α step (s)")
NEWTON = (
    Option("newton_rel_tol", non_negative, "a finite value ≥ 0", "tolerance", "Newton's relative tolerance"),
    Option("newton_abs_tol", non_negative, "a finite value ≥ 0", "tolerance", "Newton's absolute tolerance (N)"),
)
SPECTRAL_RADIUS = Option("spectral_radius", unit_interval, "0 ≤ ρ∞ ≤ 1", None, "generalized-α's ρ∞")
EXUDYN_CHAIN_OPTIONS = (
    Option("method", one_of("auto", "DOPRI5", "generalized-alpha"), "auto, DOPRI5 or generalized-alpha"),
    Option("rtol", fraction, "0 < rtol < 1", "rtol", "the run's relative accuracy"),
    STEP,
    *NEWTON,
    SPECTRAL_RADIUS,
    Option("samples_per_check", whole_positive, "a whole number ≥ 1", None, "output samples between checks"),
    PERTURBATION,
)
EXUDYN_CHAIN_CAPABILITIES = {
    "statics": "capabilities:statics",
    "eigenfrequencies": "capabilities:eigenfrequencies",
    "mass_stiffness": "capabilities:mass_stiffness",
}
EXUDYN_SHEET_OPTIONS = (STEP, *NEWTON, SPECTRAL_RADIUS, PERTURBATION)
register(Solver("exudyn", "chain", "exudyn.chain", EXUDYN_CHAIN_OPTIONS, EXUDYN_CHAIN_CAPABILITIES, CHAIN_DEFAULTS))
register(Solver("exudyn", "sheet", "exudyn.sheet", EXUDYN_SHEET_OPTIONS, SHEET_CAPABILITIES, SHEET_DEFAULTS))

# the in-house reduced-Lagrangian solvers: the chain in minimal coordinates, the sheet's tiles
RTOL = Option("rtol", fraction, "0 < rtol < 1", "rtol", "relative tolerance")
MAX_STEP = Option("max_step", positive, "a finite value > 0 (s)", None, "largest step (s)")
CHAIN_METHODS = ("auto", "DOP853", "Radau", "RK45", "BDF", "LSODA")
REDUCED_CHAIN_OPTIONS = (
    Option("method", one_of(*CHAIN_METHODS), f"auto or one of {', '.join(CHAIN_METHODS[1:])}", None, "integrator"),
    RTOL,
    Option("atol", positive_or_per_entry, "a value > 0 or one per state entry", "tolerance", "absolute tolerance"),
    MAX_STEP,
    Option("first_step", positive, "a finite value > 0 (s)", None, "first step (s)"),
    PERTURBATION,
)
REDUCED_CHAIN_CAPABILITIES = {
    "statics": "capabilities:statics",
    "eigenfrequencies": "capabilities:eigenfrequencies",
    "linearise": "capabilities:linearise",
    "equations": "capabilities:ChainEquations",
}
register(
    Solver("reduced", "chain", "reduced.solver", REDUCED_CHAIN_OPTIONS, REDUCED_CHAIN_CAPABILITIES, CHAIN_DEFAULTS)
)
REDUCED_SHEET_CAPABILITIES = {
    **SHEET_CAPABILITIES,
    "linearise": "linearise",
    "linearise_rotating": "sheet_rotating:linearise_rotating",
    "spun_equilibrium": "sheet_relax:spun_equilibrium",
}
FRAME = Option("frame", one_of("inertial", "turning"), "inertial or turning", None, "integration frame (spin)")
RATE_SCALE = Option(
    "rate_scale", one_of("component", "spin"), "component or spin", None, "error scale of the tiles' rates (spin)"
)
JACOBIAN = Option("jacobian", one_of("coloured", "split"), "coloured or split", None, "dense rows apart (polar)")
register(
    Solver(
        "reduced",
        "sheet",
        "reduced.sheet",
        (RTOL, MAX_STEP, PERTURBATION, FRAME, RATE_SCALE, JACOBIAN),
        REDUCED_SHEET_CAPABILITIES,
        SHEET_DEFAULTS,
    )
)
