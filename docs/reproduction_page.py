"""Write the documentation's "Reproduction of the paper" page from ``reproduction/README.md``.

That README is written beside the study it describes, so its relative links and images
point into ``reproduction/``. The page is a copy made at every build in which each
relative link or image is rewritten to reach the same file from the page's directory
(Sphinx then copies linked files as downloads and images into the site); a link to the
repository's README.md goes to the documentation's front page, which shows it, and other
Markdown files are offered as downloads. A link to a file that is not in the repository
(a result the study writes but the repository does not keep) becomes its plain text, so
a missing output never breaks the build. When the README does not exist yet the page is
a stub that says so.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

TITLE = "Reproduction of the paper"

STUB = f"""\
# {TITLE}

The reproduction of Pastewka & Robbins, PNAS 111, 3298 (2014) with roughcontact (the
parameter study, its results and their comparison with the paper's figures) is
described in `reproduction/README.md` of the repository, which is not written yet; this
page shows it once it exists.

Until then, {{doc}}`/tours` shows how to run a parameter study (`roughcontact study run`)
and {{doc}}`/model` how its results are analysed.
"""

# [text](target) and ![alt](target "title"); the target has no spaces or parentheses.
LINK = re.compile(
    r"(?P<bang>!?)\[(?P<text>[^\]]*)\]\((?P<target>[^)\s]+)(?P<title>\s+\"[^\"]*\")?\)"
)
FENCE = re.compile(r"^ {0,3}(`{3,}|~{3,})")
EXTERNAL = re.compile(r"^([a-zA-Z][a-zA-Z0-9+.-]*:|#|/)")  # URLs, anchors, absolute paths


def rewrite_links(
    text: str,
    source_dir: Path,
    page_dir: Path,
    pages: dict[Path, str] | None = None,
    docs_dir: Path | None = None,
) -> str:
    """Make the relative links of Markdown ``text`` (written in ``source_dir``) work from
    ``page_dir``; links to files that do not exist become their text. Code is left alone.

    ``pages`` maps files to the documentation pages that show them (``"/index.md"``,
    relative to the documentation's source directory ``docs_dir``; the anchor is dropped,
    since the page need not have it); Markdown files outside ``docs_dir`` are linked as
    downloads (``path:``).
    """
    pages = {Path(k).resolve(): v for k, v in (pages or {}).items()}
    docs = (docs_dir or page_dir).resolve()

    def link(match: re.Match) -> str:
        target = match.group("target")
        if EXTERNAL.match(target):
            return match.group(0)
        path, _, anchor = target.partition("#")
        resolved = (source_dir / path).resolve()
        if not resolved.exists():
            return match.group("text")
        if resolved in pages:
            new = pages[resolved]
        else:
            new = Path(os.path.relpath(resolved, page_dir.resolve())).as_posix()
            if resolved.suffix in (".md", ".rst") and not resolved.is_relative_to(docs):
                new = f"path:{new}"  # a Markdown file that is no page of the documentation
            new += f"#{anchor}" if anchor else ""
        return f"{match.group('bang')}[{match.group('text')}]({new}{match.group('title') or ''})"

    out, fence = [], None
    for line in text.splitlines(keepends=True):
        opening = FENCE.match(line)
        if fence is None and opening:
            fence = opening.group(1)
        elif fence is not None and opening and opening.group(1).startswith(fence):
            fence = None
        elif fence is None:
            line = LINK.sub(link, line)
        out.append(line)
    return "".join(out)


def page_text(readme: Path, page_dir: Path, docs_dir: Path, pages: dict | None = None) -> str:
    """The page's Markdown: the README with its links rewritten, or the stub."""
    if not readme.is_file():
        return STUB
    text = readme.read_text(encoding="utf-8")
    text = rewrite_links(text, readme.parent, page_dir, pages, docs_dir)
    if not text.lstrip().startswith("# "):  # the page needs a title for the contents
        text = f"# {TITLE}\n\n{text}"
    return text


def write_reproduction_page(
    readme: Path, out: Path, docs_dir: Path, pages: dict[Path, str] | None = None
) -> Path:
    """Write ``out/reproduction.md`` (only when its text changes: incremental builds)."""
    out.mkdir(parents=True, exist_ok=True)
    page = out / "reproduction.md"
    text = page_text(readme, out, docs_dir, pages)
    if not page.is_file() or page.read_text(encoding="utf-8") != text:
        page.write_text(text, encoding="utf-8")
    return page
