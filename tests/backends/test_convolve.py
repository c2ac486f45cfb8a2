"""The solvers' periodic convolution against numpy.fft (an FFT no one here wrote)."""

from __future__ import annotations

import numpy as np
import pytest

import roughcontact as rc
from roughcontact import _backend
from roughcontact.solvers.fourier import compliance_operator, stiffness_operator


def _reference(x, kernel):
    x = x.astype(np.float64)
    return np.fft.irfft2(np.fft.rfft2(x) * kernel, s=x.shape)


def _case(shape, dtype, seed=0):
    rng = np.random.default_rng(seed)
    x = rng.standard_normal(shape).astype(dtype)
    kernel = rng.uniform(0.5, 2.0, (shape[0], shape[1] // 2 + 1)).astype(dtype)
    return x, kernel


@pytest.fixture(params=["pocketfft", "public"])
def path(request, monkeypatch):
    """Both NumPy paths: scipy's pocketfft binding and the public scipy.fft fallback."""
    if request.param == "public":
        monkeypatch.setattr(_backend, "_pocketfft", lambda: None)
    elif _backend._pocketfft() is None:
        pytest.skip("this scipy has no usable pocketfft binding")
    return request.param


@pytest.mark.parametrize("shape", [(64, 64), (48, 40), (33, 17), (2, 128)])
@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_convolve_is_the_fourier_multiplication(path, shape, dtype):
    x, kernel = _case(shape, dtype)
    want = _reference(x, kernel)
    tol = 50 * np.finfo(dtype).eps * np.abs(want).max()
    kept = x.copy()
    got = _backend.convolve(x, kernel)
    assert got.dtype == dtype and got.shape == shape
    np.testing.assert_allclose(got, want, atol=tol)
    np.testing.assert_array_equal(x, kept)  # the input is left alone
    # with caller-owned buffers: the result lands in `out`, the same values
    spectrum = np.empty(kernel.shape, dtype=np.result_type(dtype, np.complex64))
    out = np.full(shape, np.nan, dtype=dtype)
    again = _backend.convolve(x, kernel, spectrum=spectrum, out=out)
    assert again is out
    np.testing.assert_array_equal(again, got)


def test_pocketfft_binding_is_scipys_public_transform_bit_for_bit():
    # on power-of-two grids both paths run the same passes
    if _backend._pocketfft() is None:
        pytest.skip("this scipy has no usable pocketfft binding")
    import scipy.fft

    for dtype in (np.float32, np.float64):
        x, kernel = _case((64, 32), dtype, seed=3)
        want = _backend.irfft2(scipy.fft.rfft2(x) * kernel, x.shape)
        np.testing.assert_array_equal(_backend.convolve(x, kernel), want)


@pytest.mark.parametrize("which", [compliance_operator, stiffness_operator])
def test_operator_reuses_its_spectrum_without_aliasing_results(path, which):
    # one spectrum array per dtype serves every call: earlier results must stay intact,
    # for float64 and float32 calls mixed, and `out` must receive the result
    sub = rc.Substrate((24, 20), contact_modulus=2.0, pixel_size=0.5)
    apply = which(sub)
    k, c = sub.multipliers(np.zeros(1))
    kernel = c if which is compliance_operator else k
    xs = [_case((24, 20), np.float64, seed=s)[0] for s in range(3)]
    results = [apply(x.reshape(-1)) for x in xs]
    single = apply(xs[0].astype(np.float32).reshape(-1))
    out = np.empty(24 * 20)
    into = apply(xs[1].reshape(-1), out=out)
    for x, r in zip(xs, results, strict=True):
        np.testing.assert_allclose(r.reshape(x.shape), _reference(x, kernel), atol=1e-12)
    assert single.dtype == np.float32
    np.testing.assert_allclose(single, results[0], atol=1e-5 * np.abs(results[0]).max())
    assert np.shares_memory(into, out)
    np.testing.assert_array_equal(into, results[1])
