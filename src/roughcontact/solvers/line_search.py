"""The line search of the energy minimisers (smooth and hard-core adhesive laws)."""

from __future__ import annotations

import math

import numpy as np

from ._inplace import Workspace
from .bounded_rules import BOUNDED_LINE_SEARCH_RTOL
from .reductions import dot
from .roots import bracketed_root
from .smooth_rules import GUESS_MAX, GUESS_MIN, LINE_SEARCH_MAX_EVAL

__all__ = ["line_minimum"]


def line_minimum(
    interaction,
    gap,
    s,
    kw,
    ks,
    slope0,
    rtol=BOUNDED_LINE_SEARCH_RTOL,
    max_eval=LINE_SEARCH_MAX_EVAL,
    with_pressure=False,
    work=None,
    elastic_slope=None,
    speculate=None,
    speculated=None,
    band=None,
    trial=None,
):
    """Step ``alpha`` minimising E along ``w + alpha s`` (a root of the directional slope).

    phi'(alpha) = s.(kw + alpha ks) - s.p_int(gap + alpha s); the elastic part is linear
    in alpha. Bracket a sign change, then regula falsi with Anderson-Björck updates and
    bisection safeguards (:func:`.roots.bracketed_root`) until
    ``|phi'| <= rtol |phi'(0)|``. Returns ``alpha`` (NaN if no bracket was found), and with
    ``with_pressure`` ``(alpha, sites, pressure)``: the interaction pressure at
    ``gap + alpha s`` (the last evaluation, so the caller's gradient needs no evaluation
    of its own) on ``sites`` (see :mod:`._inplace`; None: every site), zero elsewhere.
    The interaction acts on the sites of ``work``'s patch only (a free boundary's work
    grid: none on the padding). ``elastic_slope``, when the caller has it, is ``s.kw``
    (then ``kw`` is not read). ``ks`` (``K s``) may be a function of no arguments giving
    it, called once the band and the curvature at alpha = 0 are done (the caller's ``K z``
    may still be running). NumPy arrays (the compiled loops' line search is
    :func:`roughcontact.solvers._smooth_jax.line_minimum`). ``speculate`` and
    ``speculated`` are accepted and ignored (they served the retired device loops).
    ``band``, when the caller has them (:class:`._inplace.StickyBand`): ``(sites,
    s[sites], gap[sites], V''(gap[sites]) or None)``, sites that cover every one that
    can feel the interaction for ``alpha <= 4``. ``trial``, a dict: receives the last
    trial's "gap" (on the sites) and, from a law with ``pressure_and_curvature``, its
    "curvature".
    """
    c0 = dot(s, kw) if elastic_slope is None else elastic_slope
    work = work or Workspace(gap)
    both = getattr(interaction, "pressure_and_curvature", None) if trial is not None else None
    curv_a = None
    if band is not None:
        sites, sa, ga, curv_a = band
        band = True
    else:
        # sites that can feel the interaction for alpha <= 4; the others only matter beyond
        band = math.isfinite(interaction.cutoff)
        sites = work.band(gap, s, GUESS_MAX, interaction.cutoff) if band else work.patch
        sa, ga = (s, gap) if sites is None else (s[sites], gap[sites])
    last = {}

    def slope(alpha):
        g = np.multiply(sa, alpha)  # ga + alpha * sa, in one array
        g += ga
        if both is None:
            p = interaction.pressure(g)
        else:
            p, trial["curvature"] = both(g)
        if trial is not None:
            trial["gap"] = g
        last.update(pressure=p, sites=sites)
        return c0 + alpha * c1 - dot(sa, p)

    def result(alpha):
        if not with_pressure:
            return alpha
        if not math.isfinite(alpha):
            return alpha, None, None
        # the band's pressure is that of every site for alpha <= 4 (zero off the band)
        return alpha, last["sites"], last["pressure"]

    # Newton guess with the curvature at alpha = 0 (ks is asked for last: the caller may
    # still be computing it)
    curv = dot(sa * sa, interaction.curvature(ga) if curv_a is None else curv_a)
    c1 = dot(s, ks() if callable(ks) else ks)
    curv = curv + c1
    hi = -slope0 / curv if curv > 0 else 1.0
    hi = min(max(hi, GUESS_MIN), GUESS_MAX)
    f_hi = slope(hi)
    lo, f_lo = 0.0, slope0
    n_eval = 1
    if abs(f_hi) <= rtol * abs(slope0):
        return result(hi)
    while f_hi < 0 and n_eval < max_eval:
        if hi >= GUESS_MAX and band:  # beyond the pre-selected band: every site of the patch
            band, sites = False, work.patch
            sa, ga = (s, gap) if sites is None else (s[sites], gap[sites])
        lo, f_lo = hi, f_hi
        hi *= 2.0
        f_hi = slope(hi)
        n_eval += 1
    if f_hi < 0:
        return result(math.nan)
    alpha, _ = bracketed_root(
        slope, lo, f_lo, hi, f_hi, lambda f: abs(f) <= rtol * abs(slope0), max_eval - n_eval
    )
    return result(alpha)
