r"""The 9-3 Lennard-Jones wall shared by :class:`SmoothLJ93` and :class:`LennardJones93`.

:math:`V_{LJ}(g) = \epsilon[(2/15)(\sigma/g)^9 - (\sigma/g)^3]` per unit area, the
interaction of a half-space of 12-6 LJ atoms with a wall (Steele 1973). Its minimum is at
:math:`g = a_0 = \sigma (2/5)^{1/6}`, where :math:`V_{LJ}(a_0) = -(2/3)\sqrt{5/2}\,\epsilon`.
"""

from __future__ import annotations

import numpy as np

from .._backend import array_namespace, constant

__all__ = [
    "SIGMA_OVER_A0",
    "lj93_derivative",
    "lj93_derivatives",
    "lj93_terms",
    "lj93_with_core",
]

SIGMA_OVER_A0 = 2.5 ** (1.0 / 6.0)
# g_min as a fraction of a0: below it the core is continued as a C2 quadratic, so a solver
# that overshoots into g <= 0 gets a finite restoring force instead of an overflow
CORE_FRACTION = 0.05


def curvature_at_minimum(sigma: float, a0: float) -> float:
    """V_LJ''(a0) per unit epsilon (pressure / length per unit ε)."""
    return (2.0 / 15.0) * 90.0 * sigma**9 / a0**11 - 12.0 * sigma**3 / a0**5


def _powers(g, sigma: float):
    """1/g, (σ/g)³ and (σ/g)⁹."""
    # (constant: the Python scalar on NumPy, elsewhere an array made once: see there)
    inv = constant(1.0, g) / g
    s3 = constant(sigma, inv) * inv
    s3 = s3 * s3 * s3  # products, not ** 3: NumPy's pow is 4x slower (solvers' hot path)
    return inv, s3, s3 * s3 * s3


def _first(epsilon: float, inv, s3, s9):
    """V_LJ' from :func:`_powers` (pressure)."""
    c = constant
    return c(epsilon, s3) * (c(-(18.0 / 15.0), s9) * s9 + c(3.0, s3) * s3) * inv


def _second(epsilon: float, inv, s3, s9):
    """V_LJ'' from :func:`_powers` (pressure / length)."""
    c = constant
    return c(epsilon, s3) * (c(180.0 / 15.0, s9) * s9 - c(12.0, s3) * s3) * (inv * inv)


def lj93_terms(g, epsilon: float, sigma: float):
    """V_LJ, V_LJ' and V_LJ'' at gaps ``g > 0`` (energy/area, pressure, pressure/length)."""
    inv, s3, s9 = _powers(g, sigma)
    v = epsilon * ((2.0 / 15.0) * s9 - s3)
    return v, _first(epsilon, inv, s3, s9), _second(epsilon, inv, s3, s9)


def lj93_with_core(g, epsilon: float, sigma: float, a0: float):
    """V_LJ and derivatives, continued below ``CORE_FRACTION * a0`` by a C2 quadratic."""
    g_min = CORE_FRACTION * a0
    gc = array_namespace(g).maximum(g, g_min)
    v, dv, d2v = lj93_terms(gc, epsilon, sigma)
    below = g - gc  # < 0 only under g_min
    return v + dv * below + 0.5 * d2v * below**2, dv + d2v * below, d2v


def lj93_derivative(g, epsilon: float, sigma: float, a0: float, order: int, branch: bool = True):
    """V_LJ' (``order=1``) or V_LJ'' (``order=2``) of :func:`lj93_with_core`, only that one.

    The solvers' hot path (the pressure or the curvature on the sites in the core):
    :func:`lj93_with_core` computes all three terms. The quadratic continuation below
    ``CORE_FRACTION * a0`` has V'' constant and V' linear there. ``branch=False`` adds
    the continuation's term without testing whether any gap needs it.
    """
    xp = array_namespace(g)
    g_min = CORE_FRACTION * a0
    gc = xp.maximum(g, constant(g_min, g))
    powers = _powers(gc, sigma)
    if order == 2:
        return _second(epsilon, *powers)
    dv = _first(epsilon, *powers)
    # rare: a solver's trial step deep into the core; without ``branch`` (a GPU: the test
    # would wait for the device) always, exactly dv where g >= g_min (g - gc = 0 there)
    if not branch or bool(xp.any(g < g_min)):
        dv = dv + _second(epsilon, *powers) * (g - gc)
    return dv


def lj93_derivatives(g, epsilon: float, sigma: float, a0: float):
    """``(V_LJ', V_LJ'')`` of :func:`lj93_with_core` from one set of powers (NumPy): the
    values of :func:`lj93_derivative` with ``order=1`` and ``order=2``."""
    g_min = CORE_FRACTION * a0
    gc = np.maximum(g, g_min)
    # _powers, _second and _first with the same operations in the same order (products
    # commute exactly), written into fewer arrays
    inv = np.divide(1.0, gc)
    s3 = np.multiply(inv, sigma)
    t = np.multiply(s3, s3)
    t *= s3
    s3 = t
    s9 = np.multiply(s3, s3)
    s9 *= s3
    second = np.multiply(s9, 180.0 / 15.0)
    b = np.multiply(s3, 12.0)
    second -= b
    second *= epsilon
    second *= np.multiply(inv, inv, out=b)
    dv = np.multiply(s9, -(18.0 / 15.0), out=s9)
    dv += np.multiply(s3, 3.0, out=b)
    dv *= epsilon
    dv *= inv
    if g.shape[0] and float(np.minimum.reduce(g)) < g_min:
        dv = dv + second * (g - gc)
    return dv, second
