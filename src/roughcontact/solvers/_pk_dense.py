"""Polonsky-Keer iterations on full-grid masks, for any array-API backend (CuPy on a GPU).

The same steps as the index-array loop in :mod:`._pk_sparse` (see :mod:`.polonsky_keer`
for the method and the residual), written with ``where``-masks because the array API has
no integer-array assignment. Every pass is over the whole grid, which a GPU does at memory
bandwidth; per iteration only scalars (step length, norms, flags, and the few sites of a
point correction) go to the host. Tested to take exactly the steps of the NumPy loop.
"""

from __future__ import annotations

import math

from .._backend import array_device, array_namespace, dtype_name, to_numpy
from .fourier import point_response
from .loop_control import ReliableUpdates, StallGuard, stopping
from .pk_rules import JOINING_KEEPS_DIRECTIONS, POINT_CORRECTIONS, StepKind
from .reductions import dot, total
from .result import SolveStatus


def _count(xp, mask) -> int:
    return int(xp.sum(xp.astype(mask, xp.int64)))


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
        values = to_numpy(xp.take(coeffs, sites)).tolist()  # a few scalars to the host
        s2 = xp.reshape(s, self.shape)
        for site, value in zip(to_numpy(sites).tolist(), values, strict=True):
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
    zero = xp.zeros((), dtype=hf.dtype, device=array_device(hf))
    s = conv(p) - hf  # s = u - h, so that the gap is s + d
    c = p > 0
    t = kernel = None
    delta, g_old, exact = False, 1.0, True
    kind = StepKind(pb.precondition is not None)
    reliable = ReliableUpdates(pb.tol)

    def fast(op, x):  # op in fast precision, the result back in the heights' precision
        return xp.astype(op(x), hf.dtype)

    status, message = SolveStatus.ITERATION_LIMIT, "iteration cap reached"
    residual, it = math.inf, 0
    stall = StallGuard(dtype_name(hf))
    while True:
        n_c = _count(xp, c)
        if n_c == 0:  # displacement control lost all contact: restart from overlap
            overlap = s < -offset
            if not bool(xp.any(overlap)):
                residual, status, message = 0.0, SolveStatus.CONVERGED, "no contact"
                break
            p = xp.where(overlap, -(s + offset) * pb.winkler, zero)
            s, c, exact, delta = conv(p) - hf, overlap, True, False
            kind.lost_contact(residual)  # plain steps for a while (see _pk_sparse)
            continue
        d = -total(xp.where(c, s, zero)) / n_c if target is not None else offset
        gap = s + d
        g = xp.where(c, gap, zero)
        out = (gap < 0) & ~c  # interpenetrating sites that carry no pressure
        any_out = bool(xp.any(out))
        viol = -float(xp.min(xp.where(out, gap, zero))) if any_out else 0.0
        residual = max(float(xp.max(xp.abs(g))), viol) / pb.scale
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
            n_out = _count(xp, out)
            c, out, any_out = c | out, c & ~c, False
            n_c, g = _count(xp, c), xp.where(c, gap, zero)
            delta = delta and n_out <= JOINING_KEEPS_DIRECTIONS * n_c  # t is 0 on the new sites
        if not pre:
            z = g
        else:
            z = xp.where(c, fast(pb.precondition, g), zero)
            if target is not None:
                z = xp.where(c, z - total(z) / n_c, zero)
            elif pb.rigid_mean:
                z = xp.where(c, z + pb.site_stiffness * total(g) / g.shape[0], zero)
        g_z = dot(g, z)
        t = z + (g_z / g_old) * t if delta else z
        if target is not None:  # keep the load fixed along the search direction
            t = xp.where(c, t - total(t) / n_c, zero)
        g_old = g_z
        r = fast(pb.fast_conv, t)
        denom = dot(r, t)
        tau = dot(g, t) / denom if denom > 0 else math.nan
        if not math.isfinite(tau):
            status = SolveStatus.NON_FINITE
            message = f"breakdown at iteration {it}: non-finite step (check the inputs)"
            break

        p_new = p - tau * t
        clipped = c & (p_new <= 0)
        if not any_out and not bool(xp.any(clipped)):
            p, s = p_new, s - tau * r  # exact by linearity: G(p - tau t) - h
            exact, delta = False, True
        else:
            # projection, then I_ol: unloaded interpenetrating sites get pressure back
            ol = out | (clipped & (g < 0)) if not pre else out
            p = xp.where(ol, -tau * gap, xp.where(clipped, zero, p_new))
            delta = not bool(xp.any(ol))
            c = p > 0
            t = xp.where(c, t, zero)
            changed = clipped | out  # where p differs from p_new = p - tau t
            correction = p - p_new
            # s = G(p_new + correction) - h: point responses for a few sites, else a
            # convolution of the correction
            s = s - tau * r
            if _count(xp, changed) <= POINT_CORRECTIONS:
                kernel = kernel or _RollKernel(substrate, hf)
                s = kernel.add(s, changed, correction)
            else:
                s = s + fast(pb.fast_conv, correction)
            exact = False
            if target is not None:
                p_sum = total(p)
                if not p_sum > 0:  # everything was clipped: restart from uniform pressure
                    p, delta = xp.full_like(p, target / p.shape[0]), False
                    kind.lost_contact(residual)
                    c = xp.ones_like(c)
                    s, exact = conv(p) - hf, True
                elif p_sum != target:  # back to the load: s = lam (u + G c) - h
                    lam = target / p_sum
                    p = p * lam
                    s = lam * s + (lam - 1.0) * hf
        # c is still p > 0: scaling by lam > 0 keeps the signs, and without a projection
        # p - tau t stays positive on c and zero off it
        if pb.callback is not None and pb.callback(it, residual):
            status, message = SolveStatus.CALLBACK, "stopped by callback"
            break
    return p, (s + hf if exact else None), it, residual, status, message
