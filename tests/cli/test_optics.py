"""`lightsail-mbs optics`: grating tables by RCWA, the built-ins, info, and one-line errors."""

import json
import math

import numpy as np
import pytest

from lightsail_mbs.cli import main
from lightsail_mbs.model import optics, rcwa


@pytest.fixture(autouse=True)
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("LIGHTSAIL_MBS_CACHE", str(tmp_path / "cache"))
    return tmp_path / "cache" / "optics"


def test_grating_table_written_and_read_back(tmp_path, capsys, cache):
    out = tmp_path / "big.npz"
    args = ["optics", "grating", "--design", "bigrating", "--harmonics", "6", "--step", "5", "--tolerance", "0"]
    args += ["--grade", "2", "--out", str(out)]
    assert main(args) == 0
    assert "c_n(0)" in capsys.readouterr().out and len(list(cache.glob("rcwa-*.npz"))) == 1
    table = optics.OpticalTable.load(out)
    direct = rcwa.force_coefficients(rcwa.orders(rcwa.GRATINGS["bigrating"], 0.0, "TE", 6))
    assert (table.c_n[table.theta == 0][0], table.c_t[table.theta == 0][0]) == pytest.approx(direct, rel=1e-13)
    assert main(["optics", "info", str(out), "--angles", "0,7.5", "--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert info["kind"] == "grating" and info["harmonics"] == 6 and info["polarization"] == "TE"
    cn, ct = table.coefficients(np.radians([0.0, 7.5]))
    assert [v["c_n"] for v in info["values"]] == pytest.approx(cn, rel=1e-15)
    assert [v["c_t"] for v in info["values"]] == pytest.approx(ct, rel=1e-15)
    assert main(["optics", "info", str(out)]) == 0
    assert "Rayleigh" not in capsys.readouterr().err


def test_layer_specs_equal_the_simple_options(tmp_path):
    common = [
        "--period",
        "1.8e-6",
        "--harmonics",
        "5",
        "--step",
        "10",
        "--no-cache",
        "--tolerance",
        "0",
        "--grade",
        "0",
    ]
    simple = common + ["--bar-height", "0.4e-6", "--bar-index", "eps=12.25", "--fill-factor", "0.4"]
    simple += ["--film-thickness", "0.3e-6", "--film-index", "1.45", "--polarization", "mean"]
    layered = common + ["--layer", "0.4e-6,1,0.3:0.7=3.5", "--layer", "0.3e-6,1.45", "--polarization", "mean"]
    assert main(["optics", "grating", *simple, "--out", str(tmp_path / "a.npz")]) == 0
    assert main(["optics", "grating", *layered, "--out", str(tmp_path / "b.npz")]) == 0
    a, b = (optics.OpticalTable.load(tmp_path / f"{k}.npz") for k in "ab")
    assert a.metadata["geometry_key"] == b.metadata["geometry_key"]
    np.testing.assert_array_equal(a.c_n, b.c_n)
    # a symmetric cell, unpolarised: no sideways force at normal incidence
    assert abs(a.c_t[a.theta == 0][0]) < 1e-12


def test_builtin_tables(tmp_path):
    assert main(["optics", "mirror", "--out", str(tmp_path / "m.npz")]) == 0
    assert (
        main(["optics", "facet", "--reflectivity", "0.8", "--absorptivity", "0.1", "--out", str(tmp_path / "f.npz")])
        == 0
    )
    th = np.linspace(-1.5, 1.5, 31)
    for name, table in (("m", optics.mirror()), ("f", optics.facet(0.8, 0.1))):
        back = optics.OpticalTable.load(tmp_path / f"{name}.npz")
        np.testing.assert_array_equal(np.array(back.coefficients(th)), np.array(table.coefficients(th)))


@pytest.mark.parametrize(
    "args, name",
    [
        (["grating", "--design", "bigrating", "--out", "x.txt"], "--out"),
        (
            ["grating", "--period", "1e-6", "--bar-height", "1e-7", "--bars", "0.1:0.5,0.4:0.6", "--out", "x.npz"],
            "bars",
        ),
        (["grating", "--period", "1e-6", "--bar-height", "1e-7", "--fill-factor", "1.5", "--out", "x.npz"], "fill"),
        (["grating", "--period", "1e-6", "--bar-height", "1e-7", "--out", "x.npz"], "--fill-factor"),
        (["grating", "--bar-height", "1e-7", "--fill-factor", "0.5", "--out", "x.npz"], "--period"),
        (
            [
                "grating",
                "--design",
                "bigrating",
                "--bar-height",
                "1e-7",
                "--fill-factor",
                "0.5",
                "--bar-index",
                "kryptonite",
                "--out",
                "x.npz",
            ],
            "--bar-index",
        ),
        (["grating", "--design", "bigrating", "--layer", "1e-7", "--out", "x.npz"], "--layer"),
        (["grating", "--design", "bigrating", "--theta-max", "95", "--out", "x.npz"], "theta_max"),
        (["grating", "--design", "bigrating", "--harmonics", "0", "--out", "x.npz"], "harmonics"),
        (["facet", "--reflectivity", "0.9", "--absorptivity", "0.2", "--out", "x.npz"], "absorptivity"),
        (["info", "missing.npz"], "no such"),
    ],
)
def test_errors_are_one_line_and_name_the_option(tmp_path, capsys, monkeypatch, args, name):
    monkeypatch.chdir(tmp_path)
    assert main(["optics", *args]) == 2
    err = capsys.readouterr().err
    assert err.startswith("lightsail-mbs: error:") and name in err and err.count("\n") == 1
    assert not list(tmp_path.glob("x.*"))


def test_theta_range_and_step_reach_the_table(tmp_path):
    out = tmp_path / "t.npz"
    args = ["--design", "symmetric", "--harmonics", "4", "--theta-max", "30", "--step", "3", "--no-cache"]
    args += ["--tolerance", "0"]
    assert main(["optics", "grating", *args, "--out", str(out)]) == 0
    table = optics.OpticalTable.load(out)
    assert table.theta_range == pytest.approx((-math.radians(30), math.radians(30)))
    assert np.max(np.diff(table.theta)) <= math.radians(3) + 1e-15


def test_simulate_takes_a_table_and_refuses_a_bad_one(tmp_path, capsys):
    """simulate --optics: the mirror table's run is the Eq. (11) run's, a grating's is not, and a missing or
    foreign file is one line naming the option before any solving."""
    from lightsail_mbs import Result

    out = tmp_path / "big.npz"
    grating = ["optics", "grating", "--design", "bigrating", "--harmonics", "6", "--step", "5", "--tolerance", "0"]
    assert main([*grating, "--grade", "2", "--out", str(out)]) == 0
    base = ["simulate", "--solver", "reduced", "--n", "8", "--t-final", "0.02", "--quiet"]
    runs = {}
    for name, extra in {"eq11": [], "mirror": ["--optics", "mirror"], "grating": ["--optics", str(out)]}.items():
        assert main([*base, *extra, "--out", str(tmp_path / name)]) == 0
        runs[name] = Result.load(tmp_path / f"{name}.npz")
    assert runs["grating"].params.optics == str(out)
    assert np.array_equal(runs["eq11"].theta, runs["mirror"].theta)
    assert not np.allclose(runs["eq11"].x, runs["grating"].x, rtol=0, atol=1e-6)  # c_t(0) ≠ 0 drives it sideways
    capsys.readouterr()
    (tmp_path / "junk.npz").write_text("junk")
    for bad in (tmp_path / "missing.npz", tmp_path / "junk.npz"):
        assert main([*base, "--optics", str(bad)]) == 2
        err = capsys.readouterr().err.strip()
        assert err.startswith("lightsail-mbs: error: optics=") and "\n" not in err


def test_payload_and_curved_rest_options_make_the_case():
    from lightsail_mbs import SailParameters
    from lightsail_mbs.cli import build_parser
    from lightsail_mbs.cli.options import params_from_args

    args = ["simulate", "--n", "9", "--billow-radius", "2", "--billow-rest", "--payload-mass", "1e-3"]
    args += ["--payload-stem", "6", "--payload-inertia", "1e-6", "--optics", "mirror"]
    p = params_from_args(build_parser().parse_args(args))
    assert p == SailParameters(
        n=9,
        billow_radius=2.0,
        billow_rest=True,
        payload_mass=1e-3,
        payload_stem=6.0,
        payload_inertia=1e-6,
        optics="mirror",
    )
    assert main(["simulate", "--payload-stem", "6", "--t-final", "0.01"]) == 2  # a stem without a payload


def test_wavelengths_option_writes_one_table_with_the_axis(tmp_path, capsys):
    """--wavelengths START:STOP:COUNT: one version 2 file; each wavelength's table is the one --wavelength
    alone gives (Si evaluated there); info shows the axis; a laser outside the range and a decreasing list
    are one-line errors."""
    out, one = tmp_path / "spectrum.npz", tmp_path / "one.npz"
    common = ["optics", "grating", "--period", "1.8e-6", "--bar-height", "0.4e-6", "--bar-index", "Si"]
    common += ["--fill-factor", "0.4", "--harmonics", "4", "--theta-max", "10", "--step", "5", "--tolerance", "0"]
    assert main([*common, "--wavelength", "1.25e-6", "--wavelengths", "1.2e-6:1.3e-6:3", "--out", str(out)]) == 0
    assert "wavelength axis of 3 wavelengths" in capsys.readouterr().out
    spectrum = optics.read_spectrum(out)
    assert spectrum.wavelengths.tolist() == pytest.approx([1.2e-6, 1.25e-6, 1.3e-6], rel=1e-15)
    assert main([*common, "--wavelength", "1.3e-6", "--out", str(one)]) == 0
    assert spectrum.tables[2].digest == optics.OpticalTable.load(one).digest
    assert optics.OpticalTable.load(out).digest == spectrum.tables[1].digest  # the laser's, 1.25 µm
    assert main(["optics", "info", str(out)]) == 0
    assert "wavelength axis: 3 wavelengths" in capsys.readouterr().out
    assert main([*common, "--wavelength", "1.1e-6", "--wavelengths", "1.2e-6", "1.3e-6", "--out", str(out)]) == 2
    assert "--wavelength=1.1e-06 is invalid" in capsys.readouterr().err
    assert main([*common, "--wavelengths", "1.3e-6", "1.2e-6", "--out", str(out)]) == 2
    assert "--wavelengths=" in capsys.readouterr().err
