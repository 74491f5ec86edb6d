"""The whole acceleration: a Starshot-class sail (Parkin 2018's point design) and a lab-scale film.

Runs lightsail_mbs.paper.journey (see its docstring): writes journey.md (included by docs/journey.md),
journey_summary.csv, journey_starshot.{csv,png} and journey_lab-1000W-spot.{csv,png} into --out.
Usage: python scenarios/journey.py [--out DIR] [--quick] [--no-shape-runs]
"""

from lightsail_mbs.cli.options import scenario_parser
from lightsail_mbs.paper import journey

if __name__ == "__main__":
    parser = scenario_parser(__doc__, "n = 10, one lab power (smoke test)")
    parser.add_argument("--no-shape-runs", dest="shape_runs", action="store_false", help="skip the shape runs")
    args = parser.parse_args()
    journey.run(args.out, quick=args.quick, shape_runs=args.shape_runs)
