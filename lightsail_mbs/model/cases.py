"""The paper's cases by name (Sec. IV): ``paper_case`` and ``PAPER_CASES``, the fields of the shipped case files
in ``model/cases/``."""

from __future__ import annotations

from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import casefile
from lightsail_mbs.model.parameters import SailParameters, read_case_file


def paper_case(name: str, **changes) -> SailParameters:
    """The paper's cases by name (Sec. IV): 'rigid' (Fig. 5), 'torsion-stable' (Fig. 6),
    'torsion-soft' (Fig. 7), 'tnt-stable' (Fig. 10), 'tnt-soft' (Fig. 11). Their runs:
    :func:`lightsail_mbs.solvers.settings.paper_settings`."""
    if name not in PAPER_CASES:
        raise ParameterError(f"case={name!r} is invalid: allowed one of {', '.join(PAPER_CASES)}")
    return SailParameters(**{**PAPER_CASES[name], **changes})


PAPER_CASES = casefile.CaseFolder(
    ("rigid", "torsion-stable", "torsion-soft", "tnt-stable", "tnt-soft"), lambda path: read_case_file(path)[0]
)  # name -> the fields its case file (model/cases/NAME.toml) sets
