"""The pipelines behind the paper's figures, importable so that a regular install reproduces them.

Each module ``lightsail_mbs.paper.<name>`` has ``FIGURES`` (the paper's figure numbers it draws) and
``run(out, *, solver, workers, scheduler, quick, store, progress) -> dict``: it runs its cases through
the resumable sweep store, writes its PNG and CSV files into ``out``, prints the numbers it plotted and
returns them. ``lightsail-mbs reproduce --figure N`` calls it.
"""
from __future__ import annotations

import importlib

# paper figure number -> pipeline module of this package
PIPELINES = {5: "fig5", 6: "fig6_8", 7: "fig6_8", 8: "fig6_8", 9: "fig9", 10: "fig10_11", 11: "fig10_11",
             12: "fig12", **{k: "fig18_23" for k in range(18, 24)}}


def pipeline(name: str):
    """The pipeline module ``lightsail_mbs.paper.<name>``."""
    return importlib.import_module(f"{__name__}.{name}")
