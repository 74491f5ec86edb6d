"""The twins' options: how a twin of the uncertainty estimate (:mod:`lightsail_mbs.solvers.uncertainty`) loosens or
tightens the base run's numerical options, found by their roles (solvers.contract, rule 8).

A twin multiplies every tolerance of the base run by a factor F (its rtol, and its atol or Newton tolerances if
given) and a fixed step by √F, the methods with a fixed step (generalized-α) being second order. The loose twin
loosens by F = `loosening` (LOOSEN for the adaptive methods, DOP853_LOOSEN for the reduced solver's DOP853, STEP_LOOSEN
for generalized-α: the step × 2, and Exudyn's chain loosens its Newton tolerances as rtol², so by 16); the tightened
twins divide by `tightening` (TIGHTEN, WIDE_TIGHTEN for DOP853; generalized-α two twins, `sequence`: the step / 2
and / 4 with the tolerances / HALF_TIGHTEN and / STEP_TIGHTEN). Why these factors: the uncertainty module's docstring.
"""

from __future__ import annotations

import math

from lightsail_mbs.solvers import contract

LOOSEN = 10.0  # the loose twin's tolerances are the base run's × LOOSEN (adaptive methods)
DOP853_LOOSEN = 3.0  # the reduced solver's DOP853: rtol × 3
STEP_LOOSEN = 4.0  # generalized-α: rtol × 4, the step × 2
TIGHTEN = 10.0  # the fallback's tight twin: the base run's tolerances / TIGHTEN (adaptive methods)
WIDE_TIGHTEN = 100.0  # the fallback, the reduced solver's DOP853: rtol / 100
HALF_TIGHTEN = 4.0  # the fallback, generalized-α (a fixed step): the middle twin, tolerances / 4, the step / 2
STEP_TIGHTEN = 16.0  # the fallback, generalized-α: the tight twin, tolerances / 16, the step / 4


def is_fixed_step(info: dict) -> bool:
    """Whether the base run is generalized-α at a fixed step (Exudyn's chains and sheets)."""
    return info.get("method") == "generalized-alpha"


def tightening(info: dict) -> float:
    """F of the tight twin (module docstring): STEP_TIGHTEN for generalized-α, WIDE_TIGHTEN for DOP853,
    else TIGHTEN."""
    method = info.get("method")
    return STEP_TIGHTEN if is_fixed_step(info) else WIDE_TIGHTEN if method == "DOP853" else TIGHTEN


def sequence(info: dict) -> list[tuple[str, float]]:
    """The twins of the tolerance sequence after the base run: (name, F), the tightest last."""
    if is_fixed_step(info):
        return [("half", HALF_TIGHTEN), ("tight", STEP_TIGHTEN)]
    return [("tight", tightening(info))]


def loosening(info: dict) -> float:
    """F of the loose twin (module docstring): STEP_LOOSEN for generalized-α, DOP853_LOOSEN for DOP853, else
    LOOSEN."""
    return STEP_LOOSEN if is_fixed_step(info) else DOP853_LOOSEN if info.get("method") == "DOP853" else LOOSEN


def looser(twin_info: dict, info: dict) -> bool:
    """Whether a twin ran at a larger fixed step (generalized-α) or rtol (the adaptive methods) than the base
    run (`info`): a solver may cap its step (Exudyn's sheet: at the output interval), and a loose twin at the
    base run's step is the base run again, whose difference from it says nothing."""
    name = "step_size" if is_fixed_step(info) and info.get("step_size") else "rtol"
    return info.get(name) is not None and float(twin_info.get(name) or 0.0) > float(info[name]) * (1 + 1e-12)


def loosened(options: dict, info: dict, roles: dict | None = None) -> dict:
    """The loose twin's options: tightened(...) by 1/loosening(info), every tolerance × F, a fixed step × √F."""
    return tightened(options, info, 1.0 / loosening(info), roles)


def tightened(options: dict, info: dict, factor: float | None = None, roles: dict | None = None) -> dict:
    """A twin's options: the relative tolerance (the one the base run used, from its info) and the absolute
    or Newton tolerances, if given, divided by F (default tightening(info)); a fixed step divided by √F —
    the given one, or the base run's (info), with its Newton tolerances / F, when the solver has no rtol to
    derive them from (Exudyn's sheet). `roles`: the solver's option names per role (solvers.contract,
    rule 8; default: every registered solver's). A tolerance never goes below the floor the base run reports
    (info["<name>_floor"]: Exudyn's sheet, the round-off of its stiff connectors, under which Newton
    does not converge and every step is retried at a smaller step; a 12 × 12 sheet at E = E_m = 4.5e9 Pa
    ran 90× slower with its absolute tolerance at a quarter of the base run's)."""
    roles = contract.registered_roles() if roles is None else roles
    factor = tightening(info) if factor is None else factor
    tight = dict(options)
    relative = [name for name in roles["rtol"] if name in info]
    for name in relative:
        tight[name] = float(info[name]) / factor

    def divided(name, value):
        floor = float(info.get(f"{name}_floor") or 0.0)
        return max(value / factor, floor)

    for name in roles["tolerance"]:
        if options.get(name) is not None:
            value = options[name]
            tight[name] = divided(name, value) if not hasattr(value, "__len__") else [divided(name, v) for v in value]
    for name in roles["step"]:
        if options.get(name) is not None:
            tight[name] = options[name] / math.sqrt(factor)
        elif not relative and info.get(name) is not None:
            tight[name] = float(info[name]) / math.sqrt(factor)
            for tolerance in roles["tolerance"]:
                if options.get(tolerance) is None and info.get(tolerance):
                    tight[tolerance] = divided(tolerance, float(info[tolerance]))
    return tight


def held_at_floor(twin_options: dict, info: dict, roles: dict | None = None) -> list[str]:
    """The tolerances of a twin that its floor (info["<name>_floor"]) kept from tightening."""
    roles = contract.registered_roles() if roles is None else roles
    return [
        name
        for name in roles["tolerance"]
        if info.get(f"{name}_floor") and twin_options.get(name) == info[f"{name}_floor"]
    ]
