"""Adhesive solves on JAX heights: the compiled loops' entry points and their result records.

:func:`minimize_energy_jax` runs :mod:`._smooth_jax` (smooth laws) for one offset: the
inputs are checked as for the NumPy solvers (:func:`.inputs.check_problem`), the loop is
one compiled program, and the host reads its iteration count, residual and status once
(then :func:`.observables.make_result` reduces the record's scalars in one transfer).
The fields of the result stay JAX arrays on the heights' device. jax is imported only
when JAX heights arrive (this module is imported lazily by :mod:`.solve`).
"""

from __future__ import annotations

import time

import jax.numpy as jnp

from ._pk_jax import check_jax_inputs
from .adhesive_rules import floor_verdict, physical_pressure_scale, state_verdict
from .bounded_rules import FULL_CONTACT_NOTE, ON_WALL
from .fourier import compliance_operator
from .inputs import check_hard_wall_offset, check_problem, warm_deflection
from .loop_control import STALL_PATIENCE, crawl_guarded, crawl_message
from .observables import make_result
from .result import SolveStatus
from .smooth_rules import FLOOR_PATIENCE, REFRESH_EVERY, RESTART_EVERY

__all__ = ["minimize_energy_bounded_jax", "minimize_energy_jax"]


def _initial_deflection(initial, substrate, h):
    """The warm start's deflection (2D, mean-free with a rigid mean) or zeros."""
    if initial is None:
        return jnp.zeros_like(h)
    w = warm_deflection(initial, substrate, h, compliance_operator(substrate, work_grid=True))
    w = jnp.reshape(w, h.shape)
    return w - jnp.mean(w) if substrate.rigid_mean else w


def minimize_energy_jax(
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
    """:func:`.smooth.minimize_energy` for JAX ``heights`` (length), compiled.

    The same parameters, results and units (offset: length; ``tol`` on
    ``max |K w - p_int| / E*``; ``load``: mean pressure, load control in the one
    minimisation, :mod:`._free_mean`'s method with :mod:`.adhesive_rules`' rules, in the
    same compiled loop, ``offset`` then where it starts); periodic substrates only, no
    ``callback``, ``device`` None (place the heights with ``jax.device_put``). Returns a
    :class:`ContactResult` whose fields are JAX arrays on the heights' device.
    """
    from . import _smooth_jax as sj

    t_start = time.perf_counter()
    dtype = check_jax_inputs(heights, substrate, dtype, device, callback)
    h, tol = check_problem(heights, substrate, tol, offset, None, dtype)
    offset = float(offset)
    base = offset - h
    w = _initial_deflection(initial, substrate, h)
    st, k = sj.prepare(w, substrate, interaction, base=base, tol=tol, max_iter=int(max_iter),
                       restart_every=int(restart_every), refresh_every=int(refresh_every),
                       warm=initial is not None, load=None if load is None else float(load),
                       heights=h)  # fmt: skip
    st = sj.run(st, k, law=interaction, rigid=bool(substrate.rigid_mean),
                stall=dtype == "float32", floor=dtype == "float64")  # fmt: skip
    names = {sj.CONVERGED: "converged", sj.LIMIT: "limit", sj.STALLED: "stalled",
             sj.FLOOR: "floor", sj.LINE_SEARCH_FAILED: "line_search",
             sj.DETACHED: "detached"}  # fmt: skip

    def resolve(values):  # the loop's outcome, read with the record (one transfer)
        it, residual, code, best, floor_best, scale, min_gap, *moved = values
        it, code = int(it), int(code)
        status, message = _outcome(names.get(code, "non_finite"), it, best, floor_best, scale,
                                   substrate, tol, physical)  # fmt: skip
        if code == sj.DETACHED:
            status, message = SolveStatus.DETACHED, _detached(load, it, min_gap)
        status, message = state_verdict(
            status, message, float(scale), interaction, physical, substrate.contact_modulus,
            float(residual), tol, float(jnp.finfo(h.dtype).eps),
        )  # fmt: skip
        return it, residual, status, message, *moved

    def physical():  # only for a stop at the floor (a transfer of the heights, then)
        return physical_pressure_scale(h, substrate, interaction)

    scalars = (st.it, st.residual, st.status, st.best, st.floor_best, jnp.max(jnp.abs(st.p)),
               jnp.min(st.gap))  # fmt: skip
    if load is None:
        p, rep, att, deflection = sj.fields(st, k, interaction)
    else:  # the offset moved with the gap's mean: read with the record
        p, rep, att, deflection, offset = sj.moved_fields(st, k, interaction, offset)
        scalars = (*scalars, offset)
    return make_result(h, substrate, p, deflection, offset, 0, 0.0, None, "", tol,
                       "preconditioned-cg", time.perf_counter() - t_start, repulsive=rep,
                       attractive=att, outcome=(scalars, resolve))  # fmt: skip


def _outcome(kind, it, best, floor_best, scale, substrate, tol, physical=None):
    """The :class:`SolveStatus` and message of a compiled loop's stop ``kind``, in the
    NumPy loops' words; a stop at the float64 floor is judged as the NumPy loop judges it,
    on the physical pressure scale ``physical()`` (:func:`.adhesive_rules.floor_verdict`:
    "stalled" or "runaway"), never on the state's own maximum ``scale``."""
    if kind == "converged":
        return SolveStatus.CONVERGED, "converged"
    if kind == "limit":
        return SolveStatus.ITERATION_LIMIT, "iteration cap reached"
    if kind == "stalled":
        return SolveStatus.STALLED, (
            f"stalled at residual {best:.2g} for {STALL_PATIENCE} iterations: the float32 "
            "rounding floor (use dtype='float64' or a larger tol)"
        )
    if kind == "floor":
        verdict, message = floor_verdict(
            float(floor_best), float(scale), scale if physical is None else physical(),
            substrate.contact_modulus, tol, FLOOR_PATIENCE,
        )  # fmt: skip
        return (SolveStatus.RUNAWAY if verdict == "runaway" else SolveStatus.STALLED), message
    if kind == "line_search":
        return SolveStatus.LINE_SEARCH_FAILED, f"line search failed at iteration {it}"
    if kind == "no_descent":
        return SolveStatus.LINE_SEARCH_FAILED, (
            f"no descent along the projected direction at iteration {it}"
        )
    return SolveStatus.NON_FINITE, (
        f"non-finite state at iteration {it} (check inputs and the interaction)"
    )


def minimize_energy_bounded_jax(
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
    device=None,
    dtype=None,
    load=None,
):
    """:func:`.bounded.minimize_energy_bounded` for JAX ``heights`` (length), compiled.

    The same parameters, results and units (offset: length, at least mean(heights) with a
    rigid mean; ``tol`` on the largest free-site force imbalance / E*; ``load``: mean
    pressure, load control in the one minimisation as the NumPy loop's, the multiplier
    ``mu = -load`` and the mean of ``w`` free, ``offset`` where it starts); periodic
    substrates only, no ``callback``, ``device`` None. Returns a :class:`ContactResult`
    whose fields are JAX arrays on the heights' device (``pressure``: the traction).
    """
    from . import _bounded_jax as bj

    t_start = time.perf_counter()
    dtype = check_jax_inputs(heights, substrate, dtype, device, callback)
    h, tol = check_problem(heights, substrate, tol, offset, None, dtype)
    offset = float(offset)
    (scale,) = check_hard_wall_offset(h, substrate, offset, also=["std"])
    scale = scale or substrate.pixel_size
    base = offset - h
    if initial is None:
        w = jnp.zeros_like(h)
    else:
        compliance = compliance_operator(substrate, work_grid=True)
        w = jnp.reshape(warm_deflection(initial, substrate, h, compliance), h.shape)
    st, k = bj.prepare(w, substrate, base=base, wall_tol=ON_WALL * scale, tol=tol,
                       max_iter=int(max_iter), restart_every=int(restart_every),
                       load=None if load is None else float(load), heights=h,
                       law=interaction)  # fmt: skip
    crawl = crawl_guarded()  # load control's cold hard-core solve (loop_control)
    rigid = bool(substrate.rigid_mean)
    st = bj.run(st, k, law=interaction, rigid=rigid,
                stall=dtype == "float32", crawl=crawl)  # fmt: skip
    names = {bj.CONVERGED: "converged", bj.LIMIT: "limit", bj.STALLED: "stalled",
             bj.LINE_SEARCH_FAILED: "line_search", bj.NO_DESCENT: "no_descent"}  # fmt: skip

    def resolve(values):  # the loop's outcome, read with the record (one transfer)
        it, residual, code, best, min_gap, full, *moved = values
        it, code = int(it), int(code)
        status, message = _outcome(names.get(code, "non_finite"), it, best, 0.0, 0.0, substrate,
                                   tol)  # fmt: skip
        if status is SolveStatus.CONVERGED and load is None and rigid and bool(full):
            message += FULL_CONTACT_NOTE
        if crawl and code == bj.LIMIT and it < max_iter:
            message = crawl_message(float(best))
        if code == bj.DETACHED:
            status, message = SolveStatus.DETACHED, _detached(load, it, min_gap)
        return it, residual, status, message, *moved

    gap = k.base + st.w
    scalars = (st.it, st.residual, st.status, st.best, jnp.min(gap), jnp.all(gap <= k.wall_tol))
    if load is None:
        traction, rep, att, deflection = bj.fields(st, k, interaction)
    else:  # the offset moved with the mean of w: read with the record
        traction, rep, att, deflection, offset = bj.moved_fields(st, k, interaction, offset)
        scalars = (*scalars, offset)
    return make_result(h, substrate, traction, deflection, offset, 0, 0.0, None, "", tol,
                       "bounded-cg", time.perf_counter() - t_start, repulsive=rep,
                       attractive=att, outcome=(scalars, resolve))  # fmt: skip


def _detached(load, it, min_gap):
    """A lost tensile load's message, :meth:`._free_mean.FreeMean._lost`'s words."""
    return (
        f"no state reached carries load {float(load):g}: at iteration {it} the surfaces separate "
        f"(smallest gap {float(min_gap):.3g}, beyond the attraction's peak, where no site "
        "pulls that hard): beyond the pull-off force"
    )


#: :func:`.load_control.solve_at_load` passes the load to this minimiser (its one
#: minimisation, in the compiled loop) where it does to the NumPy ones.
minimize_energy_jax.takes_load = True
minimize_energy_bounded_jax.takes_load = True
