"""The README's GIFs: the soft torsion sail (paper Fig. 7) and the rigid ν = 3/2 sail failing at its trough.

Runs lightsail_mbs.paper.animations (see its docstring): writes OUT/<case>.gif; the runs and frames go to
STORE/animations (--store, default OUT/store). Usage: python scenarios/animations.py [--out DIR] [--store DIR]
[--solver exudyn|reduced] [--cases NAME …] [--frames 60] [--size 600x300] [--fps 12] [--until-ratio 3] [--quick]
"""

from lightsail_mbs.cli.options import scenario_parser
from lightsail_mbs.paper import animations

if __name__ == "__main__":
    parser = scenario_parser(__doc__, "n = 10, 12 frames at 300x150 (smoke test)")
    parser.set_defaults(solver="exudyn")
    parser.add_argument(
        "--store", default=None, help="store root: runs (<case>.npz, reused) and frames in STORE/animations [OUT/store]"
    )
    parser.add_argument("--cases", nargs="+", default=list(animations.CASES), choices=list(animations.CASES))
    parser.add_argument("--frames", type=int, default=None, help="[60; quick 12]")
    parser.add_argument("--size", default=None, help="[600x300; quick 300x150]")
    parser.add_argument("--fps", type=float, default=animations.FPS)
    parser.add_argument(
        "--until-ratio", type=float, default=animations.UNTIL_RATIO, help="cut each run at this amplitude ratio [3]"
    )
    a = parser.parse_args()
    animations.run(
        a.out,
        solver=a.solver,
        quick=a.quick,
        store=a.store,
        cases=a.cases,
        frames=a.frames,
        size=a.size,
        fps=a.fps,
        until_ratio=a.until_ratio,
    )
