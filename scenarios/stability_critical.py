"""Critical E (torsion) and T (TnT) from short scaled runs, against a₀, Eqs 8/10 and the bisected 6 s map.

Runs lightsail_mbs.paper.stability_critical (see its docstring): writes stability_critical.png and
stability_critical_*.csv into --out. --solver is the solver of the map bisection (store OUT/store).
Usage: python scenarios/stability_critical.py [--out DIR] [--quick] [--store DIR] [--fig9 CSV] [--fig12 CSV]
"""

from lightsail_mbs.cli.options import scenario_parser
from lightsail_mbs.paper import stability_critical

if __name__ == "__main__":
    parser = scenario_parser(__doc__, "three a₀, two modes, no map bisection, short curves (smoke test)")
    parser.add_argument("--store", default=None, help="folder of the sweep store of the bisections [OUT/store]")
    parser.add_argument("--fig9", default=None, help="fig9_boundaries.csv of `reproduce --figure 9` to compare with")
    parser.add_argument("--fig12", default=None, help="fig12_boundaries.csv of `reproduce --figure 12` to compare with")
    args = parser.parse_args()
    stability_critical.run(
        args.out, solver=args.solver, quick=args.quick, store=args.store, fig9=args.fig9, fig12=args.fig12
    )
