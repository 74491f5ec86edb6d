"""The solver contract: what a solver declares, what every run of it guarantees, and the registry.

A solver is one engine for one model family ("chain": the paper's slices, "sheet": the tiles), declared
once as a :class:`Solver` in :data:`REGISTRY`. ``solve(params, name, settings, **options)`` finds it by
its name and the family of ``params``, checks the options against its schema, and runs it through the
template of :func:`lightsail_mbs.solvers.solve` (failure located by event, uncertainty twins). The rules
a solver keeps (a third engine follows them from this docstring alone):

1. **Declaration.** ``Solver(name, family, module, options, capabilities, defaults)``: ``module``
   (relative to ``lightsail_mbs.solvers``) exposes ``run``; ``options`` is its option schema;
   ``capabilities`` maps what else it offers analysis to functions of its package (rule 9); ``defaults``
   names its default-options function (rule 10). A name may be registered once per family.
2. **Options are checked before anything is solved.** An option not in the schema, or a value the
   schema does not allow, raises ``ParameterError`` with one line naming the option, the solver and what is
   allowed (:meth:`Solver.check_options`). The module may check further (combinations), before solving.
3. **The run.** ``run(params, settings, *, progress=False, **options) -> Result`` starts from rest in
   ``shapes.initial_state(params)`` (the sheet: ``model.sheet``), in the frame accelerating at g₀.
4. **Sampling.** Its output is sampled on ``settings.sample_times()`` (t = 0 included) and nowhere else,
   from its own steps or their interpolant; the amplitude of each sample is the shared failure rule's.
5. **Stop rule.** With ``settings.stop_at_failure`` it stops at the first sample whose amplitude reaches
   ``settings.failure_ratio`` × the initial one (``skeleton.FailureMonitor``), else at ``t_final``.
6. **Errors are results.** A failure of the method (no convergence, a too small step, a non-finite state,
   an engine error) ends the run with ``Result.error`` set and the samples up to there; it never raises.
7. **Statistics.** ``Result.info`` holds ``method`` and the tolerances it ran with (``rtol`` where it has
   one, ``step_size`` for a fixed step, each Newton tolerance and its ``<name>_floor`` where Newton has
   one), and its counters under scipy's names where they apply: ``steps``, ``nfev`` (right-hand sides),
   ``njev`` (Jacobians), ``nlu`` (factorisations), ``newton_iterations``.
8. **The uncertainty hooks.** Each option's ``role`` tells the estimate (:mod:`~lightsail_mbs.solvers.uncertainty`)
   how to tighten or perturb a run: ``"rtol"`` (divided by F), ``"tolerance"`` (an absolute or Newton
   tolerance: divided by F, never below its floor), ``"step"`` (a fixed step: divided by √F) and
   ``"perturbation"`` (the amplitude, m, of a seeded roughness added to the start). A solver without a
   perturbation option cannot be assessed.
9. **Capabilities.** ``capabilities`` maps the analyses the solver supports beyond ``run`` (the names of
   :data:`CAPABILITIES`, each with its call) to the functions that do them: a function of the solver's
   module (``"static_centres"``), or of another module of its own package (``"capabilities:statics"``:
   ``lightsail_mbs.solvers.<package>.capabilities.statics``). Analysis calls them through
   :meth:`Solver.capability` (``lookup(name, params).capability("statics")``), never a solver's module; a
   solver that lacks one gives one ``ParameterError`` line naming what it offers.
10. **Default options.** ``defaults`` names (as a capability is named) a function
    ``(params, settings, **options) -> dict``: the value each option of the schema takes in a run of
    ``params`` under ``settings`` given ``options`` (None: left to the integrator).
    :meth:`Solver.default_options` calls it; studies read a solver's default step or tolerance there.
"""

from __future__ import annotations

import importlib
import math
import numbers
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from lightsail_mbs.model.parameters import ParameterError

FAMILIES = ("chain", "sheet")
ROLES = ("rtol", "tolerance", "step", "perturbation")
# rule 9: the capabilities a solver may declare, each with its call and what it returns
CAPABILITIES = {
    "statics": "(params) -> the static equilibrium under the case's load: a ChainState (chain), the tile "
    "centres (N, 3) (sheet)",
    "eigenfrequencies": "(params[, count]) -> ω (rad/s, ascending) of the equations linearised at rest in the "
    "initial state",
    "linearise": "(params, state, ...) -> ∂ẏ/∂y of the first-order equations at rest in `state`",
    "linearise_rotating": "(params, state) -> the sheet's equations linearised in the frame turning with its spin "
    "about `state`: ξ̇ = η, η̇ = K ξ + C η (centrifugal and Coriolis terms included)",
    "spun_equilibrium": "(params[, lit]) -> (centres, quaternions) of every body of the spinning sheet at rest in "
    "its turning frame, unlit (or lit by a beam centred on the spin axis)",
    "mass_stiffness": "(params, load, step, relative_epsilon) -> (M, K) of M q̈ + K q = 0 at the initial state",
    "equations": "(params) -> the chain's equations of motion in minimal coordinates (rhs, accelerations, "
    "coordinates of a state, centres, state scales, slice loads)",
}


def family_of(params) -> str:
    """The model family of a case: "sheet" for model "sheet", else "chain"."""
    return "sheet" if params.model == "sheet" else "chain"


def _real(value) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool) and math.isfinite(value)


def positive(value) -> bool:
    return _real(value) and value > 0


def non_negative(value) -> bool:
    return _real(value) and value >= 0


def fraction(value) -> bool:
    return _real(value) and 0 < value < 1


def unit_interval(value) -> bool:
    return _real(value) and 0 <= value <= 1


def positive_or_per_entry(value) -> bool:
    """A positive number, or an array of them (one per state entry)."""
    if np.ndim(value) == 0:
        return positive(value)
    values = np.asarray(value, float)
    return bool(values.size and np.all(np.isfinite(values)) and np.all(values > 0))


def whole_positive(value) -> bool:
    return isinstance(value, numbers.Integral) and not isinstance(value, bool) and value >= 1


def one_of(*choices) -> Callable:
    def check(value) -> bool:
        return value is None or value in choices

    return check


@dataclass(frozen=True)
class Option:
    """One option of a solver: its name, what values it allows (a check and its words), its role for the
    uncertainty estimate (rule 8; None: no role) and a line of help. None is always allowed: the default."""

    name: str
    check: Callable
    allowed: str
    role: str | None = None
    help: str = ""


@dataclass(frozen=True)
class Solver:
    """One registered solver of one model family (module docstring, rule 1)."""

    name: str
    family: str
    module: str
    options: tuple[Option, ...]
    capabilities: dict = field(default_factory=dict)
    defaults: str | None = None

    @property
    def label(self) -> str:
        return f"the {self.name} {self.family} solver"

    def check_options(self, options: dict) -> None:
        """Rule 2: one ParameterError naming the first unknown option or disallowed value."""
        known = {option.name: option for option in self.options}
        for name, value in options.items():
            if name not in known:
                raise ParameterError(f"option {name!r} is invalid for {self.label}: allowed {', '.join(known)}")
            option = known[name]
            if value is not None and not option.check(value):
                raise ParameterError(f"{name}={value!r} is invalid for {self.label}: allowed {option.allowed}")

    def roles(self) -> dict[str, tuple[str, ...]]:
        """Rule 8: the option names of each role."""
        return {role: tuple(o.name for o in self.options if o.role == role) for role in ROLES}

    def run(self, params, settings, *, progress: bool = False, **options):
        """The module's run (rule 3), imported on first use."""
        return self.implementation().run(params, settings, progress=progress, **options)

    def implementation(self):
        return importlib.import_module(f"lightsail_mbs.solvers.{self.module}")

    def resolve(self, target: str) -> Callable:
        """The function a declaration names (rule 9): "function" in the solver's module, or
        "module:function" in a module of the solver's package; imported on first use."""
        if ":" not in target:
            return getattr(self.implementation(), target)
        module, function = target.split(":")
        package = self.module.split(".")[0]
        return getattr(importlib.import_module(f"lightsail_mbs.solvers.{package}.{module}"), function)

    def capability(self, name: str) -> Callable:
        """The function behind a declared capability (rule 9); ParameterError when it is not declared."""
        if name not in self.capabilities:
            offered = ", ".join(self.capabilities) or "none"
            raise ParameterError(f"{self.label} has no capability {name!r}: it offers {offered}")
        return self.resolve(self.capabilities[name])

    def default_options(self, params, settings, **options) -> dict:
        """Rule 10: the value of each option in a run of `params` under `settings` given `options`."""
        if self.defaults is None:
            raise ParameterError(f"{self.label} declares no default options")
        return self.resolve(self.defaults)(params, settings, **options)


REGISTRY: dict[tuple[str, str], Solver] = {}


def register(solver: Solver) -> Solver:
    """Add a solver to the registry (rule 1); a second registration of a name and family is refused."""
    if solver.family not in FAMILIES:
        raise ParameterError(f"family={solver.family!r} is invalid: allowed one of {', '.join(FAMILIES)}")
    for option in solver.options:
        if option.role is not None and option.role not in ROLES:
            raise ParameterError(f"role={option.role!r} of option {option.name!r} is invalid: allowed {ROLES}")
    for capability in solver.capabilities:
        if capability not in CAPABILITIES:
            raise ParameterError(f"capability {capability!r} is invalid: allowed one of {', '.join(CAPABILITIES)}")
    key = (solver.name, solver.family)
    if key in REGISTRY:
        raise ParameterError(f"solver {solver.name!r} is registered for the {solver.family} family already")
    REGISTRY[key] = solver
    return solver


def registered_roles() -> dict[str, tuple[str, ...]]:
    """The option names of each role over every registered solver (for options not tied to one solver)."""
    merged = {role: [] for role in ROLES}
    for solver in REGISTRY.values():
        for role, option_names in solver.roles().items():
            merged[role] += [name for name in option_names if name not in merged[role]]
    return {role: tuple(option_names) for role, option_names in merged.items()}


def names() -> tuple[str, ...]:
    """Every registered solver name, in registration order."""
    return tuple(dict.fromkeys(name for name, _ in REGISTRY))


def lookup(name: str, params) -> Solver:
    """The solver `name` for the family of `params`; one ParameterError line when there is none."""
    return declared(name, family_of(params), f"model={params.model!r}")


def declared(name: str, family: str, case: str | None = None) -> Solver:
    """The solver `name` of `family`; one ParameterError line when there is none (`case`: how the caller
    named the family, for that line)."""
    if name not in names():
        raise ParameterError(f"solver={name!r} is invalid: allowed one of {', '.join(names())}")
    if (name, family) not in REGISTRY:
        others = [n for n, f in REGISTRY if f == family]
        raise ParameterError(
            f"solver={name!r} is invalid for a {family} ({case or f'family={family!r}'}): allowed one of "
            f"{', '.join(others)}"
        )
    return REGISTRY[(name, family)]
