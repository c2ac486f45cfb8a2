"""Input checks shared by the solvers, and their default tolerances."""

from __future__ import annotations

import contextlib
import contextvars
import math

import numpy as np

from .._accelerator import to_device
from .._backend import (
    array_device,
    array_namespace,
    dtype_name,
    is_numpy_array,
    to_numpy,
)
from .._validate import ParameterError, heights2d, real_array, tolerance
from .reductions import fetch

__all__ = [
    "DEFAULT_TOL",
    "check_hard_wall_offset",
    "check_problem",
    "checked_heights",
    "default_tolerance",
    "height_statistics",
    "lowest_hard_wall_offset",
    "warm_deflection",
]


#: Default tolerance of every solver's residual, and the smallest float32 can reach
#: (measured: the residuals of all three solvers stall at 3e-7 to 6e-7 in single
#: precision; see the README).
DEFAULT_TOL = {"float64": 1e-8, "float32": 1e-6}
#: Grids up to this many sites get :data:`DEFAULT_TOL`; in float32 the default grows
#: beyond (:func:`default_tolerance`).
FLOAT32_TOL_SITES = 1 << 20


def default_tolerance(precision: str, sites: int) -> float:
    """The tolerance a solve gets when none is given (the residual: max force imbalance /
    E*, dimensionless).

    float64: :data:`DEFAULT_TOL`. float32: 1e-6 on grids up to 1024² and
    ``1e-6 * sqrt(sites / 1024²)`` beyond (4e-6 at 4096²), because the rounding floor of
    the residual grows with the grid: the float32 state of the 9-3 wall on the benchmark
    surface (lambda_L = n/2) holds its force balance to 3e-7 to 8e-7 at 256², 9.8e-7 at
    2048² and 1.7e-6 at 4096² (evaluated in float64; the adhesive loops advance the
    deflection itself and form the exact ``K w`` in float64, see :mod:`.smooth`), so 1e-6
    stalls there. Larger surfaces have larger gaps and pressures, whose float32 rounding
    sets that floor. The square root is our rule, not measured beyond 4096²; it keeps a
    margin of 2.3x over the 4096² floor. An explicit ``tol`` in float32 only has to be at
    least 1e-6.
    """
    if precision != "float32" or sites <= FLOAT32_TOL_SITES:
        return DEFAULT_TOL[precision]
    return DEFAULT_TOL["float32"] * math.sqrt(sites / FLOAT32_TOL_SITES)


#: The heights a caller has checked already (see :func:`checked_heights`).
_CHECKED: contextvars.ContextVar = contextvars.ContextVar("checked_heights", default=None)
#: ... and their statistics (see :func:`height_statistics`), or None.
_STATISTICS: contextvars.ContextVar = contextvars.ContextVar("height_stats", default=None)


@contextlib.contextmanager
def checked_heights(heights, statistics=None):
    """Within the block, :func:`check_problem` trusts ``heights`` (this very array, which
    it returned): a caller that solves many problems on it (load control's inner solves)
    does not check them again (on a GPU each check waits for the device).
    ``statistics``: :func:`height_statistics` of them, which the solvers then reuse."""
    token = _CHECKED.set(heights)
    token_stats = _STATISTICS.set(statistics)
    try:
        yield heights
    finally:
        _STATISTICS.reset(token_stats)
        _CHECKED.reset(token)


def height_statistics(heights) -> dict[str, float]:
    """The heights' mean, largest magnitude (``top``), largest value (``max``) and rms
    about the mean (``std``, of the flat array as the solvers take it), in one transfer;
    those of :func:`checked_heights`' block when given there (no transfer)."""
    known = _STATISTICS.get()
    if known is not None and heights is _CHECKED.get():
        return known
    xp = array_namespace(heights)
    values = fetch(xp, [xp.mean(heights), xp.max(xp.abs(heights)), xp.max(heights),
                        xp.std(xp.reshape(heights, (-1,)))])  # fmt: skip
    return dict(zip(("mean", "top", "max", "std"), values, strict=True))


def check_problem(heights, substrate, tol, offset=None, device=None, dtype=None):
    """Validate the common inputs; return ``(heights, tol)`` ready for the solvers.

    The heights come back on ``device`` in ``dtype`` (float64 unless ``"float32"`` is
    asked for; NumPy heights contiguous) and the solvers then compute there. ``tol``
    None gives :func:`default_tolerance` for that precision and grid; in float32 a tolerance
    below 1e-6 is rejected (it could never be met).
    """
    if heights is _CHECKED.get():  # checked by the caller (see checked_heights)
        h = to_device(heights, device, dtype or "float64")
    else:
        heights = real_array("heights", heights)  # before to_device casts complex or bool
        h = heights2d("heights", to_device(heights, device, dtype or "float64"))
    if is_numpy_array(h):
        h = np.ascontiguousarray(h)
    if tuple(h.shape) != substrate.shape:
        raise ParameterError(
            f"heights shape {h.shape} differs from substrate shape {substrate.shape}"
        )
    if offset is not None and not math.isfinite(float(offset)):
        raise ParameterError(f"offset must be finite, got {offset!r}")
    precision = dtype_name(h)
    if tol is None:
        return h, default_tolerance(precision, math.prod(h.shape))
    return h, tolerance("tol", tol, precision, DEFAULT_TOL["float32"])


def lowest_hard_wall_offset(heights, substrate) -> float:
    """The smallest offset a hard wall admits (length): mean(h) with a rigid mean, else -inf.

    With a rigid uniform mode the mean deflection is zero, so the mean gap is
    ``d - mean(h)``; below ``mean(h)`` every state interpenetrates somewhere.
    """
    if not substrate.rigid_mean:
        return -math.inf
    return float(array_namespace(heights).mean(heights))


def check_hard_wall_offset(heights, substrate, offset, also=()) -> list[float]:
    """Reject an offset below :func:`lowest_hard_wall_offset` (no impenetrable state).

    ``also``: the caller's device scalars, returned as floats from the same transfer;
    or the names of :func:`height_statistics` (their values, from the statistics that a
    :func:`checked_heights` block gives: no transfer).
    """
    xp = array_namespace(heights)
    known = _STATISTICS.get() if heights is _CHECKED.get() else None
    if known is not None and all(isinstance(x, str) for x in also):
        mean, top, also = known["mean"], known["top"], [known[x] for x in also]
        if offset is None or not substrate.rigid_mean:
            return also
    else:
        flat = xp.reshape(heights, (-1,))
        named = {"mean": xp.mean, "top": lambda x: xp.max(xp.abs(x)), "max": xp.max}
        named["std"] = xp.std
        also = [named[x](flat) if isinstance(x, str) else x for x in also]
        if offset is None or not substrate.rigid_mean:
            return fetch(xp, also)
        # lowest_hard_wall_offset (the mean) and max|h| in one transfer (a GPU waits once)
        mean, top, *also = fetch(xp, [xp.mean(heights), xp.max(xp.abs(heights)), *also])
    # the mean's rounding in the heights' precision (float32: ~1e-7 of max|h|), so that
    # float32 accepts the offsets float64 accepts (d = 0 on a mean-zero surface)
    slack = max(1e-12, 64 * float(xp.finfo(heights.dtype).eps))
    if offset < mean - slack * (top + abs(offset)):
        raise ParameterError(
            f"offset must be >= mean(heights) = {mean:g} for a hard wall on a substrate with "
            f"a rigid mean (got {offset:g}: the surfaces would overlap everywhere)"
        )
    return also


def warm_deflection(initial, substrate, heights, compliance):
    """The flat deflection on the work grid that a warm start gives, a fresh array.

    ``initial`` is a :class:`ContactResult` (its ``deflection``) or an array of the
    patch's shape; it comes on the heights' backend, device and dtype. Periodic: that
    deflection. Free boundary (the work grid is padded): a result's pressure through the
    work grid's ``compliance`` (so the padding's deflection fits it), else the array's
    deflection, zero on the padding.
    """
    xp = array_namespace(heights)
    padded = tuple(substrate.work_shape) != tuple(substrate.shape)
    source = initial.pressure if padded and hasattr(initial, "pressure") else initial
    w = getattr(source, "deflection", source)
    w = w if xp is array_namespace(w) else to_numpy(w)
    w = xp.asarray(w, device=array_device(heights), copy=True)
    w = xp.reshape(xp.astype(w, heights.dtype), (-1,))
    if w.shape[0] != heights.shape[0] * heights.shape[1]:
        raise ParameterError(f"initial must have the substrate's shape {substrate.shape}")
    if not padded:
        return w
    w = xp.reshape(substrate.embed(xp.reshape(w, tuple(heights.shape))), (-1,))
    return compliance(w) if source is not initial else w
