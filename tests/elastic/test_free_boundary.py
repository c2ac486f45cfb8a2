"""The free-boundary (non-periodic) half-space against closed forms and a peer library.

Conventions: deflection w positive into the substrate, pressure p positive when
compressive, E* = E/(1 - nu^2); Boussinesq's point load F then deflects the surface by
w = F (1 - nu^2)/(pi E r) = F/(pi E* r) (Johnson, Contact Mechanics (1985), eq. 3.19b).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import roughcontact as rc
from roughcontact.elastic import love_rectangle


def _love_log_form(x, y, a, b, p=1.0, es=1.0):
    """Love (1929) / Johnson (1985) eq. 3.25 in its logarithmic form: the deflection at
    (x, y) under uniform p on |x'| <= a, |y'| <= b. Written out independently of the
    package's asinh form (near the rectangle its cancellation is harmless)."""

    def r(u, v):
        return math.hypot(u, v)

    xp, xm, yp, ym = x + a, x - a, y + b, y - b
    terms = (
        xp * math.log((yp + r(yp, xp)) / (ym + r(ym, xp)))
        + yp * math.log((xp + r(yp, xp)) / (xm + r(yp, xm)))
        + xm * math.log((ym + r(ym, xm)) / (yp + r(yp, xm)))
        + ym * math.log((xm + r(ym, xm)) / (xp + r(ym, xp)))
    )
    return p * terms / (math.pi * es)


def test_construction_and_refusals():
    sub = rc.Substrate((12, 10), periodic=False)
    assert sub.work_shape == (24, 20) and not sub.rigid_mean and not sub.periodic
    assert sub.stiffness.shape == sub.compliance.shape == (24, 11)
    assert "periodic=False" in repr(sub) and "periodic" not in repr(rc.Substrate((12, 10)))
    assert isinstance(sub, rc.ElasticOperator)
    assert sub.coarsened() == rc.Substrate((6, 5), pixel_size=2.0, periodic=False)
    with pytest.raises(rc.ParameterError, match="periodic=False needs thickness=None"):
        rc.Substrate((12, 10), thickness=5.0, periodic=False)
    with pytest.raises(rc.ParameterError, match="periodic must be True or False"):
        rc.Substrate((12, 10), periodic="no")


def test_boussinesq_point_load_without_periodic_images():
    # one loaded pixel: far from it the deflection is F/(pi E* r); the pixel's extent adds
    # (a0/r)^2 / 24 (the mean of 1/|x - x'| over a square pixel, Taylor to second order)
    es, a0, n = 2.5, 0.3, 96
    sub = rc.Substrate((n, n), contact_modulus=es, pixel_size=a0, periodic=False)
    p = np.zeros((n, n))
    p[5, 7] = 3.0
    w = sub.deflection(p)
    force = 3.0 * a0**2
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    r = np.hypot(i - 5, j - 7) * a0
    far = r >= 12 * a0
    boussinesq = force / (math.pi * es * r[far]) * (1 + a0**2 / (24 * r[far] ** 2))
    np.testing.assert_allclose(w[far], boussinesq, rtol=2e-6)
    # the periodic substrate sees the images (and has a zero mean deflection): far away
    # it is off by more than the whole Boussinesq deflection there
    periodic = rc.Substrate((n, n), contact_modulus=es, pixel_size=a0).deflection(p)
    corner = (n - 1, n - 1)
    assert abs(periodic[corner] - w[corner]) > w[corner]
    assert abs(periodic.mean()) < 1e-12 * w.max() < w.mean()


def test_loaded_pixel_centre_is_loves_square():
    # centre of a uniformly loaded square of side c: 4 c asinh(1)/(pi E*) ~ 1.122 c/E*
    sub = rc.Substrate((8, 8), contact_modulus=2.0, pixel_size=0.5, periodic=False)
    p = np.zeros((8, 8))
    p[3, 4] = 1.0
    want = 4 * 0.5 * math.asinh(1.0) / (math.pi * 2.0)
    assert sub.deflection(p)[3, 4] == pytest.approx(want, rel=1e-14)
    assert want * 2.0 / 0.5 == pytest.approx(1.1222, abs=1e-4)


def test_uniform_rectangle_is_loves_closed_form():
    # a rectangle of 9 x 5 loaded pixels: the sum of the pixels' responses is Love's
    # rectangle exactly (the integral is additive), at its centre, the middle of its
    # edges, its corners' sites and outside it
    nx, ny, es, a0 = 40, 30, 1.5, 2.0
    sub = rc.Substrate((nx, ny), contact_modulus=es, pixel_size=a0, periodic=False)
    p = np.zeros((nx, ny))
    p[10:19, 12:17] = 0.7
    w = sub.deflection(p)
    a, b = 4.5 * a0, 2.5 * a0  # half-widths; the centre is site (14, 14)
    for i, j in [(14, 14), (10, 14), (14, 12), (18, 16), (25, 3), (0, 29), (39, 0)]:
        x, y = (i - 14) * a0, (j - 14) * a0
        assert w[i, j] == pytest.approx(_love_log_form(x, y, a, b, 0.7, es), rel=1e-11)
    # Johnson's centre value 4p/(pi E*) [a asinh(b/a) + b asinh(a/b)]
    centre = 4 * 0.7 / (math.pi * es) * (a * math.asinh(b / a) + b * math.asinh(a / b))
    assert w[14, 14] == pytest.approx(centre, rel=1e-13)


def test_far_field_quadrature_matches_the_closed_form():
    # beyond FAR_FIELD pixels the response is integrated by Gauss-Legendre: there it
    # must equal the closed form (whose float64 cancellation is still small at 8-40 a0)
    from roughcontact.elastic.free_boundary import FAR_FIELD, pixel_response

    s = np.arange(0, 40)
    got = pixel_response(s, s)
    closed = love_rectangle(s[:, None], s[None, :], 0.5, 0.5)
    far = np.hypot(s[:, None], s[None, :]) >= FAR_FIELD
    np.testing.assert_allclose(got[far], closed[far], rtol=1e-12)
    np.testing.assert_array_equal(got[~far], closed[~far])


def test_uniform_disc_centre_and_edge():
    # uniform p on a disc of radius a (Johnson 1985, eqs. 3.32-3.33): w(0) = 2 p a/E*,
    # w(a) = 4 p a/(pi E*); a pixelated disc of radius 30 a0, to its discretisation
    n, radius = 96, 30.0
    sub = rc.Substrate((n, n), periodic=False)
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    r = np.hypot(i - 48, j - 48)
    p = np.where(r <= radius, 1.0, 0.0)
    # the disc whose area is that of the pixels loaded
    a = math.sqrt(p.sum() / math.pi)
    w = sub.deflection(p)
    assert w[48, 48] == pytest.approx(2 * a, rel=2e-3)
    edge = np.abs(r - a) < 0.5
    assert w[edge].mean() == pytest.approx(4 * a / math.pi, rel=1e-2)
    periodic = rc.Substrate((n, n)).deflection(p)
    assert abs(periodic[48, 48] - 2 * a) > 0.2 * 2 * a  # its images (and zero mean) show


def test_linear_convolution_by_direct_summation():
    # Hockney's padding makes the FFT convolution the linear one: against the direct sum
    # of Love's pixel response over every pair of sites (a 12 x 10 patch, 14 400 pairs)
    nx, ny, a0 = 12, 10, 0.5
    sub = rc.Substrate((nx, ny), pixel_size=a0, periodic=False)
    p = np.random.default_rng(1).normal(size=(nx, ny))
    w = sub.deflection(p)
    want = np.zeros((nx, ny))
    for i in range(nx):
        for j in range(ny):
            for k in range(nx):
                for m in range(ny):
                    x, y = (i - k) * a0, (j - m) * a0
                    want[i, j] += p[k, m] * _love_log_form(x, y, a0 / 2, a0 / 2)
    np.testing.assert_allclose(w, want, atol=1e-12 * np.abs(want).max())


def test_energy_is_the_work_and_its_gradient_the_pressure():
    # E_el = 1/2 a0^2 sum p w with p the pressure of w (zero off the patch), and
    # dE/dw_i = a0^2 p_i (central differences: E is quadratic, exact up to rounding)
    a0, es = 0.7, 1.3
    sub = rc.Substrate((20, 16), contact_modulus=es, pixel_size=a0, periodic=False)
    p = np.random.default_rng(2).normal(size=(20, 16))
    w = sub.deflection(p)
    np.testing.assert_allclose(sub.pressure(w), p, atol=1e-10 * np.abs(p).max())
    energy = sub.energy(w)
    assert energy == pytest.approx(0.5 * a0**2 * float((p * w).sum()), rel=1e-10)
    assert energy > 0
    eps = 1e-3
    for site in [(0, 0), (7, 3), (19, 15), (10, 8)]:
        e = np.zeros_like(w)
        e[site] = eps
        slope = (sub.energy(w + e) - sub.energy(w - e)) / (2 * eps)
        assert slope == pytest.approx(a0**2 * p[site], rel=1e-6, abs=1e-9)


def test_operators_keep_precision_and_backend_shapes():
    sub = rc.Substrate((10, 14), periodic=False)
    p = np.random.default_rng(3).normal(size=(10, 14))
    w32 = sub.deflection(p.astype(np.float32))
    assert w32.dtype == np.float32 and w32.shape == (10, 14) and w32.flags.c_contiguous
    np.testing.assert_allclose(w32, sub.deflection(p), rtol=1e-5, atol=1e-5)
    k, c = sub.multipliers(np.zeros(1, np.float32))
    assert k.dtype == c.dtype == np.float32 and k.shape == (20, 15)
    np.testing.assert_allclose(sub.multipliers(np.zeros(1)).stiffness * sub.compliance, 1.0)
    embedded = sub.embed(p)
    assert embedded.shape == (20, 28) and not embedded[10:].any() and not embedded[:, 14:].any()
    np.testing.assert_array_equal(sub.crop(embedded), p)
    with pytest.raises(rc.ParameterError, match="deflection must be finite"):
        sub.pressure(np.full((10, 14), np.nan))


@pytest.mark.peers
def test_matches_contact_mechanics_free_half_space():
    # the peer's FreeFFTElasticHalfSpace (Hockney padding of Love's pixel response) on
    # the same pressure: it takes forces p a0^2 on the padded grid and returns the
    # displacement positive out of the substrate, i.e. -w
    cm = pytest.importorskip("ContactMechanics")
    nx, ny, a0, es = 24, 18, 0.5, 2.0
    peer = cm.FreeFFTElasticHalfSpace((nx, ny), es, physical_sizes=(nx * a0, ny * a0))
    p = np.random.default_rng(4).uniform(0.0, 1.0, (nx, ny))
    forces = np.zeros(peer.nb_domain_grid_pts)
    forces[:nx, :ny] = p * a0**2
    displacement = peer.evaluate_disp(forces)[:nx, :ny]
    sub = rc.Substrate((nx, ny), contact_modulus=es, pixel_size=a0, periodic=False)
    w = sub.deflection(p)
    np.testing.assert_allclose(w, -displacement, rtol=1e-11, atol=1e-13 * w.max())
