"""FlexSailSim's published case (1 m disc, 120 Hz, w = 0.4 D, 10 % offset, −2° tilt, 1 GW/m², 5 s) with bending.

Runs lightsail_mbs.paper.flexsail.write (see its docstring): runs the cases not yet saved, reads back the
others (--out/data/flexsail_*.npz), and writes flexsail.md into --out. --run NAME runs (or reads) only that case.
Usage: python scenarios/flexsail.py [--out DIR] [--quick] [--run NAME ...]
"""

from lightsail_mbs.cli.options import scenario_parser
from lightsail_mbs.paper import flexsail

if __name__ == "__main__":
    parser = scenario_parser(__doc__, "5 ms spans (smoke test)")
    parser.add_argument("--run", action="append", choices=sorted(flexsail.RUNS), help="only this case (repeatable)")
    args = parser.parse_args()
    print(flexsail.write(args.out, quick=args.quick, names=args.run))
