"""The sheet against the strip: critical modulus, Gaussian beam, stabilising edge tension.

Runs lightsail_mbs.paper.sheet_physics (see its docstring): writes sheet_physics.png,
sheet_physics_failure.png, sheet_physics.md and
sheet_physics_{twin,unlit,scan,modulus,horizon,resolution,tension,gaussian}.csv into --out; every run goes
through the store under --out, so a rerun resumes from the finished runs.
Usage: python scenarios/sheet_physics.py [--out DIR] [--quick] [--workers N]
"""

from lightsail_mbs.cli.options import scenario_parser
from lightsail_mbs.paper import sheet_physics

if __name__ == "__main__":
    parser = scenario_parser(__doc__, "one 6 × 6 grid, 1 s runs (smoke test)")
    parser.add_argument("--workers", type=int, default=None, help="processes [default: all cores]")
    args = parser.parse_args()
    sheet_physics.run(args.out, workers=args.workers, quick=args.quick)
