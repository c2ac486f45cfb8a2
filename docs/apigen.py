"""Write the API reference pages (reStructuredText) from the package's ``__all__`` lists.

One page per public package or module (no leading underscore in its dotted name; the
command-line modules are documented by the CLI reference instead). A page shows the
module's docstring, a summary table (autosummary) of every name in its ``__all__`` and
the full documentation (autodoc + numpydoc) of the names whose *home* it is, so every
object is described exactly once: the home of a name is the deepest public module whose
``__all__`` holds the same object (usually the module that defines it); the summary
tables of the packages that re-export it link there.

The pages are regenerated on every build from the installed package, so a name added to
an ``__all__`` appears without editing the documentation.
"""

from __future__ import annotations

import importlib
import pkgutil
from pathlib import Path

#: The order of the reference's table of contents; public modules of the package that are
#: not listed here follow in alphabetical order, so a new module is never left out.
ORDER = (
    "roughcontact.surfaces",
    "roughcontact.elastic",
    "roughcontact.interactions",
    "roughcontact.solvers",
    "roughcontact.analysis",
    "roughcontact.theory",
    "roughcontact.criterion",
    "roughcontact.studies",
    "roughcontact.plot",
)
EXCLUDED = ("roughcontact.cli",)  # the CLI reference (sphinx-click) documents the commands


def _public(name: str) -> bool:
    return not any(part.startswith("_") for part in name.split(".")) and not any(
        name == excluded or name.startswith(excluded + ".") for excluded in EXCLUDED
    )


def _children(package: str) -> list[str]:
    module = importlib.import_module(package)
    if not hasattr(module, "__path__"):
        return []
    return [
        info.name
        for info in pkgutil.iter_modules(module.__path__, package + ".")
        if _public(info.name)
    ]


def _submodules(package: str) -> list[str]:
    out = []
    for child in _children(package):
        out.append(child)
        out.extend(_submodules(child))
    return out


def sections() -> list[str]:
    """The public modules directly under ``roughcontact``, in the order of :data:`ORDER`."""
    return sorted(
        _children("roughcontact"), key=lambda m: (ORDER.index(m) if m in ORDER else len(ORDER), m)
    )


def public_modules() -> list[str]:
    """Every documented module: the top level, then each section and its submodules."""
    out = ["roughcontact"]
    for section in sections():
        out.append(section)
        out.extend(_submodules(section))
    return out


def _all(module_name: str) -> list[str]:
    return list(getattr(importlib.import_module(module_name), "__all__", []))


def homes(modules: list[str]) -> dict[tuple[str, str], str]:
    """(module, name) -> the module whose page documents that object in full."""
    # (name, id(object)) -> the modules exporting that object under that name; the name
    # is part of the key because equal small constants can be one object.
    exported: dict[tuple[str, int], list[str]] = {}
    for module_name in modules:
        module = importlib.import_module(module_name)
        for name in _all(module_name):
            exported.setdefault((name, id(getattr(module, name))), []).append(module_name)
    out = {}
    for module_name in modules:
        module = importlib.import_module(module_name)
        for name in _all(module_name):
            candidates = exported[name, id(getattr(module, name))]
            out[module_name, name] = max(candidates, key=lambda m: (m.count("."), m))
    return out


def aliases(modules: list[str], home: dict[tuple[str, str], str]) -> dict[str, str]:
    """``module.name`` -> ``home.name`` for every name exported away from its home, so that
    a reference to ``roughcontact.solve`` finds the description of
    ``roughcontact.solvers.solve.solve`` (see ``missing-reference`` in conf.py)."""
    return {
        f"{module}.{name}": f"{where}.{name}"
        for (module, name), where in home.items()
        if where != module
    }


def _title(text: str, char: str = "=") -> str:
    return f"{text}\n{char * len(text)}\n"


def module_page(module_name: str, modules: list[str], home: dict) -> str:
    names = _all(module_name)
    own = [n for n in names if home[module_name, n] == module_name]
    children = [
        m for m in modules if m.rpartition(".")[0] == module_name and module_name != "roughcontact"
    ]
    lines = [_title(f"``{module_name}``"), f".. automodule:: {module_name}\n"]
    if names:
        lines.append(".. rubric:: Public names\n")
        lines.append(".. autosummary::\n")
        lines += [f"   {_item(module_name, home[module_name, n], n)}" for n in names]
        lines.append("")
    if own:
        # Described here; the other pages' tables link to these descriptions.
        lines.append(f".. currentmodule:: {module_name}\n")
        for name in own:
            kind = _kind(module_name, name)
            lines.append(f".. auto{kind}:: {name}")
            if kind in ("class", "exception"):
                lines.append("   :members:")
            elif kind == "data" and not isinstance(_object(module_name, name), int | float | str):
                lines.append("   :no-value:")  # tables and mappings: their docs say what
            lines.append("")
    if children:
        lines.append(".. rubric:: Modules\n")
        lines.append(".. toctree::\n   :maxdepth: 1\n")
        lines += [f"   {child}" for child in children]
        lines.append("")
    return "\n".join(lines) + "\n"


def _item(module_name: str, home: str, name: str) -> str:
    """An autosummary entry, relative to the page's module as autosummary requires."""
    if home == module_name:
        return name
    if home.startswith(module_name + "."):
        return f"~{home[len(module_name) + 1 :]}.{name}"
    return f"~{home}.{name}"


def _object(module_name: str, name: str):
    return getattr(importlib.import_module(module_name), name)


def _kind(module_name: str, name: str) -> str:
    obj = _object(module_name, name)
    if isinstance(obj, type):
        return "exception" if issubclass(obj, BaseException) else "class"
    if callable(obj):
        return "function"
    return "data"


def index_page() -> str:
    lines = [
        _title("API reference"),
        "Generated from the docstrings of the installed package. Lattice units unless",
        "stated otherwise: lengths in a0, pressures in E*, areas and loads per A0 (see",
        ":doc:`/model`).\n",
        ".. toctree::\n   :maxdepth: 1\n",
        "   roughcontact",
        *(f"   {section}" for section in sections()),
        "",
    ]
    return "\n".join(lines) + "\n"


def write_api(out: Path) -> dict[str, str]:
    """Write ``index.rst`` and one page per public module into ``out``; return the
    :func:`aliases` of the re-exported names."""
    modules = public_modules()
    home = homes(modules)
    out.mkdir(parents=True, exist_ok=True)
    pages = {"index": index_page()}
    pages.update({m: module_page(m, modules, home) for m in modules})
    written = []
    for stem, text in pages.items():
        path = out / f"{stem}.rst"
        if not path.is_file() or path.read_text(encoding="utf-8") != text:
            path.write_text(text, encoding="utf-8")  # unchanged pages keep their mtime
        written.append(path)
    for stale in set(out.glob("*.rst")) - set(written):
        stale.unlink()
    return aliases(modules, home)
