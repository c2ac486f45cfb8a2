"""float32 option and device selection (CPU side; the GPU tests are in test_cupy.py and
test_routing.py).

Oracle: the float64 solution of the same problem. The single-precision floor
(residuals stall at 3e-7 to 6e-7, so tol >= 1e-6) was measured on 256² problems; here the
float32 states must agree with float64 to the accuracy that tolerance implies.
"""

import os

import numpy as np
import pytest

import roughcontact as rc
from roughcontact._accelerator import to_device

N = 64
H = rc.self_affine((N, N), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=11)
SUB = rc.Substrate((N, N))
# offsets a few tenths of the rms height into contact (the LJ wall's equilibrium gap is a0)
D_LJ = float(H.max()) + 1.0 - 0.3 * float(H.std())
D_HARD = float(H.max()) - 0.3 * float(H.std())

CASES = [
    ("hardwall", rc.HardWall(), {"load": 5e-3}),
    ("lj93smooth", rc.SmoothLJ93.from_adhesion_length(0.005), {"offset": D_LJ}),
    ("exponential", rc.Exponential(work_of_adhesion=0.005, range=0.5), {"offset": D_HARD}),
    ("exponential-load", rc.Exponential(work_of_adhesion=0.005, range=0.5), {"load": 1e-3}),
]


@pytest.mark.parametrize(("name", "law", "control"), CASES, ids=[c[0] for c in CASES])
def test_float32_agrees_with_float64(name, law, control):
    ref = rc.solve(H, SUB, law, tol=1e-10, **control)
    got = rc.solve(H, SUB, law, dtype="float32", **control)
    assert got.converged, got.message
    assert got.tol == 1e-6  # the float32 default
    assert got.pressure.dtype == np.float32
    err = np.linalg.norm(got.pressure - ref.pressure) / np.linalg.norm(ref.pressure)
    assert err < (2e-4 if "load" in control else 2e-5)  # load control: |ΔN| <= tol E*
    assert got.load == pytest.approx(ref.load, rel=1e-4, abs=got.tol)  # tol is in E*
    assert abs(got.repulsive_area - ref.repulsive_area) <= 2.0 / N**2


def test_float32_default_tolerance_grows_beyond_1024_squared():
    """Measured on an H200: at 4096² the float32 residual floor is 1.0e-6 to 1.3e-6, so the
    1e-6 of smaller grids stalled; the default there is 4e-6 (float64 keeps 1e-8)."""
    from roughcontact.solvers.inputs import DEFAULT_TOL, default_tolerance

    assert default_tolerance("float32", 256 * 256) == DEFAULT_TOL["float32"] == 1e-6
    assert default_tolerance("float32", 1024 * 1024) == 1e-6
    assert default_tolerance("float32", 2048 * 2048) == pytest.approx(2e-6)
    assert default_tolerance("float32", 4096 * 4096) == pytest.approx(4e-6)
    assert default_tolerance("float64", 4096 * 4096) == 1e-8
    got = rc.solve(H, SUB, rc.HardWall(), load=1e-3, dtype="float32", tol=1e-6)
    assert got.tol == 1e-6  # an explicit tolerance is kept (>= 1e-6)


def test_float32_rejects_a_tolerance_below_its_floor():
    with pytest.raises(rc.ParameterError, match=r"tol must be >= 1e-06 with dtype='float32'"):
        rc.solve(H, SUB, rc.HardWall(), load=1e-3, dtype="float32", tol=1e-8)
    with pytest.raises(rc.ParameterError, match="dtype must be one of float64, float32"):
        rc.solve(H, SUB, rc.HardWall(), load=1e-3, dtype="float16")


def test_float32_stops_at_its_rounding_floor_and_says_so():
    # full contact at a mean pressure ~ E*: float32 cannot resolve 1e-6 E* of imbalance
    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    deep = float(H.max()) - float(H.std())  # N/A0 = 2.6 E*
    assert rc.solve(H, SUB, law, offset=deep).converged  # float64 can
    res = rc.solve(H, SUB, law, offset=deep, dtype="float32", max_iter=5000)
    assert not res.converged and res.iterations < 1000
    assert "float32 rounding floor" in res.message


def test_float32_path_records_its_precision():
    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    offsets = D_LJ + np.array([0.4, 0.2, 0.0])
    ref = rc.approach_retract(H, SUB, law, offsets=offsets, tol=1e-8)
    got = rc.approach_retract(H, SUB, law, offsets=offsets, dtype="float32")
    assert got.attrs["dtype"] == "float32" and ref.attrs["dtype"] == "float64"
    assert got.attrs["device"] == "cpu"
    np.testing.assert_allclose(got["load"], ref["load"], rtol=1e-4, atol=1e-9)


def test_float64_is_the_default_even_for_float32_heights():
    res = rc.solve(H.astype(np.float32), SUB, rc.HardWall(), load=5e-3)
    assert res.pressure.dtype == np.float64 and res.tol == 1e-8


def test_to_device():
    xp = pytest.importorskip("array_api_strict")
    a = xp.asarray(H)
    back = to_device(a, "cpu")
    assert isinstance(back, np.ndarray) and np.array_equal(back, H)
    assert to_device(H) is H  # nothing to do: no copy
    assert to_device(H, dtype="float32").dtype == np.float32
    assert to_device([[1, 2], [3, 4]]).dtype == np.float64
    assert type(to_device(a)) is type(a)  # None keeps the namespace
    with pytest.raises(rc.ParameterError, match="device must be 'cpu', 'cuda' or 'cuda:N'"):
        to_device(H, "gpu")
    with pytest.raises(rc.ParameterError, match="device must be"):
        to_device(H, 0)


def test_cuda_without_a_gpu_is_a_clear_error():
    try:
        import jax

        if jax.devices("gpu"):
            pytest.skip("JAX has a GPU here")
    except Exception:  # noqa: BLE001 - no JAX, or no CUDA backend: the case tested
        pass
    with pytest.raises(rc.ParameterError, match="device='cuda'"):
        rc.solve(H, SUB, rc.HardWall(), load=1e-3, device="cuda")


def test_fft_threads_only_on_large_grids(monkeypatch):
    # starting threads costs more than they save on small grids (see THREADED_FFT_MIN_SIZE)
    from roughcontact import _backend

    monkeypatch.delenv("ROUGHCONTACT_FFT_WORKERS", raising=False)
    cores = _backend.default_workers()
    assert cores >= 1
    assert _backend.default_workers(256 * 256) == 1
    assert _backend.default_workers(_backend.THREADED_FFT_MIN_SIZE) == cores
    monkeypatch.setenv("ROUGHCONTACT_FFT_WORKERS", "3")
    assert _backend.default_workers(256 * 256) == 3
    # whatever the threads, the same transform
    x = np.random.default_rng(0).standard_normal((64, 48))
    np.testing.assert_allclose(_backend.irfft2(_backend.rfft2(x), x.shape), x, atol=1e-12)


@pytest.mark.parametrize("shape", [(64, 64), (48, 40), (33, 17), (2, 128)])
@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_inverse_fft_one_axis_at_a_time_is_scipys(shape, dtype):
    # the inverse runs axis by axis (faster than scipy.fft.irfft2 in double precision):
    # scipy's result, bit for bit on power-of-two grids, and the input is left alone
    # unless overwrite_x is given
    import scipy.fft

    from roughcontact import _backend

    x = np.random.default_rng(1).standard_normal(shape).astype(dtype)
    q = _backend.rfft2(x)
    kept = q.copy()
    got = _backend.irfft2(q, shape)
    ref = scipy.fft.irfft2(kept, s=shape)
    assert got.dtype == ref.dtype == dtype
    np.testing.assert_array_equal(q, kept)
    if all(m & (m - 1) == 0 for m in shape):
        np.testing.assert_array_equal(got, ref)
    np.testing.assert_allclose(got, ref, atol=20 * np.finfo(dtype).eps * np.abs(ref).max())
    np.testing.assert_allclose(got, x, atol=20 * np.finfo(dtype).eps * np.abs(x).max())


def test_namespace_shortcuts_agree_with_array_api_compat():
    # the shortcut for plain ndarrays must answer what array_api_compat answers
    import array_api_compat
    import array_api_strict

    from roughcontact import _backend

    cases = [
        np.zeros(3),
        np.zeros((2, 2), dtype=np.float32),
        np.float64(1.0),
        np.ma.masked_array([1.0, 2.0]),
        array_api_strict.asarray([1.0, 2.0]),
    ]
    for x in cases:
        assert _backend.array_namespace(x) is array_api_compat.array_namespace(x)
        assert _backend.is_numpy_array(x) == array_api_compat.is_numpy_array(x)
    a, b = np.zeros(2), np.ones(2)
    assert _backend.array_namespace(a, b) is array_api_compat.array_namespace(a, b)


@pytest.mark.skipif(not hasattr(os, "fork"), reason="needs os.fork")
def test_background_thread_works_after_fork():
    # a forked child inherits the executor object but not its thread
    from roughcontact import _backend

    assert _backend.in_background(lambda: 2 + 3)() == 5
    pid = os.fork()
    if pid == 0:  # child: must compute, not wait forever for a thread it lacks
        try:
            code = 0 if _backend.in_background(lambda: 7 * 6)(timeout=20) == 42 else 1
        except BaseException:  # noqa: BLE001 - any failure is the child's exit code
            code = 2
        os._exit(code)
    _, status = os.waitpid(pid, 0)
    assert os.WIFEXITED(status) and os.WEXITSTATUS(status) == 0
