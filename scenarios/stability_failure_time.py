"""Failure-time law t_f = F(r, ν) t_c of the unstable regime, held against scaled runs.

Runs lightsail_mbs.paper.stability_failure_time (see its docstring): writes stability_failure_time.png and
stability_failure_time_*.csv into --out. The scaled runs integrate the reduced equations (--solver is not
used). Usage: python scenarios/stability_failure_time.py [--out DIR] [--quick]
"""

from lightsail_mbs.cli.options import scenario_parser
from lightsail_mbs.paper import stability_failure_time

if __name__ == "__main__":
    args = scenario_parser(__doc__, "fewer thicknesses, amplitudes, ratios and n (smoke test)").parse_args()
    stability_failure_time.run(args.out, quick=args.quick)
