"""Adhesive reference theories: JKR, DMT, Maugis-Dugdale, Johnson's adhesive sinusoid.

Each result is checked against an independent route (superposition of Hertz and flat
punch, Griffith's condition from the stress field, quadrature of the Green's function)
and against its known limits.
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from roughcontact._validate import ParameterError
from roughcontact.theory import (
    JOHNSON_ALPHA_MAX,
    JOHNSON_FULL_CONTACT_ALPHA,
    JKRContact,
    MaugisDugdaleContact,
    dmt_contact_radius,
    dmt_load,
    dmt_pull_off_force,
    hertz_load,
    jkr,
    jkr_contact_radius,
    jkr_indentation,
    jkr_load,
    jkr_pull_off,
    jkr_pull_off_force,
    jkr_zero_load_contact_radius,
    johnson_parameter,
    johnson_sinusoid_mean_gap,
    johnson_sinusoid_mean_pressure,
    johnson_sinusoid_pressure,
    johnson_sinusoid_pull_off_pressure,
    johnson_sinusoid_spontaneous_full_contact,
    johnson_sinusoid_thresholds,
    maugis_dugdale,
    maugis_dugdale_nondimensional,
    maugis_dugdale_pull_off,
    maugis_dugdale_pull_off_force,
    maugis_parameter,
    tabor_parameter,
    westergaard_contact_half_width,
    westergaard_full_contact_pressure,
    westergaard_pressure,
)

R, E, W = 40.0, 2.0, 0.03  # sphere radius, contact modulus, work of adhesion


# ----------------------------------------------------------------------------- JKR
@pytest.mark.parametrize("a", [0.5, 2.0, 7.5])
def test_jkr_is_hertz_plus_flat_punch_with_griffith(a):
    # JKR = Hertz at radius a minus a flat punch of load N_P (Johnson 1985, 5.5): the
    # punch's edge stress-intensity factor K = N_P / (2 a sqrt(pi a)) must satisfy
    # K^2 / (2 E*) = w, and the punch displaces by N_P / (2 a E*)
    n_hertz = 4 * E * a**3 / (3 * R)
    n_punch = n_hertz - jkr_load(a, R, E, W)
    K = n_punch / (2 * a * math.sqrt(math.pi * a))
    assert K**2 / (2 * E) == pytest.approx(W, rel=1e-12)
    assert jkr_indentation(a, R, E, W) == pytest.approx(
        a * a / R - n_punch / (2 * a * E), rel=1e-12
    )
    c = jkr(contact_radius=a, radius=R, contact_modulus=E, work_of_adhesion=W)
    assert isinstance(c, JKRContact)
    assert c.stress_intensity_factor == pytest.approx(K, rel=1e-12)
    assert c.contact_area == pytest.approx(math.pi * a * a)


def test_jkr_zero_load_and_inverse():
    a0 = jkr_zero_load_contact_radius(R, E, W)
    assert a0 == pytest.approx((9 * math.pi * W * R**2 / (2 * E)) ** (1 / 3), rel=1e-14)
    assert jkr_load(a0, R, E, W) == pytest.approx(0.0, abs=1e-12)
    assert jkr_contact_radius(0.0, R, E, W) == pytest.approx(a0, rel=1e-13)
    n_c = -1.5 * math.pi * W * R
    for N in (n_c * 0.999, 0.5 * n_c, 0.0, 1.0, 50.0):
        a = jkr_contact_radius(N, R, E, W)
        assert jkr_load(a, R, E, W) == pytest.approx(N, rel=1e-9, abs=1e-11)
    with pytest.raises(ParameterError, match="load"):
        jkr_contact_radius(1.01 * n_c, R, E, W)


def test_jkr_pull_off_load_and_displacement_control():
    a = np.linspace(1e-4, 10.0, 400001)
    N = jkr_load(a, R, E, W)
    d = jkr_indentation(a, R, E, W)
    # load control: the minimum of N(a)
    lc = jkr_pull_off(R, E, W, control="load")
    assert N.min() == pytest.approx(-1.5 * math.pi * W * R, rel=1e-9)
    assert lc.load == pytest.approx(N.min(), rel=1e-9)
    assert lc.contact_radius == pytest.approx(a[N.argmin()], abs=2 * (a[1] - a[0]))
    assert jkr_pull_off_force(R, W) == pytest.approx(1.5 * math.pi * W * R)
    assert lc.indentation == pytest.approx(
        -0.25 * (3 * math.pi**2 * W**2 * R / E**2) ** (1 / 3), rel=1e-12
    )
    # displacement control: the minimum of delta(a), at a_c / 9^(1/3), N = -(5/6) pi w R
    dc = jkr_pull_off(R, E, W, control="displacement")
    assert dc.contact_radius == pytest.approx(a[d.argmin()], abs=2 * (a[1] - a[0]))
    assert dc.load == pytest.approx(-5 / 6 * math.pi * W * R, rel=1e-12)
    assert jkr_pull_off_force(R, W, control="displacement") == pytest.approx(
        5 / 9 * jkr_pull_off_force(R, W)
    )
    assert dc.contact_radius == pytest.approx(lc.contact_radius / 9 ** (1 / 3), rel=1e-12)
    assert dc.indentation == pytest.approx(
        -0.75 * (math.pi**2 * W**2 * R / E**2) ** (1 / 3), rel=1e-12
    )
    # the displacement-controlled path is stable (d delta/da > 0) at the load minimum, so
    # it passes through N = -(3/2) pi w R before jumping out: the largest tension
    # measured under displacement control is the load-control pull-off
    stable = a > dc.contact_radius
    assert N[stable].min() == pytest.approx(-1.5 * math.pi * W * R, rel=1e-9)
    with pytest.raises(ParameterError, match="control"):
        jkr_pull_off(R, E, W, control="force")


def test_jkr_tends_to_hertz_at_large_load():
    a = 1e3
    assert jkr_load(a, R, E, W) == pytest.approx(4 * E * a**3 / (3 * R), rel=1e-3)
    assert jkr_indentation(a, R, E, W) == pytest.approx(a * a / R, rel=1e-3)


def test_jkr_array_and_scalar_output():
    out = jkr_load(np.array([0.0, 1.0]), R, E, W)
    assert out.shape == (2,) and out[0] == 0.0
    assert isinstance(jkr_load(1.0, R, E, W), float)
    assert isinstance(jkr_indentation(1.0, R, E, W), float)


# ----------------------------------------------------------------------------- DMT
def test_dmt():
    a = np.array([0.0, 1.0, 3.0])
    np.testing.assert_allclose(
        dmt_load(a, R, E, W), hertz_load(a**2 / R, R, E) - 2 * math.pi * W * R, rtol=1e-13
    )
    assert dmt_pull_off_force(R, W) == pytest.approx(2 * math.pi * W * R)
    assert dmt_pull_off_force(R, W) / jkr_pull_off_force(R, W) == pytest.approx(4 / 3)
    for N in (-2 * math.pi * W * R, -1.0, 0.0, 3.0):
        assert dmt_load(dmt_contact_radius(N, R, E, W), R, E, W) == pytest.approx(N, abs=1e-12)
    assert dmt_contact_radius(-2 * math.pi * W * R, R, E, W) == 0.0
    with pytest.raises(ParameterError, match="load"):
        dmt_contact_radius(-2.01 * math.pi * W * R, R, E, W)


# ------------------------------------------------------------------- Maugis-Dugdale
def test_maugis_parameter_conventions():
    s0 = 0.1
    lam = maugis_parameter(radius=R, contact_modulus=E, work_of_adhesion=W, cohesive_stress=s0)
    K = 4 * E / 3  # Maugis' modulus
    assert lam == pytest.approx(2 * s0 * (R / (math.pi * W * K**2)) ** (1 / 3), rel=1e-14)
    assert lam == pytest.approx(s0 * (9 * R / (2 * math.pi * W * E**2)) ** (1 / 3), rel=1e-14)
    # Lennard-Jones 9-3 mapped on a Dugdale zone with the same peak stress 1.03 w/z0:
    # lambda = 1.16 mu (Johnson & Greenwood 1997)
    z0 = 0.7
    mu = tabor_parameter(radius=R, contact_modulus=E, work_of_adhesion=W, range_length=z0)
    assert mu == pytest.approx((R * W**2 / (E**2 * z0**3)) ** (1 / 3), rel=1e-14)
    lam_lj = maugis_parameter(
        radius=R, contact_modulus=E, work_of_adhesion=W, cohesive_stress=1.03 * W / z0
    )
    assert lam_lj / mu == pytest.approx(1.16, abs=0.005)


def test_maugis_dugdale_tends_to_jkr_and_dmt_curves():
    A = np.array([0.3, 0.8, 1.2, 2.0, 3.0])
    N, D, m = maugis_dugdale_nondimensional(A, 1e5)
    np.testing.assert_allclose(N, A**3 - np.sqrt(6 * A**3), atol=1e-4)  # JKR
    np.testing.assert_allclose(D, A**2 - np.sqrt(8 * A / 3), atol=1e-4)
    np.testing.assert_allclose(m, 1.0, atol=1e-4)
    N, D, m = maugis_dugdale_nondimensional(A, 1e-8)
    np.testing.assert_allclose(N, A**3 - 2, atol=1e-4)  # DMT
    np.testing.assert_allclose(D, A**2, atol=1e-3)
    assert np.all(m > 100)


@pytest.mark.parametrize("lam, limit", [(1e-3, 2.0), (1e-4, 2.0), (1e3, 1.5), (1e5, 1.5)])
def test_maugis_dugdale_pull_off_limits(lam, limit):
    p = maugis_dugdale_pull_off(lam)
    assert p.coefficient == pytest.approx(limit, abs=1e-3)
    if limit == 1.5:
        # JKR pull-off contact radius: A^3 = (9/8)(4/3) = 3/2
        assert p.contact_radius == pytest.approx(1.5 ** (1 / 3), abs=1e-3)


def test_maugis_dugdale_pull_off_monotone_and_values():
    lams = np.logspace(-3, 3, 31)
    c = np.array([maugis_dugdale_pull_off(x).coefficient for x in lams])
    assert np.all(np.diff(c) < 0)
    assert np.all((c > 1.5) & (c < 2.0))
    # reference values computed from the equations (cross-checked against the Adhesion
    # package's independent implementation, see test_maugis_dugdale_against_peer)
    for lam, ref in [(0.1, 1.95059), (0.5, 1.71825), (1.0, 1.60073), (2.0, 1.53460)]:
        assert maugis_dugdale_pull_off(lam).coefficient == pytest.approx(ref, abs=2e-5)


@pytest.mark.parametrize("lam", [0.05, 0.3, 1.0, 3.0, 30.0])
def test_maugis_dugdale_pull_off_is_a_minimum_on_the_displacement_stable_branch(lam):
    p = maugis_dugdale_pull_off(lam)
    A = p.contact_radius * np.array([0.98, 1.0, 1.02])
    N, D, _ = maugis_dugdale_nondimensional(A, lam)
    assert N[1] <= N[0] and N[1] <= N[2]
    assert N[1] == pytest.approx(-p.coefficient, rel=1e-12)
    assert D[2] > D[0]  # d delta / d a > 0: stable under displacement control too


@pytest.mark.peers
def test_maugis_dugdale_against_peer():
    md = pytest.importorskip("Adhesion.ReferenceSolutions.MaugisDugdale")
    A = np.array([0.2, 0.7, 1.1, 2.5])
    for lam in (0.1, 1.0, 4.0):
        N, D, _ = maugis_dugdale_nondimensional(A, lam)
        N_ref, D_ref = md._load_and_displacement(A, lam)
        np.testing.assert_allclose(N, N_ref, rtol=1e-9, atol=1e-12)
        np.testing.assert_allclose(D, D_ref, rtol=1e-9, atol=1e-12)


def test_maugis_dugdale_dimensional():
    s0 = 0.05
    a = 3.0
    c = maugis_dugdale(
        contact_radius=a, radius=R, contact_modulus=E, work_of_adhesion=W, cohesive_stress=s0
    )
    assert isinstance(c, MaugisDugdaleContact)
    K = 4 * E / 3
    lam = maugis_parameter(radius=R, contact_modulus=E, work_of_adhesion=W, cohesive_stress=s0)
    N, D, m = maugis_dugdale_nondimensional(a / (math.pi * W * R**2 / K) ** (1 / 3), lam)
    assert c.maugis_parameter == lam
    assert c.load == pytest.approx(N * math.pi * W * R, rel=1e-14)
    assert c.indentation == pytest.approx(D * (math.pi**2 * W**2 * R / K**2) ** (1 / 3), rel=1e-14)
    assert c.cohesive_radius == pytest.approx(m * a, rel=1e-14) and m > 1
    assert c.range_length == pytest.approx(W / s0)
    F = maugis_dugdale_pull_off_force(
        radius=R, contact_modulus=E, work_of_adhesion=W, cohesive_stress=s0
    )
    assert F == pytest.approx(maugis_dugdale_pull_off(lam).coefficient * math.pi * W * R)
    # a stiff, strong cohesive zone is JKR: same load at the same contact radius
    stiff = maugis_dugdale(
        contact_radius=a, radius=R, contact_modulus=E, work_of_adhesion=W, cohesive_stress=1e4
    )
    assert stiff.load == pytest.approx(jkr_load(a, R, E, W), rel=1e-3)
    assert stiff.indentation == pytest.approx(jkr_indentation(a, R, E, W), rel=1e-3)


# -------------------------------------------------------------- Johnson's sinusoid
D0, LAM = 0.5, 64.0  # amplitude, wavelength


def test_johnson_parameter():
    alpha = johnson_parameter(amplitude=D0, wavelength=LAM, contact_modulus=E, work_of_adhesion=W)
    assert alpha == pytest.approx(math.sqrt(2 * LAM * W / (math.pi**2 * E * D0**2)), rel=1e-14)
    p_star = westergaard_full_contact_pressure(D0, LAM, E)
    assert alpha**2 == pytest.approx(2 / math.pi * W / (p_star * D0), rel=1e-13)


def test_johnson_sinusoid_without_adhesion_is_westergaard():
    p_star = westergaard_full_contact_pressure(D0, LAM, E)
    for frac in (0.05, 0.3, 0.7, 0.95):
        pbar = frac * p_star
        a = westergaard_contact_half_width(pbar, D0, LAM, E)
        assert johnson_sinusoid_mean_pressure(a, D0, LAM, E, 0.0) == pytest.approx(pbar)
        x = np.linspace(-a, a, 7)[1:-1]
        np.testing.assert_allclose(
            johnson_sinusoid_pressure(x, a, D0, LAM, E, 0.0),
            westergaard_pressure(x, pbar, D0, LAM, E),
            rtol=1e-12,
        )
    t = johnson_sinusoid_thresholds(0.0)
    assert (t.pull_off, t.jump_in, t.jump_in_contact_fraction) == (0.0, 1.0, 1.0)
    # and continuously so: alpha -> 0 sends the jump to full contact to p*
    assert johnson_sinusoid_thresholds(1e-6).jump_in == pytest.approx(1.0, abs=1e-3)


@pytest.mark.parametrize("frac", [0.1, 0.4, 0.8])
def test_johnson_sinusoid_pressure_field(frac):
    a = frac * LAM / 2
    pbar = johnson_sinusoid_mean_pressure(a, D0, LAM, E, W)
    # the mean of p(x) is pbar (x -> theta substitution removes the edge singularity)
    s = math.sin(math.pi * a / LAM)

    def integrand(theta):
        x = LAM / math.pi * math.asin(s * math.sin(theta))
        dxdtheta = LAM / math.pi * s * math.cos(theta) / math.cos(math.pi * x / LAM)
        return johnson_sinusoid_pressure(x, a, D0, LAM, E, W) * dxdtheta

    total, _ = quad(integrand, -math.pi / 2 + 1e-12, math.pi / 2 - 1e-12, limit=200)
    assert total / LAM == pytest.approx(pbar, rel=1e-7, abs=1e-12)
    # Griffith at the edge: p ~ -K / sqrt(2 pi (a - x)) with K^2 / (2 E*) = w
    eps = a * 1e-9
    K = -johnson_sinusoid_pressure(a - eps, a, D0, LAM, E, W) * math.sqrt(2 * math.pi * eps)
    assert K**2 / (2 * E) == pytest.approx(W, rel=1e-4)
    assert johnson_sinusoid_pressure(a + 1e-9, a, D0, LAM, E, W) == 0.0
    # periodic
    assert johnson_sinusoid_pressure(0.3 * a + 2 * LAM, a, D0, LAM, E, W) == pytest.approx(
        johnson_sinusoid_pressure(0.3 * a, a, D0, LAM, E, W)
    )


@pytest.mark.parametrize("frac", [0.15, 0.5, 0.9])
@pytest.mark.parametrize("w", [0.0, W])
def test_johnson_sinusoid_mean_gap_from_greens_function(frac, w):
    # mean gap = Delta - w(crest); with zero mean deflection, the periodic line-load
    # Green's function gives w(0) = -(2/(pi E*)) int p(s) ln|2 sin(pi s/lambda)| ds
    a = frac * LAM / 2
    s = math.sin(math.pi * a / LAM)

    def integrand(theta):
        x = LAM / math.pi * math.asin(s * math.sin(theta))
        dxdtheta = LAM / math.pi * s * math.cos(theta) / math.cos(math.pi * x / LAM)
        p = johnson_sinusoid_pressure(x, a, D0, LAM, E, w)
        return p * math.log(abs(2 * s * math.sin(theta))) * dxdtheta

    integral, _ = quad(integrand, -math.pi / 2 + 1e-12, math.pi / 2 - 1e-12, points=[0], limit=400)
    w_crest = -2 / (math.pi * E) * integral
    assert johnson_sinusoid_mean_gap(a, D0, LAM, E, w) == pytest.approx(D0 - w_crest, rel=1e-6)


def test_johnson_sinusoid_full_contact_limits():
    # the gap closes as a -> lambda/2, and with adhesion the load needed -> -infinity
    a = LAM / 2 * (1 - 1e-9)
    assert johnson_sinusoid_mean_gap(a, D0, LAM, E, W) == pytest.approx(0.0, abs=1e-6 * D0)
    assert johnson_sinusoid_mean_pressure(
        a, D0, LAM, E, W
    ) < -100 * westergaard_full_contact_pressure(D0, LAM, E)


def test_johnson_sinusoid_small_alpha_is_jkr_cylinder():
    # for a << lambda each crest is a 2D JKR cylinder of radius lambda^2/(4 pi^2 Delta),
    # pull-off per length 3 (pi w^2 R E* / 16)^(1/3) (e.g. Chaudhury et al. 1996)
    w = 1e-7
    alpha = johnson_parameter(amplitude=D0, wavelength=LAM, contact_modulus=E, work_of_adhesion=w)
    assert alpha < 1e-2
    radius = LAM**2 / (4 * math.pi**2 * D0)
    p_c = johnson_sinusoid_pull_off_pressure(
        amplitude=D0, wavelength=LAM, contact_modulus=E, work_of_adhesion=w
    )
    assert p_c * LAM == pytest.approx(3 * (math.pi * w**2 * radius * E / 16) ** (1 / 3), rel=2e-4)
    assert johnson_sinusoid_thresholds(alpha).pull_off == pytest.approx(
        3 * (alpha / 4) ** (4 / 3), rel=2e-4
    )


def test_johnson_sinusoid_thresholds():
    alphas = np.linspace(0.01, 1.06, 40)
    ts = [johnson_sinusoid_thresholds(x) for x in alphas]
    pull = np.array([t.pull_off for t in ts])
    jump = np.array([t.jump_in for t in ts])
    assert np.all(np.diff(pull) > 0) and np.all(np.diff(jump) < 0)
    # the thresholds are the extrema of pbar/p* = sin^2 psi - alpha sqrt(tan psi)
    for t in ts[::7]:
        psi = np.linspace(1e-6, math.pi / 2 - 1e-6, 200001)
        f = np.sin(psi) ** 2 - t.alpha * np.sqrt(np.tan(psi))
        stable = (psi > t.pull_off_contact_fraction * math.pi / 2) & (
            psi < t.jump_in_contact_fraction * math.pi / 2
        )
        assert -f[psi < t.jump_in_contact_fraction * math.pi / 2].min() == pytest.approx(
            t.pull_off, rel=1e-8
        )
        assert f[stable].max() == pytest.approx(t.jump_in, abs=1e-8)
        assert np.all(np.diff(f[stable]) > 0)


def test_johnson_spontaneous_full_contact_threshold():
    assert JOHNSON_FULL_CONTACT_ALPHA == pytest.approx(0.5699, abs=1e-4)
    t = johnson_sinusoid_thresholds(JOHNSON_FULL_CONTACT_ALPHA)
    assert t.jump_in == pytest.approx(0.0, abs=1e-12)
    assert t.jump_in_contact_fraction == pytest.approx(2 / 3, rel=1e-9)  # psi = pi/3
    assert not johnson_sinusoid_thresholds(0.56).spontaneous_full_contact
    assert johnson_sinusoid_thresholds(0.58).spontaneous_full_contact
    assert johnson_sinusoid_spontaneous_full_contact(0.58)
    assert not johnson_sinusoid_spontaneous_full_contact(0.56)
    # no partial contact carries a compressive load above the threshold
    psi = np.linspace(1e-6, math.pi / 2 - 1e-6, 100001)
    assert np.all(np.sin(psi) ** 2 - 0.58 * np.sqrt(np.tan(psi)) < 0)
    assert np.any(np.sin(psi) ** 2 - 0.56 * np.sqrt(np.tan(psi)) > 0)


def test_johnson_alpha_max():
    assert JOHNSON_ALPHA_MAX == pytest.approx(1.0652, abs=1e-4)
    psi = np.linspace(0, math.pi / 2, 100001)
    assert JOHNSON_ALPHA_MAX == pytest.approx(
        (4 * np.sin(psi) ** 1.5 * np.cos(psi) ** 2.5).max(), rel=1e-8
    )
    t = johnson_sinusoid_thresholds(JOHNSON_ALPHA_MAX * (1 - 1e-9))
    assert t.pull_off_contact_fraction == pytest.approx(t.jump_in_contact_fraction, abs=1e-3)
    with pytest.raises(ParameterError, match="alpha"):
        johnson_sinusoid_thresholds(JOHNSON_ALPHA_MAX)


@pytest.mark.parametrize("alpha", [0.05, 0.3, 0.57, 1.0])
def test_johnson_pull_off_is_stable_under_displacement_control(alpha):
    # the mean gap decreases with the contact width at the load minimum: a
    # displacement-controlled retraction passes through it before jumping out
    t = johnson_sinusoid_thresholds(alpha)
    w = alpha**2 * math.pi**2 * E * D0**2 / (2 * LAM)
    a = t.pull_off_contact_fraction * LAM / 2
    da = 1e-4 * a
    g = johnson_sinusoid_mean_gap(np.array([a - da, a + da]), D0, LAM, E, w)
    assert g[1] < g[0]
    p_star = westergaard_full_contact_pressure(D0, LAM, E)
    assert johnson_sinusoid_mean_pressure(a, D0, LAM, E, w) == pytest.approx(
        -t.pull_off * p_star, rel=1e-9
    )


# ----------------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: jkr_load(1.0, -R, E, W), "radius"),
        (lambda: jkr_load(-1.0, R, E, W), "contact_radius"),
        (lambda: jkr_indentation(1.0, R, 0.0, W), "contact_modulus"),
        (
            lambda: jkr(contact_radius=1.0, radius=R, contact_modulus=E, work_of_adhesion=-W),
            "work_of_adhesion",
        ),
        (lambda: jkr_contact_radius(math.nan, R, E, W), "load"),
        (lambda: jkr_zero_load_contact_radius(R, E, math.inf), "work_of_adhesion"),
        (lambda: dmt_load(1.0, R, E, 0.0), "work_of_adhesion"),
        (lambda: dmt_pull_off_force(0.0, W), "radius"),
        (
            lambda: maugis_parameter(
                radius=R, contact_modulus=E, work_of_adhesion=W, cohesive_stress=-1.0
            ),
            "cohesive_stress",
        ),
        (lambda: maugis_dugdale_pull_off(0.0), "maugis_parameter"),
        (lambda: maugis_dugdale_nondimensional(-1.0, 1.0), "contact_radius"),
        (
            lambda: maugis_dugdale(
                contact_radius=0.0,
                radius=R,
                contact_modulus=E,
                work_of_adhesion=W,
                cohesive_stress=1.0,
            ),
            "contact_radius",
        ),
        (
            lambda: tabor_parameter(
                radius=R, contact_modulus=E, work_of_adhesion=W, range_length=0.0
            ),
            "range_length",
        ),
        (
            lambda: johnson_parameter(
                amplitude=0.0, wavelength=LAM, contact_modulus=E, work_of_adhesion=W
            ),
            "amplitude",
        ),
        (lambda: johnson_sinusoid_mean_pressure(LAM / 2, D0, LAM, E, W), "contact_half_width"),
        (lambda: johnson_sinusoid_mean_gap(1.0, D0, LAM, E, -W), "work_of_adhesion"),
        (lambda: johnson_sinusoid_pressure(0.0, 1.0, D0, -LAM, E, W), "wavelength"),
        (lambda: johnson_sinusoid_thresholds(-0.1), "alpha"),
        (lambda: johnson_sinusoid_spontaneous_full_contact(math.nan), "alpha"),
    ],
)
def test_bad_inputs(call, name):
    with pytest.raises(ParameterError, match=name):
        call()
