"""Sphinx extension: the ``lightsail-mbs`` command-line reference, generated from its argparse parser.

1. The directive ``cli-reference`` imports the parser factory named by the configuration value
   ``cli_reference_parser`` (default ``lightsail_mbs.cli:build_parser``), prints the top-level help and
   then, for every subcommand, a section titled ``lightsail-mbs <command>`` holding the subcommand's
   one-line help and its full ``format_help()`` as a literal block.  Nested subcommands are walked
   recursively.  Help is rendered at a fixed width (``cli_reference_width`` columns, default 100) and
   without colour, so the page does not depend on the terminal of the machine that builds it.
2. Every ``lightsail-mbs …`` command line in a ``bash``/``console``/``shell`` code block of any page is
   parsed (never run) with the same parser; a line the parser rejects is a warning at that line, which
   ``sphinx-build -W`` turns into an error.  So the guides cannot drift from the CLI.  Switch the check
   off with ``cli_check_commands = False``; silence single warnings with
   ``suppress_warnings = ["cli.command"]``.

Use in a MyST page::

    ```{cli-reference}
    ```
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import io
import os
import shlex

from docutils import nodes
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective

logger = logging.getLogger(__name__)

SHELL_LANGUAGES = {"bash", "console", "shell", "sh", "shell-session"}
COMMAND_SEPARATORS = {"&&", "||", "|", ";", ">", ">>", "2>", "&"}


def load_parser(spec: str) -> argparse.ArgumentParser:
    """Call the factory ``module:function`` named by *spec* and return its parser."""
    module_name, _, function_name = spec.partition(":")
    factory = getattr(importlib.import_module(module_name), function_name or "build_parser")
    return factory()


@contextlib.contextmanager
def fixed_terminal(width: int):
    """Make argparse format for a terminal *width* columns wide, without colour."""
    saved = {key: os.environ.get(key) for key in ("COLUMNS", "NO_COLOR", "PYTHON_COLORS")}
    os.environ["COLUMNS"] = str(width + 2)  # HelpFormatter uses the terminal width minus 2
    os.environ["NO_COLOR"] = "1"
    os.environ["PYTHON_COLORS"] = "0"
    try:
        yield
    finally:
        for key, value in saved.items():
            if value is None:
                os.environ.pop(key, None)
            else:
                os.environ[key] = value


def subcommands(parser: argparse.ArgumentParser):
    """(name, one-line help, subparser) for every subcommand of *parser*, aliases once."""
    seen = set()
    for action in parser._actions:
        if not isinstance(action, argparse._SubParsersAction):
            continue
        helps = {choice.dest: choice.help or "" for choice in action._choices_actions}
        for name, subparser in action.choices.items():
            if id(subparser) in seen:
                continue
            seen.add(id(subparser))
            yield name, helps.get(name, ""), subparser


class CliReference(SphinxDirective):
    """Emit the help of the parser and of each of its subcommands (see the module docstring)."""

    has_content = False
    option_spec = {"parser": str, "width": int}

    def run(self) -> list[nodes.Node]:
        config = self.env.config
        spec = self.options.get("parser", config.cli_reference_parser)
        width = self.options.get("width", config.cli_reference_width)
        self.env.note_reread()  # the help texts live in the code: re-read this page every build
        try:
            parser = load_parser(spec)
        except Exception as exc:  # an import error must name itself in the build log, not crash it
            logger.warning(
                "cli-reference: cannot build the parser %s: %s",
                spec,
                exc,
                location=self.get_location(),
                type="cli",
                subtype="import",
            )
            return []
        with fixed_terminal(width):
            result: list[nodes.Node] = [self.help_block(parser)]
            result.extend(self.sections(parser))
        return result

    @staticmethod
    def help_block(parser: argparse.ArgumentParser) -> nodes.literal_block:
        text = parser.format_help().rstrip() + "\n"
        block = nodes.literal_block(text, text)
        block["language"] = "text"
        return block

    def sections(self, parser: argparse.ArgumentParser) -> list[nodes.section]:
        out = []
        for _name, summary, subparser in subcommands(parser):
            title = subparser.prog
            section = nodes.section(ids=[nodes.make_id("cli-" + title)], names=[nodes.fully_normalize_name(title)])
            section += nodes.title("", "", nodes.literal(title, title))
            if summary:
                section += nodes.paragraph(summary, summary)
            section += self.help_block(subparser)
            section.extend(self.sections(subparser))
            self.state.document.note_implicit_target(section, section)
            out.append(section)
        return out


def command_lines(text: str, program: str):
    """(line offset, argv) for every invocation of *program* in a shell snippet.

    Backslash continuations are joined, a leading ``$`` prompt is dropped, comments and anything after a
    command separator (``&&``, ``|``, ``;``, redirections) are cut off.
    """
    logical, start, pending = [], 0, ""
    for offset, raw in enumerate(text.splitlines()):
        if not pending:
            start = offset
        line = raw.rstrip()
        if line.endswith("\\"):
            pending += line[:-1] + " "
            continue
        logical.append((start, pending + line))
        pending = ""
    if pending:
        logical.append((start, pending))
    for offset, line in logical:
        line = line.strip()
        if line.startswith("$ "):
            line = line[2:].lstrip()
        if not line.startswith(program + " "):
            continue
        try:
            words = shlex.split(line, comments=True)
        except ValueError:
            continue
        argv = []
        for word in words[1:]:
            if word in COMMAND_SEPARATORS:
                break
            argv.append(word)
        yield offset, argv


def check_commands(app, doctree: nodes.document) -> None:
    """Parse every documented ``lightsail-mbs`` command line; warn where the parser rejects one."""
    if not app.config.cli_check_commands:
        return
    blocks = [node for node in doctree.findall(nodes.literal_block) if node.get("language", "") in SHELL_LANGUAGES]
    if not blocks:
        return
    parser = getattr(app, "_cli_reference_parser", None)
    if parser is None:
        try:
            parser = load_parser(app.config.cli_reference_parser)
        except Exception as exc:
            logger.warning(
                "cli check: cannot build the parser %s: %s",
                app.config.cli_reference_parser,
                exc,
                type="cli",
                subtype="import",
            )
            app.config.cli_check_commands = False
            return
        app._cli_reference_parser = parser
    program = parser.prog
    for block in blocks:
        for offset, argv in command_lines(block.astext(), program):
            stderr = io.StringIO()
            try:
                with contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
                    parser.parse_args(argv)
            except SystemExit as exc:
                if exc.code not in (0, None):
                    message = stderr.getvalue().strip().splitlines()
                    line = (block.line or 0) + 1 + offset  # block.line: the line of the opening fence
                    logger.warning(
                        "documented command does not parse: %s %s — %s",
                        program,
                        shlex.join(argv),
                        message[-1] if message else f"exit {exc.code}",
                        location=(app.env.docname, line),
                        type="cli",
                        subtype="command",
                    )


def setup(app):
    app.add_config_value("cli_reference_parser", "lightsail_mbs.cli:build_parser", "env")
    app.add_config_value("cli_reference_width", 100, "env")
    app.add_config_value("cli_check_commands", True, "env")
    app.add_directive("cli-reference", CliReference)
    app.connect("doctree-read", check_commands)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
