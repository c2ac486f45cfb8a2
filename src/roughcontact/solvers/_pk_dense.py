"""Polonsky-Keer iterations on full-grid masks, for any array-API backend (CuPy on a GPU).

The same steps as the index-array loop in :mod:`.polonsky_keer` (see there for the
method and the residual), written with ``where``-masks because the array API has no
integer-array assignment. Every pass is over the whole grid, which a GPU does at memory
bandwidth; per iteration only scalars (step length, norms, flags) go to the host.
"""

from __future__ import annotations

import math

from .._backend import array_device, array_namespace, dtype_name
from ._ops import StallGuard, dot, total


def _count(xp, mask) -> int:
    return int(xp.sum(xp.astype(mask, xp.int64)))


def iterate_dense(p, pb):
    """Iterate from pressure ``p`` on the problem ``pb``; see ``polonsky_keer._iterate_sparse``.

    Returns ``(p, iterations, residual, converged, message)``.
    """
    xp = array_namespace(p)
    hf, conv, target, offset = pb.hf, pb.conv, pb.target, pb.offset
    zero = xp.zeros((), dtype=hf.dtype, device=array_device(hf))
    s = conv(p) - hf  # s = u - h, so that the gap is s + d
    c = p > 0
    t = None
    delta, g_old, exact = False, 1.0, True
    converged, message, residual, it = False, "iteration cap reached", math.inf, 0
    stall = StallGuard(dtype_name(hf))
    while True:
        n_c = _count(xp, c)
        if n_c == 0:  # displacement control lost all contact: restart from overlap
            overlap = s < -offset
            if not bool(xp.any(overlap)):
                residual, converged, message = 0.0, True, "no contact"
                break
            p = xp.where(overlap, -(s + offset) * pb.winkler, zero)
            s, c, exact, delta = conv(p) - hf, overlap, True, False
            continue
        d = -total(xp.where(c, s, zero)) / n_c if target is not None else offset
        gap = s + d
        g = xp.where(c, gap, zero)
        out = (gap < 0) & ~c  # interpenetrating sites that carry no pressure
        any_out = bool(xp.any(out))
        viol = -float(xp.min(xp.where(out, gap, zero))) if any_out else 0.0
        residual = max(float(xp.max(xp.abs(g))), viol) / pb.scale
        if residual <= pb.tol:
            if exact:
                converged, message = True, "converged"
                break
            s, exact = conv(p) - hf, True  # confirm without round-off drift
            continue
        if (stalled := stall(residual)) is not None:
            message = stalled
            break
        if it >= pb.max_iter:
            break
        it += 1

        g_norm = dot(g, g)
        t = g + (g_norm / g_old) * t if delta else g
        if target is not None:  # keep the load fixed along the search direction
            t = xp.where(c, t - total(t) / n_c, zero)
        g_old = g_norm
        r = conv(t)
        denom = dot(r, t)
        tau = dot(g, t) / denom if denom > 0 else math.nan
        if not math.isfinite(tau):
            message = f"breakdown at iteration {it}: non-finite step (check the inputs)"
            break

        p_new = p - tau * t
        clipped = c & (p_new <= 0)
        if not any_out and not bool(xp.any(clipped)):
            p, s = p_new, s - tau * r  # exact by linearity: G(p - tau t) - h
            exact, delta = False, True
        else:
            # projection, then I_ol: unloaded interpenetrating sites get pressure back
            ol = out | (clipped & (g < 0))
            p = xp.where(ol, -tau * gap, xp.where(clipped, zero, p_new))
            delta = not bool(xp.any(ol))
            c = p > 0
            t = xp.where(c, t, zero)
            if target is not None:
                p_sum = total(p)
                if not p_sum > 0:  # everything was clipped: restart from uniform pressure
                    p, delta = xp.full_like(p, target / p.shape[0]), False
                else:
                    p = p * (target / p_sum)
            s, exact = conv(p) - hf, True
        c = p > 0
        if pb.callback is not None and pb.callback(it, residual):
            message = "stopped by callback"
            break
        if not math.isfinite(total(p)):
            message = f"non-finite pressure at iteration {it}"
            break
    return p, it, residual, converged, message
