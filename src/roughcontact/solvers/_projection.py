"""The bounded solver's projection onto the feasible set and its direction rules.

See :mod:`.bounded` (the method); split from it to keep each module short.
"""

from __future__ import annotations

import math

from .._backend import array_device, array_namespace, is_numpy_array
from .bounded_rules import GRADIENT_HALVINGS, PROJECTION_MAX_STEPS, PROJECTION_RTOL
from .line_search import line_minimum
from .reductions import dot as _dot
from .reductions import fetch, total, vdot, vtotal

__all__ = ["project_feasible"]


def project_feasible(v, lower, zero_mean: bool):
    """Euclidean projection of ``v`` onto ``{w >= lower}`` (and ``mean(w) = 0``).

    With the mean constraint the projection is ``max(v + λ, lower)`` with the scalar λ
    chosen so the mean vanishes: a root of a convex, piecewise-linear, nondecreasing
    function, found exactly by Newton's method in a few steps.
    """
    xp = array_namespace(v)
    if not zero_mean:
        return xp.maximum(v, lower)
    if not is_numpy_array(v):
        return _project_on_device(v, lower, xp)
    lam, lower_sum, v_sum = float(xp.mean(v)), total(xp.abs(lower)), total(xp.abs(v))
    lam, scale = -lam, lower_sum + v_sum + 1e-300
    best, u_best = math.inf, None
    for _ in range(PROJECTION_MAX_STEPS):
        u = xp.maximum(v + lam, lower)
        f = total(u)
        if abs(f) >= best:  # no better at the precision of v (float32 stops here)
            return u_best
        if abs(f) <= PROJECTION_RTOL * scale:
            break
        best, u_best = abs(f), u
        count = int(xp.count_nonzero(v + lam > lower))
        if count == 0:  # everything clipped: move to the first breakpoint
            lam = float(xp.max(lower - v))
            continue
        lam -= f / count
    return u


#: Newton steps of the projection computed ahead of each transfer off NumPy (it usually
#: converges in 2-4; the steps not needed are a few elementwise passes)
NEWTON_AHEAD = 3


def _project_on_device(v, lower, xp):
    """:func:`project_feasible` off NumPy: the same Newton steps, :data:`NEWTON_AHEAD` of
    them computed on the device before each transfer (one host sync for most projections);
    the host then takes the sequential loop's decisions on their sums and counts."""
    f64 = xp.float64

    def ahead(lam):
        steps = []
        for _ in range(NEWTON_AHEAD):
            shift = lam if lam.dtype == v.dtype else xp.astype(lam, v.dtype)  # as a float
            u = xp.maximum(v + shift, lower)
            f = vtotal(u)
            count = xp.astype(xp.count_nonzero(v + shift > lower), f64)
            steps.append((u, f, count))
            # everything clipped: to the first breakpoint
            breakpoint_ = xp.astype(xp.max(lower - v), f64)
            lam = xp.where(count > 0.0, lam - f / xp.where(count > 0.0, count, 1.0), breakpoint_)
        return steps, lam

    steps, lam = ahead(-xp.astype(xp.mean(v), f64))
    head = [vtotal(xp.abs(lower)), vtotal(xp.abs(v))]
    best, u_best, done = math.inf, None, 0
    while True:
        values = fetch(xp, [*head, *(x for _, f, count in steps for x in (f, count))])
        if head:
            scale, head = values[0] + values[1] + 1e-300, []
            values = values[2:]
        for (u, _, _), f in zip(steps, values[::2], strict=True):
            done += 1
            if abs(f) >= best:  # no better at the precision of v (float32 stops here)
                return u_best
            if abs(f) <= PROJECTION_RTOL * scale or done >= PROJECTION_MAX_STEPS:
                return u
            best, u_best = abs(f), u
        steps, lam = ahead(lam)


def _direction_on_device(xp, rr, z, z_old, s, gz_old, restart, active, active_old):
    """The PR+ direction ``-z + beta s``, its slope ``rr.s`` and ``rr.z`` as device scalars
    (the host branches' values: ``beta = 0`` on a restart, a changed face or ``gz_old =
    0``; a direction that does not descend becomes ``-z``)."""
    gz = vdot(rr, z)
    if restart:
        s = -z
    else:
        zero = xp.zeros((), dtype=xp.float64, device=array_device(rr))
        pr = (gz - vdot(rr, z_old)) / xp.where(gz_old == zero, 1.0, gz_old)
        keep = ~xp.any(active != active_old) & (gz_old != zero)
        beta = xp.where(keep, xp.maximum(pr, zero), zero)
        s = -z + (beta if beta.dtype == s.dtype else xp.astype(beta, s.dtype)) * s
    slope0 = vdot(rr, s)
    ascent = slope0 >= 0.0
    return xp.where(ascent, -z, s), xp.where(ascent, -gz, slope0), gz


def _projected_gradient_step(w, kw, rr, e_cur, lower, rigid, stiff, energy, interaction, gap, work):
    """A projected steepest-descent step that lowers E, or None (Bertsekas 1976).

    The direction ``-rr`` (zero on the active face; zero-mean with a rigid mean) starts
    at the line minimum of E along it and is halved until the projected state lowers the
    energy; for a small enough step it always does unless ``w`` is stationary.
    """
    s = -rr
    ks = stiff(s)
    alpha = line_minimum(interaction, gap, s, kw, ks, -_dot(rr, rr), work=work)
    alpha = alpha if math.isfinite(alpha) and alpha > 0 else 1.0
    for _ in range(GRADIENT_HALVINGS):
        w_try = project_feasible(w + alpha * s, lower, rigid)
        kw_try = stiff(w_try)
        e_try = energy(w_try, kw_try)
        if e_try < e_cur:
            return w_try, kw_try, e_try
        alpha *= 0.5
    return None
