"""`lightsail-mbs` command line: parse, call the library, print. One module per subcommand."""
from __future__ import annotations

import argparse
import importlib
import sys

from lightsail_mbs.model.parameters import ParameterError

# subcommand modules of this package; each defines register(subparsers) and sets `func`
COMMANDS = ["theory", "simulate", "render", "montecarlo", "reproduce", "crosscheck", "stability"]


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="lightsail-mbs", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    for name in COMMANDS:
        importlib.import_module(f".{name}", __name__).register(sub)
    return parser


def main(argv=None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except ParameterError as exc:
        print(f"lightsail-mbs: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("lightsail-mbs: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
