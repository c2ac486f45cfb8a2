r"""JKR and DMT theories: an adhesive rigid sphere on an elastic half-space.

A paraboloid of radius ``R`` (the small-slope sphere of :mod:`.hertz`) touches a
half-space of contact modulus ``E* = E / (1 - nu^2)``; the surfaces adhere with work of
adhesion ``w`` (energy per area, i.e. pressure × length). Loads ``N`` are positive when
they push the bodies together (the README's conventions), so adhesion shows up as negative (tensile)
loads; *pull-off forces* are reported as positive magnitudes. ``a`` is the contact
radius and ``delta`` the rigid-body approach (indentation), positive into the substrate.

**JKR** (K. L. Johnson, K. Kendall, A. D. Roberts, Proc. R. Soc. Lond. A 324, 301
(1971); K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985,
section 5.5) -- short-range adhesion, a crack-like stress singularity at ``r = a`` with
energy release rate ``G = K_I^2 / (2 E*) = w``::

    N(a)     = 4 E* a^3 / (3 R) - sqrt(8 pi w E* a^3)
    delta(a) = a^2 / R - sqrt(2 pi w a / E*)
    a^3(N)   = (3 R / (4 E*)) [N + 3 pi w R + sqrt(6 pi w R N + (3 pi w R)^2)]

* zero load:            ``a0^3 = 9 pi w R^2 / (2 E*)``
* load control:         pull-off ``N_c = -(3/2) pi w R`` at ``a_c^3 = 9 pi w R^2 / (8 E*)``
  (where ``dN/da = 0``), ``delta_c = -(1/4) (3 pi^2 w^2 R / E*^2)^(1/3)``
* displacement control: jump-out where ``d delta / d a = 0``, at
  ``a_d^3 = pi w R^2 / (8 E*) = a_c^3 / 9`` and ``N_d = -(5/6) pi w R`` (5/9 of the
  load-control pull-off), ``delta_d = -(3/4) (pi^2 w^2 R / E*^2)^(1/3)``.

Under displacement control the path ``N(delta)`` passes *through* the load-control
minimum ``-(3/2) pi w R`` on its stable branch (``a_c > a_d``: ``d delta/da > 0`` at
``a_c``) before jumping out at ``-(5/6) pi w R``; the largest tensile force measured
along a displacement-controlled retraction is therefore ``(3/2) pi w R`` too (D. Maugis,
*Contact, Adhesion and Rupture of Elastic Solids*, Springer, 2000, ch. 5; K. L. Johnson,
Proc. R. Soc. Lond. A 453, 163 (1997)).

**DMT** (B. V. Derjaguin, V. M. Muller, Yu. P. Toporov, J. Colloid Interface Sci. 53,
314 (1975); in the form of Maugis 2000, ch. 5) -- long-range adhesion that does not
deform the surfaces: the Hertz profile carries an extra load ``2 pi w R``::

    N(a) = 4 E* a^3 / (3 R) - 2 pi w R,   delta = a^2 / R,   pull-off 2 pi w R (at a = 0)

(the Bradley/Derjaguin force of a rigid sphere, the same under load and displacement
control). Any consistent units; in lattice units lengths are in a0 and pressures in E*.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validate import ParameterError, positive
from .._validate import finite as _finite
from .._validate import nonnegative_array as _nonnegative_array

__all__ = [
    "JKRContact",
    "dmt_contact_radius",
    "dmt_load",
    "dmt_pull_off_force",
    "jkr",
    "jkr_contact_radius",
    "jkr_indentation",
    "jkr_load",
    "jkr_pull_off",
    "jkr_pull_off_force",
    "jkr_zero_load_contact_radius",
]


def _out(x):
    return x if np.ndim(x) else float(x)


def _check(radius, contact_modulus, work_of_adhesion):
    return (
        positive("radius", radius),
        positive("contact_modulus", contact_modulus),
        positive("work_of_adhesion", work_of_adhesion),
    )


@dataclass(frozen=True)
class JKRContact:
    """One JKR equilibrium state (see :func:`jkr`).

    Attributes
    ----------
    contact_radius : float
        a [length].
    load : float
        ``N = 4 E* a^3/(3R) - sqrt(8 pi w E* a^3)`` [force]; < 0 is tensile.
    indentation : float
        ``delta = a^2/R - sqrt(2 pi w a / E*)`` [length].
    radius : float
        Sphere radius R [length].
    contact_modulus : float
        E* [pressure].
    work_of_adhesion : float
        w [pressure × length].
    """

    contact_radius: float
    load: float
    indentation: float
    radius: float
    contact_modulus: float
    work_of_adhesion: float

    @property
    def contact_area(self) -> float:
        """``pi a^2`` [length^2]."""
        return math.pi * self.contact_radius**2

    @property
    def stress_intensity_factor(self) -> float:
        """Mode-I stress intensity factor at the contact edge, ``sqrt(2 E* w)`` [pressure ×
        length^(1/2)] (Griffith: ``G = K^2/(2E*) = w``); the same for every state."""
        return math.sqrt(2.0 * self.contact_modulus * self.work_of_adhesion)


def jkr_load(contact_radius, radius, contact_modulus, work_of_adhesion):
    """JKR load at contact radius a, ``N = 4 E* a^3/(3R) - sqrt(8 pi w E* a^3)``.

    Parameters
    ----------
    contact_radius : float or array
        a >= 0 [length].
    radius : float
        Sphere radius R > 0 [length].
    contact_modulus : float
        E* > 0 [pressure].
    work_of_adhesion : float
        w > 0 [pressure × length].

    Returns
    -------
    float or ndarray
        N [force] (> 0 pushes the bodies together).

    References
    ----------
    Johnson, Kendall & Roberts, Proc. R. Soc. Lond. A 324, 301 (1971); Johnson,
    Contact Mechanics (1985), section 5.5.
    """
    R, E, w = _check(radius, contact_modulus, work_of_adhesion)
    a = _nonnegative_array("contact_radius", contact_radius)
    return _out(4.0 * E * a**3 / (3.0 * R) - np.sqrt(8.0 * math.pi * w * E * a**3))


def jkr_indentation(contact_radius, radius, contact_modulus, work_of_adhesion):
    """JKR indentation at contact radius a, ``delta = a^2/R - sqrt(2 pi w a/E*)`` [length].

    Parameters as in :func:`jkr_load`. ``delta < 0`` means the sphere's apex is above
    the undeformed surface (the substrate is pulled up into a neck).
    """
    R, E, w = _check(radius, contact_modulus, work_of_adhesion)
    a = _nonnegative_array("contact_radius", contact_radius)
    return _out(a**2 / R - np.sqrt(2.0 * math.pi * w * a / E))


def jkr(*, contact_radius, radius, contact_modulus, work_of_adhesion) -> JKRContact:
    """The JKR state with contact radius a (Johnson, Kendall & Roberts 1971).

    Parameters
    ----------
    contact_radius : float
        a > 0 [length].
    radius, contact_modulus, work_of_adhesion : float
        R [length], E* [pressure], w [pressure × length], all > 0.

    Returns
    -------
    JKRContact
    """
    a = positive("contact_radius", contact_radius)
    R, E, w = _check(radius, contact_modulus, work_of_adhesion)
    return JKRContact(
        contact_radius=a,
        load=jkr_load(a, R, E, w),
        indentation=jkr_indentation(a, R, E, w),
        radius=R,
        contact_modulus=E,
        work_of_adhesion=w,
    )


def jkr_contact_radius(load, radius, contact_modulus, work_of_adhesion) -> float:
    """Contact radius of the stable (load-controlled) JKR branch at load N [length].

    ``a^3 = (3R/(4E*)) [N + 3 pi w R + sqrt(6 pi w R N + (3 pi w R)^2)]`` (Johnson,
    Kendall & Roberts 1971; Johnson 1985, section 5.5, who write ``K = 4E*/3``).

    Parameters
    ----------
    load : float
        N >= -(3/2) pi w R [force] (below that there is no equilibrium: pull-off).
    radius, contact_modulus, work_of_adhesion : float
        R, E*, w > 0.
    """
    R, E, w = _check(radius, contact_modulus, work_of_adhesion)
    N = _finite("load", load)
    s = 3.0 * math.pi * w * R
    disc = 6.0 * math.pi * w * R * N + s * s
    if disc < -1e-12 * s * s:
        raise ParameterError(
            f"load must be >= -(3/2) pi w R = {-0.5 * s:.6g} (the JKR pull-off force), got {N!r}"
        )
    return (3.0 * R / (4.0 * E) * (N + s + math.sqrt(max(disc, 0.0)))) ** (1.0 / 3.0)


def jkr_zero_load_contact_radius(radius, contact_modulus, work_of_adhesion) -> float:
    """Contact radius at zero load, ``a0 = (9 pi w R^2 / (2 E*))^(1/3)`` [length]."""
    R, E, w = _check(radius, contact_modulus, work_of_adhesion)
    return (4.5 * math.pi * w * R * R / E) ** (1.0 / 3.0)


def jkr_pull_off(radius, contact_modulus, work_of_adhesion, *, control="load") -> JKRContact:
    """The JKR state at which the contact separates.

    Parameters
    ----------
    radius, contact_modulus, work_of_adhesion : float
        R, E*, w > 0.
    control : {"load", "displacement"}
        ``"load"``: the minimum of N(a), ``a_c^3 = 9 pi w R^2/(8 E*)``, ``N = -(3/2) pi w R``.
        ``"displacement"``: the minimum of delta(a) (rigid grips),
        ``a_d^3 = pi w R^2/(8 E*)``, ``N = -(5/6) pi w R``.

    Returns
    -------
    JKRContact
        ``load`` is the (negative) force at the instability.
    """
    R, E, w = _check(radius, contact_modulus, work_of_adhesion)
    if control == "load":
        a = (9.0 * math.pi * w * R * R / (8.0 * E)) ** (1.0 / 3.0)
    elif control == "displacement":
        a = (math.pi * w * R * R / (8.0 * E)) ** (1.0 / 3.0)
    else:
        raise ParameterError(f"control must be 'load' or 'displacement', got {control!r}")
    return jkr(contact_radius=a, radius=R, contact_modulus=E, work_of_adhesion=w)


def jkr_pull_off_force(radius, work_of_adhesion, *, control="load") -> float:
    """JKR pull-off force magnitude: ``(3/2) pi w R`` (load control) or ``(5/6) pi w R``
    (displacement control, the jump-out point) [force]; independent of E*.

    Under displacement control the *largest* tensile force along the path is still
    ``(3/2) pi w R`` (see the module docstring); ``(5/6) pi w R`` is the force at which
    the contact jumps out.
    """
    R = positive("radius", radius)
    w = positive("work_of_adhesion", work_of_adhesion)
    if control == "load":
        return 1.5 * math.pi * w * R
    if control == "displacement":
        return 5.0 / 6.0 * math.pi * w * R
    raise ParameterError(f"control must be 'load' or 'displacement', got {control!r}")


def dmt_load(contact_radius, radius, contact_modulus, work_of_adhesion):
    """DMT load at contact radius a, ``N = 4 E* a^3/(3R) - 2 pi w R`` [force].

    The contact profile is Hertz's (``delta = a^2/R``, see :func:`~.hertz.hertz`);
    parameters as in :func:`jkr_load`.

    References
    ----------
    Derjaguin, Muller & Toporov, J. Colloid Interface Sci. 53, 314 (1975); Maugis,
    Contact, Adhesion and Rupture of Elastic Solids (2000), ch. 5.
    """
    R, E, w = _check(radius, contact_modulus, work_of_adhesion)
    a = _nonnegative_array("contact_radius", contact_radius)
    return _out(4.0 * E * a**3 / (3.0 * R) - 2.0 * math.pi * w * R)


def dmt_contact_radius(load, radius, contact_modulus, work_of_adhesion) -> float:
    """DMT contact radius ``a = (3R (N + 2 pi w R) / (4 E*))^(1/3)`` [length].

    Parameters
    ----------
    load : float
        N >= -2 pi w R [force].
    radius, contact_modulus, work_of_adhesion : float
        R, E*, w > 0.
    """
    R, E, w = _check(radius, contact_modulus, work_of_adhesion)
    N = _finite("load", load)
    n_eff = N + 2.0 * math.pi * w * R
    if n_eff < 0:
        raise ParameterError(
            f"load must be >= -2 pi w R = {-2.0 * math.pi * w * R:.6g} (the DMT pull-off "
            f"force), got {N!r}"
        )
    return (3.0 * R * n_eff / (4.0 * E)) ** (1.0 / 3.0)


def dmt_pull_off_force(radius, work_of_adhesion) -> float:
    """DMT (Bradley) pull-off force ``2 pi w R`` [force], independent of E* and of the
    control mode."""
    R = positive("radius", radius)
    w = positive("work_of_adhesion", work_of_adhesion)
    return 2.0 * math.pi * w * R
