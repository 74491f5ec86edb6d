"""Spinning sails in the beam: the rigid criterion, a stiff and a flexible disc across it, the two solvers,
and maps of the ride verdict with a movie of a spinning sail riding.

Tables: lightsail_mbs.paper.spinning_beam.write (see its docstring) writes spinning_beam.md into --out;
maps: lightsail_mbs.paper.spinning_maps.write writes spinning_maps.md, .png, .csv and spinning_ride.gif
(its sweep store in OUT/store/spinning_maps: a rerun reads the finished cases); --only movie makes
spinning_ride.gif alone (lightsail_mbs.paper.spinning_maps.movie).
Usage: python scenarios/spinning_beam.py [--out DIR] [--quick] [--only tables|maps|movie] [--workers N]
"""

from pathlib import Path

from lightsail_mbs.cli.options import scenario_parser
from lightsail_mbs.paper import spinning_beam, spinning_maps

if __name__ == "__main__":
    parser = scenario_parser(__doc__, "short runs and 2 × 2 maps (smoke test)")
    parser.add_argument("--only", choices=("tables", "maps", "movie"), help="one part only [default: tables and maps]")
    parser.add_argument("--workers", type=int, help="local processes of the maps' sweep [default: all cores]")
    args = parser.parse_args()
    if args.only == "movie":
        print(spinning_maps.movie(Path(args.out), quick=args.quick))
    if args.only in (None, "tables"):
        print(spinning_beam.write(args.out, quick=args.quick))
    if args.only in (None, "maps"):
        print(spinning_maps.write(args.out, workers=args.workers, quick=args.quick))
