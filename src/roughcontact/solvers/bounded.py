r"""Energy minimisation for adhesive laws on a hard wall (bound-constrained, non-convex).

Minimises, at fixed offset ``d``,

.. math:: E(w) = E_{el}(w) + a_0^2 \sum_i V(d - h_i + w_i)
          \quad\text{subject to}\quad g_i = d - h_i + w_i \ge 0

(and :math:`\bar w = 0` when the substrate's uniform mode is rigid), for hard-core laws
such as :class:`~roughcontact.interactions.Exponential` and
:class:`~roughcontact.interactions.MaugisDugdale`. The method is a gradient-projection
conjugate-gradient scheme in the spirit of Moré & Toraldo (SIAM J. Optim. 1, 93 (1991))
and of the bounded CG of Bugnicourt et al. (Tribol. Lett. 66, 29 (2018)):

* the *active face* is the set of sites on the wall (g = 0) whose reaction
  :math:`r_i - \mu = (K w)_i - p_{int}(0) - \mu` pushes into it; ``μ`` is the
  Lagrange multiplier of the rigid mean (minus the mean pressure, i.e. the load);
* on the free sites the gradient is preconditioned by the substrate's Green's function
  restricted to the face, so the iteration count hardly depends on the grid size;
* steps that would cross the wall are projected onto the feasible set
  :math:`\{w \ge h - d,\ \bar w = 0\}` (clip plus a uniform shift, found by a
  finite Newton iteration), as Polonsky & Keer project their pressures; a projected step
  that does not lower the energy is halved, then replaced by a projected steepest-descent
  step (Bertsekas, IEEE Trans. Autom. Control 21, 174 (1976)), which lowers it for a short
  enough step: a preconditioned direction, once projected, need not descend.

Under load control (``load``, NumPy, periodic, rigid mean) the multiplier is the load,
``μ = -N``, and the mean of ``w`` (the offset) is free, with a uniform block in the
preconditioner (:mod:`._free_mean`): one minimisation instead of nested solves.

Convergence measure (``residual``): the largest force imbalance on a free site,
``max |K w - p_int(g) - μ| / E*``; sites on the active face satisfy the contact
conditions by construction. Cost: two FFT convolutions per iteration, the
preconditioner and ``K s`` (both in float32: the first only steers, the second only
updates ``K w`` by increments, which is recomputed exactly in float64 as the residual
falls and before convergence is declared, as in :mod:`.smooth`), and a float64 one on
projected steps (their energy test needs the exact ``K w``).

Off NumPy (a GPU) the loop is split into init / step / terminate (:mod:`._blocks`,
:mod:`._bounded_steps`): the common iteration (the line search's Newton guess taken and
feasible) is a device step without host sync, its scalars (``μ``, inner products,
``beta``, the largest feasible step) 0-d device arrays; the host reads the state once per
block of up to 8 steps. An iteration that needs the host (the bracketing line search, a
projection onto the wall, whose Newton steps read their scalars one transfer each, an
exact refresh, convergence) freezes the state and the sequential loop takes it: the same
iterations and values. The energy is evaluated only for the projected steps' test.

The result's ``pressure`` is the surface traction: the interaction pressure on free
sites, the elastic pressure (reaction plus adhesion) on the wall. Repulsive sites are
those where it is > 0 (only wall sites), attractive those where it is < 0.

A free boundary (``Substrate(..., periodic=False)``): as in :mod:`.smooth`, the
deflection lives on the zero-padded work grid and the interaction and the wall act on the
patch only (no bound on the padding, whose sites are free and carry no pressure at
equilibrium).
"""

from __future__ import annotations

import math
import time

from array_api_compat import is_jax_array  # (looks at sys.modules: imports no jax)

from .._backend import (
    array_device,
    array_namespace,
    computes_on_heights_device,
    dtype_name,
    is_numpy_array,
)
from ._free_mean import FreeMean
from ._inplace import Workspace
from ._projection import _direction_on_device, _projected_gradient_step, project_feasible
from .bounded_rules import ON_WALL, PROJECTED_HALVINGS
from .fourier import (
    compliance_operator,
    in_single_precision,
    on_work_grid,
    patch_sites,
    stiffness_operator,
)
from .inputs import check_hard_wall_offset, check_problem, warm_deflection
from .line_search import line_minimum
from .loop_control import ReliableUpdates, StallGuard, stopping
from .observables import make_result
from .reductions import dot as _dot
from .reductions import fetch, on_device, vdot, vtotal
from .result import SolveStatus

__all__ = ["minimize_energy_bounded", "project_feasible"]


@computes_on_heights_device
def minimize_energy_bounded(
    heights,
    substrate,
    interaction,
    *,
    offset,
    initial=None,
    tol=None,
    max_iter=5000,
    callback=None,
    restart_every=200,
    device=None,
    dtype=None,
    load=None,
):
    """Solve a hard-core adhesive contact state at fixed ``offset`` (or ``load``).

    Parameters
    ----------
    heights : (nx, ny) array
        Rigid surface heights (length).
    substrate : Substrate (or any :class:`~roughcontact.elastic.operator.ElasticOperator`)
    interaction : hard-core law (``hard_core = True``), e.g. Exponential, MaugisDugdale
    offset : float
        Offset ``d`` (length); gap ``g = d - h + w >= 0``.
    initial : ContactResult or array, optional
        Warm start (its deflection, projected onto the feasible set; on a free boundary
        as for :func:`.smooth.minimize_energy`).
    tol : float, optional
        Tolerance on the largest free-site force imbalance / E*.
        Default 1e-8 (float64) or 1e-6 (float32, also the smallest allowed there).
    max_iter : int
        Iteration cap; reaching it returns ``converged=False``.
    callback : callable, optional
        ``callback(iteration, residual)``; return True to stop.
    device : {None, "cpu", "cuda", "cuda:N"}, optional
        Where to compute (default: where ``heights`` live); see :func:`roughcontact.to_device`.
    dtype : {None, "float64", "float32"}, optional
        Precision of the computation (default float64). float32 halves memory and
        time on a GPU; its accuracy floor is documented in the README.
    load : float, optional
        Mean pressure to carry inside the one minimisation (:mod:`._free_mean`; NumPy, a
        periodic substrate with a rigid mean): the multiplier is ``mu = -load`` and the
        mean of ``w`` (the offset) is free; ``offset`` is where it starts.

    Returns
    -------
    ContactResult
    """
    if is_jax_array(heights):  # the compiled loop (jax is imported only here)
        from ._adhesive_jax import minimize_energy_bounded_jax

        return minimize_energy_bounded_jax(
            heights, substrate, interaction, offset=offset, initial=initial, tol=tol,
            max_iter=max_iter, callback=callback, restart_every=restart_every,
            device=device, dtype=dtype, load=load,
        )  # fmt: skip
    t_start = time.perf_counter()
    h, tol = check_problem(heights, substrate, tol, offset, device, dtype)
    offset = float(offset)
    shape = h.shape
    es = substrate.contact_modulus
    rigid = substrate.rigid_mean
    xp = array_namespace(h)
    # the variable lives on the work grid (the patch itself unless the boundary is free)
    base = on_work_grid(substrate, offset - h)  # gap = base + w
    n = base.shape[0]
    patch = patch_sites(substrate, h)  # None: every site is on the patch
    work = None if patch is None else Workspace(base, patch)
    lower = -base if patch is None else xp.where(patch, -base, -math.inf)  # no wall off it
    # the offset's check and the heights' rms in one transfer
    # (none where load control's checked heights bring their statistics)
    (scale,) = check_hard_wall_offset(h, substrate, offset, also=["std"])
    scale = scale or substrate.pixel_size
    # single precision for what only steers (the preconditioner) or updates K w by
    # increments (K s); exact float64 K w on projected steps and as ReliableUpdates says
    green = in_single_precision(compliance_operator(substrate, work_grid=True))
    stiff = stiffness_operator(substrate, work_grid=True)
    stiff_single = in_single_precision(stiff)
    on_wall_tol = ON_WALL * scale

    def on_patch(x):
        return x if work is None else x[work.patch]

    def law(evaluate, gap_):
        """The interaction's ``evaluate`` on the patch, zero on the padding."""
        if work is None:
            return evaluate(gap_)
        out = xp.zeros_like(gap_)
        out[work.patch] = evaluate(gap_[work.patch])
        return out

    if initial is not None:
        w0 = warm_deflection(initial, substrate, h, compliance_operator(substrate, work_grid=True))
    else:
        w0 = xp.zeros(n, dtype=h.dtype, device=array_device(h))
    # under load control (load given) the mean of w is free and mu = -load (_free_mean)
    free_mode = None if load is None else FreeMean.of(
        load, interaction, substrate, h, Workspace(base), rigid and patch is None)
    pin = rigid and free_mode is None  # the rigid mean as a constraint
    w = project_feasible(w0 - xp.mean(w0) if rigid else w0, lower, pin)
    kw = stiff(w)
    work_load = 0.0 if free_mode is None else free_mode.load  # N: its work N sum(w)

    def energy(w_, kw_):  # a device scalar off NumPy
        e = 0.5 * vdot(w_, kw_) + vtotal(interaction.energy(on_patch(base + w_)))
        return e + work_load * vtotal(w_) if work_load else e

    # off NumPy (a GPU) the loop's scalars stay 0-d device arrays and the host reads them
    # in two transfers per iteration: the residual at the top, and the line search's first
    # slope with the largest feasible step (each transfer waits for the device)
    dev, f64 = not is_numpy_array(h), xp.float64

    def in_dt(x):  # a float64 device scalar in the fields' precision (as a Python float)
        return xp.astype(x, h.dtype) if on_device(x) and x.dtype != h.dtype else x

    counted = []  # the last masks counted, with their counts (each mask is counted 2-3 times)

    def count(mask):
        """The sites of ``mask`` (a 0-d float64 device array; off NumPy only)."""
        for seen, k in counted:
            if seen is mask:  # the same array: the top's free sites, then the state's
                return k
        k = xp.sum(xp.astype(mask, f64))
        counted[:] = [(mask, k), *counted[:1]]  # (keeps the masks alive: ids stay theirs)
        return k

    # off NumPy the constants of the field operations are arrays made once, of shape (1,)
    # in the fields' dtype (a Python scalar operand is converted at every use: on
    # array_api_strict two arrays more per operation), 0-d float64 for the device scalars;
    # on NumPy the same Python scalars as before
    zero, zero_i, wall_tol = 0.0, 0, on_wall_tol
    if dev:
        zero64, one64 = (xp.asarray(v, dtype=f64, device=array_device(h)) for v in (0.0, 1.0))
        zero, wall_tol = (xp.full((1,), v, dtype=h.dtype, device=array_device(h))
                          for v in (0.0, on_wall_tol))  # fmt: skip
        zero_i = zero

    def masked_mean(x, mask, fallback, k=None):
        """mean of x over mask, else fallback(): a float on NumPy, off it a device scalar
        (``k``: the mask's count if known)"""
        if not dev:
            return float(xp.mean(x[mask])) if xp.any(mask) else fallback()
        k = count(mask) if k is None else k
        mean = xp.sum(xp.where(mask, x, zero), dtype=f64) / xp.maximum(k, one64)
        return xp.where(k > zero64, mean, fallback())

    s = ks = z_old = None
    gz_old, active_old = 1.0, None
    status, message = SolveStatus.ITERATION_LIMIT, "iteration cap reached"
    residual, it, mu = math.inf, 0, 0.0
    stall = StallGuard(dtype_name(h))
    reliable, exact = ReliableUpdates(tol), True  # exact: kw is K w from a fresh convolution
    free = xp.ones(n, dtype=xp.bool, device=array_device(h))

    def top(w, kw):
        """The gap, the multiplier mu, the active face, the free sites and the free sites'
        force imbalance ``rr`` of the state ``(w, K w)``."""
        gap = base + w
        r = kw - law(interaction.pressure, gap)
        on_wall = gap <= wall_tol
        if patch is not None:
            on_wall = on_wall & patch
        mu = -work_load
        if pin:
            mean = (lambda: vtotal(r) / n) if dev else (lambda: float(xp.mean(r)))
            mu = masked_mean(r, ~on_wall, mean)
        active = on_wall & (r - in_dt(mu) > zero_i)
        free = ~active
        if pin:
            mu = masked_mean(r, free, lambda: mu)
        return gap, mu, active, free, xp.where(free, r - in_dt(mu), zero)

    def speculate(alpha, pressure):
        """Off NumPy: the state after the line search's first guess, whose residual and
        free-site count come over in the line search's transfer (one host sync for an
        iteration that takes the guess, if it stays feasible)."""
        w_, kw_ = w + in_dt(alpha) * s, kw + in_dt(alpha) * ks
        state = top(w_, kw_)
        return (w_, kw_, state), [xp.max(xp.abs(state[-1])), count(state[3])]

    ahead, guess = None, {}  # the top's state fetched with the line search; speculate's
    while True:
        if ahead is None:
            gap, mu, active, free, rr = top(w, kw)
            if dev:
                rr_max, n_free = fetch(xp, [xp.max(xp.abs(rr)), count(free)])
            else:
                rr_max, n_free = float(xp.max(xp.abs(rr))), None
        else:
            ((gap, mu, active, free, rr), (rr_max, n_free)), ahead = ahead, None
        residual = rr_max / es
        if not math.isfinite(residual):
            status = SolveStatus.NON_FINITE
            message = f"non-finite state at iteration {it} (check inputs and the interaction)"
            break
        if (update := reliable.check(residual, exact)) == "refresh":
            kw, exact = stiff(w), True
            continue
        if update == "restart":
            s = None  # the conjugate directions were built on a drifted gradient
        done = residual <= tol or not (n_free > 0 if dev else bool(xp.any(free)))
        if (end := stopping(done, residual, stall, it, max_iter)) is not None:
            status, message = end
            break
        if callback is not None and it > 0 and callback(it, residual):
            status, message = SolveStatus.CALLBACK, "stopped by callback"
            break
        it += 1
        reliable.step()
        z = xp.where(free, green(rr), 0.0)
        if rigid:
            z = xp.where(free, z - in_dt(masked_mean(z, free, lambda: 0.0)), 0.0)
        if free_mode is not None:  # the uniform block on the free sites
            if (z := free_mode.add_on(z, rr, gap, free, it)) is None:
                status, message = SolveStatus.DETACHED, free_mode.detached
                break
            z = xp.where(free, z, 0.0)
        restart = s is None or it % restart_every == 0 or active_old is None
        if dev:
            s, slope0, gz = _direction_on_device(xp, rr, z, z_old, s, gz_old, restart,
                                                 active, active_old)  # fmt: skip
        else:
            gz = _dot(rr, z)
            restart = restart or bool(xp.any(active != active_old))
            restart = restart or gz_old == 0  # no previous direction to conjugate to
            beta = 0.0 if restart else max(0.0, (gz - _dot(rr, z_old)) / gz_old)  # PR+
            s = -z + beta * s if beta > 0 else -z
            slope0 = _dot(rr, s)
            if slope0 >= 0:
                s, slope0 = -z, -gz
        z_old, gz_old, active_old = z, gz, active
        ks = stiff_single(s)
        crossing = s < 0 if patch is None else (s < 0) & patch
        if dev:  # the largest feasible step, brought over with the line search's slope
            ratio = -gap / xp.where(crossing, s, -1.0)
            steps = [xp.min(xp.where(crossing, ratio, math.inf))]
        alpha = line_minimum(interaction, gap, s, kw + work_load if work_load else kw, ks,
                             slope0, work=work,
                             also=steps if dev else None, speculate=speculate if dev else None,
                             speculated=guess, next_point=dev)  # fmt: skip
        if not math.isfinite(alpha):
            status = SolveStatus.LINE_SEARCH_FAILED
            message = f"line search failed at iteration {it}"
            break
        if dev:
            alpha_max = steps[0]
        else:
            alpha_max = (
                float(xp.min(-gap[crossing] / s[crossing])) if xp.any(crossing) else math.inf
            )
        if alpha <= alpha_max:
            if guess:  # the first guess, feasible: its state and scalars are at hand
                (w, kw, state), values = guess.pop("state"), guess.pop("values")
                ahead = (state, values)
            else:
                w += alpha * s
                kw += alpha * ks
            exact = False
            continue
        guess.clear()
        e_cur = energy(w, kw)  # (the energy is only needed here)
        # the step crosses the wall: project it, halve it while it does not lower E
        for _ in range(PROJECTED_HALVINGS):
            w_try = project_feasible(w + alpha * s, lower, pin)
            kw_try = stiff(w_try)
            e_try = energy(w_try, kw_try)
            if dev:  # the next top's scalars come with the energy test (one transfer)
                state = top(w_try, kw_try)
                scalars = [
                    xp.astype(e_try <= e_cur, f64),
                    xp.max(xp.abs(state[-1])),
                    count(state[3]),
                ]
                lower_e, *values = fetch(xp, scalars)
                if lower_e:
                    ahead = (state, values)
                    break
            elif bool(e_try <= e_cur):
                break
            alpha *= 0.5
        else:
            # the preconditioned direction mixes sites across the face, so once projected
            # it need not descend (e.g. after an offset change lifts a whole contact off
            # the wall); the projected gradient does, for a short enough step
            step = _projected_gradient_step(
                w, kw + work_load if work_load else kw, rr, e_cur, lower, pin, stiff, energy,
                interaction, gap, work,
            )
            if step is None:
                status = SolveStatus.LINE_SEARCH_FAILED
                message = f"no descent along the projected direction at iteration {it}"
                break
            w_try, kw_try, e_try = step
        w, kw, exact = w_try, kw_try, True
        s = None  # the face changed: restart the conjugate directions

    gap = base + w
    if free_mode is not None:  # the offset moved with the mean of w
        moved = float(xp.mean(w))
        offset, w = offset + moved, w - moved
    p_int = law(interaction.pressure, gap)
    traction = on_patch(xp.where(free, p_int, kw - in_dt(mu)))  # none on the padding
    return make_result(
        h,
        substrate,
        xp.reshape(traction, shape),
        xp.reshape(on_patch(w), shape),
        offset,
        it,
        residual,
        status,
        message,
        tol,
        "bounded-cg",
        time.perf_counter() - t_start,
        repulsive=xp.reshape(traction > 0, shape),
        attractive=xp.reshape(traction < 0, shape),
    )
