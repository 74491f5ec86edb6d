"""The API reference's docstring processing (docs/_ext/api_docstrings.py): the case's fields documented from
their table, absolute values kept from reST's substitutions, signatures' numbers shortened, and the check that
fails a docs build whose HTML shows a cross-reference role as literal text."""

import dataclasses
import sys
from pathlib import Path
from types import SimpleNamespace

import pytest

from lightsail_mbs.model.fields import FIELDS
from lightsail_mbs.model.parameters import SailParameters

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "docs" / "_ext"))
api_docstrings = pytest.importorskip("api_docstrings")  # needs sphinx (the dev extras)


def test_every_case_field_is_documented_with_its_help_and_unit():
    lines = api_docstrings.case_field_lines()
    assert lines[1:3] == ["Parameters", "----------"]
    for field in dataclasses.fields(SailParameters):
        info = FIELDS[field.name]
        k = lines.index(f"{field.name} : {field.type}")
        text = lines[k + 1]
        assert text.startswith(f"    {info.help}") and "Default: " in text
        assert (f"[{info.unit}]" in text) == bool(info.unit)
    youngs = lines[lines.index("youngs_modulus : float") + 1]
    assert youngs.endswith("Default: 4.5e+13.")  # as the command line writes it
    beam_centre = lines[lines.index("beam_centre : float | None") + 1]
    assert beam_centre.endswith("Default: None: the sail's middle L/2.")


def test_bars_are_escaped_outside_literals_roles_and_literal_blocks():
    lines = ["|x − y| and ``|q|`` and :math:`|z|`", "The matrix::", "", "    |A|", "after |b|"]
    assert api_docstrings.escape_bars(lines) == [
        r"\|x − y\| and ``|q|`` and :math:`|z|`",
        "The matrix::",
        "",
        "    |A|",
        r"after \|b\|",
    ]


def test_signature_numbers_are_written_short():
    signature = "(e: float = 45000000000000.0, h=1e-06)"
    signature, _ = api_docstrings.short_numbers(None, "class", "X", None, {}, signature, None)
    assert signature == "(e: float = 4.5e+13, h=1e-06)"


@pytest.mark.parametrize(
    "html, raw",
    [
        ("<p>see <code>:class:`~lightsail_mbs.result.Result`</code></p>", True),
        ("<pre>Uses :meth:`solve` and :mod:`lightsail_mbs.model`</pre>", True),
        ('<p>see <a href="x.html#Result"><code>Result</code></a></p>', False),
    ],
)
def test_the_build_check_warns_at_a_raw_role(tmp_path, monkeypatch, html, raw):
    (tmp_path / "_api").mkdir()
    (tmp_path / "_api" / "page.html").write_text(html, encoding="utf-8")
    (tmp_path / "_sources").mkdir()
    (tmp_path / "_sources" / "page.txt").write_text(":class:`x`", encoding="utf-8")  # the sources are not pages
    warnings = []
    monkeypatch.setattr(api_docstrings.logger, "warning", lambda *args, **kwargs: warnings.append(args))
    app = SimpleNamespace(outdir=str(tmp_path), builder=SimpleNamespace(format="html"))
    api_docstrings.check_raw_roles(app, None)
    assert bool(warnings) == raw
    assert all("page.html" in str(w[1]) for w in warnings)
