import numpy as np
import pytest

from roughcontact._validate import ParameterError
from roughcontact.surfaces.generate import self_affine
from roughcontact.surfaces.statistics import power_spectrum, statistics


def _modes(h, pixel_size=1.0):
    """|q| and Persson C(q) for every mode of the full FFT (q=0 included)."""
    nx, ny = h.shape
    H = np.fft.fft2(h)
    C = pixel_size**4 * np.abs(H) ** 2 / ((2 * np.pi) ** 2 * nx * ny * pixel_size**2)
    qx = 2 * np.pi * np.fft.fftfreq(nx, d=pixel_size)
    qy = 2 * np.pi * np.fft.fftfreq(ny, d=pixel_size)
    return np.hypot(qx[:, None], qy[None, :]), C


def test_real_float64_mean_zero_shape():
    h = self_affine(64, hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=0)
    assert h.shape == (64, 64)
    assert h.dtype == np.float64
    assert np.isrealobj(h)
    assert abs(h.mean()) < 1e-14 * np.abs(h).max()
    assert np.all(np.isfinite(h))


def test_periodic_no_seam_at_the_boundary():
    # A periodic surface has no seam: the height jump across the cell boundary is
    # statistically the same as between interior neighbours (a non-periodic field,
    # e.g. a crop of a larger one, would show a much larger jump).
    h = self_affine((64, 96), hurst=0.8, rms_height=1.0, short_cutoff=4, seed=3)
    for axis in (0, 1):
        d = np.diff(h, axis=axis)
        interior = np.sqrt(np.mean(d**2))
        seam = np.take(h, 0, axis=axis) - np.take(h, -1, axis=axis)
        assert np.sqrt(np.mean(seam**2)) < 2.0 * interior
    # and no power in the Nyquist modes
    H = np.fft.fft2(h)
    assert np.all(np.abs(H[32, :]) < 1e-10)
    assert np.all(np.abs(H[:, 48]) < 1e-10)


def test_cropped_field_would_fail_the_seam_check():
    # guard for the test above: a crop of a larger surface does show a seam
    big = self_affine(256, hurst=0.8, rms_height=1.0, short_cutoff=4, long_cutoff=128, seed=3)
    h = big[:64, :96]
    d = np.diff(h, axis=0)
    seam = h[0] - h[-1]
    assert np.sqrt(np.mean(seam**2)) > 2.0 * np.sqrt(np.mean(d**2))


def test_reproducible_and_seed_dependent():
    kw = dict(hurst=0.7, rms_slope=0.2, short_cutoff=4)
    a = self_affine(64, seed=42, **kw)
    b = self_affine(64, seed=42, **kw)
    c = self_affine(64, seed=43, **kw)
    np.testing.assert_array_equal(a, b)
    assert np.abs(a - c).max() > 0.1 * np.abs(a).max()


def test_generator_object_seed():
    a = self_affine(32, hurst=0.7, rms_slope=0.2, short_cutoff=4, seed=np.random.default_rng(5))
    b = self_affine(32, hurst=0.7, rms_slope=0.2, short_cutoff=4, seed=5)
    np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("target", [0.1, 0.37])
@pytest.mark.parametrize("pixel_size", [1.0, 0.25])
def test_rms_slope_exact(target, pixel_size):
    h = self_affine(
        (64, 80),
        hurst=0.8,
        rms_slope=target,
        short_cutoff=4 * pixel_size,
        pixel_size=pixel_size,
        seed=1,
    )
    s = statistics(h, pixel_size=pixel_size)
    assert abs(s.rms_slope - target) < 1e-10 * target
    # independently: grid mean of the spectral gradient (no Nyquist power present)
    nx, ny = h.shape
    H = np.fft.fft2(h)
    qx = 2 * np.pi * np.fft.fftfreq(nx, d=pixel_size)[:, None]
    qy = 2 * np.pi * np.fft.fftfreq(ny, d=pixel_size)[None, :]
    gx = np.fft.ifft2(1j * qx * H).real
    gy = np.fft.ifft2(1j * qy * H).real
    np.testing.assert_allclose(np.sqrt(np.mean(gx**2 + gy**2)), target, rtol=1e-10)


@pytest.mark.parametrize("short_cutoff", [2.0, 3.0, 8.0])
def test_rms_height_exact(short_cutoff):
    h = self_affine(64, hurst=0.3, rms_height=2.5, short_cutoff=short_cutoff, seed=7)
    assert abs(statistics(h).rms_height - 2.5) < 1e-10 * 2.5
    assert abs(np.std(h) - 2.5) < 1e-10 * 2.5


@pytest.mark.parametrize("hurst", [0.3, 0.8])
def test_psd_slope_between_cutoffs(hurst):
    n, lam_s, lam_L = 256, 4.0, 128.0
    q_s, q_L = 2 * np.pi / lam_s, 2 * np.pi / lam_L
    Cs = []
    for seed in range(4):
        h = self_affine(
            n, hurst=hurst, rms_height=1.0, short_cutoff=lam_s, long_cutoff=lam_L, seed=seed
        )
        q, C = power_spectrum(h, nbins=128)
        Cs.append(C)
    C = np.mean(Cs, axis=0)
    sel = (q > 1.5 * q_L) & (q < 0.8 * q_s)
    slope = np.polyfit(np.log(q[sel]), np.log(C[sel]), 1)[0]
    assert abs(slope - (-2 * (1 + hurst))) < 0.15, slope


def test_zero_power_above_short_cutoff():
    lam_s = 6.0
    h = self_affine(128, hurst=0.5, rms_slope=0.1, short_cutoff=lam_s, seed=2)
    q, C = _modes(h)
    above = q > 2 * np.pi / lam_s * (1 + 1e-9)
    assert above.sum() > 1000
    assert C[above].max() < 1e-24 * C.max()
    below = (q < 2 * np.pi / lam_s) & (q > 0)
    assert np.count_nonzero(C[below] > 1e-20 * C.max()) > 0.99 * below.sum()


def test_rolloff_flat_below_long_cutoff():
    n, lam_s, lam_L, hurst = 128, 4.0, 32.0, 0.8
    q_L = 2 * np.pi / lam_L
    inner, ring = [], []
    for seed in range(30):
        h = self_affine(
            n, hurst=hurst, rms_height=1.0, short_cutoff=lam_s, long_cutoff=lam_L, seed=seed
        )
        q, C = _modes(h)
        # compensate the power law; the model is then flat at its q_L value everywhere below
        # 2*q_L: constant inside q < q_L (roll-off), (q/q_L)^(2+2H) * C constant above.
        inner.append(C[(q > 0) & (q < q_L)].mean())
        r = (q >= q_L) & (q < 2 * q_L)
        ring.append((C[r] * (q[r] / q_L) ** (2 + 2 * hurst)).mean())
    ratio = np.mean(np.array(inner) / np.array(ring))
    assert 0.75 < ratio < 1.33, ratio


def test_no_rolloff_means_zero_power_below_long_cutoff():
    lam_L = 32.0
    h = self_affine(
        128, hurst=0.8, rms_height=1.0, short_cutoff=4, long_cutoff=lam_L, rolloff=False, seed=1
    )
    q, C = _modes(h)
    low = q < 2 * np.pi / lam_L * (1 - 1e-9)
    assert low.sum() > 10
    assert C[low].max() < 1e-24 * C.max()


def test_default_long_cutoff_is_half_the_smaller_side():
    kw = dict(hurst=0.6, rms_height=1.0, short_cutoff=4, seed=11)
    a = self_affine((64, 128), **kw)
    b = self_affine((64, 128), long_cutoff=32.0, **kw)
    np.testing.assert_array_equal(a, b)


def test_rectangular_grid():
    h = self_affine((48, 96), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=0, pixel_size=0.5)
    assert h.shape == (48, 96)
    assert abs(statistics(h, pixel_size=0.5).rms_slope - 0.1) < 1e-12
    q, C = _modes(h, pixel_size=0.5)
    # both orientations carry power (not accidentally transposed/truncated)
    H = np.abs(np.fft.fft2(h))
    assert H[1:5, 0].max() > 0 and H[0, 1:5].max() > 0


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(hurst=0.0), "hurst"),
        (dict(hurst=1.2), "hurst"),
        (dict(hurst=-0.5), "hurst"),
        (dict(hurst="x"), "hurst"),
        (dict(short_cutoff=1.5), "short_cutoff"),
        (dict(short_cutoff=-4), "short_cutoff"),
        (dict(long_cutoff=3.0), "long_cutoff"),
        (dict(long_cutoff=200.0), "long_cutoff"),
        (dict(rms_slope=-0.1), "rms_slope"),
        (dict(rms_slope=0.0), "rms_slope"),
        (dict(rms_slope=None, rms_height=-1.0), "rms_height"),
        (dict(rms_height=1.0), "rms_height"),
        (dict(rms_slope=None), "rms_slope"),
        (dict(pixel_size=0.0), "pixel_size"),
        (dict(shape=(1, 64)), "shape"),
        (dict(shape="big"), "shape"),
    ],
)
def test_bad_inputs(kwargs, name):
    base = dict(shape=64, hurst=0.8, rms_slope=0.1, short_cutoff=4.0, seed=0)
    base.update(kwargs)
    shape = base.pop("shape")
    with pytest.raises(ParameterError, match=name):
        self_affine(shape, **base)


def test_hurst_one_allowed():
    h = self_affine(32, hurst=1.0, rms_slope=0.1, short_cutoff=4, seed=0)
    assert abs(statistics(h).rms_slope - 0.1) < 1e-12


def test_empty_band_raises():
    # no wavevector strictly between the cutoffs and no roll-off
    with pytest.raises(ParameterError, match="cutoffs"):
        self_affine(16, hurst=0.5, rms_slope=0.1, short_cutoff=6.5, long_cutoff=7.0, rolloff=False)
