"""The substrate's Fourier operators as the solvers apply them (flat float arrays).

Built on the public members of :class:`~roughcontact.elastic.operator.ElasticOperator`
(``multipliers``, ``embed``, ``crop``, ``shape``, ``work_shape``), so every substrate
that provides them works with every solver. Two kinds of operator:

* on the patch (``work_grid=False``): a flat field of the heights' grid in and out,
  ``crop(F^-1[m F[embed(x)]])``. For the compliance this is the exact deflection of a
  pressure on the patch, periodic or free; for the stiffness of a free boundary it is the
  padded grid's stiffness restricted to the patch (a preconditioner, not the inverse of
  the cropped compliance). The hard-wall solver (pressure variable) uses these.
* on the work grid (``work_grid=True``): a flat field of the work grid in and out, for
  the solvers whose variable is the deflection (it lives on the whole work grid, see
  :mod:`roughcontact.elastic.operator`). The same as the patch operators when periodic.
"""

from __future__ import annotations

import numpy as np

from .._backend import (
    _pocketfft,
    _pocketfft_convolve,
    array_device,
    array_namespace,
    convolve,
    default_workers,
    irfft2,
    is_numpy_array,
)

__all__ = [
    "compliance_operator",
    "in_precision",
    "in_single_precision",
    "on_work_grid",
    "patch_sites",
    "point_response",
    "stiffness_operator",
]

_STIFFNESS, _COMPLIANCE = 0, 1  # the fields of FourierMultipliers


def _padded(substrate) -> bool:
    return tuple(substrate.work_shape) != tuple(substrate.shape)


def _fourier_operator(substrate, which: int, work_grid: bool):
    """``apply(x_flat, out=None)``: a flat field through one of the substrate's Fourier
    multipliers. On NumPy it keeps one spectrum array (and, on the patch of a padded
    substrate, one embedding and one work-grid result) per dtype for all its calls (so an
    operator is made per solve and not shared between threads); ``out`` (NumPy, flat,
    x's dtype) receives the result."""
    padded = _padded(substrate) and not work_grid
    shape = substrate.work_shape if work_grid else substrate.shape
    spectra, buffers = {}, {}
    direct = {}  # dtype -> (kernel, spectrum, pocketfft, workers): the periodic NumPy path

    def apply(x_flat, out=None):
        if type(x_flat) is np.ndarray and not padded:
            # the solvers' hot path (twice per iteration): what the general path below
            # looks up per call (the multipliers, the FFT binding, the threads), once
            fast = direct.get(x_flat.dtype)
            if fast is None:
                fast = direct[x_flat.dtype] = _direct(substrate, which, x_flat)
            kernel, spectrum, pf, workers = fast
            if pf is not None:
                x = x_flat.reshape(shape)
                out = None if out is None else out.reshape(shape)
                return _pocketfft_convolve(pf, x, kernel, spectrum, out, workers).reshape(-1)
        xp = array_namespace(x_flat)
        kernel = substrate.multipliers(x_flat)[which]  # cached per backend and dtype
        x = xp.reshape(x_flat, shape)
        if not is_numpy_array(x_flat):
            y = convolve(substrate.embed(x), kernel) if padded else convolve(x, kernel)
            return xp.reshape(substrate.crop(y) if padded else y, (-1,))
        spectrum = spectra.get(x.dtype)
        if spectrum is None:
            spectrum = spectra[x.dtype] = np.empty(
                kernel.shape, dtype=np.result_type(x.dtype, np.complex64)
            )
        if not padded:
            out = None if out is None else out.reshape(shape)
            return convolve(x, kernel, spectrum=spectrum, out=out).reshape(-1)
        buffer = buffers.get(x.dtype)
        if buffer is None:  # the padding of the embedding stays zero for good
            work = substrate.work_shape
            buffer = buffers[x.dtype] = (np.zeros(work, x.dtype), np.empty(work, x.dtype))
        full = convolve(substrate.embed(x, out=buffer[0]), kernel, spectrum=spectrum, out=buffer[1])
        patch = substrate.crop(full)
        if out is None:
            return patch.reshape(-1)  # a copy: the patch is not contiguous
        out.reshape(shape)[...] = patch
        return out

    return apply


def _direct(substrate, which, like):
    """``(kernel, spectrum, pocketfft binding or None, workers)`` of an operator for the
    NumPy flat fields of ``like``'s dtype (the same transform as :func:`convolve`)."""
    kernel = substrate.multipliers(like)[which]
    spectrum = np.empty(kernel.shape, dtype=np.result_type(like.dtype, np.complex64))
    return kernel, spectrum, _pocketfft(), default_workers(like.size)


def compliance_operator(substrate, *, work_grid: bool = False):
    """p -> G p: deflection (length) of a pressure field (pressure); a rigid mean gives a
    zero mean. On the patch (exact, periodic or free) or on the work grid."""
    return _fourier_operator(substrate, _COMPLIANCE, work_grid)


def stiffness_operator(substrate, *, work_grid: bool = False):
    """w -> K w: elastic pressure of a deflection; with a rigid mean its mean is zero.

    On the patch of a free boundary this is the padded stiffness restricted to the patch
    (symmetric positive definite, an approximate inverse of the patch's compliance: the
    hard-wall solver's preconditioner); on the work grid it is exact.
    """
    return _fourier_operator(substrate, _STIFFNESS, work_grid)


def point_response(substrate, like):
    """Deflection (length) under a unit pressure on site (0, 0), on the work grid.

    The inverse FFT of the compliance multipliers (the FFT of a unit point force is
    exactly 1): half a convolution. On ``like``'s backend, device and dtype. Site
    ``(i, j)`` of the patch moves ``x`` by ``response[(x - i) mod work_shape]``.
    """
    xp = array_namespace(like)
    complex_dtype = xp.complex64 if like.dtype == xp.float32 else xp.complex128
    compliance = substrate.multipliers(like).compliance
    return irfft2(xp.astype(compliance, complex_dtype), tuple(substrate.work_shape))


def on_work_grid(substrate, field):
    """A field of the patch (2D) as a flat field of the work grid (zero off the patch)."""
    xp = array_namespace(field)
    return xp.reshape(substrate.embed(field), (-1,))


def patch_sites(substrate, like):
    """Flat boolean mask of the patch on the work grid (``like``'s backend and device),
    or None when the work grid is the patch (periodic)."""
    if not _padded(substrate):
        return None
    xp = array_namespace(like)
    ones = xp.ones(tuple(substrate.shape), dtype=xp.bool, device=array_device(like))
    mask = xp.zeros(tuple(substrate.work_shape), dtype=xp.bool, device=array_device(like))
    return xp.reshape(substrate.embed(ones, out=mask), (-1,))


def in_single_precision(operator):
    """The linear operator ``operator`` evaluated in float32, its result in the input's dtype.

    For preconditioners only: a preconditioner need not be exact, and a float32 FFT pair
    costs 0.4-0.7 of a float64 one (scipy.fft, 256²-2048²). Its rounding
    (~1e-7 relative to the result) perturbs search directions, never a residual.
    """

    def apply(x):
        xp = array_namespace(x)
        if x.dtype == xp.float32:
            return operator(x)
        return xp.astype(operator(xp.astype(x, xp.float32)), x.dtype)

    return apply


def in_precision(operator, dtype):
    """The linear operator ``operator`` evaluated and returned in ``dtype``.

    For the increments and search directions of a mixed-precision iteration, which casts
    back only what it needs (a float32 result is a smaller array to read).
    """

    def apply(x, out=None):
        xp = array_namespace(x)
        return operator(x if x.dtype == dtype else xp.astype(x, dtype), out=out)

    return apply
