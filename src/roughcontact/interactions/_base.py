"""What every interaction law provides (the Interaction protocol).

A law depends on the local gap ``g`` only and is evaluated per unit area:

* ``energy(g)`` -- V(g), energy per area (pressure × length);
* ``pressure(g)`` -- p = -V'(g) (pressure; > 0 repulsive, < 0 attractive);
* ``curvature(g)`` -- V''(g) (pressure / length);
* ``classify(g)`` -- (repulsive, attractive) boolean masks;
* ``cutoff`` -- gap beyond which V = 0 exactly (``inf`` for unbounded laws);
* ``hard_core`` -- True if the law is only defined for g >= 0 and the non-penetration
  constraint g >= 0 is enforced by the solver (bound-constrained minimisation); the
  solver then also decides which contact sites are repulsive (the README's model: the site's net
  force pushes the surfaces apart).
"""

from __future__ import annotations

import numpy as np

from .._backend import array_namespace

__all__ = ["GapLaw"]


class GapLaw:
    """Mixin: ``energy``/``pressure``/``curvature`` from one ``_evaluate(g) -> (V, V', V'')``."""

    hard_core: bool = False

    def _evaluate(self, gap):  # pragma: no cover - abstract
        raise NotImplementedError

    def energy(self, gap):
        """V(g), energy per area (pressure × length)."""
        return self._evaluate(gap)[0]

    def pressure(self, gap):
        """p(g) = -V'(g) (pressure; > 0 repulsive)."""
        return -self._evaluate(gap)[1]

    def curvature(self, gap):
        """V''(g) (pressure / length)."""
        return self._evaluate(gap)[2]

    def classify(self, gap):
        """(repulsive, attractive) masks: the site's force pushes apart / pulls together."""
        p = self.pressure(gap)
        return p > 0, p < 0


def as_gap(gap):
    """``(xp, g)``: the array namespace of ``gap`` and the gap as a float array of it.

    float32 gaps stay float32 (the solvers' single-precision option); anything else
    becomes float64.
    """
    if not hasattr(gap, "__array_namespace__"):
        gap = np.asarray(gap, dtype=float)
    xp = array_namespace(gap)
    if gap.dtype in (xp.float64, xp.float32):
        return xp, gap
    return xp, xp.astype(gap, xp.float64)
