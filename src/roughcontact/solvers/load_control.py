r"""Load control for adhesive laws: find the offset whose equilibrium carries the load.

For the smooth and the bounded solver on NumPy heights, and their compiled loops on JAX
heights (:mod:`._adhesive_jax`, the same method and rules), a periodic substrate with a rigid
mean (and for a law without hard core a load within :data:`ONE_MINIMISATION_LOADS` physical
pressure scales), the load goes inside the one minimisation (:mod:`._free_mean`: the uniform
mode of the gap is free and its force is the load not carried; on the wall the multiplier is
the load): about the cost of an offset-controlled solve (cold from 128² on started from the
2x2-coarsened grid's state, :func:`_coarse_start`: 0.5-1.0x its iterations at 128²-256²
for a smooth law, 0.6-1.6x for a hard core; 1.05-1.1x a warm path step; against 10-30x
for the search below: benchmarks/README.md). A cold hard-core solve that still crawls
through the jump into contact (the bounded solver's search from the first wall contact,
:data:`.bounded_rules.CONTACT_DOUBLINGS`, removed most such crawls: 24 of 72 cold solves
at 256² restarted before it, 8 after) starts again from a hard-wall state once its
residual falls less
than 3-fold in 40 iterations (:func:`.loop_control.guarding_crawl`) or after
:data:`COLD_HARD_CORE_BUDGET` iterations (:func:`_from_hard_wall`). A cold tensile load
is approached from the state at load 0; for a hard core, where that approach separates
beyond its pull-off force, the unloading branch from the hard-wall state is tried too
(its state can hold more contact and more tension; the message says which branch).
Where that fails (a non-finite state, a failed line search), and for every other case, the
root search over nested solves below.

Why the nested search cost 10-30x (measured, 128²-256², ℓa 0.005 and 0.05, load 1e-3 and
0): 16-30 inner solves per load (about 9 while the bracket's step doubles from 0.01 rms,
then 7-21 of regula falsi to the load's tolerance tol·E*), each 25-180 iterations although
warm-started, because a change of the offset perturbs every contact at once.

Under load control the offset ``d`` is the unknown conjugate to the load: on a stable
branch the mean pressure :math:`\bar p(d)` of the displacement-controlled equilibrium
decreases monotonically with ``d``, so the state with :math:`\bar p = N/A_0` is the root
of a scalar function. It is bracketed by steps of doubling length from the warm start's
offset, then located by regula falsi (Illinois variant), each evaluation a
displacement-controlled solve warm-started from the nearest state already computed. A
load that no stable state carries (it lies inside a jump of :math:`\bar p(d)`) is
reported as not converged, with the offsets between which the jump occurs.

Tolerance on the load: ``|p̄ - N/A0| <= tol * E*``, the same scale as the force-balance
tolerance of the inner solves. Laws whose force is discontinuous (Maugis–Dugdale) make
:math:`\bar p(d)` jump by :math:`\sigma_0 a_0^2/A_0` whenever a site crosses the end of
the cohesive zone, so on a grid some loads are carried by no state: they are reported
as not converged, and displacement control is the way to follow such a law.

The search never goes below the offset where the law's repulsion is the load plus ten
physical pressure scales (full contact at that load, :func:`.adhesive_rules.lowest_smooth_offset`):
doubling steps once jumped from an adhesive state at d = 1.12 to d = -0.16, a runaway of
uniform p = 3.7e13 E*, reported as "stalled" (128², ℓa 0.05, load 1e-3).
"""

from __future__ import annotations

import contextlib
import dataclasses
import math
import time

from .._backend import array_namespace, dtype_name, is_numpy_array
from .adhesive_rules import (
    NESTED_TOL,
    carrying,
    largest_attraction,
    lowest_smooth_offset,
    nests,
    physical_pressure_scale,
)
from .inputs import check_problem, checked_heights, height_statistics
from .loop_control import CRAWL_IMPROVEMENT, CRAWL_PATIENCE, guarding_crawl
from .polonsky_keer import polonsky_keer
from .result import SolveStatus
from .roots import false_position, illinois

__all__ = ["solve_at_load"]


#: The load inside the one minimisation (a law without hard core) up to this many physical
#: pressure scales
#: (:mod:`.adhesive_rules`); beyond (1e9 E*: 3300 iterations there, ~600 by the nested
#: search, which starts at full contact at the load) the nested root search.
ONE_MINIMISATION_LOADS = 100.0


#: A cold load-controlled solve with a hard-core law (Maugis–Dugdale, Exponential) gets this
#: many iterations from first contact (and its nested start's coarse solve as many); then
#: it starts again from a hard-wall state (:func:`_from_hard_wall`). Measured (128², 36
#: surfaces and laws, loads -1e-4, 0, 1e-3 E*): from first contact 5-130 iterations where
#: the jump into contact goes well, but 345-5000 (the cap: not converged) for short-ranged
#: or weak Maugis-Dugdale laws at loads <= 0, where the projected steps crawl through the
#: jump (the wall's sites change every iteration, restarting the conjugate directions);
#: from the hard-wall state 13-25 hard-wall and 1-59 adhesive iterations in every case.
#: (Those counts predate :data:`.bounded_rules.CONTACT_DOUBLINGS`, which removed most of the
#: crawls: 3592 -> 2716 fine-grid iterations over 72 such solves at 128², 9 -> 2 restarts.)
COLD_HARD_CORE_BUDGET = 150


#: Why :func:`_from_hard_wall` started again, as its message says it.
CRAWLED = (
    f"the solve from first contact crawled (its residual fell less than "
    f"{1 / CRAWL_IMPROVEMENT:.0f}-fold in {CRAWL_PATIENCE} iterations, or "
    f"{COLD_HARD_CORE_BUDGET} passed: a slow jump into contact)"
)
SEPARATED = (
    "the approach from first contact (the jump into contact at load 0, then pulled to "
    "this load) separated beyond its pull-off force"
)


#: What a load-controlled solve's message says when it started again from a hard-wall state
#: (:func:`_from_hard_wall`).
RESTARTED = "started from the hard-wall state"


def hard_wall_start_load(load: float, interaction) -> float:
    """Mean pressure (E* units) of the hard-wall state a hard-core load-controlled solve
    starts again from: ``max(load, 0) + sigma_max``, the law's largest attraction
    (:func:`.adhesive_rules.largest_attraction`) above the load, so the contacts are formed
    deeper than the adhesive state's and the solve reaches it by unloading."""
    return max(load, 0.0) + largest_attraction(interaction)


def _from_hard_wall(run, heights, substrate, interaction, load, max_iter, total, why=CRAWLED):
    """The load-controlled solve again, from the hard-wall state at load
    ``max(load, 0) + sigma_max`` (the law's largest attraction, pressure): its offset and
    deflection, contacts already formed. ``(result, what the message adds)``.

    That start lies deeper in contact than the adhesive state, which the solve reaches by
    unloading: on the unloading branch, which can hold more contact at the same load than
    the approach from first contact (adhesion hysteresis), and so carry a tension beyond
    the approach's pull-off force; the message says so, and ``why`` it started again.
    """
    target = hard_wall_start_load(load, interaction)
    hard = polonsky_keer(heights, substrate, load=target)  # (its default tol: the dtype's)
    total["it"] += hard.iterations
    res = run(load, float(hard.offset), hard, max(max_iter - hard.iterations, 1))
    return res, (
        f"; {RESTARTED} at load {target:.3g} E* after {why}: the state "
        "reached by unloading from it, which can hold more contact than an approach to "
        "this load (adhesion hysteresis)"
    )


def _one_minimisation(minimize, heights, substrate) -> bool:
    """Whether ``minimize`` takes the load itself (:mod:`._free_mean`): the smooth or the
    bounded solver on NumPy heights, or a compiled loop that says so (``takes_load``:
    :mod:`._adhesive_jax`), on a periodic substrate with a rigid mean."""
    from .bounded import minimize_energy_bounded
    from .smooth import minimize_energy

    periodic = tuple(substrate.work_shape) == tuple(substrate.shape)
    numpy = minimize in (minimize_energy, minimize_energy_bounded) and is_numpy_array(heights)
    return ((numpy or getattr(minimize, "takes_load", False)) and periodic
            and substrate.rigid_mean)  # fmt: skip


def _coarse_start(minimize, heights, substrate, interaction, load, tol, max_iter, dtype):
    """Nested iteration of a cold solve in the one minimisation: ``(offset, deflection,
    iterations)`` of the same load solved on the grid coarsened 2x2 (offset and deflection
    None when that solve did not converge), or None where it does not apply.

    The coarse problem: 2x2 block means of the heights on the substrate's ``coarsened()``
    twin (twice the pixel size; the same continuum problem at half the resolution), solved
    cold by ``minimize`` (the same loop, NumPy or compiled) to
    :data:`.adhesive_rules.NESTED_TOL`; its deflection copied to each block's four sites
    (the same mean, on the heights' device) and its offset start the fine solve, which
    then corrects the state at its own scale. One level only and only where
    :func:`.adhesive_rules.nests` says (why: there); a coarse solve that did not converge
    leaves the fine solve its cold start. Cold from first contact the offset has
    to travel about one rms height while the contacts form one after another; on the
    coarse grid that costs a quarter (measured in benchmarks/README.md).
    """
    if not nests(heights.shape) or not hasattr(substrate, "coarsened"):
        return None
    xp = array_namespace(heights)
    nx, ny = heights.shape
    mx, my = nx // 2, ny // 2
    coarse = xp.mean(xp.reshape(heights, (mx, 2, my, 2)), axis=(1, 3))
    eq = interaction.equilibrium_distance or 0.0  # None: hard core
    start = float(xp.max(coarse)) + eq
    with carrying(load):
        res = minimize(
            coarse, substrate.coarsened(), interaction, offset=start, initial=None,
            tol=max(NESTED_TOL, tol), max_iter=max_iter, callback=None, dtype=dtype, load=load,
        )  # fmt: skip
    if not res.converged:
        return None, None, int(res.iterations)
    w = xp.reshape(res.deflection, (mx, 1, my, 1))  # on the heights' device
    fine = xp.reshape(xp.broadcast_to(w, (mx, 2, my, 2)), (nx, ny))
    return float(res.offset), fine, int(res.iterations)


def solve_at_load(
    minimize,
    heights,
    substrate,
    interaction,
    *,
    load,
    initial,
    tol,
    max_iter,
    callback,
    device=None,
    dtype=None,
):
    """Solve for mean pressure ``load`` with a displacement-controlled ``minimize``."""
    t0 = time.perf_counter()
    load = float(load)
    # moved to the device once; every solve below then computes where the heights are
    h, tol = check_problem(heights, substrate, tol, None, device, dtype)
    heights = h
    load_tol = tol * substrate.contact_modulus
    dtype = dtype_name(h)
    # the heights' statistics in one transfer, which the inner solves reuse (no transfer)
    stats = height_statistics(h)
    scale = max(stats["std"], substrate.pixel_size)
    states: dict[float, object] = {}
    total = {"it": 0, "coarse": 0}  # iterations here; on the coarsened grid (nested)

    def evaluate(d):
        near = min(states, key=lambda x: abs(x - d)) if states else None
        start = states[near] if near is not None else initial
        # checked above: not again in every inner solve; their floor judged with the load
        with checked_heights(heights, stats), carrying(load):
            res = minimize(
                heights, substrate, interaction, offset=d, initial=start, tol=tol,
                max_iter=max_iter, callback=callback, dtype=dtype,
            )  # fmt: skip
        total["it"] += res.iterations
        states[d] = res
        return res

    def keep_only(*offsets):
        # the states warm-start later solves where they are (on a GPU: device memory); the
        # next offset lies beyond d_a (bracketing) or inside [d_a, d_b] (regula falsi), so
        # no other state can be the nearest one: drop them, holding at most two
        for d in [d for d in states if d not in offsets]:
            del states[d]

    def finish(res, converged, message, failure=SolveStatus.NO_STABLE_STATE):
        # an inner solve that failed keeps its own status and message; else ``failure``
        # says which of the ways a load can be out of reach it is
        if not res.converged:
            status = res.status
        else:
            status = SolveStatus.CONVERGED if converged else failure
        if total["coarse"]:  # iterations counts this grid's; the coarse work is said here
            message += (f"; nested iteration: {total['coarse']} iterations on the "
                        "2x2-coarsened grid first")
        return dataclasses.replace(
            res,
            iterations=total["it"],
            converged=bool(converged and res.converged),
            status=status,
            message=message if res.converged else res.message,
            solve_seconds=time.perf_counter() - t0,
        )

    if initial is not None and hasattr(initial, "offset"):
        d_a = float(initial.offset)
    else:
        d_a = stats["max"] + (interaction.equilibrium_distance or 0.0)  # None: hard core
    if _one_minimisation(minimize, h, substrate) and (
        interaction.hard_core  # full contact on the wall carries any load: no runaway
        or abs(load) <= ONE_MINIMISATION_LOADS
        * physical_pressure_scale(h, substrate, interaction)
    ):
        # the load inside the one minimisation (:mod:`._free_mean`): the cost of an
        # offset-controlled solve; the nested search below only where it fails
        def run(target, start, init, cap=max_iter, guard=False):
            # nested iteration (cold: from the coarse grid's state, if that converged); the
            # crawl guard (``guard``) on the fine grid only: the coarse solve costs a
            # quarter, and it cut coarse solves that converge in 41-44 iterations
            # (128², Maugis-Dugdale, load 1e-3)
            if init is None and (coarse := _coarse_start(
                    minimize, heights, substrate, interaction, target, tol, cap,
                    dtype)) is not None:  # fmt: skip
                total["coarse"] += coarse[2]
                if coarse[0] is not None:
                    start, init = coarse[0], coarse[1]
            with (checked_heights(heights, stats), carrying(target),
                  guarding_crawl() if guard else contextlib.nullcontext()):  # fmt: skip
                res = minimize(
                    heights, substrate, interaction, offset=start, initial=init, tol=tol,
                    max_iter=cap, callback=callback, dtype=dtype, load=target,
                )  # fmt: skip
            total["it"] += res.iterations
            return res

        budget = interaction.hard_core and max_iter > COLD_HARD_CORE_BUDGET
        restarted = []  # what the message adds about a restart from a hard-wall state

        def cold(target):
            # a hard core: from first contact within a budget and while it makes progress
            # (the crawl guard), else from a hard-wall state
            res = run(target, d_a, None, COLD_HARD_CORE_BUDGET if budget else max_iter, budget)
            if budget and res.status is SolveStatus.ITERATION_LIMIT:
                res, note = _from_hard_wall(run, heights, substrate, interaction, target,
                                            max_iter - res.iterations, total)  # fmt: skip
                restarted.append(note)
            return res

        res = cold(load) if initial is None else run(load, d_a, initial)
        if res.status is SolveStatus.DETACHED and initial is None:
            # a cold tensile load pulls a barely touching surface off: into contact at
            # load 0 first (the jump in), then pulled to the load from that state
            first = cold(0.0)
            if first.converged:
                res = run(load, first.offset, first)
            if res.status is SolveStatus.DETACHED and budget and not restarted:
                # beyond the approach's pull-off, a hard core's unloading branch (from the
                # hard-wall state, deeper in contact) can still carry the tension: said if
                # it does, else the approach's detachment stands and its message says both
                unloaded, note = _from_hard_wall(
                    run, heights, substrate, interaction, load, max_iter, total, SEPARATED)
                if unloaded.converged:
                    res = unloaded
                    restarted.append(note)
                else:
                    res = dataclasses.replace(res, message=res.message + (
                        "; nor did the state unloaded from the hard-wall state at load "
                        f"{hard_wall_start_load(load, interaction):.3g} E* carry it "
                        "(no branch tried holds this tension)"))  # fmt: skip
        if res.converged and abs(res.load - load) <= load_tol:
            full = interaction.hard_core and res.repulsive_area >= 1.0
            return finish(res, True, "converged (load control)" + (
                "; full contact: every site on the wall, whose reaction carries the load at "
                "offset mean(heights)" if full else "") + "".join(restarted[:1]))  # fmt: skip
        stops = (SolveStatus.CALLBACK, SolveStatus.ITERATION_LIMIT, SolveStatus.STALLED,
                 SolveStatus.DETACHED)  # fmt: skip
        if res.status in stops:
            return finish(res, False, res.message + "".join(restarted[:1]))
    if load < 0 and initial is None and not states:
        # cold and tensile: the nested search would open up from first contact and find
        # the surfaces detached; the state at load 0 (the jump into contact) first
        first = solve_at_load(minimize, heights, substrate, interaction, load=0.0, initial=None,
                              tol=tol, max_iter=max_iter, callback=callback)  # fmt: skip
        total["it"] += first.iterations
        if first.converged:
            d_a, states[first.offset] = first.offset, first
    res_a = evaluate(d_a)
    f_a = res_a.load - load
    if not res_a.converged or abs(f_a) <= load_tol:
        return finish(res_a, abs(f_a) <= load_tol, "converged (load control)")
    # too much compression (f > 0) -> open up (larger d), else close in
    direction = 1.0 if f_a > 0 else -1.0
    step = 0.01 * scale
    # a hard core admits no offset at or below its lowest one (the surfaces would overlap
    # everywhere): approach that bound by halving instead
    # (lowest_hard_wall_offset: the mean with a rigid mean)
    lowest = -math.inf
    if interaction.hard_core and substrate.rigid_mean:
        lowest = stats["mean"]
    elif substrate.rigid_mean:  # no lower than full contact at the load (adhesive_rules)
        pressure_scale = physical_pressure_scale(h, substrate, interaction)
        lowest = lowest_smooth_offset(interaction, stats["mean"], load, pressure_scale)
    for _ in range(60):
        keep_only(d_a)
        d_b = d_a + direction * step
        near_bound = d_b <= lowest
        if near_bound and not interaction.hard_core:
            if d_a <= lowest:
                return finish(
                    res_a, False, f"load {load:g} not reached: it is {res_a.load:g} at offset "
                    f"{d_a:g}, in full contact (the law's repulsion there exceeds the load by "
                    "ten times the pressure scale E*·h'rms)",
                    SolveStatus.FULL_CONTACT,
                )  # fmt: skip
            d_b = lowest
        elif near_bound:
            if d_a - lowest <= 1e-6 * scale:
                return finish(
                    res_a, False, f"load {load:g} not reached: it is {res_a.load:g} at offset "
                    f"{d_a:g}, next to mean(heights) where the contact is complete",
                    SolveStatus.FULL_CONTACT,
                )  # fmt: skip
            d_b = 0.5 * (d_a + lowest)
        res_b = evaluate(d_b)
        f_b = res_b.load - load
        if not res_b.converged or abs(f_b) <= load_tol:
            return finish(res_b, abs(f_b) <= load_tol, "converged (load control)")
        if (f_b > 0) != (f_a > 0):
            break
        if abs(f_b - f_a) <= load_tol and step > scale and not near_bound:
            # the load no longer changes with d: detached (beyond the pull-off force)
            return finish(
                res_b, False, f"no state carries load {load:g}: it stays {res_b.load:g} "
                f"up to offset {d_b:g} (beyond the pull-off force?)",
                SolveStatus.DETACHED,
            )  # fmt: skip
        d_a, f_a, res_a, step = d_b, f_b, res_b, 2.0 * step
    else:
        return finish(
            res_b,
            False,
            f"load {load:g} not bracketed by offsets up to {d_b:g}",
            SolveStatus.NOT_BRACKETED,
        )
    side = 0
    for _ in range(200):
        keep_only(d_a, d_b)
        d = false_position(d_a, f_a, d_b, f_b)
        res = evaluate(d)
        f = res.load - load
        if not res.converged or abs(f) <= load_tol:
            return finish(res, abs(f) <= load_tol, "converged (load control)")
        d_a, f_a, d_b, f_b, side = illinois(d_a, f_a, d_b, f_b, d, f, side)
        if abs(d_b - d_a) <= 1e-12 * (abs(d) + scale):
            break
    return finish(
        res,
        False,
        f"no stable state carries load {load:g}: the load jumps between offsets "
        f"{min(d_a, d_b):.12g} and {max(d_a, d_b):.12g} (an instability; use offset control)",
    )
