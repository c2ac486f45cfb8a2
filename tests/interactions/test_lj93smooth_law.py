"""The paper's smoothed 9-3 LJ wall: continuity, minimum, derivatives, parameters."""

import numpy as np
import pytest

from roughcontact import ParameterError, SmoothLJ93


@pytest.fixture(params=[0.0005, 0.005, 0.05])
def law(request):
    return SmoothLJ93.from_adhesion_length(request.param)


def test_minimum_depth_and_stiffness(law):
    a0 = law.equilibrium_distance
    assert law.energy(np.array([a0]))[0] == pytest.approx(-law.work_of_adhesion, rel=1e-12)
    assert law.pressure(np.array([a0]))[0] == pytest.approx(0.0, abs=1e-12)
    assert law.curvature(np.array([a0 - 1e-12, a0]))[0] == pytest.approx(law.stiffness, rel=1e-6)
    assert law.stiffness == pytest.approx(0.5)  # E*/(2 a0)
    assert law.adhesion_length == pytest.approx(law.range**2 / 24)


@pytest.mark.parametrize("where", ["a0", "cutoff"])
def test_continuity_of_v_dv_d2v(law, where):
    g0 = law.equilibrium_distance if where == "a0" else law.cutoff
    eps = 1e-9
    g = np.array([g0 - eps, g0 + eps])
    for f, scale in (
        (law.energy, law.work_of_adhesion),
        (law.pressure, law.stiffness * law.range),
        (law.curvature, law.stiffness),
    ):
        v = f(g)
        assert abs(v[1] - v[0]) <= 1e-6 * scale


def test_derivatives_by_finite_differences(law):
    g = np.concatenate([np.linspace(-0.2, 0.04, 7), np.linspace(0.3, law.cutoff + 0.2, 41)])
    h = 1e-6
    fd_p = -(law.energy(g + h) - law.energy(g - h)) / (2 * h)
    np.testing.assert_allclose(law.pressure(g), fd_p, rtol=1e-5, atol=1e-9 * law.stiffness)
    fd_c = -(law.pressure(g + h) - law.pressure(g - h)) / (2 * h)
    np.testing.assert_allclose(law.curvature(g), fd_c, rtol=1e-4, atol=1e-6 * law.stiffness)


def test_zero_beyond_cutoff_and_finite_in_core(law):
    g = np.array([law.cutoff, law.cutoff + 1.0, 10.0])
    assert not law.energy(g).any() and not law.pressure(g).any()
    core = law.pressure(np.array([-1.0, 0.0, 0.01]))
    assert np.all(np.isfinite(core)) and np.all(core > 0)


def test_any_two_of_three():
    ref = SmoothLJ93(range=0.4)
    k, dr, w = ref.stiffness, ref.range, ref.work_of_adhesion
    for kw in (
        {"stiffness": k, "range": dr},
        {"stiffness": k, "work_of_adhesion": w},
        {"range": dr, "work_of_adhesion": w},
        {"work_of_adhesion": w},
        {"stiffness": k, "range": dr, "work_of_adhesion": w},
    ):
        other = SmoothLJ93(**kw)
        assert (other.stiffness, other.range) == pytest.approx((k, dr))
        assert other.work_of_adhesion == pytest.approx(w)


@pytest.mark.parametrize(
    "kwargs,match",
    [
        ({"stiffness": 1.0, "range": 0.5, "work_of_adhesion": 1.0}, "inconsistent"),
        ({"range": 0.0}, "range"),
        ({"range": 0.3, "stiffness": -1.0}, "stiffness"),
        ({"work_of_adhesion": -0.1}, "work_of_adhesion"),
        ({}, "range or work_of_adhesion"),
    ],
)
def test_bad_parameters(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        SmoothLJ93(**kwargs)


def test_classify(law):
    a0 = law.equilibrium_distance
    rep, att = law.classify(np.array([0.5 * a0, a0, a0 + 0.5 * law.range, law.cutoff + 1]))
    assert rep.tolist() == [True, False, False, False]
    assert att.tolist() == [False, False, True, False]


def test_fields_of_any_shape_give_the_same_values(law):
    # the core is selected by index arrays on flat fields and by masks otherwise
    g = np.linspace(-0.2, law.cutoff + 0.2, 96)
    for f in (law.pressure, law.curvature):
        np.testing.assert_array_equal(f(g.reshape(8, 12)).ravel(), f(g))
