"""Shared command-line options: the case (SailParameters) and the run control (RunSettings), one option
per field."""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model.parameters import SailParameters

# option name -> (SailParameters field, type, help)
CASE_OPTIONS = {
    "--model": ("model", str, "rigid | torsion | tnt | sheet"),
    "--n": ("n", int, "number of slices (sheet: tiles along L, also --nx)"),
    "--ny": ("ny", int, "sheet: tiles across the width W"),
    "--length": ("length", float, "sail length L (m)"),
    "--width": ("width", float, "sail width W (m)"),
    "--thickness": ("thickness", float, "thickness h (m)"),
    "--density": ("density", float, "density ρ (kg/m³)"),
    "--modulus": ("youngs_modulus", float, "Young's modulus E (Pa)"),
    "--tension": ("tension", float, "boundary tension T (N), TnT only"),
    "--intensity": ("intensity", float, "laser intensity I₀ (W/m²)"),
    "--defect-amplitude": ("defect_amplitude", float, "initial defect amplitude a₀ (m)"),
    "--defect-mode": ("defect_mode", float, "defect mode number ν (wavelengths over L)"),
    "--defect-seed": (
        "defect_seed",
        int,
        "an integer: a seeded random multi-mode defect of amplitude a₀ (modes ν = 1/2 … K/2); unset: the sine "
        "of --defect-mode",
    ),
    "--defect-mode-count": ("defect_mode_count", int, "multi-mode defect: modes ν_k = k/2, k = 1…K"),
    "--defect-spectrum": ("defect_spectrum", float, "multi-mode defect: mean amplitude ∝ ν^(−β)"),
    "--roughness": (
        "roughness",
        float,
        "seeded roughness (m) at every wavelength the slices or tiles carry, added to the defect",
    ),
    "--roughness-seed": ("roughness_seed", int, "seed of the roughness"),
    "--mode-y": (
        "defect_mode_y",
        float,
        "sheet: defect mode ν_y across the width, w = a₀ sin(2πνx/L) sin(2πν_y y/W); unset: uniform across W",
    ),
    "--membrane-modulus": ("membrane_modulus", float, "sheet: in-plane (membrane) modulus E_m (Pa); unset: E"),
    "--edge-tension": ("edge_tension", float, "sheet: follower tension on all four edges (N per metre of edge)"),
    "--billow-radius": ("billow_radius", float, "initial arc radius R_c (m), > 0 concave to the laser; inf = flat"),
    "--beam-waist": ("beam_waist", float, "Gaussian beam waist w (m); inf = uniform beam"),
    "--beam-center": ("beam_center", float, "Gaussian beam axis x_c (m); default L/2"),
    "--beam-center-y": ("beam_center_y", float, "sheet: Gaussian beam axis y_c (m); default W/2"),
    "--reflectivity": ("reflectivity", float, "specular reflectivity R"),
    "--absorptivity": ("absorptivity", float, "absorptivity α"),
    "--optics": (
        "optics",
        str,
        "the slices' force law from a table: 'mirror' or a table file (lightsail-mbs optics … --out); "
        "unset: the R/α law",
    ),
    "--optics-layout": (
        "optics_layout",
        str,
        "uniform | mirrored-halves (the right half carries the table turned over)",
    ),
    "--payload-mass": ("payload_mass", float, "payload on a rigid stem from the sail's middle, mass m_p (kg)"),
    "--payload-inertia": ("payload_inertia", float, "the payload's own inertia J_p (kg·m²)"),
    "--payload-stem": ("payload_stem", float, "stem length d from the sail's middle towards the laser (m)"),
    "--initial-tilt": ("initial_tilt", float, "the initial shape turned about the craft's centre of mass (rad)"),
    "--torsional-damping": ("torsional_damping", float, "torsional damping c_T (N·m·s/rad)"),
    "--axial-damping": ("axial_damping", float, "axial damping c_s (N·s/m)"),
    "--stiffness-damping": (
        "stiffness_damping",
        float,
        "material damping β (s): c = β k on every spring; loss factor η at ω: β = η/ω",
    ),
}
# option name -> (RunSettings field, type, help)
RUN_OPTIONS = {
    "--t-final": ("t_final", float, "final time (s)"),
    "--output-interval": ("output_interval", float, "output interval (s); default min(1 ms, t_final/1000)"),
    "--failure-ratio": ("failure_ratio", float, "failure when amplitude ≥ ratio × initial"),
}
# shorter spellings accepted for some options
ALIASES = {
    "--defect-amplitude": ["--amplitude"],
    "--defect-mode": ["--mode"],
    "--n": ["--nx"],
    "--defect-mode-count": ["--defect-modes"],
}


def add_case_options(parser: argparse.ArgumentParser, run: bool = True) -> None:
    """The case options (and, with run=True, the run options) on a parser."""
    defaults = SailParameters()
    g = parser.add_argument_group("case (defaults: the paper's torsion case)")
    for opt, (name, typ, text) in CASE_OPTIONS.items():
        g.add_argument(
            opt,
            *ALIASES.get(opt, []),
            dest=name,
            type=typ,
            default=None,
            help=f"{text} [default {getattr(defaults, name)}]",
        )
    g.add_argument(
        "--bending",
        dest="bending",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="torsional springs k_T = EI/l on/off [default: on for torsion, off for tnt as in the paper]",
    )
    g.add_argument(
        "--axial-springs",
        dest="axial_springs",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="TnT: extensible slices with k_s = (n−1)EhW/L, or their rigid limit [default on]",
    )
    g.add_argument(
        "--billow-rest",
        dest="billow_rest",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="torsion springs at rest on the billowed arc (a sail made curved) [default off: at rest flat]",
    )
    if not run:
        return
    settings = RunSettings()
    g = parser.add_argument_group("run")
    for opt, (name, typ, text) in RUN_OPTIONS.items():
        g.add_argument(opt, dest=name, type=typ, default=None, help=f"{text} [default {getattr(settings, name)}]")
    g.add_argument(
        "--run-past-failure",
        dest="stop_at_failure",
        action="store_false",
        default=None,
        help="keep integrating after the amplitude has doubled",
    )


def params_from_args(args: argparse.Namespace, base: SailParameters | None = None) -> SailParameters:
    """The SailParameters of the given case options (base's values, or the defaults, for the others)."""
    names = [v[0] for v in CASE_OPTIONS.values()] + ["bending", "axial_springs", "billow_rest"]
    given = {k: getattr(args, k) for k in names if getattr(args, k, None) is not None}
    return base.replace(**given) if base is not None else SailParameters(**given)


def settings_from_args(args: argparse.Namespace, base: RunSettings | None = None) -> RunSettings:
    """The RunSettings of the given run options (base's values, or the defaults, for the others)."""
    names = [v[0] for v in RUN_OPTIONS.values()] + ["stop_at_failure"]
    given = {k: getattr(args, k) for k in names if getattr(args, k, None) is not None}
    return base.replace(**given) if base is not None else RunSettings(**given)


def scenario_parser(doc: str, quick_help: str) -> argparse.ArgumentParser:
    """Options shared by the scenario scripts beyond the paper: --out (default ./results), --solver
    (default reduced), --quick (a smoke test, described by quick_help)."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument("--out", default="results", help="output folder of PNG and CSV files [results]")
    parser.add_argument("--solver", choices=("reduced", "exudyn"), default="reduced")
    parser.add_argument("--quick", action="store_true", help=quick_help)
    return parser


def writable_folder(folder, option: str) -> Path:
    """Create the folder if needed and prove it writable with a temporary file, before any computation;
    ParameterError naming the option otherwise."""
    folder = Path(folder)
    try:
        if folder.exists() and not folder.is_dir():
            raise NotADirectoryError(20, "not a folder")
        folder.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=folder):
            pass
    except OSError as exc:
        raise ParameterError(
            f"{option}={str(folder)!r} is invalid: cannot write there ({exc.strerror or exc})"
        ) from None
    return folder


def writable_file(path, option: str, suffix: str) -> Path:
    """The output file path with its suffix, in a writable folder (writable_folder), not a folder itself."""
    path = Path(path).with_suffix(suffix)
    if path.is_dir():
        raise ParameterError(f"{option}={str(path)!r} is invalid: a folder, allowed a file name")
    try:
        writable_folder(path.parent, option)
    except ParameterError as exc:
        raise ParameterError(
            f"{option}={str(path)!r} is invalid: cannot write to its folder "
            f"{str(exc).split('cannot write there ', 1)[-1]}"
        ) from None
    return path
