"""Wall time of the reduced solver vs n at fixed simulated time (issue 4 scaling table).

`python validation/reduced_scaling.py` prints a Markdown table for n = 10, 30, 100, 300, 1000 and
the fitted exponent p of wall ∝ n^p, for
* the rigid chain (paper Fig. 5 load, ν = 3/2, 4 ms: before failure for every n), whose step count
  does not depend on n, so the exponent is the formulation's;
* the soft torsion chain (E = 4.5e9 Pa, 0.5 s), whose highest bending frequency grows as n², so an
  explicit method's step count grows with n too (the exponent per right-hand-side call is also given).
Each time is the minimum of `--repeats` runs (CPU time of this process, robust to other load).
"""
import argparse
import time

import numpy as np

from lightsail_mbs import paper_case, solve

SIZES = (10, 30, 100, 300, 1000)


def timed(params, repeats):
    best, result = np.inf, None
    for _ in range(repeats):
        start = time.process_time()
        result = solve(params, "reduced")
        best = min(best, time.process_time() - start)
    return best, result


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    cases = {"rigid, 4 ms": lambda n: paper_case("rigid", n=n, t_final=0.004),
             "soft torsion, 0.5 s": lambda n: paper_case("torsion-soft", n=n, t_final=0.5)}
    for label, make in cases.items():
        print(f"\n### {label}\n\n| n | CPU time (s) | steps | RHS calls | µs per RHS call |\n|---|---|---|---|---|")
        walls, per_call = [], []
        for n in SIZES:
            wall, r = timed(make(n), args.repeats)
            walls.append(wall)
            per_call.append(wall / r.info["nfev"])
            print(f"| {n} | {wall:.3g} | {r.info['steps']} | {r.info['nfev']} | {1e6 * per_call[-1]:.0f} |", flush=True)
        p_wall = np.polyfit(np.log(SIZES), np.log(walls), 1)[0]
        p_call = np.polyfit(np.log(SIZES), np.log(per_call), 1)[0]
        print(f"\nfitted exponent: wall ∝ n^{p_wall:.2f}; per RHS call ∝ n^{p_call:.2f}")


if __name__ == "__main__":
    main()
