"""The case source of a command (its positional CASE): a case file, a saved run, or a paper case by name.

Each gives the case's fields and the run entries (its [run] table, or the saved run's settings); the
options given are applied over them (merged), and a bad entry is one line naming the source
(ParameterError). A saved run's fields are those a case file would hold (casefile.case_fields): a default
that follows other fields (bending, beam_centre) is left out at its followed value and so follows an option
that changes them.
"""

from __future__ import annotations

import argparse
import json
from dataclasses import dataclass
from pathlib import Path

from lightsail_mbs.model.casefile import case_fields
from lightsail_mbs.model.cases import PAPER_CASES
from lightsail_mbs.model.parameters import ParameterError, SailParameters, case_of, read_case_file
from lightsail_mbs.model.records import current_names


@dataclass(frozen=True)
class CaseSource:
    case: dict  # SailParameters fields
    run: dict  # RunSettings fields


def case_source(args: argparse.Namespace) -> CaseSource | None:
    """The command's case source (args.case_file), read once; None when the command was given none."""
    text = getattr(args, "case_file", None)
    if text is None:
        return None
    if getattr(args, "_case_source", None) is None:
        args._case_source = read_source(text)
    return args._case_source


def read_source(text: str) -> CaseSource:
    """The case and run of a case file (.toml), a saved run (.json or .npz) or a paper case's name."""
    path = Path(text)
    if not path.exists() and text in PAPER_CASES:
        path = PAPER_CASES.path(text)
    elif not path.exists():
        raise ParameterError(
            f"{text}: no such file (allowed a case file .toml, a saved run's .json or .npz, or a paper case: "
            f"{', '.join(PAPER_CASES)})"
        )
    if path.suffix == ".npz":
        from lightsail_mbs.result import Result

        saved = Result.load(path)
        return CaseSource(case_fields(saved.params), saved.settings.to_dict())
    if path.suffix == ".json":
        fields, run = _saved_run_json(path)
        return CaseSource(case_fields(case_of(path, **fields)), run)
    return CaseSource(*read_case_file(path))


def merged(source_name: str, build, source: dict, given: dict, section: str = ""):
    """build(**{**source, **given}): the source's entries with the options given over them; a ParameterError
    about an entry that no option gave is prefixed with the source's name (and section, e.g. "[run] ")."""
    try:
        return build(**{**source, **given})
    except ParameterError as exc:
        if str(exc).split("=", 1)[0] in given:
            raise
        raise ParameterError(f"{source_name}: {section}{exc}") from None


def _saved_run_json(path: Path) -> tuple[dict, dict]:
    """(case fields, settings) of a saved run's summary (RUN.json, written next to RUN.npz)."""
    from lightsail_mbs.result import FORMAT, FORMAT_VERSION

    try:
        summary = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, ValueError) as exc:
        raise ParameterError(f"{path}: not a saved run's summary (.json: {exc})") from None
    if not isinstance(summary, dict) or summary.get("format") != FORMAT or "parameters" not in summary:
        raise ParameterError(f"{path}: not a saved lightsail-mbs run's summary (the .json next to a run's .npz)")
    version = summary.get("format_version")
    if not isinstance(version, int) or version > FORMAT_VERSION:
        raise ParameterError(f"{path}: format_version {version!r} is invalid: allowed up to {FORMAT_VERSION}")
    parameters, settings = summary["parameters"], summary.get("settings") or {}
    names = {f for f in SailParameters.__dataclass_fields__}
    fields = current_names(parameters) if isinstance(parameters, dict) else {"parameters": parameters}
    unknown = sorted(set(fields) - names)
    if unknown or not isinstance(settings, dict):
        raise ParameterError(
            f"{path}: parameters {unknown[:1] or settings!r} are invalid: allowed SailParameters fields"
        )
    return fields, settings
