"""A fast, deterministic stand-in for a solver, importable by sweep worker processes, and a held real one.

``fake_case`` fails when E < E_cr,max (paper Eq. 8), so the boundary of the fake map is known exactly.
Options (part of the case key): as_result (return a Result, not a dict), marker_dir (one file per
execution, to count them), sleep (s; stable_sleep for stable cases), raise_modes / error_modes /
crash_modes (modes ν that raise, return an error, kill the worker).

``held_solve`` runs the real solvers (``real_cases``) after leaving a marker that names the worker's
process and pausing, both set by environment variables (so the cases' keys are those of plain cases):
the fault tests kill that process in the middle of its case.

Run as a script, it runs a small fake sweep (the interrupted-sweep test kills it part-way), or with
``held STORE WORKERS [SCHEDULER]`` the real cases through ``held_solve``.
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


HOLD = "LIGHTSAIL_TEST_HOLD"  # seconds held_solve pauses before solving
MARKERS = "LIGHTSAIL_TEST_MARKERS"  # folder where held_solve leaves one <key>.<pid>.<uuid> file per execution


def held_solve(case):
    """The real solver of the case (studies.sweep.solve_case), after a marker naming this process in
    $LIGHTSAIL_TEST_MARKERS (if set) and a pause of $LIGHTSAIL_TEST_HOLD seconds."""
    from lightsail_mbs.studies.sweep import solve_case

    if os.environ.get(MARKERS):
        Path(os.environ[MARKERS], f"{case.key}.{os.getpid()}.{uuid.uuid4().hex}").touch()
    time.sleep(float(os.environ.get(HOLD, "0")))
    return solve_case(case)


def real_cases():
    """Six short real runs, full Results saved: four reduced and two Exudyn, soft to stiff torsion sails."""
    from lightsail_mbs.studies.sweep import Case

    return [
        Case(SailParameters(n=12, youngs_modulus=e), solver, save_result=True, settings=RunSettings(t_final=0.05))
        for solver, moduli in (("reduced", (4.5e9, 4.5e11, 4.5e13, 4.5e15)), ("exudyn", (4.5e9, 4.5e13)))
        for e in moduli
    ]


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

    if sys.argv[1] == "held":
        store, workers, scheduler = sys.argv[2], int(sys.argv[3]), (sys.argv[4:] or [None])[0]
        run_sweep(real_cases(), store, workers=workers, scheduler=scheduler, progress=False, case_function=held_solve)
    else:
        store, markers, sleep = sys.argv[1], sys.argv[2], float(sys.argv[3])
        run_sweep(small_sweep(markers, sleep), store, workers=2, progress=False, case_function=fake_case)
