"""The help a user reads (lightsail-mbs COMMAND --help): every option says what it is and, when it has a
default, states it in one form, ``[default: …]``; defaults that follow other fields say so; numbers are written
as a user reads them (4.5e+13, not 45000000000000.0); the tension options name their unit per model."""

import argparse
import re

import pytest

from lightsail_mbs.cli import build_parser
from lightsail_mbs.cli.options import CASE_FIELDS, field_help, option_name
from lightsail_mbs.model.fields import FIELDS


def parsers():
    """(command line, parser) of every command and subcommand."""
    todo, found = [("lightsail-mbs", build_parser())], []
    while todo:
        name, parser = todo.pop()
        found.append((name, parser))
        for action in parser._actions:
            if isinstance(action, argparse._SubParsersAction):
                todo += [(f"{name} {sub}", p) for sub, p in action.choices.items()]
    return found


OPTIONS = [
    (name, action)
    for name, parser in parsers()
    for action in parser._actions
    if action.option_strings and not isinstance(action, (argparse._HelpAction, argparse._VersionAction))
]


@pytest.mark.parametrize("name, action", OPTIONS, ids=[f"{n} {a.option_strings[0]}" for n, a in OPTIONS])
def test_every_option_says_what_it_is_and_its_default_in_one_form(name, action):
    text = action.help or ""
    assert text and not text.startswith("["), f"{name} {action.option_strings[0]}: no help"
    assert not re.search(r"\[default(?!: )", text)
    trailing = re.search(r"\[([^\[\]]*)\]$", text)
    if trailing:  # a closing bracket is the default
        assert trailing.group(1).startswith("default: "), text
    flag = isinstance(action, (argparse._StoreTrueAction, argparse._StoreFalseAction, argparse._StoreConstAction))
    if action.default not in (None, argparse.SUPPRESS) and not flag and not action.required:
        assert "[default: " in text, f"{name} {action.option_strings[0]} has default {action.default!r} unstated"


def test_no_number_in_any_help_is_written_out_in_full():
    for name, parser in parsers():
        text = parser.format_help()
        assert not re.search(r"\d{7,}|\b0\.0000", text), name


def test_each_case_option_group_names_its_case_file_table():
    """A field's option sits under the title of its section, which names the case file's table that holds it."""
    simulate = dict(parsers())["lightsail-mbs simulate"]
    titles = {a.dest: g.title for g in simulate._action_groups for a in g._group_actions}
    for name, info in FIELDS.items():
        assert titles[name].startswith(f"case [{info.group}]"), (name, titles[name])


def test_no_default_is_shown_as_a_python_none():
    for name, parser in parsers():
        assert "[default: None]" not in " ".join(parser.format_help().split()), name


def test_defaults_that_follow_other_fields_say_so():
    follows = [name for name, info in FIELDS.items() if info.follows]
    assert "beam_centre" in follows
    for name in follows:
        assert CASE_FIELDS[name].default is None  # resolved from the other fields on construction
        assert field_help(name).endswith(f"[default: {FIELDS[name].follows}]")
    simulate = dict(parsers())["lightsail-mbs simulate"].format_help()
    beam_centre = " ".join(simulate.split("--beam-centre BEAM_CENTRE")[-1].split("--")[0].split())
    assert beam_centre.endswith("[default: the sail's middle L/2]"), beam_centre
    assert "[default: 4.5e+13]" in simulate and "45000000000000" not in simulate


def test_tension_is_named_with_its_unit_per_model():
    """The chain's boundary tension is a force (N); the sheet's edge tension a force per metre of edge (N/m)."""
    assert option_name("tension") != option_name("edge_tension")
    assert "(N)" in field_help("tension") and "tnt" in field_help("tension")
    assert "(N/m)" in field_help("edge_tension")


def test_the_initial_beta_help_names_the_cases_that_refuse_it():
    """A free sail only, and no optical table (the case refuses both): the help says so before a run does."""
    text = field_help("initial_beta")
    assert "0 ≤ β₀ < 1" in text and "boundary" in text and "optical table" in text
