r"""Johnson's adhesive sinusoid: a 1D wavy surface in JKR-type adhesive contact.

The geometry of :mod:`.westergaard`: a rigid surface ``h(x) = Delta cos(2 pi x/lambda)``
(crests at ``x = 0, lambda, ...``, larger ``h`` closer to the substrate) on an elastic
half-space of contact modulus E* (plane strain), now with work of adhesion ``w`` acting
JKR-like (zero range) at the edges of the contact strips ``|x| < a`` (K. L. Johnson,
Int. J. Solids Struct. 32, 423 (1995)).

**Solution.** The pressure is Westergaard's non-adhesive distribution for the strip
half-width ``a`` plus the tensile "periodic flat punch" distribution (Koiter's row of
cracks), ``-P cos(pi x/lambda) / sqrt(sin^2(pi a/lambda) - sin^2(pi x/lambda))`` of
mean ``-P``, whose stress intensity factor at ``x = a`` is ``K_I = P sqrt(lambda
cot(pi a/lambda))``. Griffith's condition ``K_I^2 / (2 E*) = w`` fixes ``P``; with
``psi = pi a / lambda``, the Westergaard full-contact pressure ``p* = pi E* Delta /
lambda`` and Johnson's adhesion parameter

.. math:: \alpha = \sqrt{\frac{2 \lambda w}{\pi^2 E^* \Delta^2}}
          \qquad (\alpha^2 = \frac{2}{\pi} \frac{w}{p^* \Delta}),

the mean pressure (positive compressive) is::

    pbar / p* = sin^2(psi) - alpha sqrt(tan(psi))                                  (1)

and the mean gap (of the hard-contact problem: zero gap in the strips) is::

    gbar / Delta = cos^2(psi) + 2 (pbar/p*) ln(sin(psi))                           (2)

(2) follows from the periodic line-load Green's function (the crest's deflection
relative to the mean deflection; G. Carbone & L. Mangialardi, J. Mech. Phys. Solids 52,
1267 (2004)); for alpha = 0 both reduce to Westergaard's solution
(``sin^2 psi = pbar/p*``, see :mod:`.westergaard`).

**Stability and thresholds.** Under load control a state is stable where
``d pbar / d psi > 0``, i.e. where ``4 sin^(3/2)(psi) cos^(5/2)(psi) > alpha``. For
``alpha < alpha_max = 3^(3/4) 5^(5/4) / 16 = 1.0652`` that holds between a minimum
``psi_min`` and a maximum ``psi_max`` of (1):

* *pull-off*: a partial contact on the stable branch separates at the minimum,
  ``pbar_c = p* min(1) < 0``; for small alpha, ``pbar_c / p* = -3 (alpha/4)^(4/3)``,
  the 2D JKR (cylinder) pull-off ``3 (pi w^2 R E* / 16)^(1/3)`` per crest with
  ``R = lambda^2/(4 pi^2 Delta)``;
* *jump to full contact*: above the maximum ``pbar_j = p* max(1)`` no partial contact
  exists and the surfaces snap into full contact; for alpha = 0, ``pbar_j = p*``;
* *spontaneous full contact*: ``pbar_j <= 0`` (full contact at zero, or even tensile,
  load) exactly when ``max_psi sin^2(psi) / sqrt(tan(psi)) = 3^(3/4)/4 <= alpha``,
  i.e. ``alpha >= 3^(3/4)/4 = 0.5699`` (the maximum is at ``psi = pi/3``).

Once in full contact the JKR model needs an infinite tension to separate the surfaces
(no flaw to start a crack); a finite-range interaction gives a finite, law-dependent
value that this theory does not describe.

**Displacement control.** In roughcontact the mean gap of a contact on a half-space is
the offset ``d`` (minus the mean height, here 0), because the uniform mode carries no
deflection (with a law whose equilibrium gap is ``a0``, ``d - a0`` plays the role of (2)). So a
displacement-controlled path follows (1)-(2) parametrically in ``psi``; it is stable
where ``d gbar / d psi < 0``. At the pull-off point ``d gbar / d psi < 0`` for every
``0 < alpha < alpha_max`` (checked numerically on a dense grid), so the largest tension
on a quasi-static displacement-controlled retraction from a partial contact is the same
``|pbar_c|`` (as for the JKR sphere); the contact then jumps out at the maximum of (2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validate import ParameterError, nonnegative, positive
from .westergaard import westergaard_full_contact_pressure

__all__ = [
    "JOHNSON_ALPHA_MAX",
    "JOHNSON_FULL_CONTACT_ALPHA",
    "JohnsonSinusoidThresholds",
    "johnson_parameter",
    "johnson_sinusoid_mean_gap",
    "johnson_sinusoid_mean_pressure",
    "johnson_sinusoid_pressure",
    "johnson_sinusoid_pull_off_pressure",
    "johnson_sinusoid_spontaneous_full_contact",
    "johnson_sinusoid_thresholds",
]

#: alpha above which full contact is reached at zero load, ``3^(3/4)/4 = 0.5699``.
JOHNSON_FULL_CONTACT_ALPHA = 3.0**0.75 / 4.0
#: alpha above which no stable partial contact exists, ``3^(3/4) 5^(5/4)/16 = 1.0652``.
JOHNSON_ALPHA_MAX = 3.0**0.75 * 5.0**1.25 / 16.0
_PSI_STAR = math.atan(math.sqrt(0.6))  # where 4 sin^(3/2) cos^(5/2) is largest


def johnson_parameter(*, amplitude, wavelength, contact_modulus, work_of_adhesion) -> float:
    """Johnson's adhesion parameter ``alpha = sqrt(2 lambda w / (pi^2 E* Delta^2))``.

    Parameters
    ----------
    amplitude : float
        Delta > 0 [length] (``h = Delta cos(2 pi x/lambda)``, peak-to-valley 2 Delta).
    wavelength : float
        lambda > 0 [length].
    contact_modulus : float
        E* > 0 [pressure].
    work_of_adhesion : float
        w > 0 [pressure × length].

    Returns
    -------
    float
        alpha (dimensionless); ``alpha^2 = (2/pi) w / (p* Delta)``.

    References
    ----------
    K. L. Johnson, Int. J. Solids Struct. 32, 423 (1995).
    """
    D = positive("amplitude", amplitude)
    lam = positive("wavelength", wavelength)
    E = positive("contact_modulus", contact_modulus)
    w = positive("work_of_adhesion", work_of_adhesion)
    return math.sqrt(2.0 * lam * w / (math.pi**2 * E * D * D))


def _contact_half_width(name, value, lam):
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a number or array, got {value!r}") from None
    if not np.all(np.isfinite(a)) or np.any(a <= 0) or np.any(a >= lam / 2):
        raise ParameterError(
            f"{name} must be in (0, wavelength/2) = (0, {lam / 2:g}) (partial contact), "
            f"got {value!r}"
        )
    return a


def _pbar(psi, alpha):
    return np.sin(psi) ** 2 - alpha * np.sqrt(np.tan(psi))


def johnson_sinusoid_mean_pressure(
    contact_half_width, amplitude, wavelength, contact_modulus, work_of_adhesion
):
    """Mean pressure of a partial adhesive contact, Eq. (1) of the module docstring.

    Parameters
    ----------
    contact_half_width : float or array
        a in (0, lambda/2) [length]: each contact strip is ``|x - n lambda| < a``.
    amplitude, wavelength, contact_modulus : float
        Delta, lambda [length], E* [pressure], all > 0.
    work_of_adhesion : float
        w >= 0 [pressure × length]; 0 gives Westergaard's ``p* sin^2(pi a/lambda)``.

    Returns
    -------
    float or ndarray
        pbar [pressure], positive compressive (negative: the contact holds under tension).
    """
    lam = positive("wavelength", wavelength)
    p_star = westergaard_full_contact_pressure(amplitude, lam, contact_modulus)
    w = nonnegative("work_of_adhesion", work_of_adhesion)
    alpha = (
        0.0
        if w == 0
        else johnson_parameter(
            amplitude=amplitude,
            wavelength=lam,
            contact_modulus=contact_modulus,
            work_of_adhesion=w,
        )
    )
    a = _contact_half_width("contact_half_width", contact_half_width, lam)
    p = p_star * _pbar(np.pi * a / lam, alpha)
    return p if p.ndim else float(p)


def johnson_sinusoid_mean_gap(
    contact_half_width, amplitude, wavelength, contact_modulus, work_of_adhesion
):
    """Mean gap of a partial adhesive contact, Eq. (2) of the module docstring [length].

    ``gbar = Delta [cos^2(psi) + 2 (pbar/p*) ln sin(psi)]`` with ``psi = pi a/lambda``:
    the mean of ``d - h + w`` when the gap is zero in the strips and the mean deflection is
    zero (a half-space, whose uniform mode carries no deflection: roughcontact's offset
    ``d`` of a hard-wall contact). Parameters as in :func:`johnson_sinusoid_mean_pressure`.
    """
    lam = positive("wavelength", wavelength)
    D = positive("amplitude", amplitude)
    p_star = westergaard_full_contact_pressure(D, lam, contact_modulus)
    pbar = np.asarray(
        johnson_sinusoid_mean_pressure(
            contact_half_width, D, lam, contact_modulus, work_of_adhesion
        )
    )
    psi = np.pi * np.asarray(contact_half_width, dtype=float) / lam
    g = D * (np.cos(psi) ** 2 + 2.0 * pbar / p_star * np.log(np.sin(psi)))
    return g if g.ndim else float(g)


def johnson_sinusoid_pressure(
    x, contact_half_width, amplitude, wavelength, contact_modulus, work_of_adhesion
):
    """Contact pressure p(x) of a partial adhesive contact of half-width a.

    ``p = 2 p* cos(pi x/lambda) sqrt(s^2 - sin^2(pi x/lambda))
    - P cos(pi x/lambda) / sqrt(s^2 - sin^2(pi x/lambda))`` for ``|x| < a`` (x measured
    from the nearest crest, ``s = sin(pi a/lambda)``), 0 outside: Westergaard's pressure
    for the half-width a plus the tensile periodic flat punch of mean ``-P``, with
    ``P = sqrt(2 E* w tan(pi a/lambda) / lambda)`` (Johnson 1995). Near the edges
    ``p ~ -K_I / sqrt(2 pi (a - |x|))`` with ``K_I = sqrt(2 E* w)``.

    Parameters
    ----------
    x : float or array
        Position [length] (any real x; the solution is periodic).
    contact_half_width, amplitude, wavelength, contact_modulus, work_of_adhesion
        As in :func:`johnson_sinusoid_mean_pressure` (a scalar half-width).

    Returns
    -------
    float or ndarray
        p(x) [pressure], positive compressive; ``-inf``-like (large tensile) values
        close to the edges, which are integrable.
    """
    lam = positive("wavelength", wavelength)
    p_star = westergaard_full_contact_pressure(amplitude, lam, contact_modulus)
    E = positive("contact_modulus", contact_modulus)
    w = nonnegative("work_of_adhesion", work_of_adhesion)
    a = float(_contact_half_width("contact_half_width", contact_half_width, lam))
    x = np.asarray(x, dtype=float)
    s2 = math.sin(math.pi * a / lam) ** 2
    P = math.sqrt(2.0 * E * w * math.tan(math.pi * a / lam) / lam)
    xr = x - lam * np.round(x / lam)
    c = np.cos(np.pi * xr / lam)
    inside = np.abs(xr) < a
    root = np.sqrt(np.where(inside, s2 - np.sin(np.pi * xr / lam) ** 2, 1.0))
    p = np.where(inside, 2.0 * p_star * c * root - P * c / root, 0.0)
    return p if p.ndim else float(p)


@dataclass(frozen=True)
class JohnsonSinusoidThresholds:
    """Load-control thresholds of Johnson's adhesive sinusoid, in units of ``p*``.

    Attributes
    ----------
    alpha : float
        Johnson's parameter.
    pull_off : float
        ``-min pbar/p*`` >= 0 over the stable branch: the tension (magnitude) at which a
        partial contact separates.
    pull_off_contact_fraction : float
        ``2a/lambda`` at pull-off.
    jump_in : float
        ``max pbar/p*`` over the stable branch: above it the surfaces jump into full
        contact (<= 0 for ``alpha >= 0.5699``: full contact at zero load).
    jump_in_contact_fraction : float
        ``2a/lambda`` at the jump to full contact.
    """

    alpha: float
    pull_off: float
    pull_off_contact_fraction: float
    jump_in: float
    jump_in_contact_fraction: float

    @property
    def spontaneous_full_contact(self) -> bool:
        """True when full contact is reached without a compressive load (jump_in <= 0)."""
        return self.jump_in <= 0.0


def johnson_sinusoid_thresholds(alpha) -> JohnsonSinusoidThresholds:
    """Pull-off and jump-to-full-contact pressures of Johnson's sinusoid (units of p*).

    The extrema of ``pbar/p* = sin^2 psi - alpha sqrt(tan psi)`` are the roots of
    ``4 sin^(3/2)(psi) cos^(5/2)(psi) = alpha``, one on each side of
    ``psi* = atan(sqrt(3/5))`` (found with :func:`scipy.optimize.brentq`).

    Parameters
    ----------
    alpha : float
        Johnson's parameter, ``0 <= alpha < 1.0652`` (above, no partial contact is stable:
        the surfaces always snap into full contact).

    Returns
    -------
    JohnsonSinusoidThresholds
        ``alpha = 0``: pull-off 0, jump-in 1 (Westergaard).
    """
    from scipy.optimize import brentq  # scipy on first use: import roughcontact stays light

    al = nonnegative("alpha", alpha)
    if al >= JOHNSON_ALPHA_MAX:
        raise ParameterError(
            f"alpha must be in [0, {JOHNSON_ALPHA_MAX:.6f}) for a stable partial contact to "
            f"exist (above, the surfaces always snap into full contact), got {alpha!r}"
        )
    if al == 0.0:
        return JohnsonSinusoidThresholds(0.0, 0.0, 0.0, 1.0, 1.0)

    def slope(psi):  # proportional to d pbar / d psi
        return 4.0 * math.sin(psi) ** 1.5 * math.cos(psi) ** 2.5 - al

    kw = {"xtol": 1e-15, "rtol": 1e-15, "maxiter": 400}
    psi_min = brentq(slope, 0.0, _PSI_STAR, **kw)
    psi_max = brentq(slope, _PSI_STAR, math.pi / 2, **kw)
    return JohnsonSinusoidThresholds(
        alpha=al,
        pull_off=-float(_pbar(psi_min, al)),
        pull_off_contact_fraction=2.0 * psi_min / math.pi,
        jump_in=float(_pbar(psi_max, al)),
        jump_in_contact_fraction=2.0 * psi_max / math.pi,
    )


def johnson_sinusoid_pull_off_pressure(
    *, amplitude, wavelength, contact_modulus, work_of_adhesion
) -> float:
    """Pull-off pressure magnitude ``|pbar_c|`` of a partial adhesive contact [pressure].

    Parameters as in :func:`johnson_parameter`; needs ``alpha < 1.0652`` (see
    :func:`johnson_sinusoid_thresholds`).
    """
    alpha = johnson_parameter(
        amplitude=amplitude,
        wavelength=wavelength,
        contact_modulus=contact_modulus,
        work_of_adhesion=work_of_adhesion,
    )
    p_star = westergaard_full_contact_pressure(amplitude, wavelength, contact_modulus)
    return johnson_sinusoid_thresholds(alpha).pull_off * p_star


def johnson_sinusoid_spontaneous_full_contact(alpha) -> bool:
    """True if the surfaces jump into full contact at zero load: ``alpha >= 3^(3/4)/4``."""
    return nonnegative("alpha", alpha) >= JOHNSON_FULL_CONTACT_ALPHA
