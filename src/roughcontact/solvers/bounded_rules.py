"""Rules of the bounded (hard-core) minimiser shared by its NumPy loop and its compiled one.

The NumPy loop (:mod:`.bounded`, with :mod:`._projection`) and the compiled
JAX loop (:mod:`._bounded_jax`) take the same steps: these constants are stated once here
and imported by both (as :mod:`.pk_rules` is for the hard wall and :mod:`.smooth_rules`
for the smooth minimiser, whose line search both share).
"""

from __future__ import annotations

__all__ = [
    "BOUNDED_LINE_SEARCH_RTOL",
    "CONTACT_DOUBLINGS",
    "FULL_CONTACT_NOTE",
    "GRADIENT_HALVINGS",
    "ON_WALL",
    "PROJECTED_HALVINGS",
    "PROJECTION_MAX_STEPS",
    "PROJECTION_RTOL",
]

#: The bounded solver's line search stops at ``|phi'(alpha)| <= this |phi'(0)|`` (the default
#: of :func:`.line_search.line_minimum`).
BOUNDED_LINE_SEARCH_RTOL = 1e-3

#: A site is on the wall when its gap is at most ON_WALL times the heights' rms (their
#: pixel size for a flat surface): the rounding of ``base + w`` at a clipped site.
ON_WALL = 1e-12

#: A step that crosses the wall is projected and halved at most PROJECTED_HALVINGS times
#: until the energy does not rise; then a projected steepest-descent step is halved at
#: most GRADIENT_HALVINGS times until it lowers the energy (else: no descent).
PROJECTED_HALVINGS = 6
GRADIENT_HALVINGS = 40

#: When every halving rises, the projected path is searched upward from the first wall
#: contact along the direction, ``alpha_max`` (no site crosses the wall there, and the
#: energy falls along the line up to its minimum): ``alpha_max 2^j`` for j = 0, 1, ...
#: below the last halving, at most CONTACT_DOUBLINGS of them, stopping at the first rise;
#: the lowest is taken if it does not raise the energy (then the projected gradient).
#: Why: under cold load control the direction carries the body's lift, along which a
#: barely touching surface meets no stiffness, and the line minimum lay 50-100 times
#: beyond any step the wall admits (128², Exponential w 0.002, range 0.2, load 0: alpha 48
#: against 0.5 once in contact); all six halvings rose, and the projected gradient's short
#: steps crawled through the jump into contact (3-fold in 40 iterations: the crawl guard,
#: then a restart from the hard wall). Measured over 72 cold load solves (128², 4 surfaces
#: x 6 laws x 3 loads): fine-grid iterations 3592 -> 2716, restarts 9 -> 2; at 256² 7278 ->
#: 4685 and 24 -> 8 (benchmarks/README.md).
CONTACT_DOUBLINGS = 30

#: The projection's Newton iteration for the multiplier of the mean: at most
#: PROJECTION_MAX_STEPS steps, done when ``|sum| <= PROJECTION_RTOL (sum|lower| + sum|v|)``.
PROJECTION_MAX_STEPS = 200
PROJECTION_RTOL = 1e-13

#: What a converged offset-controlled state adds when every site is on the wall: with a
#: rigid mean that is the offset mean(heights) (within ON_WALL), whose one feasible state is
#: full contact. Its load is not fixed by the offset: the loops take the multiplier of the
#: mean as the smallest wall reaction (mu = min r), so that every site presses on the wall
#: and the least compressed one with zero traction (before, mu = mean r left half the sites
#: "free" with a force imbalance no feasible step could reduce: the iteration cap).
FULL_CONTACT_NOTE = (
    "; full contact: every site on the wall at offset mean(heights), where the load is "
    "any at or above the one reported (its smallest: the least compressed site at zero "
    "traction)"
)
