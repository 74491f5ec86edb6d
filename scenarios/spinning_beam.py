"""Spinning sails in the beam: the rigid criterion, a stiff and a flexible disc across it, the two solvers,
and maps of the ride verdict with a movie of a spinning sail riding.

Tables: lightsail_mbs.paper.spinning_beam.write (see its docstring) writes spinning_beam.md into --out;
maps: lightsail_mbs.paper.spinning_maps.write writes spinning_maps.md, .png, .csv and spinning_ride.gif
(its sweep store in OUT/store/spinning_maps: a rerun reads the finished cases).
Usage: python scenarios/spinning_beam.py [--out DIR] [--quick] [--only tables|maps] [--workers N]
"""

from lightsail_mbs.cli.options import scenario_parser
from lightsail_mbs.paper import spinning_beam, spinning_maps

if __name__ == "__main__":
    parser = scenario_parser(__doc__, "short runs and 2 × 2 maps (smoke test)")
    parser.add_argument("--only", choices=("tables", "maps"), help="one part only [default: both]")
    parser.add_argument("--workers", type=int, help="local processes of the maps' sweep [default: all cores]")
    args = parser.parse_args()
    if args.only != "maps":
        print(spinning_beam.write(args.out, quick=args.quick))
    if args.only != "tables":
        print(spinning_maps.write(args.out, workers=args.workers, quick=args.quick))
