r"""The untruncated 9-3 Lennard-Jones wall (for comparison with the smoothed one).

.. math:: V(g) = \epsilon\,[(2/15)(\sigma/g)^9 - (\sigma/g)^3],\qquad
          \sigma = a_0 (5/2)^{1/6},\qquad w = -V(a_0) = \tfrac23\sqrt{5/2}\,\epsilon

per unit area, with its minimum at the equilibrium distance :math:`a_0`. Its stiffness
:math:`k = V''(a_0) = 27 w / a_0^2` is fixed by w and a0, and its attraction decays as
:math:`g^{-4}` (infinite range: every site with g > a0 is attractive). Below
``0.05 a0`` the core is continued by a C2 quadratic (finite restoring force).

Reference: W. A. Steele, Surf. Sci. 36, 317 (1973); Pastewka & Robbins, PNAS 111, 3298
(2014), Methods (the smoothed variant is :class:`~roughcontact.interactions.SmoothLJ93`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from .._validate import positive
from ._base import GapLaw, as_gap
from ._lj93 import SIGMA_OVER_A0, curvature_at_minimum, lj93_with_core

__all__ = ["LennardJones93"]


@dataclass(frozen=True)
class LennardJones93(GapLaw):
    """Untruncated 9-3 LJ wall with minimum -w at gap a0 (see module docstring).

    Parameters
    ----------
    work_of_adhesion : float
        w = -V(a0) (pressure × length, e.g. E* a0 in lattice units).
    equilibrium_distance : float
        a0, gap of the energy minimum (length).
    """

    work_of_adhesion: float
    equilibrium_distance: float = 1.0
    name: str = field(default="lj93", init=False)
    hard_core: bool = field(default=False, init=False)

    def __post_init__(self):
        object.__setattr__(
            self, "work_of_adhesion", positive("work_of_adhesion", self.work_of_adhesion)
        )
        object.__setattr__(
            self,
            "equilibrium_distance",
            positive("equilibrium_distance", self.equilibrium_distance),
        )

    @classmethod
    def from_epsilon_sigma(cls, epsilon: float, sigma: float) -> LennardJones93:
        """From the LJ parameters ε (energy/area) and σ (length) of V_LJ."""
        eps = positive("epsilon", epsilon)
        a0 = positive("sigma", sigma) / SIGMA_OVER_A0
        return cls(work_of_adhesion=(2.0 / 3.0) * math.sqrt(2.5) * eps, equilibrium_distance=a0)

    @property
    def sigma(self) -> float:
        return self.equilibrium_distance * SIGMA_OVER_A0

    @property
    def epsilon(self) -> float:
        return 1.5 * self.work_of_adhesion / math.sqrt(2.5)

    @property
    def stiffness(self) -> float:
        """k = V''(a0) = 27 w / a0² (pressure / length)."""
        return self.epsilon * curvature_at_minimum(self.sigma, self.equilibrium_distance)

    @property
    def cutoff(self) -> float:
        return math.inf

    def _evaluate(self, gap):
        g = as_gap(gap)[1]
        return lj93_with_core(g, self.epsilon, self.sigma, self.equilibrium_distance)

    def classify(self, gap):
        """(repulsive, attractive): g < a0 and g > a0."""
        g = as_gap(gap)[1]
        a0 = self.equilibrium_distance
        return g < a0, g > a0
