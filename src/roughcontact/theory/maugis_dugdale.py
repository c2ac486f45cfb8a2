r"""Maugis–Dugdale theory: the JKR–DMT transition for an adhesive sphere.

A rigid paraboloid of radius ``R`` on an elastic half-space of contact modulus
``E* = E/(1 - nu^2)``. The adhesive traction is a Dugdale cohesive zone: a constant
tension ``sigma0`` acts on the annulus ``a < r < c`` outside the contact disc of radius
``a``, up to the radius ``c`` where the gap reaches ``h0 = w / sigma0`` (so that the
work of separation is ``sigma0 h0 = w``, the work of adhesion). D. Maugis, J. Colloid
Interface Sci. 150, 243 (1992); D. Maugis, *Contact, Adhesion and Rupture of Elastic
Solids*, Springer (2000), ch. 5; K. L. Johnson & J. A. Greenwood, J. Colloid Interface
Sci. 192, 326 (1997).

**Moduli.** Maugis writes the JKR/Hertz equations with ``K = (4/3) E*``, where ``E*``
is the contact modulus used everywhere in roughcontact (``1/E* = (1-nu1^2)/E1 +
(1-nu2^2)/E2``); i.e. ``K = (4/3) E/(1-nu^2)`` for a rigid sphere on an elastic body.
With that ``K``, the non-dimensional variables are::

    A      = a / (pi w R^2 / K)^(1/3)          = a (4 E* / (3 pi w R^2))^(1/3)
    N_hat  = N / (pi w R)                      (N > 0 pushes the bodies together)
    D_hat  = delta / (pi^2 w^2 R / K^2)^(1/3)  (rigid-body approach)
    m      = c / a  >= 1
    lambda = 2 sigma0 (R / (pi w K^2))^(1/3)   = sigma0 (9 R / (2 pi w E*^2))^(1/3)

(``lambda`` is *Maugis' parameter*; written with ``E*`` in place of ``K`` it would be
``(4/3)^(2/3) = 1.21`` times larger.) The equilibrium equations are, with
``mu = sqrt(m^2 - 1)``::

    (lambda A^2 / 2) [mu + (m^2 - 2) atan mu] + (4 lambda^2 A / 3) [mu atan mu - m + 1] = 1
    N_hat = A^3 - lambda A^2 [mu + m^2 atan mu]
    D_hat = A^2 - (4/3) lambda A mu

The first (the Griffith condition ``G = w`` evaluated with the Dugdale zone) fixes
``m`` for given ``A``: its left side grows monotonically in ``m`` from 0 at ``m = 1``,
so the root is unique and is found by :func:`scipy.optimize.brentq`.

**Limits.** ``lambda -> infinity``: ``m -> 1`` and the equations reduce to JKR
(``N_hat = A^3 - A^(3/2) sqrt(6)``, pull-off ``N_hat = -3/2``). ``lambda -> 0``:
``m -> infinity`` and they reduce to DMT (``N_hat = A^3 - 2``, pull-off ``-2``).

**Pull-off.** Under load control the contact separates at the minimum of ``N_hat(A)``;
the pull-off force ``N_hat_c pi w R`` decreases monotonically from ``2 pi w R``
(``lambda -> 0``) to ``(3/2) pi w R`` (``lambda -> infinity``); e.g. ``N_hat_c = 1.7182``
at ``lambda = 0.5``, ``1.6007`` at ``lambda = 1``, ``1.5346`` at ``lambda = 2`` (computed
here; see the test-suite for the checks). The minimum lies on the branch that is stable
under displacement control too (``dD_hat/dA > 0`` there), so the largest tensile force
along a displacement-controlled retraction is the same ``N_hat_c`` (as for JKR; Maugis
2000, ch. 5).

**Other interaction laws.** For a smooth law the usual mapping (Greenwood, Proc. R.
Soc. Lond. A 453, 1277 (1997); Johnson & Greenwood 1997) takes ``sigma0`` equal to the
law's largest attractive stress and ``h0 = w/sigma0``; for the Lennard-Jones 9-3 law
``sigma0 = 1.03 w/z0`` and ``lambda = 1.16 mu`` with Tabor's parameter
``mu = (R w^2 / (E*^2 z0^3))^(1/3)`` (:func:`tabor_parameter`). The mapping is
approximate (a few per cent in the pull-off force in the transition region).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validate import ParameterError, positive

__all__ = [
    "MaugisDugdaleContact",
    "MaugisDugdalePullOff",
    "maugis_dugdale",
    "maugis_dugdale_nondimensional",
    "maugis_dugdale_pull_off",
    "maugis_dugdale_pull_off_force",
    "maugis_parameter",
    "tabor_parameter",
]


def _check(radius, contact_modulus, work_of_adhesion, cohesive_stress):
    return (
        positive("radius", radius),
        positive("contact_modulus", contact_modulus),
        positive("work_of_adhesion", work_of_adhesion),
        positive("cohesive_stress", cohesive_stress),
    )


def maugis_parameter(*, radius, contact_modulus, work_of_adhesion, cohesive_stress) -> float:
    """Maugis' parameter ``lambda = 2 sigma0 (R / (pi w K^2))^(1/3)`` with ``K = 4E*/3``.

    Parameters
    ----------
    radius : float
        Sphere radius R > 0 [length].
    contact_modulus : float
        E* > 0 [pressure] (roughcontact's contact modulus; Maugis' ``K`` is ``4E*/3``).
    work_of_adhesion : float
        w > 0 [pressure × length].
    cohesive_stress : float
        Dugdale stress sigma0 > 0 [pressure]; the range of the law is ``h0 = w/sigma0``.

    Returns
    -------
    float
        lambda (dimensionless): small -> DMT, large -> JKR.
    """
    R, E, w, s0 = _check(radius, contact_modulus, work_of_adhesion, cohesive_stress)
    K = 4.0 * E / 3.0
    return 2.0 * s0 * (R / (math.pi * w * K * K)) ** (1.0 / 3.0)


def tabor_parameter(*, radius, contact_modulus, work_of_adhesion, range_length) -> float:
    """Tabor's parameter ``mu = (R w^2 / (E*^2 z0^3))^(1/3)`` (Tabor, J. Colloid Interface
    Sci. 58, 2 (1977)); ``z0`` is the range (equilibrium spacing) of the law [length].

    For the Lennard-Jones 9-3 law mapped on a Dugdale zone with the same peak stress,
    ``lambda = 1.16 mu`` (Johnson & Greenwood 1997).
    """
    R = positive("radius", radius)
    E = positive("contact_modulus", contact_modulus)
    w = positive("work_of_adhesion", work_of_adhesion)
    z0 = positive("range_length", range_length)
    return (R * w * w / (E * E * z0**3)) ** (1.0 / 3.0)


def _mu_minus_atan(mu: float) -> float:
    """``mu - atan(mu)`` without cancellation for small mu."""
    if mu < 1e-3:
        m2 = mu * mu
        return mu * m2 * (1.0 / 3.0 - m2 / 5.0 + m2 * m2 / 7.0)
    return mu - math.atan(mu)


def _griffith(mu: float, A: float, lam: float) -> float:
    """Left side minus right side of the Griffith condition, as a function of mu."""
    m = math.sqrt(1.0 + mu * mu)
    t = math.atan(mu)
    # mu + (m^2 - 2) atan mu = (mu - atan mu) + mu^2 atan mu
    f1 = _mu_minus_atan(mu) + mu * mu * t
    # mu atan mu - m + 1 = mu atan mu - mu^2 / (1 + m)
    f2 = mu * t - mu * mu / (1.0 + m)
    return 0.5 * lam * A * A * f1 + 4.0 / 3.0 * lam * lam * A * f2 - 1.0


def _solve_mu(A: float, lam: float) -> float:
    from scipy.optimize import brentq  # scipy on first use: import roughcontact stays light

    hi = 1.0
    while _griffith(hi, A, lam) < 0.0:
        hi *= 4.0
        if hi > 1e300:  # pragma: no cover - A*lam underflow; guarded by the callers
            raise ParameterError(f"no Maugis-Dugdale solution for A={A!r}, lambda={lam!r}")
    return brentq(_griffith, 0.0, hi, args=(A, lam), xtol=1e-300, rtol=1e-15, maxiter=400)


def _state(A: float, lam: float):
    mu = _solve_mu(A, lam)
    m = math.sqrt(1.0 + mu * mu)
    t = math.atan(mu)
    N = A**3 - lam * A * A * (mu + m * m * t)
    D = A * A - 4.0 / 3.0 * lam * A * mu
    return N, D, m


def maugis_dugdale_nondimensional(contact_radius, maugis_parameter):
    """Solve the Maugis–Dugdale equations at non-dimensional contact radius A.

    Parameters
    ----------
    contact_radius : float or array
        A = a (4E*/(3 pi w R^2))^(1/3) > 0 (dimensionless).
    maugis_parameter : float
        lambda > 0.

    Returns
    -------
    load, indentation, m : float or ndarray
        ``N_hat = N/(pi w R)``, ``D_hat = delta / (pi^2 w^2 R/K^2)^(1/3)`` and
        ``m = c/a`` (see the module docstring), each shaped like ``contact_radius``.
    """
    lam = positive("maugis_parameter", maugis_parameter)
    try:
        A = np.asarray(contact_radius, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(
            f"contact_radius must be a positive number or array, got {contact_radius!r}"
        ) from None
    if not np.all(np.isfinite(A)) or np.any(A <= 0):
        raise ParameterError(f"contact_radius must be finite and > 0, got {contact_radius!r}")
    out = np.array([_state(float(x), lam) for x in A.ravel()]).reshape((*A.shape, 3))
    N, D, m = out[..., 0], out[..., 1], out[..., 2]
    if A.ndim == 0:
        return float(N), float(D), float(m)
    return N, D, m


@dataclass(frozen=True)
class MaugisDugdaleContact:
    """One Maugis–Dugdale equilibrium state (see :func:`maugis_dugdale`).

    Attributes
    ----------
    contact_radius : float
        a [length].
    cohesive_radius : float
        c = m a, outer radius of the Dugdale zone [length].
    load : float
        N [force] (< 0 tensile).
    indentation : float
        delta, rigid-body approach [length].
    maugis_parameter : float
        lambda.
    radius, contact_modulus, work_of_adhesion, cohesive_stress : float
        R [length], E* [pressure], w [pressure × length], sigma0 [pressure].
    """

    contact_radius: float
    cohesive_radius: float
    load: float
    indentation: float
    maugis_parameter: float
    radius: float
    contact_modulus: float
    work_of_adhesion: float
    cohesive_stress: float

    @property
    def range_length(self) -> float:
        """Dugdale range ``h0 = w / sigma0`` [length]."""
        return self.work_of_adhesion / self.cohesive_stress


def _scales(R, E, w):
    K = 4.0 * E / 3.0
    length = (math.pi * w * R * R / K) ** (1.0 / 3.0)
    depth = (math.pi**2 * w * w * R / (K * K)) ** (1.0 / 3.0)
    force = math.pi * w * R
    return length, depth, force


def maugis_dugdale(
    *, contact_radius, radius, contact_modulus, work_of_adhesion, cohesive_stress
) -> MaugisDugdaleContact:
    """The Maugis–Dugdale state with contact radius a (Maugis 1992).

    Parameters
    ----------
    contact_radius : float
        a > 0 [length].
    radius, contact_modulus, work_of_adhesion, cohesive_stress : float
        R [length], E* [pressure], w [pressure × length], sigma0 [pressure], all > 0.

    Returns
    -------
    MaugisDugdaleContact
    """
    a = positive("contact_radius", contact_radius)
    R, E, w, s0 = _check(radius, contact_modulus, work_of_adhesion, cohesive_stress)
    lam = maugis_parameter(radius=R, contact_modulus=E, work_of_adhesion=w, cohesive_stress=s0)
    length, depth, force = _scales(R, E, w)
    N, D, m = _state(a / length, lam)
    return MaugisDugdaleContact(
        contact_radius=a,
        cohesive_radius=m * a,
        load=N * force,
        indentation=D * depth,
        maugis_parameter=lam,
        radius=R,
        contact_modulus=E,
        work_of_adhesion=w,
        cohesive_stress=s0,
    )


@dataclass(frozen=True)
class MaugisDugdalePullOff:
    """Non-dimensional pull-off state of the Maugis–Dugdale theory under load control.

    Attributes
    ----------
    maugis_parameter : float
        lambda.
    coefficient : float
        ``N_hat_c = |N_c| / (pi w R)``, between 3/2 (JKR) and 2 (DMT).
    contact_radius : float
        A at pull-off (non-dimensional, see the module docstring).
    indentation : float
        D_hat at pull-off.
    m : float
        c/a at pull-off.
    """

    maugis_parameter: float
    coefficient: float
    contact_radius: float
    indentation: float
    m: float


def maugis_dugdale_pull_off(maugis_parameter) -> MaugisDugdalePullOff:
    """Pull-off under load control: the minimum of ``N_hat(A)`` over the branch.

    Parameters
    ----------
    maugis_parameter : float
        lambda > 0 (finite; use 1e-6 ... 1e6 for the limits).

    Returns
    -------
    MaugisDugdalePullOff
        ``coefficient`` goes monotonically from 2 (DMT, lambda -> 0) to 3/2 (JKR,
        lambda -> infinity).
    """
    from scipy.optimize import minimize_scalar  # on first use: import roughcontact stays light

    lam = positive("maugis_parameter", maugis_parameter)

    def load(logA):
        return _state(math.exp(logA), lam)[0]

    # the minimiser sits near A ~ 2 lambda (DMT side) and A -> 1.5^(1/3) (JKR side):
    # locate it on a log grid, then refine with a bounded Brent search
    grid = np.linspace(math.log(min(1e-3, 0.05 * lam)), math.log(4.0), 61)
    values = [load(x) for x in grid]
    i = int(np.argmin(values))
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
    res = minimize_scalar(load, bounds=(lo, hi), method="bounded", options={"xatol": 1e-10})
    logA = res.x if res.fun <= values[i] else grid[i]
    A = math.exp(logA)
    N, D, m = _state(A, lam)
    return MaugisDugdalePullOff(
        maugis_parameter=lam, coefficient=-N, contact_radius=A, indentation=D, m=m
    )


def maugis_dugdale_pull_off_force(
    *, radius, contact_modulus, work_of_adhesion, cohesive_stress
) -> float:
    """Maugis–Dugdale pull-off force magnitude ``N_hat_c(lambda) pi w R`` [force].

    Parameters as in :func:`maugis_parameter`. Between ``(3/2) pi w R`` (JKR) and
    ``2 pi w R`` (DMT).
    """
    R, E, w, s0 = _check(radius, contact_modulus, work_of_adhesion, cohesive_stress)
    lam = maugis_parameter(radius=R, contact_modulus=E, work_of_adhesion=w, cohesive_stress=s0)
    return maugis_dugdale_pull_off(lam).coefficient * math.pi * w * R
