"""Reliability round three, reading: the kind of file first, plausible data, fuzzed input.

FIFOs and devices given as inputs are refused without being opened (a read would block),
.npy headers that lie about their size are refused before numpy allocates, study files
nested too deep are one line; a constant surface is "flat", absurd heights or pixel sizes
and a header that disagrees with its data are refused at the reading edge; damaged inputs
give one ParameterError line, never another exception.
"""

import io
import os
import shutil
import time

import numpy as np
import pytest
from _helpers import DATA, POSIX, SMOKE
from _helpers import cli_one_line_error as _one_line
from _helpers import random_surface as _surface
from click.testing import CliRunner

from roughcontact import ParameterError, _io, _plausibility
from roughcontact._files import npy_header, regular_input
from roughcontact.cli.main import main
from roughcontact.studies import load_study
from roughcontact.surfaces import load_heights
from roughcontact.topography import file_kind, load_topography

# --- one reader: the kind of file first ------------------------------------------------


@POSIX
@pytest.mark.parametrize("name", ["f.txt", "f.npy", "f.dat", "f.toml", "f.nc"])
def test_fifo_inputs_are_refused_without_blocking(tmp_path, name):
    fifo = tmp_path / name
    os.mkfifo(fifo)
    t0 = time.monotonic()
    for read in (
        load_heights,
        load_topography,
        load_study,
        lambda p: _io.read_netcdf(p, refusal="not a NetCDF file"),
    ):
        with pytest.raises(ParameterError, match="FIFO"):
            read(fifo)
    assert file_kind(fifo) in ("npy", "text")  # looked at without opening it
    assert time.monotonic() - t0 < 10


@POSIX
@pytest.mark.parametrize(
    "args",
    [
        ["contact", "{f}", "--load", "1e-3"],
        ["path", "{f}", "--loads", "1e-3", "2e-3", "1e-3", "-o", "{d}/p.nc"],
        ["study", "run", "{f}", "-o", "{d}/s"],
        ["analyze", "{f}"],
        ["study", "report", "{f}", "-o", "{d}/r"],
    ],
)
def test_fifo_on_the_command_line_is_one_line(tmp_path, args):
    fifo = tmp_path / "f.txt"
    os.mkfifo(fifo)
    args = [a.format(f=fifo, d=tmp_path) for a in args]
    _one_line(CliRunner().invoke(main, args), "FIFO")


def test_character_device_and_directory_are_not_files(tmp_path):
    if os.path.exists("/dev/zero"):
        with pytest.raises(ParameterError, match="character device"):
            load_heights("/dev/zero")
    with pytest.raises(ParameterError, match="directory"):
        regular_input(tmp_path, "surface")
    with pytest.raises(ParameterError, match="no such file"):
        regular_input(tmp_path / "absent.npy", "surface")


@pytest.mark.parametrize("shape", [(100_000, 100_000), (2**40, 2), (3, 3)])
def test_npy_header_claiming_more_than_the_file_holds(tmp_path, shape):
    buf = io.BytesIO()
    header = {"descr": "<f8", "fortran_order": False, "shape": shape}
    np.lib.format.write_array_header_1_0(buf, header)
    path = tmp_path / "h.npy"
    path.write_bytes(buf.getvalue() + b"\0" * 64)  # 8 float64: fewer than claimed
    with pytest.raises(ParameterError, match="claims shape") as err:
        load_heights(path)
    assert "\n" not in str(err.value)


def test_npy_header_accepts_an_honest_file(tmp_path):
    np.save(tmp_path / "ok.npy", _surface())
    assert npy_header(tmp_path / "ok.npy") == ((16, 16), np.dtype("<f8"))


def test_instrument_file_renamed_npy_is_named_as_such(tmp_path):
    fake = tmp_path / "scan.npy"
    shutil.copy(DATA / "di-1.di", fake)
    with pytest.raises(ParameterError, match="not a NumPy .npy file") as err:
        load_heights(fake)
    assert "allow_pickle" not in str(err.value)


def test_toml_with_a_byte_order_mark_is_read(tmp_path):
    bom = tmp_path / "bom.toml"
    bom.write_text(SMOKE.read_text(), encoding="utf-8-sig")
    assert bom.read_bytes().startswith(b"\xef\xbb\xbf")
    assert len(load_study(bom).tasks) == len(load_study(SMOKE).tasks)


@pytest.mark.parametrize(
    "text",
    [
        "x = " + "[" * 50_000 + "1" + "]" * 50_000,
        "x = " + "{a=" * 50_000 + "1" + "}" * 50_000,
        "x." + ".".join(["a"] * 50_000) + " = 1",  # tomllib: quadratic time, not recursion
        "[" + ".".join(['"a"'] * 50_000) + "]",
        "[[cases]]\nhurst." + ".".join(["b"] * 30_000) + " = 1",
    ],
    ids=["arrays", "inline-tables", "dotted-key", "dotted-table", "dotted-case"],
)
def test_deeply_nested_toml_is_one_line(tmp_path, text):
    deep = tmp_path / "deep.toml"
    deep.write_text(text + "\n")
    t0 = time.monotonic()
    with pytest.raises(ParameterError, match="nested") as err:
        load_study(deep)
    assert "\n" not in str(err.value)
    assert time.monotonic() - t0 < 5


def test_nesting_count_ignores_brackets_in_strings_and_comments(tmp_path):
    text = SMOKE.read_text() + "\n# [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[\n"
    text = text.replace('name = "smoke"', 'name = "smoke [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[["')
    path = tmp_path / "s.toml"
    path.write_text(text)
    assert load_study(path).name.startswith("smoke [")


# --- plausibility at the reading edge ------------------------------------------------


@pytest.mark.parametrize("value", [0.0, 1e-6, 1.0, -3e5])
def test_constant_surface_is_flat_for_every_reader(tmp_path, value):
    h = np.full((32, 32), value)
    h[3, 4] = np.nextafter(value, np.inf)  # rounding is not roughness
    np.save(tmp_path / "c.npy", h)
    with pytest.raises(ParameterError, match="flat surface"):
        load_topography(tmp_path / "c.npy")
    r = CliRunner().invoke(main, ["contact", str(tmp_path / "c.npy"), "--load", "1e-3"])
    _one_line(r, "flat surface")
    r = CliRunner().invoke(
        main,
        ["stick", str(tmp_path / "c.npy"), "--pixel-size", "10 nm", "--modulus", "1 GPa",
         "--work-of-adhesion", "50 mJ/m^2"],
    )  # fmt: skip
    _one_line(r, "flat")


def test_a_topography_given_directly_is_checked_too():
    from roughcontact.topography import Topography
    from roughcontact.topography.verdict import stick

    rubber = {"modulus": "1 GPa", "work_of_adhesion": "50 mJ/m^2"}
    huge = Topography(_surface() * 1e300, 1e-8, info={"length_unit": "m"})
    with pytest.raises(ParameterError, match="out of range") as err:
        stick(huge, **rubber)
    assert "flat" not in str(err.value)
    flat = Topography(np.full((16, 16), 1e-6), 1e-8, info={"length_unit": "m"})
    with pytest.raises(ParameterError, match="flat surface"):
        stick(flat, **rubber)


def test_huge_heights_are_out_of_range_not_flat(tmp_path):
    np.save(tmp_path / "big.npy", _surface() * 1e300)
    with pytest.raises(ParameterError) as err:
        load_topography(tmp_path / "big.npy")
    assert "flat" not in str(err.value) and "1e+150" in str(err.value)
    r = CliRunner().invoke(
        main,
        ["stick", str(tmp_path / "big.npy"), "--pixel-size", "10 nm", "--modulus", "1 GPa",
         "--work-of-adhesion", "50 mJ/m^2"],
    )  # fmt: skip
    _one_line(r, "out of range")
    assert "flat" not in r.stderr


@pytest.mark.parametrize(
    ("scale", "pixel", "words"),
    [
        (1e13, 1e-8, ["peak-to-valley", "m"]),  # flipped bits: an rms of 10^13 m
        (1e-45, 1e-8, ["peak-to-valley"]),
        (1e-9, 1e-41, ["pixel size"]),
        (1e-9, 10.0, ["pixel size"]),
    ],
)
def test_physical_bounds_of_instrument_files(scale, pixel, words):
    from roughcontact._plausibility import check_metres

    with pytest.raises(ParameterError) as err:
        check_metres(_surface() * scale, (pixel, pixel), "path 'x.plu'")
    for word in words:
        assert word in str(err.value)
    check_metres(_surface() * 1e-9, (1e-8, 1e-8), "path 'x.plu'")


@pytest.mark.parametrize("offset", [52, 54, 56, 60, 72])
def test_metropro_header_that_disagrees_with_its_data(tmp_path, offset):
    pytest.importorskip("SurfaceTopography")
    raw = bytearray((DATA / "metropro-1.dat").read_bytes())
    raw[offset : offset + 2] = b"\0\0"  # one zeroed header field
    damaged = tmp_path / "m.dat"
    damaged.write_bytes(bytes(raw))
    with pytest.raises(ParameterError) as err:
        load_topography(damaged, fill_missing=True)
    assert "\n" not in str(err.value)


def test_the_real_instrument_files_stay_plausible():
    pytest.importorskip("SurfaceTopography")
    for name in ("metropro-1.dat", "di-1.di", "nid-1.nid", "dektak-1.csv"):
        topo = load_topography(DATA / name)
        assert topo.length_unit == "m"


def test_flat_surface_with_relative_offset_units(tmp_path):
    from roughcontact import relative_offsets

    flat = np.zeros((8, 8))
    for unit in ("rms_height", "bearing_area"):
        with pytest.raises(ParameterError, match="flat"):
            relative_offsets(flat, [0.5, 0.0], unit)
    assert list(relative_offsets(flat, [0.5, 0.0], "length")) == [0.5, 0.0]
    np.save(tmp_path / "z.npy", np.full((16, 16), 2.0))
    for unit, values in (
        ("rms_height", ["0.5", "-0.5", "0.25"]),
        ("bearing_area", ["0", "1", "0.5"]),
    ):
        r = CliRunner().invoke(
            main,
            ["path", str(tmp_path / "z.npy"), "--offsets", *values, "--offset-unit", unit,
             "-o", str(tmp_path / "p.nc")],
        )  # fmt: skip
        _one_line(r, "flat")
        assert not (tmp_path / "p.nc").exists()


def test_plausibility_bounds_are_documented():
    doc = _plausibility.__doc__
    for bound in ("1e150", "1e-9", "1 fm", "1 m", "1 pm"):
        assert bound in doc


# --- fuzz: damaged inputs give one ParameterError line, never another exception --------


@pytest.mark.parametrize("seed", range(3))
def test_fuzzed_inputs_are_one_line_errors(tmp_path, seed):
    rng = np.random.default_rng(seed)
    buf = io.BytesIO()
    np.save(buf, _surface(seed))
    good_npy = bytearray(buf.getvalue())
    flips = rng.integers(0, len(good_npy), size=20)
    good_npy[flips[0] % 128] ^= 0xFF  # the header too
    for i in flips[1:]:
        good_npy[i] ^= 1 << int(rng.integers(8))
    toml = bytearray(SMOKE.read_bytes())
    for i in rng.integers(0, len(toml), size=5):
        toml[i] = int(rng.integers(256))
    cases = {
        "a.npy": bytes(good_npy),
        "b.npy": rng.bytes(int(rng.integers(0, 300))),
        "c.txt": rng.bytes(200),
        "d.toml": bytes(toml),
        "e.nc": rng.bytes(512),
    }
    readers = {
        ".npy": [load_heights, load_topography],
        ".txt": [load_heights],
        ".toml": [load_study],
        ".nc": [lambda p: _io.read_netcdf(p, refusal="not a NetCDF file")],
    }
    for name, content in cases.items():
        path = tmp_path / name
        path.write_bytes(content)
        for read in readers[path.suffix]:
            try:
                read(path)
            except ParameterError as err:
                assert "\n" not in str(err), str(err)
