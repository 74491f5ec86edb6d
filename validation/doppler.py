"""The Doppler shift inside time-domain runs: `nice -n 10 python validation/doppler.py`.

Writes validation/doppler.md: the paper's soft torsion sail at 1e13 W/m² from β₀ = 0.1 and the journey's heated,
tension-relieved Starshot-class TnT snapshot from β₀ = 0.15, each run to failure by both solvers with the Doppler
term and at the constant sail-frame intensity of its start (lightsail_mbs.paper.doppler, whose docstring
states the cases). tests/paper/test_doppler.py asserts the agreement.
"""

from pathlib import Path

from lightsail_mbs.paper.doppler import report

HEADER = """# The Doppler shift inside a run

Made by `nice -n 10 python validation/doppler.py` (lightsail_mbs.paper.doppler: the cases are stated there).
t_f: the failure time with the Doppler term from β₀, ± the solver's numerical uncertainty (twin runs); the
run at the constant intensity I₀D(β₀) of the start; shift = (t_f − t_f,const)/t_f,const; r t_f/4 the estimate
of a growth rate ∝ √I' (r = 2D₀g₀/c); g₀t_f/c with g₀ at the lab intensity.

"""

if __name__ == "__main__":
    out = Path(__file__).with_suffix(".md")
    out.write_text(HEADER + report())
    print(out.read_text())
