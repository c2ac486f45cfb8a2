"""Spikes, sentinel values and isolated pixels (issue 41, item 2).

Oracles: surfaces of known statistics (``rc.self_affine``) with spikes or sentinel pixels
put in here at known places; the rms slope of the clean surface; the surfaces on which
nothing may be flagged (self-affine of any H, white noise, quantised noise, a tilted
terrace staircase).
"""

import json

import numpy as np
import pytest
from click.testing import CliRunner

import roughcontact as rc
from roughcontact.cli.main import main
from roughcontact.topography import stick
from roughcontact.topography.outliers import SPIKE_THRESHOLD, find_outliers

NM = 1e-9
SILICON = {"modulus": "160 GPa", "poisson": 0.22, "work_of_adhesion": "0.1 J/m^2"}


def _surface(n=128, hurst=0.8, seed=1):
    return rc.self_affine((n, n), hurst=hurst, rms_height=1.0, short_cutoff=2, seed=seed)


@pytest.mark.parametrize("hurst", [0.2, 0.5, 0.8, 1.0])
def test_nothing_is_flagged_on_surfaces_without_outliers(hurst):
    for seed in range(3):
        h = _surface(hurst=hurst, seed=seed)
        assert find_outliers(h)[1]["points"] == 0
        assert find_outliers(h[:, 0])[1]["points"] == 0
        assert find_outliers(h + 0.3 * np.arange(128)[:, None])[1]["points"] == 0  # a tilt
    rng = np.random.default_rng(0)
    assert find_outliers(rng.standard_normal((128, 128)))[1]["points"] == 0
    assert find_outliers(np.round(3 * rng.standard_normal((128, 128))))[1]["points"] == 0


def test_steps_and_scratches_are_the_surface_not_spikes():
    x, y = np.meshgrid(np.arange(96), np.arange(96), indexing="ij")
    terraces = np.floor((x + 0.6 * y) / 12.0) + 1e-3 * _surface(96)  # diagonal steps
    assert find_outliers(terraces)[1]["points"] == 0
    scratch = _surface(96)
    scratch[40, :] -= 30.0  # a groove along y: a spike across it, not along it
    assert find_outliers(scratch)[1]["points"] == 0


def test_spikes_are_found_counted_and_removed_by_default(tmp_path):
    """0.5 % spike pixels (single pixels and some pairs) double h'rms; removed, the clean
    surface's h'rms comes back within 3 %."""
    h = _surface(256)
    rng = np.random.default_rng(5)
    inner = np.zeros(h.shape, bool)
    inner[1:-1, 1:-1] = True  # at the edge a spike is tested along the edge only
    idx = rng.choice(np.flatnonzero(inner), int(0.005 * h.size), replace=False)
    spiky = h.copy()
    spiky.flat[idx] += rng.choice([-1.0, 1.0], idx.size) * 15 * np.std(h)
    found, report = find_outliers(spiky)
    assert report["spikes"] == idx.size and found.flat[idx].all() and found.sum() == idx.size
    path = tmp_path / "spiky.npy"
    np.save(path, spiky)
    kw = {"reliability_cutoff": "2 nm", **SILICON}  # the same scales for the three
    clean = stick(rc_topo(h), **kw).statistics.rms_slope
    kept = stick(path, pixel_size="1 nm", height_unit="nm", outliers="keep", **kw)
    removed = stick(path, pixel_size="1 nm", height_unit="nm", **kw)
    assert kept.statistics.rms_slope > 2 * clean  # the spikes set h'rms when kept
    assert removed.statistics.rms_slope == pytest.approx(clean, rel=0.03)
    d = removed.to_dict()
    assert d["outliers"]["spikes"] == idx.size and d["outliers"]["action"] == "removed"
    assert d["inputs"]["outliers"] == "remove"
    note = next(n for n in d["notes"] if n.startswith("outliers:"))
    assert f"{idx.size} spikes" in note and "removed" in note and "--outliers keep" in note
    k = kept.to_dict()["outliers"]
    assert k["action"] == "kept" and k["points"] == idx.size
    # the CLI: the option and its text
    args = ["stick", str(path), "--pixel-size", "1nm", "--height-unit", "nm",
            "--modulus", "160GPa", "--work-of-adhesion", "0.1J/m^2"]  # fmt: skip
    out = CliRunner().invoke(main, [*args, "--outliers", "keep", "--json"])
    assert out.exit_code == 0 and json.loads(out.output)["outliers"]["action"] == "kept"
    text = CliRunner().invoke(main, args).output
    assert f"outliers: {idx.size} of {h.size} points" in text


def rc_topo(h):
    from roughcontact.topography import Topography

    return Topography(h * NM, (NM, NM), height_unit="m", info={"length_unit": "m"})


def test_sentinel_pixels_in_a_missing_region(tmp_path):
    """A missing region (NaN) with hundreds of isolated "valid" pixels holding one
    sentinel value: found as a sentinel, removed by default; kept, they raise h'rms and
    the note on the filling says so with the right sign."""
    h = _surface(128)
    holed = h.copy()
    holed[20:70, 30:90] = np.nan  # 18 % missing
    sentinel = holed.copy()
    pins = np.zeros(h.shape, bool)
    pins[22:68:3, 32:88:3] = True  # isolated pixels, none next to another
    sentinel[pins] = -7.5
    n = int(pins.sum())
    assert n > 200
    found, report = find_outliers(sentinel, np.isnan(sentinel))
    assert report["sentinel_value"] == -7.5 and report["sentinel_points"] == n
    assert found[pins].all() and found.sum() == n
    ref_path, path = tmp_path / "holed.npy", tmp_path / "sentinel.npy"
    np.save(ref_path, holed)
    np.save(path, sentinel)
    kw = {"pixel_size": "1 nm", "height_unit": "nm", "fill_missing": True, **SILICON}
    ref = stick(ref_path, **kw)  # the same holes, no sentinel
    removed = stick(path, **kw)
    kept = stick(path, outliers="keep", **kw)
    assert removed.statistics.rms_slope == pytest.approx(ref.statistics.rms_slope, rel=1e-9)
    assert kept.statistics.rms_slope > 1.5 * ref.statistics.rms_slope
    d = removed.to_dict()
    assert d["outliers"]["sentinel_points"] == n and d["missing_data"]["outliers"] == n
    # the filling's note has the sign it measures: lower for plain holes, higher with pins
    fill = [x for x in ref.notes if x.startswith("filled")][0]
    assert "lower than that of the measured points alone" in fill
    pinned = [x for x in kept.notes if x.startswith("filled")][0]
    assert "higher than that of the measured points alone" in pinned
    assert kept.to_dict()["missing_data"]["slope_change"] > 0 > ref.to_dict()[
        "missing_data"]["slope_change"]  # fmt: skip


def test_the_rule_is_stated_with_its_threshold():
    h = _surface(64)
    h[30, 30] += 50.0
    report = find_outliers(h)[1]
    assert report["spikes"] == 1 and report["threshold"] == SPIKE_THRESHOLD
    assert "1.4826 MAD" in report["rule"] and "every axis and diagonal" in report["rule"]


def test_islands_in_a_hole_are_judged_by_the_height_distribution():
    """Pairs of valid pixels inside a missing region: the surface's own heights stay,
    heights 10 rms away from the interpolation around them go (isolated, not spikes)."""
    h = _surface(128)
    hole = np.zeros(h.shape, bool)
    hole[30:80, 30:90] = True
    pairs = np.zeros(h.shape, bool)
    pairs[33:78:4, 33:88:4] = True
    pairs[33:78:4, 34:89:4] = True  # two pixels side by side: not isolated pixels
    missing = hole & ~pairs
    true_heights = np.where(missing, np.nan, h)
    assert find_outliers(true_heights, missing)[1]["points"] == 0
    wild = true_heights.copy()
    rng = np.random.default_rng(2)
    wild[pairs] = rng.choice([-1, 1], int(pairs.sum())) * rng.uniform(10, 20, int(pairs.sum()))
    found, report = find_outliers(wild, missing)
    assert report["isolated"] == int(pairs.sum()) and found[pairs].all()
    assert report["sentinel_value"] is None and report["spikes"] == 0
