"""The studies of the paper and beyond it, as importable pipelines: a regular install reproduces them.

Two registers of pipeline modules ``lightsail_mbs.paper.<module>``:

* ``PIPELINES`` (paper figure number -> module): the paper's figures (Figs 5–12, 18–23). Each module
  has ``FIGURES``, the figure numbers it draws.
* ``SCENARIOS`` (name -> module): the studies beyond the paper — beam profile and optics, material
  damping, random defects, linear and finite-amplitude stability, failure-time law, the documentation's
  animations, the sheet against the strip.

Every pipeline has ``run(out, *, solver, workers, scheduler, quick, store, progress, **options) -> dict``:
it runs its cases (through the resumable sweep store, default OUT/store/<name>, where it has any),
writes its PNG/GIF and CSV files into ``out``, prints the numbers it plotted and returns them; ``quick``
is a smoke test, not the published numbers. ``lightsail-mbs reproduce --figure N`` and
``lightsail-mbs reproduce --scenario NAME`` call them; ``scenarios/NAME.py`` are short scripts around
the scenario pipelines with their own options.
"""

from __future__ import annotations

import importlib

# paper figure number -> pipeline module of this package
PIPELINES = {
    5: "fig5",
    6: "fig6_8",
    7: "fig6_8",
    8: "fig6_8",
    9: "fig9",
    10: "fig10_11",
    11: "fig10_11",
    12: "fig12",
    **{k: "fig18_23" for k in range(18, 24)},
}

# scenario name (scenarios/<name>.py) -> pipeline module of this package
SCENARIOS = {
    "beam_optics": "beam_optics",
    "dissipation": "dissipation",
    "montecarlo": "defects_montecarlo",
    "stability_linear": "stability_linear",
    "stability_critical": "stability_critical",
    "stability_failure_time": "stability_failure_time",
    "animations": "animations",
    "sheet_physics": "sheet_physics",
}


def pipeline(name: str):
    """The pipeline module ``lightsail_mbs.paper.<name>``."""
    return importlib.import_module(f"{__name__}.{name}")


def scenario(name: str):
    """The pipeline module of the scenario ``name`` (a key of SCENARIOS)."""
    from lightsail_mbs.base.validation import ParameterError

    if name not in SCENARIOS:
        raise ParameterError(f"scenario={name!r} is invalid: allowed one of {', '.join(SCENARIOS)}")
    return pipeline(SCENARIOS[name])
