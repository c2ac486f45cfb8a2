"""Polonsky-Keer iterations on full-grid masks, for any array-API backend (CuPy on a GPU).

The same steps as the index-array loop in :mod:`._pk_sparse` (see :mod:`.polonsky_keer`
for the method and the residual), written with ``where``-masks because the array API has
no integer-array assignment. Every pass is over the whole grid, which a GPU does at memory
bandwidth. Tested to take exactly the steps of the NumPy loop.

Host traffic: the scalars of an iteration (the contact set's size, the load's offset,
norms, the step length) stay 0-d arrays on the device; the host reads them
(:func:`.reductions.fetch`) where the loop branches on them: after the step its length
(finite or not) and how many sites the projection changes (none; a few: point
responses; more: a convolution), and at the top the contact set's size, the residual's
two extremes and the load after a projection (convergence, exact refreshes, restarts).
When no site changes (most iterations) the next top's quantities are computed before
the step's transfer and come with it: one transfer per such iteration, two after a
projection. Each transfer waits for the device (a host sync); before, an iteration made
9-14 of them (``benchmarks/host_syncs.py``).
"""

from __future__ import annotations

import math

from .._backend import array_device, array_namespace, dtype_name, to_numpy
from .fourier import point_response
from .loop_control import ReliableUpdates, StallGuard, stopping
from .pk_rules import JOINING_KEEPS_DIRECTIONS, POINT_CORRECTIONS, StepKind
from .reductions import fetch
from .result import SolveStatus


class _RollKernel:
    """Response of the substrate to unit point forces, as rolled copies of one response."""

    def __init__(self, substrate, hf):
        self.g0 = point_response(substrate, hf)  # on the work grid
        self.shape = substrate.shape
        self.crop = substrate.crop

    def add(self, s, changed, coeffs):
        """``s + sum_j coeffs[j] G(x - x_j)`` over the sites where ``changed`` (G rolled
        on the work grid, periodic or Hockney's padded one, and cropped to the patch)."""
        xp = array_namespace(s)
        sites = xp.nonzero(changed)[0]
        # a few sites and values to the host in one transfer (indices exact in float64)
        f64 = xp.float64
        both = to_numpy(xp.stack([xp.astype(sites, f64), xp.astype(xp.take(coeffs, sites), f64)]))
        s2 = xp.reshape(s, self.shape)
        for site, value in zip(both[0].astype(int).tolist(), both[1].tolist(), strict=True):
            shift = divmod(site, self.shape[1])
            s2 = s2 + value * self.crop(xp.roll(self.g0, shift, axis=(0, 1)))
        return xp.reshape(s2, (-1,))


def iterate_dense(p, pb, substrate):
    """Iterate from pressure ``p`` on the problem ``pb``; see :func:`._pk_sparse.iterate_sparse`.

    Returns ``(p, deflection, iterations, residual, status, message)`` (deflection
    None unless the last state is an exact evaluation).
    """
    xp = array_namespace(p)
    hf, conv, target, offset = pb.hf, pb.conv, pb.target, pb.offset
    dt, f64, dev = hf.dtype, xp.float64, array_device(hf)
    load = target is not None

    def const(value, dtype=dt):
        return xp.asarray(value, dtype=dtype, device=dev)

    def in_dt(x):  # a float64 0-d scalar in the fields' precision (as a Python float is)
        return x if x.dtype == dt else xp.astype(x, dt)

    def total(x):  # sum accumulated in float64, a 0-d array
        return xp.sum(x, dtype=f64)

    def count(mask):
        return xp.sum(xp.astype(mask, f64))

    def fast(op, x):  # op in fast precision, the result back in the heights' precision
        return xp.astype(op(x), dt)

    zero, zero64, nan64 = const(0.0), const(0.0, f64), const(math.nan, f64)
    one64 = const(1.0, f64)
    s = conv(p) - hf  # s = u - h, so that the gap is s + d
    c = p > 0
    t = kernel = None
    # delta: whether t holds conjugate directions to build on: a Python bool, or a 0-d
    # device bool where it depends on the step (sites joining, I_ol on a plain step)
    delta, g_old, exact = False, one64, True
    p_sum = None  # the load after the last projection (load control; 0: all clipped)
    kind = StepKind(pb.precondition is not None)
    reliable = ReliableUpdates(pb.tol)
    status, message = SolveStatus.ITERATION_LIMIT, "iteration cap reached"
    residual, it = math.inf, 0
    stall = StallGuard(dtype_name(hf))
    fixed = None if load else in_dt(const(offset, f64))

    def top(s, c, n_c):
        """The gap, its part on the contact set, the interpenetrating sites off it, and
        the scalars the host reads: the set's size and the two extremes of the residual."""
        gap = s + (in_dt(-(total(xp.where(c, s, zero)) / n_c)) if load else fixed)
        g = xp.where(c, gap, zero)
        out = (gap < zero) & ~c  # interpenetrating sites that carry no pressure
        return gap, g, out, [n_c, xp.max(xp.abs(g)), xp.min(xp.where(out, gap, zero))]

    ahead = None  # the top's quantities, computed and fetched with the last step
    while True:
        if ahead is None:
            n_c = count(c)
            gap, g, out, scalars = top(s, c, n_c)
            if p_sum is not None:
                scalars.append(p_sum)
            n_c_host, g_max, out_min, *rest = fetch(xp, scalars)  # host sync 1
        else:
            (gap, g, out, (n_c_host, g_max, out_min)), ahead, rest = ahead, None, []
        if rest and not rest[0] > 0:  # the projection clipped everything: restart from
            # uniform pressure, with plain steps for a while (see _pk_sparse)
            p, delta, p_sum = xp.full_like(p, target / p.shape[0]), False, None
            kind.lost_contact(residual)
            c = xp.ones_like(c)
            s, exact = conv(p) - hf, True
            continue
        p_sum = None
        if n_c_host == 0:  # displacement control lost all contact: restart from overlap
            overlap = s < -offset
            if not bool(xp.any(overlap)):
                residual, status, message = 0.0, SolveStatus.CONVERGED, "no contact"
                break
            p = xp.where(overlap, -(s + offset) * pb.winkler, zero)
            s, c, exact, delta = conv(p) - hf, overlap, True, False
            kind.lost_contact(residual)  # plain steps for a while (see _pk_sparse)
            continue
        any_out = out_min < 0  # gap < 0 on every such site
        viol = -out_min if any_out else 0.0
        residual = max(g_max, viol) / pb.scale
        if not math.isfinite(residual):  # a non-finite pressure shows in the gap
            status, message = SolveStatus.NON_FINITE, f"non-finite pressure at iteration {it}"
            break
        if (update := reliable.check(residual, exact)) == "refresh":
            s, exact = conv(p) - hf, True
            continue
        if update == "restart":
            delta = False
        if (end := stopping(residual <= pb.tol, residual, stall, it, pb.max_iter)) is not None:
            status, message = end
            break
        it += 1
        reliable.step()
        if kind.resumes(residual):
            delta = False
        pre = kind.pre

        if pre and any_out:  # the interpenetrating sites join the step (see _pk_sparse)
            n_out = count(out)
            c, out, any_out = c | out, c & ~c, False
            n_c, g = count(c), xp.where(c, gap, zero)
            if delta is not False:  # t is 0 on the new sites
                delta = (n_out <= JOINING_KEEPS_DIRECTIONS * n_c) & delta
        if not pre:
            z = g
        else:
            z = xp.where(c, fast(pb.precondition, g), zero)
            if load:
                z = xp.where(c, z - in_dt(total(z) / n_c), zero)
            elif pb.rigid_mean:
                z = xp.where(c, z + in_dt(pb.site_stiffness * total(g) / g.shape[0]), zero)
        g_z = total(g * z)
        if delta is False:
            t = z
        else:
            beta = g_z / g_old
            t = z + in_dt(beta if delta is True else xp.where(delta, beta, zero64)) * t
        del z  # (peak device memory: fields are dropped as soon as they are spent)
        if load:  # keep the load fixed along the search direction
            t = xp.where(c, t - in_dt(total(t) / n_c), zero)
        g_old = g_z
        r = fast(pb.fast_conv, t)
        denom = total(r * t)
        tau = xp.where(denom > zero64, total(g * t) / denom, nan64)
        tau_dt = in_dt(tau)
        p_new = p - tau_dt * t
        clipped = c & (p_new <= zero)
        changed = clipped | out  # where a projection makes p differ from p_new
        s_new = s - tau_dt * r  # exact by linearity: G(p - tau t) - h
        del r
        # the next top's quantities if no site changes (the common case), fetched with
        # the step: one host sync for such an iteration
        *following, scalars = top(s_new, c, n_c)
        tau_host, n_changed, *scalars = fetch(xp, [tau, count(changed), *scalars])  # sync 2
        if not math.isfinite(tau_host):
            status = SolveStatus.NON_FINITE
            message = f"breakdown at iteration {it}: non-finite step (check the inputs)"
            break

        if n_changed == 0:
            p, s = p_new, s_new
            exact, delta = False, True
            ahead = (*following, scalars)
        else:
            # projection, then I_ol: unloaded interpenetrating sites get pressure back
            ol = out | (clipped & (g < zero)) if not pre else out
            p = xp.where(ol, -tau_dt * gap, xp.where(clipped, zero, p_new))
            delta = not any_out if pre else ~xp.any(ol)
            c = p > 0
            t = xp.where(c, t, zero)
            correction = p - p_new
            # s = G(p_new + correction) - h: point responses for a few sites, else a
            # convolution of the correction
            s = s_new
            if n_changed <= POINT_CORRECTIONS:
                kernel = kernel or _RollKernel(substrate, hf)
                s = kernel.add(s, changed, correction)
            else:
                s = s + fast(pb.fast_conv, correction)
            exact = False
            if load:  # back to the load: s = lam (u + G c) - h; checked at the top
                p_sum = total(p)
                lam = xp.where(p_sum > zero64, target / p_sum, one64)  # 1: nothing to do
                p = p * in_dt(lam)
                s = in_dt(lam) * s + in_dt(lam - 1.0) * hf
        # c is still p > 0: scaling by lam > 0 keeps the signs, and without a projection
        # p - tau t stays positive on c and zero off it
        if pb.callback is not None and pb.callback(it, residual):
            status, message = SolveStatus.CALLBACK, "stopped by callback"
            break
    return p, (s + hf if exact else None), it, residual, status, message
