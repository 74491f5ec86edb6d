"""Gaussian beams, partial reflectors and off-centre beams on the paper's torsion sail.

Runs lightsail_mbs.paper.beam_optics (see its docstring): writes beam_optics.png, beam_optics_profile.csv
and beam_optics_tilt.csv into --out. Usage: python scenarios/beam_optics.py [--out DIR]
[--solver reduced|exudyn] [--quick]
"""

from lightsail_mbs.cli.options import scenario_parser
from lightsail_mbs.paper import beam_optics

if __name__ == "__main__":
    args = scenario_parser(__doc__, "n = 10, 1 s runs (smoke test)").parse_args()
    beam_optics.run(args.out, solver=args.solver, quick=args.quick)
