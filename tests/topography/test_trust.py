"""Measured scans a user can trust: one test per failure of issue #29.

Oracles: surfaces of known spectrum (``rc.self_affine``) with a known white-noise floor or
a known blur; the bias a filled fraction must cause (computed from the unfilled surface);
Johnson's composite modulus written out here; Eq. 10 (``stickiness_criterion``) at the
measured statistics; the scaling ``margin ~ kappa_rep`` of Eq. 10.
"""

import math
import re

import numpy as np
import pytest
from scipy.ndimage import gaussian_filter

import roughcontact as rc
from roughcontact import ParameterError
from roughcontact.criterion import stickiness_criterion
from roughcontact.moduli import composite_modulus
from roughcontact.topography import Topography, load_topography, scale_statistics, stick
from roughcontact.topography.fitrange import good_range, self_affine_problem
from roughcontact.topography.missing import MISSING_FILL_MAX
from roughcontact.topography.notes import PAPER_WALL_KAPPA_REP
from roughcontact.topography.report import summary

NM = 1e-9
SILICON = {"modulus": "160 GPa", "poisson": 0.22, "work_of_adhesion": "0.1 J/m^2"}
PDMS = {"modulus": "2 MPa", "poisson": 0.5, "work_of_adhesion": "0.05 J/m^2"}


def _surface(hurst=0.8, n=256, seed=1):
    """Heights [m] of a periodic self-affine map, 1 nm pixels, h_rms 1 nm."""
    return rc.self_affine((n, n), hurst=hurst, rms_height=NM, short_cutoff=2, seed=seed) * 1.0


def _topo(h, a=NM):
    return Topography(h, (a, a), height_unit="m", info={"length_unit": "m"})


def _npy(tmp_path, h, name="scan.npy"):
    path = tmp_path / name
    np.save(path, h / NM)
    return path


# ----------------------------------------------------------------- 1. missing points


def _holes(shape, fraction, seed=0):
    rng = np.random.default_rng(seed)
    mask = np.zeros(shape, bool)
    mask.flat[rng.choice(mask.size, round(fraction * mask.size), replace=False)] = True
    return mask


def test_a_few_missing_points_are_filled_by_default_and_said(tmp_path):
    h = _surface()
    holed = h.copy()
    holed[_holes(h.shape, 0.004)] = np.nan
    r = stick(_npy(tmp_path, holed), pixel_size="1 nm", height_unit="nm", **SILICON)
    filled = r.topography.info["missing_data"]
    assert filled["points"] == round(0.004 * h.size) and not filled["asked"]
    text = "\n".join(summary(r))
    assert f"filled {filled['points']} of {h.size} missing points" in text
    assert "harmonic interpolation" in text
    assert any("missing points" in n for n in r.to_dict()["notes"])


def test_many_missing_points_are_refused_naming_fraction_and_option(tmp_path):
    holed = _surface()
    holed[_holes(holed.shape, 0.27)] = np.nan
    path = _npy(tmp_path, holed)
    with pytest.raises(ParameterError) as err:
        stick(path, pixel_size="1 nm", height_unit="nm", **SILICON)
    text = str(err.value)
    assert "\n" not in text and "27.0%" in text and "--fill-missing" in text
    with pytest.raises(ParameterError, match="fill_missing=False"):
        stick(path, pixel_size="1 nm", height_unit="nm", fill_missing=False, **SILICON)
    r = stick(path, pixel_size="1 nm", height_unit="nm", fill_missing=True, **SILICON)
    note = next(n for n in r.notes if "missing points" in n)
    assert "27.000%" in note and "more than the 1%" in note  # the fraction is stated


def test_the_default_threshold_bias_is_below_the_fill_fraction():
    """Filling f of the points lowers h'rms^2 by about f (module docstring of missing)."""
    from roughcontact.topography._grid import harmonic_fill

    h = _surface(hurst=0.6, seed=4)
    exact = scale_statistics(h, NM, periodic=True).rms_slope
    mask = _holes(h.shape, MISSING_FILL_MAX, seed=2)
    holed = h.copy()
    holed[mask] = np.nan
    filled = harmonic_fill(holed, mask, periodic=True)
    got = scale_statistics(filled, NM, periodic=True).rms_slope
    assert 1 - (got / exact) ** 2 == pytest.approx(MISSING_FILL_MAX, rel=0.5)


def test_load_topography_and_the_cli_readers_share_the_policy(tmp_path):
    holed = _surface()
    holed[_holes(holed.shape, 0.05)] = np.nan
    path = _npy(tmp_path, holed)
    with pytest.raises(ParameterError, match="5.0%"):
        load_topography(path, pixel_size=NM, height_unit="nm")
    topo = load_topography(path, pixel_size=NM, height_unit="nm", fill_missing=True)
    assert np.isfinite(topo.heights).all()


# ------------------------------------------------ 2. a fit that knows where data is good


def test_noise_floor_is_found_and_the_fit_stays_above_it():
    h = _surface(hurst=0.8)
    noisy = h + 0.2 * NM * np.random.default_rng(0).standard_normal(h.shape)
    stats = scale_statistics(noisy, NM)
    good = good_range(stats.psd, stats.measured_scale, 256 * NM / 4)
    assert good.noise_floor is not None and good.short > 3 * stats.measured_scale
    r = stick(_topo(noisy), **SILICON)
    assert r.statistics.fit.hurst == pytest.approx(0.8, abs=0.2)  # the naive fit: 0.67
    assert r.statistics.measured_scale == pytest.approx(good.short, rel=0.01)
    assert "noise floor" in r.inputs["reliability_cutoff_source"]
    assert any("noise floor" in line for line in summary(r))


def test_clean_spectrum_keeps_the_whole_range():
    stats = scale_statistics(_surface(hurst=0.5), NM, periodic=True)
    good = good_range(stats.psd, stats.measured_scale, 64 * NM)
    assert good.noise_floor is None and good.usable
    assert good.short == pytest.approx(stats.measured_scale, rel=0.15)


@pytest.mark.parametrize("case", ["noise only", "blurred"])
def test_spectrum_that_is_not_self_affine_gives_no_extrapolated_verdict(case):
    rng = np.random.default_rng(3)
    if case == "noise only":  # white noise: H = -1 (the .mnt failure)
        h = NM * rng.standard_normal((128, 128))
    else:  # smooth bumps: steeper than any self-affine spectrum (the .al3d H = 2.14)
        h = gaussian_filter(_surface(hurst=0.8, n=128), 4, mode="wrap")
    r = stick(_topo(h), reliability_cutoff="4 nm", **PDMS)
    v = r.verdict
    assert not v.extrapolated and v.scope != "all scales"
    assert self_affine_problem(r.statistics.fit) == v.no_extrapolation
    measured = stickiness_criterion(rms_slope=r.statistics.rms_slope,
                                    rms_curvature=r.statistics.rms_curvature,
                                    contact_modulus=r.inputs["contact_modulus"],
                                    work_of_adhesion=0.05, interaction_range="0.5 nm")  # fmt: skip
    assert v.margin == pytest.approx(measured.margin, rel=1e-12)
    # a scoped answer is not the surface's: sticky is None, the measured one beside it
    assert v.sticky is None and v.sticky_measured_scale is measured.sticky
    assert "at the measured scale" in v.text and "no verdict for the whole surface" in v.text
    lines = summary(r)
    assert lines[1].startswith("no extrapolated verdict because")
    assert "--fit-range" in lines[1] and "--reliability-cutoff" in lines[1]
    assert not any(line.startswith("extrapolated down to") for line in lines)
    d = r.to_dict()
    assert d["sticky"] is None and d["sticky_measured_scale"] is measured.sticky
    assert d["scope"] == "measured scale"
    assert "(sticky): undecided" in "\n".join(lines)
    assert d["extrapolated"] is None and d["criterion_atomic"] is None
    assert d["no_extrapolation"] == v.no_extrapolation


def test_necessary_condition_decides_without_an_extrapolation():
    """Roughness below the measured scale only raises h'rms: a failed necessary condition
    is 'not sticky' at every scale even when nothing can be extrapolated."""
    h = NM * np.random.default_rng(3).standard_normal((128, 128))
    r = stick(_topo(h), **SILICON)
    assert r.sticky is False and r.verdict.scope == "all scales (necessary condition)"
    assert r.sticky_measured_scale is False  # the surface's answer holds for the scale too
    assert "necessary condition" in r.verdict.text


def test_continuum_validity_is_said_where_the_extrapolation_reaches_atoms():
    r = stick(_topo(_surface(hurst=0.8)), **PDMS)
    v = r.verdict
    assert v.continuum_limit is not None
    k = v.centre
    d_rep = 4 * v.slopes[k] / v.curvatures[k]
    j = int(np.flatnonzero(v.scales == v.continuum_limit)[0])
    assert d_rep[j] <= 3 * 0.3 * NM or v.slopes[k, j] >= 1
    assert np.all((d_rep[:j] > 0.9 * NM) & (v.slopes[k, :j] < 1))
    assert any("outside its validity" in line for line in summary(r))


# -------------------------------------------- 3. every note in the text, readable ranges


def test_every_note_is_in_the_text_and_ranges_read_well():
    r = stick(_topo(_surface(hurst=0.3)), **SILICON)
    text = "\n".join(summary(r))
    for note in r.notes:
        assert note in text
    # "H = -0.79--0.58" and "0.73-1.07" were unreadable: ranges read "A to B"
    assert not re.search(r"\d\.\d+--?\d", text), text
    assert re.search(r"H = -?\d\.\d\d to -?\d\.\d\d", text)


# ------------------------------------------------------------------- 4. two bodies


def test_composite_modulus_of_two_bodies():
    one = composite_modulus("160 GPa", 0.22)
    assert one.contact_modulus == pytest.approx(160e9 / (1 - 0.22**2))
    assert math.isinf(one.counter) and "rigid" in one.text
    two = composite_modulus("160 GPa", 0.22, "160 GPa", 0.22)
    assert two.contact_modulus == pytest.approx(one.contact_modulus / 2)  # silicon on silicon
    mixed = composite_modulus(2e6, 0.5, 70e9, 0.3)
    assert 1 / mixed.contact_modulus == pytest.approx((1 - 0.25) / 2e6 + (1 - 0.09) / 70e9)
    with pytest.raises(ParameterError, match="counter_poisson"):
        composite_modulus(1e9, 0.3, None, 0.3)


def test_stick_takes_the_counter_surface():
    topo = _topo(_surface(hurst=0.5))
    rigid = stick(topo, **SILICON)
    pair = stick(topo, counter_modulus="160 GPa", counter_poisson=0.22, **SILICON)
    assert pair.inputs["contact_modulus"] == pytest.approx(rigid.inputs["contact_modulus"] / 2)
    assert pair.margin == pytest.approx(2 * rigid.margin, rel=1e-9)  # margin ~ l_a = w/E*
    assert any("1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2" in line for line in summary(pair))
    assert any("rigid counter-surface" in line for line in summary(rigid))


# ------------------------------------------------------------------- 5. both kappa_rep


def test_both_kappa_rep_and_which_stands_when_they_disagree():
    topo = _topo(_surface(hurst=0.5))
    ref = stick(topo, **SILICON, atomic_spacing="2 nm")  # a0 = lambda_c: no sweep below it
    assert ref.verdict.scales.size == 1
    # E* that puts the margin at 0.8 with kappa_rep = 2 (not sticky): 3.4 makes it 1.36
    modulus = ref.inputs["contact_modulus"] * ref.margin / 0.8
    r = stick(topo, modulus=modulus, work_of_adhesion="0.1 J/m^2", atomic_spacing="2 nm")
    check = r.kappa_rep_check
    assert check["kappa_rep"] == PAPER_WALL_KAPPA_REP
    assert r.margin == pytest.approx(0.8, rel=1e-9)
    assert check["verdict"].margin == pytest.approx(r.margin * PAPER_WALL_KAPPA_REP / 2)
    assert r.sticky is False and check["verdict"].sticky is True
    assert not check["agree"] and check["stand_behind"] == 2.0
    line = next(x for x in summary(r) if "kappa_rep matters" in x)
    assert "stands behind kappa_rep = 2" in line
    d = r.to_dict()["kappa_rep_comparison"]
    assert d["other"]["kappa_rep"] == PAPER_WALL_KAPPA_REP and d["agree"] is False


# ------------------------------------------------ 6. --simulate for the materials people use


def test_simulation_uses_the_range_asked_for_and_soft_solids_jump_into_contact():
    """Silicon's Delta_r = 0.5 nm is simulated as asked (it was 0.065 nm); PDMS
    (l_a/a0 = 62.5, refused before) jumps into contact: the model's own limit, sticky."""
    a = 0.6 * NM  # Nyquist 4 a0: the synthetic surfaces continue the scan directly
    h = rc.self_affine(64, hurst=0.8, rms_slope=0.2, short_cutoff=2 * a, pixel_size=a, seed=2)
    topo = Topography(h, (a, a), periodic=True, height_unit="m", info={"length_unit": "m"})
    kw = {"detrend": "height", "simulate": True, "simulate_size": 64, "simulate_seeds": 1}
    si = stick(topo, **SILICON, **kw).simulation
    assert si.interaction["range"] == pytest.approx(0.5 * NM)
    assert si.interaction["law"] == "dugdale"
    # 64^2 sites: the window (rms height 0.5 a0) lies within reach of a 1.7 a0 attraction,
    # its seed sticks against the necessary condition -- said, and not taken as sticky
    assert si.verdict == "undecided" and any("finite-size effect" in n for n in si.notes)
    soft = stick(topo, **PDMS, **kw)
    sim = soft.simulation
    assert sim.interaction["adhesion_length_over_a0"] == pytest.approx(62.5, rel=1e-9)
    assert sim.verdict == "sticky" and sim.inverse_kappa.n == 0
    assert sim.runs[0].pull_off > 0
    assert any("jumped into contact" in n for n in sim.notes)
    assert any("jumped into contact" in line for line in summary(soft))


@pytest.mark.parametrize(
    ("hurst", "stderr", "word"),
    [
        (2.14, 0.15, "not self-affine"),  # the .al3d fit of the issue
        (-0.68, 0.05, "not self-affine"),  # the .mnt fit along its noise floor
        (0.09, 0.17, "reaches H <= 0"),  # the .plu fit: band -0.25 to 0.43
        (0.04, 0.06, "reaches H <= 0"),  # nid-1.nid: h'rms 4.7 at 0.3 nm
        (0.7, 0.2, "poorly"),  # band 0.3 to 1.1
        (0.38, 0.16, ""),  # a wide band inside (0, 1): propagated, not refused
        (0.8, 0.05, ""),
    ],
)
def test_which_fits_support_an_extrapolation(hurst, stderr, word):
    from roughcontact.topography.statistics import HurstFit

    fit = HurstFit(hurst, stderr, 2, 1e8, 1e-36, (10 * NM, 1e-6), 12)
    problem = self_affine_problem(fit)
    assert (word in problem) if word else problem == ""
    if word:
        assert "10 nm to 1 um" in problem and f"{hurst:.2f}" in problem


def test_criterion_command_takes_the_counter_surface():
    import json

    from click.testing import CliRunner

    from roughcontact.cli.main import main

    base = ["criterion", "--youngs-modulus", "160GPa", "--poisson", "0.22",
            "--work-of-adhesion", "0.1", "--rms-slope", "0.1", "--range", "0.5nm",
            "--d-rep", "10nm", "--json"]  # fmt: skip
    rigid = json.loads(CliRunner().invoke(main, base).output)
    r = CliRunner().invoke(main, [*base, "--counter-modulus", "160GPa", "--counter-poisson",
                                  "0.22"])  # fmt: skip
    pair = json.loads(r.output)
    assert pair["contact_modulus"] == pytest.approx(rigid["contact_modulus"] / 2)
    assert pair["margin"] == pytest.approx(2 * rigid["margin"])  # margin ~ w/E*
    assert "(1-nu2^2)/E2" in pair["contact_modulus_formula"]
