"""The smooth solver's device steps off NumPy: blocks without host syncs.

See :mod:`.smooth` (the method) and :mod:`._blocks` (the structure). A device step is
the common iteration of the sequential loop: the block-preconditioned PR+ direction and
the line search's Newton guess taken (``|phi'(hi)| <= rtol |phi'(0)|``), with the new
state's force imbalance. Every other case (the guess not taken: bracketing; an exact
refresh due; convergence; a non-finite value) freezes the state for the host's
sequential loop, which takes that iteration itself: the same values and iterations as
before, with one host sync per block instead of one or two per iteration. The
preconditioner's stiff sites are refreshed by the host between blocks, at the
iterations where the sequential loop refreshes them.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from .._backend import array_device
from ._block import _direction_on_device, _direction_stiffness, _precondition
from .line_search import device_guess
from .reductions import fetch, vdot

__all__ = ["SmoothState"]


class SmoothState(NamedTuple):
    """The smooth loop's state between steps (device arrays)."""

    gap: object  # the iterate
    kw: object  # K w (updated by increments between exact refreshes)
    gr: object  # the force imbalance K w - p_int (mean-free with a rigid mean)
    p_near: object  # the interaction pressure at gap
    s: object  # the search direction and ...
    ks: object  # ... its elastic pressure K s
    z_old: object  # the last preconditioned gradient and ...
    gz_old: object  # ... its product with the gradient (0-d float64)


class _DeviceSteps:
    """Device steps of one smooth solve (from the closures of its solver function)."""

    def __init__(self, xp, work, interaction, imbalance, operators, rigid, modulus, rtol):
        self.xp, self.work, self.interaction, self.imbalance = xp, work, interaction, imbalance
        self.compliance, self.elastic_pressure, self.fast = operators
        self.rigid, self.modulus, self.rtol = rigid, modulus, rtol

    def state(self, gap, kw, gr, p_near, s, ks, z_old, gz_old):
        """The host loop's variables as a :class:`SmoothState`."""
        xp = self.xp
        if isinstance(gz_old, float):
            gz_old = xp.asarray(gz_old, dtype=xp.float64, device=array_device(gap))
        return SmoothState(gap, kw, gr, p_near, s, ks, z_old, gz_old)

    def step(self, st, stiff, diagonal, restart: bool, threshold, alive):
        """One iteration, no host sync; frozen (``st`` itself) unless ``alive``, the top
        needs no decision and the guess is taken. Returns ``(state, go)``."""
        xp, work = self.xp, self.work
        residual = xp.max(xp.abs(st.gr)) / self.modulus
        ok = alive & (residual > threshold) & (residual < math.inf)
        z, kz = _precondition(st.gr, stiff, diagonal, self.compliance, self.elastic_pressure,
                              self.rigid, work=work, fast=self.fast)  # fmt: skip
        s, slope0, beta, gz = _direction_on_device(xp, work, st.gr, z, st.z_old, st.s,
                                                   st.gz_old, restart)  # fmt: skip
        ks = _direction_stiffness(work, st.ks, beta, kz)
        elastic_slope = slope0 + vdot(s, st.p_near)
        hi, f_hi, p = device_guess(self.interaction, st.gap, s, ks, slope0, work,
                                   elastic_slope=elastic_slope)  # fmt: skip
        go = ok & (xp.abs(f_hi) <= self.rtol * xp.abs(slope0))
        gap, kw = work.axpy(st.gap, hi, s), work.axpy(st.kw, hi, ks)
        new = SmoothState(gap, kw, self.imbalance(kw, p, None), p, s, ks, z, gz)
        return SmoothState(*(xp.where(go, v, old) for v, old in zip(new, st, strict=True))), go

    def block(self, st, stiff, diagonal, restarts, threshold, tops=False):
        """Steps with the preconditioner's ``stiff`` sites and ``diagonal``, one per entry
        of ``restarts`` (whether it restarts the directions), and one host sync. Returns
        ``(state, steps taken, max gr, min gr, the residual after each step)`` (the last
        only with ``tops``)."""
        xp = self.xp
        dev = array_device(st.gap)
        threshold = xp.asarray(threshold, dtype=xp.float64, device=dev)
        alive = xp.asarray(True, device=dev)  # once a step froze, all the block's do
        taken, after = xp.asarray(0.0, dtype=xp.float64, device=dev), []
        for restart in restarts:
            st, alive = self.step(st, stiff, diagonal, restart, threshold, alive)
            taken = taken + xp.astype(alive, xp.float64)
            if tops:
                after.append(xp.max(xp.abs(st.gr)))
        values = fetch(xp, [taken, xp.max(st.gr), xp.min(st.gr), *after])
        return st, int(values[0]), values[1], values[2], [v / self.modulus for v in values[3:]]
