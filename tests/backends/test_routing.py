"""Two backends: NumPy for the CPU, the compiled (JAX) program for everything else.

Arrays of other libraries go to the compiled program through DLPack and the result's
fields come back in the caller's namespace, on its device (``roughcontact._accelerator``);
what cannot go there is solved by the NumPy loops and returned the same way. On the CPU
the foreign arrays are array_api_strict's and a minimal DLPack-speaking array type (as
torch's tensors speak it); ``device="cuda"`` is checked on a GPU only.
"""

from __future__ import annotations

import numpy as np
import pytest

import roughcontact as rc
from roughcontact import _accelerator
from roughcontact.errors import ParameterError

jax = pytest.importorskip("jax")
xp = pytest.importorskip("array_api_strict")

N = 32
H = rc.self_affine((N, N), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=3)
SUB = rc.Substrate((N, N))
TOP = float(H.max())
FIELDS = ("pressure", "gap", "deflection")
EXPONENTIAL = rc.Exponential(work_of_adhesion=0.01, range=0.4)
SPHERE = rc.sphere((N, N), 20.0)

# (law, heights, control): every compiled loop and load control for each kind of law
CASES = [
    (rc.HardWall(), H, {"load": 2e-3}),
    (rc.HardWall(), H, {"offset": TOP - 0.1}),
    (rc.SmoothLJ93.from_adhesion_length(0.005), H, {"offset": TOP + 0.6}),
    (rc.SmoothLJ93.from_adhesion_length(0.05), SPHERE, {"load": 1e-3}),
    (EXPONENTIAL, SPHERE, {"offset": -0.4}),
    (EXPONENTIAL, SPHERE, {"load": 2e-4}),
]
IDS = ["hardwall-load", "hardwall-offset", "lj93-offset", "lj93-load", "exp-offset", "exp-load"]


def rel_l2(a, b) -> float:
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return float(np.linalg.norm(a - b) / max(np.linalg.norm(b), 1e-300))


class _Namespace:
    """The namespace of :class:`Foreign`: what the route asks of a caller's library."""

    @staticmethod
    def from_dlpack(x, **kwargs):
        return Foreign(np.from_dlpack(x))

    @staticmethod
    def asarray(x, device=None, **kwargs):
        return Foreign(np.asarray(x))


class Foreign:
    """A minimal array of another library (a stand-in for a torch tensor): an
    ``__array_namespace__``, a device and DLPack, nothing else."""

    device = "cpu"

    def __init__(self, a):
        self._a = np.asarray(a)
        self.shape, self.dtype, self.ndim = self._a.shape, self._a.dtype, self._a.ndim

    def __array_namespace__(self, api_version=None):
        return _Namespace

    def __dlpack__(self, **kwargs):
        return self._a.__dlpack__(**kwargs)

    def __dlpack_device__(self):
        return self._a.__dlpack_device__()

    def __array__(self, dtype=None, copy=None):
        return self._a


@pytest.mark.parametrize(("law", "heights", "control"), CASES, ids=IDS)
def test_foreign_heights_run_the_compiled_program(law, heights, control):
    ref = rc.solve(heights, SUB, law, **control)  # NumPy
    with jax.enable_x64(True):
        compiled = rc.solve(jax.numpy.asarray(heights), SUB, law, **control)
    got = rc.solve(xp.asarray(heights), SUB, law, **control)
    assert ref.converged and got.converged
    for name in FIELDS:  # the caller's namespace
        assert isinstance(getattr(got, name), type(xp.asarray(H))), name
        assert getattr(got, name).dtype == xp.float64
    # the compiled program's state (its iterations), equal to NumPy's
    assert got.iterations == compiled.iterations and got.solver == compiled.solver
    for name in FIELDS:
        assert rel_l2(getattr(got.to_numpy(), name), getattr(ref, name)) < 1e-6, name
    assert got.repulsive_area == pytest.approx(ref.repulsive_area, abs=1e-6)


def test_a_dlpack_array_of_another_library_comes_back_in_its_namespace():
    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    ref = rc.solve(H, SUB, law, offset=TOP + 0.6)
    got = rc.solve(Foreign(H), SUB, law, offset=TOP + 0.6)
    assert all(type(getattr(got, k)) is Foreign for k in FIELDS)
    assert rel_l2(got.pressure._a, ref.pressure) < 1e-6
    # a warm start from that result and from a NumPy one, in the caller's namespace
    for initial in (got, ref, Foreign(ref.deflection)):
        warm = rc.solve(Foreign(H), SUB, law, offset=TOP + 0.5, initial=initial)
        assert warm.converged and type(warm.pressure) is Foreign


def test_warm_starts_and_public_solvers_keep_the_callers_namespace():
    from roughcontact.solvers import minimize_energy, polonsky_keer

    first = polonsky_keer(xp.asarray(H), SUB, load=2e-3)
    warm = polonsky_keer(xp.asarray(H), SUB, load=2.4e-3, initial=first)
    ref = polonsky_keer(H, SUB, load=2.4e-3)
    assert warm.converged and warm.iterations <= ref.iterations
    assert isinstance(warm.pressure, type(xp.asarray(H)))
    assert rel_l2(warm.to_numpy().pressure, ref.pressure) < 1e-6
    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    got = minimize_energy(xp.asarray(H), SUB, law, offset=TOP + 0.6)
    assert isinstance(got.deflection, type(xp.asarray(H)))
    assert rel_l2(got.to_numpy().deflection, minimize_energy(H, SUB, law, offset=TOP + 0.6)
                  .deflection) < 1e-6  # fmt: skip


def test_a_path_converts_once_and_progress_sees_the_callers_namespace(monkeypatch):
    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    offsets = TOP + np.array([0.6, 0.4, 0.2, 0.0])
    routes = []
    plan = _accelerator.plan
    monkeypatch.setattr(_accelerator, "plan", lambda *a: routes.append(plan(*a)) or routes[-1])
    seen = []
    ds = rc.approach_retract(xp.asarray(H), SUB, law, offsets=offsets, fields_at=[-1],
                             progress=lambda step, n, res: seen.append(type(res.pressure)))
    # the heights went once through DLPack: every state's solve took them as they were
    assert routes[0] is not None and routes[1:] == [None] * (len(routes) - 1)
    assert len(routes) > ds.sizes["step"]
    assert seen == [type(xp.asarray(H))] * ds.sizes["step"]
    ref = rc.approach_retract(H, SUB, law, offsets=offsets, fields_at=[-1])
    np.testing.assert_allclose(ds["repulsive_area"], ref["repulsive_area"], atol=1e-6)
    np.testing.assert_array_equal(ds["jump"], ref["jump"])
    assert rel_l2(ds["pressure"].values, ref["pressure"].values) < 1e-6


@pytest.mark.parametrize("why", ["free-boundary", "callback", "no-jax", "dlpack-refused"])
def test_what_cannot_go_to_the_compiled_program_is_solved_by_numpy(monkeypatch, why):
    sub = rc.Substrate((N, N), periodic=False) if why == "free-boundary" else SUB
    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    kwargs = {"callback": lambda it, r: False} if why == "callback" else {}
    heights = xp.asarray(H)
    if why == "no-jax":
        monkeypatch.setattr(_accelerator, "_jax_installed", lambda: False)
    if why == "dlpack-refused":

        def refuse(self, **kwargs):
            raise BufferError("no DLPack here")

        monkeypatch.setattr(Foreign, "__dlpack__", refuse)
        heights = Foreign(H)
    ref = rc.solve(H, sub, law, offset=TOP + 0.6, **kwargs)
    got = rc.solve(heights, sub, law, offset=TOP + 0.6, **kwargs)
    assert got.iterations == ref.iterations  # the NumPy loop's own steps
    assert type(got.pressure) is type(heights)
    assert rel_l2(got.to_numpy().pressure, ref.pressure) < 1e-12


def test_device_cpu_means_numpy():
    got = rc.solve(xp.asarray(H), SUB, rc.HardWall(), load=2e-3, device="cpu")
    assert all(type(getattr(got, k)) is np.ndarray for k in FIELDS)
    with jax.enable_x64(True):
        jh = jax.numpy.asarray(H)
    got = rc.solve(jh, SUB, rc.HardWall(), load=2e-3, device="cpu")
    assert type(got.pressure) is np.ndarray and got.solver == "polonsky-keer"


def _has_gpu() -> bool:
    try:
        return bool(jax.devices("gpu"))
    except RuntimeError:
        return False


@pytest.mark.skipif(_has_gpu(), reason="a GPU is present")
def test_cuda_without_a_jax_gpu_is_one_line_naming_the_install():
    for call in (
        lambda: rc.solve(H, SUB, rc.HardWall(), load=1e-3, device="cuda"),
        lambda: rc.approach_retract(H, SUB, loads=[1e-3], device="cuda:0"),
        lambda: _accelerator.jax_gpu("cuda"),
    ):
        with pytest.raises(ParameterError, match=r"device='cuda(:0)?'.*jax\[cuda12\]") as err:
            call()
        assert "\n" not in str(err.value)


def test_check_device_takes_no_gpu_and_says_what_to_install(monkeypatch):
    assert _accelerator.check_device(None) is None and _accelerator.check_device("cpu") == "cpu"
    with pytest.raises(ParameterError, match="device must be 'cpu', 'cuda' or 'cuda:N'"):
        _accelerator.check_device("gpu")
    monkeypatch.setattr(_accelerator, "_has_jax_cuda", lambda: True)
    assert _accelerator.check_device("cuda:1") == "cuda:1"  # the index: at the first solve
    monkeypatch.setattr(_accelerator, "_has_jax_cuda", lambda: False)
    monkeypatch.setattr(_accelerator, "_jax_loaded", lambda: False)
    with pytest.raises(ParameterError, match=r"jax\[cuda12\]"):
        _accelerator.check_device("cuda")


def test_heights_that_reach_neither_backend_are_one_line():
    class Opaque(Foreign):
        def __dlpack__(self, **kwargs):
            raise BufferError("no DLPack here")

        def __array__(self, dtype=None, copy=None):
            raise TypeError("no host copy either")

    with pytest.raises(ParameterError, match="can go neither to the compiled program") as err:
        rc.solve(Opaque(H), SUB, rc.HardWall(), load=2e-3)
    assert "\n" not in str(err.value)


@pytest.mark.skipif(not _has_gpu(), reason="needs JAX with a CUDA device")
@pytest.mark.parametrize(("law", "heights", "control"), CASES[::2], ids=IDS[::2])
def test_device_cuda_runs_the_compiled_program_on_the_gpu(law, heights, control):
    ref = rc.solve(heights, SUB, law, **control)
    got = rc.solve(heights, SUB, law, device="cuda", **control)
    assert got.converged and got.to_numpy().pressure.dtype == np.float64
    try:
        import cupy
    except ImportError:
        assert next(iter(got.pressure.devices())).platform == "gpu"
    else:
        assert isinstance(got.pressure, cupy.ndarray)
    assert rel_l2(got.to_numpy().pressure, ref.pressure) < 1e-6


def test_a_gpu_solve_the_compiled_loops_cannot_take_says_it_runs_on_the_host():
    class OnAGpu(Foreign):  # as a CuPy array reports itself through DLPack
        def __dlpack_device__(self):
            return (2, 0)

    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    ref = rc.solve(H, SUB, law, offset=TOP + 0.6, callback=lambda it, r: False)
    with pytest.warns(RuntimeWarning, match="runs the NumPy loops on the host"):
        got = rc.solve(OnAGpu(H), SUB, law, offset=TOP + 0.6, callback=lambda it, r: False)
    assert type(got.pressure) is Foreign and got.iterations == ref.iterations


def test_gpu_heights_jax_cannot_take_are_solved_on_the_host_with_a_warning(monkeypatch):
    class OnAGpu(Foreign):  # a GPU array this JAX (CPU only) refuses through DLPack
        def __dlpack_device__(self):
            return (2, 0)

        def __dlpack__(self, **kwargs):
            raise BufferError("no CUDA backend")

    ref = rc.solve(H, SUB, rc.HardWall(), load=2e-3)
    with pytest.warns(RuntimeWarning, match=r"JAX could not take them.*jax\[cuda12\]"):
        got = rc.solve(OnAGpu(H), SUB, rc.HardWall(), load=2e-3)
    assert type(got.pressure) is Foreign and got.iterations == ref.iterations
