"""Loop control shared by the iterative solvers: exact refreshes, stall guard, stopping."""

from __future__ import annotations

import math

from .result import SolveStatus

__all__ = [
    "RELIABLE_DROP",
    "RELIABLE_EVERY",
    "STALL_IMPROVEMENT",
    "STALL_PATIENCE",
    "ReliableUpdates",
    "StallGuard",
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
    short by it.
    """

    def __init__(self, precision: str, patience: int = STALL_PATIENCE):
        self.active = precision == "float32"
        self.patience, self.best, self.since = patience, math.inf, 0

    def __call__(self, residual: float) -> str | None:
        """The not-converged message if no new best residual came in ``patience`` calls."""
        if not self.active:
            return None
        if residual < STALL_IMPROVEMENT * self.best:
            self.best, self.since = residual, 0
            return None
        self.since += 1
        if self.since < self.patience:
            return None
        return (
            f"stalled at residual {self.best:.2g} for {self.patience} iterations: the float32 "
            "rounding floor (use dtype='float64' or a larger tol)"
        )


def stopping(done: bool, residual: float, stall, it: int, max_iter: int):
    """Why an iteration loop stops here: ``(status, message)``, or None to go on.

    ``done``: the convergence test passed; ``stall``: the loop's :class:`StallGuard`.
    """
    if done:
        return SolveStatus.CONVERGED, "converged"
    if (stalled := stall(residual)) is not None:
        return SolveStatus.STALLED, stalled
    if it >= max_iter:
        return SolveStatus.ITERATION_LIMIT, "iteration cap reached"
    return None
