"""Sphinx configuration of the roughcontact documentation.

Build (warnings are errors)::

    pip install -e ".[docs]"
    sphinx-build -W --keep-going -b html docs docs/_build/html

The pages that show parts of the repository's README.md include them (MyST ``{include}``
between heading markers), so the README stays the one copy. Two kinds of page are
written into ``docs/generated/`` at every build: the API reference from the installed
package's ``__all__`` lists (:mod:`apigen`) and the reproduction page from
``reproduction/README.md``, or a stub while that file does not exist
(:mod:`reproduction_page`).
"""

from __future__ import annotations

import importlib.util
import sys
import warnings
from pathlib import Path

import roughcontact

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
GENERATED = DOCS / "generated"  # written by this file at every build (git ignores it)
sys.path.insert(0, str(DOCS))

from apigen import write_api  # noqa: E402
from reproduction_page import write_reproduction_page  # noqa: E402

project = "roughcontact"
author = "the roughcontact developers"
copyright = "the roughcontact developers"  # noqa: A001 (Sphinx's name)
release = roughcontact.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "sphinx_click",
    "myst_parser",
]
# No sphinx.ext.intersphinx: CI reaches the package index only.

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store"]
# Literal text everywhere: with smartquotes, "--offsets" in the CLI reference (sphinx-click)
# became an en dash, and an option copied from the page failed.
smartquotes = False

# -- MyST (Markdown pages and the README parts they include)
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence"]
myst_heading_anchors = 3

# -- autodoc / autosummary / numpydoc
autosummary_generate = False  # the summary tables link to autodoc entries on the pages
autosummary_ignore_module_all = False  # a module's __all__ is its public API
autodoc_typehints = "none"  # numpydoc's Parameters sections state the types and units
autodoc_member_order = "bysource"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks: set[str] = set()

# -- HTML
html_theme = "furo" if importlib.util.find_spec("furo") else "alabaster"
html_title = f"roughcontact {release}"
html_static_path: list[str] = []

write_reproduction_page(
    ROOT / "reproduction" / "README.md", GENERATED, DOCS, pages={ROOT / "README.md": "/index.md"}
)
API_ALIASES = write_api(GENERATED / "api")


def _numpydoc_warnings_to_sphinx(app) -> None:
    """numpydoc reports a docstring section it cannot parse (e.g. "Unknown section") as a
    Python warning, and then drops that section; make it a Sphinx warning, so that -W
    fails on it like on any other docstring error."""
    from sphinx.util import logging

    logger = logging.getLogger("numpydoc")
    show = warnings.showwarning

    def showwarning(message, category, filename, lineno, file=None, line=None):
        if issubclass(category, UserWarning) and "numpydoc" in str(filename):
            logger.warning("%s", message, type="numpydoc")
        else:
            show(message, category, filename, lineno, file, line)

    warnings.showwarning = showwarning


def _by_name() -> dict[str, str]:
    """Short name -> its one described full name (names described twice are left out)."""
    full = set(API_ALIASES.values())
    names: dict[str, set[str]] = {}
    for name in full:
        names.setdefault(name.rpartition(".")[2], set()).add(name)
    return {short: next(iter(f)) for short, f in names.items() if len(f) == 1}


API_BY_NAME = _by_name()


def _resolve_alias(app, env, node, contnode):
    """A Python reference to a re-exported name (``roughcontact.solve``, or ``solve`` in a
    module that imports it) that has no description of its own resolves to the
    description at the name's home."""
    if node.get("refdomain") != "py":
        return None
    reftarget = node.get("reftarget", "")
    module = node.get("py:module") or ""
    target = (
        API_ALIASES.get(reftarget)
        or API_ALIASES.get(f"{module}.{reftarget}")
        or ("." not in reftarget and API_BY_NAME.get(reftarget))
    )
    if not target:
        return None
    domain = env.domains["py"]
    return domain.resolve_xref(
        env, node["refdoc"], app.builder, node["reftype"], target, node, contnode
    )


def setup(app):
    _numpydoc_warnings_to_sphinx(app)
    app.connect("missing-reference", _resolve_alias)
