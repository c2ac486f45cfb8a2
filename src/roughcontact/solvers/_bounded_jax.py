"""The bounded (hard-core) minimiser as one compiled JAX program (``jax.jit`` + ``lax.while_loop``).

The method of :mod:`.bounded` (gradient-projection conjugate gradients: the active face on
the wall, PR+ directions preconditioned by the Green's function on the free sites, the
line search of :mod:`.line_search`, steps that cross the wall projected onto
``{w >= h - d, mean(w) = 0}`` by :mod:`._projection`'s finite Newton iteration and halved
until the energy does not rise, else a projected steepest-descent step) for heights given
as JAX arrays, under displacement control on a periodic substrate, or under load control
in the one minimisation (:mod:`._free_mean`'s method: the multiplier ``mu = -N``, the mean
of ``w`` free, the uniform block on the free sites by :mod:`.adhesive_rules`' rules).
Its constants are those of :mod:`.bounded_rules`, :mod:`.smooth_rules` and
:mod:`.loop_control`, shared with the NumPy loop. Every decision (the face, the line
search, the projection's Newton steps, the halvings, exact refreshes of ``K w``, the
float32 stall guard, convergence) is taken on the device; the host reads the result once
the loop stops.

As in :mod:`._smooth_jax`, the law is evaluated on every site and sums run in XLA's
order, so the iterates agree with the NumPy loop's to rounding; float64 needs
``jax_enable_x64`` while the program runs.
"""

from __future__ import annotations

from functools import partial
from typing import NamedTuple

import jax
import jax.numpy as jnp
from jax import lax

from . import adhesive_rules as rules
from ._smooth_jax import _conv, _dot, accumulation_dtype, line_minimum
from .bounded_rules import (
    BOUNDED_LINE_SEARCH_RTOL,
    CONTACT_DOUBLINGS,
    GRADIENT_HALVINGS,
    PROJECTED_HALVINGS,
    PROJECTION_MAX_STEPS,
    PROJECTION_RTOL,
)
from .loop_control import (
    CRAWL_IMPROVEMENT,
    CRAWL_PATIENCE,
    RELIABLE_DROP,
    RELIABLE_EVERY,
    STALL_IMPROVEMENT,
    STALL_PATIENCE,
)

__all__ = ["Constants", "State", "prepare", "project", "run"]

_STIFFNESS, _COMPLIANCE = 0, 1  # the fields of FourierMultipliers
#: The status codes the loop leaves in ``State.status``.
RUNNING, CONVERGED, LIMIT, STALLED, NON_FINITE, LINE_SEARCH_FAILED, NO_DESCENT = range(7)
DETACHED = 7  # a tensile load lost (load control)


class Constants(NamedTuple):
    """The problem, as device arrays (the compiled program's inputs)."""

    base: object  # offset - heights (2D): the gap is base + w
    stiff: object  # stiffness multipliers, the fields' dtype (rfft2 layout)
    green32: object  # compliance multipliers in float32 (the preconditioner's)
    stiff32: object  # stiffness multipliers in float32 (K s)
    modulus: object  # E* (pressure)
    wall_tol: object  # a gap at most this is on the wall (length)
    tol: object
    max_iter: object  # (int32)
    restart_every: object  # (int32)
    # load control in the one minimisation (:mod:`._free_mean`: mu = -load, the mean of w
    # free, a uniform block on the free sites; None: offset control)
    load: object = None  # the mean pressure to carry
    reach: object = None  # the uniform shift's bound, max(std(h), a0) (length)
    size: object = None  # the substrate's longer side (length)
    self_stiffness: object = None  # K_ii (pressure/length)
    peak: object = None  # the gap of the law's largest tension (a tensile load)


class State(NamedTuple):
    """The loop's state: device arrays only (scalars 0-d, in the accumulation dtype)."""

    w: object  # the deflection (2D; feasible)
    kw: object  # K w (updated by increments between exact evaluations)
    s: object  # the search direction
    z_old: object  # the last preconditioned gradient, ...
    gz_old: object  # ... its product with the gradient and ...
    active_old: object  # ... the active face it was built on (bool, 2D)
    directions: object  # whether s holds a direction to build on (bool)
    has_old: object  # whether z_old, active_old are set (bool)
    exact: object  # whether kw is K w from a fresh convolution (bool)
    it: object  # iterations (int32)
    residual: object  # the residual at the top of the last iteration
    reliable: object  # ReliableUpdates: the residual of the last exact state, ...
    since: object  # ... the iterations since it (int32) and ...
    iterated: object  # ... the incremental residual that asked for the refresh
    best: object  # StallGuard (float32): the best residual and ...
    since_best: object  # ... the iterations since it improved (int32)
    mu: object  # the top's multiplier of the mean and ...
    free: object  # ... its free sites (bool, 2D): the traction of the result
    status: object  # RUNNING or why the loop stopped (int32)
    # load control: the uniform mode along the contact's response (FreeMean.add_on,
    # adhesive_rules.contact_mode): the wall's sites it was computed on, u and k
    contact: object = None  # (bool, 2D)
    contact_u: object = None
    contact_k: object = None
    has_contact: object = None  # whether they are set (bool)


def project(v, lower, rigid, acc):
    """:func:`._projection.project_feasible` on the device: ``max(v + lam, lower)`` with the
    multiplier ``lam`` of the zero mean found by the same Newton steps."""
    if not rigid:
        return jnp.maximum(v, lower)
    dt = v.dtype
    scale = jnp.sum(jnp.abs(lower), dtype=acc) + jnp.sum(jnp.abs(v), dtype=acc) + 1e-300
    breakpoint_ = jnp.max(lower - v).astype(acc)  # everything clipped: the first breakpoint

    def step(c):  # (lam, best, u_best, out, k, done)
        lam, best, u_best, out, k, _ = c
        u = jnp.maximum(v + lam.astype(dt), lower)
        f = jnp.sum(u, dtype=acc)
        worse = jnp.abs(f) >= best  # no better at the precision of v (float32 stops here)
        close = jnp.abs(f) <= PROJECTION_RTOL * scale
        count = jnp.sum(v + lam.astype(dt) > lower, dtype=acc)
        nxt = jnp.where(count > 0, lam - f / jnp.where(count > 0, count, 1.0), breakpoint_)
        out = jnp.where(worse, u_best, u)
        keep = ~worse & ~close
        return (jnp.where(keep, nxt, lam), jnp.where(keep, jnp.abs(f), best),
                jnp.where(keep, u, u_best), out, k + 1, ~keep)  # fmt: skip

    lam = -jnp.mean(v).astype(acc)
    c = (lam, jnp.asarray(jnp.inf, acc), v, v, jnp.int32(0), jnp.asarray(False))
    c = lax.while_loop(lambda c: ~c[5] & (c[4] < PROJECTION_MAX_STEPS), step, c)
    return c[3]


def prepare(w, substrate, *, base, wall_tol, tol, max_iter, restart_every, load=None,
            heights=None, law=None):  # fmt: skip
    """The initial state (``w`` projected onto the feasible set) and the :class:`Constants`;
    ``load`` (mean pressure, with ``heights`` and ``law``): load control in the one
    minimisation (:mod:`._free_mean`, its rules from :mod:`.adhesive_rules`)."""
    acc = accumulation_dtype()
    dev = base.device
    multipliers = substrate.multipliers(base)
    single = substrate.multipliers(base.astype(jnp.float32))

    def scalar(v, dtype=acc):
        return jax.device_put(jnp.asarray(v, dtype=dtype), dev)

    i32 = jnp.int32
    k = Constants(
        base=base, stiff=multipliers[_STIFFNESS], green32=single[_COMPLIANCE],
        stiff32=single[_STIFFNESS], modulus=scalar(substrate.contact_modulus),
        wall_tol=scalar(wall_tol, base.dtype), tol=scalar(tol), max_iter=scalar(max_iter, i32),
        restart_every=scalar(restart_every, i32),
    )  # fmt: skip
    if load is not None:  # the free mode's scalars, on the device (no transfer)
        peak = rules.attraction_peak_gap(law) if load < 0 else 0.0
        reach = jnp.maximum(jnp.std(heights.astype(acc)), substrate.pixel_size)
        k = k._replace(
            load=scalar(load), reach=reach,
            size=scalar(max(substrate.shape) * substrate.pixel_size),
            self_stiffness=scalar(substrate.self_stiffness), peak=scalar(peak),
        )  # fmt: skip
    return _initial(w, k, bool(substrate.rigid_mean)), k


@partial(jax.jit, static_argnames=("rigid",))
def _initial(w, k, rigid):
    acc = k.tol.dtype
    pin = rigid and k.load is None  # the rigid mean as a constraint (not under load)
    w = project(w - jnp.mean(w) if rigid else w, -k.base, pin, acc)
    inf, zero_i = jnp.asarray(jnp.inf, acc), jnp.asarray(0, jnp.int32)
    false = jnp.asarray(False)
    zeros = jnp.zeros_like(w)
    return State(
        w=w, kw=_conv(w, k.stiff), s=zeros, z_old=zeros, gz_old=jnp.asarray(1.0, acc),
        active_old=jnp.zeros(w.shape, bool), directions=false, has_old=false,
        exact=jnp.asarray(True), it=zero_i, residual=inf, reliable=inf, since=zero_i,
        iterated=inf, best=inf, since_best=zero_i, mu=jnp.zeros((), acc),
        free=jnp.ones(w.shape, bool), status=zero_i, contact=jnp.zeros(w.shape, bool),
        contact_u=jnp.ones_like(w), contact_k=jnp.ones((), acc), has_contact=false,
    )  # fmt: skip


@partial(
    jax.jit, static_argnames=("law", "rigid", "stall", "crawl"), donate_argnames="st"
)  # the state's buffers are reused
def run(st, k, *, law, rigid, stall, crawl=False):
    """Iterate from ``st`` until the status is not RUNNING; one compiled program.

    ``law``: the hard-core interaction (hashable); ``rigid``: the substrate's uniform mode
    is rigid; ``stall``: the float32 stall guard; ``crawl``: the crawl guard
    (:func:`.loop_control.guarding_crawl`; a stop by it is LIMIT).
    """
    dt, acc = st.w.dtype, st.gz_old.dtype
    f32 = jnp.float32
    lower = -k.base
    rtol = BOUNDED_LINE_SEARCH_RTOL
    free_mode = k.load is not None  # load control in the one minimisation
    pin = rigid and not free_mode  # the rigid mean as a constraint

    def elastic(s, kw):  # s.(K w + N): the load's work enters the slope (free mode)
        return dot(s, kw) + (k.load * tot(s) if free_mode else 0.0)

    def tot(x):
        return jnp.sum(x, dtype=acc)

    def dot(a, b):
        return _dot(a, b, acc)

    def masked_mean(x, mask, fallback):
        count = tot(mask)
        return jnp.where(count > 0, tot(jnp.where(mask, x, 0.0)) / jnp.maximum(count, 1.0),
                         fallback)  # fmt: skip

    def top(w, kw):
        """The gap, the multiplier mu, the active face, the free sites and the free sites'
        force imbalance (:func:`.bounded.minimize_energy_bounded`'s ``top``)."""
        gap = k.base + w
        r = kw - law.pressure(gap)
        on_wall = gap <= k.wall_tol
        mu = -k.load if free_mode else jnp.zeros((), acc)
        if pin:  # every site on the wall: the smallest reaction (bounded_rules)
            mu = masked_mean(r, ~on_wall, jnp.min(r).astype(acc))
        active = on_wall & (r - mu.astype(dt) > 0)
        free = ~active
        if pin:
            mu = masked_mean(r, free, mu)
        return gap, mu, active, free, jnp.where(free, r - mu.astype(dt), 0.0)

    def energy(w, kw):
        e = 0.5 * dot(w, kw) + tot(law.energy(k.base + w))
        return e + k.load * tot(w) if free_mode else e

    def exact_k(w):
        return _conv(w, k.stiff)

    def single(x, kernel):  # a float32 convolution, its result in the fields' dtype
        return _conv(x.astype(f32), kernel).astype(dt)

    def halve(w, s, alpha, e_cur, tries, strict):
        """Projected steps ``w + alpha s``, halving alpha until the energy does not rise
        (``strict``: falls); ``(w, K w, found)``."""

        def body(c):
            alpha, _, _, _, j = c
            w_try = project(w + alpha.astype(dt) * s, lower, pin, acc)
            kw_try = exact_k(w_try)
            e_try = energy(w_try, kw_try)
            found = e_try < e_cur if strict else e_try <= e_cur
            return jnp.where(found, alpha, 0.5 * alpha), w_try, kw_try, found, j + 1

        c = (alpha, w, w, jnp.asarray(False), jnp.int32(0))
        c = lax.while_loop(lambda c: ~c[3] & (c[4] < tries), body, c)
        return c[1], c[2], c[3]

    def from_first_contact(w, s, alpha_max, alpha_top, e_cur):
        """Projected steps ``w + a s``, ``a = alpha_max 2^j`` below ``alpha_top``, upward
        until the energy rises: the lowest if it does not raise ``e_cur`` (the NumPy
        loop's ``_projection._from_first_contact``); ``(w, K w, found)``. Only scalars
        are carried (the state's footprint): the chosen step is formed again."""

        def body(c):
            a, a_b, e_b, found, _, j = c
            w_try = project(w + a.astype(dt) * s, lower, pin, acc)
            e_try = energy(w_try, exact_k(w_try))
            rose = found & (e_try > e_b)
            better = ~rose & (e_try <= e_cur) & (~found | (e_try <= e_b))
            return (2.0 * a, jnp.where(better, a, a_b), jnp.where(better, e_try, e_b),
                    found | better, rose, j + 1)  # fmt: skip

        def more(c):
            return (c[5] < CONTACT_DOUBLINGS) & (c[0] > 0) & (c[0] < alpha_top) & ~c[4]

        a0 = alpha_max.astype(acc)
        c = (a0, a0, e_cur, jnp.asarray(False), jnp.asarray(False), jnp.int32(0))
        _, a_b, _, found, _, _ = lax.while_loop(more, body, c)
        w_b = project(w + a_b.astype(dt) * s, lower, pin, acc)
        return w_b, exact_k(w_b), found

    def cross_the_wall(st, gap, rr, s, ks, alpha, alpha_max):
        """The step crosses the wall: projected and halved, then upward from the first
        wall contact (:data:`.bounded_rules.CONTACT_DOUBLINGS`), else projected gradient."""
        e_cur = energy(st.w, st.kw)
        w1, kw1, found = halve(st.w, s, alpha, e_cur, PROJECTED_HALVINGS, False)
        top = alpha * 0.5 ** (PROJECTED_HALVINGS - 1)  # the last halving tried
        w1, kw1, found = lax.cond(
            found, lambda: (w1, kw1, found),
            lambda: from_first_contact(st.w, s, alpha_max, top, e_cur))  # fmt: skip

        def gradient():  # the projected steepest-descent step (Bertsekas 1976)
            s_g = -rr
            ks_g = exact_k(s_g)
            a, _ = line_minimum(law, gap, s_g, elastic(s_g, st.kw), dot(s_g, ks_g), -dot(rr, rr),
                                acc, rtol)  # fmt: skip
            a = jnp.where(jnp.isfinite(a) & (a > 0), a, 1.0)
            return halve(st.w, s_g, a, e_cur, GRADIENT_HALVINGS, True)

        w1, kw1, found = lax.cond(found, lambda: (w1, kw1, found), gradient)
        status = jnp.where(found, RUNNING, NO_DESCENT).astype(jnp.int32)
        moved = st._replace(w=w1, kw=kw1, exact=jnp.asarray(True), directions=jnp.asarray(False))
        return lax.cond(found, lambda: moved, lambda: st._replace(status=status))

    def iterate(st, gap, mu, active, free, rr):
        it = st.it + 1
        st = st._replace(it=it, since=st.since + 1, mu=mu, free=free)
        z = jnp.where(free, single(rr, k.green32), 0.0)
        if rigid:
            z = jnp.where(free, z - masked_mean(z, free, 0.0).astype(dt), 0.0)
        lost = jnp.asarray(False)
        if free_mode:  # the uniform block on the free sites (FreeMean.add_on)
            n_act = tot(active)
            floor = rules.wall_uniform_stiffness(0.0, k.self_stiffness, k.modulus, k.size,
                                                 xp=jnp)  # fmt: skip
            stale = ~st.has_contact | rules.contact_stale(tot(active != st.contact), n_act,
                                                          xp=jnp)  # fmt: skip

            def fresh():
                a = (n_act / active.size).astype(dt)
                v = single(jnp.where(active, 1.0 - a, -a), k.green32)
                u, k_c = rules.contact_mode(v, active, floor, xp=jnp)
                return active, u, k_c.astype(acc)

            contact, u, k_c = lax.cond(
                stale, fresh, lambda: (st.contact, st.contact_u, st.contact_k))
            st = st._replace(contact=contact, contact_u=u, contact_k=k_c,
                             has_contact=jnp.asarray(True))  # fmt: skip
            u = jnp.where(free, u, 0.0)
            c = rules.uniform_shift(dot(u, rr) / rr.size, k_c, k.reach, xp=jnp)
            z = jnp.where(free, z + c.astype(dt) * u, 0.0)
            lost = rules.tension_lost(law, k.load, jnp.min(gap).astype(acc), k.peak, xp=jnp)
        restart = ~st.directions | (it % k.restart_every == 0) | ~st.has_old
        gz = dot(rr, z)
        restart = restart | jnp.any(active != st.active_old) | (st.gz_old == 0)
        pr = (gz - dot(rr, st.z_old)) / jnp.where(st.gz_old == 0, 1.0, st.gz_old)
        beta = jnp.where(restart, 0.0, jnp.maximum(pr, 0.0))
        s = jnp.where(beta > 0, -z + beta.astype(dt) * st.s, -z)
        slope0 = dot(rr, s)
        ascent = slope0 >= 0
        s, slope0 = jnp.where(ascent, -z, s), jnp.where(ascent, -gz, slope0)
        st = st._replace(s=s, z_old=z, gz_old=gz, active_old=active, has_old=jnp.asarray(True),
                         directions=jnp.asarray(True))  # fmt: skip
        ks = single(s, k.stiff32)
        alpha, _ = line_minimum(law, gap, s, elastic(s, st.kw), dot(s, ks), slope0, acc, rtol)
        crossing = s < 0
        alpha_max = jnp.min(jnp.where(crossing, -gap / jnp.where(crossing, s, -1.0), jnp.inf))
        feasible = alpha <= alpha_max.astype(acc)
        moved = st._replace(w=st.w + alpha.astype(dt) * s, kw=st.kw + alpha.astype(dt) * ks,
                            exact=jnp.asarray(False))  # fmt: skip
        failed = st._replace(status=jnp.int32(LINE_SEARCH_FAILED))
        if free_mode:  # a lost tensile load stops before the step, as the NumPy loop does
            code = jnp.where(lost, DETACHED, LINE_SEARCH_FAILED).astype(jnp.int32)
            failed, alpha = failed._replace(status=code), jnp.where(lost, jnp.nan, alpha)
        return lax.cond(
            ~jnp.isfinite(alpha),
            lambda: failed,
            lambda: lax.cond(feasible, lambda: moved,
                             lambda: cross_the_wall(st, gap, rr, s, ks, alpha, alpha_max)),
        )  # fmt: skip

    def proceed(st, residual, gap, mu, active, free, rr):
        drifted = residual > 2.0 * st.iterated
        st = lax.cond(
            st.exact,
            lambda: st._replace(reliable=residual, since=jnp.int32(0),
                                iterated=jnp.asarray(jnp.inf, acc),
                                directions=st.directions & ~drifted),
            lambda: st,
        )  # fmt: skip
        stalled = jnp.asarray(False)
        if stall or crawl:  # the crawl guard replaces the float32 stall guard (loop_control)
            factor = CRAWL_IMPROVEMENT if crawl else STALL_IMPROVEMENT
            improved = residual < factor * st.best
            st = st._replace(best=jnp.where(improved, residual, st.best),
                             since_best=jnp.where(improved, 0, st.since_best + 1))  # fmt: skip
            stalled = st.since_best >= (CRAWL_PATIENCE if crawl else STALL_PATIENCE)
        done = (residual <= k.tol) | ~jnp.any(free)
        status = jnp.select([done, stalled, st.it >= k.max_iter],
                            [CONVERGED, LIMIT if crawl else STALLED, LIMIT],
                            RUNNING).astype(jnp.int32)  # fmt: skip
        st = st._replace(residual=residual)
        stop = st._replace(status=status, mu=mu, free=free)
        return lax.cond(status == RUNNING, lambda: iterate(st, gap, mu, active, free, rr),
                        lambda: stop)  # fmt: skip

    def body(st):
        gap, mu, active, free, rr = top(st.w, st.kw)
        residual = jnp.max(jnp.abs(rr)).astype(acc) / k.modulus
        due = (residual <= k.tol) | (residual <= RELIABLE_DROP * st.reliable)
        due = ~st.exact & (due | (st.since >= RELIABLE_EVERY))
        branch = jnp.where(~jnp.isfinite(residual), 0, jnp.where(due, 1, 2))
        return lax.switch(branch, [
            lambda: st._replace(residual=residual, status=jnp.int32(NON_FINITE), mu=mu,
                                free=free),
            lambda: st._replace(kw=exact_k(st.w), exact=jnp.asarray(True), iterated=residual),
            lambda: proceed(st, residual, gap, mu, active, free, rr),
        ])  # fmt: skip

    return lax.while_loop(lambda st: st.status == RUNNING, body, st)


@partial(jax.jit, static_argnames=("law",))
def fields(st, k, law):
    """The traction (interaction pressure on free sites, elastic pressure on the wall),
    the repulsive and attractive masks and the deflection."""
    p = law.pressure(k.base + st.w)
    traction = jnp.where(st.free, p, st.kw - st.mu.astype(st.kw.dtype))
    return traction, traction > 0, traction < 0, st.w


@partial(jax.jit, static_argnames=("law",))
def moved_fields(st, k, law, offset):
    """:func:`fields` after load control in the one minimisation: the offset moved with
    the mean of ``w`` (as :func:`.bounded.minimize_energy_bounded`), ``w`` mean-free."""
    traction, rep, att, w = fields(st, k, law)
    moved = jnp.mean(w.astype(k.tol.dtype))
    return traction, rep, att, w - moved.astype(w.dtype), offset + moved
