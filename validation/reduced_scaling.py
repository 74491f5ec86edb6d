"""Wall time of the reduced solver vs n at fixed simulated time (scaling table).

`python validation/reduced_scaling.py` prints Markdown tables for n = 10, 30, 100, 300, 1000 and
the fitted exponents p of CPU time ∝ n^p, per run and per right-hand-side call, for
* the rigid chain (paper Fig. 5 load, ν = 3/2, 4 ms: before failure for every n), whose step count
  hardly depends on n, so the exponent is the formulation's;
* the soft torsion chain (E = 4.5e9 Pa, 0.5 s), whose highest bending frequency
  ω_max ≈ 2√(k_T/J_G) ∝ n² would bound an explicit step; the method chosen from the stiffness
  (implicit Radau from n ≈ 90) keeps the step count flat (the table lists ω_max·t_final);
* with `--tnt`: the extensible TnT chain (T = 3.34e-3 N, 0.5 s, Radau).
`--tolerances` prints instead the convergence study behind the default tolerances (failure time
of the soft paper cases and the rigid case vs rtol). Each time is the minimum of `--repeats` runs
(CPU time of this process, robust to other load); the compiled code is warmed up first.
"""

import argparse
import functools
import math
import time

import numpy as np

from lightsail_mbs import RunSettings, paper_case, paper_settings
from lightsail_mbs import solve as solve_with_estimate

solve = functools.partial(solve_with_estimate, uncertainty=False)  # single runs: no error bars in this report


SIZES = (10, 30, 100, 300, 1000)


def timed(params, settings, repeats, **options):
    best, result = np.inf, None
    for _ in range(repeats):
        start = time.process_time()
        result = solve(params, "reduced", settings, **options)
        best = min(best, time.process_time() - start)
    return best, result


def highest_bending_frequency(p):
    """2√(k_T/J_G): the free-free chain's top torsion-spring mode (rad/s), 0 without springs."""
    return 2 * math.sqrt(p.torsional_stiffness / p.slice_inertia) if p.torsional_stiffness else 0.0


def scaling(cases, repeats):
    for label, (make, settings, sizes) in cases.items():
        print(
            f"\n### {label}\n\n| n | CPU time (s) | steps | RHS calls | µs per step | µs per RHS call "
            f"| ω_max·t |\n|---|---|---|---|---|---|---|"
        )
        walls, per_call, per_step = [], [], []
        for n in sizes:
            p = make(n)
            wall, r = timed(p, settings, repeats)
            walls.append(wall)
            per_call.append(wall / r.info["nfev"])
            per_step.append(wall / max(r.info["steps"], 1))
            print(
                f"| {n} | {wall:.3g} | {r.info['steps']} | {r.info['nfev']} | {1e6 * per_step[-1]:.1f} "
                f"| {1e6 * per_call[-1]:.2f} | {highest_bending_frequency(p) * settings.t_final:.3g} |",
                flush=True,
            )
        fit = [np.polyfit(np.log(sizes), np.log(v), 1)[0] for v in (walls, per_step, per_call)]
        print(
            f"\nfitted exponents: CPU time ∝ n^{fit[0]:.2f}; per step ∝ n^{fit[1]:.2f}; per RHS call ∝ n^{fit[2]:.2f}"
        )


def tolerances():
    print("| case | rtol | failure time (s) | change vs loosest | steps |\n|---|---|---|---|---|")
    for case, rtols in [
        ("torsion-soft", (1e-6, 1e-7, 1e-8, 1e-9, 1e-10)),
        ("tnt-soft", (1e-6, 1e-7, 1e-8, 1e-9)),
        ("rigid", (1e-8, 1e-9, 1e-10, 1e-11)),
    ]:
        reference = None
        for rtol in rtols:
            r = solve(paper_case(case), "reduced", paper_settings(case), rtol=rtol)
            reference = reference or r.failure_time
            print(
                f"| {case} | {rtol:g} | {r.failure_time:.6f} | {(r.failure_time - reference) / reference:+.1e} "
                f"| {r.info['steps']} |",
                flush=True,
            )


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--tnt", action="store_true", help="also the extensible TnT chain (Radau)")
    parser.add_argument("--tolerances", action="store_true", help="print the tolerance convergence study instead")
    args = parser.parse_args()
    if args.tolerances:
        tolerances()
        return
    short = RunSettings(t_final=0.01)
    solve(paper_case("torsion-soft", n=5), "reduced", short)  # load the compiled code
    cases = {
        "rigid, 4 ms": (lambda n: paper_case("rigid", n=n), RunSettings(t_final=0.004), SIZES),
        "soft torsion, 0.5 s": (lambda n: paper_case("torsion-soft", n=n), RunSettings(t_final=0.5), SIZES),
    }
    if args.tnt:
        solve(paper_case("tnt-stable", n=5), "reduced", short)
        cases["extensible TnT T = 3.34e-3 N, 0.5 s (Radau)"] = (
            lambda n: paper_case("tnt-stable", n=n),
            RunSettings(t_final=0.5),
            SIZES,
        )
    scaling(cases, args.repeats)


if __name__ == "__main__":
    main()
