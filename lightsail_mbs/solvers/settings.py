"""Run control: :class:`~lightsail_mbs.base.settings.RunSettings` (defined in the leaf layer, so that the
Result and every room below the solvers can carry it) and the runs of the paper's named cases."""

from __future__ import annotations

from lightsail_mbs.base.settings import FIELDS, MAX_SAMPLES, RunSettings
from lightsail_mbs.base.validation import ParameterError

__all__ = ["FIELDS", "MAX_SAMPLES", "RunSettings", "paper_settings"]


def paper_settings(name: str, **changes) -> RunSettings:
    """The run of the paper's named case (lightsail_mbs.model.cases.paper_case): 10 ms for the
    rigid sail (Fig. 5), 6 s for the torsion and TnT sails (Figs 6–8, 10–11)."""
    from lightsail_mbs.model.cases import PAPER_CASES

    if name not in PAPER_CASES:
        raise ParameterError(f"case={name!r} is invalid: allowed one of {', '.join(PAPER_CASES)}")
    return RunSettings(**{"t_final": 0.01 if name == "rigid" else 6.0, **changes})
