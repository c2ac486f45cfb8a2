"""The documentation (docs/): it builds with warnings as errors, and its generated pages
cover what they must.

* ``test_sphinx_build`` runs the README's build command (Sphinx, ``-W``) where Sphinx and
  the docs extra are installed (``pip install -e ".[docs]"``), and checks the built site
  against the package itself: every command of the click tree has its section in the
  CLI reference, every name of every public ``__all__`` its entry in the API reference.
* The page generators of docs/ (``apigen``, ``reproduction_page``) are tested without
  Sphinx: every public name is documented exactly once, and the reproduction page's
  rewritten links reach the same files as the original ones.
"""

from __future__ import annotations

import importlib
import importlib.util
import os
import re
import subprocess
import sys
import tomllib
from html.parser import HTMLParser
from pathlib import Path

import click
import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
README = ROOT / "README.md"
BUILD = ["-W", "-b", "html", "docs", "docs/_build/html"]  # the README's sphinx-build arguments


def _docs_module(name: str):
    spec = importlib.util.spec_from_file_location(f"docs_{name}", DOCS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


# --------------------------------------------------------------------------- the build


class _Ids(HTMLParser):
    """Every ``id`` attribute of an HTML page."""

    def __init__(self):
        super().__init__()
        self.ids: set[str] = set()

    def handle_starttag(self, tag, attrs):
        self.ids.update(value for key, value in attrs if key == "id" and value)


def _ids(page: Path) -> set[str]:
    parser = _Ids()
    parser.feed(page.read_text(encoding="utf-8"))
    return parser.ids


def _commands(group: click.Group, prefix: str) -> list[str]:
    out = []
    for name, command in group.commands.items():
        out.append(f"{prefix} {name}")
        if isinstance(command, click.Group):
            out.extend(_commands(command, f"{prefix} {name}"))
    return out


@pytest.mark.slow
def test_sphinx_build(tmp_path):
    for module in ("sphinx", "numpydoc", "sphinx_click", "myst_parser"):
        pytest.importorskip(
            module, reason='the docs extra is not installed (pip install ".[docs]")'
        )
    html = tmp_path / "html"
    args = [*BUILD[:-2], "--keep-going", "-d", str(tmp_path / "doctrees"), "docs", str(html)]
    process = subprocess.run(
        [sys.executable, "-m", "sphinx", *args],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=600,
        env={**os.environ, "MPLBACKEND": "Agg"},
    )
    assert process.returncode == 0, (
        f"sphinx-build {' '.join(args)} failed (warnings are errors):\n"
        + "\n".join(line for line in process.stderr.splitlines() if line.strip())[-6000:]
    )

    from roughcontact.cli.main import main

    cli_ids = _ids(html / "cli.html")
    missing = [c for c in _commands(main, "roughcontact") if c.replace(" ", "-") not in cli_ids]
    assert not missing, f"commands without a section in the CLI reference: {missing}"

    apigen = _docs_module("apigen")
    modules = apigen.public_modules()
    home = apigen.homes(modules)
    pages: dict[str, set[str]] = {}
    absent = []
    for (module, name), where in sorted(home.items()):
        ids = pages.setdefault(where, _ids(html / "generated" / "api" / f"{where}.html"))
        if f"{where}.{name}" not in ids:
            absent.append(f"{module}.{name} (on the page of {where})")
    assert not absent, f"public names without an entry in the API reference: {absent}"
    for page in ("index", "model", "tours", "performance", "generated/reproduction"):
        assert (html / f"{page}.html").is_file(), page
    # The model page's references to the API ({func}`roughcontact.solve`, ...) are links.
    model = (html / "model.html").read_text(encoding="utf-8")
    references = re.findall(
        r'(<a [^>]*>)?<code class="xref py[^"]*"><span class="pre">([^<]*)', model
    )
    assert references and not [name for link, name in references if not link]


# --------------------------------------------------------------------------- the API pages


def test_every_public_name_is_documented_once_where_it_is_exported():
    apigen = _docs_module("apigen")
    modules = apigen.public_modules()
    assert "roughcontact" in modules and not any(".cli" in m or "._" in m for m in modules)
    for section in ("analysis", "surfaces", "elastic", "interactions", "solvers", "theory"):
        assert f"roughcontact.{section}" in modules
    for section in ("criterion", "studies", "plot"):
        assert f"roughcontact.{section}" in modules
    home = apigen.homes(modules)
    described: dict[tuple[str, int], str] = {}
    for module in modules:
        exported = getattr(importlib.import_module(module), "__all__", [])
        for name in exported:
            where = home[module, name]
            obj = getattr(importlib.import_module(module), name)
            # The home exports the very same object under the same name ...
            assert getattr(importlib.import_module(where), name) is obj, (module, name, where)
            assert name in importlib.import_module(where).__all__
            # ... and one object under one name has one home, wherever it is exported.
            assert described.setdefault((name, id(obj)), where) == where, (module, name)
    assert set(roughcontact_all()) <= {name for (module, name) in home if module == "roughcontact"}


def roughcontact_all() -> list[str]:
    import roughcontact

    return list(roughcontact.__all__)


def test_module_page_lists_every_name_and_describes_its_own(tmp_path):
    apigen = _docs_module("apigen")
    aliases = apigen.write_api(tmp_path)
    assert {p.stem for p in tmp_path.glob("*.rst")} == {"index", *apigen.public_modules()}
    assert aliases["roughcontact.solve"] == "roughcontact.solvers.solve.solve"
    assert "roughcontact.solvers.solve.solve" not in aliases  # a home is no alias
    text = (tmp_path / "roughcontact.analysis.rst").read_text()
    import roughcontact.analysis as analysis

    summary = text.split(".. autosummary::")[1].split(".. ")[0]
    listed = [line.strip().rsplit(".", 1)[-1] for line in summary.splitlines() if line.strip()]
    assert listed == list(analysis.__all__)
    # perimeter is defined (and described) in contact_geometry, listed in the package.
    assert "~contact_geometry.perimeter" in text and ".. autofunction:: perimeter" not in text
    own = (tmp_path / "roughcontact.analysis.contact_geometry.rst").read_text()
    assert ".. autofunction:: perimeter" in own


# --------------------------------------------------------------------------- reproduction page


def test_reproduction_page_is_a_stub_until_the_readme_exists(tmp_path):
    page = _docs_module("reproduction_page")
    out = page.write_reproduction_page(tmp_path / "reproduction" / "README.md", tmp_path, tmp_path)
    text = out.read_text()
    assert text.startswith("# Reproduction of the paper") and "not written yet" in text


def test_reproduction_links_reach_the_same_files(tmp_path):
    page = _docs_module("reproduction_page")
    repo = tmp_path / "repo"
    (repo / "reproduction" / "figures").mkdir(parents=True)
    (repo / "docs" / "generated").mkdir(parents=True)
    (repo / "reproduction" / "figures" / "fig2.png").write_bytes(b"png")
    (repo / "reproduction" / "data.csv").write_text("a\n")
    (repo / "README.md").write_text("# x\n")
    (repo / "docs" / "model.md").write_text("# m\n")
    readme = repo / "reproduction" / "README.md"
    readme.write_text(
        "## Results\n\n"
        '![Fig. 2](figures/fig2.png) and [the data](data.csv#L1 "csv") and '
        "[missing](out/collected.nc) and [home](../README.md#studies) and "
        "[model](../docs/model.md) and [web](https://doi.org/10.1073/pnas.1320846111) "
        "and [here](#results).\n\n"
        "```bash\ncat [not a link](data.csv)\n```\n"
    )
    out_dir = repo / "docs" / "generated"
    pages = {repo / "README.md": "/index.md"}
    text = page.page_text(readme, out_dir, repo / "docs", pages)

    links = dict(re.findall(r"\[([^\]]*)\]\(([^)\s]+)", text))
    # Relative targets, resolved from the page's directory, are the original files.
    assert (out_dir / links["Fig. 2"]).resolve() == (
        repo / "reproduction/figures/fig2.png"
    ).resolve()
    assert (out_dir / links["the data"].split("#")[0]).resolve() == (
        repo / "reproduction/data.csv"
    ).resolve()
    assert links["the data"].endswith("#L1") and '"csv")' in text
    assert (out_dir / links["model"]).resolve() == (repo / "docs" / "model.md").resolve()
    assert links["home"] == "/index.md"  # the page that shows the repository's README
    assert "missing" not in links and " and missing and " in text  # not in the repository
    assert links["web"] == "https://doi.org/10.1073/pnas.1320846111"
    assert links["here"] == "#results"
    assert "cat [not a link](data.csv)" in text  # code is left alone
    assert text.startswith("# Reproduction of the paper\n\n## Results")  # a title is added


def test_markdown_outside_the_docs_is_a_download(tmp_path):
    page = _docs_module("reproduction_page")
    (tmp_path / "notes.md").write_text("n\n")
    (tmp_path / "docs").mkdir()
    text = page.rewrite_links("[n](notes.md)", tmp_path, tmp_path / "docs", {}, tmp_path / "docs")
    assert text == "[n](path:../notes.md)"


# --------------------------------------------------------------------------- commands and rules


def _section(text: str, heading: str) -> str:
    return text.split(f"\n## {heading}\n", 1)[1].split("\n## ", 1)[0]


def test_readme_and_ci_run_the_tested_build():
    section = _section(README.read_text(encoding="utf-8"), "Documentation")
    command = f'pip install -e ".[docs]" && sphinx-build {" ".join(BUILD)}'
    assert command in section.splitlines(), f"README's Documentation section lacks {command!r}"
    ci = (ROOT / ".ci" / "run").read_text()
    assert re.search(r"sphinx-build -W\b.* docs docs/_build/html", ci), ".ci/run builds no docs"
    assert 'pip install --quiet -e ".[docs]"' in ci
    extra = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    extra = extra["optional-dependencies"]["docs"]
    names = {re.split(r"[<>=!\[ ]", requirement)[0].lower() for requirement in extra}
    assert {"sphinx", "numpydoc", "sphinx-click", "myst-parser"} <= names


def test_docs_and_sources_name_no_file_a_user_does_not_have():
    offenders = []
    for base in (DOCS, ROOT / "src"):
        for path in base.rglob("*"):
            skip = {"_build", "generated", "__pycache__"} & set(path.relative_to(base).parts)
            if not path.is_file() or skip or path.suffix not in (".py", ".md", ".rst", ".txt"):
                continue
            text = path.read_text(encoding="utf-8", errors="replace")
            for pattern in (r"\bSPEC\b", r"\.\./shared\b", r"/work/shared\b"):
                if re.search(pattern, text):
                    offenders.append(f"{path.relative_to(ROOT)}: {pattern}")
    assert not offenders, offenders
