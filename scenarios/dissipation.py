"""Heat from material damping in the oscillating TnT sail against the tension.

Runs lightsail_mbs.paper.dissipation (see its docstring): writes dissipation.png and dissipation.csv into
--out. Usage: python scenarios/dissipation.py [--out DIR] [--beta S] [--solver reduced|exudyn] [--quick]
"""

from lightsail_mbs.cli.options import scenario_parser
from lightsail_mbs.paper import dissipation

if __name__ == "__main__":
    parser = scenario_parser(__doc__, "n = 10, 1 s runs (smoke test)")
    parser.add_argument("--beta", type=float, default=dissipation.BETA, help="material damping β (s) [1e-4]")
    args = parser.parse_args()
    dissipation.run(args.out, beta=args.beta, solver=args.solver, quick=args.quick)
