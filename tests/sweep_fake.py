"""A fast, deterministic stand-in for a solver, importable by sweep worker processes.

Fails when E < E_cr,max (paper Eq. 8), so the boundary of the fake map is known exactly.
Options (part of the case key): as_result (return a Result, not a dict), marker_dir (one file per
execution, to count them), sleep (s; stable_sleep for stable cases), raise_modes / error_modes /
crash_modes (modes ν that raise, return an error, kill the worker).
Run as a script, it runs a small sweep (the interrupted-sweep test kills it part-way).
Imported by the tests as ``tests.sweep_fake`` (tests/ is a package); as a script it needs only lightsail_mbs.
"""

import os
import sys
import time
import uuid
from collections import Counter
from pathlib import Path

import numpy as np

from lightsail_mbs import Result, RunSettings, SailParameters
from lightsail_mbs.model import theory


def fake_case(case):
    options = case.options
    if options.get("marker_dir"):
        Path(options["marker_dir"], f"{case.key}.{uuid.uuid4().hex}").touch()
    p = case.params
    threshold = theory.critical_modulus_max(p)
    failed = p.youngs_modulus < threshold
    sleep = options.get("sleep", 0.0)
    time.sleep(sleep if failed else options.get("stable_sleep", sleep))
    if p.defect_mode in options.get("raise_modes", ()):
        raise RuntimeError("fake solver blew up")
    if p.defect_mode in options.get("crash_modes", ()):
        os._exit(3)
    if options.get("as_result"):
        return fake_result(p, growth_rate=np.log(4.0) if failed else 0.0, settings=case.settings)
    return {
        "failed": bool(failed),
        "failure_time": 0.1 * p.youngs_modulus / threshold if failed else None,
        "error": "fake divergence" if p.defect_mode in options.get("error_modes", ()) else None,
        "threshold": threshold,
    }


def fake_result(p, growth_rate, settings=None):
    """A Result whose sine shape grows as exp(growth_rate · t) over 1 s (kept with the given run settings)."""
    t = np.linspace(0.0, 1.0, 21)
    x = np.tile((np.arange(p.n) + 0.5) / p.n * p.length, (t.size, 1))
    y = p.defect_amplitude * np.exp(growth_rate * t)[:, None] * np.sin(2 * np.pi * p.defect_mode * x / p.length)
    zero = np.zeros_like(x)
    settings = settings or RunSettings(t_final=1.0)
    return Result.from_trajectory(p, "fake", t, x, y, zero, zero, zero, zero, settings=settings)


def executions(marker_dir) -> Counter:
    """How many times each case key was executed (one marker file per execution)."""
    return Counter(name.split(".")[0] for name in os.listdir(marker_dir))


def small_sweep(marker_dir, sleep=0.0, **options):
    """12 torsion cases: 4 moduli × 3 thicknesses."""
    from lightsail_mbs.studies.sweep import Case

    return [
        Case(
            SailParameters(thickness=h, youngs_modulus=e),
            "fake",
            dict(marker_dir=str(marker_dir), sleep=sleep, **options),
        )
        for h in (1e-7, 1e-6, 1e-5)
        for e in (1e9, 1e11, 1e13, 1e15)
    ]


if __name__ == "__main__":
    from lightsail_mbs.studies.sweep import run_sweep

    store, markers, sleep = sys.argv[1], sys.argv[2], float(sys.argv[3])
    run_sweep(small_sweep(markers, sleep), store, workers=2, progress=False, case_function=fake_case)
