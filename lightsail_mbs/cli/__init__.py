"""`lightsail-mbs` command line: parse, call the library, print. One module per subcommand.

Every command checks what it will read and write before it computes. A foreseeable failure (a bad
parameter, a missing or foreign input file, an output path that cannot be written) ends the command
with one line on stderr naming the problem and exit status 2; an unforeseen error prints one line and
the file where its full traceback was written (exit status 1).
"""

from __future__ import annotations

import argparse
import importlib
import os
import re
import sys
import tempfile
import traceback
from datetime import datetime

from lightsail_mbs.base.validation import ParameterError

DESCRIPTION = """\
Does a laser-driven lightsail keep its shape under the beam, or crumple? lightsail-mbs simulates a sail (the
paper's chain of rigid slices held by torsion or tension springs, or a sheet of tiles) on two independent
solvers and answers with the time it fails (its defect has doubled) or that it does not, with the answer's
uncertainty; the closed-form theory, stability boundaries, Monte Carlo sweeps and the paper's figures too.

A case is given by options (--modulus 4.5e9, ...), over a case file or a saved run if one is named first:
  lightsail-mbs theory torsion-soft --save-case mine.toml
  lightsail-mbs simulate mine.toml --n 40 --out run.npz
  lightsail-mbs info run.npz
Each command's own options: lightsail-mbs COMMAND --help."""

# subcommand modules of this package; each defines register(subparsers) and sets `func`. Registering
# imports no more than the options need (numpy, the parameter classes): each command imports the
# library it calls inside its run(), so a command pays only for what it uses.
COMMANDS = [
    "theory",
    "simulate",
    "info",
    "render",
    "montecarlo",
    "reproduce",
    "crosscheck",
    "stability",
    "converge",
    "store",
    "optics",
    "journey",
    "export",
]


class Parser(argparse.ArgumentParser):
    """argparse's parser whose usage errors are one line (naming the option) and exit status 2, and which
    reads a negative number in scientific notation (``--thickness -1e-6``) as a value, not an option."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def build_parser() -> argparse.ArgumentParser:
    parser = Parser(prog="lightsail-mbs", description=DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--version", action="version", version=f"%(prog)s {_version()}")
    sub = parser.add_subparsers(dest="command", required=True, title="commands", metavar="COMMAND")
    for name in COMMANDS:
        importlib.import_module(f".{name}", __name__).register(sub)
    return parser


def _version() -> str:
    from importlib import metadata

    try:
        return metadata.version("lightsail-mbs")
    except metadata.PackageNotFoundError:
        return "(not installed)"


def main(argv=None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except ParameterError as exc:
        return _fail(str(exc))
    except BrokenPipeError:  # the reader of stdout went away (e.g. `| head`): no message, as other tools
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 1
    except OSError as exc:
        where = f"{exc.filename}: " if exc.filename else ""
        return _fail(f"{where}{exc.strerror or exc}")
    except KeyboardInterrupt:
        print("lightsail-mbs: interrupted", file=sys.stderr)
        return 130
    except Exception as exc:  # noqa: BLE001 - the last line of defence: one line, the traceback in a file
        if _is_run_file_error(exc):
            return _fail(str(exc))
        log = _write_traceback()
        print(f"lightsail-mbs: internal error: {type(exc).__name__}: {exc} (traceback in {log})", file=sys.stderr)
        return 1


def _is_run_file_error(exc: Exception) -> bool:
    """True for a RunFileError (a missing or foreign run file); result.py is loaded if one was raised."""
    result = sys.modules.get("lightsail_mbs.result")
    return result is not None and isinstance(exc, result.RunFileError)


def _fail(message: str) -> int:
    print(f"lightsail-mbs: error: {message}", file=sys.stderr)
    return 2


def _write_traceback() -> str:
    stamp = datetime.now().strftime("%Y%m%d-%H%M%S")
    with tempfile.NamedTemporaryFile("w", prefix=f"lightsail-mbs-{stamp}-", suffix=".log", delete=False) as log:
        traceback.print_exc(file=log)
    return log.name


if __name__ == "__main__":
    sys.exit(main())
