"""Sphinx extension: the package's docstrings as the API reference shows them, and a check of the result.

1. The case's fields.  :class:`~lightsail_mbs.model.parameters.SailParameters` documents its fields in a
   table, :data:`lightsail_mbs.model.fields.FIELDS` (help, unit, allowed values, the field its default
   follows, the model family), not in its docstring; this extension appends a numpydoc ``Parameters``
   section generated from that table and the class's defaults, so the reference lists every field with
   its help and unit and cannot drift from the command line, which is generated from the same table.
2. Absolute values.  The docstrings write plain Unicode maths, where ``|x|`` is an absolute value or a
   norm; reST would read it as a substitution reference.  The bars are escaped, outside inline literals,
   roles and literal blocks, before napoleon reads the docstring.
3. Numbers in signatures as a user reads them: a default written out in full (``45000000000000.0``) is
   shown as :func:`lightsail_mbs.model.fields.number` writes it (``4.5e+13``), as the command line does.
4. The check.  When the HTML build has finished, every page is searched for a cross-reference role
   (``:class:`…```, ``:mod:``, ``:meth:``, ``:func:``, …) left as literal text, the sign of a docstring
   or page that was not parsed as markup; each is a warning (``api.raw-role``), which ``sphinx-build -W``
   turns into an error.
"""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

from sphinx.util import logging

logger = logging.getLogger(__name__)

CASE_CLASS = "lightsail_mbs.model.parameters.SailParameters"
# inline literals, roles and interpreted text: left as written
_SPANS = re.compile(r"``.*?``|:[\w:.+-]+:`[^`]*`|`[^`]*`_{0,2}")
# a cross-reference role as it reads when it was not parsed
RAW_ROLE = re.compile(r":(?:py:)?(?:class|mod|meth|func|attr|data|exc|obj|doc|ref|term|math):`")
# a float literal in a signature
FLOAT = re.compile(r"(?<![\w.])\d+\.\d*(?:e[+-]?\d+)?(?![\w.])")


def case_field_lines() -> list[str]:
    """A numpydoc ``Parameters`` section of the case's fields from FIELDS and the class's defaults."""
    from lightsail_mbs.model.fields import FIELDS, number
    from lightsail_mbs.model.parameters import SailParameters

    lines = ["", "Parameters", "----------"]
    for field in dataclasses.fields(SailParameters):
        info = FIELDS[field.name]
        if info.follows:
            default = f"None: {info.follows}"
        elif isinstance(field.default, str):
            default = repr(field.default)
        else:
            default = number(field.default)
        unit = f" [{info.unit}]" if info.unit else ""
        allowed = f" Allowed: {info.allowed}." if info.allowed else ""
        lines += [
            f"{field.name} : {field.type}",
            f"    {info.help}{unit}.{allowed} Default: {default}.",
        ]
        if info.family != "all":
            lines.append(f"    Used only by model {', '.join(repr(m) for m in info.models)} (others keep the default).")
    return lines


def escape_bars(lines: list[str]) -> list[str]:
    """The lines with ``|`` written ``\\|`` outside inline literals, roles and literal blocks."""
    out, literal_indent = [], None
    for line in lines:
        indent = len(line) - len(line.lstrip())
        if literal_indent is not None and line.strip() and indent <= literal_indent:
            literal_indent = None
        if literal_indent is None:
            parts = _SPANS.split(line)
            spans = _SPANS.findall(line)
            line = "".join(p.replace("|", r"\|") + (spans[i] if i < len(spans) else "") for i, p in enumerate(parts))
            if line.rstrip().endswith("::"):
                literal_indent = indent
        out.append(line)
    return out


def process_docstring(app, what, name, obj, options, lines):
    if what == "class" and name == CASE_CLASS:
        lines += case_field_lines()
    lines[:] = escape_bars(lines)


def short_numbers(app, what, name, obj, options, signature, return_annotation):
    """The signature with its float literals written as fields.number writes them."""
    from lightsail_mbs.model.fields import number

    if signature:
        return FLOAT.sub(lambda m: number(float(m.group())), signature), return_annotation
    return None


def check_raw_roles(app, exception):
    """Warn at every raw role in the built HTML pages."""
    if exception is not None or app.builder.format != "html":
        return
    out = Path(app.outdir)
    for page in sorted(out.rglob("*.html")):
        if page.relative_to(out).parts[0] in ("_sources", "_static", "_modules"):
            continue
        text = page.read_text(encoding="utf-8")
        for match in RAW_ROLE.finditer(text):
            snippet = text[match.start() : match.start() + 60].split("\n")[0]
            logger.warning(
                "%s: a role shown as literal text: %s", page.relative_to(out), snippet, type="api", subtype="raw-role"
            )


def setup(app):
    # before napoleon (priority 500), which then reads the generated section
    app.connect("autodoc-process-docstring", process_docstring, priority=400)
    app.connect("autodoc-process-signature", short_numbers)
    app.connect("build-finished", check_raw_roles)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
