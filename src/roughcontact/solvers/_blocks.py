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

__all__ = ["BLOCK", "FIRST_BLOCK", "Schedule"]

#: The most device steps between two host checks.
BLOCK = 8
#: The steps of the first block after a host decision (then doubled while no step freezes).
FIRST_BLOCK = 2


class Schedule:
    """Lengths of the blocks of steps between host checks (see the module docstring).

    ``every=1`` checks after every step (a callback must see every iteration).
    """

    def __init__(self, every: int | None = None):
        self.most = BLOCK if every is None else every
        self.length = min(FIRST_BLOCK, self.most)

    def next(self, limit: int) -> int:
        """The next block's length, at most ``limit`` (steps left before a known stop)."""
        return max(1, min(self.length, limit))

    def ran(self, full: bool) -> None:
        """Record how the last block ended: all its steps taken, or one froze."""
        self.length = min(2 * self.length, self.most) if full else min(FIRST_BLOCK, self.most)
