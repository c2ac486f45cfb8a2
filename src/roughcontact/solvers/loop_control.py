"""Loop control shared by the iterative solvers: exact refreshes, stall guard, stopping."""

from __future__ import annotations

import contextlib
import contextvars
import math

from .result import SolveStatus

__all__ = [
    "CRAWL_IMPROVEMENT",
    "CRAWL_PATIENCE",
    "RELIABLE_DROP",
    "RELIABLE_EVERY",
    "STALL_IMPROVEMENT",
    "STALL_PATIENCE",
    "ReliableUpdates",
    "CrawlGuard",
    "StallGuard",
    "crawl_guarded",
    "crawl_message",
    "guarding_crawl",
    "stall_guard",
    "stopping",
]


#: Mixed-precision iterations ("reliable updates"): an exact evaluation of what the
#: single-precision increments update is redone once the residual has fallen by this
#: factor since the last one (their drift, ~1e-7 of the distance travelled, is then far
#: below the residual) ...
RELIABLE_DROP = 1e-3
#: ... and at the latest after this many iterations, so that drift can never stall a solve.
RELIABLE_EVERY = 50

#: The float32 stall guard (:class:`StallGuard`, and the compiled loops' copy of it): a
#: stall after STALL_PATIENCE iterations without a new best residual below
#: STALL_IMPROVEMENT times the best.
STALL_PATIENCE = 200
STALL_IMPROVEMENT = 0.99

#: The crawl guard of a cold hard-core load-controlled solve (:func:`guarding_crawl`, the
#: bounded loops): it stops when the residual has not fallen below CRAWL_IMPROVEMENT times
#: its best for CRAWL_PATIENCE iterations, and load control starts again from a hard-wall
#: state (:func:`.load_control._from_hard_wall`). Measured (4 surfaces, 6 Maugis-Dugdale
#: and Exponential laws, loads -1e-4, 0, 1e-3 E*): at 128² every solve that converges
#: within 150 iterations takes a 3-fold step down within every 40 (at 256² all but two of
#: 72, which converged in 116 and 141 and are restarted now), while those that crawl
#: through a slow jump into contact (the residual stuck at 3e-5 to 5e-4 E* for hundreds of
#: iterations, the offset creeping) are caught after 41-103 iterations instead of the 150
#: of the budget: 23 % fewer fine-grid iterations over the 72 solves at 256²
#: (benchmarks/README.md).
CRAWL_PATIENCE = 40
CRAWL_IMPROVEMENT = 1.0 / 3.0

_CRAWL: contextvars.ContextVar = contextvars.ContextVar("crawl_guard", default=False)


@contextlib.contextmanager
def guarding_crawl():
    """Within the block the bounded loops (NumPy and compiled) stop a solve that crawls
    (:data:`CRAWL_PATIENCE`, :data:`CRAWL_IMPROVEMENT`) with status ``iteration_limit``
    and :func:`crawl_message`: load control's cold hard-core solves."""
    token = _CRAWL.set(True)
    try:
        yield
    finally:
        _CRAWL.reset(token)


def crawl_guarded() -> bool:
    """Whether the crawl guard is on (:func:`guarding_crawl`)."""
    return _CRAWL.get()


def crawl_message(best: float) -> str:
    """The message of a solve the crawl guard stopped (``best``: its best residual)."""
    return (
        f"no progress: the residual stayed above {best:.2g} (less than a "
        f"{1 / CRAWL_IMPROVEMENT:.0f}-fold fall) for {CRAWL_PATIENCE} iterations (crawl guard)"
    )


class ReliableUpdates:
    """When a mixed-precision iteration replaces its incremental update by an exact one.

    The iterations update a field (``G p - h``, ``K w``) by single-precision increments,
    whose rounding accumulates to ~1e-7 of the distance travelled. Call :meth:`check`
    with every residual: it answers ``"refresh"`` when an exact (float64) evaluation is
    due (the residual fell by :data:`RELIABLE_DROP` since the last one, or
    :data:`RELIABLE_EVERY` iterations passed, or the tolerance is met: convergence is
    only declared on an exact state), and ``"restart"`` on the exact state's residual
    when it exceeds twice the iterated one, i.e. the drift had overtaken the residual
    and the conjugate directions, built on the drifted one, must be restarted. The
    "reliable updates" of Sleijpen & van der Vorst (Computing 56, 141 (1996)).
    """

    def __init__(self, tol: float):
        self.tol, self.reliable, self.since, self.iterated = tol, math.inf, 0, math.inf

    def check(self, residual: float, exact: bool) -> str | None:
        if exact:
            drifted = residual > 2.0 * self.iterated
            self.reliable, self.since, self.iterated = residual, 0, math.inf
            return "restart" if drifted else None
        drop = residual <= RELIABLE_DROP * self.reliable
        if residual <= self.tol or drop or self.since >= RELIABLE_EVERY:
            self.iterated = residual
            return "refresh"
        return None

    def step(self) -> None:
        """Count an iteration of incremental updates."""
        self.since += 1


class StallGuard:
    """Detects a float32 solve stuck at its rounding floor, so it stops early and says so.

    In single precision the residual cannot fall below roughly ``1e-7 * max|p| / E*``
    (more under heavy compression); without this guard such a solve would spend its
    whole iteration cap there. Active only for float32: a float64 solve is never cut
    short by it. ``status``: what a stop by it reports.
    """

    status = SolveStatus.STALLED

    def __init__(self, precision: str, patience: int = STALL_PATIENCE,
                 improvement: float = STALL_IMPROVEMENT, active: bool | None = None):  # fmt: skip
        self.active = precision == "float32" if active is None else active
        self.patience, self.improvement = patience, improvement
        self.best, self.since = math.inf, 0

    def __call__(self, residual: float) -> str | None:
        """The not-converged message if no new best residual came in ``patience`` calls."""
        if not self.active:
            return None
        if residual < self.improvement * self.best:
            self.best, self.since = residual, 0
            return None
        self.since += 1
        if self.since < self.patience:
            return None
        return (
            f"stalled at residual {self.best:.2g} for {self.patience} iterations: the float32 "
            "rounding floor (use dtype='float64' or a larger tol)"
        )


class CrawlGuard(StallGuard):
    """:class:`StallGuard`'s test with the crawl guard's patience and improvement, always
    active (:func:`guarding_crawl`); it replaces the float32 stall guard, which cannot stop
    a loop before it (no 3-fold fall in 40 iterations comes before no 1 % fall in 200). Its
    stop is an ``iteration_limit``: load control starts again from a hard-wall state."""

    status = SolveStatus.ITERATION_LIMIT

    def __init__(self):
        super().__init__("", CRAWL_PATIENCE, CRAWL_IMPROVEMENT, active=True)

    def __call__(self, residual: float) -> str | None:
        return None if super().__call__(residual) is None else crawl_message(self.best)


def stall_guard(precision: str) -> StallGuard:
    """A loop's guard: the crawl guard inside :func:`guarding_crawl`, else the float32
    stall guard of ``precision``."""
    return CrawlGuard() if crawl_guarded() else StallGuard(precision)


def stopping(done: bool, residual: float, stall, it: int, max_iter: int):
    """Why an iteration loop stops here: ``(status, message)``, or None to go on.

    ``done``: the convergence test passed; ``stall``: the loop's :class:`StallGuard` (or
    :class:`CrawlGuard`), whose ``status`` a stop by it reports.
    """
    if done:
        return SolveStatus.CONVERGED, "converged"
    if (stalled := stall(residual)) is not None:
        return stall.status, stalled
    if it >= max_iter:
        return SolveStatus.ITERATION_LIMIT, "iteration cap reached"
    return None
