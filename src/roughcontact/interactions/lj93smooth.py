r"""The paper's interaction: a 9-3 Lennard-Jones wall smoothly truncated by a quartic.

Pastewka & Robbins, PNAS 111, 3298 (2014), Methods. With the equilibrium
distance :math:`a_0`, the stiffness :math:`k = V''(a_0)` and the range :math:`\Delta r`,
and :math:`x = (g - a_0)/\Delta r`:

.. math::
    V(g) = \begin{cases}
      V_{LJ}(g) - V_{LJ}(a_0) - w & g < a_0 \\
      -w (1 - x)^3 (1 + 3x)          & a_0 \le g < a_0 + \Delta r \\
      0                              & g \ge a_0 + \Delta r
    \end{cases}

with :math:`V_{LJ} = \epsilon[(2/15)(\sigma/g)^9 - (\sigma/g)^3]`,
:math:`\sigma = a_0 (5/2)^{1/6}` (so that :math:`V_{LJ}'(a_0) = 0`) and :math:`\epsilon`
such that :math:`V_{LJ}''(a_0) = k`. Continuity of V, V', V'' forces
:math:`w = k \Delta r^2 / 12`. Everything is per unit area: V in pressure × length, the
pressure :math:`p = -V'` (positive = repulsive), k in pressure / length. The paper's
per-site stiffness :math:`E^* a_0/2` is :math:`k = E^*/(2 a_0)` per area, which gives
:math:`\ell_a = w/E^* = \Delta r^2/(24 a_0)`.

Below ``g_min = 0.05 a0`` the core is continued as the quadratic with the same V, V',
V'' at ``g_min`` (finite and strongly repulsive), so a solver that overshoots into
g <= 0 gets a restoring force instead of an overflow.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from .._backend import constant, is_cupy_array, is_numpy_array
from .._validate import ParameterError, positive
from ._base import as_gap
from ._fused import kernel
from ._lj93 import (
    CORE_FRACTION,
    SIGMA_OVER_A0,
    curvature_at_minimum,
    lj93_derivative,
    lj93_derivatives,
    lj93_terms,
    lj93_with_core,
)

__all__ = ["SmoothLJ93"]


@dataclass(frozen=True, init=False)
class SmoothLJ93:
    """Smoothed 9-3 Lennard-Jones wall (see module docstring).

    Parameters
    ----------
    contact_modulus : float
        E* (pressure); sets the default stiffness k = E*/(2 a0).
    pixel_size : float
        a0 of the lattice (length); the default equilibrium distance.
    equilibrium_distance : float, optional
        Gap of the energy minimum (length); default ``pixel_size``.
    stiffness, range, work_of_adhesion : float, optional
        Any two of k (pressure/length), Δr (length), w (pressure × length); the third
        follows from w = k Δr²/12. With only one of range / work_of_adhesion the
        stiffness defaults to E*/(2 a0).
    """

    name: str
    equilibrium_distance: float
    stiffness: float
    range: float
    work_of_adhesion: float
    contact_modulus: float
    epsilon: float
    sigma: float
    hard_core: bool = False
    adhesive: ClassVar[bool] = True

    def __init__(
        self,
        *,
        contact_modulus=1.0,
        pixel_size=1.0,
        equilibrium_distance=None,
        stiffness=None,
        range=None,
        work_of_adhesion=None,
    ):  # noqa: A002
        es = positive("contact_modulus", contact_modulus)
        a0 = positive(
            "equilibrium_distance",
            pixel_size if equilibrium_distance is None else equilibrium_distance,
        )
        k = None if stiffness is None else positive("stiffness", stiffness)
        dr = None if range is None else positive("range", range)
        w = None if work_of_adhesion is None else positive("work_of_adhesion", work_of_adhesion)
        given = sum(v is not None for v in (k, dr, w))
        if given == 0 or (given == 1 and k is not None):
            raise ParameterError(
                "SmoothLJ93 needs range or work_of_adhesion (any two of "
                "stiffness, range, work_of_adhesion; w = k*range**2/12)"
            )
        if k is None and (dr is None or w is None):
            k = es / (2.0 * a0)
        if dr is None:
            dr = math.sqrt(12.0 * w / k)
        elif w is None:
            w = k * dr * dr / 12.0
        elif k is None:
            k = 12.0 * w / (dr * dr)
        elif not math.isclose(w, k * dr * dr / 12.0, rel_tol=1e-9):
            raise ParameterError(
                f"stiffness={k}, range={dr}, work_of_adhesion={w} are inconsistent: "
                f"continuity of V, V', V'' needs work_of_adhesion = stiffness*range**2/12 "
                f"= {k * dr * dr / 12.0}"
            )
        sigma = a0 * SIGMA_OVER_A0
        d2 = curvature_at_minimum(sigma, a0)
        set_ = object.__setattr__
        for key, val in (
            ("name", "lj93smooth"),
            ("equilibrium_distance", a0),
            ("stiffness", k),
            ("range", dr),
            ("work_of_adhesion", w),
            ("contact_modulus", es),
            ("epsilon", k / d2),
            ("sigma", sigma),
            ("hard_core", False),
        ):
            set_(self, key, val)

    @classmethod
    def from_adhesion_length(cls, adhesion_length, *, contact_modulus=1.0, pixel_size=1.0):
        """The paper's parametrisation: ℓa = w/E* (length), k = E*/(2 a0), Δr = √(24 a0 ℓa)."""
        la = positive("adhesion_length", adhesion_length)
        es = positive("contact_modulus", contact_modulus)
        return cls(contact_modulus=es, pixel_size=pixel_size, work_of_adhesion=la * es)

    @property
    def cutoff(self) -> float:
        """Gap beyond which V = 0 exactly (a0 + Δr)."""
        return self.equilibrium_distance + self.range

    @property
    def adhesion_length(self) -> float:
        """ℓa = w/E* (length)."""
        return self.work_of_adhesion / self.contact_modulus

    # ---------------------------------------------------------------- evaluation
    def _evaluate(self, gap):
        xp, g = as_gap(gap)
        a0, dr, w = self.equilibrium_distance, self.range, self.work_of_adhesion
        v = xp.zeros_like(g)
        dv = xp.zeros_like(g)
        d2v = xp.zeros_like(g)
        core = g < a0
        if xp.any(core):
            vc, dvc, d2vc = lj93_with_core(g[core], self.epsilon, self.sigma, a0)
            v[core] = vc - lj93_terms(a0, self.epsilon, self.sigma)[0] - w
            dv[core] = dvc
            d2v[core] = d2vc
        band = (g >= a0) & (g < a0 + dr)
        if xp.any(band):
            x = (g[band] - a0) / dr
            m = 1.0 - x
            v[band] = -w * m**3 * (1.0 + 3.0 * x)
            dv[band] = 12.0 * w * x * m**2 / dr
            d2v[band] = 12.0 * w * m * (1.0 - 3.0 * x) / dr**2
        return v, dv, d2v

    def energy(self, gap):
        """V(g), energy per area (pressure × length)."""
        return self._evaluate(gap)[0]

    def pressure(self, gap):
        """p(g) = -V'(g) (pressure; > 0 repulsive)."""
        # the solvers' hot path: the quartic on every site (zero from the cutoff on,
        # where 1 - x is clipped to 0), then the 9-3 core only where g < a0
        xp, g = as_gap(gap)
        if is_cupy_array(g) and (fused := kernel("pressure")) is not None:
            return fused(g, *self._kernel_args(-12.0 * self.work_of_adhesion / self.range))
        # (constant: the Python scalar on NumPy, elsewhere an array made once: see there)
        m = self._remaining_range(xp, g)
        p = constant(1.0, m) - m  # x
        p *= m
        p *= m
        p *= constant(-12.0 * self.work_of_adhesion / self.range, p)
        return self._core(xp, g, p, 1, sign=-1.0)

    def curvature(self, gap):
        """V''(g) (pressure / length)."""
        xp, g = as_gap(gap)
        if is_cupy_array(g) and (fused := kernel("curvature")) is not None:
            scale = 12.0 * self.work_of_adhesion / self.range**2
            return fused(g, *self._kernel_args(scale))
        m = self._remaining_range(xp, g)
        d2v = constant(3.0, m) * m - constant(2.0, m)  # 1 - 3x
        d2v *= m
        d2v *= constant(12.0 * self.work_of_adhesion / self.range**2, d2v)
        return self._core(xp, g, d2v, 2, sign=1.0)

    def pressure_and_curvature(self, gap):
        """``(pressure(gap), curvature(gap))`` in one evaluation (the same values).

        The line search of the smooth solver's NumPy loop evaluates both at its trial
        points (the curvature at the accepted one is the next line search's Newton
        guess): on NumPy the quartic's ``1 - x`` and the core's sites and powers are
        computed once for both; elsewhere the two calls.
        """
        if type(gap) is not np.ndarray or gap.dtype not in (np.float64, np.float32):
            return self.pressure(gap), self.curvature(gap)
        g, w, dr = gap, self.work_of_adhesion, self.range
        m = self.cutoff - g  # (_remaining_range's operations)
        m *= 1.0 / dr
        np.clip(m, 0.0, 1.0, out=m)
        p = 1.0 - m  # x (the operations and their order of pressure and curvature)
        p *= m
        p *= m
        p *= -12.0 * w / dr
        d2v = 3.0 * m
        d2v -= 2.0  # 1 - 3x
        d2v *= m
        d2v *= 12.0 * w / dr**2
        core = np.flatnonzero(g < self.equilibrium_distance) if g.ndim == 1 else None
        if core is None:  # (not a flat field: the two evaluations)
            return self.pressure(g), self.curvature(g)
        if core.size:
            gc = g[core]
            dv, second = lj93_derivatives(gc, self.epsilon, self.sigma, self.equilibrium_distance)
            p[core] = -1.0 * dv
            d2v[core] = 1.0 * second
        return p, d2v

    def _kernel_args(self, scale):
        """The scalars of the fused CuPy kernels (:mod:`._fused`), after the gap."""
        a0 = self.equilibrium_distance
        return (
            self.cutoff, 1.0 / self.range, scale, a0, CORE_FRACTION * a0, self.sigma,
            self.epsilon, -(18.0 / 15.0), 180.0 / 15.0, 12.0, 3.0, 2.0,
        )  # fmt: skip

    def _remaining_range(self, xp, g):
        """1 - x = (a0 + Δr - g)/Δr clipped to [0, 1] (a new array).

        Exactly 0 from the cutoff on (the sign of a0 + Δr - g is exact, where x = (g -
        a0)/Δr could round below 1 there): V, V', V'' vanish exactly beyond it.
        """
        m = constant(self.cutoff, g) - g
        m *= constant(1.0 / self.range, m)
        if is_numpy_array(m):
            return np.clip(m, 0.0, 1.0, out=m)
        # two plain passes: array_api_compat's clip allocates and checks on every call
        # (0.45 ms per call at 1024² on CuPy)
        return xp.minimum(xp.maximum(m, constant(0.0, m)), constant(1.0, m))

    def _core(self, xp, g, out, derivative, sign):
        """``out`` with ``sign`` times that derivative of the core where g < a0 (``out``
        itself, overwritten there, on NumPy; a new array elsewhere)."""
        core = g < constant(self.equilibrium_distance, g)
        if not is_numpy_array(core):
            # on every site, selected by a mask: no test on the host (a sync on a GPU) and
            # no gather (CuPy's boolean indexing syncs too); the same values on the core
            d = lj93_derivative(
                g, self.epsilon, self.sigma, self.equilibrium_distance, derivative, branch=False
            )
            return xp.where(core, constant(sign, d) * d, out)
        if core.ndim == 1:
            core = np.flatnonzero(core)  # index arrays: cheaper gathers on a part of the band
            if core.size == 0:
                return out
        elif not core.any():
            return out
        d = lj93_derivative(
            g[core], self.epsilon, self.sigma, self.equilibrium_distance, derivative
        )
        out[core] = sign * d
        return out

    def classify(self, gap):
        """(repulsive, attractive) masks: g < a0, and a0 < g < a0 + Δr (README: 'The model')."""
        g = as_gap(gap)[1]
        a0 = self.equilibrium_distance
        return g < a0, (g > a0) & (g < a0 + self.range)
