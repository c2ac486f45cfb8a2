"""Bad input on the command line: exit code 2 and one line ``roughcontact: error: ...``
on stderr naming the option and its accepted range, never a traceback; JSON output
never holds NaN or Infinity. A hypothesis fuzz over the numeric options of contact, path
and surface checks that nothing else escapes (exit codes 0, 2, 3, 4 only)."""

import json
import math

import numpy as np
import pytest
import xarray as xr
from _helpers import cli_one_line_error
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from roughcontact import _validate
from roughcontact.cli.main import MAX_STEPS, main

N = 16


def invoke(*args, **kwargs):
    return CliRunner().invoke(main, [str(a) for a in args], **kwargs)


def strict_json(text):
    """Parse JSON that must hold no NaN/Infinity (json.loads would accept them)."""

    def refuse(constant):
        raise AssertionError(f"JSON output holds {constant}")

    return json.loads(text, parse_constant=refuse)


SURFACE = ["--hurst", "0.8", "--rms-slope", "0.1", "--short-cutoff", "4", "--seed", "1"]


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("bad-input")
    s = d / "S.npy"
    r = invoke("surface", s, "--size", 64, *SURFACE)
    assert r.exit_code == 0, r.output
    small = d / "small.npy"
    assert invoke("surface", small, "--size", N, *SURFACE).exit_code == 0
    p = d / "p.nc"
    r = invoke("path", small, "--offsets", 0, 0.2, 0.02, "--offset-unit", "bearing_area", "-o", p)
    assert r.exit_code == 0, r.output
    return {"S": s, "small": small, "path": p, "dir": d}


# -- the reported cases -----------------------------------------------------------------


@pytest.mark.parametrize("tol", ["2", "1", "0", "-1e-8", "nan", "inf"])
def test_contact_tol_outside_0_1(files, tol):
    r = invoke("contact", files["S"], "--load", "1e-3", "--tol", tol)
    cli_one_line_error(r, "--tol", "(0, 1)", tol if tol[0].isalpha() else "")


def test_contact_tol_float32_floor(files):
    r = invoke("contact", files["S"], "--load", "1e-3", "--tol", "1e-7", "--dtype", "float32")
    cli_one_line_error(r, "tol", "1e-06", "float32")


def test_max_iter_range(files):
    cli_one_line_error(
        invoke("contact", files["S"], "--load", "1e-3", "--max-iter", 0), "--max-iter"
    )


def test_path_fields_at_out_of_range(files, tmp_path):
    out = tmp_path / "q.nc"
    args = ["path", files["small"], "--offsets", 0, 0.1, 0.05, "--offset-unit", "bearing_area"]
    for step in (999, 3, -4):
        r = invoke(*args, "-o", out, "--fields-at", step)
        cli_one_line_error(r, "fields_at", str(step), "3 steps", "-3 to 2")
        assert not out.exists()  # refused before any solve
    r = invoke(*args, "-o", out, "--fields-at", -1, "--fields-at", 0)
    assert r.exit_code == 0, r.output
    assert list(xr.load_dataset(out, engine="h5netcdf")["field_step"].values) == [0, 2]


def test_study_fields_at_out_of_range(tmp_path, make_study):
    study = make_study(extra="[output]\nfields_at = [-1, 999]")  # 6 + 5 = 11 steps
    r = invoke("study", "run", study, "-o", tmp_path / "out", "--no-progress")
    cli_one_line_error(r, "fields_at", "999", "11 steps", "-11 to 10")
    assert not (tmp_path / "out").exists()


def test_surface_json_never_holds_nan(files, tmp_path):
    # representable heights whose slopes overflow: their statistics print as null
    r = invoke(
        "surface", tmp_path / "x.npy", "--size", N, "--hurst", "0.8", "--rms-height", "1e140",
        "--short-cutoff", "4e-20", "--pixel-size", "1e-20", "--json",
    )  # fmt: skip
    assert r.exit_code == 0, r.output
    stats = strict_json(r.stdout)
    assert stats["rms_slope"] is None and stats["rms_height"] == pytest.approx(1e140)
    assert r.stderr == ""  # no overflow warnings either


def test_heights_whose_rms_overflows(files, tmp_path):
    r = invoke(
        "surface", tmp_path / "x.npy", "--size", N, "--hurst", "0.8", "--rms-height", "1e300",
        "--short-cutoff", "4", "--json",
    )  # fmt: skip
    cli_one_line_error(r, "rms_height", "1e150")
    assert r.stdout == ""
    big = tmp_path / "big.npy"
    np.save(big, np.load(files["S"]) * 1e300)
    r = invoke("contact", big, "--load", "1e-3", "--json")
    cli_one_line_error(r, "big.npy", "rms", "overflow")
    assert r.stdout == ""


@pytest.mark.parametrize(
    ("kind", "word"), [("bool", "dtype bool"), ("complex", "complex"), ("object", "")]
)
def test_heights_files_of_the_wrong_kind(files, tmp_path, kind, word):
    h = np.load(files["S"])
    data = {"bool": h > 0, "complex": h + 1j * h, "object": h.astype(object)}[kind]
    path = tmp_path / f"{kind}.npy"
    np.save(path, data, allow_pickle=kind == "object")
    r = invoke("contact", path, "--load", "1e-3")
    cli_one_line_error(r, f"{kind}.npy", word)


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--fit-max-area", "0"], ["--fit-max-area", "(0, 1]"]),
        (["--fit-max-area", "2"], ["--fit-max-area", "(0, 1]"]),
        (["--target-area", "1"], ["--target-area", "(0, 1)"]),
        (["--target-area", "nan"], ["--target-area", "(0, 1)"]),
    ],
)
def test_analyze_options_share_the_schema(files, args, words):
    cli_one_line_error(invoke("analyze", files["path"], *args, "--json"), *words)


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--target-area", "5"], ["--target-area", "(0, 1)"]),
        (["--dpi", "-5"], ["--dpi", "[10, 2400]"]),
        (["--dpi", "100000"], ["--dpi", "[10, 2400]"]),
    ],
)
def test_figures_options(files, tmp_path, args, words):
    cli_one_line_error(invoke("figures", files["dir"], "-o", tmp_path / "f", *args), *words)


def test_surface_too_large_for_memory(tmp_path, monkeypatch):
    out = tmp_path / "x.npy"
    args = ["surface", out, *SURFACE]
    line = cli_one_line_error(invoke(*args, "--size", 1_000_000), "shape", "TiB", "available")
    assert "1000000" in line
    monkeypatch.setattr(_validate, "available_memory", lambda: 4 * 2**30)  # 4 GiB here
    cli_one_line_error(invoke(*args, "--size", 30000), "(30000, 30000)", "53.6 GiB", "4 GiB")
    assert not out.exists()


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--seed", "-1"], ["--seed", ">= 0", "-1"]),
        (["--size", "1"], ["--size", ">= 2"]),
        (["--pixel-size", "1e-300"], ["--pixel-size", "[1e-25, 1e25]"]),
    ],
)
def test_surface_options(tmp_path, args, words):
    base = ["surface", tmp_path / "x.npy", "--size", N, *SURFACE]
    cli_one_line_error(invoke(*base, *args), *words)


@pytest.mark.parametrize(
    ("offsets", "words"),
    [
        (["nan", "0", "0.1"], ["--offsets", "finite", "nan"]),
        (["inf", "0", "1"], ["--offsets", "finite", "inf"]),
        (["4", "-1000000", "0.000001"], ["--offsets", str(MAX_STEPS)]),
        (["0", "1", "0"], ["--offsets", "non-zero"]),
    ],
)
def test_path_offsets(files, tmp_path, offsets, words):
    r = invoke("path", files["small"], "--offsets", *offsets, "-o", tmp_path / "q.nc")
    cli_one_line_error(r, *words)


def test_contact_pixel_size_underflow(files):
    cli_one_line_error(
        invoke("contact", files["S"], "--load", "1e-3", "--pixel-size", "1e-300"),
        "--pixel-size",
        "[1e-25, 1e25]",
    )


def test_study_file_of_random_bytes(tmp_path):
    study = tmp_path / "random.toml"
    study.write_bytes(np.random.default_rng(0).bytes(512))
    cli_one_line_error(
        invoke("study", "run", study, "-o", tmp_path / "out"), "random.toml", "UTF-8"
    )


@pytest.mark.parametrize("value", [0.0, math.nan, -1.0])
def test_analyze_path_file_with_bad_modulus(files, tmp_path, value):
    ds = xr.load_dataset(files["path"], engine="h5netcdf")
    ds.attrs["contact_modulus"] = value
    edited = tmp_path / "edited.nc"
    ds.to_netcdf(edited, engine="h5netcdf")
    r = invoke("analyze", edited, "--json")
    cli_one_line_error(r, "contact_modulus", "> 0 and finite")
    assert r.stdout == ""  # nothing (no LAPACK text) breaks --json


@pytest.mark.parametrize(
    ("manifest", "words"),
    [
        ("junk", ["study.json"]),
        ("[1, 2]", ["study.json", "JSON object"]),
        ('{"name": "x"}', ["study.json", "sha256"]),
        ('{"name": "x", "sha256": "a", "settings": {}, "tasks": 3}', ["tasks", "list"]),
        (
            '{"name": "x", "sha256": "a", "settings": {}, "tasks": [{"id": 1}]}',
            ["tasks[0]", "'id'", "'params'"],
        ),
        (
            '{"name": "x", "sha256": "a", "settings": {}, '
            '"tasks": [{"id": "0", "params": {"size": "big", "seed": 1}}]}',
            ["size", "'big'", "integers"],
        ),
    ],
)
def test_study_collect_malformed_manifest(tmp_path, manifest, words):
    study = tmp_path / "study"
    study.mkdir()
    (study / "study.json").write_text(manifest)
    r = invoke("study", "collect", study, "-o", tmp_path / "c.nc")
    cli_one_line_error(r, *words)


def test_hard_wall_study_with_tensile_loads(tmp_path):
    study = tmp_path / "hw.toml"
    study.write_text(
        "[surface]\nsize = 16\nhurst = 0.8\nrms_slope = 0.1\nshort_cutoff = 4.0\nseeds = [1]\n"
        '[interaction]\nlaw = "hardwall"\n'
        '[path]\ncontrol = "load"\nvalues = [0.01, -0.01]\n'
    )
    r = invoke("study", "run", study, "-o", tmp_path / "out", "--no-progress")
    cli_one_line_error(r, "hardwall", "tensile", ">= 0")
    assert not (tmp_path / "out").exists()


def test_contact_json_is_strict(files):
    r = invoke("contact", files["small"], "--offset", "1e3", "--json")  # out of contact
    assert r.exit_code == 0, r.output
    strict_json(r.stdout)


# -- fuzz: random numbers in every numeric option ---------------------------------------

SPECIAL = [0.0, -0.0, 1.0, -1.0, 0.5, 1e-300, 5e-324, 1e300, 1.7976931348623157e308, -1e300]
FLOATS = st.one_of(
    st.sampled_from([*SPECIAL, math.nan, math.inf, -math.inf]),
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(min_value=-10, max_value=10),
)
INTS = st.one_of(st.sampled_from([0, 1, -1, 2, 3, 8, 2**31, -(2**63)]), st.integers(-100, 100))
FUZZ = settings(
    max_examples=50,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)


def check_outcome(r, step_failed_ok=False):
    """Exit codes 0, 2, 3, 4 only, never an exception; bad input (2) is one line.

    ``step_failed_ok``: ``roughcontact path`` also documents 1, a step that failed (the
    solver broke down, e.g. at a tol below float64's rounding floor; the steps before it
    are in the file), reported in one line too.
    """
    allowed = (0, 1, 2, 3, 4) if step_failed_ok else (0, 2, 3, 4)
    clean_exit = r.exception is None or isinstance(r.exception, SystemExit)
    assert clean_exit and r.exit_code in allowed, (r.exit_code, r.output, r.exception)
    assert "Traceback" not in r.output
    lines = [line for line in r.stderr.splitlines() if line.strip()]
    if r.exit_code == 1:
        assert lines and "steps before it are in" in lines[-1], r.stderr
    if r.exit_code == 2:
        assert len(lines) == 1 and lines[0].startswith("roughcontact: error:"), r.stderr


def optional(name, values):
    return st.one_of(st.just([]), values.map(lambda x: [name, repr(x)]))


@FUZZ
@given(
    control=st.sampled_from(["--load", "--offset"]),
    value=FLOATS,
    extra=st.lists(
        st.one_of(
            optional("--modulus", FLOATS),
            optional("--pixel-size", FLOATS),
            optional("--tol", FLOATS),
            optional("--max-iter", st.integers(-(2**40), 300)),
            st.tuples(optional("--thickness", FLOATS), optional("--poisson", FLOATS)).map(
                lambda t: t[0] + t[1]
            ),
            optional("--adhesion-length", FLOATS).map(
                lambda a: a and ["--interaction", "lj93smooth", *a]
            ),
            st.tuples(
                st.sampled_from(["exponential", "dugdale", "lj93"]),
                optional("--work-of-adhesion", FLOATS),
                optional("--range", FLOATS),
            ).map(lambda t: ["--interaction", t[0], *t[1], *t[2]]),
        ),
        max_size=3,
    ),
)
def test_fuzz_contact(files, control, value, extra):
    args = [a for group in extra for a in group]
    check_outcome(invoke("contact", files["small"], control, repr(value), *args))


@FUZZ
@given(
    start=FLOATS,
    stop=FLOATS,
    step=FLOATS,
    unit=st.sampled_from(["absolute", "length", "rms_height", "bearing_area"]),
    fields_at=st.lists(INTS, max_size=2),
    until_area=st.one_of(st.none(), FLOATS),
    tol=st.one_of(st.none(), FLOATS),
)
def test_fuzz_path(files, tmp_path, start, stop, step, unit, fields_at, until_area, tol):
    with np.errstate(all="ignore"):
        count = abs(stop - start) / abs(step) if step else math.inf
    if math.isfinite(count) and 40 < count < MAX_STEPS:
        step = math.copysign(abs(stop - start) / 40, step)  # keep the run short
    args = ["path", files["small"], "--offsets", repr(start), repr(stop), repr(step)]
    args += ["--offset-unit", unit, "-o", tmp_path / "fuzz.nc", "--retract"]
    args += [a for i in fields_at for a in ("--fields-at", i)]
    args += ["--until-area", repr(until_area)] if until_area is not None else []
    args += ["--tol", repr(tol)] if tol is not None else []
    check_outcome(invoke(*args), step_failed_ok=True)


@FUZZ
@given(
    size=st.one_of(INTS, st.integers(2, 48), st.just(10**6)),
    hurst=FLOATS,
    slope=FLOATS,
    cutoff=FLOATS,
    long_cutoff=st.one_of(st.none(), FLOATS),
    pixel_size=st.one_of(st.none(), FLOATS),
    seed=st.one_of(st.none(), INTS),
)
def test_fuzz_surface(tmp_path, size, hurst, slope, cutoff, long_cutoff, pixel_size, seed):
    args = ["surface", tmp_path / "fuzz.npy", "--size", size, "--hurst", repr(hurst)]
    args += ["--rms-slope", repr(slope), "--short-cutoff", repr(cutoff), "--json"]
    args += ["--long-cutoff", repr(long_cutoff)] if long_cutoff is not None else []
    args += ["--pixel-size", repr(pixel_size)] if pixel_size is not None else []
    args += ["--seed", seed] if seed is not None else []
    r = invoke(*args)
    check_outcome(r)
    if r.exit_code == 0:
        strict_json(r.stdout)


@pytest.mark.parametrize(
    "args",
    [
        ["surface", "x.npy", "--size", "abc", "--hurst", "0.8", "--short-cutoff", "4"],
        ["nosuchcommand"],
        ["contact"],
        ["path", "s.npy", "--offsets", "1", "2"],
    ],
)
def test_click_usage_errors_are_one_line(args, tmp_path):
    r = CliRunner().invoke(main, args)
    assert r.exit_code == 2
    lines = [line for line in r.stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("roughcontact: error:")
    assert "Traceback" not in r.output and "Usage:" not in r.output
