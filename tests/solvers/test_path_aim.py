"""Paths a user can aim: ``until_area``, the pull-off only when measured, the heights.

Oracles: a path stopped by ``until_area`` is, by definition, the path over the values it
visited (the same warm-started solves, the same retraction); the pull-off is the
definition max(0, -min retract load) when the surfaces separated; the stored heights
and substrate attributes rebuild the inputs exactly.
"""

import math

import numpy as np
import pytest
import xarray as xr

import roughcontact as rc
from roughcontact.elastic import Substrate

N = 32
H = rc.self_affine((N, N), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=3)
SUB = rc.Substrate((N, N))
OFFSETS = H.max() - np.linspace(0.0, 0.2, 9)  # hard wall: from first contact inwards
PER_STEP = ("offset", "load", "repulsive_area", "attractive_area", "mean_gap", "iterations")


def _same_steps(a, b):
    """Two paths with the same states (per-step variables, branches, kept fields)."""
    assert a.sizes["step"] == b.sizes["step"]
    for name in PER_STEP:
        np.testing.assert_allclose(a[name].values, b[name].values, rtol=1e-12, atol=0)
    np.testing.assert_array_equal(a["branch"].values, b["branch"].values)
    if "field_step" in b.coords or "field_step" in a.coords:
        np.testing.assert_array_equal(a["field_step"].values, b["field_step"].values)
        for name in ("pressure", "gap", "deflection"):
            np.testing.assert_allclose(a[name].values, b[name].values, rtol=1e-12, atol=0)


@pytest.fixture(scope="module")
def full():
    return rc.approach_retract(H, SUB, offsets=OFFSETS, retract=False)


@pytest.mark.parametrize("retract", [False, True])
def test_until_area_stops_at_the_first_step_reaching_it(full, retract):
    area = full["repulsive_area"].values
    assert np.all(np.diff(area) >= 0) and area[4] > area[3]  # pushed in: the area grows
    target = 0.5 * (area[3] + area[4])  # first reached at step 4
    ds = rc.approach_retract(H, SUB, offsets=OFFSETS, retract=retract, until_area=target)
    k = int(np.argmax(area >= target))
    assert k == 4 and ds.attrs["until_area_reached"] == 1
    assert ds.attrs["until_area"] == target
    approach = ds.isel(step=ds["branch"].values == "approach")
    _same_steps(approach, full.isel(step=slice(0, k + 1)))
    # the retraction mirrors the visited values: the same as a path over them
    visited = rc.approach_retract(H, SUB, offsets=OFFSETS[: k + 1], retract=retract)
    _same_steps(ds, visited)
    if retract:
        assert ds.sizes["step"] == 2 * k + 1
        np.testing.assert_array_equal(ds["offset"].values[k:], OFFSETS[: k + 1][::-1])


def test_until_area_reached_exactly_at_a_state_stops_there(full):
    area = full["repulsive_area"].values
    assert area[2] == area[3] > area[1]  # a tie: the first of the two stops the approach
    ds = rc.approach_retract(H, SUB, offsets=OFFSETS, retract=False, until_area=area[2])
    assert ds.sizes["step"] == 3 and ds.attrs["until_area_reached"] == 1  # >=, not >


def test_until_area_not_reached_runs_the_whole_path(full):
    ds = rc.approach_retract(H, SUB, offsets=OFFSETS, retract=False, until_area=1.0)
    assert ds.attrs["until_area_reached"] == 0
    _same_steps(ds, full)
    plain = rc.approach_retract(H, SUB, offsets=OFFSETS[:2], retract=False)
    assert math.isnan(plain.attrs["until_area"]) and plain.attrs["until_area_reached"] == 0


def test_until_area_under_load_control():
    loads = [1e-3, 2e-3, 4e-3, 8e-3, 1.6e-2]
    full = rc.approach_retract(H, SUB, loads=loads, retract=False)
    target = float(full["repulsive_area"].values[2])
    ds = rc.approach_retract(H, SUB, loads=loads, retract=True, until_area=target)
    _same_steps(ds, rc.approach_retract(H, SUB, loads=loads[:3], retract=True))


@pytest.mark.parametrize("retract", [False, True])
def test_fields_at_counts_from_the_end_of_the_path_followed(full, retract):
    area = full["repulsive_area"].values
    steps = [-1, -2, -4, 1, 50]  # 50: beyond the end, ignored
    ds = rc.approach_retract(
        H, SUB, offsets=OFFSETS, retract=retract, until_area=area[4], fields_at=steps
    )
    visited = rc.approach_retract(
        H, SUB, offsets=OFFSETS[:5], retract=retract, fields_at=[-1, -2, -4, 1]
    )
    _same_steps(ds, visited)
    n = ds.sizes["step"]
    assert list(ds["field_step"].values) == sorted({n - 1, n - 2, n - 4, 1})


@pytest.mark.parametrize("bad", [0, -0.1, 1.5, math.nan, "a lot"])
def test_until_area_out_of_range(bad):
    with pytest.raises(rc.ParameterError, match=r"until_area .*\(0, 1\]"):
        rc.approach_retract(H, SUB, offsets=OFFSETS, until_area=bad)


def test_pull_off_is_nan_when_the_surfaces_never_separated():
    # starts inside contact: the retraction ends in the first state, still in contact
    ds = rc.approach_retract(H, SUB, offsets=OFFSETS[2:], retract=True)
    assert ds["repulsive_area"].values[-1] > 0
    assert math.isnan(ds.attrs["pull_off"]) and ds.attrs["separated"] == 0
    # from first contact (no repulsive area at d = max h) the hard wall separates: 0
    ds = rc.approach_retract(H, SUB, offsets=OFFSETS, retract=True)
    assert ds["repulsive_area"].values[-1] == 0
    assert ds.attrs["pull_off"] == 0.0 and ds.attrs["separated"] == 1
    # no retraction: nothing measured
    ds = rc.approach_retract(H, SUB, offsets=OFFSETS, retract=False)
    assert math.isnan(ds.attrs["pull_off"]) and ds.attrs["separated"] == 0


def test_pull_off_of_an_adhesive_path_that_separates():
    law = rc.SmoothLJ93.from_adhesion_length(0.01)
    first = float(H.max()) + law.equilibrium_distance
    offsets = first + np.arange(1.5, -0.31, -0.15)
    ds = rc.approach_retract(H, SUB, law, offsets=offsets, retract=True, tol=1e-8)
    back = ds.isel(step=ds["branch"].values == "retract")
    assert ds.attrs["separated"] == 1 and back["repulsive_area"].values[-1] == 0
    assert ds.attrs["pull_off"] == max(0.0, -float(back["load"].min()))  # the definition
    assert ds.attrs["pull_off"] > 0


def test_heights_and_substrate_rebuild_from_the_dataset(tmp_path):
    layer = Substrate((N, N), thickness=20.0, poisson=0.3, base="frictionless")
    ds = rc.approach_retract(H, layer, offsets=OFFSETS[:2], dtype="float32", retract=False)
    assert ds["heights"].dims == ("x", "y") and ds["heights"].dtype == np.float64
    np.testing.assert_array_equal(ds["heights"].values, H)  # float64, not the float32 used
    ds.to_netcdf(tmp_path / "p.nc", engine="h5netcdf")
    half = rc.approach_retract(H.tolist(), SUB, offsets=OFFSETS[:1], retract=False)
    np.testing.assert_array_equal(half["heights"].values, H)  # host float64 from a list
    half.to_netcdf(tmp_path / "h.nc", engine="h5netcdf")
    for name, sub in (("p.nc", layer), ("h.nc", SUB)):
        with xr.open_dataset(tmp_path / name, engine="h5netcdf") as back:
            a = back.attrs
            np.testing.assert_array_equal(back["heights"].values, H)
            thickness = float(a["thickness"])
            rebuilt = Substrate(
                tuple(int(n) for n in np.atleast_1d(a["grid"])),
                contact_modulus=float(a["contact_modulus"]),
                pixel_size=float(a["pixel_size"]),
                thickness=None if math.isinf(thickness) else thickness,
                poisson=float(a["poisson"]),
                base=str(a["base"]) or "bonded",
            )
            assert rebuilt == sub
            np.testing.assert_array_equal(rebuilt.stiffness, sub.stiffness)
    assert layer.base == "frictionless" and ds.attrs["base"] == "frictionless"
    assert half.attrs["base"] == ""  # a half-space has no base
