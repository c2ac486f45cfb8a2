"""The path dataset's one owner: its layout, builder, reader and writer.

Oracles: the definition of a path (each step one :func:`roughcontact.solve`, warm-started
from the step before; the pull-off force the most tensile load of a retraction that
separates the surfaces; a jump a deflection change beyond ``jump_factor |Δd| + range/2``)
written out here step by step with plain xarray, independently of ``pathdata``; and
NetCDF itself for the round trip. Grids of 32².
"""

import math

import numpy as np
import pytest
import xarray as xr
from _helpers import one_line_message

import roughcontact as rc
from roughcontact.analysis.contact_geometry import contact_patches
from roughcontact.pathdata import (
    ATTRIBUTES,
    FIELDS,
    PER_STEP,
    REQUIRED,
    VARIABLES,
    add_fields,
    check_path,
    read_path,
    write_path,
)
from roughcontact.solvers.path import provenance
from roughcontact.solvers.result import STATE_SCALARS

N = 32
H = rc.self_affine((N, N), hurst=0.8, rms_slope=0.1, short_cutoff=4.0, seed=3)
SUB = rc.Substrate((N, N))
LAW = rc.SmoothLJ93(work_of_adhesion=0.01)
TOL = 1e-6
# from above the reach of the attraction into contact and back: the retraction separates
OFFSETS = float(H.max()) + LAW.equilibrium_distance + LAW.range - np.linspace(-0.5, 1.5, 7)
FIELDS_AT = (0, 3, -1)
TIMING = ("solve_seconds",)


@pytest.fixture(scope="module")
def path():
    return rc.approach_retract(
        H, SUB, LAW, offsets=OFFSETS, retract=True, tol=TOL, fields_at=FIELDS_AT
    )


def _by_hand():
    """The path as its definition has it, built step by step with plain xarray."""
    values = np.concatenate((OFFSETS, OFFSETS[-2::-1]))
    branch = ["approach"] * OFFSETS.size + ["retract"] * (OFFSETS.size - 1)
    states, previous = [], None
    for d in values:
        previous = rc.solve(H, SUB, LAW, offset=float(d), initial=previous, tol=TOL)
        states.append(previous)
    data = {k: ("step", np.array([getattr(s, k) for s in states])) for k in STATE_SCALARS}
    patches = [contact_patches(s.pressure > 0)[1].size for s in states]
    data["repulsive_patches"] = ("step", np.array(patches))
    jump = [False] + [
        float(np.abs(b.deflection - a.deflection).max())
        > 2.0 * abs(b.offset - a.offset) + 0.5 * LAW.range
        for a, b in zip(states, states[1:], strict=False)
    ]
    data["jump"] = ("step", np.array(jump))
    data["branch"] = ("step", np.array(branch))
    data["status"] = ("step", np.array([s.status.value for s in states]))
    ds = xr.Dataset(data, coords={"step": np.arange(values.size)})
    kept = sorted(i % values.size for i in FIELDS_AT)
    ds = ds.assign_coords(field_step=kept)
    for name in ("pressure", "gap", "deflection"):
        stack = np.stack([getattr(states[i], name) for i in kept])
        ds[name] = (("field_step", "x", "y"), stack)
    ds["heights"] = (("x", "y"), H)
    back = [s.load for s, b in zip(states, branch, strict=True) if b == "retract"]
    assert states[-1].repulsive_area == 0  # the problem is chosen so that it separates
    ds.attrs = {
        "control": "offset",
        "pull_off": max(0.0, -min(back)),
        "separated": 1,
        "all_converged": int(all(s.converged for s in states)),
        **provenance(H, SUB, LAW),
        "until_area": math.nan,
        "dtype": "float64",
        "device": "cpu",
        "until_area_reached": 0,
        "units": "lattice units unless given: loads and areas per nominal area A0",
    }
    return ds


def _untimed(ds):
    ds = ds.drop_vars([k for k in TIMING if k in ds.variables])
    ds.attrs = {k: v for k, v in ds.attrs.items() if k != "total_seconds"}
    return ds


def test_approach_retract_is_the_path_by_definition(path):
    expected = _by_hand()
    xr.testing.assert_identical(_untimed(path), _untimed(expected))
    assert list(path.variables) == list(expected.variables)  # the order of the file too
    for name in expected.variables:
        assert path[name].dtype == expected[name].dtype, name


def test_the_table_describes_every_variable_and_attribute(path):
    table = {v.name: v for v in VARIABLES}
    for name in path.data_vars:
        assert path[name].dims == table[name].dims
        assert path[name].dtype.kind == table[name].kind, name
    assert set(PER_STEP) <= set(path.data_vars) and set(FIELDS) <= set(path.data_vars)
    assert set(path.attrs) <= {a.name for a in ATTRIBUTES}
    # the state's scalars lead the per-step variables, in the state record's order
    assert PER_STEP[: len(STATE_SCALARS)] == STATE_SCALARS
    assert set(REQUIRED) <= set(PER_STEP)


def test_collected_step_variables_come_from_the_table():
    from roughcontact.studies.collect import STEP_VARIABLES
    from roughcontact.studies.schema import FIELDS as STUDY_FIELDS

    # a collected study's 'status' is the task's: every other per-step variable is kept
    assert set(PER_STEP) - set(STEP_VARIABLES) == {"status"}
    assert tuple(n for n in PER_STEP if n in STEP_VARIABLES) == STEP_VARIABLES
    assert STUDY_FIELDS == FIELDS


def test_round_trip_through_the_writer_and_the_reader(path, tmp_path):
    out = write_path(path, tmp_path / "p.nc", attrs={"surface_file": "h.npy"})
    assert "surface_file" not in path.attrs  # added to the file, not to the dataset
    back = read_path(out)
    assert back.attrs.pop("surface_file") == "h.npy"
    xr.testing.assert_identical(back, path)
    assert list(back.attrs) == list(path.attrs)
    for name in path.variables:
        assert back[name].dims == path[name].dims
        if path[name].dtype.kind != "U":  # text comes back as Python strings
            assert back[name].dtype == path[name].dtype, name
    # a failed write leaves nothing behind: the one writer is the atomic one
    assert sorted(p.name for p in tmp_path.iterdir()) == ["p.nc"]
    # the yes/no attributes come back as booleans (stored 1/0: netCDF has no bool), and a
    # path read back is written again as it was
    assert back.attrs["separated"] is True and back.attrs["all_converged"] is True
    again = read_path(write_path(back, tmp_path / "q.nc"))
    assert again.attrs["separated"] is True
    xr.testing.assert_identical(again, back)


def test_an_empty_path_round_trips(tmp_path):
    ds = rc.approach_retract(H, SUB, offsets=[float(H.max())], retract=False)
    empty = ds.isel(step=slice(0, 0))
    back = read_path(write_path(empty, tmp_path / "e.nc"))
    assert back.sizes["step"] == 0 and set(PER_STEP) <= set(back.variables)


@pytest.mark.parametrize("missing", ["perimeter", "branch"])
def test_reading_refuses_a_missing_variable(path, tmp_path, missing):
    f = write_path(path.drop_vars(missing), tmp_path / "m.nc")
    with pytest.raises(rc.ParameterError) as err:
        read_path(f)
    one_line_message(err, "lacks", missing)


@pytest.mark.parametrize(
    "edit",
    [
        lambda ds: ds.assign(offset=(("other",), ds["offset"].values)),
        lambda ds: ds.assign(pressure=(("x", "y"), ds["pressure"].values[0])),
        lambda ds: ds.assign(heights=(("y", "x"), ds["heights"].values.T)),
    ],
    ids=["step-variable", "field", "heights"],
)
def test_reading_refuses_wrong_dims(path, tmp_path, edit):
    bad = edit(path)
    name = next(n for n in ("offset", "pressure", "heights") if bad[n].dims != path[n].dims)
    f = write_path(bad, tmp_path / "d.nc")
    with pytest.raises(rc.ParameterError) as err:
        read_path(f)
    one_line_message(err, f"variable {name} has dims", "expected (" + ", ".join(path[name].dims))
    read_path(f, check=False)  # unchecked, it opens


def test_reading_refuses_what_is_not_netcdf(tmp_path):
    junk = tmp_path / "junk.nc"
    junk.write_text("not netcdf")
    with pytest.raises(rc.ParameterError) as err:
        read_path(junk)
    one_line_message(err, "not a readable NetCDF", "junk.nc")


def test_check_names_an_out_of_range_attribute(path):
    ds = path.copy()
    ds.attrs["pixel_size"] = -1.0
    with pytest.raises(rc.ParameterError) as err:
        check_path(ds)
    one_line_message(err, "pixel_size", "accepted")


def test_adding_fields_equals_keeping_them_on_the_path():
    kw = {"offsets": OFFSETS, "retract": False, "tol": TOL}
    some = rc.approach_retract(H, SUB, LAW, fields_at=(0,), **kw)
    both = rc.approach_retract(H, SUB, LAW, fields_at=(0, 4), **kw)
    state = {}
    rc.approach_retract(H, SUB, LAW, fields_at=(0,), progress=_keep(state, 4), **kw)
    merged = add_fields(some, {4: state["fields"]})
    xr.testing.assert_identical(_untimed(merged), _untimed(both))
    assert list(merged.variables)[-3:] == list(FIELDS)  # the maps after the rest
    assert add_fields(some, {}) is some
    with pytest.raises(rc.ParameterError) as err:
        add_fields(some.drop_vars("gap"), {4: state["fields"]})
    one_line_message(err, "gap")


def _keep(state, step):
    def progress(i, n, res):
        if i - 1 == step:
            state["fields"] = (res.pressure, res.gap, res.deflection)

    return progress
