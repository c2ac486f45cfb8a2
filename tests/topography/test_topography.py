"""The Topography record and the grid repairs done while reading.

Oracles: a plane (a line) is harmonic, so harmonic filling reproduces it exactly at
interior holes, as numpy.interp does in 1D; rounded positions lie within half a digit
of the uniform grid they were rounded from.
"""

from __future__ import annotations

import datetime
import json

import numpy as np
import pytest

from roughcontact import ParameterError
from roughcontact.topography import Topography
from roughcontact.topography._grid import harmonic_fill, uniform_positions


def test_record_fields_and_summary():
    h = np.arange(12.0).reshape(3, 4)
    when = datetime.datetime(2024, 5, 1, 12, 0)
    topo = Topography(h, (2e-9, 3e-9), channel="Height", source="scan.di", height_unit="nm",
                      info={"length_unit": "m", "acquisition_time": when, "n": np.int64(3),
                            "array": np.ones(3), "bad": float("nan")})  # fmt: skip
    assert topo.dim == 2 and topo.shape == (3, 4)
    assert topo.physical_size == pytest.approx((6e-9, 12e-9))
    assert topo.info == {"length_unit": "m", "acquisition_time": "2024-05-01T12:00:00",
                         "n": 3, "bad": None}  # fmt: skip
    d = json.loads(json.dumps(topo.to_dict(), allow_nan=False))
    assert d["shape"] == [3, 4] and d["pixel_size"] == [2e-9, 3e-9]
    assert d["physical_size"] == pytest.approx([6e-9, 12e-9])
    assert d["length_unit"] == "m" and d["height_unit"] == "nm" and d["channel"] == "Height"
    assert d["rms_height"] == pytest.approx(np.std(h)) and d["max_height"] == 11.0


def test_record_is_frozen_and_owns_its_heights():
    h = np.ones((3, 3))
    topo = Topography(h, 1.0)
    h[0, 0] = 5.0
    assert topo.heights[0, 0] == 1.0
    with pytest.raises(ValueError):
        topo.heights[0, 0] = 2.0
    with pytest.raises(AttributeError):
        topo.periodic = True
    assert topo.length_unit == "a0" and Topography(np.ones(4), 0.5).physical_size == (2.0,)


@pytest.mark.parametrize(
    ("heights", "pixel_size", "match"),
    [
        (np.ones((3, 3)), 0.0, "pixel_size"),
        (np.ones((3, 3)), (1.0, 2.0, 3.0), "pixel_size"),
        (np.ones((3, 3)), float("inf"), "pixel_size"),
        (np.ones((3, 3)), True, "pixel_size"),
        (np.ones((2, 2, 2)), 1.0, "1D"),
        (np.ones(1), 1.0, "at least 2"),
        (np.array([[1.0, np.nan], [0.0, 0.0]]), 1.0, "finite"),
        (np.ones((2, 2), dtype=complex), 1.0, "complex"),
    ],
)
def test_record_rejects_bad_input(heights, pixel_size, match):
    with pytest.raises(ParameterError, match=match):
        Topography(heights, pixel_size)


def test_harmonic_fill_keeps_a_plane_2d():
    x, y = np.meshgrid(np.arange(12.0), np.arange(10.0), indexing="ij")
    plane = 2.0 - 0.4 * x + 0.7 * y
    missing = np.zeros(plane.shape, dtype=bool)
    missing[2:5, 3:8] = True
    missing[8, 1] = True
    data = np.where(missing, 1e9, plane)  # values at missing points are ignored
    np.testing.assert_allclose(harmonic_fill(data, missing), plane, rtol=0, atol=1e-12)


def test_harmonic_fill_is_linear_interpolation_1d():
    rng = np.random.default_rng(2)
    h = rng.standard_normal(40)
    missing = np.zeros(40, dtype=bool)
    missing[[3, 4, 5, 17, 30, 31]] = True
    i = np.arange(40)
    expected = np.interp(i, i[~missing], h[~missing])
    np.testing.assert_allclose(harmonic_fill(h, missing), expected, rtol=0, atol=1e-12)


def test_harmonic_fill_periodic_wraps_and_all_missing_refused():
    h = np.array([0.0, 2.0, 0.0, 4.0])
    missing = np.array([True, False, False, False])
    # periodic: point 0 lies between 4 (its left neighbour, wrapped) and 2; else only 2
    assert harmonic_fill(h, missing, periodic=True)[0] == pytest.approx(3.0)
    assert harmonic_fill(h, missing, periodic=False)[0] == pytest.approx(2.0)
    with pytest.raises(ParameterError, match="every point"):
        harmonic_fill(h, np.ones(4, dtype=bool))


def test_uniform_positions_of_rounded_samples():
    true = 0.3 + 0.15625 * np.arange(500)
    start, step, deviation = uniform_positions(np.round(true, 1))
    assert step == pytest.approx(0.15625, rel=1e-4) and start == pytest.approx(0.3, abs=0.01)
    # rounding moves a point by at most half the last digit (0.32 steps) from the true grid
    assert 0.25 < deviation < 0.5
    with pytest.raises(ParameterError, match="increase"):
        uniform_positions(np.array([0.0, 2.0, 1.0]))
