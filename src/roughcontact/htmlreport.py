"""One self-contained HTML page (and its Markdown) from a report's blocks.

The owner of ``report.html``: ``roughcontact stick -o DIR`` and ``roughcontact study report
-o DIR`` describe their result record as a list of blocks (:class:`Heading`,
:class:`Para`, :class:`Table`, :class:`Bullets`, :class:`Code`, :class:`Figure`,
:class:`Callout`), built from the typed record itself (the stick result of
:mod:`roughcontact.topography.html`, the study's claims of
:mod:`roughcontact.studies.report`), never from text output. :func:`render_html` turns
them into one page through a Jinja2 template with autoescaping; :func:`markdown_lines`
turns the same blocks into Markdown (the study's ``README.md``).

The page is self-contained: CSS inline, figures inline as ``data:`` URIs (PNG, or SVG on
request), no script, no font or file fetched from anywhere; print CSS keeps
figures and table rows whole on A4 or Letter. Paragraph text may carry three inline
marks, written by this package's own code: ``*emphasis*``, ``**strong**`` and
```code``` (as in Markdown; a ``*`` after a letter, as in ``E*``, is a star).
"""

from __future__ import annotations

import base64
import datetime
import io
import platform
import re
import sys
from dataclasses import dataclass

__all__ = [
    "Bullets",
    "Callout",
    "Code",
    "Figure",
    "Heading",
    "Para",
    "Table",
    "figure_block",
    "markdown_lines",
    "provenance",
    "render_html",
]


# ---------------------------------------------------------------------------- blocks
@dataclass(frozen=True)
class Heading:
    """A section heading (level 2 or 3; level 1 is the page title)."""

    text: str
    level: int = 2
    kind = "heading"

    @property
    def anchor(self) -> str:
        return re.sub(r"[^a-z0-9]+", "-", self.text.lower()).strip("-")[:60] or "section"


@dataclass(frozen=True)
class Para:
    """A paragraph: its lines are joined by line breaks (inline marks allowed)."""

    lines: tuple
    kind = "para"

    def __init__(self, *lines: str):
        object.__setattr__(self, "lines", tuple(lines))


@dataclass(frozen=True)
class Table:
    """A table: ``header`` cells (each with its unit, e.g. ``"pressure (Pa)"``), ``rows``
    of cells (str; numbers already formatted), an optional caption."""

    header: tuple
    rows: tuple
    caption: str = ""
    kind = "table"


@dataclass(frozen=True)
class Bullets:
    """A bulleted list (inline marks allowed)."""

    items: tuple
    kind = "bullets"


@dataclass(frozen=True)
class Code:
    """Preformatted lines (commands to run)."""

    lines: tuple
    language: str = "console"
    kind = "code"


@dataclass(frozen=True)
class Figure:
    """An inline figure: a ``data:`` URI, its alt text and caption; ``file`` is its name
    beside the Markdown (``figures/x.png``) or empty."""

    uri: str
    alt: str
    caption: str = ""
    file: str = ""
    kind = "figure"


@dataclass(frozen=True)
class Callout:
    """The answer in a box: a title, a tone (``"sticky"``, ``"not-sticky"``, ``"open"``)
    and rows of (label, value)."""

    title: str
    tone: str
    rows: tuple
    kind = "callout"


def figure_block(fig, *, alt: str, caption: str = "", fmt: str = "png", dpi: int = 150):
    """A :class:`Figure` of a matplotlib figure, inline (``svg`` or ``png`` at ``dpi``)."""
    buffer = io.BytesIO()
    meta = {"Date": None} if fmt == "svg" else {"Software": None}
    fig.savefig(buffer, format=fmt, dpi=dpi, metadata=meta)
    mime = "image/svg+xml" if fmt == "svg" else "image/png"
    return Figure(data_uri(buffer.getvalue(), mime), alt, caption)


def data_uri(data: bytes, mime: str) -> str:
    """``data:MIME;base64,...`` of ``data``."""
    return f"data:{mime};base64," + base64.b64encode(data).decode("ascii")


# ---------------------------------------------------------------------------- provenance
def _version(dist: str) -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version(dist)
    except PackageNotFoundError:
        return "not installed"


def provenance(command: str | None = None) -> list[tuple[str, str]]:
    """(label, value) rows: roughcontact's version, the command line, the date (UTC), the
    versions of Python, NumPy, SciPy, SurfaceTopography and matplotlib."""
    from . import __version__

    now = datetime.datetime.now(datetime.UTC).replace(microsecond=0)
    return [
        ("roughcontact", __version__),
        ("command", command or "(called from Python)"),
        ("date", now.isoformat().replace("+00:00", " UTC")),
        ("Python", platform.python_version()),
        ("NumPy", _version("numpy")),
        ("SciPy", _version("scipy")),
        ("SurfaceTopography", _version("SurfaceTopography")),
        ("matplotlib", _version("matplotlib")),
    ]


def command_line() -> str:
    """The command line of this process (``roughcontact ...``), shell-quoted."""
    import shlex
    from pathlib import Path

    name = Path(sys.argv[0]).name if sys.argv else ""
    if name == "__main__.py":
        return shlex.join(["python", "-m", "roughcontact", *sys.argv[1:]])
    prog = "roughcontact" if name.startswith("roughcontact") or not name else name
    return shlex.join([prog, *sys.argv[1:]])


# ---------------------------------------------------------------------------- Markdown
def markdown_lines(blocks) -> list[str]:
    """The blocks as Markdown lines (a blank line after each block)."""
    out = []
    for b in blocks:
        if b.kind == "heading":
            out.append("#" * b.level + " " + b.text)
        elif b.kind == "para":
            out += b.lines
        elif b.kind == "table":
            out.append("| " + " | ".join(b.header) + " |")
            out.append("|" + "---|" * len(b.header))
            out += ["| " + " | ".join(str(c) for c in row) + " |" for row in b.rows]
        elif b.kind == "bullets":
            out += [f"- {item}" for item in b.items]
        elif b.kind == "code":
            out += [f"```{b.language}", *b.lines, "```"]
        elif b.kind == "figure":  # a figure line of its own, as Markdown images were
            out.append(f"![{b.alt}]({b.file})\n")
            continue
        elif b.kind == "callout":
            out += [f"**{b.title}**", ""] + [f"- {k}: {v}" for k, v in b.rows]
        out.append("")
    return out


# ---------------------------------------------------------------------------- HTML
_MARKS = (
    (re.compile(r"(?<![\w*])\*\*(?=\S)(.+?)(?<=\S)\*\*(?![\w*])"), r"<strong>\1</strong>"),
    (re.compile(r"(?<![\w*])\*(?=\S)(.+?)(?<=\S)\*(?![\w*])"), r"<em>\1</em>"),
)


def _inline(text) -> object:
    """Escape ``text``, then turn its inline marks into HTML (code first: nothing inside
    a code span is marked)."""
    from markupsafe import Markup, escape

    parts = re.split(r"(`[^`]+`)", str(text))
    html = []
    for part in parts:
        if part.startswith("`") and part.endswith("`") and len(part) > 1:
            html.append(f"<code>{escape(part[1:-1])}</code>")
            continue
        s = str(escape(part))
        for pattern, repl in _MARKS:
            s = pattern.sub(repl, s)
        html.append(s)
    return Markup("".join(html))


_CSS = """
:root{--fg:#1b1b1b;--mute:#555;--line:#c9c9c9;--head:#eef1f4;--ok:#2e7d32;--no:#b71c1c;
--open:#b26a00}
*{box-sizing:border-box}
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,"Helvetica Neue",Arial,sans-serif;
color:var(--fg);line-height:1.45;max-width:62rem;margin:0 auto;padding:1rem 1.5rem 3rem}
h1{font-size:1.6rem;margin:.5rem 0 .25rem}
h2{font-size:1.25rem;margin:1.8rem 0 .5rem;border-bottom:1px solid var(--line);
padding-bottom:.2rem}
h3{font-size:1.05rem;margin:1.2rem 0 .4rem}
p.sub{color:var(--mute);margin-top:0}
code{font-family:ui-monospace,"DejaVu Sans Mono",Menlo,Consolas,monospace;font-size:.9em;
background:#f4f4f4;padding:0 .2em;border-radius:3px}
pre{background:#f4f4f4;padding:.6rem .8rem;overflow-x:auto;font-size:.85rem}
.table{overflow-x:auto}
table{border-collapse:collapse;margin:.4rem 0 1rem;font-size:.88rem}
caption{caption-side:top;text-align:left;color:var(--mute);font-size:.85rem;
padding-bottom:.2rem}
th,td{border:1px solid var(--line);padding:.25rem .5rem;text-align:left;vertical-align:top}
thead th{background:var(--head)}
figure{margin:1rem 0;break-inside:avoid;page-break-inside:avoid}
figure img{display:block;max-width:min(100%,46rem);height:auto}
figcaption{color:var(--mute);font-size:.85rem;margin-top:.3rem;max-width:48rem}
.callout{border-left:.5rem solid var(--open);background:#f7f7f5;padding:.6rem 1rem;
margin:1rem 0;break-inside:avoid}
.callout.sticky{border-color:var(--ok)}.callout.not-sticky{border-color:var(--no)}
.callout h2{border:0;margin:.2rem 0 .5rem;font-size:1.4rem}
.callout table{margin:0;font-size:.92rem}
.callout th{background:none;border:0;padding:.15rem .8rem .15rem 0;white-space:nowrap;
vertical-align:top}
.callout td{border:0;padding:.15rem 0}
footer{margin-top:2rem;color:var(--mute);font-size:.85rem}
@page{size:auto;margin:14mm}
@media print{
body{max-width:none;padding:0;font-size:10pt}
h2,h3{break-after:avoid;page-break-after:avoid}
table{font-size:8pt}
tr,figure,.callout{break-inside:avoid;page-break-inside:avoid}
.table{overflow:visible}
figure img{max-height:10.5cm;width:auto;max-width:100%}
footer{break-inside:avoid;page-break-inside:avoid}
pre{white-space:pre-wrap}
}
"""

_TEMPLATE = """<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta name="generator" content="roughcontact {{ version }}">
<title>{{ title }}</title>
<style>{{ css }}</style>
</head>
<body>
<header>
<h1>{{ title }}</h1>
{% if subtitle %}<p class="sub">{{ subtitle | inline }}</p>{% endif %}
</header>
<main>
{% for b in blocks %}
{% if b.kind == "heading" %}
<h{{ b.level }} id="{{ b.anchor }}">{{ b.text | inline }}</h{{ b.level }}>
{% elif b.kind == "para" %}
<p>{% for line in b.lines %}{{ line | inline }}{% if not loop.last %}<br>
{% endif %}{% endfor %}</p>
{% elif b.kind == "table" %}
<div class="table"><table>
{% if b.caption %}<caption>{{ b.caption | inline }}</caption>{% endif %}
<thead><tr>{% for h in b.header %}<th scope="col">{{ h | inline }}</th>{% endfor %}</tr></thead>
<tbody>
{% for row in b.rows %}<tr>{% for c in row %}<td>{{ c | inline }}</td>{% endfor %}</tr>
{% endfor %}</tbody>
</table></div>
{% elif b.kind == "bullets" %}
<ul>{% for item in b.items %}<li>{{ item | inline }}</li>{% endfor %}</ul>
{% elif b.kind == "code" %}
<pre><code>{{ b.lines | join("\\n") }}</code></pre>
{% elif b.kind == "figure" %}
<figure><img src="{{ b.uri }}" alt="{{ b.alt }}">
{% if b.caption %}<figcaption>{{ b.caption | inline }}</figcaption>{% endif %}</figure>
{% elif b.kind == "callout" %}
<section class="callout {{ b.tone }}" id="verdict">
<h2>{{ b.title | inline }}</h2>
<table>{% for k, v in b.rows %}<tr><th scope="row">{{ k }}</th><td>{{ v | inline }}</td></tr>
{% endfor %}</table>
</section>
{% endif %}
{% endfor %}
</main>
<footer>
<h2 id="provenance">Provenance</h2>
<div class="table"><table>
<thead><tr><th scope="col">item</th><th scope="col">value</th></tr></thead>
<tbody>
{% for k, v in provenance %}<tr><td>{{ k }}</td><td><code>{{ v }}</code></td></tr>
{% endfor %}</tbody>
</table></div>
<p>Written by roughcontact {{ version }}: one self-contained file, nothing fetched from
the network.</p>
</footer>
</body>
</html>
"""


def render_html(title: str, blocks, *, subtitle: str = "", provenance_rows=()) -> str:
    """The page: ``title``, the ``blocks`` in order, the provenance table (from
    :func:`provenance`). Every text is escaped (Jinja2 autoescaping)."""
    import jinja2

    from . import __version__

    env = jinja2.Environment(autoescape=True, trim_blocks=True, lstrip_blocks=True,
                             undefined=jinja2.StrictUndefined)  # fmt: skip
    env.filters["inline"] = _inline
    page = env.from_string(_TEMPLATE).render(
        title=title,
        subtitle=subtitle,
        blocks=list(blocks),
        provenance=list(provenance_rows),
        css=_markup(_CSS),
        version=__version__,
    )
    return page


def _markup(text):
    from markupsafe import Markup

    return Markup(text)
