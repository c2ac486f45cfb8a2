"""Reliability round four: the library's misuse errors name the parameter.

A law given as a registry name, offsets of the wrong shape, a dict for a path dataset,
a 1-D contact mask: each a one-line ParameterError naming what was expected, never an
AttributeError, TypeError or IndexError from deep inside. And the share of missing
points is printed with the digits that tell it from the 1 % limit.
"""

import numpy as np
import pytest
from _helpers import one_line_message
from _helpers import random_surface as _surface

from roughcontact import ParameterError, Substrate, approach_retract, contact_patches, solve
from roughcontact.analysis.path_analysis import analyze_path
from roughcontact.interactions import HardWall


def _h():
    h = _surface(2, 32)
    return h - h.mean()


def test_solve_takes_a_registry_name_and_says_what_a_law_needs():
    h, sub = _h(), Substrate((32, 32))
    offset = float(h.max()) - 0.05
    by_name = solve(h, sub, "hardwall", offset=offset)
    by_object = solve(h, sub, HardWall(), offset=offset)
    assert by_name.converged
    assert by_name.load == pytest.approx(by_object.load, rel=1e-12)
    with pytest.raises(ParameterError) as err:
        solve(h, sub, "lj93smooth", offset=offset)
    one_line_message(err.value, "SmoothLJ93", "work_of_adhesion")
    for bad in ("hard wall", 3, object()):
        with pytest.raises(ParameterError) as err:
            solve(h, sub, bad, offset=offset)
        one_line_message(err.value, "interaction", "hardwall")


def test_approach_retract_refuses_offsets_that_are_not_one_value_per_step():
    h, sub = _h(), Substrate((32, 32))
    for bad in (np.ones((3, 2)), [[0.1, 0.2]], ["a", "b"]):
        with pytest.raises(ParameterError) as err:
            approach_retract(h, sub, offsets=bad)
        one_line_message(err.value, "offsets")
    with pytest.raises(ParameterError) as err:
        approach_retract(h, sub, loads=np.ones((2, 2)))
    one_line_message(err.value, "loads", "1-D")


@pytest.mark.parametrize("bad", [{}, None, 3.0, [1, 2]])
def test_analyze_path_names_its_dataset_argument(bad):
    with pytest.raises(ParameterError) as err:
        analyze_path(bad)
    one_line_message(err.value, "ds", "Dataset")


@pytest.mark.parametrize("shape", [(5,), (2, 2, 2), ()])
def test_contact_patches_wants_a_2d_mask(shape):
    with pytest.raises(ParameterError) as err:
        contact_patches(np.ones(shape, dtype=bool))
    one_line_message(err.value, "mask", "2D")
    labels, sizes = contact_patches(np.eye(4, dtype=bool))
    assert labels.shape == (4, 4) and sizes.sum() == 4


def test_missing_points_just_over_the_limit_are_not_printed_as_the_limit():
    from roughcontact.topography.missing import fill_note, missing_policy

    for fraction, shown in ((0.0105, "1.05%"), (0.01001, "1.001%"), (0.02, "2.0%")):
        note = fill_note({"points": 1, "fraction": fraction})
        assert f"; {shown} is more than the 1%" in note, note
    data = np.zeros((20, 100))
    data.flat[:21] = np.nan  # 21 of 2000 points: 1.05 %
    with pytest.raises(ParameterError) as err:
        missing_policy("scan", data, None, True, {})
    one_line_message(err.value, "1.05% of the points", "more than the 1%")
