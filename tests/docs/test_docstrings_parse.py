"""Every docstring the API reference shows parses as reStructuredText without a warning, as the docs build
(``sphinx-build -W``) requires: the same steps as the build (docs/_ext/api_docstrings.py, then napoleon's numpy
sections, then docutils), on the modules docs/api.md lists, found by reading the source (no import). A failure
names the module, the object and docutils' message, minutes before the docs build would."""

import ast
import io
import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "docs" / "_ext"))
api_docstrings = pytest.importorskip("api_docstrings")  # needs sphinx (the dev extras)

from docutils import nodes  # noqa: E402
from docutils.core import publish_doctree  # noqa: E402
from docutils.parsers.rst import Directive, directives, roles  # noqa: E402
from sphinx.ext.napoleon import Config  # noqa: E402
from sphinx.ext.napoleon.docstring import NumpyDocstring  # noqa: E402

SPHINX_ROLES = "class mod meth func attr data exc obj doc ref math term".split()
SPHINX_DIRECTIVES = ("attribute", "method", "function", "data", "rubric")  # what napoleon may write
DEFINITIONS = (ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)
NAPOLEON = Config(napoleon_google_docstring=False, napoleon_numpy_docstring=True, napoleon_use_rtype=False)


def _literal(name, rawtext, text, lineno, inliner, options=None, content=None):
    return [nodes.literal(rawtext, text)], []


class _Skipped(Directive):
    """A Sphinx directive, taken as written (its content is Sphinx's to render)."""

    has_content = True
    optional_arguments = 10
    final_argument_whitespace = True
    option_spec = {"type": directives.unchanged, "value": directives.unchanged, "no-index": directives.flag}

    def run(self):
        return []


for _role in SPHINX_ROLES:
    roles.register_local_role(_role, _literal)
    roles.register_local_role(f"py:{_role}", _literal)
for _directive in SPHINX_DIRECTIVES:
    directives.register_directive(_directive, _Skipped)


def documented_modules() -> list[str]:
    """The modules docs/api.md lists in its autosummary tables."""
    text = (ROOT / "docs" / "api.md").read_text(encoding="utf-8")
    return re.findall(r"^\s+(lightsail_mbs(?:\.\w+)*)\s*$", text, re.M)


def module_file(module: str) -> Path:
    path = ROOT.joinpath(*module.split("."))
    return path / "__init__.py" if path.is_dir() else path.with_suffix(".py")


def docstrings(path: Path):
    """(name, docstring, kind) of the module and of its public classes, functions and methods."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    if doc := ast.get_docstring(tree):
        yield "(module)", doc, "module"

    def walk(body, prefix, in_class):
        for node in body:
            if isinstance(node, DEFINITIONS) and not node.name.startswith("_"):
                kind = "class" if isinstance(node, ast.ClassDef) else "method" if in_class else "function"
                if doc := ast.get_docstring(node):
                    yield prefix + node.name, doc, kind
                if isinstance(node, ast.ClassDef):
                    yield from walk(node.body, f"{prefix}{node.name}.", True)

    yield from walk(tree.body, "", False)


def problems(doc: str, kind: str) -> str:
    """docutils' warnings for a docstring as the build processes it ('' when it parses cleanly)."""
    text = str(NumpyDocstring(api_docstrings.escape_bars(doc.splitlines()), NAPOLEON, what=kind))
    stream = io.StringIO()
    publish_doctree(text, settings_overrides={"warning_stream": stream, "report_level": 2, "halt_level": 5})
    return stream.getvalue().strip()


def test_api_md_lists_modules_that_exist():
    modules = documented_modules()
    assert len(modules) > 100 and "lightsail_mbs.model.parameters" in modules
    assert [m for m in modules if not module_file(m).exists()] == []


@pytest.mark.parametrize("module", documented_modules())
def test_docstrings_parse_without_warnings(module):
    found = [f"{name}: {msg}" for name, doc, kind in docstrings(module_file(module)) if (msg := problems(doc, kind))]
    assert not found, "\n".join(found)


def test_the_check_finds_what_the_build_would_reject():
    assert "Unexpected indentation" in problems("A paragraph\nof two lines\n    indented: a formula\n", "function")
    assert problems("The matrix::\n\n    |A| = 1\n\nand |x| is fine.", "function") == ""
