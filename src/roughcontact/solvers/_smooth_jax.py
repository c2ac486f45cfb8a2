"""The smooth-interaction minimiser as one compiled JAX program (``jax.jit`` + ``lax.while_loop``).

The method of :mod:`.smooth` (nonlinear conjugate gradients, Polak–Ribière+, the block
preconditioner of Green's function and stiff-site diagonal, the line search of
:mod:`.line_search` with the bracketing of :mod:`.roots`, exact refreshes of ``K w`` as
:class:`.loop_control.ReliableUpdates` says, the float32 stall guard and the float64
floor guard), for heights given as JAX arrays, under displacement control on a periodic
substrate, or under load control with the load inside the one minimisation
(:mod:`._free_mean`'s method: the gap's uniform mode free, gradient ``K w - p_int + N``,
the preconditioner's block on the uniform mode and the lift at fixed contact, a lost
tensile load; its rules :mod:`.adhesive_rules`' functions, called on 0-d device arrays).
Its constants are those
of :mod:`.smooth_rules` and :mod:`.loop_control`, shared with the NumPy loop. The whole
solve is one XLA program: the state is a
:class:`State` record of device arrays, every decision (the line search's bracket and
regula falsi steps included) is a ``where`` selection, a ``lax.cond`` or a
``lax.while_loop`` on the device, and nothing reaches the host until the loop ends
(tested under ``jax.transfer_guard("disallow")``); the host then reads the iteration
count, residual and status in one transfer.

Differences from the NumPy loop, all deliberate: the interaction is evaluated on every
site (a law vanishes exactly beyond its cutoff, so the values are those of the NumPy
loop's band of sites), and sums run in XLA's order, so the iterates agree to rounding.
The convolutions that only steer (the Green's-function block) or update ``K w`` by
increments (``K z``) run in float32 as there; ``K w`` is recomputed in the heights'
precision, and for float32 heights from the deflection advanced beside the gap, in
float64 where ``jax_enable_x64`` allows it (as the NumPy loop; :func:`_initial`).

Precision: float64 needs ``jax_enable_x64`` while the program runs (see
:func:`._jax_common.precision_scope`); with it the sums are accumulated in float64.
"""

from __future__ import annotations

from functools import partial
from typing import NamedTuple

import jax
import jax.numpy as jnp
from jax import lax

from . import adhesive_rules as rules
from .loop_control import RELIABLE_DROP, RELIABLE_EVERY, STALL_IMPROVEMENT, STALL_PATIENCE
from .smooth_rules import (
    EPS64,
    FLOOR_PATIENCE,
    FLOOR_ULPS,
    GUESS_MAX,
    GUESS_MIN,
    LINE_SEARCH_MAX_EVAL,
    LINE_SEARCH_RTOL,
    STIFF_FRACTION,
)

__all__ = ["Constants", "State", "line_minimum", "prepare", "run"]

_STIFFNESS, _COMPLIANCE = 0, 1  # the fields of FourierMultipliers
#: The status codes the loop leaves in ``State.status``.
RUNNING, CONVERGED, LIMIT, STALLED, FLOOR, NON_FINITE, LINE_SEARCH_FAILED, DETACHED = range(8)


class Constants(NamedTuple):
    """The problem, as device arrays (the compiled program's inputs)."""

    base: object  # offset - heights (2D): the gap is base + w
    stiff: object  # stiffness multipliers, the fields' dtype (rfft2 layout)
    green32: object  # compliance multipliers in float32 (the preconditioner's)
    stiff32: object  # stiffness multipliers in float32 (K z)
    green: object  # compliance multipliers, the fields' dtype (no stiff site yet)
    modulus: object  # E* (pressure)
    self_stiffness: object  # K_ii (pressure/length)
    tol: object
    max_iter: object  # (int32)
    restart_every: object  # (int32)
    refresh_every: object  # (int32)
    refresh_at_once: object  # a warm start refreshes the stiff sites at once (bool)
    # load control in the one minimisation (:mod:`._free_mean`; None: offset control)
    load: object = None  # the mean pressure to carry
    reach: object = None  # the uniform shift's bound, max(std(h), a0) (length)
    size: object = None  # the substrate's longer side (length; k_u's elastic floor)
    peak: object = None  # the gap of the law's largest tension (a tensile load)
    # float32 fields with float64 available: the stiffness multipliers in float64, for the
    # exact K w (a float32 FFT's own error, ~1e-7 log2(sites) of the largest pressure, set
    # a residual floor of ~3e-6 E* at 4096²); None: K w in the fields' dtype
    stiff_exact: object = None


class State(NamedTuple):
    """The loop's state: device arrays only (scalars 0-d, in the accumulation dtype)."""

    gap: object  # the iterate (2D)
    kw: object  # K w (updated by increments between exact refreshes)
    gr: object  # the force imbalance K w - p_int (mean-free with a rigid mean)
    p: object  # the interaction pressure at gap
    s: object  # the search direction and ...
    ks: object  # ... its elastic pressure
    z_old: object  # the last preconditioned gradient and ...
    gz_old: object  # ... its product with the gradient
    stiff: object  # the preconditioner's stiff sites (bool, 2D) and ...
    diagonal: object  # ... 1/(K_ii + V'') there, zero elsewhere
    has_stiff: object  # whether any site is stiff (bool)
    directions: object  # whether s, ks hold conjugate directions to build on (bool)
    exact: object  # whether kw is K w from a fresh convolution (bool)
    it: object  # iterations (int32)
    residual: object  # the residual at the top of the last iteration
    reliable: object  # ReliableUpdates: the residual of the last exact state, ...
    since: object  # ... the iterations since it (int32) and ...
    iterated: object  # ... the incremental residual that asked for the refresh
    best: object  # StallGuard (float32): the best residual and ...
    since_best: object  # ... the iterations since it improved (int32)
    reference: object  # FloorGuard (float64): the best residual that halved, ...
    floor_best: object  # ... the best residual and ...
    floor_since: object  # ... the iterations since the reference (int32)
    status: object  # RUNNING or why the loop stopped (int32)
    k_u: object = None  # the uniform mode's stiffness (load control; None: offset control)
    # load control: the second uniform direction, the lift at fixed contact (FreeMean.add,
    # _free_mean.lift_mode), its K u, the block's (h00, h01, h11) and whether it is set
    lift_u: object = None
    lift_ku: object = None
    lift_h: object = None
    has_lift: object = None
    w: object = None  # float32: the deflection, advanced with the gap (None in float64)


def _conv(x, kernel):
    return jnp.fft.irfft2(jnp.fft.rfft2(x) * kernel, s=x.shape).astype(x.dtype)


def accumulation_dtype():
    """float64 when JAX may make it (``jax_enable_x64``), else float32."""
    return jnp.float64 if bool(jax.config.jax_enable_x64) else jnp.float32


def prepare(w, substrate, interaction, *, base, tol, max_iter, restart_every, refresh_every,
            warm, load=None, heights=None):  # fmt: skip
    """The initial state and the :class:`Constants` on the heights' device.

    ``w``: the initial deflection (2D JAX array, mean-free with a rigid mean); ``base``
    ``offset - heights`` (2D); ``warm``: whether ``w`` is a warm start; ``load`` (mean
    pressure, with ``heights``): load control in the one minimisation, the gap's uniform
    mode free (:mod:`._free_mean`, its rules from :mod:`.adhesive_rules`).
    """
    acc = accumulation_dtype()
    dev = base.device
    multipliers = substrate.multipliers(base)
    stiff, green = multipliers[_STIFFNESS], multipliers[_COMPLIANCE]
    single = substrate.multipliers(base.astype(jnp.float32))

    def scalar(v, dtype=acc):
        return jax.device_put(jnp.asarray(v, dtype=dtype), dev)

    i32 = jnp.int32
    k = Constants(
        base=base, stiff=stiff, green32=single[_COMPLIANCE], stiff32=single[_STIFFNESS],
        green=green, modulus=scalar(substrate.contact_modulus),
        self_stiffness=scalar(substrate.self_stiffness), tol=scalar(tol),
        max_iter=scalar(max_iter, i32), restart_every=scalar(restart_every, i32),
        refresh_every=scalar(refresh_every, i32), refresh_at_once=scalar(warm, bool),
    )  # fmt: skip
    if load is not None:  # the free mode's scalars, on the device (no transfer)
        reach = jnp.maximum(jnp.std(heights.astype(acc)), substrate.pixel_size)
        peak = rules.attraction_peak_gap(interaction) if load < 0 else 0.0
        k = k._replace(load=scalar(load), reach=reach, size=scalar(
            max(substrate.shape) * substrate.pixel_size), peak=scalar(peak))  # fmt: skip
    if base.dtype == jnp.float32 and acc == jnp.float64:
        k = k._replace(stiff_exact=substrate.multipliers(base.astype(acc))[_STIFFNESS])
    st = _initial(w, k, interaction, bool(substrate.rigid_mean))
    if load is not None:
        # set at the first iteration (two buffers: the state's are donated)
        st = st._replace(k_u=scalar(1.0), lift_u=jnp.zeros_like(st.gap),
                         lift_ku=jnp.zeros_like(st.gap),
                         lift_h=jnp.ones((3,), acc), has_lift=jnp.asarray(False))  # fmt: skip
    return st, k


@partial(jax.jit, static_argnames=("law", "rigid"))
def _initial(w, k, law, rigid):
    acc = k.tol.dtype
    kw = _exact_kw(w, k)
    gap = k.base + w
    p = law.pressure(gap)
    inf, zero_i = jnp.asarray(jnp.inf, acc), jnp.asarray(0, jnp.int32)
    false, true = jnp.asarray(False), jnp.asarray(True)
    zeros = jnp.zeros_like(gap)
    # float32 also advances the deflection w itself: K w formed from gap - base carries the
    # gap's rounding, ulp(max gap) ~ 4e-6 a0 where the gap spans 40 a0 (4096² surfaces), and
    # that set a residual floor of ~E* ulp(max gap) / a0; w's own rounding is ulp(max |w|)
    single = gap.dtype == jnp.float32
    return State(
        gap=gap, kw=kw, gr=_imbalance(kw, p, rigid, k.load), p=p, s=zeros, ks=zeros, z_old=zeros,
        gz_old=jnp.asarray(1.0, acc), stiff=jnp.zeros(gap.shape, bool), diagonal=zeros,
        has_stiff=false, directions=false, exact=true, it=zero_i, residual=inf,
        reliable=inf, since=zero_i, iterated=inf, best=inf, since_best=zero_i,
        reference=inf, floor_best=inf, floor_since=zero_i, status=zero_i,
        w=w.astype(gap.dtype) if single else None,
    )  # fmt: skip


def _exact_kw(w, k):
    """``K w`` in the fields' dtype, convolved in float64 where :class:`Constants` holds
    the float64 multipliers (float32 fields, ``jax_enable_x64``)."""
    if k.stiff_exact is None:
        return _conv(w, k.stiff)
    return _conv(w.astype(k.stiff_exact.dtype), k.stiff_exact).astype(w.dtype)


def _imbalance(kw, p, rigid, load=None):
    """K w - p_int, without its mean when the uniform mode is rigid (its force is the load);
    under load control in the one minimisation (``load``, mean pressure) ``K w - p_int + N``
    (the enthalpy's gradient: its mean is the load not carried)."""
    if load is not None:
        return kw + load.astype(kw.dtype) - p
    if not rigid:
        return kw - p
    acc = accumulation_dtype()
    m = (jnp.sum(kw, dtype=acc) - jnp.sum(p, dtype=acc)) / kw.size
    return kw - m.astype(kw.dtype) - p


def _dot(a, b, acc):
    """Inner product accumulated in ``acc`` (the factors widened first, as NumPy's einsum)."""
    return jnp.sum(a.astype(acc) * b.astype(acc))


def line_minimum(law, gap, s, c0, c1, slope0, acc, rtol=LINE_SEARCH_RTOL):
    """:func:`.line_search.line_minimum` on the device: the step ``alpha`` along ``s`` from
    ``gap`` (NaN when no bracket is found) and the interaction pressure there.

    The directional slope is ``phi'(alpha) = c0 + alpha c1 - s.p_int(gap + alpha s)``
    (``c0 = s.K w``, ``c1 = s.K s``). The Newton guess with the curvature at 0, clipped to
    [GUESS_MIN, GUESS_MAX], is taken when ``|phi'| <= rtol |phi'(0)|``; else
    the step doubles until the slope is not negative and :func:`.roots.bracketed_root`'s
    regula falsi with Anderson–Björck updates and bisection safeguards finds the root,
    in at most LINE_SEARCH_MAX_EVAL evaluations in all.
    """
    dt = gap.dtype
    rtol_slope = rtol * jnp.abs(slope0)

    def slope(alpha):
        p = law.pressure(gap + alpha.astype(dt) * s)
        return c0 + alpha * c1 - _dot(s, p, acc), p

    curv = _dot(s * s, law.curvature(gap), acc) + c1
    convex = curv > 0
    hi = jnp.where(convex, -slope0 / jnp.where(convex, curv, 1.0), 1.0)
    hi = jnp.clip(hi, GUESS_MIN, GUESS_MAX).astype(acc)
    f_hi, p_hi = slope(hi)
    ok = jnp.abs(f_hi) <= rtol_slope
    zero = jnp.zeros((), acc)

    def doubling(c):  # bracket: (lo, f_lo, hi, f_hi, p, evaluations)
        lo, f_lo, hi, f_hi, p, k = c
        f_2, p_2 = slope(2.0 * hi)
        return hi, f_hi, 2.0 * hi, f_2, p_2, k + 1

    lo, f_lo, hi, f_hi, p_hi, n_eval = lax.while_loop(
        lambda c: ~ok & (c[3] < 0) & (c[5] < LINE_SEARCH_MAX_EVAL),
        doubling, (zero, slope0, hi, f_hi, p_hi, jnp.int32(1)),
    )  # fmt: skip
    failed = ~ok & (f_hi < 0)

    def regula_falsi(c):  # (a, f_a, b, f_b, x, p, bisect, k, done)
        a, f_a, b, f_b, _, _, bisect, k, _ = c
        d = f_b - f_a
        x = (a * f_b - b * f_a) / jnp.where(d != 0, d, 1.0)
        inside = (d != 0) & (jnp.minimum(a, b) < x) & (x < jnp.maximum(a, b))
        x = jnp.where(bisect, 0.5 * (a + b), jnp.where(inside, x, 0.5 * (a + b)))
        f_x, p = slope(x)
        done = jnp.abs(f_x) <= rtol_slope
        bisect = ((f_x > 0) == (f_b > 0)) & (jnp.abs(f_x) > 0.5 * jnp.abs(f_b))
        same = (f_x > 0) == (f_b > 0)  # Anderson-Björck: keep a, scale f_a
        m = jnp.where(f_b != 0, 1.0 - f_x / jnp.where(f_b != 0, f_b, 1.0), 0.0)
        a, f_a = jnp.where(same, a, b), jnp.where(same, f_a * jnp.where(m > 0, m, 0.5), f_b)
        return a, f_a, x, f_x, x, p, bisect, k + 1, done

    left = LINE_SEARCH_MAX_EVAL - n_eval
    c = (lo, f_lo, hi, f_hi, hi, p_hi, jnp.asarray(False), jnp.int32(0), ok | failed)
    c = lax.while_loop(lambda c: ~c[8] & (c[7] < left), regula_falsi, c)
    alpha = jnp.where(failed, jnp.nan, c[4])
    return alpha, c[5]


@partial(
    jax.jit, static_argnames=("law", "rigid", "stall", "floor"), donate_argnames="st"
)  # the state's buffers are reused
def run(st, k, *, law, rigid, stall, floor):
    """Iterate from ``st`` until the status is not RUNNING; one compiled program.

    ``law``: the interaction (hashable); ``rigid``: the substrate's uniform mode is
    rigid; ``stall``/``floor``: the float32 stall guard / the float64 floor guard.
    """
    dt, acc = st.gap.dtype, st.gz_old.dtype
    f32 = jnp.float32
    free = k.load is not None  # load control in the one minimisation (a static structure)
    n = st.gap.size

    def tot(x):
        return jnp.sum(x, dtype=acc)

    def dot(a, b):
        return _dot(a, b, acc)

    def precondition(st, gr):
        """``z`` (the block-preconditioned ``gr``) and ``K z`` (see :mod:`._block`)."""

        def green_only():  # K K^-1 is the identity on the non-uniform modes
            return _conv(gr, k.green), gr

        def block():
            soft_block = _conv(jnp.where(st.stiff, 0.0, gr.astype(f32)), k.green32)
            z_stiff = gr * st.diagonal  # zero off the stiff sites
            shift = jnp.zeros((), acc)
            if rigid:  # the mean of z
                stiff_block = tot(jnp.where(st.stiff, soft_block, 0.0))
                shift = (tot(soft_block) - stiff_block + tot(z_stiff)) / n
            shift = shift.astype(dt)
            z = jnp.where(st.stiff, z_stiff - shift, soft_block.astype(dt) - shift)
            return z, _conv(z.astype(f32), k.stiff32).astype(dt)

        return lax.cond(st.has_stiff, block, green_only)

    def stiff_sites(st):
        curvature = law.curvature(st.gap)
        stiff = curvature > (STIFF_FRACTION * k.self_stiffness).astype(dt)
        inverse = 1.0 / (k.self_stiffness.astype(dt) + jnp.where(stiff, curvature, 0.0))
        return st._replace(stiff=stiff, diagonal=jnp.where(stiff, inverse, 0.0),
                           has_stiff=jnp.any(stiff))  # fmt: skip

    def iterate(st):
        it = st.it + 1
        st = st._replace(it=it, since=st.since + 1)
        restart = ~st.directions | (it % k.restart_every == 0)
        refresh = (it % k.refresh_every == 0) | ((it == 1) & k.refresh_at_once)
        st = lax.cond(refresh, stiff_sites, lambda st: st, st)
        if free:  # the block on the mean-free part, the uniform block (:mod:`._free_mean`)
            mean = tot(st.gr) / n
            z, kz = precondition(st, st.gr - mean.astype(dt))
            st, lost = uniform_block(st, it)
            h = st.lift_h
            c0, c1 = rules.pair_coefficients(h[0], h[1], h[2], mean, dot(st.lift_u, st.gr) / n,
                                             k.reach, xp=jnp)  # fmt: skip
            c0 = jnp.where(st.has_lift, c0, rules.uniform_shift(mean, st.k_u, k.reach, xp=jnp))
            c1 = jnp.where(st.has_lift, c1, 0.0).astype(dt)
            z = z + c0.astype(dt) + c1 * st.lift_u
            kz = kz + c1 * st.lift_ku
        else:
            z, kz = precondition(st, st.gr)
        gz = dot(st.gr, z)
        restart = restart | (st.gz_old == 0)
        pr = (gz - dot(st.gr, st.z_old)) / jnp.where(st.gz_old == 0, 1.0, st.gz_old)
        beta = jnp.where(restart, 0.0, jnp.maximum(pr, 0.0))
        s = beta.astype(dt) * st.s - z
        slope0 = dot(st.gr, s)
        ascent = slope0 >= 0  # not a descent direction: along the preconditioned -gr
        s = jnp.where(ascent, -z, s)
        slope0, beta = jnp.where(ascent, -gz, slope0), jnp.where(ascent, 0.0, beta)
        ks = beta.astype(dt) * st.ks - kz
        elastic_slope = slope0 + dot(s, st.p)  # s.K w (s.gr = s.K w - s.p_int)
        alpha, p = line_minimum(law, st.gap, s, elastic_slope, dot(s, ks), slope0, acc)
        moved = st._replace(
            gap=st.gap + alpha.astype(dt) * s, kw=st.kw + alpha.astype(dt) * ks, p=p, s=s,
            ks=ks, z_old=z, gz_old=gz, directions=jnp.asarray(True), exact=jnp.asarray(False),
            w=None if st.w is None else st.w + alpha.astype(dt) * s,
        )  # fmt: skip
        moved = moved._replace(gr=_imbalance(moved.kw, p, rigid, k.load))
        failed = st._replace(status=jnp.int32(LINE_SEARCH_FAILED))
        if free:  # a lost tensile load stops before the step, as the NumPy loop does
            code = jnp.where(lost, DETACHED, LINE_SEARCH_FAILED).astype(jnp.int32)
            failed = failed._replace(status=code)
            return lax.cond(jnp.isfinite(alpha) & ~lost, lambda: moved, lambda: failed)
        return lax.cond(jnp.isfinite(alpha), lambda: moved, lambda: failed)

    def uniform_block(st, it):
        """``k_u`` refreshed (at iteration 1 and every ``refresh_every``-th + 1, as
        :class:`._free_mean.FreeMean`) by :func:`.adhesive_rules.uniform_stiffness`; and
        whether a tensile load is lost (:func:`.adhesive_rules.tension_lost`)."""
        due = (it == 1) | (it % k.refresh_every == 1)
        curvature = lambda: tot(jnp.maximum(law.curvature(st.gap), 0.0)) / n  # noqa: E731
        mean_curv = lax.cond(due, curvature, lambda: jnp.zeros((), acc))
        k_u = rules.uniform_stiffness(mean_curv, k.modulus, k.size, xp=jnp)
        st = st._replace(k_u=jnp.where(due, k_u, st.k_u))

        def lift():  # _free_mean.lift_mode: two float32 convolutions
            c = law.curvature(st.gap)
            d = jnp.where(c > 0, c, 0.0)  # (a NaN counts as 0, as in k_u)
            stiff = d > (STIFF_FRACTION * k.self_stiffness).astype(dt)
            a = (tot(stiff) / n).astype(dt)
            v = _conv(jnp.where(stiff, 1.0 - a, -a).astype(f32), k.green32).astype(dt)
            u, ok = rules.lift_shape(v, stiff, xp=jnp)
            ku = _conv(u.astype(f32), k.stiff32).astype(dt)
            h = rules.lift_block(d, u, ku, k.modulus * jnp.pi / k.size, tot, dot, xp=jnp)
            h = jnp.stack(h).astype(acc)
            return u, ku, h, ok

        u, ku, h, ok = lax.cond(due, lift, lambda: (st.lift_u, st.lift_ku, st.lift_h,
                                                      st.has_lift))  # fmt: skip
        st = st._replace(lift_u=u, lift_ku=ku, lift_h=h, has_lift=ok)
        lost = rules.tension_lost(law, k.load, jnp.min(st.gap).astype(acc), k.peak, xp=jnp)
        return st, lost

    def exact_refresh(st, residual):
        kw = _exact_kw(_deflection(st, k), k)
        if st.w is not None:  # float32: the gap (and its pressure) re-formed from w, which
            # clears the rounding the gap's increments gathered since the last refresh
            gap = k.base + st.w
            st = st._replace(gap=gap, p=law.pressure(gap))
        return st._replace(kw=kw, gr=_imbalance(kw, st.p, rigid, k.load),
                           exact=jnp.asarray(True), iterated=residual)  # fmt: skip

    def proceed(st, residual):
        # ReliableUpdates.check on an exact state: restart directions that had drifted
        drifted = residual > 2.0 * st.iterated
        st = lax.cond(
            st.exact,
            lambda: st._replace(reliable=residual, since=jnp.int32(0),
                                iterated=jnp.asarray(jnp.inf, acc),
                                directions=st.directions & ~drifted),
            lambda: st,
        )  # fmt: skip
        stalled = jnp.asarray(False)
        if stall:  # StallGuard (float32)
            improved = residual < STALL_IMPROVEMENT * st.best
            st = st._replace(best=jnp.where(improved, residual, st.best),
                             since_best=jnp.where(improved, 0, st.since_best + 1))  # fmt: skip
            stalled = st.since_best >= STALL_PATIENCE
        at_floor = jnp.asarray(False)
        if floor:  # FloorGuard (float64)
            best = jnp.minimum(st.floor_best, residual)
            halved = best < 0.5 * st.reference
            since = jnp.where(halved, 0, st.floor_since + 1)
            due = ~halved & (since >= FLOOR_PATIENCE)
            scale = lax.cond(due, lambda: jnp.max(jnp.abs(st.p)).astype(acc),
                             lambda: jnp.zeros((), acc))  # (a pass only when due)  # fmt: skip
            at_floor = due & (best <= FLOOR_ULPS * (EPS64 * scale / k.modulus))
            renew = halved | (due & ~at_floor)  # slow but above the floor: a new window
            st = st._replace(floor_best=best, reference=jnp.where(renew, best, st.reference),
                             floor_since=jnp.where(renew, 0, since))  # fmt: skip
        status = jnp.select(
            [residual <= k.tol, stalled, at_floor, st.it >= k.max_iter],
            [CONVERGED, STALLED, FLOOR, LIMIT], RUNNING,
        ).astype(jnp.int32)  # fmt: skip
        st = st._replace(residual=residual)
        return lax.cond(status == RUNNING, iterate, lambda st: st._replace(status=status), st)

    def body(st):
        residual = jnp.max(jnp.abs(st.gr)).astype(acc) / k.modulus
        due = (residual <= k.tol) | (residual <= RELIABLE_DROP * st.reliable)
        due = ~st.exact & (due | (st.since >= RELIABLE_EVERY))
        branch = jnp.where(~jnp.isfinite(residual), 0, jnp.where(due, 1, 2))
        return lax.switch(branch, [
            lambda st, r: st._replace(residual=r, status=jnp.int32(NON_FINITE)),
            exact_refresh,
            proceed,
        ], st, residual)  # fmt: skip

    return lax.while_loop(lambda st: st.status == RUNNING, body, st)


@partial(jax.jit, static_argnames=("law",))
def fields(st, k, law):
    """The interaction pressure, the repulsive and attractive masks and the deflection."""
    rep, att = law.classify(st.gap)
    return law.pressure(st.gap), rep, att, _deflection(st, k)


def _deflection(st, k):
    """The deflection: float32 advances it itself (see :func:`_initial`), float64 is exact
    as ``gap - base``."""
    return st.gap - k.base if st.w is None else st.w


@partial(jax.jit, static_argnames=("law",))
def moved_fields(st, k, law, offset):
    """:func:`fields` after load control in the one minimisation: the offset moved with
    the gap's mean (:meth:`._free_mean.FreeMean.moved`), the deflection mean-free."""
    shift = jnp.mean(_deflection(st, k).astype(k.tol.dtype))
    p, rep, att, deflection = fields(st, k, law)
    return p, rep, att, deflection - shift.astype(deflection.dtype), offset + shift
