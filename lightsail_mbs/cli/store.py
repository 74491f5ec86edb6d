"""`lightsail-mbs store`: the state of a sweep's case store, without computing anything."""

from __future__ import annotations

import json
from pathlib import Path

from lightsail_mbs.base.validation import ParameterError


def register(sub) -> None:
    p = sub.add_parser("store", help="count a case store's current, stale, corrupt and incomplete records")
    p.add_argument("directory", help="a sweep's store folder (e.g. results/store/fig9)")
    p.add_argument("--json", action="store_true", help="print the keys by state as one JSON object")
    p.set_defaults(func=run)


def run(args) -> int:
    from lightsail_mbs.result import code_version
    from lightsail_mbs.studies.store import CaseStore

    if not Path(args.directory).is_dir():
        raise ParameterError(f"directory={args.directory!r} is invalid: allowed an existing store folder")
    found = CaseStore(args.directory).audit()
    if args.json:
        print(json.dumps(found))
        return 0
    print(f"{args.directory}: code version {code_version()}")
    for state, keys in found.items():
        print(f"  {state:10s} {len(keys)}")
    stale = sum(len(found[s]) for s in ("stale", "corrupt", "incomplete"))
    if stale:
        print(f"  {stale} record(s) will be recomputed by the next sweep that asks for them")
    return 0
