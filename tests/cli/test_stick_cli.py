"""``roughcontact stick SCAN``: text, --json, -o DIR, bad input, and real instrument files.

Oracles: the Python call :func:`roughcontact.stick` on the same scan (the command adds
only units parsing and output), :func:`roughcontact.criterion.stickiness_criterion` on the
printed statistics, and the files the report must (and must only) contain.
"""

import json
import math
import shutil
from pathlib import Path

import numpy as np
import pytest
from _helpers import cli_one_line_error
from click.testing import CliRunner

import roughcontact as rc
from roughcontact.cli.main import main
from roughcontact.criterion import stickiness_criterion

DATA = Path(__file__).resolve().parents[1] / "data" / "topographies"
MATERIAL = ["--modulus", "10MPa", "--work-of-adhesion", "50mJ/m^2"]
REPORT = {"result.json", "summary.txt", "scan.png", "psd.png", "slope.png", "margin.png",
          "report.html"}  # fmt: skip
#: the record of what roughcontact wrote there (a rerun into DIR goes ahead)
MANIFEST = ".roughcontact-manifest.json"


@pytest.fixture(scope="module")
def scan(tmp_path_factory):
    """A self-affine 128^2 scan in nm, saved as .npy (pixel size 5 nm given on the command)."""
    h = rc.self_affine(128, hurst=0.4, rms_slope=0.2, short_cutoff=10.0, pixel_size=5.0, seed=2)
    path = tmp_path_factory.mktemp("scan") / "scan.npy"
    np.save(path, h)
    return path


def _run(args):
    return CliRunner().invoke(main, ["stick", *[str(a) for a in args]])


def _real(name):
    path = DATA / name
    assert path.is_file(), f"test data {path} missing from the repository"
    return path


NPY = ["--pixel-size", "5nm", "--height-unit", "nm"]


def test_text_output(scan):
    r = _run([scan, *NPY, *MATERIAL])
    assert r.exit_code == 0, r.output
    lines = r.output.splitlines()
    assert lines[0].startswith("verdict: ")
    assert any(line.startswith("measured down to") and "margin" in line for line in lines)
    assert any(line.startswith("extrapolated down to 0.3 nm") for line in lines)
    assert any(line.startswith("note: E* = ") for line in lines)  # every note in the text
    assert any(line.startswith("the field's criteria side by side") for line in lines)
    assert any(line.startswith("Persson & Tosatti") for line in lines)
    assert not any("--" in w for line in lines for w in line.split() if w[:1].isdigit())


def test_json_keys_units_and_the_python_call(scan):
    r = _run([scan, *NPY, *MATERIAL, "--range", "0.4nm", "--kappa-rep", "2.5", "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.output)
    for key in ("sticky", "margin", "rms_slope", "rms_curvature", "d_rep", "units", "verdict",
                "hurst", "hurst_stderr", "reliability_cutoff", "flip_scale", "measured",
                "extrapolated", "inputs", "margin_atomic", "criteria"):  # fmt: skip
        assert key in d
    assert d["units"]["rms_curvature"].startswith("1/m") and d["units"]["d_rep"].startswith("m")
    assert d["inputs"]["contact_modulus"] == pytest.approx(1e7)
    assert d["inputs"]["interaction_range"] == pytest.approx(4e-10)
    assert d["inputs"]["kappa_rep"] == 2.5
    assert d["scan"]["pixel_size"] == pytest.approx([5e-9, 5e-9])
    assert d["simulation"] is None
    ref = stickiness_criterion(contact_modulus=1e7, work_of_adhesion=0.05, kappa_rep=2.5,
                               interaction_range=4e-10, rms_slope=d["rms_slope"],
                               rms_curvature=d["rms_curvature"])  # fmt: skip
    assert d["margin"] == pytest.approx(ref.margin, rel=1e-12)
    py = rc.stick(scan, pixel_size=5e-9, height_unit="nm", modulus="10 MPa",
                  work_of_adhesion=0.05, interaction_range="0.4 nm", kappa_rep=2.5)  # fmt: skip
    assert d == json.loads(json.dumps(py.to_dict()))


def test_report_directory(scan, tmp_path):
    out = tmp_path / "report"
    r = _run([scan, *NPY, *MATERIAL, "-o", out])
    assert r.exit_code == 0, r.output
    assert r.output.splitlines()[-1] == f"report: {out}"
    assert {p.name for p in out.iterdir()} == REPORT | {MANIFEST}
    assert {p.name for p in tmp_path.iterdir()} == {"report"}  # nothing outside DIR
    d = json.loads((out / "result.json").read_text())
    assert d["sticky"] in (True, False, None) and "units" in d
    assert (out / "summary.txt").read_text().splitlines()[0] == r.output.splitlines()[0]
    for name in REPORT - {"result.json", "summary.txt", "report.html"}:
        assert (out / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert (out / "report.html").read_text().startswith("<!DOCTYPE html>")


def test_bad_input_one_line_exit_2(scan, tmp_path):
    err = cli_one_line_error(
        _run([scan, *NPY, "--modulus", "-10MPa", "--work-of-adhesion", "50mJ/m^2"])
    )
    assert "modulus" in err
    err = cli_one_line_error(
        _run([scan, *NPY, "--modulus", "10 m", "--work-of-adhesion", "5mJ/m^2"])
    )
    assert "modulus" in err
    err = cli_one_line_error(_run([tmp_path / "missing.npy", *NPY, *MATERIAL]))
    assert "missing.npy" in err
    corrupt = tmp_path / "corrupt.npy"
    corrupt.write_bytes(b"\x93NUMPY garbage that is not an array")
    cli_one_line_error(_run([corrupt, *NPY, *MATERIAL]))
    err = cli_one_line_error(_run([scan, *MATERIAL]))  # no pixel size: lattice units
    assert "pixel_size" in err
    cli_one_line_error(_run([scan, *NPY, *MATERIAL, "--detrend", "cubic"]))
    cli_one_line_error(_run([scan, *NPY, *MATERIAL, "--fit-range", "1nm", "1 kg"]))
    out = tmp_path / "afile"
    out.write_text("")
    cli_one_line_error(_run([scan, *NPY, *MATERIAL, "-o", out]))


def test_unknown_channel_and_corrupted_instrument_file(tmp_path):
    path = _real("nid-1.nid")
    err = cli_one_line_error(_run([path, *MATERIAL, "--channel", "no such channel"]))
    assert "channel" in err
    for size in (5000, 100_000):  # truncated: header only, header and part of the data
        bad = tmp_path / f"bad{size}.nid"
        bad.write_bytes(path.read_bytes()[:size])
        cli_one_line_error(_run([bad, *MATERIAL]))
    garbage = tmp_path / "garbage.di"
    garbage.write_bytes(b"\\*File list\r\n\x00\x01 not an AFM file")
    cli_one_line_error(_run([garbage, *MATERIAL]))


@pytest.mark.parametrize("name", ["di-1.di", "nid-1.nid", "dektak-1.csv"])
def test_real_files(name, tmp_path):
    path = _real(name)
    local = tmp_path / name
    shutil.copyfile(path, local)
    r = _run([local, *MATERIAL, "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.output)
    assert d["sticky"] in (True, False, None)
    assert d["scan"]["dim"] == (1 if name.endswith(".csv") else 2)
    assert d["scan"]["isotropy_assumed"] is name.endswith(".csv")
    assert d["measured_scale"] >= 2 * max(d["scan"]["pixel_size"]) * (1 - 1e-12)
    assert d["rms_slope"] > 0 and d["d_rep"] > 0 and 0 < d["hurst_stderr"] < 1
    ref = stickiness_criterion(contact_modulus=1e7, work_of_adhesion=0.05,
                               interaction_range=5e-10, rms_slope=d["rms_slope"],
                               rms_curvature=d["rms_curvature"])  # fmt: skip
    assert d["margin"] == pytest.approx(ref.margin, rel=1e-12)
    text = _run([local, *MATERIAL])
    assert text.exit_code == 0 and text.output.startswith(f"verdict: {d['verdict']}")


# l_a/a0 = w/(E* a0) = 0.05 at a0 = 0.3 nm: the paper's strong adhesion, which the
# simulation handles (the rubber of MATERIAL has 16.7 and is refused)
STIFF = ["--modulus", "100GPa", "--work-of-adhesion", "1.5J/m^2"]
SIMULATE = ["--simulate", "--simulate-size", "64", "--simulate-seeds", "1"]


@pytest.fixture(scope="module")
def fine_scan(tmp_path_factory):
    """A periodic 128^2 scan with 0.6 nm pixels (its Nyquist wavelength is 4 a0), in nm."""
    h = rc.self_affine(128, hurst=0.8, rms_slope=0.1, short_cutoff=1.2, pixel_size=0.6, seed=5)
    path = tmp_path_factory.mktemp("fine") / "fine.npy"
    np.save(path, h)
    return path


FINE = ["--pixel-size", "0.6nm", "--height-unit", "nm", "--periodic", "--detrend", "height"]


def test_simulate_json_text_and_report(fine_scan, tmp_path):
    r = _run([fine_scan, *FINE, *STIFF, *SIMULATE, "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.output)
    sim = d["simulation"]
    py = rc.stick(fine_scan, pixel_size=0.6e-9, height_unit="nm", periodic=True,
                  detrend="height", modulus="100 GPa", work_of_adhesion=1.5, simulate=True,
                  simulate_size=64, simulate_seeds=1)  # fmt: skip
    assert sim["seeds"][0]["kappa"] == pytest.approx(py.simulation.runs[0].kappa, rel=1e-9)
    assert sim["verdict"] == py.simulation.verdict == "sticky"
    assert sim["surface"]["size"] == 64 and len(sim["seeds"]) == 1
    assert sim["interaction"]["adhesion_length_over_a0"] == pytest.approx(0.05)
    assert sim["interaction"]["range"] == pytest.approx(0.5e-9)  # the range asked for
    seed = sim["seeds"][0]
    assert seed["pull_off_pressure"] == pytest.approx(seed["pull_off"] * 1e11)  # E* in Pa
    assert d["units"]["simulation.seeds.pull_off_pressure"].startswith("Pa")
    out = tmp_path / "report"
    text = _run([fine_scan, *FINE, *STIFF, *SIMULATE, "-o", out])
    assert text.exit_code == 0, text.output
    lines = text.output.splitlines()
    assert any(line.startswith("simulated: sticky over 1 of 1 seeds") for line in lines)
    assert any("range 0.5 nm (Maugis-Dugdale" in line for line in lines)
    assert any(line.startswith("per seed kappa") and " Pa" in line for line in lines)
    assert {p.name for p in out.iterdir()} == REPORT | {"contact_map.png", MANIFEST}
    assert (out / "contact_map.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert json.loads((out / "result.json").read_text())["simulation"]["verdict"] == "sticky"


def test_simulate_bad_options_one_line(fine_scan):
    for option, value in (("--simulate-size", "32"), ("--simulate-size", "x"),
                          ("--simulate-seeds", "0"), ("--simulate-seeds", "100")):  # fmt: skip
        err = cli_one_line_error(_run([fine_scan, *FINE, *STIFF, "--simulate", option, value]))
        assert option in err
    soft = ["--modulus", "1 MPa", "--work-of-adhesion", "50 mJ/m^2"]  # l_a/a0 = 167 > 100
    err = cli_one_line_error(_run([fine_scan, *FINE, *soft, "--simulate"]))
    assert "l_a/a0" in err and "167" in err


# --------------------------------------------- issue #29: real files, stiff to soft materials

SILICON = ["--modulus", "160GPa", "--poisson", "0.22", "--work-of-adhesion", "0.1J/m^2"]
PDMS = ["--modulus", "2MPa", "--poisson", "0.5", "--work-of-adhesion", "0.05J/m^2"]
ALL_FILES = ["di-1.di", "nid-1.nid", "metropro-1.dat", "dektak-1.csv"]


@pytest.mark.parametrize("name", ALL_FILES)
def test_every_real_file_ends_in_a_verdict_that_states_its_grounds(name):
    """Silicon is not sticky on the rough scans, PDMS sticky on all four (the smooth
    ones); a verdict from a spectrum that is not self-affine says so in the text."""
    for material in (SILICON, PDMS):
        r = _run([_real(name), *material, "--json"])
        assert r.exit_code == 0, r.output
        d = json.loads(r.output)
        text = _run([_real(name), *material]).output
        assert text.startswith(f"verdict: {d['verdict']}")
        for note in d["notes"]:
            assert note in text  # every note in the text output, not only in JSON
        if d["no_extrapolation"]:
            assert "no extrapolated verdict because" in text and d["extrapolated"] is None
        else:
            assert 0 < d["hurst"] < 1  # never a confident extrapolation from H outside (0, 1)
        if material is PDMS and d["scope"] == "measured scale":  # a scoped answer only
            assert d["sticky"] is None and d["sticky_measured_scale"] is True
        elif material is PDMS:
            assert d["sticky"] is True and d["sticky_measured_scale"] is True
        elif name != "metropro-1.dat":  # the optical flat: depends on unmeasured roughness
            assert d["sticky"] is False
        else:
            assert d["sticky"] is None and "depends on roughness below" in d["verdict"]


def test_the_stylus_profile_is_not_self_affine_above_its_resolution():
    """dektak-1.csv: H < 0 between the stylus' resolution and the scan size -- nothing is
    extrapolated, the text says why and how to proceed."""
    r = _run([_real("dektak-1.csv"), *PDMS])
    assert r.exit_code == 0, r.output
    lines = r.output.splitlines()
    assert lines[0] == (
        "verdict: no verdict for the whole surface: sticky at the measured scale (roughness "
        "down to 3.86 um) only; no extrapolated verdict"
    )
    assert "(sticky_measured_scale): sticky" in r.output
    assert lines[1].startswith("no extrapolated verdict because the spectrum")
    assert "outside (0, 1)" in lines[1] and "--fit-range" in lines[1]
    fixed = _run([_real("dektak-1.csv"), *PDMS, "--fit-range", "4um", "20um", "--json"])
    assert json.loads(fixed.output)["hurst_fit_range"] == pytest.approx([4e-6, 20e-6])


def test_counter_surface_and_fill_missing_options(scan, tmp_path):
    rigid = json.loads(_run([scan, *NPY, *SILICON, "--json"]).output)
    pair = json.loads(
        _run(
            [
                scan,
                *NPY,
                *SILICON,
                "--counter-modulus",
                "160GPa",
                "--counter-poisson",
                "0.22",
                "--json",
            ]
        ).output  # fmt: skip
    )
    assert pair["inputs"]["contact_modulus"] == pytest.approx(
        rigid["inputs"]["contact_modulus"] / 2
    )
    h = np.load(scan)
    h[3, 4] = np.nan  # 1 of 16384 points: filled by default, and said
    holed = tmp_path / "holed.npy"
    np.save(holed, h)
    r = _run([holed, *NPY, *SILICON])
    assert r.exit_code == 0 and "note: filled 1 of 16384 missing points" in r.output
    err = cli_one_line_error(_run([holed, *NPY, *SILICON, "--no-fill-missing"]))
    assert "--fill-missing" in err
    h[:40] = np.nan  # 31 %: refused by default, filled when asked, with the fraction
    h[100, 3] = np.nan
    np.save(holed, h)
    err = cli_one_line_error(_run([holed, *NPY, *SILICON]))
    assert "31.3% of the points (5121 of 16384)" in err and "--fill-missing" in err
    r = _run([holed, *NPY, *SILICON, "--fill-missing"])
    assert r.exit_code == 0 and "31.256% of the scan" in r.output


def test_simulate_reports_the_hysteresis_in_si(fine_scan):
    """Each seed's cycle from its lattice path (E* a0 per A0) times E* a0 in SI, by hand:
    E* = 100 GPa, a0 = 0.3 nm -> 30 J/m^2 per unit; the scan is 128^2 pixels of 0.6 nm."""
    from roughcontact.analysis.hysteresis import hysteresis

    py = rc.stick(fine_scan, pixel_size=0.6e-9, height_unit="nm", periodic=True,
                  detrend="height", modulus="100 GPa", work_of_adhesion=1.5, simulate=True,
                  simulate_size=64, simulate_seeds=1)  # fmt: skip
    hy = py.hysteresis
    one = hysteresis(py.simulation.runs[0].path)
    W = one.dissipated_energy  # here ~0: no jumps at this weak DMT-like adhesion
    assert math.isfinite(W) and hy["seeds"][0]["dissipated_energy"] == W
    assert hy["jumps_mean"] == one.jumps
    assert hy["dissipated_energy_si"] == pytest.approx(W * 1e11 * 0.3e-9, rel=1e-12)
    assert hy["scan_area"] == pytest.approx((128 * 0.6e-9) ** 2, rel=1e-12)
    assert hy["dissipated_energy_scan"] == pytest.approx(W * 30.0 * (128 * 0.6e-9) ** 2, rel=1e-12)
    assert hy["seeds"][0]["patch_area"] == pytest.approx((64 * 0.3e-9) ** 2, rel=1e-12)
    d = py.to_dict()
    assert d["hysteresis"]["dissipated_energy_si"] == pytest.approx(hy["dissipated_energy_si"])
    assert d["hysteresis"]["dissipated_energy_si_std"] is None  # one seed: no spread
    assert d["units"]["hysteresis.dissipated_energy_si"].startswith("J/m^2")
    from roughcontact.topography.report import summary

    text = "\n".join(summary(py))
    assert "energy dissipated per approach–retraction cycle" in text and "J/m^2" in text
    assert "over the scanned area" in text and "extrapolated" in text
