"""Spinning sails in the beam: the rigid criterion, a stiff and a flexible disc across it, the two solvers.

Runs lightsail_mbs.paper.spinning_beam.write (see its docstring): writes spinning_beam.md into --out.
Usage: python scenarios/spinning_beam.py [--out DIR] [--quick]
"""

from lightsail_mbs.cli.options import scenario_parser
from lightsail_mbs.paper import spinning_beam

if __name__ == "__main__":
    args = scenario_parser(__doc__, "0.1 s and 0.05 s runs (smoke test)").parse_args()
    print(spinning_beam.write(args.out, quick=args.quick))
