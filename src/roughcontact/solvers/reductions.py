"""Reductions of the solvers' flat fields to Python floats, accumulated in float64."""

from __future__ import annotations

import numpy as np
from array_api_compat import is_numpy_namespace  # cached per namespace

from .._backend import array_namespace, is_numpy_array, to_numpy

__all__ = ["DOT_CHUNK", "dot", "fetch", "largest", "on_device", "total", "vdot", "vtotal"]


#: Length of the rows a long NumPy inner product is cut into (see :func:`dot`).
DOT_CHUNK = 8192
_HAS_VECDOT = hasattr(np, "vecdot")  # numpy >= 2


def dot(a, b) -> float:
    """Euclidean inner product of two flat arrays of one backend, as a Python float.

    Accumulated in float64 also for float32 arrays: energies and CG coefficients are
    differences of sums over the whole grid, which float32 accumulation would drown.
    """
    if is_numpy_array(a):
        n = a.shape[0]
        rows = n - n % DOT_CHUNK
        if rows and a.dtype == b.dtype == np.float64 and _HAS_VECDOT:
            # one row of DOT_CHUNK at a time: np.dot/vecdot call OpenBLAS, which runs
            # a product of more than 10 000 elements on all cores and leaves its threads
            # spinning after the call (on a shared 2-core machine that doubled the
            # hard-wall solver's time, its FFT threads starved); below that length it
            # stays on one thread and is still 2x faster than einsum (256²-1024²)
            head = np.vecdot(a[:rows].reshape(-1, DOT_CHUNK), b[:rows].reshape(-1, DOT_CHUNK)).sum()
            if rows == n:  # power-of-two grids: no tail (an empty einsum costs a few us)
                return float(head)
            return float(head + np.einsum("i,i->", a[rows:], b[rows:]))
        # einsum: no temporary and no BLAS
        return float(np.einsum("i,i->", a, b, dtype=np.float64))
    xp = array_namespace(a)
    return float(xp.sum(a * b, dtype=xp.float64))


def total(x) -> float:
    """Sum of an array of any backend as a Python float, accumulated in float64."""
    if type(x) is np.ndarray:  # the common case, without the namespace's wrapper
        return float(np.add.reduce(x, dtype=np.float64))
    xp = array_namespace(x)
    return float(xp.sum(x, dtype=xp.float64))


def vdot(a, b):
    """:func:`dot`, but off NumPy a 0-d float64 array on the device (no host sync)."""
    if is_numpy_array(a):
        return dot(a, b)
    xp = array_namespace(a)
    return xp.sum(a * b, dtype=xp.float64)


def vtotal(x):
    """:func:`total`, but off NumPy a 0-d float64 array on the device (no host sync)."""
    if type(x) is np.ndarray:
        return total(x)
    xp = array_namespace(x)
    return xp.sum(x, dtype=xp.float64)


def on_device(value) -> bool:
    """Whether ``value`` is a device scalar (a 0-d array off NumPy), not a Python float."""
    return not isinstance(value, (float, int)) and not is_numpy_array(value)


def fetch(xp, scalars) -> list[float]:
    """Python floats of several 0-d arrays of namespace ``xp``, in one transfer.

    On a GPU each ``float(x)`` of a device scalar waits for the device (a host sync);
    stacked, the values come over in one copy. Exact: every value is widened to float64
    (as ``float`` would) before stacking.
    """
    if is_numpy_namespace(xp) or not any(on_device(x) for x in scalars):
        return [float(x) for x in scalars]
    arrays = [i for i, x in enumerate(scalars) if on_device(x)]
    wide = [scalars[i] for i in arrays]
    wide = [x if x.dtype == xp.float64 else xp.astype(x, xp.float64) for x in wide]
    values = [float(x) if not on_device(x) else None for x in scalars]
    for i, v in zip(arrays, to_numpy(xp.stack(wide)).tolist(), strict=True):
        values[i] = v
    return values


def largest(values) -> float:
    """``max |values|`` of a flat array as a Python float (0 for none): the pressure scale
    of the smooth solver's floor guard."""
    if values.shape[0] == 0:
        return 0.0
    xp = array_namespace(values)
    return float(xp.max(xp.abs(values)))
