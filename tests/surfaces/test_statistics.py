import math

import numpy as np
import pytest

from roughcontact._validate import ParameterError
from roughcontact.surfaces.generate import self_affine
from roughcontact.surfaces.geometry import egg_box, sinusoid
from roughcontact.surfaces.statistics import (
    SurfaceStatistics,
    power_spectrum,
    rms_curvature,
    rms_height,
    rms_slope,
    statistics,
)


def _cosine(shape, lam, A, a0, axis=0):
    nx, ny = shape
    x = np.arange(nx)[:, None] * a0
    y = np.arange(ny)[None, :] * a0
    s = x if axis == 0 else y
    return np.broadcast_to(A * np.cos(2 * np.pi * s / lam), shape).copy()


@pytest.mark.parametrize("axis", [0, 1])
@pytest.mark.parametrize("a0", [1.0, 0.5])
@pytest.mark.parametrize("lam_pixels", [4, 8, 16])
def test_cosine_spectral_exact(axis, a0, lam_pixels):
    shape, A = (64, 48), 0.7
    lam = lam_pixels * a0
    h = _cosine(shape, lam, A, a0, axis) + 3.0  # a mean offset must not matter
    s = statistics(h, pixel_size=a0)
    k = 2 * np.pi / lam
    assert s.method == "spectral"
    np.testing.assert_allclose(s.rms_height, A / math.sqrt(2), rtol=1e-12)
    np.testing.assert_allclose(s.rms_slope, k * A / math.sqrt(2), rtol=1e-12)
    np.testing.assert_allclose(s.rms_curvature, k**2 * A / math.sqrt(2), rtol=1e-12)
    np.testing.assert_allclose(s.predicted_d_rep, 4 / k, rtol=1e-12)
    np.testing.assert_allclose(s.predicted_delta_h, A / math.sqrt(2), rtol=1e-12)


@pytest.mark.parametrize("lam_pixels", [4, 8, 16, 32])
def test_cosine_finite_difference_exact_discrete(lam_pixels):
    a0, A, shape = 0.5, 1.3, (64, 32)
    lam = lam_pixels * a0
    k = 2 * np.pi / lam
    h = _cosine(shape, lam, A, a0)
    s = statistics(h, pixel_size=a0, method="finite-difference")
    # central difference of cos(kx) is -sin(k a0)/a0 sin(kx); the 5-point Laplacian
    # multiplies cos(kx) by -(4/a0^2) sin^2(k a0/2)
    np.testing.assert_allclose(s.rms_height, A / math.sqrt(2), rtol=1e-12)
    np.testing.assert_allclose(s.rms_slope, A * math.sin(k * a0) / a0 / math.sqrt(2), rtol=1e-12)
    np.testing.assert_allclose(
        s.rms_curvature, 4 * A * math.sin(k * a0 / 2) ** 2 / a0**2 / math.sqrt(2), rtol=1e-12
    )
    # and it approaches the continuum value as O((k a0)^2)
    sp = statistics(h, pixel_size=a0)
    assert abs(s.rms_slope / sp.rms_slope - 1) <= (k * a0) ** 2 / 6 * 1.0001
    assert abs(s.rms_curvature / sp.rms_curvature - 1) <= (k * a0) ** 2 / 12 * 1.0001


def test_egg_box_analytic():
    lam, A, a0 = 8.0, 0.4, 1.0
    h = egg_box((32, 64), lam, A, pixel_size=a0)
    s = statistics(h, pixel_size=a0)
    k = 2 * np.pi / lam
    # <cos^2 cos^2> = 1/4; |grad h|^2 averages to 2 * k^2 A^2 / 4; lap h = -2 k^2 h
    np.testing.assert_allclose(s.rms_height, A / 2, rtol=1e-12)
    np.testing.assert_allclose(s.rms_slope, k * A / math.sqrt(2), rtol=1e-12)
    np.testing.assert_allclose(s.rms_curvature, 2 * k**2 * A / 2, rtol=1e-12)
    fd = statistics(h, pixel_size=a0, method="finite-difference")
    np.testing.assert_allclose(fd.rms_slope, math.sin(k * a0) * A / math.sqrt(2), rtol=1e-12)
    np.testing.assert_allclose(fd.rms_curvature, 8 * math.sin(k * a0 / 2) ** 2 * A / 2, rtol=1e-12)


def test_spectral_matches_derivative_fields_on_random_surface():
    rng = np.random.default_rng(0)
    h = rng.standard_normal((30, 41))  # odd and even sizes, full spectrum
    nx, ny = h.shape
    H = np.fft.fft2(h)
    qx = 2 * np.pi * np.fft.fftfreq(nx)[:, None]
    qy = 2 * np.pi * np.fft.fftfreq(ny)[None, :]
    qx1 = np.where(np.arange(nx)[:, None] == nx // 2, 0.0, qx)  # Nyquist row (nx even)
    gx = np.fft.ifft2(1j * qx1 * H)
    gy = np.fft.ifft2(1j * qy * H)
    lap = np.fft.ifft2(-(qx**2 + qy**2) * H)
    assert np.abs(gx.imag).max() < 1e-10 and np.abs(lap.imag).max() < 1e-10
    s = statistics(h)
    np.testing.assert_allclose(s.rms_slope, np.sqrt(np.mean(gx.real**2 + gy.real**2)), rtol=1e-12)
    np.testing.assert_allclose(s.rms_curvature, np.sqrt(np.mean(lap.real**2)), rtol=1e-12)
    np.testing.assert_allclose(s.rms_height, np.std(h), rtol=1e-12)


def test_nyquist_first_derivative_is_zero():
    h = _cosine((16, 16), 2.0, 1.0, 1.0)  # (-1)^i, the Nyquist mode
    s = statistics(h)
    assert s.rms_slope == pytest.approx(0.0, abs=1e-12)
    np.testing.assert_allclose(s.rms_curvature, np.pi**2, rtol=1e-12)
    np.testing.assert_allclose(rms_height(h), 1.0, rtol=1e-12)


def test_convenience_functions_and_to_dict():
    h = self_affine(32, hurst=0.5, rms_slope=0.2, short_cutoff=4, seed=1)
    s = statistics(h)
    assert rms_height(h) == pytest.approx(s.rms_height, rel=1e-14)
    assert rms_slope(h) == pytest.approx(s.rms_slope, rel=1e-14)
    assert rms_curvature(h) == pytest.approx(s.rms_curvature, rel=1e-14)
    fd = statistics(h, method="finite-difference")
    assert rms_slope(h, method="finite-difference") == pytest.approx(fd.rms_slope, rel=1e-14)
    d = s.to_dict()
    assert set(d) == {
        "rms_height",
        "rms_slope",
        "rms_curvature",
        "predicted_d_rep",
        "predicted_delta_h",
        "method",
        "periodic",
    }
    assert d["periodic"] is True and d["method"] == "spectral"
    assert all(type(v) is float for k, v in d.items() if k not in ("method", "periodic"))
    assert d["predicted_d_rep"] == pytest.approx(4 * s.rms_slope / s.rms_curvature)
    assert d["predicted_delta_h"] == pytest.approx(s.rms_slope**2 / s.rms_curvature)
    with pytest.raises(AttributeError):
        s.rms_slope = 1.0  # frozen
    assert isinstance(s, SurfaceStatistics)


def test_flat_surface_gives_nan_predictions():
    s = statistics(np.zeros((8, 8)))
    assert s.rms_height == 0 and s.rms_slope == 0 and s.rms_curvature == 0
    assert math.isnan(s.predicted_d_rep) and math.isnan(s.predicted_delta_h)


def test_pixel_size_scaling():
    h = self_affine(32, hurst=0.5, rms_height=1.0, short_cutoff=4, seed=2)
    s1 = statistics(h, pixel_size=1.0)
    s2 = statistics(h, pixel_size=2.0)
    np.testing.assert_allclose(s2.rms_slope, s1.rms_slope / 2, rtol=1e-12)
    np.testing.assert_allclose(s2.rms_curvature, s1.rms_curvature / 4, rtol=1e-12)


@pytest.mark.parametrize("shape", [(64, 64), (48, 80), (33, 50)])
@pytest.mark.parametrize("a0", [1.0, 0.3])
def test_power_spectrum_parseval(shape, a0):
    rng = np.random.default_rng(1)
    h = rng.standard_normal(shape) + 5.0
    q, C, n = power_spectrum(h, pixel_size=a0, return_counts=True)
    Lx, Ly = shape[0] * a0, shape[1] * a0
    total = np.sum(C * n) * (2 * np.pi / Lx) * (2 * np.pi / Ly)
    np.testing.assert_allclose(total, np.var(h), rtol=1e-12)
    assert n.sum() == shape[0] * shape[1] - 1
    assert np.all(np.diff(q) > 0) and q[0] > 0


def test_power_spectrum_of_cosine():
    # all the variance A^2/2 sits in the modes (+-k, 0); the annulus |q| = k also holds
    # (0, +-k), which carry no power, so the bin average is A^2/2 / (4 dq^2)
    L, lam, A = 64, 8.0, 2.0
    h = _cosine((L, L), lam, A, 1.0)
    q, C, n = power_spectrum(h, nbins=4096, return_counts=True)
    dq = 2 * np.pi / L
    i = np.argmax(C)
    np.testing.assert_allclose(q[i], 2 * np.pi / lam, rtol=1e-12)
    assert n[i] == 4
    np.testing.assert_allclose(C[i], A**2 / 2 / (4 * dq**2), rtol=1e-12)
    assert np.sum(np.delete(C, i)) < 1e-20


def test_power_spectrum_nbins_default_and_bad():
    q, C = power_spectrum(np.random.default_rng(0).standard_normal((32, 64)))
    assert len(q) == len(C) <= 16
    for bad in (0, -3, 2.5):
        with pytest.raises(ParameterError, match="nbins"):
            power_spectrum(np.ones((8, 8)), nbins=bad)


@pytest.mark.parametrize(
    "heights",
    [np.ones(16), np.ones((4, 4, 4)), np.full((4, 4), np.nan), np.full((4, 4), np.inf)],
)
def test_bad_heights(heights):
    with pytest.raises(ParameterError, match="heights"):
        statistics(heights)
    with pytest.raises(ParameterError, match="heights"):
        power_spectrum(heights)


def test_bad_method_and_pixel_size():
    with pytest.raises(ParameterError, match="method"):
        statistics(np.ones((4, 4)), method="wavelet")
    with pytest.raises(ParameterError, match="pixel_size"):
        statistics(np.ones((4, 4)), pixel_size=-1)


# --- a window of a larger surface (periodic=False): no derivative across its edges


def test_window_plane_and_paraboloid_exact():
    # central differences are exact for polynomials of degree 2: a tilted plane has
    # h'rms = |grad h| and no curvature; c x² + e y² has lap h = 2(c + e) everywhere.
    # Taken as one period, the plane's wrap-around jump would be a huge spurious slope.
    x = np.arange(40)[:, None] * 0.5
    y = np.arange(30)[None, :] * 0.5
    plane = 0.3 * x - 0.4 * y
    w = statistics(plane, pixel_size=0.5, periodic=False)
    assert w.rms_slope == pytest.approx(0.5, rel=1e-12) and w.rms_curvature < 1e-9
    assert (w.method, w.periodic) == ("finite-difference", False)
    assert statistics(plane, pixel_size=0.5).rms_slope > 5 * w.rms_slope
    bowl = 0.02 * x**2 - 0.05 * y**2
    assert rms_curvature(bowl, pixel_size=0.5, periodic=False) == pytest.approx(0.06, rel=1e-9)
    # the slope of the bowl: the mean of (2cx)² over the rows with two neighbours
    gx2 = np.mean((0.04 * x[1:-1]) ** 2) + np.mean((0.1 * y[:, 1:-1]) ** 2)
    assert rms_slope(bowl, pixel_size=0.5, periodic=False) == pytest.approx(math.sqrt(gx2))


def test_window_agrees_with_period_on_a_periodic_surface():
    # a periodic surface seen as a window: the same statistics as the periodic
    # differences, up to the edge rows' share of the average
    h = self_affine(128, hurst=0.8, rms_slope=0.1, short_cutoff=8, seed=3)
    w = statistics(h, periodic=False)
    p = statistics(h, method="finite-difference")
    assert w.rms_height == p.rms_height
    assert w.rms_slope == pytest.approx(p.rms_slope, rel=0.03)
    assert w.rms_curvature == pytest.approx(p.rms_curvature, rel=0.03)


def test_window_against_surface_topography():
    # peer: SurfaceTopography's non-periodic Topography (same 5-point Laplacian inside
    # the window; forward rather than central differences for the gradient)
    st = pytest.importorskip("SurfaceTopography")
    h = self_affine(128, hurst=0.8, rms_slope=0.1, short_cutoff=8, seed=3)
    h = h + 0.05 * np.arange(128)[:, None]  # a tilt: no longer periodic
    peer = st.Topography(h, (64.0, 64.0), periodic=False)
    w = statistics(h, pixel_size=0.5, periodic=False)
    assert w.rms_curvature == pytest.approx(peer.rms_laplacian(), rel=1e-10)
    assert w.rms_slope == pytest.approx(peer.rms_gradient(), rel=0.03)


def test_window_refuses_spectral_and_tiny_maps():
    with pytest.raises(ParameterError, match="method='spectral' needs a periodic map"):
        statistics(np.ones((8, 8)), method="spectral", periodic=False)
    with pytest.raises(ParameterError, match="at least 3 x 3"):
        rms_slope(np.ones((2, 8)), periodic=False)


def test_sinusoid_geometry_statistics_consistent():
    h = sinusoid((32, 16), 8.0, 1.0, axis=1)
    np.testing.assert_allclose(statistics(h).rms_slope, 2 * np.pi / 8 / math.sqrt(2), rtol=1e-12)


def test_short_cutoff_estimate_recovers_the_generator_cutoff():
    from roughcontact.surfaces.statistics import short_cutoff_estimate

    h = self_affine((128, 96), hurst=0.7, rms_slope=0.1, short_cutoff=8, seed=4)
    assert short_cutoff_estimate(h) == pytest.approx(8.0, rel=0.02)
    white = np.random.default_rng(0).normal(size=(64, 64))
    assert short_cutoff_estimate(white) == pytest.approx(2 / np.sqrt(2))  # the (π, π) mode
