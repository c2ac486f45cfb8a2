"""Operators and input checks shared by the solvers (flat float64 arrays on the grid)."""

from __future__ import annotations

import math

import numpy as np

from .._backend import array_namespace, irfft2, is_numpy_array, rfft2
from .._validate import ParameterError, heights2d

__all__ = [
    "check_hard_wall_offset",
    "check_problem",
    "compliance_operator",
    "dot",
    "stiffness_operator",
]


def _fourier_operator(substrate, which: int):
    shape = substrate.shape

    def apply(x_flat):
        xp = array_namespace(x_flat)
        xq = rfft2(xp.reshape(x_flat, shape))
        xq *= substrate._arrays(x_flat)[which]  # cached per backend
        return xp.reshape(irfft2(xq, shape, overwrite_x=True), (-1,))

    return apply


def compliance_operator(substrate):
    """p -> G p: deflection (length) of a pressure field; the rigid mean gives zero mean."""
    return _fourier_operator(substrate, 1)


def stiffness_operator(substrate):
    """w -> K w: elastic pressure of a deflection; with a rigid mean its mean is zero."""
    return _fourier_operator(substrate, 0)


def dot(a, b) -> float:
    """Euclidean inner product of two flat arrays of one backend, as a Python float."""
    if is_numpy_array(a):
        # einsum: no temporary and no BLAS threads (which cost more than they save on a
        # shared machine for vectors of this length)
        return float(np.einsum("i,i->", a, b))
    return float(array_namespace(a).sum(a * b))


def check_problem(heights, substrate, tol, offset=None) -> np.ndarray:
    """Validate the common inputs; return the heights as a contiguous float64 array."""
    h = heights2d("heights", heights)
    if is_numpy_array(h):
        h = np.ascontiguousarray(h, dtype=float)
    if tuple(h.shape) != substrate.shape:
        raise ParameterError(
            f"heights shape {h.shape} differs from substrate shape {substrate.shape}"
        )
    if offset is not None and not math.isfinite(float(offset)):
        raise ParameterError(f"offset must be finite, got {offset!r}")
    if not float(tol) > 0:
        raise ParameterError(f"tol must be > 0, got {tol!r}")
    return h


def check_hard_wall_offset(heights, substrate, offset) -> None:
    """Reject an offset that no impenetrable state reaches on a rigid-mean substrate.

    With a rigid uniform mode the mean deflection is zero, so the mean gap is
    ``d - mean(h)``; below ``mean(h)`` every state interpenetrates somewhere.
    """
    if offset is None or not substrate.rigid_mean:
        return
    xp = array_namespace(heights)
    mean = float(xp.mean(heights))
    if offset < mean - 1e-12 * (float(xp.max(xp.abs(heights))) + abs(offset)):
        raise ParameterError(
            f"offset must be >= mean(heights) = {mean:g} for a hard wall on a substrate with "
            f"a rigid mean (got {offset:g}: the surfaces would overlap everywhere)"
        )
