"""SI stickiness criterion: unit parsing and the Discussion examples of Pastewka &
Robbins, PNAS 111, 3298 (2014)."""

import json
import math

import pytest

from roughcontact import ParameterError
from roughcontact.criterion import StickinessCriterion, parse_quantity, stickiness_criterion

RUBBER = {"work_of_adhesion": "50 mJ/m^2", "rms_slope": 1, "interaction_range": "0.5 nm"}


# ------------------------------------------------------------------- unit parsing
@pytest.mark.parametrize(
    ("text", "dimension", "si"),
    [
        ("50 mJ/m^2", "energy per area", 0.05),
        ("0.05 J/m2", "energy per area", 0.05),
        ("50 mJ / m^2", "energy per area", 0.05),
        ("50 mJ m^-2", "energy per area", 0.05),
        ("0.05 N/m", "energy per area", 0.05),
        ("10 MPa", "pressure", 1e7),
        ("1 GPa", "pressure", 1e9),
        ("100 Pa", "pressure", 100.0),
        ("1.5e3kPa", "pressure", 1.5e6),
        ("2 bar", "pressure", 2e5),
        ("0.5 nm", "length", 5e-10),
        ("10 um", "length", 1e-5),
        ("10 µm", "length", 1e-5),
        ("10 μm", "length", 1e-5),
        ("3 Å", "length", 3e-10),
        ("2 mm", "length", 2e-3),
        ("0.2 1/nm", "inverse length", 2e8),
        ("1e8 m^-1", "inverse length", 1e8),
        ("5 /um", "inverse length", 5e6),
        ("0.3", "dimensionless", 0.3),
        ("7", "length", 7.0),  # plain numbers are SI
        (2.5, "pressure", 2.5),
    ],
)
def test_parse_quantity(text, dimension, si):
    assert parse_quantity(text, dimension, "x") == pytest.approx(si, rel=1e-12)


@pytest.mark.parametrize(
    ("text", "dimension", "match"),
    [
        ("10 MPa", "length", r"interaction_range must be a length .* got '10 MPa', a pressure"),
        ("0.5 nm", "pressure", r"interaction_range must be a pressure"),
        ("50 mJ", "energy per area", r"must be an energy per area .* got '50 mJ', an energy \(J\)"),
        ("3 Mpa", "pressure", r"interaction_range: unknown unit 'Mpa'"),
        ("ten nm", "length", r"interaction_range: cannot read"),
        ("5 m^x", "length", r"interaction_range: cannot read the unit"),
        ("0.1 nm", "dimensionless", r"must be a dimensionless"),
    ],
)
def test_parse_quantity_errors(text, dimension, match):
    with pytest.raises(ParameterError, match=match):
        parse_quantity(text, dimension, "interaction_range")


def test_parse_quantity_rejects_bool_and_unknown_dimension():
    with pytest.raises(ParameterError):
        parse_quantity(True, "length", "d_rep")
    with pytest.raises(ParameterError, match="dimension"):
        parse_quantity("1 m", "volume", "d_rep")


# ------------------------------------------------------------- calculator basics
def test_criterion_fields_and_youngs_modulus():
    r = stickiness_criterion(youngs_modulus="3 MPa", poisson=0.5, d_rep="10 nm", **RUBBER)
    assert isinstance(r, StickinessCriterion)
    assert r.contact_modulus == pytest.approx(4e6)  # E/(1 - nu^2)
    assert r.adhesion_length == pytest.approx(0.05 / 4e6)
    assert r.margin == pytest.approx(r.kappa_rep / r.kappa_att)
    assert r.sticky and r.kappa < 0 and r.margin > 1
    d = r.to_dict()
    json.dumps(d)
    for key in ("kappa_att", "area_ratio", "kappa", "sticky", "margin", "adhesion_length",
                "necessary_condition_met", "contact_modulus", "work_of_adhesion"):  # fmt: skip
        assert key in d
    c = stickiness_criterion(contact_modulus="4 MPa", rms_curvature="0.4 1/nm", **RUBBER)
    assert c.d_rep == pytest.approx(1e-8) and c.d_rep_source == "predicted"
    assert c.margin == pytest.approx(r.margin)
    assert stickiness_criterion(contact_modulus=4e6, d_rep=1e-8, **RUBBER).margin == pytest.approx(
        r.margin
    )


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"contact_modulus": "1 MPa", "youngs_modulus": "1 MPa"}, "exactly one of contact_mod"),
        ({}, "exactly one of contact_modulus"),
        ({"youngs_modulus": "1 MPa"}, "poisson"),
        ({"contact_modulus": "1 MPa", "poisson": 0.3}, "poisson"),
        ({"youngs_modulus": "1 MPa", "poisson": 0.7}, r"poisson must be in \(-1, 0.5\]"),
        ({"contact_modulus": "-1 MPa"}, "contact_modulus must be > 0"),
        ({"contact_modulus": "1 nm"}, "contact_modulus must be a pressure"),
        ({"contact_modulus": "1 MPa", "d_rep": "1 MPa"}, "d_rep must be a length"),
        ({"contact_modulus": "1 MPa", "rms_curvature": "1 nm", "d_rep": None}, "rms_curvature"),
        ({"contact_modulus": "1 MPa", "rms_curvature": "1 1/nm"}, "exactly one of d_rep"),
        ({"contact_modulus": "1 MPa", "atomic_spacing": "0 nm"}, "atomic_spacing"),
    ],
)
def test_criterion_bad_input(kwargs, match):
    kw = {"d_rep": "10 nm", **RUBBER, **kwargs}
    if kw.get("d_rep") is None:
        kw.pop("d_rep")
    with pytest.raises(ParameterError, match=match):
        stickiness_criterion(**kw)


# ------------------------------------------------------- the Discussion's examples
def test_diamond_adhesion_length_and_slope():
    # "diamond has E* ~ 1e12 Pa and w ~ 10 J/m^2, yielding l_a/a0 ~ 0.06 with a0 the
    # carbon bond length ... adhesion should occur for h'rms of order 0.1 and below ...
    # Increasing h'rms to 0.3 suppresses adhesion."
    kw = {"contact_modulus": "1e12 Pa", "work_of_adhesion": "10 J/m^2",
          "interaction_range": "0.154 nm", "atomic_spacing": "0.154 nm"}  # fmt: skip
    r = stickiness_criterion(rms_slope=0.1, d_rep="1.54 nm", **kw)  # d_rep ~ 10 a0
    assert r.adhesion_length_over_atomic_spacing == pytest.approx(0.06, rel=0.15)  # 0.065
    assert r.necessary_condition_met and r.sticky
    r3 = stickiness_criterion(rms_slope=0.3, d_rep="1.54 nm", **kw)
    assert not r3.necessary_condition_met and not r3.sticky


def test_van_der_waals_stiff_solids_need_slopes_of_order_1e_3():
    # "exposing surfaces to the environment ... w ~ 50 mJ/m^2. The value of l_a and the
    # rms slope needed to eliminate adhesion are reduced by two to three orders of
    # magnitude. Only ... slopes low enough to stick (<~ 1e-3)."
    for modulus in ("100 GPa", "1000 GPa"):
        kw = {"contact_modulus": modulus, "work_of_adhesion": "50 mJ/m^2",
              "interaction_range": "0.3 nm", "d_rep": "100 nm"}  # fmt: skip
        r = stickiness_criterion(rms_slope=1e-3, **kw)
        max_slope = r.adhesion_length_over_atomic_spacing / 0.4859  # necessary condition
        assert 1e-4 < max_slope < 1e-2
        assert stickiness_criterion(rms_slope=1e-5, **kw).necessary_condition_met
        assert not stickiness_criterion(rms_slope=3e-2, **kw).necessary_condition_met
    # "for most surfaces, Eq. 7 predicts kappa_att >> 1 and hence kappa ~ kappa_rep"
    r = stickiness_criterion(contact_modulus="100 GPa", work_of_adhesion="50 mJ/m^2",
                             interaction_range="0.3 nm", d_rep="100 nm", rms_slope=0.1)  # fmt: skip
    assert r.kappa_att > 100 and r.kappa == pytest.approx(2.0, rel=0.01) and not r.sticky


def test_rubber_sticks_below_about_10_mpa_paper_does_not():
    # "surfaces with w = 50 mJ/m^2, h'rms ~ 1, Delta_r ~ 0.5 nm, and d_rep ~ 10 nm will be
    # sticky if E* <~ 10 MPa ... whereas paper is much stiffer (> 1 GPa)."
    for modulus in ("1 MPa", "10 MPa"):
        assert stickiness_criterion(contact_modulus=modulus, d_rep="10 nm", **RUBBER).sticky
    for modulus in ("1 GPa", "5 GPa"):
        paper = stickiness_criterion(contact_modulus=modulus, d_rep="10 nm", **RUBBER)
        assert not paper.sticky and paper.margin < 0.1
    r = stickiness_criterion(contact_modulus="10 MPa", d_rep="10 nm", **RUBBER)
    # Eq. 10 puts the threshold at 70 MPa: the paper's "<~ 10 MPa" within its "~"
    assert r.max_sticky_contact_modulus == pytest.approx(70.4e6, rel=0.01)
    assert 10e6 < r.max_sticky_contact_modulus < 1e9
    assert r.margin == pytest.approx(7.04, rel=0.01)


def test_tape_below_dahlquist_sticks_up_to_about_100_um():
    # "Tapes are normally designed to have moduli below 0.1 MPa (Dahlquist criterion).
    # Taking h'rms ~ 1 and Delta_r ~ 0.5 nm, one finds adhesion for d_rep <~ 100 um."
    tape = stickiness_criterion(contact_modulus="0.1 MPa", d_rep="100 um", **RUBBER)
    assert tape.sticky and tape.necessary_condition_met
    assert tape.max_sticky_d_rep == pytest.approx(187e-6, rel=0.01)
    assert 100e-6 / 3 < tape.max_sticky_d_rep < 3 * 100e-6
    assert not stickiness_criterion(contact_modulus="0.1 MPa", d_rep="1 mm", **RUBBER).sticky
    at_max = stickiness_criterion(contact_modulus="0.1 MPa", d_rep=tape.max_sticky_d_rep, **RUBBER)
    assert at_max.margin == pytest.approx(1.0, rel=1e-9)
    assert math.isfinite(tape.kappa) and tape.kappa < 0
