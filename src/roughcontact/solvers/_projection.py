"""The bounded solver's projection onto the feasible set and its direction rules.

See :mod:`.bounded` (the method); split from it to keep each module short.
"""

from __future__ import annotations

import math

from .._backend import array_namespace
from .bounded_rules import (
    CONTACT_DOUBLINGS,
    GRADIENT_HALVINGS,
    PROJECTION_MAX_STEPS,
    PROJECTION_RTOL,
)
from .line_search import line_minimum
from .reductions import dot as _dot
from .reductions import total

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


def _from_first_contact(w, s, alpha_max, alpha_top, e_cur, lower, rigid, stiff, energy):
    """The lowest-energy projected step ``w + a s`` among ``a = alpha_max 2^j`` below
    ``alpha_top`` (:data:`.bounded_rules.CONTACT_DOUBLINGS`), searched upward until the
    energy rises, as ``(w, K w, E)`` if it does not raise the energy ``e_cur``, else None.

    ``alpha_max`` is where the first site along ``s`` reaches the wall: below it the step
    needs no projection, and the energy falls along the line up to its minimum.
    """
    best, alpha = None, alpha_max
    for _ in range(CONTACT_DOUBLINGS):
        if not 0.0 < alpha < alpha_top:
            break
        w_try = project_feasible(w + alpha * s, lower, rigid)
        kw_try = stiff(w_try)
        e_try = energy(w_try, kw_try)
        if best is not None and e_try > best[2]:
            break
        if e_try <= e_cur and (best is None or e_try <= best[2]):
            best = (w_try, kw_try, e_try)
        alpha *= 2.0
    return best
