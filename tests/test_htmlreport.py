"""``report.html``: rendered from the result records, escaped, self-contained (no browser).

The browser checks are in tests/test_report_browser.py. Oracles here: the record's own JSON
(``StickResult.to_dict()``, the study's ``claims.json``), the text output of the same
record, and the page's bytes (every reference inline, every text escaped).
"""

import html
import re

import numpy as np
import pytest
from _browser import external_references

import roughcontact as rc
from roughcontact import htmlreport
from roughcontact.topography.html import stick_html
from roughcontact.topography.report import summary


def test_text_is_escaped_and_only_three_inline_marks_become_html():
    page = htmlreport.render_html(
        "A <title> & more",
        [
            htmlreport.Heading("1. <b>section</b>"),
            htmlreport.Para("<script>alert(1)</script> E* a0 and E*/(2a0)",
                            "*Paper:* the `code` and **bold**"),  # fmt: skip
            htmlreport.Table(("x (m)", "y"), (("<i>", "1"),)),
        ],
    )
    assert "<script>" not in page and "&lt;script&gt;alert(1)&lt;/script&gt;" in page
    assert "<title>A &lt;title&gt; &amp; more</title>" in page
    assert "&lt;b&gt;section&lt;/b&gt;" in page and "<td>&lt;i&gt;</td>" in page
    assert "E* a0 and E*/(2a0)" in page  # a star after a letter stays a star
    assert "<em>Paper:</em>" in page and "<code>code</code>" in page
    assert "<strong>bold</strong>" in page
    assert '<th scope="col">x (m)</th>' in page
    assert external_references(page) == []


def test_markdown_of_the_same_blocks():
    h = htmlreport
    blocks = [h.Heading("T", 1), h.Para("a  ", "b"), h.Table(("h1", "h2"), (("1", "2"),)),
              h.Bullets(("x",))]  # fmt: skip
    assert htmlreport.markdown_lines(blocks) == [
        "# T", "", "a  ", "b", "", "| h1 | h2 |", "|---|---|", "| 1 | 2 |", "", "- x", ""
    ]  # fmt: skip


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    h = rc.self_affine(64, hurst=0.7, rms_slope=0.2, short_cutoff=4.0, pixel_size=2.0, seed=4)
    h[10, 10] += 50 * h.std()  # a spike, kept (outliers="keep"): the map's scale ignores it
    path = tmp_path_factory.mktemp("scan") / "scan.npy"
    np.save(path, h)
    return rc.stick(path, pixel_size=2e-9, height_unit="nm", modulus="10 MPa",
                    work_of_adhesion="50 mJ/m^2", outliers="keep")  # fmt: skip


def _text(page: str) -> str:
    """The page's text with tags removed and entities decoded (whitespace collapsed)."""
    return " ".join(html.unescape(re.sub(r"<[^>]+>", " ", page)).split())


def test_the_stick_page_says_what_the_record_says(result):
    d = result.to_dict()
    page = stick_html(result, command="roughcontact stick scan.npy")
    text = _text(page)
    assert f"Verdict: {d['verdict']}" in text
    assert f"verdict {d['verdict']}" in text  # the callout's first row
    for note in d["notes"]:  # every note of the text output, word for word
        assert " ".join(note.split()) in text, note
        assert f"note: {note}" in summary(result) or note.startswith("no extrapolated")
    for c in d["criteria"]["criteria"]:
        assert c["name"] in text and c["verdict"].split(" (")[0] in text
    assert f"{d['margin']:.3g} measured down to" in text
    versions = dict(htmlreport.provenance())
    assert f"NumPy {versions['NumPy']}" in text and "SurfaceTopography" in text
    assert "roughcontact stick scan.npy" in text
    # the order the issue asks for
    keys = ["Verdict:", "Inputs", "The scan", "Power spectral density",
            "Scale-dependent slope and margin", "The field's stickiness criteria", "Notes",
            "Provenance"]  # fmt: skip
    at = [text.index(k) for k in keys]
    assert at == sorted(at)
    assert external_references(page) == []
    alts = re.findall(r'<img src="data:image/png;base64,[^"]+" alt="([^"]*)"', page)
    assert len(alts) == 4 and all(len(a) > 20 for a in alts)


def test_the_scan_map_uses_the_percentile_scale(result):
    """The spike sets the full range; the page's map spans the heights' 1st-99th percentile."""
    from roughcontact.topography.html import SCAN_PERCENTILES
    from roughcontact.topography.report import figure_scan

    h = np.asarray(result.topography.heights) / 1e-9
    robust = figure_scan(result, percentiles=SCAN_PERCENTILES).axes[0].images[0].get_clim()
    full = figure_scan(result).axes[0].images[0].get_clim()
    assert robust == pytest.approx(np.percentile(h, SCAN_PERCENTILES), rel=1e-9)
    assert full[1] == pytest.approx(h.max(), rel=1e-9) and robust[1] < 0.5 * full[1]
    assert "the colour scale spans the heights' percentiles 1 to 99" in _text(stick_html(result))


def test_a_measured_scale_answer_is_shown_where_the_record_has_one(result, monkeypatch):
    d = result.to_dict()
    d["sticky_measured_scale"] = True
    monkeypatch.setattr(type(result), "to_dict", lambda self, **k: d)
    text = _text(stick_html(result))
    assert "at the measured scale sticky" in text
