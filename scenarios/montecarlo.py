"""Random multi-mode defects: failure probability and failure-time spread against E.

Runs lightsail_mbs.paper.defects_montecarlo (see its docstring): writes montecarlo.png and montecarlo.csv
into --out. Usage: python scenarios/montecarlo.py [--out DIR] [--seeds N] [--solver reduced|exudyn] [--quick]
"""

from lightsail_mbs.cli.options import scenario_parser
from lightsail_mbs.paper import defects_montecarlo

if __name__ == "__main__":
    parser = scenario_parser(__doc__, "n = 10, 2 s runs (smoke test)")
    parser.add_argument("--seeds", type=int, default=defects_montecarlo.SEEDS, help="defects per E [50]")
    args = parser.parse_args()
    defects_montecarlo.run(args.out, seeds=args.seeds, solver=args.solver, quick=args.quick)
