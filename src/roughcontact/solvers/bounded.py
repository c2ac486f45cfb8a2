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
  that does not lower the energy is halved; if every halving rises, the projected path
  is searched upward from the first wall contact along the direction (steps doubling
  from there until the energy rises, :data:`.bounded_rules.CONTACT_DOUBLINGS`, in the
  spirit of Moré & Toraldo's projected search); failing that, a projected
  steepest-descent step (Bertsekas, IEEE Trans. Autom. Control 21, 174 (1976)), which
  lowers it for a short enough step: a preconditioned direction, once projected, need
  not descend.

Under load control (``load``, NumPy, periodic, rigid mean) the multiplier is the load,
``μ = -N``, and the mean of ``w`` (the offset) is free, with a block in the
preconditioner along the body's lift at fixed contact (:mod:`._free_mean`,
:func:`.adhesive_rules.contact_mode`: one more float32 convolution when the wall's sites
change by more than a tenth): one minimisation instead of nested solves.

Convergence measure (``residual``): the largest force imbalance on a free site,
``max |K w - p_int(g) - μ| / E*``; sites on the active face satisfy the contact
conditions by construction. Cost: two FFT convolutions per iteration, the
preconditioner and ``K s`` (both in float32: the first only steers, the second only
updates ``K w`` by increments, which is recomputed exactly in float64 as the residual
falls and before convergence is declared, as in :mod:`.smooth`), and a float64 one on
projected steps (their energy test needs the exact ``K w``).

This module is the NumPy (CPU) loop. On accelerators the same method runs as one
compiled program (:mod:`._bounded_jax`, with the rules of :mod:`.bounded_rules` shared),
reached by JAX heights, by arrays of other libraries through DLPack and by
``device="cuda"`` (:mod:`roughcontact._accelerator`). The energy is evaluated only for
the projected steps' test.

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

import numpy as np
from array_api_compat import is_jax_array  # (looks at sys.modules: imports no jax)

from .._accelerator import routed
from .._backend import dtype_name
from ._free_mean import FreeMean
from ._inplace import Workspace
from ._projection import _from_first_contact, _projected_gradient_step, project_feasible
from .bounded_rules import FULL_CONTACT_NOTE, ON_WALL, PROJECTED_HALVINGS
from .fourier import (
    compliance_operator,
    in_single_precision,
    on_work_grid,
    patch_sites,
    stiffness_operator,
)
from .inputs import check_hard_wall_offset, check_problem, warm_deflection
from .line_search import line_minimum
from .loop_control import ReliableUpdates, stall_guard, stopping
from .observables import make_result
from .reductions import dot as _dot
from .reductions import total
from .result import SolveStatus

__all__ = ["minimize_energy_bounded", "project_feasible"]


@routed
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
        Default 1e-8 (float64) or 1e-6 (float32, also the smallest allowed there;
        larger beyond 1024²: :func:`roughcontact.solvers.inputs.default_tolerance`).
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
    # the variable lives on the work grid (the patch itself unless the boundary is free)
    base = on_work_grid(substrate, offset - h)  # gap = base + w
    n = base.shape[0]
    patch = patch_sites(substrate, h)  # None: every site is on the patch
    work = None if patch is None else Workspace(base, patch)
    lower = -base if patch is None else np.where(patch, -base, -math.inf)  # no wall off it
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
        out = np.zeros_like(gap_)
        out[work.patch] = evaluate(gap_[work.patch])
        return out

    if initial is not None:
        w0 = warm_deflection(initial, substrate, h, compliance_operator(substrate, work_grid=True))
    else:
        w0 = np.zeros(n, dtype=h.dtype)
    # under load control (load given) the mean of w is free and mu = -load (_free_mean)
    free_mode = None if load is None else FreeMean.of(
        load, interaction, substrate, h, Workspace(base), rigid and patch is None)
    pin = rigid and free_mode is None  # the rigid mean as a constraint
    w = project_feasible(w0 - np.mean(w0) if rigid else w0, lower, pin)
    kw = stiff(w)
    work_load = 0.0 if free_mode is None else free_mode.load  # N: its work N sum(w)

    def energy(w_, kw_):
        e = 0.5 * _dot(w_, kw_) + total(interaction.energy(on_patch(base + w_)))
        return e + work_load * total(w_) if work_load else e

    def masked_mean(x, mask, fallback):
        """mean of x over mask, else fallback()"""
        return float(np.mean(x[mask])) if np.any(mask) else fallback()

    s = ks = z_old = None
    gz_old, active_old = 1.0, None
    status, message = SolveStatus.ITERATION_LIMIT, "iteration cap reached"
    residual, it, mu = math.inf, 0, 0.0
    stall = stall_guard(dtype_name(h))  # (the crawl guard under cold load control)
    reliable, exact = ReliableUpdates(tol), True  # exact: kw is K w from a fresh convolution
    free = np.ones(n, dtype=bool)

    def top(w, kw):
        """The gap, the multiplier mu, the active face, the free sites and the free sites'
        force imbalance ``rr`` of the state ``(w, K w)``."""
        gap = base + w
        r = kw - law(interaction.pressure, gap)
        on_wall = gap <= on_wall_tol
        if patch is not None:
            on_wall = on_wall & patch
        mu = -work_load
        if pin:  # every site on the wall: the smallest reaction (FULL_CONTACT_NOTE)
            mu = masked_mean(r, ~on_wall, lambda: float(np.min(r)))
        active = on_wall & (r - mu > 0)
        free = ~active
        if pin:
            mu = masked_mean(r, free, lambda: mu)
        return gap, mu, active, free, np.where(free, r - mu, 0.0)

    while True:
        gap, mu, active, free, rr = top(w, kw)
        residual = float(np.max(np.abs(rr))) / es
        if not math.isfinite(residual):
            status = SolveStatus.NON_FINITE
            message = f"non-finite state at iteration {it} (check inputs and the interaction)"
            break
        if (update := reliable.check(residual, exact)) == "refresh":
            kw, exact = stiff(w), True
            continue
        if update == "restart":
            s = None  # the conjugate directions were built on a drifted gradient
        done = residual <= tol or not bool(np.any(free))
        if (end := stopping(done, residual, stall, it, max_iter)) is not None:
            status, message = end
            break
        if callback is not None and it > 0 and callback(it, residual):
            status, message = SolveStatus.CALLBACK, "stopped by callback"
            break
        it += 1
        reliable.step()
        z = np.where(free, green(rr), 0.0)
        if rigid:
            z = np.where(free, z - masked_mean(z, free, lambda: 0.0), 0.0)
        if free_mode is not None:  # the uniform block on the free sites
            if (z := free_mode.add_on(z, rr, gap, free, it, green)) is None:
                status, message = SolveStatus.DETACHED, free_mode.detached
                break
            z = np.where(free, z, 0.0)
        restart = s is None or it % restart_every == 0 or active_old is None
        gz = _dot(rr, z)
        restart = restart or bool(np.any(active != active_old))
        restart = restart or gz_old == 0  # no previous direction to conjugate to
        beta = 0.0 if restart else max(0.0, (gz - _dot(rr, z_old)) / gz_old)  # PR+
        s = -z + beta * s if beta > 0 else -z
        slope0 = _dot(rr, s)
        if slope0 >= 0:
            s, slope0 = -z, -gz
        z_old, gz_old, active_old = z, gz, active
        ks = stiff_single(s)
        crossing = s < 0 if patch is None else (s < 0) & patch
        alpha = line_minimum(interaction, gap, s, kw + work_load if work_load else kw, ks,
                             slope0, work=work)  # fmt: skip
        if not math.isfinite(alpha):
            status = SolveStatus.LINE_SEARCH_FAILED
            message = f"line search failed at iteration {it}"
            break
        alpha_max = float(np.min(-gap[crossing] / s[crossing])) if np.any(crossing) else math.inf
        if alpha <= alpha_max:
            w += alpha * s
            kw += alpha * ks
            exact = False
            continue
        e_cur = energy(w, kw)  # (the energy is only needed here)
        # the step crosses the wall: project it, halve it while it does not lower E
        for _ in range(PROJECTED_HALVINGS):
            w_try = project_feasible(w + alpha * s, lower, pin)
            kw_try = stiff(w_try)
            e_try = energy(w_try, kw_try)
            if bool(e_try <= e_cur):
                break
            alpha *= 0.5
        else:
            # then upward from the first wall contact (CONTACT_DOUBLINGS: why); else the
            # preconditioned direction, which mixes sites across the face, need not
            # descend once projected (e.g. after an offset change lifts a whole contact
            # off the wall), and the projected gradient does, for a short enough step
            step = _from_first_contact(
                w, s, alpha_max, 2.0 * alpha, e_cur, lower, pin, stiff, energy
            ) or _projected_gradient_step(
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
        moved = float(np.mean(w))
        offset, w = offset + moved, w - moved
    if status is SolveStatus.CONVERGED and pin and bool(np.all(on_patch(gap) <= on_wall_tol)):
        message += FULL_CONTACT_NOTE
    p_int = law(interaction.pressure, gap)
    traction = on_patch(np.where(free, p_int, kw - mu))  # none on the padding
    return make_result(
        h,
        substrate,
        np.reshape(traction, shape),
        np.reshape(on_patch(w), shape),
        offset,
        it,
        residual,
        status,
        message,
        tol,
        "bounded-cg",
        time.perf_counter() - t_start,
        repulsive=np.reshape(traction > 0, shape),
        attractive=np.reshape(traction < 0, shape),
    )
