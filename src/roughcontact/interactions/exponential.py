r"""Exponential adhesion, on a hard wall or with a soft repulsive core.

.. math:: V(g) = -w\, e^{-g/\rho} \qquad (g \ge 0)

per unit area: work of adhesion w, decay length ρ, largest attractive stress
:math:`w/\rho` at contact. Two ways to stop interpenetration:

* ``core_stiffness=None`` (default): a **hard wall** -- g >= 0 is a constraint that the
  bound-constrained solver enforces (the law of tamaas' ``ExponentialAdhesionFunctional``
  and of Rey, Anciaux & Molinari, Comput. Mech. 60, 69 (2017));
* ``core_stiffness=k_c``: a **soft core**, the C1 continuation
  :math:`V(g) = -w + (w/\rho) g + \tfrac12 k_c g^2` for g < 0, whose minimum lies at
  :math:`g^* = -w/(\rho k_c)`; smooth, solved by the unconstrained minimiser.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from .._backend import constant
from .._validate import positive
from ._base import GapLaw, as_gap

__all__ = ["Exponential"]


@dataclass(frozen=True)
class Exponential(GapLaw):
    """Exponential adhesion -w exp(-g/ρ) (see module docstring).

    Parameters
    ----------
    work_of_adhesion : float
        w (pressure × length).
    range : float
        Decay length ρ (length).
    core_stiffness : float or None
        k_c (pressure / length) of a soft repulsive core for g < 0; None for a hard wall.
    """

    work_of_adhesion: float
    range: float
    core_stiffness: float | None = None
    name: str = field(default="exponential", init=False)

    def __post_init__(self):
        set_ = object.__setattr__
        set_(self, "work_of_adhesion", positive("work_of_adhesion", self.work_of_adhesion))
        set_(self, "range", positive("range", self.range))
        if self.core_stiffness is not None:
            set_(self, "core_stiffness", positive("core_stiffness", self.core_stiffness))

    @property
    def hard_core(self) -> bool:  # type: ignore[override]
        return self.core_stiffness is None

    @property
    def cutoff(self) -> float:
        return math.inf

    @property
    def max_stress(self) -> float:
        """Largest attractive stress w/ρ (pressure), at g = 0."""
        return self.work_of_adhesion / self.range

    def pressure(self, gap):
        """p(g) = -V'(g) (pressure; > 0 repulsive)."""
        if self.core_stiffness is not None:
            return -self._evaluate(gap)[1]
        # the solvers' hot path: only this term (the values of ``-_evaluate(gap)[1]``;
        # max(max(g, 0), 0) = max(g, 0)): a third of the operations, one array pass each
        e = self._decay(gap)
        return -(constant(self.work_of_adhesion / self.range, e) * e)

    def energy(self, gap):
        """V(g), energy per area (pressure × length)."""
        if self.core_stiffness is not None:
            return self._evaluate(gap)[0]
        # the bounded solver's projected steps evaluate it (``_evaluate(gap)[0]``'s values)
        e = self._decay(gap)
        return constant(-self.work_of_adhesion, e) * e

    def curvature(self, gap):
        """V''(g) (pressure / length)."""
        if self.core_stiffness is not None:
            return self._evaluate(gap)[2]
        e = self._decay(gap)
        return constant(-(self.work_of_adhesion / self.range**2), e) * e

    def _decay(self, gap):
        """exp(-max(g, 0)/ρ) (hard core: the gap clipped at the wall)."""
        xp, g = as_gap(gap)
        return xp.exp(-xp.maximum(g, constant(0.0, g)) / constant(self.range, g))

    def _evaluate(self, gap):
        xp, g = as_gap(gap)
        w, rho = self.work_of_adhesion, self.range
        if self.core_stiffness is None:
            g = xp.maximum(g, 0.0)  # hard wall: the solver keeps g >= 0
        e = xp.exp(-xp.maximum(g, 0.0) / rho)
        v, dv, d2v = -w * e, (w / rho) * e, -(w / rho**2) * e
        if self.core_stiffness is not None:
            kc = self.core_stiffness
            inside = g < 0
            v = xp.where(inside, -w + (w / rho) * g + 0.5 * kc * g * g, v)
            dv = xp.where(inside, w / rho + kc * g, dv)
            d2v = xp.where(inside, xp.full_like(g, kc), d2v)
        return v, dv, d2v
