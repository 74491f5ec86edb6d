"""The solver contract (solvers.contract) and its registry (solvers.registry): declarations that match the
modules, options checked before solving, one line for a solver without the case's family, the roles the
uncertainty estimate tightens by, capabilities."""

import inspect

import pytest

from lightsail_mbs import ParameterError, RunSettings, SailParameters, solve
from lightsail_mbs.analysis import linear_stability
from lightsail_mbs.solvers import SOLVERS, contract, twin_options

SHEET = SailParameters(model="sheet", n=4, ny=4, youngs_modulus=4.5e9)


def module_options(solver: contract.Solver) -> set:
    """The options a solver module's run accepts: its keyword parameters and its OPTIONS tuple."""
    module = solver.implementation()
    keywords = {
        name
        for name, parameter in inspect.signature(module.run).parameters.items()
        if parameter.kind is inspect.Parameter.KEYWORD_ONLY and name != "progress"
    }
    return keywords | set(getattr(module, "OPTIONS", ()))


@pytest.mark.parametrize("key", sorted(contract.REGISTRY))
def test_each_declaration_names_exactly_the_options_its_module_takes(key):
    solver = contract.REGISTRY[key]
    assert {option.name for option in solver.options} == module_options(solver)


@pytest.mark.parametrize("key", sorted(contract.REGISTRY))
def test_every_declared_capability_is_a_callable_of_its_package(key):
    """Rule 9: each capability is a known name and resolves to a callable of a module of the solver's own
    package (its run module or another), named as declared."""
    solver = contract.REGISTRY[key]
    package = "lightsail_mbs.solvers." + solver.module.split(".")[0]
    for name, target in [*solver.capabilities.items(), ("defaults", solver.defaults)]:
        assert name in contract.CAPABILITIES or name == "defaults"
        function = solver.capability(name) if name != "defaults" else solver.resolve(target)
        assert callable(function)
        assert function.__module__.startswith(package + ".")
        assert function.__name__ == target.split(":")[-1]


@pytest.mark.parametrize("key", sorted(contract.REGISTRY))
def test_default_options_name_every_option_of_the_schema(key):
    """Rule 10: the default options of a run are one value (or None: the integrator's choice) per option."""
    solver = contract.REGISTRY[key]
    params = SHEET if solver.family == "sheet" else SailParameters(n=6)
    defaults = solver.default_options(params, RunSettings(t_final=0.1))
    assert set(defaults) == {option.name for option in solver.options}
    assert defaults["perturbation"] == 0.0
    for option in solver.options:
        assert defaults[option.name] is None or option.check(defaults[option.name]), option.name


def test_default_options_are_the_values_a_run_takes():
    """The defaults a study reads are those the run records: the reduced chain's method and rtol, the
    Exudyn chain's generalized-α step (a run given it records it, fitted to the output grid)."""
    settings = RunSettings(t_final=0.02, output_interval=0.01)
    p = SailParameters(n=6, youngs_modulus=4.5e9)
    reduced = contract.lookup("reduced", p)
    run = solve(p, "reduced", settings, uncertainty=False)
    defaults = reduced.default_options(p, settings)
    assert (defaults["method"], defaults["rtol"]) == (run.info["method"], run.info["rtol"])
    assert defaults["atol"].min() == run.info["atol"]
    assert reduced.default_options(p, settings, method="Radau", rtol=1e-9)["rtol"] == 1e-9
    exudyn = contract.lookup("exudyn", p).default_options(p, settings, method="generalized-alpha")
    assert exudyn["method"] == "generalized-alpha" and exudyn["step_size"] > 0
    assert contract.lookup("exudyn", p).default_options(p, settings, method="DOPRI5")["step_size"] is None


def test_a_missing_capability_is_one_line():
    """A solver that lacks a capability, a family or a name each give one ParameterError line, before
    anything is imported or solved; an unknown capability cannot be declared."""
    for solver, name, words in (
        (("exudyn", "sheet"), "linearise", "the exudyn sheet solver has no capability 'linearise': it offers"),
        (("exudyn", "chain"), "linearise", "the exudyn chain solver has no capability 'linearise': it offers"),
        (("reduced", "chain"), "mass_stiffness", "the reduced chain solver has no capability 'mass_stiffness'"),
    ):
        with pytest.raises(ParameterError, match=words) as caught:
            contract.REGISTRY[solver].capability(name)
        assert "\n" not in str(caught.value)
    with pytest.raises(ParameterError, match="solver='nosuch' is invalid: allowed one of exudyn, reduced"):
        linear_stability.angular_frequencies(SailParameters(n=4), "nosuch")
    with pytest.raises(ParameterError, match="capability 'spin' is invalid: allowed one of statics"):
        contract.register(contract.Solver("spinner", "chain", "reduced.solver", (), {"spin": "run"}))
    assert ("spinner", "chain") not in contract.REGISTRY
    undeclared = contract.Solver("plain", "chain", "reduced.solver", ())
    with pytest.raises(ParameterError, match="the plain chain solver declares no default options"):
        undeclared.default_options(SailParameters(n=4), RunSettings())


def test_the_registry_names_both_solvers_for_both_families():
    assert SOLVERS == ("exudyn", "reduced")
    assert set(contract.REGISTRY) == {(s, f) for s in SOLVERS for f in contract.FAMILIES}


def test_options_are_checked_before_anything_is_solved(monkeypatch):
    """A value the schema refuses raises one line naming option and solver, and no run starts."""
    solver = contract.REGISTRY[("reduced", "chain")]
    monkeypatch.setattr(contract.Solver, "run", lambda *a, **k: pytest.fail("a run started"))
    for options, words in (
        ({"rtol": 2.0}, "rtol=2.0 is invalid for the reduced chain solver: allowed 0 < rtol < 1"),
        ({"method": "Euler"}, "method='Euler' is invalid"),
        ({"step_size": 1e-3}, "option 'step_size' is invalid for the reduced chain solver"),
        ({"perturbation": -1.0}, "perturbation=-1.0 is invalid"),
    ):
        with pytest.raises(ParameterError, match=words) as caught:
            solve(SailParameters(n=4), solver.name, RunSettings(t_final=0.01), **options)
        assert "\n" not in str(caught.value)


def test_a_solver_without_the_family_is_one_line_not_a_key_error():
    contract.register(contract.Solver("chainonly", "chain", "reduced.solver", ()))
    try:
        with pytest.raises(ParameterError, match="solver='chainonly' is invalid for a sheet") as caught:
            solve(SHEET, "chainonly", RunSettings(t_final=0.01))
        assert "allowed one of exudyn, reduced" in str(caught.value)
        with pytest.raises(ParameterError, match="registered for the chain family already"):
            contract.register(contract.Solver("chainonly", "chain", "reduced.solver", ()))
    finally:
        contract.REGISTRY.pop(("chainonly", "chain"))
    with pytest.raises(ParameterError, match="solver='nosuch' is invalid: allowed one of exudyn, reduced"):
        solve(SHEET, "nosuch")


def test_roles_drive_the_twins_as_the_option_names_did():
    """Each solver's own roles tighten its options as the names the estimate used to hold: rtol from the
    base run's info, a given step by √F, the Newton tolerances from info when there is no rtol."""
    exudyn_sheet = contract.REGISTRY[("exudyn", "sheet")].roles()
    info = {"method": "generalized-alpha", "step_size": 1e-3, "newton_rel_tol": 1e-8, "newton_abs_tol": 4e-12}
    tight = twin_options.tightened({}, info, 16.0, exudyn_sheet)
    assert tight == {"step_size": pytest.approx(2.5e-4), "newton_rel_tol": 1e-8 / 16, "newton_abs_tol": 4e-12 / 16}
    reduced_chain = contract.REGISTRY[("reduced", "chain")].roles()
    assert twin_options.tightened({"atol": 1e-9}, {"rtol": 1e-8, "method": "DOP853"}, None, reduced_chain) == {
        "rtol": pytest.approx(1e-10),
        "atol": pytest.approx(1e-11),
    }
    assert exudyn_sheet["perturbation"] == reduced_chain["perturbation"] == ("perturbation",)


def test_capabilities_are_called_through_the_contract():
    reduced_sheet = contract.REGISTRY[("reduced", "sheet")]
    frequencies = reduced_sheet.capability("eigenfrequencies")(SHEET.replace(edge_tension=1e-3), 3)
    assert len(frequencies) == 3
    with pytest.raises(ParameterError, match="has no capability 'linearise': it offers statics, eigenfrequencies"):
        contract.REGISTRY[("exudyn", "sheet")].capability("linearise")
