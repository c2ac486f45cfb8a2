"""Instrument files on the command line: ``contact`` and ``path`` read them in metres.

The pixel size must be the one in the file's header (Nanosurf .nid: Dim0Range /
Points, 20 um / 256, parsed here), lengths are reported in metres, and bad input
(unknown channel, a line scan, a --pixel-size that contradicts the file) is one line on
stderr with exit code 2.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
from _helpers import cli_one_line_error
from click.testing import CliRunner

from roughcontact.cli.main import main

DATA = Path(__file__).resolve().parents[1] / "data" / "topographies"


def data_file(name: str) -> str:
    """A real instrument file kept in the repository (tests/data/topographies/README.md)."""
    import SurfaceTopography  # noqa: F401  (a test dependency: it must be installed)

    path = DATA / name
    assert path.is_file(), f"test data {path} missing from the repository"
    return str(path)


def header_pixel_size(path: str) -> float:
    """Dim0Range / Points of the first data set of a Nanosurf header."""
    raw = Path(path).read_bytes()
    header = raw[: raw.index(b"#!")].decode("latin-1")
    sec = header.split("[DataSet-0:1]")[1]
    return float(re.search(r"Dim0Range=(\S+)", sec).group(1)) / int(
        re.search(r"Points=(\d+)", sec).group(1)
    )


def invoke(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_contact_on_an_afm_scan_in_metres():
    path = data_file("nid-1.nid")
    r = invoke("contact", path, "--load", "0.01", "--detrend", "plane", "--json")
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    assert out["converged"] is True and 0 < out["repulsive_area"] <= 1
    s = out["surface"]
    assert s["pixel_size"] == pytest.approx([header_pixel_size(path)] * 2, rel=1e-12)
    assert s["length_unit"] == "m" and s["shape"] == [256, 256]
    assert s["channel"] == "Scan forward (Z-Axis)" and s["info"]["detrend"] == "plane"
    # the offset is a length in metres: within the scan's height range
    assert s["min_height"] - 1e-6 < out["offset"] < s["max_height"] + 1e-6


def test_contact_text_output_states_the_units():
    r = invoke("contact", data_file("nid-1.nid"), "--offset", "1", "--channel", "2")
    assert r.exit_code == 0, r.output
    assert "(length, m)" in r.stdout
    assert "'Scan backward (Z-Axis)'" in r.stdout and "7.8125e-08 m (from the file)" in r.stdout


def test_channel_by_name_and_index_agree():
    path = data_file("nid-1.nid")
    runs = [
        json.loads(invoke("contact", path, "--offset", "1", "--channel", c, "--json").stdout)
        for c in ("2", "Scan backward (Z-Axis)")
    ]
    assert runs[0]["surface"] == runs[1]["surface"]
    assert runs[0]["surface"]["info"]["channel_index"] == 2


def test_pixel_size_conflict_and_agreement():
    path = data_file("nid-1.nid")
    cli_one_line_error(
        invoke("contact", path, "--offset", "1", "--pixel-size", "1"), "--pixel-size", "7.8125e-08"
    )
    r = invoke("contact", path, "--offset", "1", "--pixel-size", "7.8125e-08")
    assert r.exit_code == 0, r.output


def test_bad_surfaces_are_one_line_errors(tmp_path):
    cli_one_line_error(
        invoke("contact", data_file("di-1.di"), "--offset", "1", "--channel", "Topo"),
        "'Topo'",
        "0 'Height', 1 'Height', 2 'Phase'",
    )
    cli_one_line_error(invoke("contact", data_file("dektak-1.csv"), "--offset", "1"), "line scan")
    np.save(tmp_path / "s.npy", np.ones((4, 4)))
    cli_one_line_error(
        invoke("path", tmp_path / "s.npy", "--loads", "1", "2", "1", "-o", tmp_path / "p.nc",
               "--channel", "1"),
        "channel",
    )  # fmt: skip


def test_path_records_the_units(tmp_path):
    xr = pytest.importorskip("xarray")
    out = tmp_path / "p.nc"
    r = invoke("path", data_file("nid-1.nid"), "--loads", "0.001", "0.002", "0.001",
               "--detrend", "plane", "-o", out, "--json")  # fmt: skip
    assert r.exit_code == 0, r.output
    summary = json.loads(r.stdout)
    assert summary["steps"] == 2 and summary["surface"]["length_unit"] == "m"
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert ds.attrs["length_unit"] == "m"
        assert ds.attrs["surface_channel"] == "Scan forward (Z-Axis)"
        assert float(ds.attrs["pixel_size"]) == pytest.approx(20e-6 / 256)


@pytest.mark.parametrize("command", ["contact", "path"])
def test_scan_readers_share_the_missing_data_policy(tmp_path, command):
    """contact and path fill a few missing points (said on stderr), refuse many with the
    fraction and --fill-missing, and fill them when asked -- as stick does."""
    rng = np.random.default_rng(1)
    h = rng.standard_normal((32, 32))
    h[5, 7] = np.nan  # 1 of 1024
    few = tmp_path / "few.npy"
    np.save(few, h)
    h[:8] = np.nan  # 256 of 1024
    many = tmp_path / "many.npy"
    np.save(many, h)
    tail = ["--load", "0.01"] if command == "contact" else ["--loads", "0.001", "0.002", "0.001"]
    if command == "path":
        tail += ["-o", str(tmp_path / "out.nc")]
    runner = CliRunner()
    r = runner.invoke(main, [command, str(few), *tail])
    assert r.exit_code == 0, r.output
    assert "note: filled 1 of 1024 missing points" in r.output  # stderr, mixed in here
    r = runner.invoke(main, [command, str(many), *tail])
    assert r.exit_code == 2 and "25.0% of the points" in r.output and "--fill-missing" in r.output
    r = runner.invoke(main, [command, str(many), *tail, "--fill-missing"])
    assert r.exit_code == 0, r.output
    assert "25.000% of the scan" in r.output
