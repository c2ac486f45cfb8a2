"""Array-API plumbing shared by the numerical core.

The shared numerical pieces (laws, operators, statistics, contact maps) are written
against the array API standard (``xp = array_namespace(x)``), so they run on NumPy, CuPy,
JAX and other array-API libraries. The solvers have two backends, NumPy loops for the CPU
and compiled (JAX) loops for accelerators; :mod:`._accelerator` routes every solve to
one of them and its result back to the caller's namespace (and owns the device names:
``to_device``, ``check_device``). On NumPy the FFTs go through
:mod:`scipy.fft`, which is faster than ``numpy.fft`` and accepts ``workers=`` for
multithreading; the solvers' convolutions (:func:`convolve`) call scipy's pocketfft
binding directly, into arrays they allocate once.
"""

from __future__ import annotations

import contextlib
import functools
import os
import sys

import array_api_compat
import numpy as np
from array_api_compat import device as array_device
from array_api_compat import is_array_api_obj, is_cupy_array, is_jax_array

from .errors import ParameterError

__all__ = [
    "DTYPES",
    "array_device",
    "array_namespace",
    "constant",
    "check_dtype",
    "convolve",
    "default_workers",
    "dtype_name",
    "in_background",
    "irfft2",
    "is_array",
    "is_cupy_array",
    "is_numpy_array",
    "jax_precision",
    "overlaps_fft",
    "rfft2",
    "to_numpy",
]


def array_namespace(*xs, **kwargs):
    """:func:`array_api_compat.array_namespace`, answered at once for one array.

    The solvers ask it several times per iteration; the shortcut gives the same module
    (``array_api_compat.numpy`` for NumPy, remembered per type for the others) in a
    tenth of the time.
    """
    if len(xs) == 1 and not kwargs:
        kind = type(xs[0])
        namespace = _NAMESPACES.get(kind)
        if namespace is None:
            namespace = array_api_compat.array_namespace(xs[0])
            _NAMESPACES[kind] = namespace  # an array type has one namespace
        return namespace
    return array_api_compat.array_namespace(*xs, **kwargs)


#: The namespace of each array type met so far (array_namespace's answer for one array
#: depends on its type alone; asked anew it costs ~10 us, dozens of times per iteration).
#: Filled on first use, NumPy's too: importing array_api_compat.numpy walks all of
#: NumPy's lazy submodules (f2py, testing, ...), ~0.15 s that ``import roughcontact``
#: need not pay.
_NAMESPACES: dict = {}


def constant(value: float, like):
    """``value`` as an operand of ``like``: the Python float on NumPy and JAX (and with a
    Python or NumPy scalar ``like``), elsewhere a cached
    array of shape ``(1,) * like.ndim`` in ``like``'s dtype on its device (the same
    values: a Python scalar operand takes the array's dtype; array_api_strict converts a
    Python scalar at every use, two arrays more per operation, which this avoids)."""
    if type(like) is np.ndarray or isinstance(like, (float, int, np.generic)):
        return value  # (the common NumPy case first: the laws call this per operation)
    if is_numpy_array(like) or is_jax_array(like):
        # JAX: a Python scalar is weakly typed (it takes the array's dtype), and a cached
        # array made while a compiled program is traced would leak the tracer
        return value
    xp = array_namespace(like)
    key = (type(like), like.dtype, array_device(like), like.ndim, float(value).hex())
    try:
        return _CONSTANTS[key]
    except KeyError:
        pass
    except TypeError:  # an unhashable device or dtype: made anew
        return xp.full((1,) * like.ndim, value, dtype=like.dtype, device=array_device(like))
    if len(_CONSTANTS) > 256:  # a few per law and dtype: a bound, not a cache policy
        _CONSTANTS.clear()
    made = xp.full((1,) * like.ndim, value, dtype=like.dtype, device=array_device(like))
    _CONSTANTS[key] = made
    return made


_CONSTANTS: dict = {}


def is_numpy_array(x) -> bool:
    """:func:`array_api_compat.is_numpy_array`, answered at once for a plain ndarray."""
    return type(x) is np.ndarray or array_api_compat.is_numpy_array(x)


def is_array(x) -> bool:
    """Whether ``x`` is an array of a backend the core computes on (NumPy, CuPy, any
    array-API library), as opposed to a list, a scalar or another array-like.

    Through :func:`array_api_compat.is_array_api_obj`: a CuPy ndarray has no
    ``__array_namespace__`` attribute (array_api_compat supplies its namespace), so a
    test of that attribute misses it and then fails in ``np.asarray`` ("Implicit
    conversion to a NumPy array is not allowed"). NumPy scalars count as arrays.
    """
    return type(x) is np.ndarray or is_array_api_obj(x)


#: Floating-point precisions the core computes in (float64 is the default).
DTYPES = ("float64", "float32")


#: Grids with fewer points than this run scipy.fft on one thread: below it, starting
#: threads costs more than they save (measured, 2 cores: a float32 FFT pair at 256² takes
#: 0.32 ms on one thread and 0.67 ms on two; at 1024² 6.2 ms against 3.2 ms).
THREADED_FFT_MIN_SIZE = 1 << 19


@functools.cache
def _cores() -> int:
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()


def default_workers(size: int | None = None) -> int:
    """Number of threads scipy.fft uses for a grid of ``size`` points.

    ``ROUGHCONTACT_FFT_WORKERS`` if set; else one below :data:`THREADED_FFT_MIN_SIZE`
    points and all cores from there (or for ``size=None``).
    """
    env = os.environ.get("ROUGHCONTACT_FFT_WORKERS")
    if env:
        return max(1, int(env))
    if size is not None and size < THREADED_FFT_MIN_SIZE:
        return 1
    return _cores()


def rfft2(x, workers: int | None = None):
    """Real 2D forward FFT over the last two axes (unnormalised)."""
    if is_numpy_array(x):
        import scipy.fft

        return scipy.fft.rfft2(x, workers=workers or default_workers(x.size))
    return array_namespace(x).fft.rfftn(x, axes=(-2, -1))


def irfft2(x, shape: tuple[int, int], workers: int | None = None, overwrite_x: bool = False):
    """Inverse of :func:`rfft2` for a real field of ``shape``.

    On NumPy one axis at a time, the complex transform over the rows in place: the same
    passes as ``scipy.fft.irfft2`` and the same result (bit for bit on power-of-two
    grids), but 1.6-1.8x faster in double precision and up to 10 % in single (scipy
    1.17, 256²-1024²; ``benchmarks/hardwall.py`` times both for its FFT reference).
    """
    if is_numpy_array(x):
        import scipy.fft

        w = workers or default_workers(shape[-2] * shape[-1])
        rows = scipy.fft.ifft(x, n=shape[-2], axis=-2, workers=w, overwrite_x=overwrite_x)
        return scipy.fft.irfft(rows, n=shape[-1], axis=-1, workers=w, overwrite_x=True)
    return array_namespace(x).fft.irfftn(x, s=shape, axes=(-2, -1))


@functools.cache
def _pocketfft():
    """scipy's pocketfft binding (it writes into given arrays), or None if unusable.

    ``scipy.fft._pocketfft.pypocketfft`` is private to scipy (there since 1.4, the same
    ``r2c/c2c/c2r(a, axes, [lastsize,] forward, inorm, out, nthreads)`` through 1.17),
    so it is used only after it reproduced the public transform on an odd-sized grid;
    otherwise :func:`convolve` takes the public API.
    """
    try:
        import scipy.fft
        from scipy.fft._pocketfft import pypocketfft

        x = np.cos(np.arange(35.0)).reshape(5, 7)
        kernel = 1.0 + np.arange(20.0).reshape(5, 4)
        got = _pocketfft_convolve(pypocketfft, x, kernel, np.empty((5, 4), complex), None, 1)
        want = scipy.fft.irfft2(scipy.fft.rfft2(x) * kernel, s=x.shape)
        if got.shape == want.shape and np.allclose(got, want, rtol=1e-12, atol=1e-12):
            return pypocketfft
    except Exception:  # noqa: BLE001 - any failure means: use the public API
        pass
    return None


def _pocketfft_convolve(pf, x, kernel, spectrum, out, workers):
    # normalisation 1/n per inverse axis (inorm=2), as scipy's ifft/irfft
    pf.r2c(x, (1,), True, 0, spectrum, workers)
    pf.c2c(spectrum, (0,), True, 0, spectrum, workers)
    np.multiply(spectrum, kernel, out=spectrum)
    pf.c2c(spectrum, (0,), False, 2, spectrum, workers)
    return pf.c2r(spectrum, (1,), x.shape[1], False, 2, out, workers)


def convolve(x, kernel, *, spectrum=None, out=None, workers: int | None = None):
    """Periodic convolution ``irfft2(rfft2(x) * kernel)`` of a real 2D field.

    Parameters
    ----------
    x : (nx, ny) real array
    kernel : (nx, ny//2 + 1) real array
        The operator's Fourier multipliers on the ``rfft2`` layout, in ``x``'s dtype.
    spectrum : (nx, ny//2 + 1) complex array, optional
        NumPy only: scratch for the spectrum (complex64 for float32 ``x``, complex128 for
        float64), reused by callers that convolve every iteration.
    out : (nx, ny) array of x's dtype, optional
        NumPy only: where the result goes (not ``x``).

    On NumPy with scipy's pocketfft binding (:func:`_pocketfft`) this is the transform
    :func:`irfft2` and :func:`rfft2` do, but without their dispatch and without fresh
    arrays: freshly mapped result arrays page-faulted often enough to make a float64
    convolution at 256²-512² twice as slow, and the float32 one 5-12 % slower (scipy
    1.17, 2 cores). Bit for bit the same result on power-of-two grids.
    """
    if not is_numpy_array(x):
        return irfft2(rfft2(x) * kernel, tuple(x.shape), workers=workers)
    pf = _pocketfft()
    w = workers or default_workers(x.size)
    if pf is None:
        q = rfft2(x, workers=w)
        q *= kernel
        result = irfft2(q, tuple(x.shape), workers=w, overwrite_x=True)
        if out is None:
            return result
        out[...] = result
        return out
    if spectrum is None:
        spectrum = np.empty(kernel.shape, dtype=np.result_type(x.dtype, np.complex64))
    return _pocketfft_convolve(pf, x, kernel, spectrum, out, w)


_BACKGROUND = None

#: Grids with fewer points than this do not hand convolutions to the background thread:
#: the hand-over (~50 us) ate the gain at 256² (measured, 2 cores: the smooth solver's
#: iteration 1.25-1.30 ms either way at 256²; 6.9-7.3 -> 6.4 ms at 512², ℓa = 0.05).
OVERLAP_MIN_SIZE = 1 << 17


def overlaps_fft(size: int) -> bool:
    """Whether a NumPy FFT of ``size`` points should run beside the caller's work.

    When scipy.fft runs on one thread for that size (see :func:`default_workers`), the
    grid has at least :data:`OVERLAP_MIN_SIZE` points and there is a second core, a
    convolution handed to :func:`in_background` runs on it while the caller goes on with
    vector work (pocketfft and NumPy's large ufuncs release the GIL).
    """
    return size >= OVERLAP_MIN_SIZE and _cores() >= 2 and default_workers(size) == 1


def in_background(fn, *args, **kwargs):
    """Run ``fn(*args, **kwargs)`` on the one background thread; returns a function of no
    arguments that waits for the result (and re-raises its exception)."""
    global _BACKGROUND
    # a forked child inherits the executor but not its thread: it makes its own
    if _BACKGROUND is None or _BACKGROUND[0] != os.getpid():
        from concurrent.futures import ThreadPoolExecutor

        executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix="roughcontact")
        _BACKGROUND = (os.getpid(), executor)
    return _BACKGROUND[1].submit(fn, *args, **kwargs).result


def to_numpy(x) -> np.ndarray:
    """Copy an array of any backend to host NumPy (only at the edges: files, plots)."""
    if is_numpy_array(x):
        return x
    if is_cupy_array(x):
        return x.get()
    try:
        return np.asarray(x)
    except RuntimeError:
        # an array-API library refusing an implicit copy off its device: move it to the
        # library's default (host) device first
        host = array_namespace(x).__array_namespace_info__().default_device()
        return np.asarray(x.to_device(host))


def check_dtype(dtype) -> str | None:
    """Normalise a precision request (``None``, ``"float64"``, ``"float32"`` or a dtype)."""
    if dtype is None:
        return None
    name = getattr(dtype, "__name__", None) or str(getattr(dtype, "name", dtype))
    if name not in DTYPES:
        raise ParameterError(f"dtype must be one of {', '.join(DTYPES)}, got {dtype!r}")
    return name


def dtype_name(x) -> str:
    """``"float32"`` or ``"float64"``: the precision a float array of any backend is in."""
    return "float32" if x.dtype == array_namespace(x).float32 else "float64"


def jax_precision(heights, dtype=None):
    """The context a solve on JAX ``heights`` runs in, so that float64 needs no global switch.

    When JAX's ``jax_enable_x64`` is off, every solve runs inside ``jax.enable_x64(True)``
    (the global setting is left alone): float64 (``dtype="float64"``, or float64 heights
    with ``dtype=None``) then computes in float64, its fields float64 JAX arrays
    (``result.to_numpy()`` keeps them so; JAX computes on them in float64 only with x64
    enabled), and float32 (float32 heights, the default there) keeps float32 fields with
    its sums accumulated in float64, as the NumPy loops and an x64 session do (float32
    sums made the bounded solver's energy test fail at the rounding level). Heights
    traced by ``jax.jit`` (or ``vmap``, ``grad``) get a one-line :class:`ParameterError`:
    the solvers compile their own loops and read results on the host.
    """
    jax = sys.modules["jax"]
    if isinstance(heights, jax.core.Tracer):
        raise ParameterError(
            "heights are traced by jax.jit (or vmap/grad): roughcontact's solvers compile "
            "their own loop and return host values; call them outside jax.jit"
        )
    if jax.config.jax_enable_x64:
        return contextlib.nullcontext()
    return jax.enable_x64(True)
