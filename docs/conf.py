"""Sphinx configuration of the lightsail-mbs documentation.

Build from the repository root (warnings are errors, as in CI):

    sphinx-build -W --keep-going -b html docs docs/_build/html

Pages are MyST Markdown.  Figures and tables of the committed results are read from where the
scripts write them (``../scenarios/figures/``, ``../validation/``), never copied into ``docs/``.

The gallery (``docs/examples/plot_*.py``, sphinx-gallery) is executed by the build; its pages are written to
``docs/gallery/``.

Set ``LIGHTSAIL_DOCS_SKIP_API=1`` to build the guides without the API reference (no autodoc imports,
no autosummary stubs): the API page then holds a one-line placeholder.  The CLI page imports
``lightsail_mbs.cli`` and the gallery runs the package either way (``-D plot_gallery=0`` skips running it).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
sys.path.insert(0, str(DOCS / "_ext"))  # local extensions (cli_reference, api_docstrings)

SKIP_API = os.environ.get("LIGHTSAIL_DOCS_SKIP_API", "") not in ("", "0")

# -- project ---------------------------------------------------------------------------------------
project = "lightsail-mbs"
author = "the lightsail-mbs authors"
copyright = "the lightsail-mbs authors"
try:
    from importlib.metadata import version as _version

    release = _version("lightsail-mbs")
except Exception:  # building from a checkout without the package installed
    release = "unknown"
version = release

# -- extensions ------------------------------------------------------------------------------------
extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx_gallery.gen_gallery",
    "cli_reference",
    "api_docstrings",
]

source_suffix = {".md": "markdown", ".rst": "restructuredtext"}  # .rst: autosummary's generated stubs
root_doc = "index"
exclude_patterns = [
    "_build",
    ".venv",
    "Thumbs.db",
    ".DS_Store",
    "NOTES.md",
    "README.front.md",  # notes for maintainers, not pages
    "examples",  # the gallery's sources; sphinx-gallery writes their pages to gallery/
]
templates_path = ["_templates"]

# MyST: $…$ and $$…$$ maths, ::: fences, definition lists; anchors for links to sections (#heading)
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3
myst_dmath_double_inline = True

# -- API reference ---------------------------------------------------------------------------------
autosummary_generate = not SKIP_API
autosummary_imported_members = False
# members defined in each module only (a package's re-exports are documented where they are defined)
autodoc_default_options = {"members": True, "show-inheritance": True, "ignore-module-all": True}
autodoc_member_order = "bysource"
# types in the signature; the descriptions are the docstrings' own (numpydoc sections, napoleon)
autodoc_typehints = "signature"
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False


if SKIP_API:
    exclude_patterns.append("_api")  # stubs left by an earlier full build

    def _placeholder_api(app, docname, source):
        """Replace the API page by one line, so the guides build without importing the package."""
        if docname == "api":
            source[0] = "# API reference\n\nNot built: this build ran with `LIGHTSAIL_DOCS_SKIP_API=1`.\n"

    def setup(app):
        app.connect("source-read", _placeholder_api)


# -- gallery ---------------------------------------------------------------------------------------
# docs/examples/plot_*.py run at every build (reduced solver, small cases: seconds each); their pages,
# figures and printed output go to docs/gallery/ (not committed). An example that raises fails the build.
# `-D plot_gallery=0` builds the pages without running them.
sphinx_gallery_conf = {
    "examples_dirs": "examples",
    "gallery_dirs": "gallery",
    "filename_pattern": r"/plot_",
    "within_subsection_order": "FileNameSortKey",
    "download_all_examples": False,
    "remove_config_comments": True,
    "show_memory": False,
    "matplotlib_animations": False,
}

# -- output ----------------------------------------------------------------------------------------
html_theme = "furo"
html_title = f"lightsail-mbs {release}"
html_theme_options = {"navigation_with_keys": True}
html_static_path = ["_static"]
html_css_files = ["docstrings.css"]  # the docstrings' indented formulas kept as written
