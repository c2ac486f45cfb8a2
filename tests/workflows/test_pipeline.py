"""``run_path``: the one workflow from a surface to an analysed path.

Oracles: the numbers of the same paths recorded from the code before ``run_path``
existed (commit 5148048's code path: ``relative_offsets`` + ``approach_retract`` +
``studies.task.AreaFields`` + ``with_fields`` + ``analyze_path``, run once; a regression
oracle, so that the callers moved onto ``run_path`` give the numbers they gave);
``approach_retract`` and ``analyze_path`` called directly for the record's pieces.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import roughcontact as rc
from roughcontact import ParameterError
from roughcontact.solvers.offsets import stepped_values
from roughcontact.workflows import AreaFields, PathRun, approach_offsets, run_path

#: Relative tolerance of the recorded numbers. On the machine that recorded them the same
#: operations reproduce them to the last bit, but another numpy (its FFT) or CPU rounds
#: differently, and a solve that stops at a residual of ``tol`` = 1e-8 can then stop an
#: iteration earlier or later: its state moves by up to ~tol, and the quantities derived
#: from it (κ from an interpolation between states) by up to ~100 tol. 1e-5 is above that
#: and far below any change of the physics (the demo prints 3 significant digits).
REL = 1e-5
#: Contact areas are site counts over the 64² grid: a site at the edge of contact, within
#: the solver's tolerance of the wall, may count on one machine and not on another.
SITES = 2 / 64**2


@pytest.fixture(scope="module")
def adhesive():
    """A 64² study-like task: lead-in, rms-height steps, retraction, a map at 2 %."""
    h = rc.self_affine((64, 64), hurst=0.8, rms_slope=0.1, short_cutoff=4.0, long_cutoff=32.0,
                       seed=7)  # fmt: skip
    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    run = run_path(
        h,
        rc.Substrate((64, 64), contact_modulus=1.0),
        law,
        offsets=stepped_values(0.5, -2.0, 0.125, name="offsets"),
        offset_unit="rms_height",
        lead_in=[3.0, 1.5],
        retract=True,
        tol=1e-8,
        fields_at_area=[0.02],
        analysis={"target_area": 0.01},
    )
    return run


def test_adhesive_path_gives_the_numbers_recorded_before_run_path(adhesive):
    # recorded from commit 5148048's code path (module docstring), full float repr
    ds, a = adhesive.path, adhesive.analysis
    assert ds.sizes["step"] == 45
    assert [int(s) for s in ds["field_step"].values] == [11]
    assert float(ds["pressure"].values.sum()) == pytest.approx(-4.867822111156882, rel=REL)
    assert float(ds["gap"].values.sum()) == pytest.approx(6770.285230773369, rel=REL)
    assert float(ds["load"].values[7]) == pytest.approx(-0.0008104970267195474, rel=REL)
    assert float(ds["load"].values.sum()) == pytest.approx(-0.07425731670710031, rel=REL)
    assert float(ds["repulsive_area"].values.sum()) == pytest.approx(1.52294921875, abs=SITES)
    assert adhesive.pull_off == pytest.approx(0.003579519761026945, rel=REL)
    recorded = {
        "kappa": -1.1469377326018264,
        "kappa_rep": 7.440075132568925,
        "kappa_att": 0.9937452099958107,
        "kappa_rep_hard_wall": 3.4114803260486415,
        "offset": 1.7532995554336586,
        "load": -0.0008718869138008927,
    }
    for key, value in recorded.items():
        assert getattr(a, key) == pytest.approx(value, rel=REL), key
    assert a.verdict == "sticky"


def test_load_control_gives_the_numbers_recorded_before_run_path():
    # the demo's load path at 64², recorded from commit 5148048's code path
    h = rc.self_affine((64, 64), hurst=0.8, rms_slope=0.1, short_cutoff=8.0, long_cutoff=32.0,
                       seed=2014)  # fmt: skip
    loads = np.geomspace(1.5e-4, 3e-3, 5)
    run = run_path(h, rc.Substrate((64, 64), contact_modulus=1.0), loads=loads, retract=False,
                   tol=1e-8)  # fmt: skip
    area = [0.006103515625, 0.011474609375, 0.022216796875, 0.038330078125, 0.070068359375]
    offset = [0.9097956362516869, 0.8529625167948612, 0.7787074881806547, 0.6745957195718532,
              0.5362410034328711]  # fmt: skip
    assert run.control == "load" and run.analysis is None and not run.area_fields
    np.testing.assert_allclose(run.path["repulsive_area"].values, area, rtol=0, atol=SITES)
    np.testing.assert_allclose(run.path["offset"].values, offset, rtol=REL, atol=0)
    np.testing.assert_array_equal(run.values, loads)


def test_the_record_is_the_direct_path_and_analysis(adhesive):
    from roughcontact.analysis.path_analysis import analyze_path

    ds = rc.approach_retract(adhesive.heights, adhesive.substrate, adhesive.interaction,
                             offsets=adhesive.values, tol=1e-8)  # fmt: skip
    for key in ("load", "offset", "repulsive_area", "attractive_area", "converged"):
        np.testing.assert_array_equal(adhesive.path[key].values, ds[key].values, err_msg=key)
    direct = analyze_path(ds, heights=adhesive.heights, substrate=adhesive.substrate)
    assert json.dumps(adhesive.analysis.to_dict()) == json.dumps(direct.to_dict())
    # the map kept is the approach state nearest 2 %, as Fig. 1 picks it among all steps
    rep = [(p > 0).mean() for p in _approach_pressures(adhesive)]
    assert int(np.argmin(np.abs(np.asarray(rep) - 0.02))) == 11
    assert set(adhesive.area_fields) == {11}
    s = adhesive.summary()
    assert s["steps"] == adhesive.steps == 45 and s["all_converged"] is True
    assert s["pull_off"] == adhesive.pull_off and adhesive.steps_not_converged == 0
    with pytest.raises(AttributeError):  # frozen
        adhesive.path = None
    assert isinstance(adhesive, PathRun)


def _approach_pressures(run):
    n = int((run.path["branch"].values == "approach").sum())
    ds = rc.approach_retract(run.heights, run.substrate, run.interaction, offsets=run.values,
                             retract=False, tol=1e-8, fields_at=list(range(n)))  # fmt: skip
    return np.asarray(ds["pressure"].values)


def test_until_area_ends_the_area_fields_with_the_approach():
    # with until_area the retraction visits the same offsets: its states must not be kept
    keep = AreaFields([0.5], approach_steps=10, until_area=0.01)

    class State:
        def __init__(self, area):
            self.pressure = np.full((10, 10), -1.0)
            self.pressure.flat[: int(area * 100)] = 1.0
            self.gap = self.deflection = self.pressure
            self.repulsive_area = area

    for step, area in enumerate([0.0, 0.02, 0.3], start=1):  # the last: a retraction step
        keep(step, 10, State(area))
    assert list(keep.fields()) == [1]


def test_analysis_failure_and_partial_paths_are_recorded():
    h = rc.self_affine((32, 32), hurst=0.8, rms_slope=0.1, short_cutoff=4.0, seed=1)
    sub = rc.Substrate((32, 32), contact_modulus=1.0)
    run = run_path(h, sub, offsets=[0.5, 0.25], offset_unit="rms_height", retract=False,
                   analysis={"target_area": 0.5})  # fmt: skip
    assert run.analysis is None and "0.5" in run.analysis_error
    assert isinstance(run.analysis_failure, ParameterError)
    offsets = approach_offsets(h, [0.5, 0.25], "rms_height", lead_in=[1.0])
    assert offsets.size == 3 and offsets[0] == pytest.approx(float(h.max()) + 1.0)


@pytest.mark.parametrize(
    ("kwargs", "needle"),
    [
        ({"offsets": [1.0], "offset_unit": "furlong"}, "offset_unit"),
        ({"loads": [1e-3], "offset_unit": "rms_height"}, "offsets only"),
        ({"loads": [1e-3], "lead_in": [1.0]}, "offsets only"),
        ({}, "exactly one of offsets or loads"),
    ],
)
def test_bad_inputs_are_one_line_parameter_errors(kwargs, needle):
    h = rc.self_affine((16, 16), hurst=0.8, rms_slope=0.1, short_cutoff=4.0, seed=1)
    with pytest.raises(ParameterError, match=needle) as info:
        run_path(h, rc.Substrate((16, 16)), **kwargs)
    assert "\n" not in str(info.value)


def test_old_homes_of_the_moved_names_still_work():
    from roughcontact.studies import task

    assert task.AreaFields is AreaFields
    assert rc.run_path is run_path
