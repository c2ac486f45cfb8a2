"""``report.html`` of ``stick -o`` and ``study report -o`` in a real browser, offline.

Headless Chromium (``apt-get install chromium``; .ci/run installs it) renders each page
with every host unresolvable. Checked: the screenshot is not blank (its grey levels
vary), the rendered DOM shows the verdict and the criteria table (or the claims), and
the page made no network request (Chromium's network log; a control page with a remote
image and font shows that the check sees one). Skipped, with the reason, only where no
Chromium-like browser is installed.
"""

import json
from pathlib import Path

import numpy as np
import pytest
from _browser import external_references, find_browser, pixel_spread, render
from click.testing import CliRunner

import roughcontact as rc
from roughcontact.cli.main import main

pytestmark = pytest.mark.skipif(
    find_browser() is None,
    reason="no Chromium-like browser installed (apt-get install chromium): the report's "
    "browser test cannot run",
)

DATA = Path(__file__).resolve().parent / "data" / "topographies"
# a blank page's screenshot has spread 0; a page of text and figures has tens of grey levels
MIN_SPREAD = 5.0


def _stick(args):
    r = CliRunner().invoke(main, ["stick", *[str(a) for a in args]])
    assert r.exit_code == 0, r.output
    return r


def _check_page(page: Path, tmp: Path, must_show) -> str:
    html = page.read_text(encoding="utf-8")
    assert external_references(html) == []  # everything inline
    out = render(page, tmp)
    assert out["requests"] == [], out["requests"]
    assert pixel_spread(out["screenshot"]) > MIN_SPREAD
    for text in must_show:
        assert text in out["dom"], text
    return out["dom"]


def test_the_network_check_sees_a_remote_image_and_font(tmp_path):
    """The control: a page that loads from the network is caught by both checks."""
    page = tmp_path / "control.html"
    page.write_text(
        '<html><body><p>x</p><img src="http://example.com/a.png" alt="a">'
        '<link rel="stylesheet" href="https://fonts.googleapis.com/css?family=Roboto">'
        "</body></html>"
    )
    assert len(external_references(page.read_text())) == 2
    out = render(page, tmp_path / "b")
    assert "http://example.com/a.png" in out["requests"]


def test_stick_report_of_a_real_scan_offline(tmp_path):
    """A 64² crop of the Nanoscope AFM scan: verdict, scope, inputs, criteria, notes."""
    topo = rc.load_topography(DATA / "di-1.di")
    crop = tmp_path / "di-1-crop.npy"
    np.save(crop, np.asarray(topo.heights)[:64, :64] / 1e-9)
    out = tmp_path / "report"
    _stick([crop, "--pixel-size", f"{topo.pixel_size[0] / 1e-9:.10g}nm", "--height-unit", "nm",
            "--modulus", "10MPa", "--work-of-adhesion", "50mJ/m^2", "-o", out])  # fmt: skip
    d = json.loads((out / "result.json").read_text())
    dom = _check_page(out / "report.html", tmp_path / "browser",
                      [f"Verdict: {d['verdict']}", "The field's stickiness criteria",
                       "Pastewka &amp; Robbins", "Persson &amp; Tosatti", "sha256",
                       "Provenance", "SurfaceTopography"])  # fmt: skip
    assert dom.index("Verdict:") < dom.index("Inputs") < dom.index("Power spectral density")
    assert dom.count("<img") >= 4 and 'alt=""' not in dom


def test_stick_report_with_simulation_offline(tmp_path):
    """--simulate adds the contact map, the force–offset loop and the per-seed table."""
    h = rc.self_affine(64, hurst=0.8, rms_slope=0.1, short_cutoff=1.2, pixel_size=0.6, seed=5)
    scan = tmp_path / "fine.npy"
    np.save(scan, h)
    out = tmp_path / "report"
    _stick([scan, "--pixel-size", "0.6nm", "--height-unit", "nm", "--periodic",
            "--detrend", "height", "--modulus", "100GPa", "--work-of-adhesion", "1.5J/m^2",
            "--simulate", "--simulate-size", "64", "--simulate-seeds", "1", "-o", out])  # fmt: skip
    d = json.loads((out / "result.json").read_text())
    assert d["simulation"] is not None
    _check_page(out / "report.html", tmp_path / "browser",
                [f"Verdict: {d['verdict']}", "The field's stickiness criteria",
                 "Simulation (--simulate)", "Force–offset loop of seed 1",
                 "Contact map of the first seed", "pull-off (Pa)"])  # fmt: skip


@pytest.mark.slow  # runs a study first (8 tasks): the heaviest of these checks
def test_study_report_offline(tmp_path, make_study):
    from roughcontact.studies import load_study, run_study

    study = tmp_path / "out"
    run_study(load_study(make_study()), study, scheduler="synchronous", progress=False)
    report = tmp_path / "report"
    r = CliRunner().invoke(main, ["study", "report", str(study), "-o", str(report)])
    assert r.exit_code == 0, r.output
    dom = _check_page(report / "report.html", tmp_path / "browser",
                      ["1. A_rep ∝ N at small area (Eq. 3)", "7. Sticky iff 1/κ_att &gt; 1/κ_rep",
                       "With the measured κ_rep", "Fig. 4:", "Provenance"])  # fmt: skip
    assert dom.count("<img") == 3
