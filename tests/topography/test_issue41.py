"""Scans a user can trust, round three (issue 41): scoped answers, model checks.

Oracles: Eq. 10 (``stickiness_criterion``) at the measured statistics; Monti, Sanner &
Pastewka's g0 = 16/3 h'rms^2/h''rms written out here from the statistics; Müser's
parameter written out with R = 1/h''rms.
"""

import numpy as np
import pytest

import roughcontact as rc
from roughcontact.topography import Topography, stick
from roughcontact.topography.report import summary

NM = 1e-9
PDMS = {"modulus": "2 MPa", "poisson": 0.5, "work_of_adhesion": "0.05 J/m^2"}
SILICON = {"modulus": "160 GPa", "poisson": 0.22, "work_of_adhesion": "0.1 J/m^2"}


def _topo(h, a=NM):
    return Topography(h, (a, a), height_unit="m", info={"length_unit": "m"})


def _surface(hurst=0.8, n=128, seed=1):
    return rc.self_affine((n, n), hurst=hurst, rms_height=NM, short_cutoff=2, seed=seed) * 1.0


# ------------------------------------------------ item 1: the surface's answer is not scoped


def test_a_measured_scale_answer_is_not_the_surface_answer():
    """White noise is not self-affine: nothing is extrapolated, so the surface's answer is
    open (null) and the measured scale's answer (sticky for PDMS) is a separate field."""
    h = NM * np.random.default_rng(3).standard_normal((64, 64))
    r = stick(_topo(h), reliability_cutoff="4 nm", **PDMS)
    assert r.verdict.scope == "measured scale"
    assert r.sticky is None and r.sticky_measured_scale is True
    d = r.to_dict()
    assert d["sticky"] is None and d["sticky_measured_scale"] is True
    assert d["measured"]["sticky"] is True  # the old key is kept
    text = "\n".join(summary(r))
    assert "answer for the whole surface (sticky): undecided" in text
    assert "(sticky_measured_scale): sticky" in text


def test_an_extrapolated_verdict_keeps_the_measured_answer_beside_it():
    r = stick(_topo(_surface()), **SILICON)
    assert r.verdict.extrapolated
    assert r.sticky_measured_scale is (r.margin > 1)
    assert r.to_dict()["sticky_measured_scale"] is (r.margin > 1)


# ------------------------------------------------- item 10: the field's model checks


def test_monti_sanner_pastewka_check_by_hand():
    r = stick(_topo(_surface()), **SILICON)
    s = r.statistics
    g0 = 16 / 3 * s.rms_slope**2 / s.rms_curvature
    msp = r.to_dict()["model_checks"]["monti_sanner_pastewka"]
    assert msp["measured"]["g0"] == pytest.approx(g0, rel=1e-12)
    assert msp["measured"]["rho_over_g0"] == pytest.approx(0.5 * NM / g0, rel=1e-12)
    assert msp["measured"]["holds"] is (0.5 * NM / g0 < 0.1)
    # extrapolated to a0: h''rms grows faster than h'rms^2, g0 shrinks
    assert msp["extrapolated"]["g0"] < msp["measured"]["g0"]
    assert msp["threshold"] == 0.1 and "Monti" in msp["reference"]
    assert any(n.startswith("Monti, Sanner & Pastewka") for n in r.notes)
    assert "rho/g0" in "\n".join(summary(r))


def test_muser_parameter_in_stick_uses_r_equal_one_over_curvature():
    r = stick(_topo(_surface()), **SILICON)
    m = next(c for c in r.criteria["criteria"] if c["key"] == "muser")
    inputs = r.criteria["inputs"]
    la = 0.1 / r.inputs["contact_modulus"]
    expected = (1 / inputs["rms_curvature"]) ** (1 / 3) * la ** (2 / 3) / (0.5 * NM)
    assert m["parameter"] == pytest.approx(expected, rel=1e-9)
    assert "unverified" not in m["verdict"]


# ------------------------------------------- item 8: --simulate for a soft material


def test_soft_simulation_says_why_in_words_a_stick_user_can_act_on(tmp_path):
    """PDMS-like (l_a/a0 = 83): every seed jumps into contact before 1 % repulsive area.
    The seeds' line and notes say so (no bare "failed", no `roughcontact path` advice),
    and Eq. 10's "undecided" on the same surfaces comes with its reason."""
    h = rc.self_affine(128, hurst=0.8, rms_slope=0.1, short_cutoff=1.2, pixel_size=0.6, seed=5)
    path = tmp_path / "fine.npy"
    np.save(path, h)
    r = stick(path, pixel_size="0.6 nm", height_unit="nm", periodic=True, detrend="height",
              modulus="2 MPa", work_of_adhesion="0.05 J/m^2", simulate=True,
              simulate_size=64, simulate_seeds=1)  # fmt: skip
    text = "\n".join(summary(r))
    assert "failed" not in text and "roughcontact path" not in text
    assert "--until-area" not in text
    seeds_line = next(x for x in summary(r) if x.startswith("per seed kappa"))
    assert "seed 1: jumped into contact, no kappa" in seeds_line
    assert any("soft-solid limit" in n for n in r.simulation.notes)
    sim_line = next(x for x in summary(r) if x.startswith("simulated:"))
    if r.simulation.predicted_verdict == "undecided":
        assert "undecided (" in sim_line  # with its reason


def test_contact_map_title_and_legend_give_the_same_area():
    """The map is the approach's state nearest 1 %: its own A_rep/A0 (0.0039 here) in the
    panel title and in the legend, not the 1 % target; an empty state gives no map."""
    from types import SimpleNamespace

    from roughcontact.topography.report import figure_contact_map

    p = np.zeros((32, 32))
    p[:2, :2] = 1.0  # A_rep/A0 = 4/1024 = 0.0039
    p[5:9, 5:9] = -1.0

    def result(pressure):
        sim = SimpleNamespace(contact_map=(1, pressure), verdict="sticky",
                              interaction={"adhesion_length_over_a0": 0.05})  # fmt: skip
        return SimpleNamespace(simulation=sim)

    fig = figure_contact_map(result(p))
    title = fig.axes[0].get_title()
    legend = fig.legends[0].get_title().get_text()
    assert "0.0039" in title and "0.0039" in legend and "0.01" not in legend
    assert figure_contact_map(result(-np.abs(p))) is None
