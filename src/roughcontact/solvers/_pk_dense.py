"""Polonsky-Keer iterations on full-grid masks, for any array-API backend (CuPy on a GPU).

The same steps as the index-array loop in :mod:`._pk_sparse` (see :mod:`.polonsky_keer`
for the method and the residual), written with masks because the array API has no
integer-array assignment. Every pass is over the whole grid, which a GPU does at memory
bandwidth.

Structure (init / step / terminate, as in optimistix; the driver is :mod:`._blocks`):
:meth:`_Dense.init` builds a :class:`State` record of device arrays (2D fields, (1, 1)
scalars), :meth:`_Dense.step` advances it by one iteration without any host sync, and the
host reads a few scalars once per block of steps (:class:`._blocks.Schedule`: up to
:data:`._blocks.BLOCK` = 8 steps). The sequential loop's branches are ``where``
selections or unconditional work: the projection is always applied (a no-op when no site
changes), and the deflection's correction is always a (float32) convolution of the
correction, zero when nothing changed (the NumPy loop adds point responses when one or
two sites change: a different rounding of the same increment, within the single-precision
increments that exact refreshes remove). The decisions that need the host (convergence, an
exact refresh of ``G p - h`` as :class:`.loop_control.ReliableUpdates` says, a lost contact
set, the return of preconditioning after one, a non-finite value, the float32 stall guard)
are tested on the device at the top of every step; a step whose top needs one leaves the
state unchanged ("frozen"), so the host finds it where the sequential loop decides, and
:meth:`_Dense.host_top` takes the decision there: the same iterations as the NumPy loop,
reported as it counts them (the first converged iteration).
"""

from __future__ import annotations

import math
from typing import NamedTuple

from .._backend import array_device, array_namespace, convolve, dtype_name
from ._blocks import Schedule
from .loop_control import RELIABLE_DROP, RELIABLE_EVERY, ReliableUpdates, StallGuard, stopping
from .pk_rules import JOINING_KEEPS_DIRECTIONS, StepKind
from .reductions import fetch
from .result import SolveStatus

__all__ = ["State", "iterate_dense"]

_STIFFNESS, _COMPLIANCE = 0, 1  # the fields of FourierMultipliers


class State(NamedTuple):
    """The loop's state: device arrays only (frozen: each step makes a new record)."""

    p: object  # pressure (2D)
    s: object  # G p - h (2D), so that the gap is s + d
    t: object  # the search direction (2D; zero off the contact set)
    c: object  # the contact set (bool 2D) ...
    cf: object  # ... as 0/1 in the fields' dtype (masks by a product: exact, finite fields)
    g_old: object  # g.z of the last step ((1, 1) float64)
    delta: object  # whether t holds conjugate directions to build on ((1, 1) bool)
    it: object  # iterations ((1, 1) float64)
    tau: object  # the last step length tried ((1, 1) float64; NaN: a breakdown)
    residual: object  # the residual at the top of the last step taken ((1, 1) float64)
    best: object  # the float32 stall guard's best residual and ...
    since: object  # ... the tops since it improved ((1, 1) float64; float32 solves only)


def _fetch(xp, scalars):
    """The (1, 1) device scalars as Python floats, in one transfer (one host sync)."""
    return fetch(xp, [xp.reshape(x, ()) for x in scalars])


def _fast_operator(substrate, which, like32):
    """A 2D patch field through one of the substrate's Fourier multipliers, in float32."""
    xp = array_namespace(like32)
    kernel = substrate.multipliers(like32)[which]
    padded = tuple(substrate.work_shape) != tuple(substrate.shape)
    f32 = like32.dtype

    def apply(x):
        x = x if x.dtype == f32 else xp.astype(x, f32)
        if padded:
            return substrate.crop(convolve(substrate.embed(x), kernel))
        return convolve(x, kernel)

    return apply


class _Dense:
    """One hard-wall solve off NumPy: constants, the step, and the host's decisions."""

    def __init__(self, pb, substrate):
        self.pb = pb
        xp = self.xp = array_namespace(pb.hf)
        self.shape = tuple(pb.shape)
        self.hf = xp.reshape(pb.hf, self.shape)
        dt, f64, dev = pb.hf.dtype, xp.float64, array_device(pb.hf)
        self.dt, self.f64, self.dev = dt, f64, dev
        self.load = pb.target is not None
        like32 = xp.zeros((1, 1), dtype=xp.float32, device=dev)
        self.green = _fast_operator(substrate, _COMPLIANCE, like32)
        self.stiff = None
        if pb.precondition is not None:
            self.stiff = _fast_operator(substrate, _STIFFNESS, like32)
        # every constant a step uses is a (1, 1) array made once (a Python scalar operand
        # would be converted, i.e. a new array, at every use)
        c = self.const
        self.zero, self.zero64, self.one64, self.nan64 = (
            c(0.0),
            c(0.0, f64),
            c(1.0, f64),
            c(math.nan, f64),
        )
        self.inf64, self.scale = c(math.inf, f64), c(pb.scale, f64)
        self.true = xp.full((1, 1), True, dtype=xp.bool, device=dev)
        self.joining = c(JOINING_KEEPS_DIRECTIONS, f64)
        self.fixed = None if self.load else c(pb.offset)
        self.target = c(pb.target, f64) if self.load else None
        self.site_stiffness, self.n = c(pb.site_stiffness, f64), c(pb.hf.shape[0], f64)
        self.improves, self.patience = c(0.99, f64), None  # float32 stall guard
        self.kind = StepKind(pb.precondition is not None)
        self.reliable = ReliableUpdates(pb.tol)
        self.stall = StallGuard(dtype_name(pb.hf))
        if self.stall.active:
            self.patience = c(float(self.stall.patience), f64)

    def const(self, value, dtype=None):
        # scalars are (1, 1) arrays, not 0-d: the array API's 0-d operands are promoted
        # to a dimension of their own (array_api_strict: one array more per operation)
        return self.xp.full((1, 1), value, dtype=dtype or self.dt, device=self.dev)

    def in_dt(self, x):  # a float64 scalar in the fields' precision (as a Python float is)
        return x if x.dtype == self.dt else self.xp.astype(x, self.dt)

    def total(self, x):  # sum accumulated in float64, a (1, 1) array
        return self.xp.sum(x, dtype=self.f64, keepdims=True)

    def init(self, p):
        """The state at pressure ``p`` (flat), with ``G p - h`` evaluated exactly."""
        xp, z64 = self.xp, self.zero64
        p = xp.reshape(p, self.shape)
        c = p > self.zero
        return State(p, self.exact_s(p), xp.zeros_like(p), c, xp.astype(c, self.dt),
                     self.one64, ~self.true, z64, z64, z64, z64, z64)  # fmt: skip

    def restart(self, st, p, c):
        """``st`` restarted at pressure ``p`` (2D) on the contact set ``c``: exact
        ``G p - h``, no conjugate directions (the iteration count goes on)."""
        cf = self.xp.astype(c, self.dt)
        return st._replace(p=p, s=self.exact_s(p), c=c, cf=cf, delta=~self.true)

    def exact_s(self, p):
        """``G p - h`` from a float64 convolution (an exact refresh)."""
        xp = self.xp
        return xp.reshape(self.pb.conv(xp.reshape(p, (-1,))), self.shape) - self.hf

    def top(self, st, pre):
        """The gap, the contact set a step acts on (with the interpenetrating sites when
        ``pre``: they join it), the gap on it, the set's size before (``n_c``) and after,
        and the residual (float64 (1, 1))."""
        xp, s, c, cf = self.xp, st.s, st.c, st.cf
        n_c = self.total(cf)
        if self.load:
            gap = s - self.in_dt(self.total(s * cf) / n_c)
        else:
            gap = s + self.fixed
        if pre:
            # the interpenetrating sites join: the residual max(|gap| on c, -gap off c
            # where gap < 0) is then max |gap| on the joined set
            c = c | (gap < self.zero)
            cf = xp.astype(c, self.dt)
            g = gap * cf
            residual = xp.max(xp.abs(g), keepdims=True) / self.scale
        else:
            g = gap * cf
            spread = xp.where(c, xp.abs(gap), -gap)
            residual = xp.maximum(xp.max(spread, keepdims=True), self.zero) / self.scale
        return gap, c, cf, g, n_c, residual

    def step(self, st, threshold=None, resume=None, count_stall=True):
        """One iteration (no host sync). With ``threshold`` (a (1, 1) float64: the refresh
        threshold of :class:`.loop_control.ReliableUpdates`) the top's host decisions are
        tested and a step that needs one leaves ``st`` unchanged (see the module
        docstring); ``resume``: the residual below which preconditioning returns."""
        xp, pb, pre, load = self.xp, self.pb, self.kind.pre, self.load
        zero, in_dt, total = self.zero, self.in_dt, self.total
        gap, c, cf, g, n_c, residual = self.top(st, pre)
        delta = st.delta
        if pre:  # the joined sites' number; they keep the directions when few
            n_step = total(cf)
            delta = delta & (n_step - n_c <= self.joining * n_step)
        else:
            n_step = n_c
            out = (gap < zero) & ~c  # interpenetrating sites that carry no pressure
        if not pre:
            z = g
        else:
            z = self.stiff(g) * cf
            if load:
                z = (z - in_dt(total(z) / n_step)) * cf
            elif pb.rigid_mean:
                z = (z + in_dt(self.site_stiffness * total(g) / self.n)) * cf
        g_z = total(g * z)
        # beta = 0 without directions: z + 0 t = z exactly (t is finite)
        t = z + in_dt(xp.where(delta, g_z / st.g_old, self.zero64)) * st.t
        if load:  # keep the load fixed along the search direction
            t = (t - in_dt(total(t) / n_step)) * cf
        r = self.green(t)
        denom = total(r * t)
        tau = xp.where(denom > self.zero64, total(g * t) / denom, self.nan64)
        tau_dt = in_dt(tau)
        p_new = st.p - tau_dt * t
        clipped = c & (p_new <= zero)
        s = st.s - tau_dt * r
        # the projection (and, plain, I_ol: unloaded interpenetrating sites get pressure
        # back); where no site changes it leaves p_new, the correction and its
        # convolution are exactly zero and the load's factor exactly one
        if pre:
            p = xp.where(clipped, zero, p_new)
            changed = clipped
            delta = self.true  # (joining sites only cut this step's directions)
        else:
            ol = out | (clipped & (g < zero))
            p = xp.where(ol, -tau_dt * gap, xp.where(clipped, zero, p_new))
            changed = clipped | out
            delta = ~xp.any(ol, keepdims=True)
        c = p > zero
        cf = xp.astype(c, self.dt)
        t = t * cf
        s = s + self.green(p - p_new)
        if load:  # back to the load: s = lam (u + G c) - h
            p_sum = total(p)
            rescale = xp.any(changed, keepdims=True) & (p_sum > self.zero64)
            lam = xp.where(rescale, self.target / p_sum, self.one64)
            p = p * in_dt(lam)
            s = in_dt(lam) * s + in_dt(lam - self.one64) * self.hf
        it = st.it + self.one64
        best, since = st.best, st.since
        if threshold is None:
            return State(p, s, t, c, cf, g_z, delta, it, tau, residual, best, since)
        ok = (residual > threshold) & (residual < self.inf64)
        if not load:
            ok = ok & (n_c > self.zero64)
        if resume is not None:
            ok = ok & (residual >= resume)
        if self.patience is not None and count_stall:
            improved = residual < self.improves * best
            best = xp.where(improved, residual, best)
            since = xp.where(improved, self.zero64, since + self.one64)
            ok = ok & (since < self.patience)
        tau = xp.where(ok, tau, st.tau)
        go = ok & xp.isfinite(tau)  # a non-finite step length freezes the state too
        new = State(p, s, t, c, cf, g_z, delta, it, tau, residual, best, since)
        return State(*(
            v if name == "tau" or v is old else xp.where(go, v, old)
            for name, v, old in zip(State._fields, new, st, strict=True)
        ))  # fmt: skip


def iterate_dense(p, pb, substrate):
    """Iterate from pressure ``p`` on the problem ``pb``; see :func:`._pk_sparse.iterate_sparse`.

    Returns ``(p, deflection, iterations, residual, status, message)`` (deflection
    None unless the last state is an exact evaluation).
    """
    loop = _Dense(pb, substrate)
    xp, kind, reliable = loop.xp, loop.kind, loop.reliable
    st = loop.init(p)
    exact, it, residual = True, 0, math.inf
    status, message = SolveStatus.ITERATION_LIMIT, "iteration cap reached"
    schedule = Schedule(1 if pb.callback is not None else None)
    decide = True  # whether the host takes the decisions of the current top
    while True:
        if decide:
            # the sequential loop's top, on the host (one transfer)
            _, _, _, _, n_c, top_residual = loop.top(st, False)
            n_c, top_residual = _fetch(xp, [n_c, top_residual])
            if n_c == 0:
                if loop.load:  # a projection clipped everything: restart from uniform
                    p0 = xp.full_like(st.p, pb.target / pb.hf.shape[0])
                    st = loop.restart(st, p0, xp.ones_like(st.c))
                else:  # displacement control lost all contact: restart from overlap
                    overlap = st.s < -loop.fixed
                    if not bool(xp.any(overlap)):
                        residual, status, message = 0.0, SolveStatus.CONVERGED, "no contact"
                        break
                    p0 = xp.where(overlap, -(st.s + loop.fixed) * pb.winkler, loop.zero)
                    st = loop.restart(st, p0, overlap)
                # plain steps for a while (see polonsky_keer): the residual before the loss
                kind.lost_contact(residual)
                exact = True
                continue
            residual = top_residual
            if not math.isfinite(residual):  # a non-finite pressure shows in the gap
                status, message = SolveStatus.NON_FINITE, f"non-finite pressure at iteration {it}"
                break
            if (update := reliable.check(residual, exact)) == "refresh":
                st, exact = st._replace(s=loop.exact_s(st.p)), True
                continue
            if update == "restart":
                st = st._replace(delta=~loop.true)
            end = stopping(residual <= pb.tol, residual, loop.stall, it, pb.max_iter)
            if end is not None:
                status, message = end
                break
            if kind.resumes(residual):
                st = st._replace(delta=~loop.true)
            if loop.stall.active:
                st = st._replace(best=loop.const(loop.stall.best, loop.f64),
                                 since=loop.const(float(loop.stall.since), loop.f64))  # fmt: skip
        # a block of steps: the first repeats the top just decided (its decisions taken)
        limit = min(RELIABLE_EVERY - reliable.since, pb.max_iter - it)
        refresh_below = max(pb.tol, RELIABLE_DROP * reliable.reliable)
        n = schedule.next(limit, residual, refresh_below)
        threshold = loop.const(refresh_below, loop.f64)
        resume = None
        if not kind.pre and math.isfinite(kind.resume_below):
            resume = loop.const(kind.resume_below, loop.f64)
        for i in range(n):
            st = loop.step(st, threshold, resume, count_stall=not (decide and i == 0))
        values = _fetch(xp, [st.it, st.tau, st.residual, st.best, st.since])  # one host sync
        taken = int(values[0]) - it
        it, exact = it + taken, exact and taken == 0
        for _ in range(taken):
            reliable.step()
        if loop.stall.active:
            loop.stall.best, loop.stall.since = values[3], int(values[4])
        if taken and pb.callback is not None:
            residual = values[2]
            if pb.callback(it, residual):
                status, message = SolveStatus.CALLBACK, "stopped by callback"
                break
        if taken < n and not math.isfinite(values[1]):
            it += 1
            status = SolveStatus.NON_FINITE
            message = f"breakdown at iteration {it}: non-finite step (check the inputs)"
            break
        schedule.ran(taken == n, taken, values[2])
        # the host decides where a step froze, and where a refresh or the cap is due
        decide = taken < n or reliable.since >= RELIABLE_EVERY or it >= pb.max_iter
        if taken:
            residual = values[2]  # the last top's (before the step): what lost_contact takes
    p = xp.reshape(st.p, (-1,))
    return p, (xp.reshape(st.s + loop.hf, (-1,)) if exact else None), it, residual, status, message
