"""Array-API plumbing shared by the numerical core.

The core is written against the array API standard (``xp = array_namespace(x)``) so the
same code runs on NumPy and CuPy.  On NumPy the FFTs go through :mod:`scipy.fft`, which
is faster than ``numpy.fft`` and accepts ``workers=`` for multithreading.
"""

from __future__ import annotations

import os

import numpy as np
from array_api_compat import array_namespace, is_numpy_array

__all__ = ["array_namespace", "default_workers", "irfft2", "is_numpy_array", "rfft2", "to_numpy"]


def default_workers() -> int:
    """Number of threads scipy.fft uses (``ROUGHCONTACT_FFT_WORKERS`` or all cores)."""
    env = os.environ.get("ROUGHCONTACT_FFT_WORKERS")
    if env:
        return max(1, int(env))
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()


def rfft2(x, workers: int | None = None):
    """Real 2D forward FFT over the last two axes (unnormalised)."""
    if is_numpy_array(x):
        import scipy.fft

        return scipy.fft.rfft2(x, workers=workers or default_workers())
    return array_namespace(x).fft.rfftn(x, axes=(-2, -1))


def irfft2(x, shape: tuple[int, int], workers: int | None = None, overwrite_x: bool = False):
    """Inverse of :func:`rfft2` for a real field of ``shape``."""
    if is_numpy_array(x):
        import scipy.fft

        return scipy.fft.irfft2(
            x, s=shape, workers=workers or default_workers(), overwrite_x=overwrite_x
        )
    return array_namespace(x).fft.irfftn(x, s=shape, axes=(-2, -1))


def to_numpy(x) -> np.ndarray:
    """Copy an array of any backend to host NumPy (only at the edges: files, plots)."""
    if is_numpy_array(x):
        return x
    if hasattr(x, "get"):  # CuPy
        return x.get()
    return np.asarray(x)
