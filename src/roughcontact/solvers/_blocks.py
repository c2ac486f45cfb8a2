"""Blocks of device steps between host checks: the driver of the solvers' array-API loops.

Off NumPy (a GPU) an iteration is split as in optimistix: ``init`` builds a frozen state
record of device arrays, ``step(state) -> state`` advances it without reading anything
back to the host (scalars stay 0-d device arrays, branches are ``where`` selections),
and the host looks at the state only between blocks of steps (one transfer of a few
scalars: one host sync per block). A step whose state needs a host decision (converged,
an exact refresh due, a lost contact set, a non-finite value, a rare fallback) leaves
the state as it is ("frozen"): the following steps of the block recompute the same
decision and change nothing, so the host finds the state exactly where the sequential
loop would have stopped to decide, and the iterations taken are the same.

Block lengths (:class:`Schedule`): a frozen step costs a whole step of device work, so
the blocks are short after a decision (:data:`FIRST_BLOCK` steps) and double while no
step freezes, up to :data:`BLOCK`. A check costs one host sync, which on a GPU idles the
device while the host launches the next kernels: about the launch time of one step's
kernels, a fraction of a step. Eight steps per check keep that below a few per cent of
the iteration time, while a decision costs on average half a block of frozen steps;
decisions are rare (a solve of 20-50 iterations makes 2-4: exact refreshes and the
convergence test).
"""

from __future__ import annotations

import math

__all__ = ["BLOCK", "FIRST_BLOCK", "Schedule"]

#: The most device steps between two host checks.
BLOCK = 8
#: The steps of the first block after a host decision (then doubled while no step freezes).
FIRST_BLOCK = 2


class Schedule:
    """Lengths of the blocks of steps between host checks (see the module docstring).

    ``every=1`` checks after every step (a callback must see every iteration). Where
    the residual falls steadily, a block is also cut at the step where the residual's
    geometric trend (over the last block) reaches the next decision's threshold, so
    that a decision wastes few frozen steps.
    """

    def __init__(self, every: int | None = None):
        self.most = BLOCK if every is None else every
        self.length = min(FIRST_BLOCK, self.most)
        self.residual, self.rate = math.nan, math.nan
        self.wait, self.waited = 0, 0  # back-off of a loop whose device steps can fail

    def ready(self) -> bool:
        """Whether to try device steps now (a loop whose first step froze waits 1, 2, 4,
        ... host iterations before trying again: a frozen step is wasted work); call
        once per host iteration."""
        if self.waited >= self.wait:
            return True
        self.waited += 1
        return False

    def next(self, limit: int, residual: float = math.nan, threshold: float = 0.0) -> int:
        """The next block's length, at most ``limit`` (steps left before a known stop);
        ``residual``: the last one seen, ``threshold``: where the host decides next."""
        n = min(self.length, limit)
        if 0.0 < self.rate < 1.0 and threshold > 0.0 and residual > threshold:
            # steps until the trend crosses the threshold: the block ends there
            n = min(n, int(math.log(threshold / residual) / math.log(self.rate)) + 1)
        return max(1, n)

    def ran(self, full: bool, steps: int = 0, residual: float = math.nan) -> None:
        """Record how the last block ended: all its steps taken, or one froze; ``steps``
        taken from the last ``residual`` seen to ``residual``."""
        self.length = min(2 * self.length, self.most) if full else min(FIRST_BLOCK, self.most)
        if steps == 0 and not full:  # not one step: back off (see ready)
            self.wait, self.waited, self.length = min(max(2 * self.wait, 1), BLOCK), 0, 1
        elif steps:
            self.wait = 0
        ok = full and steps > 0 and self.residual > 0.0 and residual > 0.0
        self.rate = (residual / self.residual) ** (1.0 / steps) if ok else math.nan
        self.residual = residual
