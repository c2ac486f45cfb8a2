"""CuPy arrays (an NVIDIA GPU): the compiled program's states equal NumPy's.

CuPy heights go to the compiled (JAX) program through DLPack and the fields come back as
CuPy arrays; ``device="cuda"`` runs the same program on JAX's GPU (CuPy fields, CuPy being
importable). Marked ``gpu`` and skipped where CuPy, a GPU or JAX's CUDA backend is
missing; CI never needs one.
"""

import numpy as np
import pytest

import roughcontact as rc

cupy = pytest.importorskip("cupy")
try:
    _GPUS = cupy.cuda.runtime.getDeviceCount()
except Exception:  # no driver
    _GPUS = 0
try:
    import jax

    _JAX_GPUS = len(jax.devices("gpu"))
except Exception:  # noqa: BLE001 - no JAX, or no CUDA backend in it
    _JAX_GPUS = 0
pytestmark = [
    pytest.mark.gpu,
    pytest.mark.skipif(_GPUS == 0, reason="no CUDA device"),
    pytest.mark.skipif(_JAX_GPUS == 0, reason="JAX without a CUDA backend"),
]


def rel_l2(a, b) -> float:
    return float(np.linalg.norm(a - b) / max(np.linalg.norm(b), 1e-300))

N = 128
H = rc.self_affine((N, N), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=7)
SUB = rc.Substrate((N, N))


def test_substrate_operators_on_the_gpu():
    p = np.random.default_rng(0).normal(size=(N, N))
    w = SUB.deflection(cupy.asarray(p))
    assert isinstance(w, cupy.ndarray)
    np.testing.assert_allclose(w.get(), SUB.deflection(p), rtol=1e-12, atol=1e-14)


@pytest.mark.parametrize(
    ("law", "control"),
    [
        (rc.HardWall(), {"load": 2e-3}),
        (rc.HardWall(), {"offset": float(H.max()) - 0.3 * float(H.std())}),
        (rc.SmoothLJ93.from_adhesion_length(0.005), {"offset": float(H.max()) + 0.8}),
        (rc.Exponential(work_of_adhesion=0.005, range=0.5), {"offset": float(H.max()) - 0.1}),
    ],
    ids=["hardwall-load", "hardwall-offset", "lj93smooth", "exponential"],
)
@pytest.mark.parametrize("how", ["device", "cupy-input"])
def test_gpu_states_equal_the_cpu_ones(law, control, how):
    ref = rc.solve(H, SUB, law, tol=1e-10, **control)
    if how == "device":
        got = rc.solve(H, SUB, law, tol=1e-10, device="cuda", **control)
    else:
        got = rc.solve(cupy.asarray(H), SUB, law, tol=1e-10, **control)
    assert got.converged, got.message
    # the record's fields stay on the GPU; to_numpy is the edge
    assert all(isinstance(getattr(got, k), cupy.ndarray) for k in ("pressure", "gap", "deflection"))
    host = got.to_numpy()
    assert rel_l2(host.pressure, ref.pressure) < 1e-6
    assert got.offset == pytest.approx(ref.offset, abs=1e-6)
    assert got.repulsive_area == pytest.approx(ref.repulsive_area, abs=1e-6)
    # a warm start from the GPU record
    warm = rc.solve(cupy.asarray(H), SUB, law, initial=got, tol=1e-10, **control)
    ref_warm = rc.solve(H, SUB, law, initial=ref, tol=1e-10, **control)
    assert warm.converged and isinstance(warm.gap, cupy.ndarray)
    assert warm.iterations <= max(2, 1.25 * ref_warm.iterations)


def test_contact_map_counts_on_the_gpu():
    from roughcontact.analysis.contact_geometry import count_patches

    rng = np.random.default_rng(1)
    for fraction in (0.0, 0.3, 0.55, 0.7, 1.0):
        mask = rng.random((N, N - 8)) < fraction
        for periodic in (True, False):
            want = rc.contact_patches(mask, periodic=periodic)[1].size
            assert count_patches(cupy.asarray(mask), periodic=periodic) == want
        assert rc.perimeter_edges(cupy.asarray(mask)) == rc.perimeter_edges(mask)


def test_gpu_path_and_float32():
    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    offsets = float(H.max()) + 1.0 - np.array([0.0, 0.1, 0.2])
    ref = rc.approach_retract(H, SUB, law, offsets=offsets)
    got = rc.approach_retract(H, SUB, law, offsets=offsets, device="cuda")
    assert got.attrs["device"].startswith("<CUDA Device") or "cuda" in got.attrs["device"].lower()
    np.testing.assert_allclose(got["load"], ref["load"], rtol=1e-6, atol=1e-12)
    single = rc.approach_retract(H, SUB, law, offsets=offsets, device="cuda", dtype="float32")
    np.testing.assert_allclose(single["load"], ref["load"], rtol=1e-4, atol=1e-6)


@pytest.mark.parametrize("dtype", ["float64", "float32"])
def test_fused_law_kernels_equal_the_numpy_law(dtype):
    # the smoothed 9-3 wall's one-pass CuPy kernels (interactions/_fused.py): built, and
    # the NumPy values, the 9-3 core and its quadratic continuation included
    from roughcontact.interactions._fused import kernel

    assert kernel("pressure") is not None and kernel("curvature") is not None
    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    g = np.concatenate([np.linspace(-0.5, 2.0, 4001), [0.0, 0.05, law.cutoff]]).astype(dtype)
    for method in ("pressure", "curvature"):
        got = getattr(law, method)(cupy.asarray(g))
        assert isinstance(got, cupy.ndarray) and got.dtype == g.dtype
        # bit for bit where NVRTC honours --fmad=false; a contracted build rounds differently
        rtol = 1e-12 if dtype == "float64" else 1e-6
        np.testing.assert_allclose(got.get(), getattr(law, method)(g), rtol=rtol, atol=0)
