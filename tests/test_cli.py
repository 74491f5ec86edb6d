"""The command line as a user runs it: JSON output, clear one-line errors, no traceback."""
import json
import subprocess
import sys

import pytest


def cli(*args):
    return subprocess.run([sys.executable, "-m", "lightsail_mbs.cli", *args], capture_output=True, text=True)


def test_theory_json_paper_numbers():
    out = cli("theory", "--thickness", "1e-6", "--density", "1000", "--intensity", "1e8",
              "--amplitude", "1e-5", "--mode", "1.5", "--json")
    assert out.returncode == 0, out.stderr
    numbers = json.loads(out.stdout)
    assert numbers["e_cr_max"] == pytest.approx(4.5e11, rel=0.01)
    assert numbers["t_cr_max"] == pytest.approx(3.34e-6, rel=0.01)
    assert numbers["g0"] == pytest.approx(2e8 / (299_792_458.0 * 1e-3))


@pytest.mark.parametrize("args, name", [
    (["--thickness", "0"], "thickness"),
    (["--n", "1"], "n"),
    (["--modulus", "nan"], "youngs_modulus"),
    (["--model", "tnt", "--tension", "-1"], "tension"),
    (["--mode", "-2"], "mode"),
])
def test_bad_input_one_line_error(args, name):
    for command in ("theory", "simulate"):
        out = cli(command, *args)
        assert out.returncode != 0
        lines = out.stderr.strip().splitlines()
        assert len(lines) == 1 and name in lines[0] and "Traceback" not in out.stderr


def test_simulate_reports_heat_of_material_damping():
    out = cli("simulate", "--model", "torsion", "--n", "6", "--modulus", "4.5e15", "--intensity", "0",
              "--stiffness-damping", "3e-3", "--t-final", "0.2", "--solver", "reduced", "--quiet")
    assert out.returncode == 0, out.stderr
    heat = float(out.stdout.split("dissipated as heat:")[1].split()[0])
    assert heat > 0
