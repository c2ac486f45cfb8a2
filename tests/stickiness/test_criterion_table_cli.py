"""``roughcontact criterion`` prints the field's criteria side by side (text and JSON)."""

from __future__ import annotations

import json

from click.testing import CliRunner

from roughcontact.cli.main import main as cli

ARGS = ["criterion", "--modulus", "1 MPa", "--work-of-adhesion", "50 mJ/m^2", "--rms-slope",
        "0.3", "--range", "0.5 nm", "--rms-curvature", "0.02 1/nm"]  # fmt: skip
SPECTRUM = ["--hurst", "0.8", "--short-cutoff", "10 nm", "--long-cutoff", "10 um"]


def test_json_adds_the_criteria_key_and_keeps_the_old_ones():
    out = CliRunner().invoke(cli, [*ARGS, *SPECTRUM, "--json"])
    assert out.exit_code == 0, out.output
    d = json.loads(out.output)
    assert d["sticky"] is True and "stickiness_parameter" in d  # the old keys stay
    rows = {c["key"]: c for c in d["criteria"]["criteria"]}
    assert rows["pastewka_robbins"]["parameter"] == d["stickiness_parameter"]
    # Persson-Tosatti from the spectrum; Dahlquist: E* = 1 MPa is 10 x 0.1 MPa
    assert rows["persson_tosatti"]["sticky"] is True
    assert rows["dahlquist"]["parameter"] == 10.0 and rows["dahlquist"]["sticky"] is False
    assert d["criteria"]["agreement"]["disagree"] is True


def test_text_table_and_no_verdict_without_the_spectrum():
    out = CliRunner().invoke(cli, ARGS)
    assert out.exit_code == 0, out.output
    assert "The field's criteria side by side" in out.output
    assert (
        "Persson & Tosatti" in out.output and "no verdict: needs the power spectrum" in out.output
    )
    assert "The criteria disagree" in out.output and "Validated against" in out.output


def test_incomplete_spectrum_is_a_one_line_error():
    out = CliRunner().invoke(cli, [*ARGS, "--hurst", "0.8"])
    assert out.exit_code == 2
    assert "--short-cutoff" in out.output and "Traceback" not in out.output
