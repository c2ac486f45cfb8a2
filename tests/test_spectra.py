"""One definition of the spectrum (roughcontact.spectra) behind every path that reads it:
surfaces.statistics / power_spectrum (one period), topography's windowed spectra and
scale-dependent moments, and the stickiness criteria's inputs_from_heights."""

import math

import numpy as np
import pytest

import roughcontact as rc
from roughcontact import spectra
from roughcontact.stickiness.inputs import inputs_from_heights
from roughcontact.topography.spectrum import power_spectrum_2d, scale_dependent_rms


def _every_path(h, a):
    """(h_rms, h'_rms, h''_rms) of one period through each public path."""
    s = rc.statistics(h, pixel_size=a)
    slope, curv = scale_dependent_rms(h, a, [a / 100], periodic=True)
    inp = inputs_from_heights(h, contact_modulus=1.0, work_of_adhesion=1.0, pixel_size=a)
    q, C, n = rc.power_spectrum(h, pixel_size=a, return_counts=True)
    binned_rms = math.sqrt(np.sum(C * n * spectra.mode_cell(h.shape, (a, a))))
    m = spectra.moments(*spectra.mode_power(h - h.mean(), (a, a)))
    return {
        "statistics": (s.rms_height, s.rms_slope, s.rms_curvature),
        "topography": (s.rms_height, float(slope[0]), float(curv[0])),
        "criteria": (inp.rms_height, inp.rms_slope, inp.rms_curvature),
        "modes": (math.sqrt(m[0]), math.sqrt(m[2]), math.sqrt(m[4])),
        "power_spectrum": (binned_rms, s.rms_slope, s.rms_curvature),
    }


@pytest.mark.parametrize("shape, k, a", [((64, 64), 3, 1.0), ((48, 40), 5, 0.25)])
def test_a_single_sinusoid_has_its_analytic_rms_slope_and_curvature(shape, k, a):
    # h = A cos(q x), q = 2 pi k / L: <h^2> = A^2/2, <h'^2> = A^2 q^2/2, <h''^2> = A^2 q^4/2
    amp = 0.3
    x = np.arange(shape[0]) * a
    q = 2 * np.pi * k / (shape[0] * a)
    h = np.repeat((amp * np.cos(q * x))[:, None], shape[1], axis=1)
    want = (amp / math.sqrt(2), amp * q / math.sqrt(2), amp * q**2 / math.sqrt(2))
    for path, got in _every_path(h, a).items():
        np.testing.assert_allclose(got, want, rtol=1e-12, err_msg=path)


def test_every_path_agrees_on_a_self_affine_period():
    h = rc.self_affine(128, hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=1)
    paths = _every_path(h, 1.0)
    for path, got in paths.items():
        np.testing.assert_allclose(got, paths["statistics"], rtol=1e-12, err_msg=path)
    _, slope, curv = paths["statistics"]
    assert slope == pytest.approx(0.1, rel=1e-12)
    assert curv == pytest.approx(0.0785, abs=5e-5)


def test_parseval_and_the_psd_normalisation():
    rng = np.random.default_rng(7)
    h = rng.normal(size=(30, 36))
    a = 0.5
    q, p = spectra.mode_power(h, (a, a))
    assert np.sum(p) - p[0, 0] == pytest.approx(np.var(h), rel=1e-12)
    # C = p / cell integrates to h_rms^2 over the 2D modes, in the windowed spectrum too
    ps = power_spectrum_2d(h, a, periodic=True, points_per_decade=7)
    assert np.sum(ps.psd * ps.counts * ps.cell) == pytest.approx(np.var(h), rel=1e-12)
    assert ps.cell == pytest.approx((2 * np.pi) ** 2 / (30 * a * 36 * a), rel=1e-15)


def test_the_nyquist_convention_is_the_one_difference():
    # the Nyquist cosine's first derivative vanishes on the grid (periodic_moments) but
    # not in the plain mode sum; its Laplacian is the same either way
    n = 16
    h = np.repeat(np.cos(np.pi * np.arange(n))[:, None], n, axis=1)
    m0, m2, m4 = spectra.periodic_moments(h, 1.0)
    plain = spectra.moments(*spectra.mode_power(h, (1.0, 1.0)))
    assert m2 == 0.0 and plain[2] == pytest.approx(np.pi**2)
    assert m4 == pytest.approx(plain[4], rel=1e-12) and m0 == pytest.approx(plain[0])


def test_bins_cover_every_mode_once():
    q = np.array([0.1, 0.2, 0.5, 1.0, 1.0])
    for edges in (spectra.linear_edges(1.0, 4), spectra.log_edges(0.1, 1.0, 3)):
        qb, vb, counts = spectra.bin_modes(q, 2 * q, edges)
        assert counts.sum() == q.size
        np.testing.assert_allclose(vb, 2 * qb)
