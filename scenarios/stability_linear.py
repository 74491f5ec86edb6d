"""Linearised flat accelerating sail, with and without the beam, from both solvers.

Runs lightsail_mbs.paper.stability_linear (see its docstring): writes stability_linear.png,
stability_linear.csv and stability_linear_exudyn_fd.csv into --out. Both solvers are always linearised
(--solver is not used). Usage: python scenarios/stability_linear.py [--out DIR] [--quick]
"""

from lightsail_mbs.cli.options import scenario_parser
from lightsail_mbs.paper import stability_linear

if __name__ == "__main__":
    args = scenario_parser(__doc__, "n = 10, three difference steps (smoke test)").parse_args()
    stability_linear.run(args.out, quick=args.quick)
