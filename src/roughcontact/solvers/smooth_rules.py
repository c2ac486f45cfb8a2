"""Rules of the smooth-interaction minimiser shared by its NumPy loop and its compiled one.

The NumPy loop (:mod:`.smooth`, with :mod:`.line_search` and :mod:`._block`) and the
compiled JAX loop (:mod:`._smooth_jax`) take the same steps: the constants below
are stated once here and imported by both (as :mod:`.pk_rules` is for the hard wall).
Each was chosen by measurement, given with it.
"""

from __future__ import annotations

__all__ = [
    "EPS64",
    "FLOOR_PATIENCE",
    "FLOOR_ULPS",
    "GUESS_MAX",
    "GUESS_MIN",
    "LINE_SEARCH_MAX_EVAL",
    "LINE_SEARCH_RTOL",
    "REFRESH_EVERY",
    "RESTART_EVERY",
    "STIFF_FRACTION",
]

#: The line search stops at ``|phi'(alpha)| <= LINE_SEARCH_RTOL |phi'(0)|``: the strong Wolfe
#: curvature condition, whose c2 = 0.1 Nocedal & Wright (Numerical Optimization, 2nd ed.,
#: §5.2) suggest for nonlinear CG. 1e-3 to 0.1 took the same iterations (benchmark approach,
#: 256²-1024², within 2 %) at 2.9 -> 2.1 evaluations per line search (ℓa = 0.05) and
#: 1.7 -> 1.1 (ℓa = 0.005) from 1e-3 to this; 0.2 changed the paths (+12 % at ℓa = 0.05).
LINE_SEARCH_RTOL = 0.05

#: The line search's first point, the Newton step with the curvature at alpha = 0, is
#: clipped to [GUESS_MIN, GUESS_MAX] (in units of the search direction); the search
#: evaluates the interaction at most LINE_SEARCH_MAX_EVAL times (doublings included).
GUESS_MIN = 1e-8
GUESS_MAX = 4.0
LINE_SEARCH_MAX_EVAL = 60

#: A site is "stiff" for the block preconditioner when V''(g) exceeds this fraction of the
#: substrate's self-stiffness K_ii (0.02-0.3 measured equally good; see :mod:`.smooth`).
STIFF_FRACTION = 0.1

#: Defaults of ``restart_every`` (steepest-descent restart period of the conjugate
#: directions) and ``refresh_every`` (period of the block preconditioner's stiff sites).
RESTART_EVERY = 200
REFRESH_EVERY = 10

#: float64 solves stop as stalled (see :class:`.smooth.FloorGuard`) when their best residual
#: has not halved in FLOOR_PATIENCE iterations and lies within FLOOR_ULPS floors ``eps max|p|/E*``.
FLOOR_PATIENCE = 100
FLOOR_ULPS = 256
EPS64 = 2.220446049250313e-16  # float64 machine epsilon, 2**-52
