r"""Constrained conjugate gradients for the non-adhesive hard wall.

Minimises the complementary energy :math:`\tfrac12 p^T G p - p^T (h - d)` over
pressures :math:`p \ge 0` (Polonsky & Keer, Wear 231, 206 (1999)), where ``G`` is the
substrate's Green's function applied by FFT: periodic, or on a free boundary the exact
free-space one of Hockney's zero-padded grid, cropped to the patch
(:mod:`roughcontact.elastic.operator`); the preconditioner's ``K`` is then the padded
grid's stiffness restricted to the patch. Under load control the mean
pressure is held at the requested load and the offset ``d`` is the Lagrange multiplier
of that constraint; under displacement control ``d`` is given.

Convergence measure (``residual``): the largest violation of the Signorini conditions,

.. math::
    r = \max\Big(\max_{p_i > 0} |g_i|,\; \max_{p_i = 0} (-g_i)\Big) \,/\, h_{rms},

i.e. the largest gap on a loaded site or interpenetration on an unloaded one, relative
to the rms height (``pixel_size`` for a flat surface). Pressures satisfy ``p >= 0``
exactly and, under load control, the load exactly.

Preconditioning (default on): the conjugate directions are built from
:math:`z = P_c K P_c\, g` instead of the gap ``g`` on the contact set ``c`` (``K`` the
substrate's stiffness, the inverse of ``G`` on the whole grid, ``P_c`` the restriction to
``c``; under load control ``z`` is made mean-free on ``c``), the FFT preconditioner of
Vollebregt (J. Comput. Phys. 257, 333 (2014)). The condition number of ``G`` on a contact
patch of radius ``R`` grows like ``R`` (its uniform mode is soft, its pixel modes stiff);
``P_c K P_c`` inverts it up to boundary effects, so the iteration count grows far less
with the grid (benchmark surface at 1e-3 E*: 96 → 33 iterations at 1024², 329 → 46 at
2048²; ``benchmarks/hardwall.py``). Three details make the preconditioned steps as
robust as the plain ones (without them, displacement control with a large contact set
could stall or cycle until the iteration cap):

* With a rigid uniform mode ``K`` has none (its stiffness is infinite, stored as zero),
  so under displacement control the gap's mean on ``c``, which only a change of the
  contact set can remove, would barely enter ``z``; the preconditioner gives that mode
  the sites' self-stiffness :math:`K_{ii}`, ``z += K_ii (1^T P_c g) / n``.
* Polonsky & Keer's I_ol rule gives an unloaded interpenetrating site the pressure
  ``-tau g`` of a plain step; with preconditioned steps these sites instead join the
  set the step acts on, so their pressure comes from ``z`` and the line minimisation
  (a site-local pressure overshoots when a whole region interpenetrates). When they are
  few (:data:`.pk_rules.JOINING_KEEPS_DIRECTIONS`) the conjugate directions are kept.
* If a preconditioned step ever clips every loaded site (all contact lost), the solve
  restarts with plain steps, so that it cannot repeat the same path, until the residual
  is below :data:`.pk_rules.RESUME_PRECONDITIONING` of its value before the loss.

Nested iteration (default on, ``nested=True``): a cold solve on a grid of at least
:data:`NESTED_MIN_SIZE` points with even sides starts from the same problem solved on the
grid coarsened 2×2 (block means of the heights, twice the pixel size, the same load or
offset; recursively, to tolerance :data:`NESTED_TOL`), its pressure copied to each
block's four sites. The fine grid then only corrects the contact set at its own scale
(benchmark surface: 33 → 20 iterations at 1024², 46 → 27 at 2048²; 1.3-2.1× faster to
the solution at 256²-2048², the coarse solves included; ``benchmarks/hardwall.py``).

Cost per iteration: one FFT convolution for the step (``G`` of the search direction),
one for the preconditioner, and a third only on iterations where the projection changed
the contact set at more than a few sites (``G`` of that correction; otherwise the
deflection is updated from the step's convolution, exact by linearity). ``precondition=
False`` gives the plain method (one convolution fewer per iteration, many more
iterations on large grids).

Mixed precision: all of these convolutions run in single precision (a float32 FFT pair
costs 0.4-0.7 of a float64 one), with "reliable updates" (Sleijpen & van der
Vorst, Computing 56, 141 (1996)). The step and correction convolutions only ever update
``G p - h`` incrementally, so their rounding (~1e-7 of the increment) accumulates to
~1e-7 of the distance travelled since the last exact evaluation. That evaluation, one
float64 convolution of the whole pressure, is redone as :class:`.loop_control.ReliableUpdates`
says (the residual fell 1000-fold, 50 iterations passed, or the tolerance is met), so
convergence is only ever declared on an exact state: the answer is as accurate as a
float64 solve (tested down to tol 1e-12 against an independent float64 deflection).

Two implementations of the same iteration, one per backend: on NumPy (the CPU) the
vector work runs on index arrays of the contact set (:mod:`._pk_sparse`; a few per cent of
the grid at small loads, so cheaper than full-grid passes on a CPU); on accelerators the
whole loop is one compiled program (:mod:`._pk_jax`, ``jax.jit`` and ``lax.while_loop``
on full-grid masks; periodic substrates, no callback, float64 inside
``jax.enable_x64``), which tests convergence on the device and returns to the host only
once it stops. JAX heights run it as they are; CuPy and other arrays that speak DLPack,
and ``device="cuda"``, reach it through :mod:`roughcontact._accelerator`, which returns
the fields in the caller's namespace. jax is imported only when such heights arrive.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

from array_api_compat import is_jax_array  # (looks at sys.modules: imports no jax)

from .._accelerator import routed
from .._backend import (
    array_device,
    array_namespace,
    dtype_name,
    is_array,
    is_numpy_array,
    to_numpy,
)
from .._validate import ParameterError
from ._pk_sparse import iterate_sparse
from .fourier import compliance_operator, in_precision, stiffness_operator
from .inputs import check_hard_wall_offset, check_problem, height_statistics
from .observables import make_result
from .result import SolveStatus

__all__ = ["polonsky_keer"]


#: Cold solves on grids of at least this many points start from the same problem solved
#: on the grid coarsened 2×2 ("nested iteration"), recursively, ...
NESTED_MIN_SIZE = 1 << 16
#: ... to this tolerance: a starting guess only.
NESTED_TOL = 1e-3


def _coarse_guess(h, substrate, load, offset, max_iter, precondition):
    """Pressure on ``h``'s grid from the problem on the grid coarsened 2×2, or None.

    The coarse heights are 2×2 block means on the substrate's ``coarsened()`` twin, with
    twice the pixel size (the same continuum problem at half the resolution; a free
    boundary stays free; block means keep mean(h), hence the
    admissible offsets), the coarse pressure is copied to the four fine sites of each
    block (and rescaled to the load by :func:`_initial_pressure`), on the heights' device.
    """
    nx, ny = h.shape
    if nx * ny < NESTED_MIN_SIZE or nx % 2 or ny % 2:
        return None
    xp = array_namespace(h)
    mx, my = nx // 2, ny // 2
    coarse = xp.mean(xp.reshape(h, (mx, 2, my, 2)), axis=(1, 3))
    sub = substrate.coarsened()
    res = polonsky_keer(
        coarse, sub, load=load, offset=offset, tol=NESTED_TOL, max_iter=max_iter,
        precondition=precondition, dtype=dtype_name(h),
    )  # fmt: skip
    p = xp.reshape(res.pressure, (mx, 1, my, 1))  # results stay on the heights' device
    return xp.reshape(xp.broadcast_to(p, (mx, 2, my, 2)), (nx, ny))


def _initial_pressure(initial, heights, substrate, load, offset):
    xp = array_namespace(heights)
    n = heights.shape[0] * heights.shape[1]
    if initial is not None:
        p0 = getattr(initial, "pressure", initial)
        if is_numpy_array(heights) or not is_array(p0):
            p0 = to_numpy(p0)  # a host array (or list) of the warm start
        p0 = xp.asarray(p0, dtype=heights.dtype, device=array_device(heights), copy=True)
        if p0.size != n:
            raise ParameterError(
                f"initial must have the substrate's shape {substrate.shape}, got {p0.size} sites"
            )
        p0 = xp.maximum(xp.reshape(p0, (-1,)), 0.0)
        total = float(xp.sum(p0))
        if load is not None:
            return p0 * (load * n / total) if total > 0 else xp.full_like(p0, load)
        if total > 0:
            return p0
    if load is not None:
        return xp.full(n, float(load), dtype=heights.dtype, device=array_device(heights))
    # displacement control: a local (Winkler) guess, E*/a0 per unit interpenetration
    scale = 0.5 * substrate.contact_modulus / substrate.pixel_size
    return xp.maximum(xp.reshape(heights, (-1,)) - offset, 0.0) * scale


@routed
def polonsky_keer(
    heights,
    substrate,
    *,
    load=None,
    offset=None,
    initial=None,
    tol=None,
    max_iter=5000,
    callback=None,
    precondition=True,
    nested=True,
    device=None,
    dtype=None,
):
    """Solve hard-wall contact by constrained conjugate gradients.

    Parameters
    ----------
    heights : (nx, ny) array
        Rigid surface heights ``h`` (length; summits point at the substrate). A JAX array
        runs the compiled loop (see the module docstring); its default precision is the
        array's own (float32 unless ``jax_enable_x64`` is on).
    substrate : Substrate (or any :class:`~roughcontact.elastic.operator.ElasticOperator`)
    load : float, optional
        Mean pressure :math:`N/A_0 \\ge 0` (pressure units). Exactly one of load/offset.
    offset : float, optional
        Offset ``d`` of the rigid surface (length); gap ``g = d - h + w``.
    initial : ContactResult or array, optional
        Warm start (its pressure; rescaled to ``load`` under load control).
    tol : float, optional
        Tolerance on the residual defined in the module docstring.
        Default 1e-8 (float64) or 1e-6 (float32, also the smallest allowed there;
        larger beyond 1024²: :func:`roughcontact.solvers.inputs.default_tolerance`).
    max_iter : int
        Iteration cap; reaching it gives ``converged=False``.
    callback : callable, optional
        ``callback(iteration, residual)`` after every iteration; return True to stop.
    precondition : bool
        Precondition the conjugate directions with the substrate's stiffness restricted
        to the contact set (see the module docstring); False gives plain Polonsky–Keer.
    nested : bool
        Without ``initial``, start from the solution of the same problem on the grid
        coarsened 2×2 (recursively, on grids of at least :data:`NESTED_MIN_SIZE` points
        with even sides; see the module docstring). ``iterations`` counts the iterations
        on this grid; ``solve_seconds`` includes the coarse solves.
    device : {None, "cpu", "cuda", "cuda:N"}, optional
        Where to compute (default: where ``heights`` live); see :func:`roughcontact.to_device`.
    dtype : {None, "float64", "float32"}, optional
        Precision of the computation (default float64); see the README for float32's
        accuracy floor.

    Returns
    -------
    ContactResult
    """
    t_start = time.perf_counter()
    if is_jax_array(heights):  # the compiled loop (jax is imported only here)
        from ._pk_jax import check_jax_inputs

        dtype = check_jax_inputs(heights, substrate, dtype, device, callback)
    h, tol = check_problem(heights, substrate, tol, offset, device, dtype)
    if (load is None) == (offset is None):
        raise ParameterError("give exactly one of load (mean pressure) or offset")
    if load is not None:
        load = float(load)
        if not math.isfinite(load) or load < 0:
            raise ParameterError(f"load must be finite and >= 0 for a hard wall, got {load!r}")
    else:
        offset = float(offset)
        check_hard_wall_offset(h, substrate, offset)
    xp = array_namespace(h)
    hf = xp.reshape(h, (-1,))
    std = None
    if is_jax_array(h):  # max and rms in one transfer (none in a path: checked_heights)
        stats = height_statistics(h)
        h_max, std = stats["max"], stats["std"]
    else:
        h_max = float(xp.max(hf))
    conv = compliance_operator(substrate)

    def result(p, u, d, it, residual, status, message):
        return make_result(
            h, substrate, xp.reshape(p, h.shape), xp.reshape(u, h.shape), d, it, residual,
            status, message, tol, "polonsky-keer", time.perf_counter() - t_start,
        )  # fmt: skip

    if load == 0.0 or (offset is not None and substrate.rigid_mean and offset >= h_max):
        # no contact: nothing to solve (the rigid surface just touches or is apart)
        zero = xp.zeros_like(hf)
        d = h_max if offset is None else offset
        return result(zero, zero, d, 0, 0.0, SolveStatus.CONVERGED, "no contact")

    if initial is None and nested:
        initial = _coarse_guess(h, substrate, load, offset, max_iter, precondition)
    p = _initial_pressure(initial, h, substrate, load, offset)
    fast = xp.float32  # the convolutions' precision (see "Mixed precision" above)
    problem = _Problem(
        hf=hf,
        shape=tuple(h.shape),
        conv=conv,
        fast_dtype=fast,
        fast_conv=conv if h.dtype == fast else in_precision(conv, fast),
        target=None if load is None else load * hf.shape[0],
        offset=offset,
        scale=(float(xp.std(hf)) if std is None else std) or substrate.pixel_size,
        winkler=0.5 * substrate.contact_modulus / substrate.pixel_size,
        precondition=in_precision(stiffness_operator(substrate), fast) if precondition else None,
        site_stiffness=substrate.self_stiffness,
        rigid_mean=substrate.rigid_mean,
        tol=tol,
        max_iter=max_iter,
        callback=callback,
    )
    if is_jax_array(h):
        from ._pk_jax import iterate_jax

        p, u, it, residual, status, message, d = iterate_jax(p, problem, substrate)
        return result(p, u, d, it, residual, status, message)
    p, u, it, residual, status, message = iterate_sparse(p, problem, substrate)
    if u is None:  # the last state was updated incrementally: evaluate it exactly
        u = conv(p)
    c = p > 0
    if load is not None and bool(xp.any(c)):
        d = -float(xp.sum(xp.where(c, u - hf, 0.0))) / float(xp.sum(xp.astype(c, h.dtype)))
    else:
        d = offset if offset is not None else h_max
    return result(p, u, d, it, residual, status, message)


@dataclass(frozen=True)
class _Problem:
    """What both iteration loops need: heights, operator, control and stopping rules."""

    hf: object  # flat heights
    shape: tuple  # the grid
    conv: object  # p -> G p (exact, in the heights' precision)
    fast_dtype: object  # the precision of the two below
    fast_conv: object  # p -> G p in fast_dtype (for increments only)
    target: float | None  # total pressure (load control) or None
    offset: float | None  # displacement control
    scale: float  # residual normalisation (length)
    winkler: float  # local stiffness for restarts from overlap (pressure/length)
    precondition: object  # g -> K g (the stiffness) in fast_dtype, or None (plain)
    site_stiffness: float  # K_ii (pressure/length): I_ol and the uniform mode, preconditioned
    rigid_mean: bool  # the substrate's uniform mode is rigid (K has none)
    tol: float
    max_iter: int
    callback: object
