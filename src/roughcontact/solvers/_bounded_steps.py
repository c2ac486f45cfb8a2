"""The bounded solver's device steps off NumPy: blocks without host syncs.

See :mod:`.bounded` (the method) and :mod:`._blocks` (the structure). A device step is
the common iteration of the sequential loop: the preconditioned PR+ direction, the line
search's Newton guess taken (``|phi'(hi)| <= rtol |phi'(0)|``) and feasible (no site
crosses the wall), and the new state's top (multiplier, active face, free sites'
imbalance). Every other case (the guess not taken: bracketing; a step crossing the wall:
the projection; an exact refresh due; convergence; a non-finite value) freezes the state
for the host's sequential loop, which takes that iteration itself: the same values and
iterations as before, with one host sync per block instead of one or two per iteration.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from .._backend import array_device
from ._projection import _direction_on_device
from .line_search import device_guess
from .reductions import fetch

__all__ = ["BoundedState"]

#: line_minimum's default tolerance, which the bounded solver's line search uses
LINE_RTOL = 1e-3


class BoundedState(NamedTuple):
    """The bounded loop's state between steps (device arrays; ``mu`` a float when the
    uniform mode is free)."""

    w: object
    kw: object  # K w
    gap: object  # the top of (w, K w): gap, multiplier, active face, free sites, ...
    mu: object
    active: object
    free: object
    rr: object  # ... the free sites' force imbalance, ...
    rr_max: object  # ... its largest magnitude and ...
    n_free: object  # ... the free sites' count (0-d float64)
    s: object  # the search direction
    z_old: object  # the last preconditioned gradient, ...
    gz_old: object  # ... its product with the gradient (0-d float64) ...
    active_old: object  # ... and the active face then


class _DeviceSteps:
    """Device steps of one bounded solve (from the closures of its solver function)."""

    def __init__(self, xp, top, green, stiff_single, masked_mean, in_dt, count, interaction,
                 rigid, modulus, work, zero):  # fmt: skip
        self.xp, self.top, self.green, self.stiff_single = xp, top, green, stiff_single
        self.masked_mean, self.in_dt, self.count = masked_mean, in_dt, count
        self.interaction, self.rigid, self.modulus, self.work = interaction, rigid, modulus, work
        # the step's constants, made once: (1,) in the fields' dtype (``zero``), 0-d
        # float64 (a Python scalar operand is converted at every use)
        dev, f64 = array_device(zero), xp.float64
        self.zero, self.minus_one, self.inf = (
            zero,
            *(xp.full((1,), v, dtype=zero.dtype, device=dev) for v in (-1.0, math.inf)),
        )
        self.zero64, self.inf64, self.rtol = (
            xp.asarray(v, dtype=f64, device=dev) for v in (0.0, math.inf, LINE_RTOL)
        )

    def state(self, w, kw, gap, mu, active, free, rr, rr_max, n_free, s, z_old, gz_old, active_old):
        """The host loop's variables as a :class:`BoundedState` (placeholders for the
        directions not made yet: a restart does not read them)."""
        xp = self.xp
        dev = array_device(w)

        def scalar(v):
            return xp.asarray(float(v), dtype=xp.float64, device=dev)

        return BoundedState(w, kw, gap, mu, active, free, rr, scalar(rr_max), scalar(n_free),
                            xp.zeros_like(w) if s is None else s,
                            xp.zeros_like(w) if z_old is None else z_old,
                            scalar(gz_old) if isinstance(gz_old, float) else gz_old,
                            active if active_old is None else active_old)  # fmt: skip

    def step(self, st, restart: bool, threshold, alive):
        """One iteration, no host sync; frozen (``st`` itself) unless ``alive`` and the
        top needs no decision and the guess is taken and feasible. Returns (state, go)."""
        xp, in_dt, zero = self.xp, self.in_dt, self.zero
        residual = st.rr_max / self.modulus
        ok = alive & (residual > threshold) & (residual < self.inf64) & (st.n_free > self.zero64)
        z = xp.where(st.free, self.green(st.rr), zero)
        if self.rigid:
            # (n_free: the free sites' count, kept with them)
            mean = self.masked_mean(z, st.free, lambda: 0.0, st.n_free)
            z = xp.where(st.free, z - in_dt(mean), zero)
        s, slope0, gz = _direction_on_device(xp, st.rr, z, st.z_old, st.s, st.gz_old, restart,
                                             st.active, st.active_old)  # fmt: skip
        ks = self.stiff_single(s)
        crossing = s < zero
        ratio = -st.gap / xp.where(crossing, s, self.minus_one)
        alpha_max = xp.min(xp.where(crossing, ratio, self.inf))
        hi, f_hi, _ = device_guess(self.interaction, st.gap, s, ks, slope0, self.work, kw=st.kw)
        go = ok & (xp.abs(f_hi) <= self.rtol * xp.abs(slope0)) & (hi <= alpha_max)
        w, kw = st.w + in_dt(hi) * s, st.kw + in_dt(hi) * ks
        gap, mu, active, free, rr = self.top(w, kw)
        new = BoundedState(w, kw, gap, mu, active, free, rr, xp.max(xp.abs(rr)),
                           self.count(free), s, z, gz, st.active)  # fmt: skip
        return BoundedState(*(
            v if isinstance(v, float) else xp.where(go, v, old)
            for v, old in zip(new, st, strict=True)
        )), go  # fmt: skip

    def block(self, st, n, it0, fresh, restart_every, threshold, tops=False):
        """``n`` steps from iteration ``it0`` (``fresh``: no directions yet) and one host
        sync. Returns ``(state, steps taken, rr_max, n_free, rr_max after each step)``
        (the last only with ``tops``)."""
        xp = self.xp
        dev = array_device(st.w)
        threshold = xp.asarray(threshold, dtype=xp.float64, device=dev)
        alive = xp.asarray(True, device=dev)  # once a step froze, all the block's do
        taken, after = xp.asarray(0.0, dtype=xp.float64, device=dev), []
        for j in range(n):
            restart = (j == 0 and fresh) or (it0 + j + 1) % restart_every == 0
            st, alive = self.step(st, restart, threshold, alive)
            taken = taken + xp.astype(alive, xp.float64)
            if tops:
                after.append(st.rr_max)
        values = fetch(xp, [taken, st.rr_max, st.n_free, *after])
        return st, int(values[0]), values[1], values[2], values[3:]
