"""Classical rough-contact theories: Persson, Bush-Gibson-Thomas, Greenwood-Williamson
with Hertz, DMT and JKR (Fuller-Tabor) summits."""

import math

import numpy as np
import pytest
from scipy.special import erf
from scipy.stats import norm

import roughcontact as rc
from roughcontact import ParameterError
from roughcontact.theory import (
    BGT_KAPPA,
    PERSSON_KAPPA,
    SummitStatistics,
    bgt_area,
    fuller_tabor_parameter,
    greenwood_williamson,
    persson_area,
    persson_load,
    spectral_moments,
    summit_statistics,
    summit_statistics_from_heights,
)


# ------------------------------------------------------------------ Persson and BGT
def test_kappa_constants():
    assert PERSSON_KAPPA == pytest.approx(math.sqrt(8 / math.pi)) and PERSSON_KAPPA > 1.5957
    assert BGT_KAPPA == pytest.approx(math.sqrt(2 * math.pi)) and BGT_KAPPA < 2.5067


@pytest.mark.parametrize(("slope", "modulus"), [(0.1, 1.0), (0.5, 3e9)])
def test_persson_small_load_kappa_and_full_contact(slope, modulus):
    p = 1e-7 * slope * modulus
    assert slope * modulus * persson_area(p, slope, modulus) / p == pytest.approx(
        PERSSON_KAPPA, rel=1e-9
    )
    loads = np.linspace(0, 5, 101) * slope * modulus
    area = persson_area(loads, slope, modulus)
    assert area[0] == 0 and np.all(np.diff(area[:40]) > 0) and np.all(np.diff(area) >= 0)
    assert area[-1] == pytest.approx(1.0, abs=1e-12)  # A -> A0 at large load
    np.testing.assert_allclose(persson_load(area[:60], slope, modulus), loads[:60], rtol=1e-9)
    # below the small-load line (area saturates)
    assert np.all(area[1:] < PERSSON_KAPPA * loads[1:] / (slope * modulus))


def test_persson_matches_G_from_the_power_spectrum():
    # A/A0 = erf(1/(2 sqrt(G))), G = (pi/4)(E*/p)^2 int q^3 C dq with C normalised as
    # rc.power_spectrum (h_rms^2 = int d^2q C): our closed form in h'_rms must agree.
    h = rc.self_affine((256, 256), hurst=0.8, rms_slope=0.2, short_cutoff=8, seed=3)
    q, C, n = rc.power_spectrum(h, return_counts=True)
    dq2 = (2 * math.pi / 256) ** 2
    int_q3C = np.sum(q**2 * C * n) * dq2 / (2 * math.pi)  # int d^2q = 2 pi int q dq
    slope = rc.statistics(h).rms_slope
    for p in (1e-3, 0.05, 0.3):
        G = math.pi / 4 / p**2 * int_q3C
        assert persson_area(p, slope) == pytest.approx(erf(1 / (2 * math.sqrt(G))), rel=0.03)


def test_bgt_small_load_law():
    assert bgt_area(2e-3, 0.1) == pytest.approx(BGT_KAPPA * 2e-3 / 0.1)
    np.testing.assert_allclose(bgt_area([0, 1e-3], 0.2, 2.0), [0, BGT_KAPPA * 1e-3 / 0.4])
    with pytest.raises(ParameterError, match="load"):
        bgt_area(-1.0, 0.1)
    with pytest.raises(ParameterError, match="area_fraction"):
        persson_load(1.0, 0.1)


# ---------------------------------------------------------- summit statistics (GW)
def test_summit_statistics_nayak_mccool():
    m0, m2, m4 = 2.0, 0.02, 0.004
    s = summit_statistics(m0, m2, m4)
    alpha = m0 * m4 / m2**2
    assert s.bandwidth == pytest.approx(20.0)
    assert s.density == pytest.approx(m4 / (6 * math.pi * math.sqrt(3) * m2))
    assert 1 / s.radius == pytest.approx(8 / 3 * math.sqrt(m4 / math.pi))
    assert s.height_std**2 == pytest.approx(m0 * (1 - 0.8968 / alpha))
    assert s.mean_height == pytest.approx(4 * math.sqrt(m0) / math.sqrt(math.pi * alpha))
    with pytest.raises(ParameterError, match="bandwidth"):
        summit_statistics(1.0, 1.0, 0.5)


def test_spectral_moments_from_heights():
    h = rc.self_affine((256, 256), hurst=0.8, rms_slope=0.1, short_cutoff=8, seed=5)
    m0, m2, m4 = spectral_moments(h)
    st = rc.statistics(h)
    assert m0 == pytest.approx(st.rms_height**2)
    # profile moments from spectral derivatives along x and y
    qx = 2 * np.pi * np.fft.fftfreq(256)
    H = np.fft.fft2(h)
    hx = np.real(np.fft.ifft2(1j * qx[:, None] * H))
    hy = np.real(np.fft.ifft2(1j * qx[None, :] * H))
    hxx = np.real(np.fft.ifft2(-(qx[:, None] ** 2) * H))
    hyy = np.real(np.fft.ifft2(-(qx[None, :] ** 2) * H))
    assert m2 == pytest.approx((np.mean(hx**2) + np.mean(hy**2)) / 2, rel=1e-6)
    assert m4 == pytest.approx((np.mean(hxx**2) + np.mean(hyy**2)) / 2, rel=0.05)  # isotropy
    s = summit_statistics_from_heights(h)
    assert s.m4 == m4 and s.bandwidth > 1


# ------------------------------------------------------------ GW area-load curves
SUMMITS = summit_statistics(1.0, 0.01, 0.001)


def test_gw_hertz_closed_form_and_small_load_kappa():
    s = SUMMITS
    t = np.array([-1.0, 0.0, 2.0, 4.0, 8.0, 12.0])
    c = greenwood_williamson(s.mean_height + t * s.height_std, s)
    i1 = norm.pdf(t) - t * norm.sf(t)  # int_t^inf (u - t) phi(u) du
    np.testing.assert_allclose(c.area_fraction, s.density * math.pi * s.radius * s.height_std * i1,
                               rtol=1e-9)  # fmt: skip
    np.testing.assert_allclose(c.contact_density, s.density * norm.sf(t), rtol=1e-12)
    # GW has no finite small-load kappa: it grows as sqrt(t) (Gaussian tail), with
    # kappa -> h' (3 pi/4) (R/sigma)^(1/2) t^(1/2) / Gamma(5/2) (1 + 11/(8 t^2) + ...)
    kappa = c.kappa(0.1)
    assert np.all(np.diff(kappa) > 0)
    asym = 0.1 * 0.75 * math.pi * math.sqrt(s.radius / s.height_std) * np.sqrt(t[4:])
    asym *= (1 + 11 / (8 * t[4:] ** 2)) / math.gamma(2.5)
    np.testing.assert_allclose(kappa[4:], asym, rtol=2e-3)


def test_gw_dmt_is_hertz_plus_adhesion_term():
    s, w = SUMMITS, 2e-3
    d = s.mean_height + np.linspace(-1, 4, 11) * s.height_std
    hz = greenwood_williamson(d, s, contact_modulus=2.0)
    dmt = greenwood_williamson(d, s, contact_modulus=2.0, work_of_adhesion=w, asperity="dmt")
    np.testing.assert_array_equal(dmt.area_fraction, hz.area_fraction)
    np.testing.assert_allclose(
        dmt.mean_pressure, hz.mean_pressure - 2 * math.pi * w * s.radius * hz.contact_density
    )


def test_gw_jkr_reduces_to_hertz_for_weak_adhesion():
    s = SUMMITS
    d = s.mean_height + np.linspace(-1, 4, 6) * s.height_std
    hz = greenwood_williamson(d, s)
    jkr = greenwood_williamson(d, s, work_of_adhesion=1e-10, asperity="jkr")
    np.testing.assert_allclose(jkr.area_fraction, hz.area_fraction, rtol=1e-3)
    np.testing.assert_allclose(jkr.mean_pressure, hz.mean_pressure, rtol=1e-3)


def test_gw_pull_off_per_asperity_for_a_narrow_height_distribution():
    # all summits at one height: the curve is that of a single asperity times eta.
    R, E, w, eta = 10.0, 1.0, 0.01, 0.01
    dd = 0.75 * (math.pi**2 * w**2 * R / E**2) ** (1 / 3)  # JKR jump-out distance
    s = SummitStatistics(density=eta, radius=R, height_std=1e-4 * dd, mean_height=0.0,
                         bandwidth=10.0, m0=1.0, m2=1.0, m4=1.0)  # fmt: skip
    d = np.append(np.linspace(-0.5 * dd, 1.2 * dd, 341), -5 * s.height_std)  # just touching
    kw = {"contact_modulus": E, "work_of_adhesion": w}
    unload = greenwood_williamson(d, s, asperity="jkr", branch="unloading", **kw)
    assert unload.pull_off == pytest.approx(eta * 1.5 * math.pi * w * R, rel=1e-4)
    load = greenwood_williamson(d, s, asperity="jkr", branch="loading", **kw)
    # on loading, contacts form at touching, where F = -(4/3) pi w R
    assert load.pull_off == pytest.approx(eta * 4 / 3 * math.pi * w * R, rel=1e-3)
    dmt = greenwood_williamson(d, s, asperity="dmt", **kw)
    assert dmt.pull_off == pytest.approx(eta * 2 * math.pi * w * R, rel=1e-9)


def test_fuller_tabor_parameter_and_pull_off_decay():
    R, E, w = 10.0, 1.0, 0.01
    sig = 0.3
    theta = fuller_tabor_parameter(sig, R, E, w)
    assert theta == pytest.approx(E * sig**1.5 / (w * math.sqrt(R)))
    dd = 0.75 * (math.pi**2 * w**2 * R / E**2) ** (1 / 3)
    assert (sig / dd) ** 1.5 == pytest.approx((4 / 3) ** 1.5 / math.pi * theta)
    # Fuller & Tabor: pull-off (per the smooth value 1.5 pi w R eta) falls with theta
    ratios = []
    for th in (0.3, 1.0, 3.0, 10.0):
        sd = (th * w * math.sqrt(R) / E) ** (2 / 3)
        s = SummitStatistics(density=0.01, radius=R, height_std=sd, mean_height=0.0,
                             bandwidth=10.0, m0=1.0, m2=1.0, m4=1.0)  # fmt: skip
        d = np.linspace(-3 * sd, 3 * sd + 2 * dd, 300)
        kw = {"work_of_adhesion": w, "asperity": "jkr", "branch": "unloading"}
        c = greenwood_williamson(d, s, **kw)
        ratios.append(c.pull_off / (0.01 * 1.5 * math.pi * w * R))
    assert all(a > b for a, b in zip(ratios, ratios[1:], strict=False))
    assert ratios[0] > 0.9 and ratios[-1] < 0.06


def test_gw_bad_input():
    with pytest.raises(ParameterError, match="asperity"):
        greenwood_williamson(1.0, SUMMITS, asperity="maugis")
    with pytest.raises(ParameterError, match="branch"):
        greenwood_williamson(1.0, SUMMITS, asperity="jkr", work_of_adhesion=1e-3, branch="up")
    with pytest.raises(ParameterError, match="work_of_adhesion"):
        greenwood_williamson(1.0, SUMMITS, work_of_adhesion=1e-3)  # hertz is non-adhesive
    with pytest.raises(ParameterError, match="work_of_adhesion"):
        greenwood_williamson(1.0, SUMMITS, asperity="dmt")
    with pytest.raises(ParameterError, match="separation"):
        greenwood_williamson(math.nan, SUMMITS)
    with pytest.raises(ParameterError, match="summit_radius"):
        fuller_tabor_parameter(1.0, 0.0, 1.0, 1.0)
