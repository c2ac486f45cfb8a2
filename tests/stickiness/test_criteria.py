"""Each stickiness criterion against its paper's formula worked by hand.

The hand-worked numbers below are computed from the formulas as printed in the papers
(written out in each test), not from roughcontact's code.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import roughcontact as rc
from roughcontact.errors import ParameterError
from roughcontact.stickiness import (
    CRITERIA,
    CriterionInputs,
    criteria_table,
    evaluate,
    format_table,
    inputs_from_heights,
    self_affine_inputs,
)


def lattice(**kw):
    base = dict(contact_modulus=1.0, work_of_adhesion=0.05, interaction_range=1.0,
                rms_height=2.0, rms_slope=0.1, rms_curvature=0.05,
                half_derivative_variance=0.1)  # fmt: skip
    base.update(kw)
    return CriterionInputs(**base)


def test_pastewka_robbins_eq10_by_hand():
    # d_rep = 4 h'/h'' = 8; S = (h' dr/(2 la)) (h' d_rep/(4 dr))^(2/3) = 1 * 0.2^(2/3)
    r = evaluate("pastewka_robbins", lattice())
    assert r.parameter == pytest.approx(0.2 ** (2 / 3), rel=1e-12)
    assert r.threshold == pytest.approx(math.pi * (3 / 16) ** (2 / 3), rel=1e-12)
    assert r.sticky is True and r.verdict == "sticky"
    assert r.margin == pytest.approx(
        math.pi * 0.9375 ** (2 / 3), rel=1e-12
    )  # pi (3/16 / 0.2)^(2/3)
    # ten times weaker adhesion: S = 3.42 > 1.03
    weak = evaluate("pastewka_robbins", lattice(work_of_adhesion=0.005))
    assert weak.parameter == pytest.approx(10 * 0.2 ** (2 / 3)) and weak.sticky is False


def test_pastewka_robbins_delegates_to_the_si_calculator():
    from roughcontact.criterion import stickiness_criterion

    si = stickiness_criterion(contact_modulus="1 MPa", work_of_adhesion="5 mJ/m^2",
                              rms_slope=0.3, interaction_range="0.4 nm",
                              rms_curvature="0.02 1/nm")  # fmt: skip
    mine = evaluate("pastewka_robbins", CriterionInputs(
        contact_modulus=1e6, work_of_adhesion=5e-3, interaction_range=0.4e-9, rms_height=1e-8,
        rms_slope=0.3, rms_curvature=2e7, units="SI"))  # fmt: skip
    assert mine.parameter == pytest.approx(si.stickiness_parameter, rel=1e-12)
    assert mine.sticky == si.sticky


def test_persson_tosatti_by_hand_on_a_sinusoid():
    # h = h0 cos(2 pi x/lam): full contact stores U/A0 = (E*/4) q h0^2/2 = E* q h0^2/8
    # (Westergaard: p* = pi E* h0/lam, U/A0 = p* h0/4); true area 1 + h'^2/2, h'^2 = q^2 h0^2/2
    n, lam, h0 = 64, 16.0, 0.8
    x = np.arange(n)
    h = np.tile(h0 * np.cos(2 * np.pi * x / lam)[:, None], (1, n))
    inp = inputs_from_heights(h, contact_modulus=2.0, work_of_adhesion=0.1, interaction_range=1)
    q = 2 * math.pi / lam
    assert inp.half_derivative_variance == pytest.approx(q * h0**2 / 2, rel=1e-12)
    r = evaluate("persson_tosatti", inp)
    u = 2.0 * q * h0**2 / 8
    assert r.values["elastic_energy_per_area"] == pytest.approx(u, rel=1e-12)
    p_star = rc.theory.westergaard_full_contact_pressure(h0, lam, 2.0)
    assert u == pytest.approx(p_star * h0 / 4, rel=1e-12)
    assert r.parameter == pytest.approx(u / (0.1 * (1 + q**2 * h0**2 / 4)), rel=1e-12)
    assert r.sticky is (r.parameter < 1)


def test_fuller_tabor_by_hand():
    # McCool: m0 = 4, m2 = h'^2/2 = 0.005, m4 = 3 h''^2/8 = 9.375e-4, alpha = m0 m4/m2^2 = 150
    # sigma_s = sqrt(m0 (1 - 0.8968/alpha)), R_s = (3/8) sqrt(pi/m4); theta = E* s^1.5/(w R^.5)
    r = evaluate("fuller_tabor", lattice())
    alpha = 4 * 9.375e-4 / 0.005**2
    s = math.sqrt(4 * (1 - 0.8968 / alpha))
    R = 0.375 * math.sqrt(math.pi / 9.375e-4)
    assert r.values["bandwidth"] == pytest.approx(150.0)
    assert r.parameter == pytest.approx(s**1.5 / (0.05 * math.sqrt(R)), rel=1e-12)
    assert r.threshold == 10 and r.sticky is (r.parameter < 10)


def test_dahlquist_needs_si():
    r = evaluate("dahlquist", lattice())
    assert r.sticky is None and r.verdict.startswith("no verdict")
    soft = lattice(contact_modulus=5e4, youngs_modulus=4e4, units="SI")
    r = evaluate("dahlquist", soft)
    assert r.parameter == pytest.approx(0.4) and r.sticky is True
    assert evaluate("dahlquist", lattice(contact_modulus=1e9, units="SI")).sticky is False


def test_muser_generalised_tabor_by_hand():
    # R = 1/h'' = 20 (the Adhesion package's example), mu = R^(1/3) l_a^(2/3)/dr with
    # l_a = w/E*; with Pastewka & Robbins' R_c = 2/h'' = 40 beside it
    r = evaluate("muser", lattice())
    assert r.parameter == pytest.approx((20 * 0.05**2) ** (1 / 3), rel=1e-12)
    assert r.values["mu_T_rc"] == pytest.approx((40 * 0.05**2) ** (1 / 3), rel=1e-12)
    assert r.values["asperity_radius"] == pytest.approx(20, rel=1e-12)
    assert r.sticky is None and "DMT-like" in r.verdict


def test_missing_inputs_give_no_verdict_not_an_error():
    inp = lattice(interaction_range=math.nan, half_derivative_variance=math.nan)
    for key in ("pastewka_robbins", "persson_tosatti", "muser"):
        r = evaluate(key, inp)
        assert r.sticky is None and r.verdict.startswith("no verdict")


def test_bad_input_is_a_one_line_error():
    with pytest.raises(ParameterError, match="work_of_adhesion"):
        lattice(work_of_adhesion=-1)
    with pytest.raises(ParameterError, match="criterion must be one of"):
        evaluate("bogus", lattice())
    with pytest.raises(ParameterError, match="exactly one of rms_slope and rms_height"):
        self_affine_inputs(hurst=0.8, short_cutoff=4, long_cutoff=64, contact_modulus=1,
                           work_of_adhesion=0.1)  # fmt: skip


def test_table_lists_every_criterion_and_says_where_they_disagree():
    table = criteria_table(lattice(work_of_adhesion=0.02), simulated="sticky")
    assert [c["key"] for c in table["criteria"]] == list(CRITERIA)
    ag = table["agreement"]
    assert set(ag["sticky"]) | set(ag["not_sticky"]) | set(ag["no_verdict"]) == set(CRITERIA)
    text = format_table(table)
    for c in table["criteria"]:
        assert c["name"] in text
    assert "Simulation: sticky" in text and "Validated" in text
    assert ("disagree" in text) == ag["disagree"]


def test_closed_form_moments_match_a_generated_surface():
    h = rc.self_affine((256, 256), hurst=0.8, rms_slope=0.1, short_cutoff=4, long_cutoff=128,
                       seed=3)  # fmt: skip
    measured = inputs_from_heights(h, contact_modulus=1, work_of_adhesion=0.01)
    closed = self_affine_inputs(hurst=0.8, rms_slope=0.1, short_cutoff=4, long_cutoff=128,
                                size=256, contact_modulus=1, work_of_adhesion=0.01)  # fmt: skip
    assert measured.rms_slope == pytest.approx(0.1, rel=1e-6)
    assert measured.rms_curvature == pytest.approx(closed.rms_curvature, rel=0.03)
    assert measured.half_derivative_variance == pytest.approx(
        closed.half_derivative_variance, rel=0.15
    )
    assert measured.rms_height == pytest.approx(closed.rms_height, rel=0.15)


def test_a_scan_window_estimates_the_moments_of_its_surface():
    from roughcontact.stickiness import criteria_table_for_heights

    h = rc.self_affine((256, 256), hurst=0.8, rms_slope=0.2, short_cutoff=8, long_cutoff=32,
                       seed=7)  # fmt: skip
    full = inputs_from_heights(h, contact_modulus=1, work_of_adhesion=0.01)
    win = inputs_from_heights(h[:128, :128], contact_modulus=1, work_of_adhesion=0.01,
                              periodic=False)  # fmt: skip
    assert win.rms_slope == pytest.approx(full.rms_slope, rel=0.15)
    assert win.rms_curvature == pytest.approx(full.rms_curvature, rel=0.15)
    # M_1 weighs long wavelengths: a window of 4 L holds fewer of them (measured 0.72-0.80)
    assert win.half_derivative_variance == pytest.approx(full.half_derivative_variance, rel=0.35)
    # without the window the edges add spurious short-wavelength power
    raw = inputs_from_heights(h[:128, :128], contact_modulus=1, work_of_adhesion=0.01)
    assert abs(raw.rms_curvature / full.rms_curvature - 1) > abs(
        win.rms_curvature / full.rms_curvature - 1
    )
    # SI scan (pixel 10 nm, heights in m): the table a stick front end shows
    table = criteria_table_for_heights(h[:128, :128] * 1e-8, pixel_size=1e-8,
                                       contact_modulus=5e4, work_of_adhesion=0.05,
                                       interaction_range=5e-10, simulated="sticky")  # fmt: skip
    rows = {c["key"]: c for c in table["criteria"]}
    assert rows["dahlquist"]["sticky"] is True and table["inputs"]["units"] == "SI"
    assert table["agreement"]["simulation"] == "sticky"


def test_each_result_is_its_descriptor_plus_numbers():
    # one owner: name, reference, formula, threshold, direction and validated regime come
    # from the criterion's frozen descriptor, whatever the inputs (a verdict or none)
    from dataclasses import FrozenInstanceError

    from roughcontact.stickiness import DESCRIPTORS

    assert list(DESCRIPTORS) == list(CRITERIA)
    for inp in (lattice(), lattice(interaction_range=math.nan, rms_height=math.nan,
                                   half_derivative_variance=math.nan)):  # fmt: skip
        for key, d in DESCRIPTORS.items():
            r = evaluate(key, inp)
            for field in ("key", "name", "reference", "formula", "parameter_symbol",
                          "threshold", "sticky_below", "validated"):  # fmt: skip
                assert getattr(r, field) == getattr(d, field), (key, field)
            assert r.notes[: len(d.notes)] == d.notes
    with pytest.raises(FrozenInstanceError):
        DESCRIPTORS["muser"].threshold = 2.0


def test_muser_states_its_definition_and_both_radii():
    """Issue 41: no "definition unverified"; R = 1/h''rms with its source, and the
    R_c = 2/h''rms value beside it."""
    r = evaluate("muser", lattice())
    assert not any("unverified" in n for n in r.notes) and "unverified" not in r.verdict
    assert any("Adhesion package" in n and "R = 1/h''rms" in n for n in r.notes)
    assert "R_c = 2/h''rms" in r.verdict and "Tribol. Lett. (2016)" in r.reference
    text = format_table(criteria_table(lattice()))
    assert "unverified" not in text and "Not evaluated: the bearing-area (BAM)" in text
