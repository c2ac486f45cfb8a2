"""Pastewka & Robbins (PNAS 2014) theory: Eqs. 4-10, the stickiness criterion and its
equivalence with kappa_att < kappa_rep, the necessary condition, and predict()."""

import json
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from roughcontact import ParameterError
from roughcontact.theory import (
    AREA_RATIO_PREFACTOR,
    KAPPA_REP,
    NECESSARY_CONDITION_CONSTANT,
    STICKINESS_THRESHOLD,
    PastewkaRobbinsPrediction,
    area_ratio,
    asperity_radius,
    attractive_load,
    height_change,
    kappa_att,
    kappa_att_from_area_ratio,
    kappa_from_components,
    necessary_condition,
    predict,
    predicted_d_rep,
    stickiness_margin,
    stickiness_parameter,
)


def test_constants():
    assert AREA_RATIO_PREFACTOR == pytest.approx((16 / (9 * math.pi)) ** (1 / 3), rel=1e-15)
    assert AREA_RATIO_PREFACTOR == pytest.approx(0.82713, abs=1e-5)
    assert STICKINESS_THRESHOLD == pytest.approx(1.02916, abs=1e-5)  # "~ 1" in Eq. 10
    assert KAPPA_REP == 2.0
    assert NECESSARY_CONDITION_CONSTANT / KAPPA_REP == pytest.approx(0.4859, abs=1e-4)  # ~0.5


def test_eq4_attractive_load():
    assert attractive_load(0.03, 0.005, 0.35) == pytest.approx(0.005 / 0.35 * 0.03)
    np.testing.assert_allclose(attractive_load([0.0, 1.0], 2.0, 4.0), [0.0, 0.5])
    with pytest.raises(ParameterError, match="attractive_area"):
        attractive_load(-1.0, 1.0, 1.0)


def test_eq6_by_hand_and_from_the_exact_cylinder_gap():
    s, d, dr = 0.1, 12.0, 0.3
    expected = (16 / (9 * math.pi)) ** (1 / 3) * (s * d / (math.pi * dr)) ** (2 / 3)
    assert area_ratio(s, d, dr) == pytest.approx(expected, rel=1e-14)
    # Independent route: the 2D Hertz (cylinder) gap outside a contact of half-width
    # a = d_rep/2 with edge slope h' = a/R (Johnson 1985, 5.x): g(x) = [x sqrt(x^2-a^2)
    # - a^2 acosh(x/a)]/(2R). d_att is where g = dr; A_rep/A_att = d_rep/(pi d_att).
    # Eq. 6 keeps the leading x^(3/2) term, exact as dr/delta_h -> 0.
    a = d / 2
    R = a / s

    def gap(x):
        return (x * math.sqrt(x * x - a * a) - a * a * math.acosh(x / a)) / (2 * R)

    for dr_small, tol in [(1e-4, 2e-3), (1e-6, 2e-4)]:
        d_att = brentq(lambda u, dr_=dr_small: gap(a + u) - dr_, 1e-14, a)
        assert d / (math.pi * d_att) == pytest.approx(area_ratio(s, d, dr_small), rel=tol)


def test_eq7_is_eq5_with_eq6_and_scales_as_one_over_la():
    s, d, dr, la = 0.3, 8.0, 0.5, 0.01
    r = area_ratio(s, d, dr)
    assert kappa_att(s, d, dr, la) == pytest.approx(s * dr / la * r, rel=1e-14)
    assert kappa_att_from_area_ratio(s, dr, la, r) == pytest.approx(kappa_att(s, d, dr, la))
    assert kappa_att(s, d, dr, 2 * la) == pytest.approx(kappa_att(s, d, dr, la) / 2)


def test_eq8_eq9():
    s, c = 0.2, 0.05
    assert asperity_radius(c) == pytest.approx(2 / c)
    assert predicted_d_rep(s, c) == pytest.approx(4 * s / c)
    assert height_change(s, predicted_d_rep(s, c)) == pytest.approx(s**2 / c)


def test_kappa_from_components():
    assert kappa_from_components(2.0, math.inf) == 2.0  # no adhesion
    assert kappa_from_components(2.0, 2.0) == math.inf  # onset of stickiness
    assert kappa_from_components(2.0, 4.0) == pytest.approx(4.0)  # 1/2 - 1/4
    assert kappa_from_components(2.0, 1.0) == pytest.approx(-2.0)  # sticky: negative
    np.testing.assert_allclose(kappa_from_components(2.0, [4.0, 1.0]), [4.0, -2.0])
    with pytest.raises(ParameterError, match="kappa_att"):
        kappa_from_components(2.0, 0.0)


def test_eq10_equivalent_to_kappa_att_below_kappa_rep_random_parameters():
    rng = np.random.default_rng(2014)
    n = 20000
    s = 10 ** rng.uniform(-3, 0.5, n)
    d = 10 ** rng.uniform(-1, 3, n)
    dr = 10 ** rng.uniform(-2, 1, n)
    la = 10 ** rng.uniform(-5, 1, n)
    kr = rng.uniform(1.5, 3.0, n)
    S = stickiness_parameter(s, d, dr, la, kr)
    ka = kappa_att(s, d, dr, la)
    np.testing.assert_allclose(S / STICKINESS_THRESHOLD, ka / kr, rtol=1e-12)
    np.testing.assert_allclose(stickiness_margin(s, d, dr, la, kr), kr / ka, rtol=1e-12)
    sticky = S < STICKINESS_THRESHOLD
    assert 0.05 < sticky.mean() < 0.95  # both outcomes are exercised
    away = np.abs(ka / kr - 1) > 1e-9  # leave out round-off ties
    assert np.array_equal(sticky[away], (ka < kr)[away])
    assert np.array_equal(sticky[away], (kappa_from_components(kr, ka) < 0)[away])


def test_necessary_condition_boundary_and_implication():
    # l_a/a0 > 0.486 h'_rms (paper: >~ 0.5 h'_rms)
    assert necessary_condition(0.5 * 0.1, 0.1, 1.0)
    assert not necessary_condition(0.45 * 0.1, 0.1, 1.0)
    assert necessary_condition(0.05, 0.1, atomic_spacing=1.0)
    assert not necessary_condition(0.05, 0.3, atomic_spacing=1.0)
    # Its derivation: Delta_r = a0 <= delta_h = h' d_rep/4; under these assumptions
    # Eq. 10 never says "sticky" while the necessary condition fails.
    rng = np.random.default_rng(7)
    n = 20000
    a0 = 10 ** rng.uniform(-1, 1, n)
    s = 10 ** rng.uniform(-3, 0.3, n)
    d = 4 * a0 / s * 10 ** rng.uniform(0, 3, n)  # delta_h >= a0
    la = a0 * s * 10 ** rng.uniform(-2, 1, n)
    sticky = stickiness_parameter(s, d, a0, la) < STICKINESS_THRESHOLD
    met = necessary_condition(la, s, a0)
    assert sticky.any()
    assert np.all(met[sticky])


@pytest.mark.parametrize(
    ("d_rep", "lambda_s"),
    [(5.7, 4), (10.9, 8), (20.8, 16)],  # predicted d_rep of H = 0.8 surfaces (Fig. 4 set)
)
def test_fig4_parameter_set_only_strong_adhesion_at_small_slope_sticks(d_rep, lambda_s):
    # Discussion: "The stickiest cases ... are for l_a/a0 ~ 0.05, h'rms = 0.1 and small
    # d_rep. Increasing h'rms to 0.3 suppresses adhesion." Delta_r = sqrt(24 a0 l_a) for
    # the paper's potential with k = E* a0/2 (SPEC section 1).
    for la in (0.0005, 0.005, 0.05):
        dr = math.sqrt(24 * la)
        for s in (0.1, 0.3):
            p = predict(rms_slope=s, interaction_range=dr, adhesion_length=la, d_rep=d_rep)
            assert p.sticky == (la == 0.05 and s == 0.1), (la, s, lambda_s, p.margin)


def test_predict_fields_and_consistency():
    p = predict(rms_slope=0.1, interaction_range=1.1, adhesion_length=0.05, rms_curvature=0.04)
    assert isinstance(p, PastewkaRobbinsPrediction)
    assert p.d_rep_source == "predicted" and p.d_rep == pytest.approx(10.0)
    assert p.area_ratio == pytest.approx(area_ratio(0.1, 10.0, 1.1))
    assert p.kappa_att == pytest.approx(kappa_att(0.1, 10.0, 1.1, 0.05))
    assert 1 / p.kappa == pytest.approx(1 / 2 - 1 / p.kappa_att)
    assert p.margin == pytest.approx(2 / p.kappa_att)
    assert p.sticky == (p.margin > 1) == (p.kappa < 0)
    assert p.height_change == pytest.approx(0.1**2 / 0.04)
    # at the threshold adhesion length the margin is exactly one
    q = predict(rms_slope=0.1, interaction_range=1.1, adhesion_length=p.threshold_adhesion_length,
                d_rep=10.0)  # fmt: skip
    assert q.margin == pytest.approx(1.0, rel=1e-12) and q.d_rep_source == "given"
    json.dumps(p.to_dict())  # JSON-ready (rms_curvature given -> finite)
    assert predict(rms_slope=0.1, interaction_range=1.1, adhesion_length=0.05,
                   d_rep=10.0).to_dict()["rms_curvature"] is None  # fmt: skip
    # kappa_rep override
    r = predict(rms_slope=0.1, interaction_range=1.1, adhesion_length=0.05, d_rep=10, kappa_rep=3)
    assert r.margin == pytest.approx(1.5 * p.margin)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"d_rep": 1.0, "rms_curvature": 1.0}, "exactly one"),
        ({}, "exactly one"),
        ({"d_rep": 0.0}, "d_rep"),
        ({"d_rep": 1.0, "kappa_rep": -2}, "kappa_rep"),
        ({"d_rep": 1.0, "atomic_spacing": math.nan}, "atomic_spacing"),
        ({"rms_curvature": -1.0}, "rms_curvature"),
    ],
)
def test_predict_bad_input(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        predict(rms_slope=0.1, interaction_range=1.0, adhesion_length=0.01, **kwargs)


@pytest.mark.parametrize("bad", [0.0, -1.0, math.inf, math.nan, "x", []])
def test_functions_reject_non_positive_input(bad):
    with pytest.raises(ParameterError, match="rms_slope"):
        area_ratio(bad, 1.0, 1.0)
    with pytest.raises(ParameterError, match="interaction_range"):
        stickiness_parameter(0.1, 1.0, bad, 0.1)
