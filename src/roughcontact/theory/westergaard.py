"""Westergaard's solution: a one-dimensional sinusoid on an elastic half-space.

A rigid wavy surface ``h(x) = Delta cos(2 pi x / lambda)`` (crests at ``x = 0, lambda,
...``; larger ``h`` is closer to the substrate) is pressed with mean pressure
``pbar`` onto a frictionless, non-adhesive elastic half-space of contact modulus E*
(plane strain). With ``p* = pi E* Delta / lambda``, the pressure needed for full
contact (H. M. Westergaard, J. Appl. Mech. 6, A49 (1939); K. L. Johnson, *Contact
Mechanics*, 1985, section 13.2)::

    pbar >= p*:  p(x) = pbar + p* cos(2 pi x / lambda)                  (full contact)
    pbar <  p*:  sin^2(pi a / lambda) = pbar / p*                       (half-width a)
                 p(x) = 2 pbar cos(pi x/lambda) / sin^2(pi a/lambda)
                        * sqrt(sin^2(pi a/lambda) - sin^2(pi x/lambda))   for |x| < a
                 p(x) = 0                                                a <= |x| <= lambda/2

with ``x`` measured from the nearest crest (the solution is periodic in ``x``). Both
branches agree at ``pbar = p*`` (``a = lambda/2``), and for ``pbar << p*`` each contact
reduces to 2D (cylinder) Hertz with ``R = lambda^2 / (4 pi^2 Delta)``.
"""

from __future__ import annotations

import math

import numpy as np

from .._validate import nonnegative, positive

__all__ = [
    "westergaard_contact_fraction",
    "westergaard_contact_half_width",
    "westergaard_full_contact_pressure",
    "westergaard_pressure",
]


def westergaard_full_contact_pressure(amplitude, wavelength, contact_modulus) -> float:
    """Mean pressure for full contact, ``p* = pi E* Delta / lambda`` [pressure] (Johnson
    1985, 13.2).

    Parameters as in :func:`westergaard_pressure`.
    """
    D = positive("amplitude", amplitude)
    lam = positive("wavelength", wavelength)
    E = positive("contact_modulus", contact_modulus)
    return math.pi * E * D / lam


def westergaard_contact_half_width(mean_pressure, amplitude, wavelength, contact_modulus) -> float:
    """Contact half-width ``a`` from ``sin^2(pi a / lambda) = pbar / p*`` [length].

    Returns ``lambda / 2`` (full contact) for ``pbar >= p*`` and 0 for ``pbar = 0``.
    Parameters as in :func:`westergaard_pressure`.
    """
    lam = positive("wavelength", wavelength)
    p_star = westergaard_full_contact_pressure(amplitude, lam, contact_modulus)
    pbar = nonnegative("mean_pressure", mean_pressure)
    if pbar >= p_star:
        return lam / 2
    return lam / math.pi * math.asin(math.sqrt(pbar / p_star))


def westergaard_contact_fraction(mean_pressure, amplitude, wavelength, contact_modulus) -> float:
    """Fraction of the surface in contact, ``2a / lambda`` (1 for ``pbar >= p*``).

    Parameters as in :func:`westergaard_pressure`.
    """
    lam = positive("wavelength", wavelength)
    a = westergaard_contact_half_width(mean_pressure, amplitude, lam, contact_modulus)
    return 2 * a / lam


def westergaard_pressure(x, mean_pressure, amplitude, wavelength, contact_modulus):
    """Contact pressure p(x) of Westergaard's problem (see the module docstring).

    Parameters
    ----------
    x : float or array
        Position [length]; crests of ``h = Delta cos(2 pi x/lambda)`` are at multiples
        of ``lambda`` (any real x, the solution is periodic).
    mean_pressure : float
        pbar >= 0 [pressure], the load per unit area.
    amplitude : float
        Delta > 0 [length].
    wavelength : float
        lambda > 0 [length].
    contact_modulus : float
        E* > 0 [pressure].

    Returns
    -------
    float or ndarray
        Pressure p(x) >= 0 [pressure], same shape as ``x``.

    References
    ----------
    H. M. Westergaard, J. Appl. Mech. 6, A49 (1939); K. L. Johnson, Contact Mechanics
    (1985), section 13.2.
    """
    lam = positive("wavelength", wavelength)
    p_star = westergaard_full_contact_pressure(amplitude, lam, contact_modulus)
    pbar = nonnegative("mean_pressure", mean_pressure)
    x = np.asarray(x, dtype=float)
    if pbar >= p_star:
        p = pbar + p_star * np.cos(2 * np.pi * x / lam)
    elif pbar == 0:
        p = np.zeros_like(x)
    else:
        s2 = pbar / p_star  # sin^2(pi a / lambda)
        xr = x - lam * np.round(x / lam)  # nearest crest: xr in [-lambda/2, lambda/2]
        c = np.cos(np.pi * xr / lam)
        root = np.sqrt(np.clip(s2 - np.sin(np.pi * xr / lam) ** 2, 0.0, None))
        p = 2 * pbar * c / s2 * root
    return p if p.ndim else float(p)
