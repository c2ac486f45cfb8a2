"""Offsets relative to the first contact: one convention for the studies and the CLI.

Oracles are the definitions: the undeformed gap at the summit is d0 at first contact,
the rms height is the standard deviation of the heights, and the bearing-area fraction is
the share of sites where the undeformed surfaces overlap (h > d - d0).
"""

import numpy as np
import pytest

import roughcontact as rc
from roughcontact.solvers.offsets import first_contact_offset, relative_offsets
from roughcontact.studies.task import path_values

H = rc.self_affine((32, 48), hurst=0.7, rms_slope=0.1, short_cutoff=4, seed=5)
LAWS = {
    "hardwall": (rc.HardWall(), 0.0),
    "lj93": (rc.LennardJones93(work_of_adhesion=0.01, equilibrium_distance=0.7), 0.7),
    "lj93smooth": (rc.SmoothLJ93.from_adhesion_length(0.01), 1.0),
    "none": (None, 0.0),
}


@pytest.mark.parametrize("name", LAWS)
def test_first_contact_is_the_summit_at_the_equilibrium_distance(name):
    law, d0 = LAWS[name]
    first = first_contact_offset(H, law)
    assert first == float(H.max()) + d0
    for unit in ("length", "rms_height", "bearing_area"):
        (d,) = relative_offsets(H, [0.0], unit, law)
        assert d == pytest.approx(first, abs=1e-14)
        assert np.min(d - H) == pytest.approx(d0, abs=1e-14)  # the undeformed gap


def test_length_and_rms_height_units():
    law, d0 = LAWS["lj93smooth"]
    v = np.array([0.5, 0.0, -0.25, -2.0])
    d = relative_offsets(H, v, "length", law)
    np.testing.assert_allclose(d, H.max() + d0 + v, rtol=0, atol=1e-14)
    d = relative_offsets(H, v, "rms_height", law, pixel_size=2.0)
    np.testing.assert_allclose((d - H.max() - d0)[v != 0] / v[v != 0], np.std(H), rtol=1e-12)
    assert d.dtype == np.float64 and d.shape == v.shape


@pytest.mark.parametrize("name", ["hardwall", "lj93"])
def test_bearing_area_is_the_overlap_of_the_undeformed_surfaces(name):
    law, d0 = LAWS[name]
    n = H.size
    k = np.array([0, 1, 7, 100, n // 2, n - 1])
    d = relative_offsets(H, k / n, "bearing_area", law)
    overlap = np.array([np.count_nonzero(H - (x - d0) > 1e-12) for x in d])  # d0 rounds
    np.testing.assert_array_equal(overlap, k)  # exactly k sites for v = k/N
    v = np.array([0.0013, 0.02, 0.31, 0.777, 1.0])
    d = relative_offsets(H, v, "bearing_area", law)
    overlap = np.array([np.count_nonzero(H - (x - d0) > 1e-12) for x in d]) / n
    assert np.all(np.abs(overlap - v) <= 1.0 / n)
    assert np.all(np.diff(d) < 0)  # growing fractions: deeper into contact


@pytest.mark.parametrize(
    ("values", "unit", "match"),
    [
        ([0.1], "mm", "unit must be one of 'length', 'rms_height', 'bearing_area'"),
        ([np.nan], "length", "finite"),
        ([np.inf], "rms_height", "finite"),
        ([1.2], "bearing_area", r"\[0, 1\]"),
        ([-0.1], "bearing_area", r"\[0, 1\]"),
    ],
)
def test_bad_values(values, unit, match):
    with pytest.raises(rc.ParameterError, match=match):
        relative_offsets(H, values, unit)


def test_the_studies_use_it():
    law, d0 = LAWS["lj93smooth"]
    params = {"pixel_size": 1.0, "contact_modulus": 1.0}
    for unit in ("length", "rms_height", "bearing_area"):
        path = {
            "values": [0.0, 0.25, 0.5] if unit == "bearing_area" else [0.5, 0.0, -1.0],
            "num": None,
            "control": "offset",
            "unit": unit,
            "lead_in": [2.0, 1.0],
        }
        got = path_values(path, H, law, params)
        np.testing.assert_array_equal(got[:2], H.max() + d0 + np.array([2.0, 1.0]))
        np.testing.assert_array_equal(got[2:], relative_offsets(H, path["values"], unit, law))


def test_stepped_values_are_the_arithmetic_progression_to_stop():
    from roughcontact.solvers.offsets import stepped_values

    # decimal steps reach STOP despite rounding (0.1 * 10 > 1 - 1e-9 steps short)
    np.testing.assert_allclose(stepped_values(0, 1, 0.1), np.linspace(0, 1, 11), atol=1e-15)
    np.testing.assert_allclose(stepped_values(1, 0, 0.1), np.linspace(1, 0, 11), atol=1e-15)
    np.testing.assert_array_equal(stepped_values(2, -1, -1), [2.0, 1.0, 0.0, -1.0])  # |STEP|
    np.testing.assert_array_equal(stepped_values(0, 0.95, 0.25), [0, 0.25, 0.5, 0.75])
    assert stepped_values(3, 3, 1).tolist() == [3.0]
    assert stepped_values(0, 2, 1).dtype == np.float64  # integers in, float64 out
    for args, words in (
        ((0, 1, 0), "--offsets STEP must be non-zero"),
        ((0, np.inf, 1), "must be finite"),
        ((0, 1e6, 1), "gives more than 100000 steps"),
    ):
        with pytest.raises(rc.ParameterError, match=words):
            stepped_values(*args, name="--offsets")
    # the studies' [path] start/stop/step step the same way
    path = {"values": None, "num": None, "start": 0.5, "stop": -2.0, "step": 0.125,
            "control": "load", "unit": "modulus"}  # fmt: skip
    loads = path_values(path, H, None, {"pixel_size": 1.0, "contact_modulus": 2.0})
    np.testing.assert_allclose(loads, 2.0 * np.linspace(0.5, -2.0, 21), atol=1e-15)
