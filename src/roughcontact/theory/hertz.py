"""Hertz contact of a rigid sphere (paraboloid) on an elastic half-space.

A paraboloid ``h = -r^2 / (2R)`` pressed with load ``N`` onto a half-space of contact
modulus ``E* = E / (1 - nu^2)`` (frictionless, non-adhesive) touches over a disc of
radius ``a`` with (K. L. Johnson, *Contact Mechanics*, Cambridge University Press,
1985, chapter 4, Eqs. 4.22-4.23)::

    a     = (3 N R / (4 E*))^(1/3)
    p(r)  = p0 sqrt(1 - r^2 / a^2)   (r < a),   0 otherwise
    p0    = 3 N / (2 pi a^2)         (= 3/2 times the mean pressure over the disc)
    delta = a^2 / R                  (indentation / rigid-body approach)
    N     = (4/3) E* R^(1/2) delta^(3/2)

Any consistent units; with the package's lattice units lengths are in a0 and
pressures in units of E* when ``contact_modulus = 1``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validate import positive

__all__ = ["HertzContact", "hertz", "hertz_load"]


@dataclass(frozen=True)
class HertzContact:
    """Hertz solution for one load (see :func:`hertz`).

    Attributes
    ----------
    load : float
        Normal load N [force].
    radius : float
        Sphere radius R [length].
    contact_modulus : float
        E* [pressure].
    contact_radius : float
        ``a = (3 N R / (4 E*))^(1/3)`` [length].
    central_pressure : float
        ``p0 = 3 N / (2 pi a^2)`` [pressure].
    indentation : float
        ``delta = a^2 / R`` [length].
    """

    load: float
    radius: float
    contact_modulus: float
    contact_radius: float
    central_pressure: float
    indentation: float

    @property
    def mean_pressure(self) -> float:
        """Mean pressure over the contact disc, ``N / (pi a^2) = 2 p0 / 3``."""
        return self.load / (math.pi * self.contact_radius**2)

    @property
    def contact_area(self) -> float:
        """Contact area ``pi a^2`` [length^2]."""
        return math.pi * self.contact_radius**2

    def pressure(self, r):
        """Hertz pressure ``p0 sqrt(1 - r^2/a^2)`` for ``|r| < a``, 0 outside.

        Parameters
        ----------
        r : float or array
            Distance from the axis [length].

        Returns
        -------
        float or ndarray
            Pressure [pressure], same shape as ``r``.
        """
        r = np.asarray(r, dtype=float)
        s = 1.0 - (r / self.contact_radius) ** 2
        p = self.central_pressure * np.sqrt(np.clip(s, 0.0, None))
        return p if p.ndim else float(p)


def hertz(*, load: float, radius: float, contact_modulus: float) -> HertzContact:
    """Hertz contact of a sphere of radius R under load N (Johnson 1985, ch. 4).

    Parameters
    ----------
    load : float
        Normal load N > 0 [force].
    radius : float
        Radius of curvature R > 0 [length].
    contact_modulus : float
        Contact modulus ``E* = E / (1 - nu^2)`` > 0 [pressure] (for two elastic bodies,
        ``1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2``).

    Returns
    -------
    HertzContact
        ``a = (3NR/(4E*))^(1/3)``, ``p0 = 3N/(2 pi a^2)``, ``delta = a^2/R``.
    """
    N = positive("load", load)
    R = positive("radius", radius)
    E = positive("contact_modulus", contact_modulus)
    a = (3 * N * R / (4 * E)) ** (1 / 3)
    return HertzContact(
        load=N,
        radius=R,
        contact_modulus=E,
        contact_radius=a,
        central_pressure=3 * N / (2 * math.pi * a**2),
        indentation=a**2 / R,
    )


def hertz_load(indentation, radius: float, contact_modulus: float):
    """Hertz load for a given indentation, ``N = (4/3) E* R^(1/2) delta^(3/2)``.

    Parameters
    ----------
    indentation : float or array
        Rigid-body approach delta [length]; ``delta <= 0`` (no contact) gives 0.
    radius : float
        Radius of curvature R > 0 [length].
    contact_modulus : float
        E* > 0 [pressure].

    Returns
    -------
    float or ndarray
        Load N [force].

    References
    ----------
    K. L. Johnson, Contact Mechanics (1985), chapter 4, Eq. 4.23.
    """
    R = positive("radius", radius)
    E = positive("contact_modulus", contact_modulus)
    d = np.clip(np.asarray(indentation, dtype=float), 0.0, None)
    N = 4.0 / 3.0 * E * math.sqrt(R) * d**1.5
    return N if N.ndim else float(N)
