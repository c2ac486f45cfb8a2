"""PSD, scale-dependent slope and curvature, Hurst fit and extrapolation of measured data.

Oracles: analytic values of sinusoids (``h'_rms = A k/sqrt(2)``, ``h''_rms = A k^2/sqrt(2)``),
Parseval's theorem, the analytic angular averages of an isotropic surface (``2`` and
``8/3``), the known H, h'_rms and short cutoff of Fourier-filtered self-affine surfaces
(whose expected scale dependence is an integral of the filter), numerical quadrature of
the extrapolated tail, and SurfaceTopography on a real AFM file.
"""

import math
from pathlib import Path

import numpy as np
import pytest

import roughcontact as rc
from roughcontact import ParameterError
from roughcontact.topography.statistics import (
    ISOTROPIC_CURVATURE_FACTOR,
    ISOTROPIC_SLOPE_FACTOR,
    fit_hurst,
    power_spectrum_1d,
    power_spectrum_2d,
    scale_dependent_rms,
    scale_statistics,
)

DATA = Path(__file__).resolve().parents[1] / "data" / "topographies"
NM = 1e-9


def _cosine2d(n, lam_px, A, a, angle_mode=(1, 0)):
    """``A cos(q.x)`` on a periodic n x n grid, wavevector (mx, my) * 2 pi/(n a)."""
    mx, my = angle_mode
    i = np.arange(n)
    phase = 2 * np.pi * (mx * i[:, None] + my * i[None, :]) / n
    return A * np.cos(phase), 2 * np.pi * math.hypot(mx, my) / (n * a)


@pytest.mark.parametrize("mode", [(8, 0), (0, 16), (6, 8)])
def test_sinusoid_map_slope_curvature_and_scale(mode):
    n, a, A = 64, 2 * NM, 3 * NM
    h, k = _cosine2d(n, None, A, a, mode)
    lam = 2 * np.pi / k
    slopes, curvs = scale_dependent_rms(h + 5 * NM, a, [0.5 * lam, lam, 1.01 * lam], periodic=True)
    np.testing.assert_allclose(slopes[:2], A * k / math.sqrt(2), rtol=1e-12)
    np.testing.assert_allclose(curvs[:2], A * k**2 / math.sqrt(2), rtol=1e-12)
    # low-passed above its wavelength: flat (to round-off)
    assert slopes[2] < 1e-12 * slopes[0] and curvs[2] < 1e-12 * curvs[0]
    psd = power_spectrum_2d(h, a, periodic=True, points_per_decade=20)
    # all power in the bin of |q| = k, and Parseval: sum C dq^2 = <h^2> = A^2/2
    power = psd.psd * psd.counts * psd.cell
    np.testing.assert_allclose(power.max(), A**2 / 2, rtol=1e-12)
    np.testing.assert_allclose(np.sum(power), A**2 / 2, rtol=1e-12)


def test_sinusoid_profile_and_isotropy_factor():
    n, a, A, m = 128, 1 * NM, 2 * NM, 8
    x = np.arange(n)
    h = A * np.sin(2 * np.pi * m * x / n)
    k = 2 * np.pi * m / (n * a)
    s, c = scale_dependent_rms(h, a, [2 * a], periodic=True)
    np.testing.assert_allclose(s, A * k / math.sqrt(2), rtol=1e-12)
    np.testing.assert_allclose(c, A * k**2 / math.sqrt(2), rtol=1e-12)
    st = scale_statistics(h, a, periodic=True, fit_range=(4 * a, 32 * a))
    assert st.isotropy_assumed and st.dim == 1
    np.testing.assert_allclose(st.rms_slope, math.sqrt(2) * A * k / math.sqrt(2), rtol=1e-12)
    np.testing.assert_allclose(st.rms_curvature, math.sqrt(8 / 3) * A * k**2 / math.sqrt(2))
    np.testing.assert_allclose(st.d_rep, 4 * st.rms_slope / st.rms_curvature)
    psd = power_spectrum_1d(h, a, periodic=True)
    np.testing.assert_allclose(np.sum(psd.psd * psd.counts * psd.cell), A**2 / 2, rtol=1e-12)


def test_isotropy_factors_from_profiles_of_a_random_isotropic_map():
    """``<|grad h|^2> = 2 <h_x^2>`` and ``<(lap h)^2> = 8/3 <h_xx^2>`` (angular averages)."""
    a = 1 * NM
    h = rc.self_affine(256, hurst=0.6, rms_slope=0.1, short_cutoff=4 * a, pixel_size=a, seed=5)
    full = rc.statistics(h, pixel_size=a)
    s2 = c2 = 0.0
    for j in range(h.shape[1]):
        s, c = scale_dependent_rms(h[:, j], a, [2 * a], periodic=True)
        s2, c2 = s2 + s[0] ** 2, c2 + c[0] ** 2
    s2, c2 = s2 / h.shape[1], c2 / h.shape[1]
    assert ISOTROPIC_SLOPE_FACTOR * s2 == pytest.approx(full.rms_slope**2, rel=0.05)
    assert ISOTROPIC_CURVATURE_FACTOR * c2 == pytest.approx(full.rms_curvature**2, rel=0.05)


def test_parseval_with_the_hann_window():
    """Non-periodic data: the PSD (q = 0 left out) sums to the variance of w (h - <h>),
    w SciPy's Hann window normalised to a mean square of 1."""
    from scipy.signal import get_window

    rng = np.random.default_rng(0)
    h = np.cumsum(rng.standard_normal(300)) * NM
    w = get_window("hann", h.size)
    w /= np.sqrt(np.mean(w**2))
    psd = power_spectrum_1d(h, 2 * NM)
    assert psd.window == "hann"
    np.testing.assert_allclose(
        np.sum(psd.psd * psd.counts * psd.cell), np.var(w * (h - h.mean())), rtol=1e-12
    )
    m = rng.standard_normal((40, 50)) * NM
    psd2 = power_spectrum_2d(m, (1 * NM, 2 * NM))
    w2 = _radial_hann(m.shape, (1 * NM, 2 * NM))
    assert psd2.window == "hann (radial)"
    assert psd2.efficiency == pytest.approx(1 / np.mean(w2**4), rel=1e-12)  # <w^2>^2/<w^4>
    np.testing.assert_allclose(
        np.sum(psd2.psd * psd2.counts * psd2.cell), np.var(w2 * (m - m.mean())), rtol=1e-12
    )
    # the rms height reported is that of the data, not of the windowed data
    st = scale_statistics(m, (1 * NM, 2 * NM), fit_range=(8 * NM, 20 * NM))
    assert st.rms_height == pytest.approx(np.std(m), rel=1e-12)


def _radial_hann(shape, sizes):
    """SurfaceTopography's radial Hann window (r_max = min(Lx, Ly)/2), mean square 1."""
    nx, ny = shape
    x = sizes[0] * (np.arange(nx) - nx // 2)
    y = sizes[1] * (np.arange(ny) - ny // 2)
    r = np.hypot(x[:, None], y[None, :])
    r_max = min(nx * sizes[0], ny * sizes[1]) / 2
    w = np.where(r < r_max, 0.5 + 0.5 * np.cos(np.pi * r / r_max), 0.0)
    return w / np.sqrt(np.mean(w**2))


@pytest.mark.parametrize("periodic", [True, False])
@pytest.mark.parametrize("hurst", [0.3, 0.8])
def test_self_affine_known_slope_and_scale_dependence(hurst, periodic):
    """h'_rms at the short cutoff is the generator's target; above it the expected
    fraction is the filter's integral ``int q^(k+1) phi^2 dq`` (rolled off below q_L),
    checked on the mean of 6 realisations (the windowed estimate scatters more)."""
    n, a, lam_s, lam_L = 256, 1 * NM, 4 * NM, 128 * NM
    lams = np.array([lam_s, 2 * lam_s, 8 * lam_s])
    ratios = []
    for seed in range(6):
        h = rc.self_affine(n, hurst=hurst, rms_slope=0.1, short_cutoff=lam_s,
                           long_cutoff=lam_L, pixel_size=a, seed=seed)  # fmt: skip
        s, c = scale_dependent_rms(h, a, lams, periodic=periodic)
        tol = 1e-12 if periodic else 0.1  # the window costs a few per cent
        assert s[0] == pytest.approx(0.1, rel=tol)
        assert c[0] == pytest.approx(rc.statistics(h, pixel_size=a).rms_curvature, rel=tol)
        ratios.append(np.concatenate([(s[1:] / s[0]) ** 2, (c[1:] / c[0]) ** 2]))
    q_s, q_L = 2 * np.pi / lam_s, 2 * np.pi / lam_L

    def moment(q_hi, k):  # int_0^q_hi q^(k+1) phi(q)^2 dq, phi^2 = q^(-2-2H), q_L^(-2-2H)
        below = q_L ** (-2 - 2 * hurst) * q_L ** (k + 2) / (k + 2)
        p = k - 1 - 2 * hurst
        return below + (q_hi ** (p + 1) - q_L ** (p + 1)) / (p + 1)

    q = 2 * np.pi / lams[1:]
    expected = [moment(qi, 2) / moment(q_s, 2) for qi in q]
    expected += [moment(qi, 4) / moment(q_s, 4) for qi in q]
    np.testing.assert_allclose(np.mean(ratios, axis=0), expected, rtol=0.12 if periodic else 0.25)


@pytest.mark.parametrize("periodic", [True, False])
@pytest.mark.parametrize("hurst", [0.3, 0.5, 0.8])
def test_hurst_exponent_recovered(hurst, periodic):
    """Stated tolerance: 0.1 (about 2 sigma of one 256^2 windowed realisation)."""
    a = 1 * NM
    h = rc.self_affine(256, hurst=hurst, rms_slope=0.1, short_cutoff=2 * a, long_cutoff=128 * a,
                       pixel_size=a, seed=7)  # fmt: skip
    st = scale_statistics(h, a, periodic=periodic)
    assert st.fit.dim == 2 and st.fit.bins >= 10
    assert st.fit.hurst == pytest.approx(hurst, abs=0.1)
    assert abs(st.fit.hurst - hurst) < 3 * st.fit.hurst_stderr + 0.02
    assert st.fit.scale_range == pytest.approx((4 * a, 64 * a))
    profile = scale_statistics(h[:, 0], a, periodic=periodic)  # C1D ~ q^(-1-2H)
    assert profile.fit.dim == 1
    assert profile.fit.hurst == pytest.approx(hurst, abs=3 * profile.fit.hurst_stderr + 0.05)


def test_hurst_stderr_matches_the_scatter_between_realisations():
    """The stated standard error is the spread of H over independent surfaces."""
    a = 1 * NM
    for periodic in (True, False):
        fits = [
            scale_statistics(
                rc.self_affine(128, hurst=0.5, rms_slope=0.1, short_cutoff=2 * a,
                               long_cutoff=64 * a, pixel_size=a, seed=seed),
                a, periodic=periodic,
            ).fit
            for seed in range(16)
        ]  # fmt: skip
        spread = np.std([f.hurst for f in fits], ddof=1)
        stated = np.mean([f.hurst_stderr for f in fits])
        assert 1 / 1.7 < stated / spread < 1.7, (periodic, stated, spread)
        assert abs(np.mean([f.hurst for f in fits]) - 0.5) < 2 * spread


def test_extrapolation_brackets_the_true_statistics():
    """Measured only down to 16 pixels, extrapolated to the true short cutoff (2 pixels):
    the truth lies within the H band, and with the true H within a few per cent."""
    a = 1 * NM
    for seed, hurst in ((1, 0.4), (2, 0.8)):
        h = rc.self_affine(256, hurst=hurst, rms_slope=0.1, short_cutoff=4 * a,
                           long_cutoff=128 * a, pixel_size=a, seed=seed)  # fmt: skip
        truth = rc.statistics(h, pixel_size=a)
        st = scale_statistics(h, a, periodic=True, reliability_cutoff=16 * a)
        assert st.measured_scale == 16 * a and st.rms_slope < 0.1
        lo, hi = st.fit.interval(2)
        band = [st.extrapolated_at(4 * a, hurst=H) for H in (lo, hi)]
        slopes, curvs = sorted(b[0] for b in band), sorted(b[1] for b in band)
        assert slopes[0] < truth.rms_slope < slopes[1]
        assert curvs[0] < truth.rms_curvature < curvs[1]
        s, c = st.extrapolated_at(4 * a, hurst=hurst)
        assert s == pytest.approx(truth.rms_slope, rel=0.1)
        assert c == pytest.approx(truth.rms_curvature, rel=0.1)
        # at and above the measured scale nothing is extrapolated
        assert st.extrapolated_at(16 * a) == pytest.approx(st.measured_at(16 * a))


def test_tail_is_the_integral_of_the_fitted_power_law():
    from scipy.integrate import quad

    a = 1 * NM
    h = rc.self_affine(128, hurst=0.7, rms_slope=0.1, short_cutoff=2 * a, pixel_size=a, seed=3)
    for heights in (h, h[:, 0]):
        fit = scale_statistics(heights, a, periodic=True).fit
        g = 2 * np.pi if fit.dim == 2 else 2.0
        q1, q2 = 2 * np.pi / (4 * a), 2 * np.pi / (0.5 * a)
        for k in (2, 4):
            for H in (fit.hurst, 0.5, 1.0):  # H = 1: the logarithmic case of h'rms
                # d^2q = 2 pi q dq (2D); both signs of q (1D)
                integrand = _moment_integrand(fit, g, k, H)
                ref = quad(integrand, q1, q2)[0]
                assert fit.tail(k, q1, q2, H) == pytest.approx(ref, rel=1e-8)


def _moment_integrand(fit, g, k, H):
    return lambda q: g * q ** (k + fit.dim - 1) * fit.psd(q, H)


def test_extrapolated_slope_grows_as_lambda_to_the_h_minus_1():
    """Deep below the measured scale ``h'_rms ~ lambda_s^(H-1)``, ``h''_rms ~ lambda_s^(H-2)``."""
    a = 1 * NM
    h = rc.self_affine(128, hurst=0.6, rms_slope=0.1, short_cutoff=2 * a, pixel_size=a, seed=4)
    st = scale_statistics(h, a, periodic=True)
    H = st.fit.hurst
    lam = np.array([1e-15, 1e-16])
    s, c = st.extrapolated_at(lam)
    assert math.log(s[1] / s[0]) / math.log(10) == pytest.approx(1 - H, rel=1e-3)
    assert math.log(c[1] / c[0]) / math.log(10) == pytest.approx(2 - H, rel=1e-3)


def test_bad_input_is_one_line():
    a = 1 * NM
    with pytest.raises(ParameterError, match="1D profile or a 2D map"):
        scale_dependent_rms(np.zeros((8, 8, 8)), a, [a])
    with pytest.raises(ParameterError, match="at least 8 points"):
        power_spectrum_2d(np.zeros((4, 40)), a)
    with pytest.raises(ParameterError, match="finite"):
        power_spectrum_1d(np.array([np.nan] + [0.0] * 20), a)
    with pytest.raises(ParameterError, match="pixel_size"):
        power_spectrum_1d(np.zeros(20), -1.0)
    with pytest.raises(ParameterError, match="one size per axis"):
        power_spectrum_2d(np.zeros((20, 20)), (a, a, a))
    with pytest.raises(ParameterError, match="scales"):
        scale_dependent_rms(np.zeros(20), a, [0.0])
    h = rc.self_affine(64, hurst=0.5, rms_slope=0.1, short_cutoff=2 * a, pixel_size=a, seed=1)
    with pytest.raises(ParameterError, match="PSD bins"):
        fit_hurst(power_spectrum_2d(h, a), (10 * a, 11 * a))
    with pytest.raises(ParameterError, match="reliability_cutoff"):
        scale_statistics(h, a, reliability_cutoff=40 * a)
    with pytest.raises(ParameterError, match="flat"):
        scale_statistics(np.ones((32, 32)), a)
    with pytest.raises(ParameterError, match="too small for the default Hurst fit"):
        scale_statistics(h[:12, :12], a)
    for err in (ParameterError,):
        with pytest.raises(err) as info:
            scale_statistics(h, a, fit_range=(3 * a,))
        assert "\n" not in str(info.value)


# --------------------------------------------------------------------------- peer check


def _nid():
    path = DATA / "nid-1.nid"
    from roughcontact.topography import detrend, load_topography

    return detrend(load_topography(path), mode="plane")


def test_psd_and_scale_dependent_slope_against_surface_topography():
    """Same window (radial / 1D Hann), conventions differing by (2 pi)^2 and 2 pi."""
    import SurfaceTopography as ST

    topo = _nid()
    heights = np.array(topo.heights)
    peer = ST.Topography(heights, topo.physical_size, periodic=False)
    (a, _), (L, _) = topo.pixel_size, topo.physical_size
    # 2D: the same bins (edges between the grid's |q|), radial averages of the mode PSD
    edges = np.geomspace(2.1 * 2 * np.pi / L, 0.97 * np.pi / a, 9)
    _, C_peer = peer.power_spectrum_from_area(collocation=edges, reliable=False)
    fine = power_spectrum_2d(heights, topo.pixel_size, points_per_decade=4000)
    mine = []
    for lo, hi in zip(edges[:-1], edges[1:], strict=True):
        sel = (fine.q >= lo) & (fine.q < hi)
        mine.append(np.sum(fine.psd[sel] * fine.counts[sel]) / np.sum(fine.counts[sel]))
    np.testing.assert_allclose((2 * np.pi) ** 2 * np.array(mine), C_peer, rtol=1e-3)
    # 1D: mode by mode (without the lowest, which our per-line mean removal changes)
    _, C1_peer = peer.power_spectrum_from_profile(resampling_method=None, reliable=False)
    p1 = power_spectrum_1d(heights, topo.pixel_size, points_per_decade=20000)
    n = min(p1.q.size, C1_peer.size - 1)
    np.testing.assert_allclose(2 * np.pi * p1.psd[1:n], C1_peer[2 : n + 1], rtol=1e-3)

    # scale-dependent slope and curvature: the PSD's moments below 2 pi/lambda
    def below(q_c, k):  # one argument: SurfaceTopography then passes |q|
        return lambda q: q**k * (q <= q_c)

    for m in (2, 8, 32):
        q_c = 2 * np.pi / (m * a) * (1 + 1e-9)
        s_peer = math.sqrt(peer.integrate_psd(below(q_c, 2)))
        c_peer = math.sqrt(peer.integrate_psd(below(q_c, 4)))
        s, c = scale_dependent_rms(heights, topo.pixel_size, [m * a])
        assert s[0] == pytest.approx(s_peer, rel=1e-3)
        assert c[0] == pytest.approx(c_peer, rel=1e-3)
