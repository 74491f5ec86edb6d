"""The Starshot-class chain's whole journey to 0.2c as one time-domain run:
`nice -n 5 python validation/journey_benchmark.py [--n 10 20] [--solver reduced]`.

Writes validation/journey_benchmark.md: for each slice count n, the case of docs/journey.md (lightsail_mbs.paper.
journey.starshot_case: SiN, 3.63 m square, 1 g, framed at 100 N, a 1 mm defect; Parkin's power and 1 g payload,
carried) run from rest to β = 0.2 by lightsail_mbs.studies.journey_run.run_time_domain: the world line, the
Doppler dimming and the heated film's tension all inside the run. The table gives the run's wall time (the
machine's load at the time is not controlled: the figure is what this run took), its steps, the proper and lab
times at the target, the verdict, and the temperature, tension and margin at the start and at the end.
"""

import argparse
import os
import time
from pathlib import Path

from lightsail_mbs.paper.journey import PARKIN_PAYLOAD, parkin_power, starshot_case
from lightsail_mbs.studies.journey import JourneySettings
from lightsail_mbs.studies.journey_run import run_time_domain
from lightsail_mbs.studies.tables import markdown_table

HEADER = """# The Starshot-class journey in the time domain

Made by `nice -n 5 python validation/journey_benchmark.py{arguments}` on {cores} cores
(lightsail_mbs.studies.journey_run; the case is docs/journey.md's Starshot-class chain). Each row is one run from
rest to β = 0.2 with the sail's world line, the Doppler dimming and the heated film's tension inside the run.
Wall: the run's own wall time, on a machine shared with other jobs; CPU: the process's CPU time for the whole
journey (the table of the heated film included), which the other jobs' load does not inflate. T, N, margin: at the
start and at the target.

"""


def row(n: int, solver: str) -> dict:
    p = starshot_case(n)
    start = time.process_time()
    report = run_time_domain(p, JourneySettings(power=parkin_power(p), carried_mass=PARKIN_PAYLOAD), solver)
    cpu = time.process_time() - start
    first, last = report["snapshots"][0], report["snapshots"][-1]
    return {
        "n": n,
        "solver": solver,
        "wall (s)": f"{report['wall_time']:.0f}",
        "CPU (s)": f"{cpu:.0f}",
        "method": report["method"],
        "steps": report["steps"],
        "τ at end (s)": f"{last['tau']:.1f}",
        "t at end (s)": f"{last['t']:.1f}",
        "β at end": f"{last['beta']:.4f}",
        "verdict": report["verdict"]["verdict"],
        "T max start → end (K)": f"{first['temperature_max']:.0f} → {last['temperature_max']:.0f}",
        "N start → end (N)": f"{first['tension']:.2f} → {last['tension']:.2f}",
        "margin start → end": f"{first['margin']:.0f} → {last['margin']:.0f}",
        "largest amplitude ratio": f"{report['run']['max_amplitude_ratio']:.3g}",
    }


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, nargs="+", default=[10])
    parser.add_argument("--solver", default="reduced", choices=("reduced", "exudyn"))
    args = parser.parse_args()
    rows = [row(n, args.solver) for n in args.n]
    given = "".join(f" --n {' '.join(map(str, args.n))}" if args.n != [10] else "")
    given += f" --solver {args.solver}" if args.solver != "reduced" else ""
    text = HEADER.format(arguments=given, cores=os.cpu_count()) + markdown_table(rows) + "\n"
    out = Path(__file__).with_suffix(".md")
    out.write_text(text)
    print(text)
