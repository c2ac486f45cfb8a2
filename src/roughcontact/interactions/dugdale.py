r"""Maugis–Dugdale cohesive zone on a hard wall.

A constant attractive stress :math:`\sigma_0 = w/\delta` acts wherever the gap is below
the cohesive width δ, nothing beyond; the hard wall g >= 0 is a constraint enforced by the
bound-constrained solver:

.. math:: V(g) = -w\,(1 - g/\delta) \quad (0 \le g < \delta), \qquad V = 0 \quad (g \ge \delta).

The force jumps at g = δ (V has a concave kink there), so no equilibrium has a site
exactly at δ and the energy minimiser remains well posed.

References: D. S. Dugdale, J. Mech. Phys. Solids 8, 100 (1960); D. Maugis, J. Colloid
Interface Sci. 150, 243 (1992).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .._backend import constant
from .._validate import positive
from ._base import GapLaw, as_gap

__all__ = ["MaugisDugdale"]


@dataclass(frozen=True)
class MaugisDugdale(GapLaw):
    """Dugdale cohesive zone of width δ and stress σ0 = w/δ on a hard wall.

    Parameters
    ----------
    work_of_adhesion : float
        w (pressure × length).
    range : float
        Cohesive-zone width δ (length); σ0 = w/δ.
    """

    work_of_adhesion: float
    range: float
    name: str = field(default="dugdale", init=False)
    hard_core: bool = field(default=True, init=False)

    def __post_init__(self):
        object.__setattr__(
            self, "work_of_adhesion", positive("work_of_adhesion", self.work_of_adhesion)
        )
        object.__setattr__(self, "range", positive("range", self.range))

    @property
    def cohesive_stress(self) -> float:
        """σ0 = w/δ (pressure)."""
        return self.work_of_adhesion / self.range

    @property
    def cutoff(self) -> float:
        return self.range

    # the solvers' hot paths (the bounded loop evaluates the law 5-7 times per iteration):
    # each term alone, in fewer passes than ``_evaluate``'s three, with its values (the
    # pressure's -0.0 beyond the zone included; the energy's zero there can be -0.0)

    def pressure(self, gap):
        """p(g) = -σ0 inside the zone (g < δ), 0 beyond (pressure)."""
        xp, g = as_gap(gap)
        p = xp.astype(g < constant(self.range, g), g.dtype)
        p *= constant(-self.cohesive_stress, p)
        return p

    def energy(self, gap):
        """V(g) = -w (1 - g/δ) inside the zone, 0 beyond (energy per area)."""
        xp, g = as_gap(gap)
        # (clipped at δ too, where the zone's mask zeroes it: an infinite gap gives 0, not NaN)
        v = xp.minimum(xp.maximum(g, constant(0.0, g)), constant(self.range, g))
        v *= constant(self.cohesive_stress, v)
        v -= constant(self.work_of_adhesion, v)
        v *= xp.astype(g < constant(self.range, g), g.dtype)
        return v

    def curvature(self, gap):
        """V''(g) = 0 (the force is constant in the zone; its jump at δ has no curvature)."""
        xp, g = as_gap(gap)
        return xp.zeros_like(g)

    def _evaluate(self, gap):
        xp, g = as_gap(gap)
        g = xp.maximum(g, 0.0)
        inside = g < self.range
        s0 = self.cohesive_stress
        zero = xp.zeros_like(g)
        v = xp.where(inside, -self.work_of_adhesion + s0 * g, zero)
        dv = xp.where(inside, xp.full_like(g, s0), zero)
        return v, dv, zero
