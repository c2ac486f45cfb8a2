r"""Green's function of a free (non-periodic) elastic half-space on a finite grid.

A uniform pressure ``p`` on the rectangle :math:`|x'| \le a,\ |y'| \le b` of the surface
of a half-space deflects the surface at ``(x, y)`` by (Love, Phil. Trans. R. Soc. A 228,
377 (1929); Johnson, *Contact Mechanics* (CUP 1985), §3.2)

.. math::
    w(x, y) = \frac{p}{\pi E^*} \int_{-a}^{a}\!\int_{-b}^{b}
    \frac{dx'\,dy'}{\sqrt{(x - x')^2 + (y - y')^2}}
    = \frac{p}{\pi E^*}\big[F(x+a, y+b) - F(x-a, y+b) - F(x+a, y-b) + F(x-a, y-b)\big],

with :math:`F(u, v) = u \operatorname{asinh}(v/|u|) + v \operatorname{asinh}(u/|v|)`
(a double antiderivative of :math:`1/r`, odd in ``u`` and in ``v``) and
:math:`E^* = E/(1-\nu^2)`; far from the rectangle it is Boussinesq's point load,
:math:`w \to 4abp/(\pi E^* r)`. Deflection is positive into the substrate, pressure
positive when compressive (the README's conventions).

The four terms of the closed form grow like ``r ln r`` while their sum falls like
``1/r``: in float64 it loses :math:`\sim\epsilon\,(r/a_0)^2` to cancellation (1e-9 at
3000 a0). From :data:`FAR_FIELD` pixels on, the same integral is therefore evaluated by a
5 × 5 Gauss–Legendre rule, whose error there is below 1e-15 (the integrand is analytic on
the pixel; measured against a 30-point rule in extended precision).

Hockney's method (Hockney, Methods Comput. Phys. 9, 135 (1970)): the response to one
loaded pixel, sampled at separations :math:`-n+1 \dots n-1` along each axis and stored on
a grid of twice the size (separation ``s`` at index ``s mod 2n``), turns the linear
(free-space) convolution of a pressure given on the ``n`` sites of the patch into the
circular one of the pressure padded with zeros to ``2n``: exact on the patch, for any
value at the unused separation ``n``.
"""

from __future__ import annotations

import math

import numpy as np

from .._backend import rfft2

__all__ = ["FAR_FIELD", "free_compliance", "love_rectangle", "pixel_response"]

#: From this distance (in pixels) on, :func:`pixel_response` integrates by Gauss–Legendre
#: quadrature instead of the closed form (see the module docstring).
FAR_FIELD = 8.0

_GAUSS_POINTS = 5


def _antiderivative(u, v):
    """F(u, v) = u asinh(v/|u|) + v asinh(u/|v|), with its limits 0 on the axes."""
    au, av = np.abs(u), np.abs(v)
    with np.errstate(divide="ignore", invalid="ignore"):
        first = np.where(au > 0, u * np.arcsinh(v / np.where(au > 0, au, 1.0)), 0.0)
        second = np.where(av > 0, v * np.arcsinh(u / np.where(av > 0, av, 1.0)), 0.0)
    return first + second


def love_rectangle(x, y, half_width_x, half_width_y, contact_modulus=1.0):
    r"""Deflection of a half-space under unit pressure on a rectangle (Love 1929).

    Parameters
    ----------
    x, y : array_like
        Where the deflection is wanted, relative to the rectangle's centre (length).
    half_width_x, half_width_y : float
        Half-widths ``a``, ``b`` of the loaded rectangle (length), > 0.
    contact_modulus : float
        :math:`E^* = E/(1-\nu^2)` (pressure).

    Returns
    -------
    ndarray
        Deflection (length) per unit pressure, the closed form of the module docstring:
        :math:`w = \tfrac{1}{\pi E^*}[F(x+a,y+b) - F(x-a,y+b) - F(x+a,y-b) + F(x-a,y-b)]`.
        At the centre of a square of side ``c``: :math:`4 c \operatorname{asinh}(1)/(\pi E^*)
        \approx 1.122\,c/E^*` (Johnson 1985, §3.2). Exact to rounding near the rectangle;
        see the module docstring for its cancellation far from it.
    """
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    a, b = float(half_width_x), float(half_width_y)
    total = (
        _antiderivative(x + a, y + b)
        - _antiderivative(x - a, y + b)
        - _antiderivative(x + a, y - b)
        + _antiderivative(x - a, y - b)
    )
    return total / (math.pi * contact_modulus)


def _gauss_pixel(x, y):
    """The integral of 1/r over the unit pixel centred at -(x, y), by 5 x 5 Gauss-Legendre."""
    t, w = np.polynomial.legendre.leggauss(_GAUSS_POINTS)
    t, w = 0.5 * t, 0.5 * w
    acc = np.zeros(np.broadcast(x, y).shape)
    for ti, wi in zip(t, w, strict=True):
        dx2 = (x - ti) ** 2
        for tj, wj in zip(t, w, strict=True):
            acc += (wi * wj) / np.sqrt(dx2 + (y - tj) ** 2)
    return acc


def pixel_response(separations_x, separations_y, pixel_size=1.0, contact_modulus=1.0):
    r"""Deflection (length) at the given separations from one pixel under unit pressure.

    Parameters
    ----------
    separations_x, separations_y : 1D array_like of int
        Separations along x and y in pixels (any sign); the result is on their outer grid.
    pixel_size : float
        :math:`a_0` (length): the loaded pixel is the square of side :math:`a_0`.
    contact_modulus : float
        :math:`E^*` (pressure).

    Returns
    -------
    ndarray, shape (len(separations_x), len(separations_y))
        :func:`love_rectangle` of the pixel, ``a = b = a0/2``, at ``(s_x a0, s_y a0)``:
        :math:`\frac{1}{\pi E^*}\iint_{pixel} dx'\,dy'/r` (length per pressure; the closed
        form within :data:`FAR_FIELD` pixels, Gauss–Legendre beyond).
    """
    sx = np.abs(np.asarray(separations_x, dtype=float))
    sy = np.abs(np.asarray(separations_y, dtype=float))
    # the quadrature everywhere, the closed form near the pixel (the rule's middle node
    # meets r = 0 on the pixel itself: replaced there)
    with np.errstate(divide="ignore"):
        out = _gauss_pixel(sx[:, None], sy[None, :]) * (pixel_size / (math.pi * contact_modulus))
    block = np.ix_(np.flatnonzero(sx < FAR_FIELD), np.flatnonzero(sy < FAR_FIELD))
    bx, by = sx[block[0]], sy[block[1]]
    closed = love_rectangle(bx, by, 0.5, 0.5, contact_modulus) * pixel_size
    out[block] = np.where(np.hypot(bx, by) < FAR_FIELD, closed, out[block])
    return out


def free_compliance(shape, pixel_size=1.0, contact_modulus=1.0) -> np.ndarray:
    r"""Compliance multipliers of the free half-space on the zero-padded grid.

    Parameters
    ----------
    shape : (int, int)
        The patch ``(nx, ny)``; the work grid is ``(2 nx, 2 ny)``.
    pixel_size, contact_modulus : float
        :math:`a_0` (length) and :math:`E^*` (pressure).

    Returns
    -------
    ndarray, shape (2 nx, ny + 1)
        ``rfft2`` of :func:`pixel_response` stored at separation ``s mod 2n`` (length per
        pressure): ``irfft2(rfft2(embed(p)) * c)`` cropped to the patch is the free-space
        deflection of the pressure ``p`` on the patch (Hockney). Real (the response is
        even) and positive.
    """
    nx, ny = shape
    # the response is even in both separations: evaluate one quadrant, mirror it
    quadrant = pixel_response(np.arange(nx + 1), np.arange(ny + 1), pixel_size, contact_modulus)
    ix = np.minimum(np.arange(2 * nx), 2 * nx - np.arange(2 * nx))
    iy = np.minimum(np.arange(2 * ny), 2 * ny - np.arange(2 * ny))
    response = quadrant[np.ix_(ix, iy)]
    return rfft2(response).real
