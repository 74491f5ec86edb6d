"""Does a finite modulus stabilise the doubly sinusoidal sheet for good? Long runs at 2–4 E_cr,max.

Runs lightsail_mbs.paper.sheet_physics.long_horizon (see its docstring): writes sheet_long_horizon.csv and
sheet_long_horizon.md into --out; every run goes through the store under --out, so a rerun resumes.
Usage: python scenarios/sheet_long_horizon.py [--out DIR] [--quick] [--workers N]
"""

from lightsail_mbs.cli.options import scenario_parser
from lightsail_mbs.paper import sheet_physics
from lightsail_mbs.solvers.settings import RunSettings

if __name__ == "__main__":
    parser = scenario_parser(__doc__, "one 6 × 6 grid, 2 s runs (smoke test)")
    parser.add_argument("--workers", type=int, default=None, help="processes [default: all cores]")
    args = parser.parse_args()
    options = (
        dict(grids=(6,), ratios=(2.0,), settings=RunSettings(t_final=2.0, output_interval=0.01)) if args.quick else {}
    )
    sheet_physics.long_horizon(args.out, workers=args.workers, **options)
