"""What broke the CuPy path, caught without a GPU.

* A CuPy ndarray has no ``__array_namespace__`` attribute (array_api_compat supplies its
  namespace), so a ``hasattr`` test took it for an array-like and ``np.asarray`` refused
  it. A stand-in class registered as ``cupy.ndarray`` (array_api_compat recognises CuPy
  by module and class name) behaves like CuPy there: no such attribute, no implicit
  conversion, ``.get()`` copies to the host.
* array_api_compat's ``fftfreq``/``rfftfreq`` accept no device but "cpu" (for CuPy
  arrays: "Unsupported device"); a namespace with that rule stands in for CuPy's.
* A study task's analysis (the hard-wall reference: several solves) ran on the host.
"""

import pathlib
import re
import sys
import types

import numpy as np
import pytest

import roughcontact as rc
from roughcontact._accelerator import to_device
from roughcontact._backend import is_array, to_numpy

xp = pytest.importorskip("array_api_strict")

SRC = pathlib.Path(rc.__file__).parent


class _FakeCupyArray:
    """A GPU array as NumPy sees a CuPy one: no implicit conversion, ``get()`` copies."""

    def __init__(self, values):
        self._values = np.asarray(values)
        self.dtype, self.shape = self._values.dtype, self._values.shape

    def __array__(self, *args, **kwargs):
        raise TypeError("Implicit conversion to a NumPy array is not allowed")

    def get(self):
        return self._values.copy()


@pytest.fixture()
def fake_cupy(monkeypatch):
    module = types.ModuleType("cupy")
    _FakeCupyArray.__module__ = "cupy"
    _FakeCupyArray.__qualname__ = _FakeCupyArray.__name__ = "ndarray"
    module.ndarray = _FakeCupyArray
    monkeypatch.setitem(sys.modules, "cupy", module)
    return _FakeCupyArray


def test_no_attribute_test_for_arrays_in_the_core():
    pattern = re.compile(r"hasattr\([^)]*__array_namespace__")
    offenders = [
        f"{path.relative_to(SRC)}:{i}"
        for path in SRC.rglob("*.py")
        for i, line in enumerate(path.read_text().splitlines(), 1)
        if pattern.search(line)
    ]
    assert not offenders, offenders


def test_a_cupy_like_array_is_an_array_and_comes_to_the_host(fake_cupy):
    x = fake_cupy(np.arange(6.0).reshape(2, 3))
    assert not hasattr(x, "__array_namespace__")  # as for cupy.ndarray
    with pytest.raises(TypeError):
        np.asarray(x)
    assert is_array(x)
    np.testing.assert_array_equal(to_numpy(x), np.arange(6.0).reshape(2, 3))
    got = to_device(x, "cpu", "float32")
    assert type(got) is np.ndarray and got.dtype == np.float32
    assert not is_array([1.0, 2.0]) and not is_array(1.0)


class _CompatFFT:
    """array_api_compat's rule for CuPy: fftfreq takes device None or "cpu" only."""

    @staticmethod
    def fftfreq(n, /, *, d=1.0, device=None):
        if device not in ("cpu", None):
            raise ValueError(f"Unsupported device {device!r}")
        return xp.fft.fftfreq(n, d=d)

    rfftfreq = fftfreq


def test_wavevectors_on_a_device_the_namespace_fft_helpers_refuse():
    from roughcontact.spectra import _rfft_wavevectors as _wavevectors

    device = xp.Device("device1")
    namespace = types.SimpleNamespace(**{k: getattr(xp, k) for k in dir(xp) if k[0] != "_"})
    namespace.fft = _CompatFFT()
    like = xp.asarray(np.zeros((6, 8)), device=device)
    got = _wavevectors(namespace, 6, 8, 0.5, like)
    want = _wavevectors(np, 6, 8, 0.5, None)
    for a, b in zip(got, want, strict=True):
        assert a.device == device
        np.testing.assert_allclose(np.asarray(a.to_device(xp.Device("CPU_DEVICE"))), b)
    # the statistics of heights on that device equal the host ones
    h = rc.self_affine((32, 24), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=3)
    stats = rc.statistics(xp.asarray(h, device=device)).to_dict()
    assert stats == pytest.approx(rc.statistics(h).to_dict())


def test_hard_wall_reference_solves_on_the_given_device(monkeypatch):
    import roughcontact.solvers as solvers
    from roughcontact.analysis.hard_wall_reference import hard_wall_reference

    h = rc.self_affine((32, 32), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=3)
    sub = rc.Substrate((32, 32))
    seen = []
    original = solvers.solve

    def watch(heights, *args, **kwargs):
        seen.append(type(heights))
        return original(heights, *args, **kwargs)

    monkeypatch.setattr(solvers, "solve", watch)
    ref = hard_wall_reference(xp.asarray(h), sub, target_area=0.02, device="cpu")
    assert seen and set(seen) == {np.ndarray}  # moved once, every solve on the host
    want = hard_wall_reference(h, sub, target_area=0.02)
    assert ref.kappa_rep == pytest.approx(want.kappa_rep)


def test_a_task_runs_its_analysis_on_its_device(monkeypatch, make_study):
    import roughcontact.analysis.path_analysis as path_analysis
    from roughcontact.studies import load_study
    from roughcontact.studies.task import compute_task

    devices = []

    def analyze(ds, **kwargs):
        devices.append(kwargs.get("device", "missing"))
        raise rc.ParameterError("recorded")

    monkeypatch.setattr(path_analysis, "analyze_path", analyze)
    task = load_study(make_study(num=3)).tasks[0]
    task = type(task)(task.id, task.params, task.settings, task.key, device="cpu")
    ds = compute_task(task)
    assert devices == ["cpu"] and ds.attrs["analysis_error"] == "recorded"
