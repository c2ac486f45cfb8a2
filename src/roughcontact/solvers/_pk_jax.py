"""The Polonsky-Keer iteration as one compiled JAX program (``jax.jit`` + ``lax.while_loop``).

The same constrained conjugate gradients as :mod:`._pk_sparse`, the NumPy loop (see
:mod:`.polonsky_keer` for the method, the residual and the preconditioner): the
accelerator backend, for heights given as JAX arrays, arrays of other libraries (through
DLPack) and ``device="cuda"`` (:mod:`roughcontact._accelerator`). The whole loop is one
XLA program: the state is a :class:`State` record of device arrays, every branch is a
``where`` selection or a ``lax.cond``, and convergence, the iteration cap, the float32
stall guard, a lost contact set and a breakdown are tested on the device at every
iteration. Nothing reaches the host until the loop ends (tested under
``jax.transfer_guard("disallow")``); the host then reads the iterations, residual, status
and offset in one transfer. On a GPU the loop therefore costs its FFTs and fused
elementwise passes, not a kernel launch per array operation.

Differences from the NumPy loop, all deliberate:

* One precision: the convolutions run in the heights' dtype (no float32 increments).
  ``G p - h`` is updated by the step's increment ``-tau G t`` (exact by linearity; ``G t``
  is the step's own convolution), plus the convolution of the projection's correction only
  on the iterations where the projection changed a site (``lax.cond``: no host decision).
  That is 1 convolution per plain and 2 per preconditioned iteration on most iterations,
  against 2 and 3 for an exact evaluation after every step. The rounding of the increments
  is removed by an exact evaluation every :data:`.loop_control.RELIABLE_EVERY` iterations
  and before convergence is declared: a state that meets the tolerance is evaluated
  exactly and tested again, so convergence is only ever declared on an exact state.
* Under load control the pressure is scaled back to the load after every step (the other
  loops only after a projection changed the contact set; the factor is 1 up to rounding
  otherwise).
* Periodic substrates only (a free boundary's zero-padded grid is not implemented here:
  :func:`check_jax_inputs` says so), and no ``callback`` (it would need the host inside
  the loop).

Precision: JAX computes in float32 unless ``jax_enable_x64`` is on; roughcontact never
changes that global setting. A float64 solve (``dtype="float64"``, or float64 heights)
runs inside ``jax.enable_x64(True)`` instead (:func:`roughcontact._backend.jax_precision`,
applied by the public entry points), so it needs no switch; there the sums are
accumulated in float64 (also for float32 fields, as the other loops do).
"""

from __future__ import annotations

from functools import partial
from typing import NamedTuple

import jax
import jax.numpy as jnp
from jax import lax

from .._validate import ParameterError
from .loop_control import RELIABLE_EVERY, STALL_IMPROVEMENT, STALL_PATIENCE
from .pk_rules import JOINING_KEEPS_DIRECTIONS, RESUME_PRECONDITIONING
from .result import SolveStatus

__all__ = ["State", "check_jax_inputs", "iterate_jax", "prepare", "run"]

_STIFFNESS, _COMPLIANCE = 0, 1  # the fields of FourierMultipliers
#: The status codes the loop leaves in ``State.status``.
RUNNING, CONVERGED, LIMIT, STALLED, NON_FINITE, BREAKDOWN, NO_CONTACT = range(7)


def x64_enabled() -> bool:
    """Whether JAX may make float64 arrays (``jax_enable_x64``)."""
    return bool(jax.config.jax_enable_x64)


def check_jax_inputs(heights, substrate, dtype, device, callback):
    """The precision a solve on JAX ``heights`` computes in (``"float32"``/``"float64"``),
    or a one-line :class:`ParameterError` for what the compiled loop does not support."""
    if device is not None:
        raise ParameterError(
            f"device must be None for JAX heights (place them with jax.device_put), got {device!r}"
        )
    if callback is not None:
        raise ParameterError("callback is not supported for JAX heights (the compiled loop "
                             "does not return to the host); pass NumPy heights")  # fmt: skip
    if not substrate.periodic:
        raise ParameterError("JAX heights need a periodic substrate (the compiled loop has no "
                             "free boundary); pass NumPy heights for a free boundary")  # fmt: skip
    if dtype is None:
        dtype = str(heights.dtype) if str(heights.dtype) in ("float32", "float64") else None
        dtype = dtype or ("float64" if x64_enabled() else "float32")
    if str(dtype) == "float64" and not x64_enabled():  # (public entries enable it: see
        raise ParameterError(  # jax_precision; reached only by a direct internal call)
            "dtype float64 with JAX heights needs jax.config.update('jax_enable_x64', True) "
            "(or pass dtype='float32')"
        )
    return str(dtype)


class Constants(NamedTuple):
    """The problem, as device arrays (the compiled program's inputs)."""

    h: object  # heights (2D)
    green: object  # compliance multipliers (rfft2 layout)
    stiff: object  # stiffness multipliers (rfft2 layout; unused by plain steps)
    target: object  # total pressure (load control)
    offset: object  # the offset (displacement control)
    scale: object  # residual normalisation (length)
    winkler: object  # local stiffness for a restart from overlap (pressure/length)
    site_stiffness: object  # K_ii (pressure/length)
    tol: object
    max_iter: object  # (int32)


class State(NamedTuple):
    """The loop's state: device arrays only (scalars 0-d, in the accumulation dtype)."""

    p: object  # pressure (2D)
    s: object  # G p - h (2D), so that the gap is s + d
    exact: object  # whether s was evaluated from p (bool), not updated by increments
    t: object  # the search direction (2D; zero off the contact set)
    g_old: object  # g.z of the last step
    delta: object  # whether t holds conjugate directions to build on (bool)
    pre: object  # whether the steps are preconditioned now (bool)
    resume_below: object  # after a lost contact set: the residual where pre returns
    it: object  # iterations (int32)
    residual: object  # the residual at the top of the last iteration
    best: object  # the stall guard's best residual and ...
    since: object  # ... the iterations since it improved (int32)
    status: object  # RUNNING or why the loop stopped (int32)


def prepare(p, substrate, *, h, target, offset, scale, winkler, tol, max_iter, precondition):
    """The initial state and the :class:`Constants` on the heights' device.

    ``p``: the initial pressure (2D JAX array, the heights' dtype); the scalars are
    Python floats (``target`` or ``offset`` None by the control not used);
    ``precondition``: whether the steps start preconditioned.
    """
    acc = jnp.float64 if x64_enabled() else jnp.float32
    multipliers = substrate.multipliers(h)  # cached per device and dtype
    green, stiff = multipliers[_COMPLIANCE], multipliers[_STIFFNESS]

    def scalar(v, dtype=acc):
        return jax.device_put(jnp.asarray(v, dtype=dtype), h.device)

    k = Constants(
        h=h, green=green, stiff=stiff, target=scalar(target or 0.0),
        offset=scalar(0.0 if offset is None else offset, h.dtype), scale=scalar(scale),
        winkler=scalar(winkler, h.dtype), site_stiffness=scalar(substrate.self_stiffness),
        tol=scalar(tol), max_iter=scalar(max_iter, jnp.int32),
    )  # fmt: skip

    def flag(v):
        return jax.device_put(jnp.asarray(v), h.device)

    # one buffer per field: ``run`` takes the state's buffers over (donated), and a buffer
    # may be donated only once
    st = State(p=p, s=_exact_s(p, k), exact=flag(True), t=jnp.zeros_like(p),
               g_old=scalar(1.0), delta=flag(False), pre=flag(bool(precondition)),
               resume_below=scalar(-jnp.inf), it=scalar(0, jnp.int32),
               residual=scalar(jnp.inf), best=scalar(jnp.inf), since=scalar(0, jnp.int32),
               status=scalar(0, jnp.int32))  # fmt: skip
    return st, k


def _conv(x, kernel):
    return jnp.fft.irfft2(jnp.fft.rfft2(x) * kernel, s=x.shape).astype(x.dtype)


@jax.jit
def _exact_s(p, k):
    return _conv(p, k.green) - k.h


@partial(
    jax.jit, static_argnames=("load", "precondition", "rigid_mean", "stall"), donate_argnames="st"
)  # the state's buffers are reused
def run(st, k, *, load, precondition, rigid_mean, stall):
    """Iterate from ``st`` until the status is not RUNNING; one compiled program.

    Returns the final :class:`State` and the offset ``d`` (the multiplier under load
    control, the given one otherwise), all on the device.
    """
    dt, acc = st.p.dtype, st.g_old.dtype
    n = st.p.size

    def tot(x):
        return jnp.sum(x, dtype=acc)

    def top(st):
        """The gap, the contact set (and as 0/1), its size and the residual."""
        c = st.p > 0
        cf = c.astype(dt)
        n_c = tot(cf)
        d = -tot(st.s * cf) / jnp.maximum(n_c, 1.0) if load else k.offset.astype(acc)
        gap = st.s + d.astype(dt)
        spread = jnp.where(c, jnp.abs(gap), -gap)
        residual = jnp.maximum(jnp.max(spread).astype(acc), 0.0) / k.scale
        return gap, c, cf, n_c, residual, d

    def lose(st, residual):
        """A restart after the whole contact set was lost: plain steps for a while."""
        resume = jnp.where(st.pre, RESUME_PRECONDITIONING * residual, st.resume_below)
        return st._replace(pre=jnp.zeros_like(st.pre), resume_below=resume,
                           delta=jnp.zeros_like(st.delta), t=jnp.zeros_like(st.t))  # fmt: skip

    def step(st, gap, c, cf, n_c, residual, pre):
        """One iteration from the top's values; ``pre`` (static) preconditioned."""
        delta = st.delta
        if pre:  # the interpenetrating sites join; they keep the directions when few
            c = c | (gap < 0)
            cf = c.astype(dt)
            g = gap * cf
            n_step = tot(cf)
            delta = delta & (n_step - n_c <= JOINING_KEEPS_DIRECTIONS * n_step)
            z = _conv(g, k.stiff) * cf
            if load:
                z = (z - (tot(z) / n_step).astype(dt)) * cf
            elif rigid_mean:  # K has no uniform mode: see polonsky_keer's docstring
                z = (z + (k.site_stiffness * tot(g) / n).astype(dt)) * cf
        else:
            g = gap * cf
            n_step = n_c
            out = (gap < 0) & ~c  # interpenetrating sites that carry no pressure
            z = g
        g_z = tot(g * z)
        beta = jnp.where(delta, g_z / st.g_old, 0.0).astype(dt)
        t = z + beta * st.t
        if load:  # keep the load fixed along the search direction
            t = (t - (tot(t) / n_step).astype(dt)) * cf
        r = _conv(t, k.green)
        denom = tot(r * t)
        tau = jnp.where(denom > 0, tot(g * t) / jnp.where(denom > 0, denom, 1.0), jnp.nan)
        tau_dt = tau.astype(dt)
        p_new = st.p - tau_dt * t
        s_new = st.s - tau_dt * r  # G p_new - h, exact by linearity
        clipped = c & (p_new <= 0)
        if pre:
            p = jnp.where(clipped, 0.0, p_new).astype(dt)
            delta = jnp.ones_like(delta)
        else:  # Polonsky & Keer's I_ol: unloaded interpenetrating sites get pressure back
            ol = out | (clipped & (g < 0))
            p = jnp.where(ol, -tau_dt * gap, jnp.where(clipped, 0.0, p_new)).astype(dt)
            delta = ~jnp.any(ol)
        correction = p - p_new  # nonzero only where the projection changed a site
        refresh = (st.it + 1) % RELIABLE_EVERY == 0  # bound the increments' rounding
        new = st._replace(t=t * (p > 0).astype(dt), g_old=g_z, delta=delta,
                          it=st.it + 1, residual=residual, exact=refresh)  # fmt: skip
        lam = None
        if load:  # back to the load; everything clipped: restart from uniform pressure
            p_sum = tot(p)
            lost = ~(p_sum > 0)
            lam = (k.target / jnp.where(lost, 1.0, p_sum)).astype(dt)
            p = jnp.where(lost, (k.target / n).astype(dt), p * lam)
            lost_st = lose(new, residual)._replace(exact=jnp.ones_like(refresh))
            new = jax.tree.map(lambda a, b: jnp.where(lost, a, b), lost_st, new)
        # one convolution, no branch: G p exactly (every RELIABLE_EVERY-th iteration, or
        # after a loss) or G of the projection's correction (zero where nothing was
        # clipped, so adding it changes nothing). A lax.cond costs a GPU a transfer of its
        # predicate to the host and a drained queue each time (6 of them per iteration
        # made ~1/3 of the 4096² iteration's time on an H200 idle)
        exact = new.exact
        conv = _conv(jnp.where(exact, p, correction), k.green)
        s_new = s_new + conv
        if lam is not None:  # G (lam p) - h = lam (G p - h) + (lam - 1) h
            s_new = lam * s_new + (lam - 1) * k.h
        new = new._replace(p=p, s=jnp.where(exact, conv - k.h, s_new))
        # a breakdown (no finite step) stops on the state it started from
        ok = jnp.isfinite(tau)
        kept = st._replace(it=st.it + 1, residual=residual, status=jnp.int32(BREAKDOWN))
        return jax.tree.map(lambda a, b: jnp.where(ok, a, b), new, kept)

    def iterate(st):
        gap, c, cf, n_c, residual, _ = top(st)
        pre = st.pre
        delta = st.delta
        if precondition:  # preconditioning returns once the residual fell enough
            resumes = ~pre & (residual < st.resume_below)
            pre, delta = pre | resumes, delta & ~resumes
        best, since = st.best, st.since
        stalled = jnp.zeros((), dtype=bool)
        if stall:
            improved = residual < STALL_IMPROVEMENT * best
            best = jnp.where(improved, residual, best)
            since = jnp.where(improved, 0, since + 1)
            stalled = since >= STALL_PATIENCE
        status = jnp.select(
            [~jnp.isfinite(residual), residual <= k.tol, stalled, st.it >= k.max_iter],
            [NON_FINITE, CONVERGED, STALLED, LIMIT], RUNNING,
        ).astype(jnp.int32)  # fmt: skip
        # a state that meets the tolerance on increments is evaluated exactly and tested
        # again (no iteration counted), so convergence is declared on an exact state only
        unverified = (status == CONVERGED) & ~st.exact
        exact_st = st._replace(exact=jnp.ones_like(st.exact))

        def verified():
            return exact_st._replace(s=_conv(st.p, k.green) - k.h)

        st = st._replace(pre=pre, delta=delta, best=best, since=since)
        stop = st._replace(residual=residual, status=status)

        def settle():  # the loop ends here (not converged): with an exact G p - h
            return lax.cond(
                stop.exact,
                lambda: stop,
                lambda: stop._replace(
                    s=_conv(stop.p, k.green) - k.h, exact=jnp.ones_like(stop.exact)
                ),
            )

        args = (gap, c, cf, n_c, residual)
        if precondition:
            go = partial(lax.cond, pre, lambda: step(st, *args, True),
                         lambda: step(st, *args, False))  # fmt: skip
        else:
            go = partial(step, st, *args, False)
        return lax.cond(status == RUNNING, go, lambda: lax.cond(unverified, verified, settle))

    def restart_from_overlap(st):
        """Displacement control lost all contact: restart from the overlap (or stop)."""
        overlap = st.s < -k.offset
        p = jnp.where(overlap, -(st.s + k.offset) * k.winkler, 0.0).astype(dt)
        moved = lose(st, st.residual)._replace(
            p=p, s=_conv(p, k.green) - k.h, exact=jnp.ones_like(st.exact)
        )
        none = st._replace(residual=jnp.zeros_like(st.residual), status=jnp.int32(NO_CONTACT))
        return lax.cond(jnp.any(overlap), lambda: moved, lambda: none)

    def body(st):
        if load:
            return iterate(st)
        no_contact = ~jnp.any(st.p > 0)
        return lax.cond(no_contact, restart_from_overlap, iterate, st)

    st = lax.while_loop(lambda st: st.status == RUNNING, body, st)
    return st, top(st)[-1]


_MESSAGES = {
    CONVERGED: (SolveStatus.CONVERGED, "converged"),
    NO_CONTACT: (SolveStatus.CONVERGED, "no contact"),
    LIMIT: (SolveStatus.ITERATION_LIMIT, "iteration cap reached"),
}


def iterate_jax(p, pb, substrate):
    """Iterate from pressure ``p`` (flat) on the problem ``pb`` (see :mod:`.polonsky_keer`).

    Returns ``(p, deflection, iterations, residual, status, message, offset)``, the fields
    flat JAX arrays on the heights' device (the deflection exact), after one transfer of
    the scalars to the host.
    """
    shape = tuple(pb.shape)
    h = jnp.reshape(pb.hf, shape)
    st, k = prepare(jnp.reshape(p, shape), substrate, h=h, target=pb.target,
                    offset=pb.offset, scale=pb.scale, winkler=pb.winkler, tol=pb.tol,
                    max_iter=pb.max_iter, precondition=pb.precondition is not None)  # fmt: skip
    st, d = run(st, k, load=pb.target is not None, precondition=pb.precondition is not None,
                rigid_mean=bool(substrate.rigid_mean), stall=h.dtype == jnp.float32)  # fmt: skip
    return finish(st, d, pb.hf)


def finish(st, d, hf):
    """The host's one read of the final state: :func:`iterate_jax`'s tuple."""
    it, residual, code, best, d = (x.item() for x in jax.device_get(
        (st.it, st.residual, st.status, st.best, d)))  # fmt: skip
    if code in _MESSAGES:
        status, message = _MESSAGES[code]
    elif code == STALLED:
        status = SolveStatus.STALLED
        message = (f"stalled at residual {best:.2g} for {STALL_PATIENCE} iterations: the "
                   "float32 rounding floor (use dtype='float64' or a larger tol)")  # fmt: skip
    elif code == NON_FINITE:
        status, message = SolveStatus.NON_FINITE, f"non-finite pressure at iteration {it}"
    else:
        status = SolveStatus.NON_FINITE
        message = f"breakdown at iteration {it}: non-finite step (check the inputs)"
    p = jnp.reshape(st.p, (-1,))
    u = jnp.reshape(st.s, (-1,)) + hf
    return p, u, it, residual, status, message, d
