"""Operators and input checks shared by the solvers (flat float arrays on the grid)."""

from __future__ import annotations

import math

import numpy as np

from .._backend import (
    array_namespace,
    convolve,
    dtype_name,
    irfft2,
    is_numpy_array,
    to_device,
)
from .._validate import ParameterError, heights2d, real_array, tolerance
from .result import SolveStatus

__all__ = [
    "DEFAULT_TOL",
    "JOINING_KEEPS_DIRECTIONS",
    "POINT_CORRECTIONS",
    "RESUME_PRECONDITIONING",
    "RELIABLE_DROP",
    "RELIABLE_EVERY",
    "ReliableUpdates",
    "StallGuard",
    "StepKind",
    "anderson_bjorck",
    "bracketed_root",
    "check_hard_wall_offset",
    "check_problem",
    "compliance_operator",
    "dot",
    "false_position",
    "illinois",
    "in_precision",
    "in_single_precision",
    "lowest_hard_wall_offset",
    "point_response",
    "stiffness_operator",
    "stopping",
    "total",
]


def _fourier_operator(substrate, which: int):
    """``apply(x_flat, out=None)``: a flat field through one of the substrate's Fourier
    multipliers. On NumPy it keeps one spectrum array per dtype for all its calls (so an
    operator is made per solve and not shared between threads); ``out`` (NumPy, flat,
    x's dtype) receives the result."""
    shape = substrate.shape
    spectra = {}

    def apply(x_flat, out=None):
        xp = array_namespace(x_flat)
        kernel = substrate._arrays(x_flat)[which]  # cached per backend and dtype
        x = xp.reshape(x_flat, shape)
        if not is_numpy_array(x_flat):
            return xp.reshape(convolve(x, kernel), (-1,))
        spectrum = spectra.get(x.dtype)
        if spectrum is None:
            spectrum = spectra[x.dtype] = np.empty(
                kernel.shape, dtype=np.result_type(x.dtype, np.complex64)
            )
        out = None if out is None else out.reshape(shape)
        return convolve(x, kernel, spectrum=spectrum, out=out).reshape(-1)

    return apply


def point_response(substrate, like):
    """Deflection (length, substrate's shape) under a unit pressure on site (0, 0).

    The inverse FFT of the compliance multipliers (the FFT of a unit point force is
    exactly 1): half a convolution. On ``like``'s backend, device and dtype.
    """
    xp = array_namespace(like)
    complex_dtype = xp.complex64 if like.dtype == xp.float32 else xp.complex128
    compliance = substrate._arrays(like)[1]
    return irfft2(xp.astype(compliance, complex_dtype), substrate.shape)


def compliance_operator(substrate):
    """p -> G p: deflection (length) of a pressure field; the rigid mean gives zero mean."""
    return _fourier_operator(substrate, 1)


def stiffness_operator(substrate):
    """w -> K w: elastic pressure of a deflection; with a rigid mean its mean is zero."""
    return _fourier_operator(substrate, 0)


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


def false_position(a, f_a, b, f_b) -> float:
    """The regula falsi point of the bracket ``[a, b]`` (its midpoint if that falls outside)."""
    d = f_b - f_a  # 0 only for a degenerate (e.g. NaN-valued) bracket: bisect then
    x = (a * f_b - b * f_a) / d if d != 0 else math.nan
    return x if min(a, b) < x < max(a, b) else 0.5 * (a + b)


def anderson_bjorck(a, f_a, b, f_b, x, f):
    """Bracket update of the Anderson-Björck method: ``(a, f_a, b, f_b)`` after ``f(x)``.

    ``[a, b]`` brackets a root (``f_a``, ``f_b`` of opposite signs) and ``b`` is the newest
    point; ``x`` becomes the new ``b``. If ``f`` has the sign of ``f_b``, ``a`` is kept and
    its value scaled by ``m = 1 - f / f_b`` (0.5 if that is not positive), the slope of
    the parabola through the three points, which keeps regula falsi from converging from
    one side only (Anderson & Björck, BIT 13, 253 (1973)).
    """
    if (f > 0) != (f_b > 0):
        return b, f_b, x, f
    m = 1.0 - f / f_b if f_b != 0 else 0.0  # f_b = 0: a NaN target; never divide by it
    return a, f_a * (m if m > 0 else 0.5), x, f


def bracketed_root(f, a, f_a, b, f_b, close_enough, max_eval: int):
    """A root of ``f`` in the bracket ``[a, b]`` (``f_a``, ``f_b`` of opposite signs).

    Regula falsi with :func:`anderson_bjorck`'s updates, and a bisection after any point
    that stayed on the side of the one before and did not halve ``|f|``: regula falsi
    alone crawls where ``f`` spans orders of magnitude (a line search's trial step deep
    into a repulsive core), taking steps that barely change ``f``. Stops at the first
    ``x`` with ``close_enough(f(x))``, or after ``max_eval`` evaluations. Returns
    ``(x, evaluations)``, ``x`` the last point evaluated (``b`` if none was).

    In the smooth solver's line search (benchmark approach, ℓa = 0.05, 256²) this took 2.9
    evaluations on average where Illinois' regula falsi took 3.9, and at most 15 where
    that took up to 55 (steps into the 9-3 core, where |phi'| reaches 1e15 |phi'(0)|).
    """
    x, bisect = b, False
    for k in range(1, max_eval + 1):
        x = 0.5 * (a + b) if bisect else false_position(a, f_a, b, f_b)
        fx = f(x)
        if close_enough(fx):
            return x, k
        bisect = (fx > 0) == (f_b > 0) and abs(fx) > 0.5 * abs(f_b)
        a, f_a, b, f_b = anderson_bjorck(a, f_a, b, f_b, x, fx)
    return x, max_eval


def illinois(a, f_a, b, f_b, x, f, side):
    """Bracket update of the Illinois method: ``(a, f_a, b, f_b, side)`` after ``f(x)``.

    ``x`` replaces the end whose value has the sign of ``f``; when the same end is
    replaced twice in a row, the other end's value is halved, which keeps regula falsi
    from stalling (Dowell & Jarratt, BIT 11, 168 (1971)).
    """
    if (f > 0) == (f_a > 0):
        return x, f, b, (0.5 * f_b if side == -1 else f_b), -1
    return a, (0.5 * f_a if side == 1 else f_a), x, f, 1


#: Up to this many sites changed by a projection, the hard-wall solver adds their point
#: responses (each a pass over the grid) instead of convolving the correction (measured
#: break-even against a float32 convolution: 2-3 sites at 1024²-2048², 4-8 at 128²-512²).
POINT_CORRECTIONS = 2

#: When interpenetrating sites join a preconditioned hard-wall step and they are at most
#: this fraction of the contact set, the conjugate directions are kept (the new sites
#: start with none), as they are when sites leave; more restart them. Restarting on every
#: join made the late iterations steepest descent whenever a site or two joined each time
#: (benchmark surface: 82 → 46 iterations at 2048², 34 → 29 at 512²; 1 % was the best of
#: 0-100 % over 1008 small cases, none of which fails to converge).
JOINING_KEEPS_DIRECTIONS = 0.01

#: After a preconditioned hard-wall step lost the whole contact set (and the solve
#: restarted from the overlap or from uniform pressure), the steps stay plain until the
#: residual is below this fraction of the one before the loss: repeating the losing path
#: is then impossible, and the preconditioner returns for the rest (plain to the end took
#: up to 1800 iterations with most of a 256x512 surface in contact; this rule, 62-378;
#: 0.3 was the best of 0.1, 0.3 and 0.5).
RESUME_PRECONDITIONING = 0.3


class StepKind:
    """Whether the hard wall's steps are preconditioned, shared by its two loops.

    Preconditioned when the problem has a preconditioner, except for a while after a
    preconditioned step lost the whole contact set: the restart then takes plain steps
    (they cannot repeat the losing path) until the residual is below
    :data:`RESUME_PRECONDITIONING` of its value before the loss.
    """

    def __init__(self, precondition: bool):
        self.pre, self.resume_below = precondition, -math.inf

    def lost_contact(self, residual: float) -> None:
        """The loop restarts because the whole contact set was lost."""
        if self.pre:
            self.pre, self.resume_below = False, RESUME_PRECONDITIONING * residual

    def resumes(self, residual: float) -> bool:
        """Whether preconditioned steps return with this one (directions must restart)."""
        if self.pre or residual >= self.resume_below:
            return False
        self.pre = True
        return True


#: Mixed-precision iterations ("reliable updates"): an exact evaluation of what the
#: single-precision increments update is redone once the residual has fallen by this
#: factor since the last one (their drift, ~1e-7 of the distance travelled, is then far
#: below the residual) ...
RELIABLE_DROP = 1e-3
#: ... and at the latest after this many iterations, so that drift can never stall a solve.
RELIABLE_EVERY = 50


class ReliableUpdates:
    """When a mixed-precision iteration replaces its incremental update by an exact one.

    The iterations update a field (``G p - h``, ``K w``) by single-precision increments,
    whose rounding accumulates to ~1e-7 of the distance travelled. Call :meth:`check`
    with every residual: it answers ``"refresh"`` when an exact (float64) evaluation is
    due (the residual fell by :data:`RELIABLE_DROP` since the last one, or
    :data:`RELIABLE_EVERY` iterations passed, or the tolerance is met: convergence is
    only declared on an exact state), and ``"restart"`` on the exact state's residual
    when it exceeds twice the iterated one, i.e. the drift had overtaken the residual
    and the conjugate directions, built on the drifted one, must be restarted. The
    "reliable updates" of Sleijpen & van der Vorst (Computing 56, 141 (1996)).
    """

    def __init__(self, tol: float):
        self.tol, self.reliable, self.since, self.iterated = tol, math.inf, 0, math.inf

    def check(self, residual: float, exact: bool) -> str | None:
        if exact:
            drifted = residual > 2.0 * self.iterated
            self.reliable, self.since, self.iterated = residual, 0, math.inf
            return "restart" if drifted else None
        drop = residual <= RELIABLE_DROP * self.reliable
        if residual <= self.tol or drop or self.since >= RELIABLE_EVERY:
            self.iterated = residual
            return "refresh"
        return None

    def step(self) -> None:
        """Count an iteration of incremental updates."""
        self.since += 1


#: Default tolerance of every solver's residual, and the smallest float32 can reach
#: (measured: the residuals of all three solvers stall at 3e-7 to 6e-7 in single
#: precision; see the README).
DEFAULT_TOL = {"float64": 1e-8, "float32": 1e-6}


def check_problem(heights, substrate, tol, offset=None, device=None, dtype=None):
    """Validate the common inputs; return ``(heights, tol)`` ready for the solvers.

    The heights come back on ``device`` in ``dtype`` (float64 unless ``"float32"`` is
    asked for; NumPy heights contiguous) and the solvers then compute there. ``tol``
    None gives :data:`DEFAULT_TOL` for that precision; in float32 a tolerance below its
    floor is rejected (it could never be met).
    """
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
        return h, DEFAULT_TOL[precision]
    return h, tolerance("tol", tol, precision, DEFAULT_TOL["float32"])


class StallGuard:
    """Detects a float32 solve stuck at its rounding floor, so it stops early and says so.

    In single precision the residual cannot fall below roughly ``1e-7 * max|p| / E*``
    (more under heavy compression); without this guard such a solve would spend its
    whole iteration cap there. Active only for float32: a float64 solve is never cut
    short by it.
    """

    def __init__(self, precision: str, patience: int = 200):
        self.active = precision == "float32"
        self.patience, self.best, self.since = patience, math.inf, 0

    def __call__(self, residual: float) -> str | None:
        """The not-converged message if no new best residual came in ``patience`` calls."""
        if not self.active:
            return None
        if residual < 0.99 * self.best:
            self.best, self.since = residual, 0
            return None
        self.since += 1
        if self.since < self.patience:
            return None
        return (
            f"stalled at residual {self.best:.2g} for {self.patience} iterations: the float32 "
            "rounding floor (use dtype='float64' or a larger tol)"
        )


def stopping(done: bool, residual: float, stall, it: int, max_iter: int):
    """Why an iteration loop stops here: ``(status, message)``, or None to go on.

    ``done``: the convergence test passed; ``stall``: the loop's :class:`StallGuard`.
    """
    if done:
        return SolveStatus.CONVERGED, "converged"
    if (stalled := stall(residual)) is not None:
        return SolveStatus.STALLED, stalled
    if it >= max_iter:
        return SolveStatus.ITERATION_LIMIT, "iteration cap reached"
    return None


def lowest_hard_wall_offset(heights, substrate) -> float:
    """The smallest offset a hard wall admits (length): mean(h) with a rigid mean, else -inf.

    With a rigid uniform mode the mean deflection is zero, so the mean gap is
    ``d - mean(h)``; below ``mean(h)`` every state interpenetrates somewhere.
    """
    if not substrate.rigid_mean:
        return -math.inf
    return float(array_namespace(heights).mean(heights))


def check_hard_wall_offset(heights, substrate, offset) -> None:
    """Reject an offset below :func:`lowest_hard_wall_offset` (no impenetrable state)."""
    mean = lowest_hard_wall_offset(heights, substrate)
    if offset is None or mean == -math.inf:
        return
    xp = array_namespace(heights)
    if offset < mean - 1e-12 * (float(xp.max(xp.abs(heights))) + abs(offset)):
        raise ParameterError(
            f"offset must be >= mean(heights) = {mean:g} for a hard wall on a substrate with "
            f"a rigid mean (got {offset:g}: the surfaces would overlap everywhere)"
        )
