"""Untruncated LJ93, exponential and Maugis-Dugdale laws: derivatives, limits, errors."""

import math

import numpy as np
import pytest

import roughcontact as rc
from roughcontact import ParameterError
from roughcontact.interactions import Exponential, LennardJones93, MaugisDugdale

SMOOTH_LAWS = [
    LennardJones93(work_of_adhesion=0.02),
    Exponential(work_of_adhesion=0.01, range=0.5, core_stiffness=2.0),
    Exponential(work_of_adhesion=0.01, range=0.5),
]


@pytest.mark.parametrize("law", SMOOTH_LAWS, ids=lambda law: law.name)
def test_pressure_and_curvature_are_derivatives(law):
    lo = 0.0 if law.hard_core else -0.3
    g = np.linspace(lo + 1e-3, 3.0, 301)
    g = g[np.abs(g) > 1e-4]  # the soft core's curvature jumps at g = 0
    h = 1e-6
    fd_p = -(law.energy(g + h) - law.energy(g - h)) / (2 * h)
    np.testing.assert_allclose(law.pressure(g), fd_p, rtol=1e-6, atol=1e-12)
    fd_c = -(law.pressure(g + h) - law.pressure(g - h)) / (2 * h)
    np.testing.assert_allclose(law.curvature(g), fd_c, rtol=1e-5, atol=1e-9)


def test_lj93_minimum_and_stiffness():
    law = LennardJones93(work_of_adhesion=0.02, equilibrium_distance=1.3)
    a0 = 1.3
    assert law.energy(np.array([a0]))[0] == pytest.approx(-0.02, rel=1e-12)
    assert law.pressure(np.array([a0]))[0] == pytest.approx(0.0, abs=1e-15)
    assert law.curvature(np.array([a0]))[0] == pytest.approx(27 * 0.02 / a0**2, rel=1e-12)
    assert law.stiffness == pytest.approx(27 * 0.02 / a0**2, rel=1e-12)
    # the smoothed wall has the same core for the same epsilon and sigma
    smooth = rc.SmoothLJ93(stiffness=law.stiffness, range=0.3, equilibrium_distance=a0)
    assert smooth.epsilon == pytest.approx(law.epsilon, rel=1e-12)
    g = np.linspace(0.5, a0, 20)
    np.testing.assert_allclose(smooth.pressure(g), law.pressure(g), rtol=1e-12, atol=1e-15)
    again = LennardJones93.from_epsilon_sigma(law.epsilon, law.sigma)
    assert again.work_of_adhesion == pytest.approx(0.02) and again.equilibrium_distance == (
        pytest.approx(a0)
    )


def test_lj93_attraction_decays_as_inverse_fourth_power():
    law = LennardJones93(work_of_adhesion=0.02)
    g = np.array([20.0, 40.0])
    p = law.pressure(g)
    assert np.all(p < 0) and p[0] / p[1] == pytest.approx(16.0, rel=1e-4)


def test_exponential_hard_and_soft_core():
    hard = Exponential(work_of_adhesion=0.01, range=0.5)
    soft = Exponential(work_of_adhesion=0.01, range=0.5, core_stiffness=2.0)
    assert hard.hard_core and not soft.hard_core
    assert hard.energy(np.array([0.0]))[0] == pytest.approx(-0.01)
    assert hard.pressure(np.array([0.0]))[0] == pytest.approx(-hard.max_stress)
    # soft core: minimum at g* = -w/(rho k_c), C1 at g = 0
    g_star = -0.01 / (0.5 * 2.0)
    assert soft.pressure(np.array([g_star]))[0] == pytest.approx(0.0, abs=1e-15)
    eps = 1e-9
    v = soft.pressure(np.array([-eps, eps]))
    assert abs(v[1] - v[0]) < 1e-8
    rep, att = soft.classify(np.array([2 * g_star, 0.5 * g_star, 1.0]))
    assert rep.tolist() == [True, False, False] and att.tolist() == [False, True, True]


def test_dugdale_is_a_constant_stress_up_to_the_cohesive_width():
    law = MaugisDugdale(work_of_adhesion=0.01, range=0.5)
    g = np.array([0.0, 0.25, 0.4999, 0.5, 2.0])
    np.testing.assert_allclose(law.pressure(g), [-0.02, -0.02, -0.02, 0.0, 0.0])
    np.testing.assert_allclose(law.energy(g), [-0.01, -0.005, -0.01 * 1e-4 / 0.5, 0.0, 0.0])
    assert law.cohesive_stress == pytest.approx(0.02) and law.hard_core
    assert law.cutoff == 0.5


@pytest.mark.parametrize(
    ("make", "name"),
    [
        (lambda: LennardJones93(work_of_adhesion=-1.0), "work_of_adhesion"),
        (lambda: LennardJones93(work_of_adhesion=0.1, equilibrium_distance=0), "equilibrium"),
        (lambda: Exponential(work_of_adhesion=0.1, range=0.0), "range"),
        (lambda: Exponential(work_of_adhesion=0.1, range=1, core_stiffness=-1), "core_stiffness"),
        (lambda: MaugisDugdale(work_of_adhesion=math.nan, range=1), "work_of_adhesion"),
        (lambda: MaugisDugdale(work_of_adhesion=0.1, range=-2), "range"),
    ],
)
def test_bad_parameters_are_named(make, name):
    with pytest.raises(ParameterError, match=name):
        make()


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_exponential_hot_path_terms_are_its_evaluations(dtype):
    # pressure and curvature compute only their term (and, off NumPy, their constants
    # once): the values of the full evaluation to the bit, on NumPy and array_api_strict
    law = rc.Exponential(work_of_adhesion=0.01, range=0.4)
    g = np.concatenate([np.random.default_rng(1).normal(size=500) * 2, [0.0, -0.0, np.inf]])
    g = g.astype(dtype)
    strict = pytest.importorskip("array_api_strict")
    for arr in (g, strict.asarray(g)):
        v, dv, d2v = law._evaluate(arr)
        np.testing.assert_array_equal(np.asarray(law.pressure(arr)), np.asarray(-dv))
        np.testing.assert_array_equal(np.asarray(law.curvature(arr)), np.asarray(d2v))
        np.testing.assert_array_equal(np.asarray(law.energy(arr)), np.asarray(v))
        assert np.asarray(law.pressure(arr)).dtype == dtype
        assert np.asarray(law.energy(arr)).dtype == dtype


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_dugdale_terms_alone_are_its_evaluations(dtype):
    # the bounded loop evaluates the law 5-7 times per iteration: each term alone (fewer
    # passes), the values of the full evaluation, inside, beyond and at the zone's end
    law = rc.MaugisDugdale(work_of_adhesion=0.01, range=0.4)
    g = np.concatenate([np.random.default_rng(2).uniform(-0.1, 1.0, 500),
                        [0.0, -0.0, 0.4, np.nextafter(0.4, 0), np.inf]])  # fmt: skip
    g = g.astype(dtype)
    strict = pytest.importorskip("array_api_strict")
    for arr in (g, strict.asarray(g)):
        v, dv, d2v = law._evaluate(arr)
        p = np.asarray(law.pressure(arr))
        np.testing.assert_array_equal(p, np.asarray(-dv))
        np.testing.assert_array_equal(np.signbit(p), np.signbit(np.asarray(-dv)))
        np.testing.assert_array_equal(np.asarray(law.energy(arr)), np.asarray(v))
        np.testing.assert_array_equal(np.asarray(law.curvature(arr)), np.asarray(d2v))
        assert p.dtype == dtype and np.asarray(law.energy(arr)).dtype == dtype
