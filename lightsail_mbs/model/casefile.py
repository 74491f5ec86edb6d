"""Case files: a case, and optionally how to run it, as a TOML file with one table per section of the case.

::

    format = "lightsail-mbs case"
    version = 2

    [sail]
    model = "torsion"

    [material]
    youngs_modulus = 4.5e+09  # Young's modulus E (Pa)

    [run]
    t_final = 6.0

The tables are the case's sections (:data:`~lightsail_mbs.model.fields.SECTIONS`), each holding the fields
of :class:`~lightsail_mbs.model.parameters.SailParameters` that its FIELDS entry puts there (a field left
out keeps its default); the optional ``[run]`` table holds those of
:class:`~lightsail_mbs.solvers.settings.RunSettings`. Version 1 files, the case's fields flat at the top,
are read too; ``format`` and ``version`` may be left out of a hand-written file (a file with section
tables is then version 2, one without version 1); a file of a newer version is refused. Reading checks
names, tables and types here (:func:`read`); the values' ranges, and that a field the case's model does
not use keeps its default, are checked by the classes built from them. Every problem is one line naming
the file, the key and what is allowed (:class:`CaseFileError`). Older names of fields (LEGACY_NAMES) are
read as the fields. An optical table's path (``optics``) is relative to the case file's folder, as written.

The paper's cases ship as case files in the folder ``cases`` next to this module (:class:`CaseFolder`).
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
from collections.abc import Mapping
from pathlib import Path

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

from lightsail_mbs.model.fields import FIELDS, SECTIONS, close_match, number
from lightsail_mbs.model.records import LEGACY_NAMES, RUN_FIELDS

FORMAT = "lightsail-mbs case"
VERSION = 2  # 1: the case's fields flat at the top; 2: in section tables
RUN_TABLE = "run"
PAPER_FOLDER = Path(__file__).with_name("cases")
KIND_TEXT = {"int": "an integer", "float": "a number", "bool": "true or false", "str": "a string"}


class CaseFileError(ValueError):
    """A case file that cannot be read: one line naming the file, the key and what is allowed."""


def read(path, fields: Mapping[str, tuple[str, str]]) -> tuple[dict, dict]:
    """(case, run) of a case file: the case's entries and those of its [run] table.

    fields maps each field name to (its type annotation, e.g. "float | None", and the text of its allowed
    values); a float field's integer value is read as a float. Raises CaseFileError for a missing or
    unreadable file, a TOML syntax error, a foreign format, a newer version, an unknown key or table, or
    a value of the wrong type."""
    path = Path(path)
    try:
        with path.open("rb") as handle:
            data = tomllib.load(handle)
    except FileNotFoundError:
        raise CaseFileError(f"{path}: no such file (expected a case file, .toml)") from None
    except IsADirectoryError:
        raise CaseFileError(f"{path}: a folder, allowed a case file (.toml)") from None
    except OSError as exc:
        raise CaseFileError(f"{path}: cannot read it ({exc.strerror or exc})") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise CaseFileError(f"{path}: not valid TOML ({exc})") from None
    version = _check_format(path, data)
    run = data.pop(RUN_TABLE, {})
    if not isinstance(run, dict):
        raise CaseFileError(f"{path}: {RUN_TABLE} = {run!r} is invalid: allowed a [run] table")
    case, keys = {}, {}
    for where, key, value in _flat(path, data, fields) if version == 1 else _sectioned(path, data, fields):
        name = LEGACY_NAMES.get(key, key)  # an older name of a field reads as the field
        if name in keys:
            raise CaseFileError(
                f"{path}: {keys[name]} and {where + key} are the same field ({name}): allowed one of them"
            )
        keys[name], case[name] = where + key, _typed(path, where + key, value, *fields[name])
    optics = case.get("optics")
    if isinstance(optics, str) and optics not in ("", "mirror") and not Path(optics).is_absolute():
        case["optics"] = str(path.parent / optics)  # a table file's path is relative to the case file's folder
    for key, value in run.items():
        if key not in RUN_FIELDS:
            hint = close_match(key, RUN_FIELDS)
            raise CaseFileError(
                f"{path}: unknown key {RUN_TABLE}.{key}{hint}: allowed in [run] {', '.join(RUN_FIELDS)}"
            )
        boolean = key == "stop_at_failure"
        if isinstance(value, bool) != boolean or not isinstance(value, (bool, int, float)):
            allowed = "true or false" if boolean else "a number"
            raise CaseFileError(f"{path}: {RUN_TABLE}.{key} = {_shown(value)} is invalid: allowed {allowed}")
    return case, run


def write(path, case: Mapping, run: Mapping | None = None, comments: Mapping[str, str] | None = None) -> Path:
    """Write a case file: the format entries, case's entries (None left out) each with its comment in the
    table of its section, and run's entries as a [run] table. Returns the path."""
    comments = comments or {}
    tables = {name: [] for name in SECTIONS}
    for key, value in case.items():
        if value is not None:
            note = f"  # {comments[key]}" if key in comments else ""
            tables[FIELDS[key].group].append(f"{key} = {_value(value)}{note}")
    tables[RUN_TABLE] = [f"{key} = {_value(value)}" for key, value in (run or {}).items() if value is not None]
    lines = [f"format = {_value(FORMAT)}", f"version = {VERSION}"]
    for name, entries in tables.items():
        if entries:
            lines += ["", f"[{name}]", *entries]
    path = Path(path)
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def write_case(path, params, settings=None) -> Path:
    """Write the case file of params (a SailParameters: its case_fields, each with its help as a comment)
    and of settings (a RunSettings, or None) as its [run] table."""
    notes = {k: f"{v.help} ({v.unit})" if v.unit else v.help for k, v in FIELDS.items()}
    case = case_fields(params)
    if params.optics_file:  # the table's path from the case file's folder, as read() takes it
        table, folder = Path(params.optics).resolve(), Path(path).resolve().parent
        try:
            case["optics"] = os.path.relpath(table, folder)
        except ValueError:  # on another drive
            case["optics"] = str(table)
    return write(path, case, settings.to_dict() if settings else None, notes)


def case_fields(params) -> dict:
    """The fields a case file holds: all but those that are None, those of the other model family at their
    defaults, and those whose default follows other fields (bending, beam_centre) at that default."""
    followed = type(params)(model=params.model, length=params.length)
    family = "sheet" if params.model == "sheet" else "chain"
    out = {}
    for f in dataclasses.fields(params):
        value, info = getattr(params, f.name), FIELDS[f.name]
        if value is None or (info.family not in ("all", family) and value == f.default):
            continue
        if info.follows is None or value != getattr(followed, f.name):
            out[f.name] = value
    return out


class CaseFolder(Mapping):
    """Case files in a folder by name (NAME.toml), in the given order; each is read, by read_case(path),
    when it is asked for."""

    def __init__(self, names, read_case, folder: Path = PAPER_FOLDER):
        self._names, self._read, self.folder = tuple(names), read_case, Path(folder)

    def path(self, name: str) -> Path:
        return self.folder / f"{name}.toml"

    def __getitem__(self, name):
        if name not in self._names:
            raise KeyError(name)
        return self._read(self.path(name))

    def __iter__(self):
        return iter(self._names)

    def __len__(self) -> int:
        return len(self._names)

    def __contains__(self, name) -> bool:
        return name in self._names


def _check_format(path: Path, data: dict) -> int:
    """The file's version (checked), its format and version entries taken out of data; a file without a
    version is version 2 if it has a section table, else 1."""
    found = data.pop("format", FORMAT)
    if found != FORMAT:
        raise CaseFileError(f"{path}: format = {_shown(found)} is invalid: allowed {_value(FORMAT)}")
    sectioned = any(key in SECTIONS and isinstance(value, dict) for key, value in data.items())
    version = data.pop("version", 2 if sectioned else 1)
    if isinstance(version, bool) or not isinstance(version, int) or not 1 <= version <= VERSION:
        newer = isinstance(version, int) and not isinstance(version, bool) and version > VERSION
        allowed = f"an integer ≤ {VERSION}" if newer else f"an integer 1 … {VERSION}"
        raise CaseFileError(
            f"{path}: version = {_shown(version)} is invalid: allowed {allowed} (this lightsail-mbs reads case "
            f"files up to version {VERSION}" + ("; a newer one wrote this file)" if newer else ")")
        )
    return version


def _flat(path: Path, data: dict, fields):
    """(where, key, value) of a version 1 file: the case's fields at the top."""
    for key, value in data.items():
        if key in RUN_FIELDS:
            raise CaseFileError(f"{path}: {key} at the top is invalid: allowed in [{RUN_TABLE}] ({RUN_TABLE}.{key})")
        if LEGACY_NAMES.get(key, key) not in fields:
            raise CaseFileError(f"{path}: {_unknown(key, value, fields)}")
        yield "", key, value


def _sectioned(path: Path, data: dict, fields):
    """(where, key, value) of a version 2 file: each field in the table of its section."""
    tables = ", ".join(f"[{name}]" for name in (*SECTIONS, RUN_TABLE))
    for table, entries in data.items():
        if not isinstance(entries, dict):
            name = LEGACY_NAMES.get(table, table)
            if name in fields:
                raise CaseFileError(
                    f"{path}: {table} at the top is invalid: allowed in [{FIELDS[name].group}] (a version 2 file "
                    "holds each field in the table of its section)"
                )
            raise CaseFileError(f"{path}: unknown key {table}: allowed format, version and the tables {tables}")
        if table not in SECTIONS:
            raise CaseFileError(f"{path}: unknown table [{table}]{close_match(table, SECTIONS)}: allowed {tables}")
        for key, value in entries.items():
            name = LEGACY_NAMES.get(key, key)
            if key in RUN_FIELDS:
                raise CaseFileError(
                    f"{path}: {table}.{key} is in the wrong table: allowed in [{RUN_TABLE}] ({RUN_TABLE}.{key})"
                )
            if name in fields and FIELDS[name].group != table:
                raise CaseFileError(
                    f"{path}: {table}.{key} is in the wrong table: allowed in [{FIELDS[name].group}] "
                    f"({FIELDS[name].group}.{name})"
                )
            if name not in fields:
                own = [n for n in fields if FIELDS[n].group == table]
                raise CaseFileError(
                    f"{path}: unknown key {table}.{key}{close_match(key, own)}: allowed in [{table}] {', '.join(own)}"
                )
            yield f"{table}.", key, value


def _typed(path: Path, key: str, value, annotation: str, allowed: str):
    """value if it has the field's type (an int as a float for a float field); CaseFileError otherwise."""
    kind = annotation.split("|")[0].strip()
    ok = {
        "bool": isinstance(value, bool),
        "int": isinstance(value, int) and not isinstance(value, bool),
        "float": isinstance(value, (int, float)) and not isinstance(value, bool),
        "str": isinstance(value, str),
    }[kind]
    if not ok:
        what = allowed if allowed.startswith(KIND_TEXT[kind]) else KIND_TEXT[kind] + (f", {allowed}" if allowed else "")
        raise CaseFileError(f"{path}: {key} = {_shown(value)} is invalid: allowed {what}")
    return float(value) if kind == "float" else value


def _unknown(key: str, value, fields) -> str:
    if isinstance(value, dict):
        tables = ", ".join(f"[{name}]" for name in (*SECTIONS, RUN_TABLE))
        return (
            f"unknown table [{key}]{close_match(key, SECTIONS)}: allowed in a version 1 file the fields at the top and "
            f"[run]; in version 2 {tables}"
        )
    return f"unknown key {key}{close_match(key, fields)}: allowed format, version, {', '.join(fields)}"


def _value(value) -> str:
    """A TOML literal of a flat scalar: true/false, an integer, a float, a basic string."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return number(value) if math.isfinite(value) else {math.inf: "inf", -math.inf: "-inf"}.get(value, "nan")
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)  # JSON's string escapes are TOML's basic-string escapes
    raise TypeError(f"not a flat scalar: {type(value).__name__}")


def _shown(value) -> str:
    try:
        return _value(value)
    except TypeError:
        return f"a {type(value).__name__} ({value!r})"[:80]
