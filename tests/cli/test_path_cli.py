"""``roughcontact path``/``contact`` aimed by the user: relative offsets, --until-area,
--adhesion-length, step caps and units in the text output, end to end on a 32² surface."""

import json
import math

import numpy as np
import pytest
import xarray as xr
from _helpers import cli_one_line_error
from click.testing import CliRunner

from roughcontact.cli.main import MAX_STEPS, main


def invoke(*args):
    """Run the CLI; numbers are passed exactly (a float's repr round-trips)."""
    return CliRunner().invoke(main, [float(a) if isinstance(a, float) else str(a) for a in args])


@pytest.fixture(scope="module")
def surface(tmp_path_factory):
    out = tmp_path_factory.mktemp("surface") / "s.npy"
    r = invoke(
        "surface",
        out,
        "--size",
        32,
        "--hurst",
        0.8,
        "--rms-slope",
        0.1,
        "--short-cutoff",
        4,
        "--seed",
        7,
        "--json",
    )
    assert r.exit_code == 0, r.output
    stats = json.loads(r.stdout)
    h = np.load(out)
    assert stats["max_height"] == float(h.max()) and stats["min_height"] == float(h.min())
    return out, h


def read(path):
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        return ds.load()


def run_path(surface_file, out, *args):
    r = invoke("path", surface_file, "-o", out, "--json", *args)
    return r, (read(out) if out.exists() else None)


def test_surface_text_output_has_the_extremes(tmp_path):
    out = tmp_path / "s.txt"
    r = invoke(
        "surface",
        out,
        "--size",
        16,
        "--hurst",
        0.8,
        "--rms-height",
        0.5,
        "--short-cutoff",
        4,
        "--seed",
        2,
    )
    assert r.exit_code == 0, r.output
    h = np.loadtxt(out)
    lines = dict(line.strip().split(": ", 1) for line in r.output.strip().splitlines())
    assert float(lines["max_height"]) == h.max() and float(lines["min_height"]) == h.min()


@pytest.mark.parametrize(
    ("unit", "law", "expect"),
    [
        ("length", [], lambda h, v: h.max() + v),
        ("rms_height", [], lambda h, v: h.max() + v * np.std(h)),
        ("length", ["--interaction", "lj93smooth", "--range", 1.0], lambda h, v: h.max() + 1 + v),
    ],
)
def test_relative_offsets_start_at_first_contact(surface, tmp_path, unit, law, expect):
    """d = max(h) + d0 + v (v h_rms): d0 = a0 for the LJ wall, 0 for the hard wall."""
    surface_file, h = surface
    out = tmp_path / "p.nc"
    args = ["--offsets", 0.5, -0.25, 0.125, "--offset-unit", unit, *law]
    r, ds = run_path(surface_file, out, *args)
    assert r.exit_code == 0, r.output
    v = 0.5 - 0.125 * np.arange(7)
    np.testing.assert_allclose(ds["offset"].values, expect(h, v), rtol=0, atol=1e-12)
    assert ds.attrs["offset_unit"] == unit
    # the same d given as absolute offsets: the same states
    d = ds["offset"].values
    r, ref = run_path(surface_file, tmp_path / "a.nc", "--offsets", d[0], d[-1], d[0] - d[1], *law)
    assert r.exit_code == 0, r.output
    np.testing.assert_allclose(ref["offset"].values, d, rtol=0, atol=1e-12)
    # offsets equal to rounding: states equal to the solver tolerance (1e-8)
    np.testing.assert_allclose(ref["load"].values, ds["load"].values, rtol=1e-6, atol=1e-12)
    assert ref.attrs["offset_unit"] == "absolute"


def test_bearing_area_offsets(surface, tmp_path):
    surface_file, h = surface
    out = tmp_path / "p.nc"
    args = ["--offsets", 0, 0.2, 0.05, "--offset-unit", "bearing_area"]
    r, ds = run_path(surface_file, out, *args)
    assert r.exit_code == 0, r.output
    v = np.arange(5) * 0.05
    overlap = [np.count_nonzero(h - d > 1e-12) / h.size for d in ds["offset"].values]
    assert np.all(np.abs(np.array(overlap) - v) <= 1 / h.size)  # the definition (d0 = 0)
    area = ds["repulsive_area"].values
    assert area[0] == 0 and np.all(np.diff(area) > 0)  # growing into contact


def test_until_area_stops_and_retracts_through_the_visited_offsets(surface, tmp_path):
    surface_file, _ = surface
    aim = ["--offsets", 0, -2, 0.25, "--offset-unit", "rms_height"]
    r, full = run_path(surface_file, tmp_path / "full.nc", *aim)
    assert r.exit_code == 0, r.output
    area = full["repulsive_area"].values
    k = 4
    assert area[k] > area[k - 1]
    target = 0.5 * (area[k - 1] + area[k])
    r, ds = run_path(surface_file, tmp_path / "p.nc", *aim, "--until-area", target, "--retract")
    assert r.exit_code == 0, r.output
    assert json.loads(r.stdout)["steps"] == 2 * k + 1
    assert ds.attrs["until_area_reached"] == 1 and ds.attrs["until_area"] == target
    n = k + 1
    np.testing.assert_array_equal(ds["offset"].values[:n], full["offset"].values[:n])
    np.testing.assert_allclose(ds["load"].values[:n], full["load"].values[:n], rtol=1e-12)
    np.testing.assert_array_equal(ds["offset"].values[k:], full["offset"].values[:n][::-1])
    assert list(ds["branch"].values) == ["approach"] * n + ["retract"] * k


def test_until_area_alone_takes_the_default_approach_and_says_so(surface, tmp_path):
    surface_file, _ = surface
    law = ["--interaction", "lj93smooth", "--adhesion-length", 0.005, "--until-area", 0.03]
    r, ds = run_path(surface_file, tmp_path / "d.nc", *law)
    assert r.exit_code == 0, r.output
    assert "default approach --offsets 0.5 -4 0.125" in json.loads(r.stdout)["approach"]
    explicit = ["--offsets", 0.5, -4.0, 0.125, "--offset-unit", "rms_height"]
    r, same = run_path(surface_file, tmp_path / "e.nc", *explicit, *law)
    assert r.exit_code == 0 and "approach" not in json.loads(r.stdout)
    np.testing.assert_array_equal(ds["offset"].values, same["offset"].values)
    assert ds.attrs["until_area_reached"] == 1 and ds.attrs["offset_unit"] == "rms_height"
    # neither an approach nor --until-area: still one line naming the options
    cli_one_line_error(
        invoke("path", surface_file, "-o", tmp_path / "n.nc"), "--offsets", "--loads"
    )


def test_until_area_not_reached_says_how_far_it_got(surface, tmp_path):
    surface_file, _ = surface
    out = tmp_path / "p.nc"
    r, ds = run_path(
        surface_file,
        out,
        "--offsets",
        0,
        -0.5,
        0.25,
        "--offset-unit",
        "rms_height",
        "--until-area",
        0.9,
    )
    assert r.exit_code == 4
    assert json.loads(r.stdout)["steps"] == 3  # the summary is still printed
    assert ds.attrs["until_area_reached"] == 0  # and the file written
    best = int(np.argmax(ds["repulsive_area"].values))
    message = r.stderr.strip()
    assert message.startswith("roughcontact: error: --until-area 0.9 not reached")
    assert f"{ds['repulsive_area'].values[best]:.6g}" in message
    assert f"offset {ds['offset'].values[best]:.6g} (length; -0.5 in --offset-unit rms_height)" in (
        message
    )


def test_pull_off_is_null_when_the_surfaces_never_separated(surface, tmp_path):
    surface_file, h = surface
    top = float(h.max())
    args = ["--offsets", top - 0.1, top - 0.3, 0.1, "--retract"]
    r, ds = run_path(surface_file, tmp_path / "p.nc", *args)
    assert r.exit_code == 0, r.output
    assert json.loads(r.stdout)["pull_off"] is None
    assert math.isnan(ds.attrs["pull_off"]) and ds.attrs["separated"] == 0
    r = invoke("path", surface_file, "-o", tmp_path / "t.nc", *args)
    assert r.exit_code == 0, r.output
    assert "pull_off: null (not measured: the surfaces never separated)" in r.output
    r = invoke("path", surface_file, "-o", tmp_path / "t.nc", "--offsets", top, top - 0.2, 0.1)
    assert "pull_off: null (not measured: no --retract)" in r.output


def test_adhesion_length_is_the_work_of_adhesion_over_the_modulus(surface, tmp_path):
    surface_file, h = surface
    law = ["--interaction", "exponential", "--range", 0.5, "--modulus", 2]
    top = float(h.max())
    same = []
    for adhesion in (["--adhesion-length", 0.005], ["--work-of-adhesion", 0.01]):
        out = tmp_path / f"{adhesion[0][2:]}.nc"
        r, ds = run_path(
            surface_file, out, *law, *adhesion, "--offsets", top + 1, top - 0.2, 0.3, "--retract"
        )
        assert r.exit_code == 0, r.output
        assert ds.attrs["work_of_adhesion"] == pytest.approx(0.01, rel=1e-15)
        r = invoke("contact", surface_file, *law, *adhesion, "--offset", top - 0.1, "--json")
        assert r.exit_code == 0, r.output
        state = json.loads(r.stdout)
        state.pop("solve_seconds")
        same.append((ds["load"].values, ds.attrs["pull_off"], state))
    np.testing.assert_array_equal(same[0][0], same[1][0])
    assert same[0][1] == same[1][1] > 0
    assert same[0][2] == same[1][2] and same[0][2]["attractive_load"] > 0


def test_contact_text_output_states_the_units(surface):
    surface_file, h = surface
    r = invoke("contact", surface_file, "--offset", repr(float(h.max()) - 0.1))
    assert r.exit_code == 0, r.output
    lines = {line.split(":")[0].strip(): line for line in r.output.strip().splitlines()}
    assert lines["offset"].endswith("(length, a0 units)")
    assert lines["load"].endswith("(N/A0, units of E*)")
    assert lines["repulsive_area"].endswith("(fraction of A0)")
    assert lines["mean_gap"].endswith("(length, a0 units)")
    r = invoke(
        "contact",
        surface_file,
        "--offset",
        repr(float(h.max()) - 0.1),
        "--modulus",
        2,
        "--pixel-size",
        0.5,
    )
    assert r.exit_code == 0, r.output
    assert "(N/A0, pressure, in the units of --modulus (E* = 2))" in r.output
    assert "(length, units of a0 = 0.5)" in r.output


@pytest.mark.parametrize(
    ("args", "needles"),
    [
        (["--offsets", 0, -1e9, 1e-5], ["--offsets", str(MAX_STEPS)]),
        (["--loads", 1e-3, 1e9, 1e-6], ["--loads", str(MAX_STEPS)]),
        (["--offsets", "nan", -1, 0.1], ["--offsets", "finite"]),
        (["--offsets", 0, "inf", 0.1], ["--offsets", "finite"]),
        (["--loads", 1e-3, 2e-3, "nan"], ["--loads", "finite"]),
        (["--offsets", 1, 0, 0], ["STEP", "non-zero"]),
        (["--offsets", 0, -1, 0.1, "--until-area", 0], ["--until-area", "(0, 1]"]),
        (["--offsets", 0, -1, 0.1, "--until-area", 1.5], ["--until-area", "(0, 1]"]),
        (["--offsets", 0, -1, 0.1, "--until-area", "nan"], ["--until-area", "(0, 1]"]),
        (
            ["--offsets", 0, 1.2, 0.1, "--offset-unit", "bearing_area"],
            ["bearing_area", "[0, 1]"],
        ),
        (["--loads", 1e-3, 2e-3, 1e-3, "--offset-unit", "length"], ["--offset-unit", "--offsets"]),
        (
            [
                "--offsets",
                0,
                -1,
                0.1,
                "--interaction",
                "lj93",
                "--adhesion-length",
                0.01,
                "--work-of-adhesion",
                0.01,
            ],
            ["--adhesion-length", "--work-of-adhesion", "not both"],
        ),
        (
            ["--offsets", 0, -1, 0.1, "--interaction", "lj93", "--adhesion-length", -0.01],
            ["--adhesion-length", "> 0"],
        ),
        (["--offsets", 0, -1, 0.1, "--adhesion-length", 0.01], ["hardwall", "--adhesion-length"]),
    ],
)
def test_path_bad_values_are_one_line(surface, tmp_path, args, needles):
    surface_file, _ = surface
    cli_one_line_error(invoke("path", surface_file, "-o", tmp_path / "p.nc", *args), *needles)


def test_contact_adhesion_length_errors(surface):
    surface_file, _ = surface
    base = ["contact", surface_file, "--offset", 0.3, "--interaction", "dugdale", "--range", 1]
    cli_one_line_error(invoke(*base, "--adhesion-length", 0), "--adhesion-length", "> 0")
    cli_one_line_error(invoke(*base, "--adhesion-length", "inf"), "--adhesion-length", "> 0")
    cli_one_line_error(
        invoke(*base, "--adhesion-length", 0.01, "--work-of-adhesion", 0.01), "not both"
    )
    cli_one_line_error(invoke(*base[:-2], "--adhesion-length", 0.01), "needs --range")
    r = invoke(*base[:4], "--interaction", "dugdale", "--range", 1)
    cli_one_line_error(r, "needs --work-of-adhesion (or --adhesion-length)")
