"""Reading instrument files: grid, sizes and heights against the files' own metadata.

The oracles are independent readers of each vendor's header (text keys or the binary
offsets of the vendor's documentation) written here, not SurfaceTopography: the heights
must equal the raw counts times the file's own scale factor, in metres, element by
element where the orientation is known (axis 0 = the fast scan direction).
"""

from __future__ import annotations

import json
import re
import struct
import sys
from pathlib import Path

import numpy as np
import pytest
from _helpers import raises_one_line

import roughcontact as rc
from roughcontact.topography import file_kind, load_topography

DATA = Path(__file__).resolve().parents[1] / "data" / "topographies"
UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "\u00b5m": 1e-6, "nm": 1e-9}


def data_file(name: str) -> Path:
    """A real instrument file kept in the repository (tests/data/topographies/README.md)."""
    import SurfaceTopography  # noqa: F401  (a test dependency: it must be installed)

    path = DATA / name
    assert path.is_file(), f"test data {path} missing from the repository"
    return path


def nanoscope(path: Path, image: int = 0) -> dict:
    """Bruker/DI Nanoscope: the text header's ``\\*Ciao image list`` number ``image``.

    Height per count = Z scale (V) x Z sensitivity (nm/V) / 2^(8 bytes per pixel).
    """
    raw = path.read_bytes()
    header = raw[: raw.index(b"\\*File list end")].decode("latin-1")
    sens = float(re.search(r"\\@Sens\. Zsens: V ([\d.eE+-]+) nm/V", header).group(1))
    section = header.split("\\*Ciao image list")[1 + image].split("\\*")[0]

    def key(name):
        return re.search(rf"\\{re.escape(name)}: (.*)", section).group(1).strip()

    size = key("Scan Size").split()
    nbytes = int(key("Bytes/pixel"))
    scale_v = float(key("@2:Z scale").split()[-2])
    counts = np.frombuffer(
        raw,
        dtype=f"<i{nbytes}",
        count=int(key("Samps/line")) * int(key("Number of lines")),
        offset=int(key("Data offset")),
    )
    return {
        "shape": (int(key("Samps/line")), int(key("Number of lines"))),
        "size": (float(size[0]) * UNITS[size[2]], float(size[1]) * UNITS[size[2]]),
        "name": re.search(r'"(.*)"', key("@2:Image Data")).group(1),
        "heights": counts * scale_v * sens * 1e-9 / 2 ** (8 * nbytes),
    }


def nanosurf(path: Path, name: str = "Z-Axis", frame: str = "Scan forward") -> dict:
    """Nanosurf .nid: ``[DataSet-g:c]`` sections; blocks follow ``#!`` in group order."""
    raw = path.read_bytes()
    start = raw.index(b"#!")
    header = raw[:start].decode("latin-1")
    order = re.findall(r"Gr\d+-Ch\d+=(DataSet-\d+:\d+)", header)
    offset = 0
    for ds in order:
        sec = dict(
            line.split("=", 1)
            for line in header.split(f"[{ds}]")[1].split("\n[")[0].splitlines()
            if "=" in line
        )
        n = int(sec["Points"]) * int(sec["Lines"])
        nbytes = int(sec["SaveBits"]) // 8
        if sec["Dim2Name"].strip() == name and sec["Frame"].strip() == frame:
            counts = np.frombuffer(raw, dtype=f"<i{nbytes}", count=n, offset=start + 2 + offset)
            unit = UNITS[sec["Dim0Unit"].strip()]
            return {
                "shape": (int(sec["Points"]), int(sec["Lines"])),
                "size": (float(sec["Dim0Range"]) * unit, float(sec["Dim1Range"]) * unit),
                "heights": counts * float(sec["Dim2Range"]) / 2 ** (8 * nbytes),
            }
        offset += n * nbytes
    raise KeyError(name)


def metropro(path: Path) -> dict:
    """Zygo MetroPro .dat: big-endian binary header at the offsets of Zygo's manual.

    Height = counts x S x W x O / R (interferometric scale factor S, wavelength W,
    obliquity O; R = 4096, 32768 or 131072 for phase_res 0, 1, 2); counts of 2147483640
    and above are invalid.
    """
    b = path.read_bytes()
    header_size = struct.unpack(">I", b[6:10])[0]
    ac_width, ac_height, buckets = struct.unpack(">HHH", b[52:58])
    width, height = struct.unpack(">HH", b[68:72])
    s, w = struct.unpack(">ff", b[164:172])
    o = struct.unpack(">f", b[176:180])[0]
    camera_res = struct.unpack(">f", b[184:188])[0]
    r = {0: 4096, 1: 32768, 2: 131072}[struct.unpack(">H", b[218:220])[0]]
    offset = header_size + buckets * ac_width * ac_height * 2
    counts = np.frombuffer(b, dtype=">i4", count=width * height, offset=offset)
    valid = counts < 2147483640
    return {
        "shape": (width, height),
        "size": (width * camera_res, height * camera_res),
        "heights": counts[valid] * s * w * o / r,
        "invalid": int((~valid).sum()),
    }


def dektak(path: Path) -> dict:
    """Dektak CSV: scan parameters, then ``Lateral um,Raw Micrometer`` rows."""
    lines = path.read_text(encoding="latin-1").splitlines()
    meta = {ln.split(",", 1)[0]: ln.split(",", 1)[1] for ln in lines if "," in ln}
    first = next(i for i, ln in enumerate(lines) if ln.startswith("Lateral um")) + 1
    rows = [ln.split(",")[:2] for ln in lines[first:] if ln.strip()]
    x, h = np.array(rows, dtype=float).T
    length, unit = meta["Length"].split()
    radius = re.search(r"Radius: ([\d.]+)", meta["Stylus"]).group(1)
    return {
        "x": x * 1e-6,
        "heights": h * 1e-6,
        "length": float(length) * UNITS[unit],
        "tip_radius": float(radius) * 1e-6,
    }


# ----------------------------------------------------------------------------- files


@pytest.mark.parametrize("image", [0, 1])
def test_nanoscope_heights_sizes_and_units(image):
    path = data_file("di-1.di")
    ref = nanoscope(path, image)
    topo = load_topography(path, channel=image)
    assert topo.shape == ref["shape"] == (512, 512)
    assert topo.physical_size == pytest.approx(ref["size"], rel=1e-12)
    assert topo.pixel_size == pytest.approx((500e-9 / 512,) * 2, rel=1e-12)
    assert topo.height_unit == "nm" and topo.length_unit == "m"
    assert topo.channel == ref["name"] == "Height"
    assert topo.info["channel_index"] == image
    # heights[i, j]: sample i of line (511 - j): lines are stored last line first
    expected = ref["heights"].reshape(512, 512).T[:, ::-1]
    np.testing.assert_allclose(topo.heights, expected, rtol=1e-12, atol=0)
    assert topo.periodic is False and topo.dim == 2


def test_nanoscope_default_channel_and_names():
    path = data_file("di-1.di")
    topo = load_topography(path)
    names = re.findall(r"@2:Image Data: S \[(\w+)\]", path.read_bytes()[:40960].decode("latin-1"))
    assert topo.info["channels"] == names == ["Height", "Height", "Phase", "AmplitudeError"]
    assert topo.channel == "Height" and topo.info["channel_index"] == 0
    # equal names: the channel id picks the second, an index too, a digit string too
    second = load_topography(path, channel="Height#2")
    assert second.info["channel_index"] == 1
    np.testing.assert_array_equal(second.heights, load_topography(path, channel="1").heights)
    assert "Dimension V" in json.dumps(topo.to_dict())


def test_nanoscope_channel_without_heights():
    raises_one_line(
        lambda: load_topography(data_file("di-1.di"), channel="Phase"),
        "'Phase'",
        "holds no heights",
        "0 'Height', 1 'Height'",
    )


@pytest.mark.parametrize(
    ("channel", "frame"), [(None, "Scan forward"), ("Scan backward (Z-Axis)", "Scan backward")]
)
def test_nanosurf_heights_sizes_and_units(channel, frame):
    path = data_file("nid-1.nid")
    ref = nanosurf(path, frame=frame)
    topo = load_topography(path, channel=channel)
    assert topo.shape == ref["shape"] == (256, 256)
    assert topo.physical_size == pytest.approx(ref["size"], rel=1e-12)
    assert ref["size"] == pytest.approx((20e-6, 20e-6))
    assert topo.height_unit == "m"
    np.testing.assert_allclose(
        topo.heights, ref["heights"].reshape(256, 256).T[:, ::-1], rtol=1e-12, atol=0
    )


def test_nanosurf_channel_by_index_equals_by_name():
    path = data_file("nid-1.nid")
    by_name = load_topography(path, channel="Scan backward (Z-Axis)")
    by_index = load_topography(path, channel=2)
    assert by_index.channel == by_name.channel == "Scan backward (Z-Axis)"
    np.testing.assert_array_equal(by_index.heights, by_name.heights)


def test_metropro_heights_sizes_and_units():
    path = data_file("metropro-1.dat")
    ref = metropro(path)
    topo = load_topography(path)
    assert topo.shape == ref["shape"] == (640, 480)
    assert topo.physical_size == pytest.approx(ref["size"], rel=1e-12)
    assert topo.physical_size == pytest.approx((0.70e-3, 0.53e-3), rel=0.01)
    assert ref["invalid"] == 0 and "missing_data" not in topo.info
    np.testing.assert_allclose(topo.heights, ref["heights"].reshape(480, 640).T, rtol=1e-12)


def test_dektak_line_scan_resampled_and_tip_radius():
    path = data_file("dektak-1.csv")
    ref = dektak(path)
    topo = load_topography(path)
    assert topo.dim == 1 and topo.shape == (9600,) == ref["x"].shape
    assert topo.physical_size[0] == pytest.approx(ref["length"], rel=1e-6)  # "Length,1500.0 um"
    assert topo.height_unit in ("\u00b5m", "um")
    assert topo.info["tip_radius"] == pytest.approx(ref["tip_radius"], rel=1e-12)
    # positions are written rounded to 0.1 um: within half a step of a uniform grid
    resampled = topo.info["resampled"]
    assert resampled["method"] == "linear" and resampled["max_deviation_steps"] <= 0.5
    # linear interpolation by less than half a step keeps the heights' moments
    assert np.mean(topo.heights) == pytest.approx(np.mean(ref["heights"]), rel=1e-4)
    assert np.std(topo.heights) == pytest.approx(np.std(ref["heights"]), rel=1e-4)
    # each uniform point lies within one step of its sample: bounded by the local change
    local = np.abs(np.diff(ref["heights"]))
    bound = np.maximum(np.r_[local, 0], np.r_[0, local])
    assert np.all(np.abs(topo.heights - ref["heights"]) <= bound + 1e-18)
    raises_one_line(lambda: load_topography(path, resample=False), "non-uniform", "resample=True")


def test_load_heights_of_instrument_files_in_metres():
    path = data_file("nid-1.nid")
    h = rc.load_heights(path, channel=1)
    np.testing.assert_array_equal(h, load_topography(path, channel=1).heights)
    assert h.flags.writeable
    raises_one_line(lambda: rc.load_heights(data_file("dektak-1.csv")), "line scan", "2D")


def test_file_kind():
    assert file_kind(data_file("di-1.di")) == "instrument"
    assert file_kind(data_file("metropro-1.dat")) == "instrument"
    assert file_kind(data_file("dektak-1.csv")) == "instrument"  # a header, then numbers


def test_instrument_file_keeps_its_own_units():
    path = data_file("nid-1.nid")
    raises_one_line(lambda: load_topography(path, pixel_size=1e-9), "pixel_size", "leave")
    raises_one_line(lambda: load_topography(path, height_unit="nm"), "height_unit", "leave")


# ---------------------------------------------------------------------------- errors


@pytest.mark.parametrize("channel", ["Amplitude", 4, -1, True])
def test_unknown_channel_lists_the_available_ones(channel):
    raises_one_line(
        lambda: load_topography(data_file("di-1.di"), channel=channel),
        "di-1.di",
        "0 'Height', 1 'Height', 2 'Phase', 3 'AmplitudeError'",
    )


@pytest.mark.parametrize(
    ("name", "channel"), [("di-1.di", None), ("nid-1.nid", 3), ("metropro-1.dat", None)]
)
def test_truncated_file(tmp_path, name, channel):
    raw = data_file(name).read_bytes()
    copy = tmp_path / name
    copy.write_bytes(raw[: len(raw) // 2])  # the channel's data is cut
    raises_one_line(lambda: load_topography(copy, channel=channel), name)
    raises_one_line(lambda: rc.load_heights(copy, channel=channel), name)


def test_missing_file(tmp_path):
    raises_one_line(lambda: load_topography(tmp_path / "nope.di"), "nope.di", "no such file")


@pytest.mark.parametrize(
    ("name", "content"),
    [
        ("noise.xyz", bytes(range(256)) * 40),
        ("words.txt", b"height map of a tyre\nmeasured yesterday\n"),
        ("garbage.txt", b"1 2 x\n3 4 5\n"),
    ],
)
def test_unknown_format(tmp_path, name, content):
    pytest.importorskip("SurfaceTopography")
    path = tmp_path / name
    path.write_bytes(content)
    if name == "garbage.txt":  # the reason numpy gives, too
        raises_one_line(lambda: load_topography(path), name, "as plain text", "'x'")
    else:
        raises_one_line(lambda: load_topography(path), name, "unknown or unreadable")
    raises_one_line(lambda: rc.load_heights(path), name)


def test_without_surface_topography(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "SurfaceTopography", None)  # import fails
    path = tmp_path / "scan.spm"
    path.write_bytes(b"\x00binary")
    raises_one_line(lambda: load_topography(path), 'pip install "roughcontact[topography]"')
    h = np.arange(12.0).reshape(3, 4)
    np.save(tmp_path / "h.npy", h)  # plain files need nothing else
    np.testing.assert_array_equal(load_topography(tmp_path / "h.npy").heights, h)


# ------------------------------------------------------------------ .npy and text


def test_plain_files_in_lattice_units_by_default(tmp_path):
    h = np.random.default_rng(0).standard_normal((4, 6))
    np.save(tmp_path / "h.npy", h)
    topo = load_topography(tmp_path / "h.npy")
    np.testing.assert_array_equal(topo.heights, h)
    assert topo.pixel_size == (1.0, 1.0) and topo.length_unit == "a0"
    assert "lattice" in topo.info["units"] and topo.channel == "heights"


def test_plain_files_with_units(tmp_path):
    h = np.random.default_rng(1).standard_normal((4, 6))
    np.savetxt(tmp_path / "h.txt", h)
    topo = load_topography(tmp_path / "h.txt", pixel_size=2e-9, height_unit="nm")
    np.testing.assert_allclose(topo.heights, h * 1e-9, rtol=1e-15)
    assert topo.pixel_size == (2e-9, 2e-9)
    assert topo.physical_size == pytest.approx((8e-9, 12e-9), rel=1e-15)
    assert topo.height_unit == "nm" and topo.length_unit == "m"
    metres = load_topography(tmp_path / "h.txt", pixel_size=(1e-9, 3e-9))  # heights in m
    np.testing.assert_array_equal(metres.heights, h)
    assert metres.pixel_size == (1e-9, 3e-9)
    raises_one_line(lambda: load_topography(tmp_path / "h.txt", height_unit="nm"), "pixel_size")
    raises_one_line(
        lambda: load_topography(tmp_path / "h.txt", pixel_size=1, height_unit="parsec"),
        "height_unit",
    )
    raises_one_line(lambda: load_topography(tmp_path / "h.txt", channel=1), "channel")


def test_plain_line_scan(tmp_path):
    (tmp_path / "line.txt").write_text("1 2 4 8\n")
    topo = load_topography(tmp_path / "line.txt", pixel_size=0.5, height_unit="um")
    assert topo.dim == 1 and topo.shape == (4,) and topo.physical_size == (2.0,)
    np.testing.assert_allclose(topo.heights, [1e-6, 2e-6, 4e-6, 8e-6])


def test_missing_points_refused_or_filled(tmp_path):
    x, y = np.meshgrid(np.arange(8.0), np.arange(9.0), indexing="ij")
    plane = 0.3 * x - 0.2 * y + 1.0
    data = plane.copy()
    data[3:5, 2:6] = np.nan  # inside the scan: a plane is harmonic, kept exactly
    np.save(tmp_path / "holes.npy", data)
    raises_one_line(
        lambda: load_topography(tmp_path / "holes.npy"), "holes.npy", "8 of 72", "11.1%",
        "--fill-missing",
    )  # fmt: skip
    topo = load_topography(tmp_path / "holes.npy", fill_missing=True)
    np.testing.assert_allclose(topo.heights, plane, rtol=0, atol=1e-12)
    missing = dict(topo.info["missing_data"])
    assert missing.pop("outliers") == 0  # issue 41: outliers removed among them
    assert abs(missing.pop("slope_change")) < 0.05  # a plane's filling: its own slope
    assert missing == {
        "points": 8, "fraction": 8 / 72, "filled": "harmonic", "asked": True
    }  # fmt: skip


# ------------------------------------------- what real files rarely show: a stand-in reader


class _Channel:
    def __init__(self, heights, unit, sizes):
        self.name, self.index, self.channel_id = "Z", 0, "Z"
        self.unit, self.physical_sizes = unit, sizes
        self.nb_grid_pts, self.info, self.height_scale_factor = heights.shape, {}, 1.0
        self.heights = heights


class _Scan:
    is_uniform, info = True, {}

    def __init__(self, channel, physical_sizes=None):
        self._h = channel.heights
        sizes = physical_sizes or channel.physical_sizes
        self.pixel_size = tuple(s / n for s, n in zip(sizes, self._h.shape, strict=True))

    def heights(self):
        return self._h


class _Reader:
    """The part of SurfaceTopography's reader interface that load_topography uses."""

    def __init__(self, heights, unit="nm", sizes=(8.0, 9.0)):
        self.channels = [_Channel(heights, unit, sizes)]
        self.default_channel = self.channels[0]

    def name(self):
        return "stand-in"

    def topography(self, channel_index, periodic, physical_sizes=None, unit=None):
        return _Scan(self.channels[channel_index], physical_sizes)


@pytest.fixture()
def stand_in(tmp_path, monkeypatch):
    """``stand_in(reader)``: a binary file that "SurfaceTopography" opens as ``reader``."""
    st = pytest.importorskip("SurfaceTopography")
    path = tmp_path / "scan.bin"
    path.write_bytes(b"\x00\x01")

    def use(reader):
        monkeypatch.setattr(st, "open_topography", lambda name: reader)
        return path

    return use


def test_masked_points_refused_or_filled(stand_in):
    x, y = np.meshgrid(np.arange(8.0), np.arange(9.0), indexing="ij")
    plane = 5.0 + 0.5 * x - 0.25 * y  # nm
    mask = np.zeros(plane.shape, dtype=bool)
    mask[2:4, 3:5] = True
    path = stand_in(_Reader(np.ma.masked_array(np.where(mask, -1e9, plane), mask)))
    raises_one_line(lambda: load_topography(path), "4 of 72", "5.6%", "fill_missing=True")
    topo = load_topography(path, fill_missing=True)
    np.testing.assert_allclose(topo.heights, plane * 1e-9, rtol=1e-12)
    assert topo.pixel_size == pytest.approx((1e-9, 1e-9))
    assert topo.info["missing_data"]["points"] == 4


def test_file_without_lateral_size_or_units(stand_in):
    h = np.arange(12.0).reshape(3, 4)
    path = stand_in(_Reader(h, unit=None, sizes=None))
    text = raises_one_line(lambda: load_topography(path), "holds no heights", "height_unit=")
    assert "as plain text" not in text  # a binary file
    raises_one_line(lambda: load_topography(path, height_unit="um"), "pixel_size", "lateral")
    topo = load_topography(path, pixel_size=2e-6, height_unit="um")
    np.testing.assert_allclose(topo.heights, h * 1e-6, rtol=1e-15)
    assert topo.pixel_size == pytest.approx((2e-6, 2e-6)) and topo.height_unit == "um"
