"""Shared command-line options: the case (SailParameters) and the run control (RunSettings).

The case options are generated from the case's field table (lightsail_mbs.model.fields.FIELDS), one per
field, so none can be missing; a command that takes a case also takes a case source as its positional
argument (a case file, a saved run's .json or .npz, or a paper case's name, lightsail_mbs.cli.cases), which
the options then override, and --save-case FILE, which writes the case it runs.
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import tempfile
from pathlib import Path

from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import materials
from lightsail_mbs.model.cases import PAPER_CASES
from lightsail_mbs.model.fields import FIELDS, SECTIONS, number
from lightsail_mbs.model.parameters import SailParameters

# the options whose name is not --field-name
OPTION_NAMES = {"youngs_modulus": "--modulus", "defect_mode_y": "--mode-y"}
# option name -> (RunSettings field, type, help)
RUN_OPTIONS = {
    "--t-final": ("t_final", float, "final time (s)"),
    "--output-interval": (
        "output_interval",
        float,
        "output interval (s) [default: min(1 ms, t_final/1000), finer for a faster case]",
    ),
    "--failure-ratio": ("failure_ratio", float, "failure when amplitude ≥ ratio × initial"),
}
# the --solver option's help, before its default
SOLVER_HELP = "the solver: exudyn (Exudyn's multibody model) or reduced (the reduced-Lagrangian solver)"
# other spellings accepted for some options
ALIASES = {
    "--defect-amplitude": ["--amplitude"],
    "--defect-mode": ["--mode"],
    "--n": ["--nx"],
    "--defect-mode-count": ["--defect-modes"],
    "--modulus": ["--youngs-modulus"],
    "--mode-y": ["--defect-mode-y"],
}
# older spellings still accepted but not shown in --help
HIDDEN_ALIASES = {"--beam-centre": ["--beam-center"], "--beam-centre-y": ["--beam-center-y"]}
CASE_FIELDS = {f.name: f for f in dataclasses.fields(SailParameters)}
OPTION_TYPES = {"int": int, "float": float, "str": str}


def option_name(field: str) -> str:
    """The command-line option of a SailParameters field: --field-name, or its OPTION_NAMES spelling."""
    return OPTION_NAMES.get(field, "--" + field.replace("_", "-"))


def field_help(name: str) -> str:
    """A case option's help: what the field is, its unit, what is allowed, the models that use it (when not
    all: FieldInfo.models), and its default (or what the default follows)."""
    info, field = FIELDS[name], CASE_FIELDS[name]
    if info.follows:
        default = info.follows
    elif isinstance(field.default, bool):
        default = "on" if field.default else "off"
    else:
        default = number(field.default)
    unit = f" ({info.unit})" if info.unit else ""
    allowed = f"; allowed {info.allowed}" if info.allowed else ""
    used = (
        ""
        if info.family == "all"
        else f"; used only by the {', '.join(info.models)} model{'s' * (len(info.models) > 1)}"
    )
    return f"{info.help}{unit}{allowed}{used} [default: {default}]".replace("%", "%%")


def add_case_options(parser: argparse.ArgumentParser, run: bool = True) -> None:
    """The case source, --save-case and one option per case field (and, with run=True, the run options)."""
    parser.add_argument(
        "case_file",
        nargs="?",
        metavar="CASE",
        help="the case to start from: a case file (.toml), a saved run (.json or .npz: its case and run) or a "
        f"paper case ({', '.join(PAPER_CASES)}); the options below override it [default: the paper's torsion case]",
    )
    parser.add_argument(
        "--save-case", metavar="FILE", help="write the case (options applied) to this case file (.toml) and go on"
    )
    groups: dict[str, argparse._ArgumentGroup] = {}
    for name, field in CASE_FIELDS.items():
        info = FIELDS[name]
        if info.group not in groups:
            title = SECTIONS[info.group]
            heading = f"case [{info.group}]" + ("" if title == info.group else f": {title}")  # its case file table
            groups[info.group] = parser.add_argument_group(heading)
        kind = field.type.split("|")[0].strip()
        how = {"action": argparse.BooleanOptionalAction} if kind == "bool" else {"type": OPTION_TYPES[kind]}
        option = option_name(name)
        groups[info.group].add_argument(
            option, *ALIASES.get(option, []), dest=name, default=None, help=field_help(name), **how
        )
        for alias in HIDDEN_ALIASES.get(option, []):
            groups[info.group].add_argument(alias, dest=name, default=None, help=argparse.SUPPRESS, **how)
    if not run:
        return
    settings = RunSettings()
    g = parser.add_argument_group("run")
    for opt, (name, typ, text) in RUN_OPTIONS.items():
        default = "" if "[default" in text else f" [default: {number(getattr(settings, name))}]"
        g.add_argument(opt, dest=name, type=typ, default=None, help=text + default)
    g.add_argument(
        "--run-past-failure",
        dest="stop_at_failure",
        action="store_false",
        default=None,
        help="keep integrating after the amplitude has doubled",
    )


def params_from_args(args: argparse.Namespace, base: SailParameters | None = None) -> SailParameters:
    """The SailParameters of the given case options over the case source (args.case_file), or over base,
    or over the defaults; with --save-case, the case (and the run entries given) written to that file."""
    from lightsail_mbs.cli.cases import case_source, merged

    given = {k: getattr(args, k) for k in CASE_FIELDS if getattr(args, k, None) is not None}
    source = case_source(args)
    if source is not None and base is not None:
        raise ParameterError(f"{args.case_file}: a case source is invalid together with --case (give one)")
    if source is not None:
        params = merged(args.case_file, SailParameters, materials.fill(given, source.case), given)
    elif base is not None:
        params = base.replace(**materials.fill(given))
    else:
        params = SailParameters(**materials.fill(given))
    if getattr(args, "save_case", None):
        run = {**(source.run if source else {}), **_given_run(args)}
        path = writable_file(args.save_case, "--save-case", ".toml")
        params.to_toml(path, merged(args.case_file, RunSettings, run, _given_run(args), "[run] ") if run else None)
        print(f"wrote the case to {path}", file=sys.stderr)
    return params


def settings_from_args(args: argparse.Namespace, base: RunSettings | None = None) -> RunSettings:
    """The RunSettings of the given run options over the case source's [run] entries, or over base, or over
    the defaults."""
    from lightsail_mbs.cli.cases import case_source, merged

    given = _given_run(args)
    source = case_source(args)
    if source is not None and source.run:
        return merged(args.case_file, RunSettings, source.run, given, "[run] ")
    return base.replace(**given) if base is not None else RunSettings(**given)


def _given_run(args: argparse.Namespace) -> dict:
    names = [v[0] for v in RUN_OPTIONS.values()] + ["stop_at_failure"]
    return {k: getattr(args, k) for k in names if getattr(args, k, None) is not None}


def scenario_parser(doc: str, quick_help: str) -> argparse.ArgumentParser:
    """Options shared by the scenario scripts beyond the paper: --out (default ./results), --solver
    (default reduced), --quick (a smoke test, described by quick_help)."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument("--out", default="results", help="output folder of PNG and CSV files [default: results]")
    parser.add_argument(
        "--solver", choices=("reduced", "exudyn"), default="reduced", help=f"{SOLVER_HELP} [default: reduced]"
    )
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
