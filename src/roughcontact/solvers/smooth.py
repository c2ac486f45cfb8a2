r"""Energy minimisation for smooth (non-convex) interactions, under displacement control.

Minimises the total energy per the substrate's nominal area

.. math:: E(w) = E_{el}(w) + a_0^2 \sum_i V(d - h_i + w_i)

over the deflection ``w`` at fixed offset ``d``, by nonlinear conjugate gradients
(Polak–Ribière+) with a line search and a block preconditioner built from the
Hessian :math:`H = K + \mathrm{diag}\,V''(g)`:

* on the *stiff* sites, where the interaction's stiffness exceeds a tenth of the
  substrate's self-stiffness, :math:`V''(g_i) > 0.1\,K_{ii}` (in contact, and the inner
  edge of the attractive well), the diagonal :math:`1/(K_{ii} + V''(g_i))`;
* on all other sites the substrate's Green's function :math:`K^{-1}` (the Fourier
  preconditioning of Bugnicourt et al., Tribol. Int. 119, 145 (2018), and the
  mass-weighting of Zhou, Moseler & Müser, Phys. Rev. B 99, 144103 (2019)), applied
  to the residual restricted to those sites.

With the Green's function alone, the largest eigenvalue of the preconditioned Hessian is
:math:`\approx 1 + V'' R / E^*` for a contact patch of radius ``R`` (the compliance of a
large patch is far above that of its sites' springs), so it grows with the patch size
and hence with the grid (at the last state of the benchmark approach, 256² / 512² / 1024²:
18.7 / 35.2 / 55.1 for ℓa = 0.005, 31 / 70 / 121 for ℓa = 0.05). The block preconditioner
cuts it to 3.3-6.0, with the smallest eigenvalue almost unchanged, which halves the
iterations at 512² and 1024² (``benchmarks/spectrum.py``, ``benchmarks/adhesive.py``).
That smallest eigenvalue (0.19 / 0.04 / 0.10 and 0.09 / 0.06 / 0.02) belongs to a
long-wavelength mode of the attractive rings, where V'' < 0 brings the state close to an
instability; no preconditioner built from ``K`` removes it, and it limits the convergence
rate once the contact set has settled. The stiff set and the diagonal are computed from the
current gap at every ``refresh_every``-th iteration (the conjugate directions are kept;
refreshing every iteration costs more iterations than it saves), and at the first
iteration of a warm start. From a cold start (no ``initial``) the first
``refresh_every - 1`` iterations use the Green's function alone, whose steps move whole
regions coherently and so set up the elastic field around the contacts first. (Starting
cold with the block preconditioner moves the stiff sites alone, and a stiff,
short-ranged wall then captures their neighbours in a metastable state of higher energy.)

Per iteration the solver needs two FFT convolutions, the preconditioner (Green's
function on the soft sites) and the elastic pressure ``K z`` of the preconditioned
gradient; with no stiff site (before contact) the second is not needed, because then
:math:`K K^{-1}` is the identity on the non-uniform modes. Both run in single precision
(a float32 convolution costs 0.4-0.7 of a float64 one): the preconditioner only
steers the search direction, and ``K z`` only updates the elastic pressure ``K w``
incrementally, so its rounding (~1e-7 of the increment) accumulates to ~1e-7 of the
distance travelled. ``K w`` is recomputed exactly (float64) when
:class:`.loop_control.ReliableUpdates` says (the residual fell 1000-fold since the last exact
evaluation, 50 iterations passed, or the tolerance is met), so the answer is that of a
float64 solve (tested down to tol 1e-12). On NumPy grids where the FFT runs on one
thread (2^17 to 2^19 points) and a second core is free, ``K z`` runs on a background
thread while the line search selects its band of sites and evaluates the curvature there
(same operations, same results; :func:`.._backend.overlaps_fft`). The step length
minimises the energy along the line to :data:`LINE_SEARCH_RTOL` (cheap because the
elastic energy is quadratic along the line and the interaction is local). (With the
earlier Green's-function preconditioner, preconditioned L-BFGS with the same line search
took the same number of iterations as conjugate gradients.)

The vector work around the two convolutions is more than half of an iteration's time
on a CPU at 256²-512², so it is kept lean: the gap is the iterate (the deflection is
formed only for an exact ``K w``; in float32 the deflection is advanced beside it and
``K w`` is formed from it in float64, because the gap's own rounding, ulp(max gap), and a
float32 FFT's error set a residual floor of ~4e-6 E* at 4096²: 1.7e-6 with the deflection
and the float64 ``K w``), the interaction pressure is held only on the line
search's band of sites that can feel the interaction (zero elsewhere; on NumPy a band
kept over iterations, :class:`._inplace.StickyBand`, whose gap and curvature come from
the last line search's trial, the law's pressure and curvature evaluated together), the
block preconditioner of a large stiff set applied with grid-sized factors
(:func:`._block._dense_blocks`), the preconditioner's mean comes from sums it already
needs, the line search's elastic slope
``s.K w`` comes from the directional derivative and the band's pressure, and on NumPy
every full-grid update writes into arrays allocated once per solve (:mod:`._inplace`):
1.3-1.5x less time per iteration than the same steps with a temporary per expression.

This module is the NumPy (CPU) loop. On accelerators the same method runs as one
compiled program (:mod:`._smooth_jax`, with the rules of :mod:`.smooth_rules` shared),
reached by JAX heights, by arrays of other libraries through DLPack and by
``device="cuda"`` (:mod:`roughcontact._accelerator`).

Convergence measure (``residual``): the largest force imbalance per unit area,
``max |K w - p_int(g)|`` (excluding the uniform mode when it is rigid), divided by the
contact modulus. Everything else in the conventions of the README ('The model').

A free boundary (``Substrate(..., periodic=False)``): the deflection is the variable on
the whole zero-padded work grid (``substrate.work_shape``), with the elastic energy of the
padded grid's stiffness and the interaction on the patch only (the heights' grid, the
work grid's corner); at equilibrium the padding carries no pressure (the residual includes
it), so the deflection of the patch is the free-space one of the patch's pressure
(:mod:`roughcontact.elastic.operator`; the idea of ContactMechanics'
``FreeFFTElasticHalfSpace``). A warm start from a result rebuilds the padding's deflection
from the result's pressure; it then starts as a cold start does, with the Green's
function alone: a change of offset moves the whole patch into the half-space, which those
steps do coherently, while the block preconditioner's local diagonal on the contact sites
crawls there (no rigid mean absorbs it as in the periodic case; measured, Hertz sphere on
64², ℓa = 0.05: a jump of the offset by 1.4 a0 took 614 iterations with the block
preconditioner at once and 39 without, load control 3410 and 345). The same method on
four times the sites: iterations comparable to a periodic solve, each about four times
the cost.
"""

from __future__ import annotations

import functools
import math
import time

import numpy as np
from array_api_compat import is_jax_array  # (looks at sys.modules: imports no jax)

from .._accelerator import routed
from .._backend import dtype_name, overlaps_fft
from .._validate import ParameterError
from ._block import (  # noqa: F401 - STIFF_FRACTION, _precondition, _stiff_sites: public here
    DENSE_FRACTION,
    STIFF_FRACTION,
    _dense_blocks,
    _direction_stiffness,
    _precondition,
    _stiff_sites,
)
from ._free_mean import FreeMean
from ._inplace import BAND_MARGIN, StickyBand, Workspace
from .adhesive_rules import floor_verdict, physical_pressure_scale, state_verdict
from .fourier import compliance_operator, on_work_grid, patch_sites, stiffness_operator
from .inputs import check_problem, warm_deflection
from .line_search import line_minimum
from .loop_control import ReliableUpdates, StallGuard, stopping
from .observables import make_result
from .reductions import dot as _dot
from .reductions import largest, total
from .result import SolveStatus
from .smooth_rules import EPS64 as _EPS64
from .smooth_rules import (  # the rules shared with the compiled loop (:mod:`._smooth_jax`)
    FLOOR_PATIENCE,
    FLOOR_ULPS,
    GUESS_MAX,
    LINE_SEARCH_RTOL,
    REFRESH_EVERY,
    RESTART_EVERY,
)

__all__ = ["minimize_energy"]


class FloorGuard:
    """Stops a float64 solve stuck at its rounding floor early, and says why.

    The residual ``max |K w - p_int| / E*`` is a difference of pressures of size
    ``p = max |p_int|``, each rounded to float64: it cannot fall much below ``p eps / E*``
    (``eps = 2**-52``; measured: 1 to 15 such units). Under deep compression (~1e8 E* and
    more) that floor lies above ``tol``, and a solve used to spend its whole iteration cap
    there (256², 1.3e13 E*: 0.7 floors from iteration 100 on). The guard stops the solve when
    the best residual has not halved over :data:`FLOOR_PATIENCE` iterations and is within
    :data:`FLOOR_ULPS` floors of its own pressure; what that means is judged on the
    *physical* scale ``physical_scale()`` (E*·h'rms or the law's largest attraction,
    :func:`.adhesive_rules.floor_verdict`), never on the state's own maximum: ``kind``
    "stalled" (:attr:`SolveStatus.STALLED`) or "runaway" (:attr:`SolveStatus.RUNAWAY`:
    uniform p = 3.7e13 E* once came back as "stalled ... as accurate as float64 allows").
    Without ``physical_scale`` the own pressure stands for it. A normal solve is never
    stopped by it. float32 keeps ``stall`` (:class:`.loop_control.StallGuard`).
    """

    status = SolveStatus.STALLED  # (what :func:`.loop_control.stopping` reports; the
    # loop turns it into RUNAWAY where ``kind`` says so)

    def __init__(self, stall, precision, pressure_scale, contact_modulus, tol,
                 physical_scale=None):  # fmt: skip
        self.stall, self.scale = stall, pressure_scale  # scale(): max |p_int| now
        self.physical = physical_scale
        self.active = precision == "float64"
        self.modulus, self.tol = contact_modulus, tol
        self.reference, self.best, self.since = math.inf, math.inf, 0
        self.kind = None  # "stalled" or "runaway" once it has stopped the solve

    def __call__(self, residual: float) -> str | None:
        """The not-converged message when the solve is stuck at the floor, else None."""
        if (message := self.stall(residual)) is not None or not self.active:
            self.kind = None if message is None else "stalled"
            return message
        self.best = min(self.best, residual)
        if self.best < 0.5 * self.reference:
            self.reference, self.since = self.best, 0
            return None
        self.since += 1
        if self.since < FLOOR_PATIENCE:
            return None
        pressure = self.scale()
        floor = _EPS64 * pressure / self.modulus
        if not self.best <= FLOOR_ULPS * floor:  # slow, but above the floor: a new window
            self.reference, self.since = self.best, 0
            return None
        physical = pressure if self.physical is None else self.physical()
        self.kind, message = floor_verdict(
            self.best, pressure, physical, self.modulus, self.tol, FLOOR_PATIENCE
        )
        return message


def _exact_kw(elastic_pressure, w, out=None):
    """``K w`` in ``w``'s dtype; float32 deflections are convolved in float64 (a float32
    FFT's own error, ~1e-7 log2(sites) of the largest pressure, is a residual floor)."""
    if w.dtype != np.float32:
        return elastic_pressure(w, out=out)
    exact = elastic_pressure(w.astype(np.float64))
    if out is None:
        return exact.astype(np.float32)
    np.copyto(out, exact, casting="same_kind")
    return out


def _local(evaluate, cutoff, gap):
    """``evaluate(gap)`` (the interaction's pressure or curvature) only where the gap is
    inside the cutoff; zero beyond it, where every law vanishes. ``gap``: the patch."""
    if not math.isfinite(cutoff):
        return evaluate(gap)
    inside = gap < cutoff
    out = np.zeros_like(gap)
    out[inside] = evaluate(gap[inside])
    return out


@routed
def minimize_energy(
    heights,
    substrate,
    interaction,
    *,
    offset,
    initial=None,
    tol=None,
    max_iter=5000,
    callback=None,
    restart_every=RESTART_EVERY,
    refresh_every=REFRESH_EVERY,
    device=None,
    dtype=None,
    load=None,
):
    """Solve a smooth-interaction contact state at fixed ``offset`` (or ``load``).

    Parameters
    ----------
    heights : (nx, ny) array
        Rigid surface heights (length).
    substrate : Substrate (or any :class:`~roughcontact.elastic.operator.ElasticOperator`)
    interaction : object with ``pressure(gap)``, ``curvature(gap)``, ``energy(gap)``,
        ``classify(gap)``, ``cutoff``
    offset : float
        Offset ``d`` (length); gap ``g = d - h + w``.
    initial : ContactResult or array, optional
        Warm start (its deflection; on a free boundary a result's pressure, whose
        deflection on the work grid is computed, or an array's deflection, zero on the
        padding).
    tol : float, optional
        Tolerance on ``max |K w - p_int| / E*`` (see module docstring).
        Default 1e-8 (float64) or 1e-6 (float32, also the smallest allowed there;
        larger beyond 1024²: :func:`roughcontact.solvers.inputs.default_tolerance`).
    max_iter : int
        Iteration cap; reaching it returns ``converged=False``.
    callback : callable, optional
        ``callback(iteration, residual)``; return True to stop.
    restart_every : int
        Steepest-descent restart period of the conjugate directions.
    refresh_every : int
        Period (iterations, >= 1) at which the preconditioner's stiff sites and diagonal
        are recomputed from the current gap (see the module docstring).
    device : {None, "cpu", "cuda", "cuda:N"}, optional
        Where to compute (default: where ``heights`` live); see :func:`roughcontact.to_device`.
    dtype : {None, "float64", "float32"}, optional
        Precision of the computation (default float64). float32 halves memory and
        time on a GPU; its accuracy floor is documented in the README.
    load : float, optional
        Mean pressure to carry (load control in the one minimisation, :mod:`._free_mean`;
        NumPy, periodic, rigid mean): ``offset`` is then where the search starts.

    Returns
    -------
    ContactResult
    """
    if is_jax_array(heights):  # the compiled loop (jax is imported only here)
        from ._adhesive_jax import minimize_energy_jax

        return minimize_energy_jax(
            heights, substrate, interaction, offset=offset, initial=initial, tol=tol,
            max_iter=max_iter, callback=callback, restart_every=restart_every,
            refresh_every=refresh_every, device=device, dtype=dtype, load=load,
        )  # fmt: skip
    t_start = time.perf_counter()
    h, tol = check_problem(heights, substrate, tol, offset, device, dtype)
    if int(refresh_every) < 1:
        raise ParameterError(f"refresh_every must be an integer >= 1, got {refresh_every!r}")
    offset = float(offset)
    shape = h.shape
    es = substrate.contact_modulus
    rigid = substrate.rigid_mean
    # the variable lives on the work grid (the patch itself unless the boundary is free)
    elastic_pressure = stiffness_operator(substrate, work_grid=True)
    compliance = compliance_operator(substrate, work_grid=True)
    self_stiffness = substrate.self_stiffness
    patch = patch_sites(substrate, h)  # None: every site is on the patch

    base = on_work_grid(substrate, offset - h)  # gap = base + w (w on the padding)
    n = base.shape[0]
    if initial is not None:
        w = warm_deflection(initial, substrate, h, compliance)
        if rigid:
            w -= np.mean(w)
    else:
        w = np.zeros(n, dtype=h.dtype)
    kw = _exact_kw(elastic_pressure, w)
    gap = base + w  # the iterate (w = gap - base is only formed when K w is recomputed)
    # float32 also advances w itself (as the compiled loop): K w formed from gap - base
    # carries the gap's rounding, ulp(max gap), a residual floor of ~E* ulp(max gap) / a0
    deflection = w if h.dtype == np.float32 else None
    del w
    work = Workspace(gap, patch)
    # float32 copies of what the single-precision convolutions take (module docstring)
    fast = np.empty(n, dtype=np.float32)
    fast_result = np.empty_like(fast)  # their results
    # K z on the second core while the line search selects its band (1-thread FFTs)
    overlap = overlaps_fft(n)
    # the interaction pressure is zero beyond its cutoff: kept as its values p_near on
    # the sites `near` (None: every site) where it can be nonzero
    cutoff = interaction.cutoff
    near = work.interacting(gap, cutoff)
    # the line search's sites kept between iterations (finite cutoff), unless K z runs
    # beside the line search: then its own band and curvature cost no time (they are
    # computed while K z is), and the kept band's wider evaluations would (512²: +4 %);
    # for a law that evaluates its pressure and curvature together (else every iteration
    # would select the band afresh)
    sticky = None
    if math.isfinite(cutoff) and not overlap and hasattr(interaction, "pressure_and_curvature"):
        reach = getattr(interaction, "range", None) or cutoff
        sticky = StickyBand(work, cutoff, BAND_MARGIN * reach)
    free = FreeMean.of(load, interaction, substrate, h, work, rigid and patch is None)
    # a warm start refreshes the block preconditioner at once, except on a free boundary
    # (module docstring)
    refresh_at_once = initial is not None and patch is None
    p_near = interaction.pressure(gap if near is None else gap[near])
    gr = np.empty_like(gap)

    def imbalance(kw, p_near, near):
        """gr = K w - p_int, without its mean when the uniform mode is rigid (its force
        is the load)."""
        m = (-free.load if free else (total(kw) - total(p_near)) / n) if rigid else 0.0
        g = work.shifted(gr, kw, m)
        if near is None:
            g -= p_near
        else:
            np.subtract.at(g, near, p_near)  # (g[near] -= p_near, without a gathered copy)
        return g

    gr = imbalance(kw, p_near, near)
    exact = True  # kw is K w from a fresh float64 convolution (not updated incrementally)
    reliable = ReliableUpdates(tol)
    stiff = diagonal = dense = blocks = None  # blocks: the arrays of dense, kept
    directions = False  # whether s, ks hold conjugate directions to build on
    s, ks, z, z_old = (np.empty_like(gap) for _ in range(4))
    gz_old = 1.0
    status, message = SolveStatus.ITERATION_LIMIT, "iteration cap reached"
    residual, it = math.inf, 0
    stall = FloorGuard(StallGuard(dtype_name(h)), dtype_name(h), lambda: largest(p_near), es,
                       tol, lambda: physical_pressure_scale(h, substrate, interaction))
    while True:
        residual = max(float(np.maximum.reduce(gr)), -float(np.minimum.reduce(gr))) / es
        if not math.isfinite(residual):
            status = SolveStatus.NON_FINITE
            message = f"non-finite state at iteration {it} (check inputs and the interaction)"
            break
        if (update := reliable.check(residual, exact)) == "refresh":
            if deflection is not None:  # the gap re-formed from w: clears its rounding
                gap = np.add(base, deflection, out=gap)
                if sticky is not None:
                    sticky.forget()  # its gap and curvature were those before
                near = work.interacting(gap, cutoff)
                p_near = interaction.pressure(gap if near is None else gap[near])
            # (gap - base in the scratch array, consumed at once)
            w = work.difference(gap, base) if deflection is None else deflection
            kw, exact = _exact_kw(elastic_pressure, w, out=kw), True
            gr = imbalance(kw, p_near, near)
            continue
        if update == "restart":
            directions = False  # they were built on a drifted gradient
        if (end := stopping(residual <= tol, residual, stall, it, max_iter)) is not None:
            status, message = end
            if status is SolveStatus.STALLED and stall.kind == "runaway":
                status = SolveStatus.RUNAWAY
            break
        if callback is not None and it > 0 and callback(it, residual):
            status, message = SolveStatus.CALLBACK, "stopped by callback"
            break
        it += 1
        reliable.step()
        restart = not directions or it % restart_every == 0
        if it % refresh_every == 0 or (it == 1 and refresh_at_once):
            known = None
            if sticky is not None and sticky.sites is not None and sticky.curvature is not None:
                known = sticky.sites, sticky.curvature  # V'' on S at this gap
            stiff, diagonal = _stiff_sites(interaction, gap, self_stiffness, work, known)
            dense = None
            if stiff is not None and stiff.size > DENSE_FRACTION * n and not overlap:
                dense = blocks = _dense_blocks(stiff, diagonal, gap, blocks)
        z_old, z = z, z_old  # z_old is the previous z; its array is reused for the new z
        z, kz = _precondition(
            free.mean_free(gr) if free else gr, stiff, diagonal, compliance, elastic_pressure,
            rigid,
            out=z, work=work, fast=fast, result=fast_result, background=overlap and not free,
            dense=dense,
        )  # fmt: skip
        if free and (z := free.add(z, gr, gap, it, refresh_every, kz=kz)) is None:
            status, message = SolveStatus.DETACHED, free.detached
            break
        gz = _dot(gr, z)
        # PR+ (gz_old is 0 only at the rounding floor of a deeply compressed state)
        restart = restart or gz_old == 0
        beta = 0.0 if restart else max(0.0, (gz - _dot(gr, z_old)) / gz_old)
        # s = -z + beta s (in place), and below ks = K s = -K z + beta ks
        s = work.scale_sub(s, beta, z) if beta > 0 else work.negative(s, z)
        slope0 = _dot(gr, s)
        if slope0 >= 0:  # not a descent direction: restart along the preconditioned -gr
            s, slope0, beta = work.negative(s, z), -gz, 0.0
        gz_old, directions = gz, True
        if callable(kz):  # K z still on the background thread: ks when the line search needs it
            ks_of_s = functools.partial(_direction_stiffness, work, ks, beta, kz)
        else:
            ks = ks_of_s = _direction_stiffness(work, ks, beta, kz)
        band = None if sticky is None else sticky.select(gap, s, GUESS_MAX, interaction.curvature)
        # s.K w from the slope, s.gr = s.K w - s.p_int (s has no mean when the mean is
        # rigid): a dot over the interaction's sites instead of the grid
        if near is None:
            elastic_slope = slope0 + _dot(s, p_near)
        else:
            s_near = band[1] if band is not None and near is band[0] else s[near]
            elastic_slope = slope0 + _dot(s_near, p_near)
        trial = {} if sticky is not None else None
        alpha, near, p_near = line_minimum(
            interaction,
            gap,
            s,
            kw,
            ks_of_s,
            slope0,
            rtol=LINE_SEARCH_RTOL,
            with_pressure=True,
            work=work,
            elastic_slope=elastic_slope,
            band=band,
            trial=trial,
        )
        if not math.isfinite(alpha):
            status = SolveStatus.LINE_SEARCH_FAILED
            message = f"line search failed at iteration {it}"
            break
        if sticky is not None:
            sticky.moved(alpha, near, trial)
        exact = False
        gap = work.axpy(gap, alpha, s)
        if deflection is not None:
            deflection = work.axpy(deflection, alpha, s)
        kw = work.axpy(kw, alpha, ks)
        gr = imbalance(kw, p_near, near)

    if free:  # the offset moved with the gap's mean
        moved, base = free.moved(offset, gap, base)
        if deflection is not None:
            deflection = deflection - (moved - offset)
        offset = moved
    if deflection is None:
        deflection = gap - base
    if patch is not None:  # the patch of the work grid (no pressure on the padding)
        gap, deflection = gap[patch], deflection[patch]
    p_int = _local(interaction.pressure, cutoff, gap)
    status, message = state_verdict(
        status, message, float(largest(p_int)), interaction,
        lambda: physical_pressure_scale(h, substrate, interaction), es, residual, tol,
        float(np.finfo(p_int.dtype).eps),
    )  # fmt: skip
    rep, att = interaction.classify(gap)
    return make_result(
        h,
        substrate,
        np.reshape(p_int, shape),
        np.reshape(deflection, shape),
        offset,
        it,
        residual,
        status,
        message,
        tol,
        "preconditioned-cg",
        time.perf_counter() - t_start,
        repulsive=np.reshape(rep, shape),
        attractive=np.reshape(att, shape),
    )
