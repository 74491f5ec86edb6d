"""`lightsail-mbs converge`: the study as a command (JSON and Markdown out, n is not an option)."""

import json

from lightsail_mbs.cli import main


def test_converge_json_and_markdown(tmp_path, capsys):
    out = tmp_path / "rigid.md"
    code = main(["converge", "--case", "rigid", "--sizes", "10,20,40", "--no-noise", "--quiet", "--json",
                 "--markdown", str(out)])  # fmt: skip
    assert code == 0
    study = json.loads(capsys.readouterr().out)
    assert [row["n"] for row in study["rows"]] == [10, 20, 40] and study["ill_posed"] is True
    assert study["parameters"]["model"] == "rigid" and study["settings"]["t_final"] == 0.01
    assert "| 40 |" in out.read_text()


def test_converge_rejects_n(capsys):
    assert main(["converge", "--n", "30"]) == 2
    assert "n is varied" in capsys.readouterr().err


def test_converge_says_not_converging_on_the_uniform_beam_starshot_sail(capsys):
    args = (
        "converge --model torsion --length 3.2 --width 3.2 --thickness 100e-9 --density 2200 --modulus 70e9 "
        "--intensity 1e10 --defect-amplitude 1e-6 --sizes 30,60,120,240 --no-noise --quiet"
    ).split()
    assert main(args) == 0
    out = capsys.readouterr().out
    assert "Fit: not converging: ill-posed in n" in out and "no limit and no n for 1 %" in out
    assert "n for 1 % (fit)" not in out and "limit " not in out.split("Fit:")[1].split(":")[0]
