"""``roughcontact stick`` on real instrument files: what the file states (issue 41, 3-5).

The stylus file is ``dektak-1.csv`` as recorded, re-encoded here the way another Dektak
export writes it (UTF-8, "Radius: 2 µm"): SurfaceTopography reads its header as Latin-1,
so the unit arrives as "Âµm". Oracles: the file's own header; the scan's pixel size and
size (Nyquist wavelength 2 pixels, the longest wavelength the scan size).
"""

import json
from pathlib import Path

import pytest
from _helpers import cli_one_line_error
from click.testing import CliRunner

from roughcontact.cli.main import main

DATA = Path(__file__).resolve().parents[1] / "data" / "topographies"
SILICON = ["--modulus", "160GPa", "--poisson", "0.22", "--work-of-adhesion", "0.1J/m^2"]


def _run(args):
    return CliRunner().invoke(main, ["stick", *[str(a) for a in args]])


def _dektak(tmp_path, stylus):
    text = (DATA / "dektak-1.csv").read_bytes().decode("latin-1")
    text = text.replace("Stylus,Radius: 2.5 \u00b5m\r\n", stylus)
    assert ("2.5 \u00b5m" in text) is False
    path = tmp_path / "stylus.csv"
    path.write_bytes(text.encode("utf-8"))
    return path


# ------------------------------------------------------------ item 3: the stated tip radius


def test_a_stated_stylus_radius_sets_the_reliability_cutoff(tmp_path):
    path = _dektak(tmp_path, "Stylus,Radius: 2 \u00b5m\r\n")
    d = json.loads(_run([path, *SILICON, "--json"]).output)
    assert d["inputs"]["tip_radius"] == pytest.approx(2e-6, rel=1e-12)
    assert d["inputs"]["tip_radius_source"] == "file"
    text = _run([path, *SILICON]).output
    assert "tip radius stated in the file, '2.0 \u00b5m'" in text
    # the same radius given on the command line: the same cutoff
    given = json.loads(_run([path, *SILICON, "--tip-radius", "2um", "--json"]).output)
    assert given["reliability_cutoff"] == pytest.approx(d["reliability_cutoff"], rel=1e-12)


def test_no_stated_radius_is_said(tmp_path):
    path = _dektak(tmp_path, "")
    d = json.loads(_run([path, *SILICON, "--json"]).output)
    assert d["inputs"]["tip_radius"] is None
    assert any(n.startswith("the file states no tip or stylus radius") for n in d["notes"])
    assert "the file states no tip or stylus radius" in _run([path, *SILICON]).output


# ------------------------------------------------------------- item 4: the data channel


def test_the_channel_read_is_named_and_the_others_listed():
    nid = DATA / "nid-1.nid"
    text = _run([nid, *SILICON]).output
    assert "data channel read: 'Scan forward (Z-Axis)' (index 0 of 4)" in text
    assert "1 'Scan forward (Z-AxisSensor)'" in text and "3 'Scan backward (Z-AxisSensor)'" in text
    d = json.loads(_run([nid, *SILICON, "--channel", "1", "--json"]).output)
    assert d["scan"]["channel"] == "Scan forward (Z-AxisSensor)"
    assert d["scan"]["channel_index"] == 1 and len(d["scan"]["channels"]) == 4
    assert any("0 'Scan forward (Z-Axis)'" in n for n in d["notes"])
    one = json.loads(_run([DATA / "metropro-1.dat", *SILICON, "--json"]).output)
    assert any("the file's only channel" in n for n in one["notes"])


# ---------------------------------------------------------- item 5: a fit range past the data


def test_a_fit_range_beyond_the_data_is_clamped_with_a_note():
    nid = DATA / "nid-1.nid"  # 256 pixels of 78.125 nm: 156 nm to 20 um
    d = json.loads(_run([nid, *SILICON, "--fit-range", "1nm", "50um", "--json"]).output)
    assert d["hurst_fit_range"] == pytest.approx([2 * 78.125e-9, 20e-6], rel=1e-9)
    note = next(n for n in d["notes"] if n.startswith("--fit-range"))
    assert "clamped" in note and "1 nm raised to 156 nm" in note and "50 um lowered" in note
    assert not any("Hurst fit from 1 nm" in n for n in d["notes"])
    err = cli_one_line_error(_run([nid, *SILICON, "--fit-range", "1nm", "200nm"]))
    assert "fit_range" in err and "less than an octave" in err


# ------------------------------------------------ item 9: a bare length for a .npy file


@pytest.fixture
def npy(tmp_path):
    import numpy as np

    import roughcontact as rc

    h = rc.self_affine((64, 64), hurst=0.8, rms_height=1.0, short_cutoff=2, seed=1)
    path = tmp_path / "surface.npy"
    np.save(path, h)
    return path


PDMS = ["--modulus", "1MPa", "--work-of-adhesion", "50mJ/m^2"]


def test_a_bare_pixel_size_is_metres_and_said_or_refused(npy):
    """``--pixel-size 2`` is 2 m pixels: out of the plausible range, refused naming the
    missing unit; a bare number in range is read as metres and said, first thing."""
    err = cli_one_line_error(_run([npy, "--pixel-size", "2", "--height-unit", "nm", *PDMS]))
    assert "pixel size 2 m is out of range" in err and "'2 nm'" in err
    r = _run([npy, "--pixel-size", "2e-9", "--height-unit", "nm", *PDMS])
    assert r.exit_code == 0, r.output
    lines = r.output.splitlines()
    assert lines[1].startswith("pixel_size '2e-9' was given without a unit: read as metres")
    d = json.loads(_run([npy, "--pixel-size", "2e-9", "--height-unit", "nm", *PDMS,
                         "--json"]).output)  # fmt: skip
    assert any("without a unit" in n for n in d["notes"])
    with_unit = _run([npy, "--pixel-size", "2 nm", "--height-unit", "nm", *PDMS]).output
    assert "without a unit" not in with_unit
    # heights without --height-unit are metres: 6 m of peak-to-valley is refused
    err = cli_one_line_error(_run([npy, "--pixel-size", "2 nm", *PDMS]))
    assert "peak-to-valley" in err and "--height-unit" in err
