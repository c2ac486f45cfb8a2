"""Bad input through the Python API: one ParameterError line naming the parameter, the
value and the accepted range, checked once (``roughcontact._validate``) and shared by the
API, the command line and the study schema."""

import json
import math
import warnings

import numpy as np
import pytest
from _helpers import one_line_message

import roughcontact as rc
from roughcontact import _validate as v
from roughcontact.analysis.path_analysis import analyze_path
from roughcontact.studies import load_study, study_from_dict
from roughcontact.studies.schema import SCHEMA

N = 16
H = rc.self_affine((N, N), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=1)
SUB = rc.Substrate((N, N))


# -- tolerances: (0, 1) everywhere, bools rejected, float32's floor kept --------------


@pytest.mark.parametrize("tol", [True, False, 2, 1.0, 0.0, -1e-8, math.nan, math.inf, "1e-8"])
def test_tolerance_outside_0_1_is_rejected(tol):
    with pytest.raises(rc.ParameterError) as err:
        rc.solve(H, SUB, load=1e-3, tol=tol)
    one_line_message(err, "tol", "(0, 1)")
    with pytest.raises(rc.ParameterError):
        rc.polonsky_keer(H, SUB, load=1e-3, tol=tol)


def test_tolerance_float32_floor_stays():
    with pytest.raises(rc.ParameterError) as err:
        rc.solve(H, SUB, load=1e-3, tol=1e-7, dtype="float32")
    one_line_message(err, "tol", "1e-06", "float32")
    assert rc.solve(H, SUB, load=1e-3, tol=1e-6, dtype="float32").converged


def test_one_range_shared_by_api_and_schema():
    assert SCHEMA["solver"]["tol"].accepted == v.TOL.accepted == "in (0, 1)"
    assert SCHEMA["analysis"]["target_area"].accepted == v.TARGET_AREA.accepted
    assert SCHEMA["analysis"]["fit_max_area"].accepted == v.FIT_MAX_AREA.accepted == "in (0, 1]"
    assert SCHEMA["surface"]["hurst"].test == v.HURST.contains  # the same bound method
    with pytest.raises(rc.ParameterError, match=r"max_iter must be an integer >= 1"):
        rc.solve(H, SUB, load=1e-3, max_iter=0)


# -- fields_at: out-of-range steps are an error naming the range ------------------------


@pytest.mark.parametrize("steps", [[999], [3], [-4], [1.5], [True]])
def test_fields_at_out_of_range(steps):
    offsets = H.max() - np.array([0.0, 0.01])  # 2 approach + 1 retract = 3 steps
    with pytest.raises(rc.ParameterError) as err:
        rc.approach_retract(H, SUB, offsets=offsets, retract=True, fields_at=steps)
    one_line_message(err, "fields_at")
    if isinstance(steps[0], int) and not isinstance(steps[0], bool):
        one_line_message(err, str(steps[0]), "-3 to 2")


def test_fields_at_negative_within_range_counts_from_the_end():
    offsets = H.max() - np.array([0.0, 0.01])
    ds = rc.approach_retract(H, SUB, offsets=offsets, retract=True, fields_at=[-1, -3, 1])
    assert list(ds["field_step"].values) == [0, 1, 2]


def _study(**path):
    return {
        "surface": {"size": 16, "hurst": 0.8, "rms_slope": 0.1, "short_cutoff": 4.0, "seeds": [1]},
        "interaction": {"law": "hardwall"},
        "path": {"values": [0.0, -0.1, -0.2, -0.3, -0.4, -0.5, -0.6], **path},
    }


def test_study_fields_at_out_of_range_before_any_work():
    data = {**_study(), "output": {"fields_at": [-1, 999]}}  # 7 + 6 = 13 steps
    with pytest.raises(rc.ParameterError) as err:
        study_from_dict(data)
    one_line_message(err, "[output]", "fields_at", "999", "13 steps", "-13 to 12")
    ok = study_from_dict({**_study(), "output": {"fields_at": [-13, 12]}})
    assert ok.settings["output"]["fields_at"] == [-13, 12]


def test_study_step_cap():
    data = _study()
    data["path"] = {"start": 0.0, "stop": -1.0, "step": 1e-9}
    with pytest.raises(rc.ParameterError) as err:
        study_from_dict(data)
    one_line_message(err, "[path]", "100000")


# -- a non-adhesive law cannot carry a tensile load: checked before any work -------------


def test_hard_wall_study_with_tensile_loads_fails_validation():
    data = _study(control="load", values=[1e-3, -1e-3])
    data["path"].pop("unit", None)
    with pytest.raises(rc.ParameterError) as err:
        study_from_dict(data)
    one_line_message(err, "[path]", "-0.001", "hardwall", "tensile", ">= 0")
    data["path"] = {"control": "load", "start": 1e-3, "stop": -1e-3, "num": 3}
    with pytest.raises(rc.ParameterError, match="tensile"):
        study_from_dict(data)
    # an adhesive law may, and a hard wall under compressive loads is fine
    adhesive = _study(control="load", values=[1e-3, -1e-3])
    adhesive["interaction"] = {"adhesion_length": 0.01}
    assert study_from_dict(adhesive).tasks
    assert study_from_dict(_study(control="load", values=[1e-3, 2e-3])).tasks


def test_study_file_of_random_bytes(tmp_path):
    bad = tmp_path / "random.toml"
    bad.write_bytes(bytes(range(128, 256)) * 3)
    with pytest.raises(rc.ParameterError) as err:
        load_study(bad)
    one_line_message(err, "random.toml", "UTF-8")


# -- heights: real, unmasked, finite, with a finite rms ---------------------------------


def test_heights_whose_rms_overflows_are_rejected():
    big = H * 1e300 / np.abs(H).max()
    with pytest.raises(rc.ParameterError) as err:
        rc.solve(big, SUB, load=1e-3)
    one_line_message(err, "heights", "rms", "overflow")
    with pytest.raises(rc.ParameterError, match="rms"):
        rc.statistics(big)
    with pytest.raises(rc.ParameterError) as err:
        rc.self_affine((N, N), hurst=0.8, rms_height=1e300, short_cutoff=4, seed=1)
    one_line_message(err, "rms_height", "1e+300", "[1e-150, 1e150]")
    # large but representable heights are fine
    assert math.isfinite(rc.statistics(H * 1e100).rms_height)


@pytest.mark.parametrize(
    ("heights", "word"),
    [
        (H > 0, "bool"),
        (H + 1j * H, "complex"),
        (H.astype(object), "object"),
        (H.astype(str), "<U"),
        (np.ma.masked_array(H, mask=H > 0), "masked"),
    ],
)
def test_heights_of_the_wrong_kind_are_rejected(tmp_path, heights, word):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no ComplexWarning: nothing is converted
        for call in (
            lambda: rc.solve(heights, SUB, load=1e-3),
            lambda: rc.statistics(heights),
            lambda: rc.save_heights(tmp_path / "x.npy", heights),
            lambda: v.heights2d("heights", heights),
        ):
            with pytest.raises(rc.ParameterError) as err:
                call()
            one_line_message(err, "heights", word)


@pytest.mark.parametrize(("kind", "word"), [("bool", "bool"), ("complex", "complex")])
def test_load_heights_rejects_bool_and_complex_files(tmp_path, kind, word):
    path = tmp_path / f"{kind}.npy"
    np.save(path, H > 0 if kind == "bool" else H + 1j * H)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(rc.ParameterError) as err:
            rc.load_heights(path)
    one_line_message(err, str(path.name), word)


@pytest.mark.parametrize("value", [5e-324, 1e-300, 1e200])
def test_magnitudes_whose_squares_leave_float64_are_rejected(value):
    with pytest.raises(rc.ParameterError) as err:
        rc.Exponential(1.0, value)
    one_line_message(err, "range", "[1e-150, 1e150]")
    with pytest.raises(rc.ParameterError, match="rms_slope"):
        rc.self_affine((N, N), hurst=0.8, rms_slope=value, short_cutoff=4)


def test_json_safe_replaces_non_finite_numbers():
    obj = {"a": math.nan, "b": [math.inf, np.float64(-np.inf), 1.5], "c": np.int64(3)}
    text = json.dumps(v.json_safe(obj), allow_nan=False)
    assert json.loads(text) == {"a": None, "b": [None, None, 1.5], "c": 3}


# -- surfaces: seed, memory, pixel size -------------------------------------------------


@pytest.mark.parametrize("seed", [-1, True, 1.5, [1, -2]])
def test_bad_seed(seed):
    with pytest.raises(rc.ParameterError) as err:
        rc.self_affine((N, N), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=seed)
    one_line_message(err, "seed", ">= 0")


def test_surface_larger_than_memory_is_refused_before_allocating(monkeypatch):
    monkeypatch.setattr(v, "available_memory", lambda: 2**30)  # 1 GiB here
    with pytest.raises(rc.ParameterError) as err:
        rc.self_affine((30000, 30000), hurst=0.8, rms_slope=0.1, short_cutoff=4)
    one_line_message(
        err, "shape", "(30000, 30000)", "GiB", "1 GiB available", "up to about 4096 x 4096"
    )
    with pytest.raises(rc.ParameterError, match="TiB"):
        rc.self_affine((10**6, 10**6), hurst=0.8, rms_slope=0.1, short_cutoff=4)


@pytest.mark.parametrize("a0", [1e-300, 8e-93, 0.0, -1.0, math.nan, math.inf, 1e200])
def test_pixel_size_range(a0):
    with pytest.raises(rc.ParameterError) as err:
        rc.Substrate((N, N), pixel_size=a0)
    one_line_message(err, "pixel_size", "[1e-25, 1e25]")
    with pytest.raises(rc.ParameterError, match="pixel_size"):
        rc.self_affine((N, N), hurst=0.8, rms_slope=0.1, short_cutoff=4, pixel_size=a0)


# -- path files: the attributes the analysis reads --------------------------------------


@pytest.fixture(scope="module")
def path_ds():
    offsets = H.max() - np.linspace(0.0, 0.3, 12)
    return rc.approach_retract(H, SUB, offsets=offsets, retract=False)


@pytest.mark.parametrize(
    ("attr", "value"),
    [
        ("contact_modulus", 0.0),
        ("contact_modulus", math.nan),
        ("rms_slope", -1.0),
        ("pixel_size", 0.0),
        ("nominal_area", math.inf),
        ("poisson", 0.9),
        ("grid", [16]),
    ],
)
def test_path_attributes_out_of_range(path_ds, attr, value):
    ds = path_ds.copy()
    ds.attrs[attr] = value
    with pytest.raises(rc.ParameterError) as err:
        analyze_path(ds, hard_wall_reference=False)
    one_line_message(err, attr, "accepted")


def test_path_with_non_finite_steps(path_ds):
    ds = path_ds.copy(deep=True)
    ds["load"].values[3] = math.nan
    with pytest.raises(rc.ParameterError) as err:
        analyze_path(ds, hard_wall_reference=False)
    one_line_message(err, "load", "finite")


@pytest.mark.parametrize(("key", "value"), [("target_area", 1.0), ("fit_max_area", 0.0)])
def test_analysis_ranges_are_the_schemas(path_ds, key, value):
    with pytest.raises(rc.ParameterError) as err:
        analyze_path(path_ds, hard_wall_reference=False, **{key: value})
    one_line_message(err, key, SCHEMA["analysis"][key].accepted)
