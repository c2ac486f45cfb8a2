r"""Greenwood–Williamson contact of a rough surface, without and with adhesion.

The rough surface is replaced by a bed of independent paraboloidal summits of equal
radius ``R_s`` with Gaussian heights, pressed onto a flat elastic body of contact
modulus E* (J. A. Greenwood and J. B. P. Williamson, Proc. R. Soc. Lond. A 295, 300
(1966)); elastic interaction between summits is neglected. ``separation`` d is the
distance from the mean plane of the heights to the flat; a summit of height ``z > d``
is indented by ``delta = z - d``. Per unit nominal area (``A0``)::

    A/A0 = eta \int pi a(z-d)^2 phi(z) dz,   p = N/A0 = eta \int F(z-d) phi(z) dz

with ``phi`` the Gaussian summit-height density (mean ``z_s``, std ``sigma_s``).

**Summit statistics from spectral moments** (P. R. Nayak, ASME J. Lubr. Technol. 93, 398
(1971); J. I. McCool, Wear 107, 37 (1986)). For an isotropic Gaussian surface with
*profile* moments ``m0 = <h^2>``, ``m2 = <(dh/dx)^2>``, ``m4 = <(d^2h/dx^2)^2>`` and
bandwidth ``alpha = m0 m4/m2^2``::

    eta     = m4/(6 pi sqrt(3) m2)              summit density (Nayak)
    R_s     = (3/8) sqrt(pi/m4)                 1/(mean summit curvature) (McCool)
    sigma_s = sqrt(m0 (1 - 0.8968/alpha))       std of summit heights (McCool)
    z_s     = 4 sqrt(m0/(pi alpha))             mean summit height (McCool)

An isotropic surface has ``<|grad h|^2> = 2 m2`` and ``<(lap h)^2> = (8/3) m4``, so
``m2 = h'_rms^2/2`` and ``m4 = 3 h''_rms^2/8`` in terms of the statistics of
:func:`roughcontact.statistics` (spectral derivatives), which
:func:`spectral_moments` uses.

**Asperity laws** (``a`` contact radius, ``w`` work of adhesion):

* ``"hertz"``: ``a^2 = R delta``, ``F = (4/3) E* R^(1/2) delta^(3/2)`` (Johnson 1985, ch. 4);
* ``"dmt"``: Hertz area, ``F_Hertz - 2 pi w R`` for every summit in contact (Derjaguin,
  Muller & Toporov 1975) -- i.e. the non-adhesive curve plus ``-2 pi w R eta P(z > d)``;
* ``"jkr"``: JKR summits, ``delta = a^2/R - sqrt(2 pi w a/E*)``,
  ``F = 4 E* a^3/(3R) - sqrt(8 pi w E* a^3)`` (Fuller & Tabor, Proc. R. Soc. Lond. A 345,
  327 (1975)). On the ``"loading"`` branch a summit makes contact when it touches
  (``delta >= 0``); on the ``"unloading"`` branch contacts survive down to the
  displacement-control jump-out ``delta = -(3/4)(pi^2 w^2 R/E*^2)^(1/3)``. The
  integral is taken over the contact radius (``delta(a)`` is monotonic on the stable
  branch), ``\int f(a) phi(d + delta(a)) delta'(a) da``, with ``scipy.integrate.quad``.

Fuller & Tabor's adhesion parameter is :func:`fuller_tabor_parameter`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validate import ParameterError, positive

__all__ = [
    "GreenwoodWilliamsonCurve",
    "SummitStatistics",
    "fuller_tabor_parameter",
    "greenwood_williamson",
    "spectral_moments",
    "summit_statistics",
    "summit_statistics_from_heights",
]

_ASPERITIES = ("hertz", "dmt", "jkr")
_BRANCHES = ("loading", "unloading")
_SQ2PI = math.sqrt(2.0 * math.pi)


@dataclass(frozen=True)
class SummitStatistics:
    """Nayak/McCool summit statistics (see the module docstring; lengths in input units).

    Attributes
    ----------
    density : float
        eta, summits per unit area [1/length^2].
    radius : float
        R_s [length].
    height_std : float
        sigma_s [length].
    mean_height : float
        z_s, above the mean plane of the heights [length].
    bandwidth : float
        alpha = m0 m4/m2^2.
    m0, m2, m4 : float
        Profile spectral moments [length^2, 1, 1/length^2].
    """

    density: float
    radius: float
    height_std: float
    mean_height: float
    bandwidth: float
    m0: float
    m2: float
    m4: float


def spectral_moments(heights, *, pixel_size: float = 1.0) -> tuple[float, float, float]:
    """Profile moments ``(m0, m2, m4)`` of an isotropic height map [length^2, 1, 1/length^2].

    ``m0 = h_rms^2``, ``m2 = h'_rms^2/2``, ``m4 = 3 h''_rms^2/8`` with the spectral
    statistics of :func:`roughcontact.statistics` (isotropy assumed).
    """
    from ..surfaces.statistics import statistics

    st = statistics(heights, pixel_size=pixel_size, method="spectral")
    return st.rms_height**2, st.rms_slope**2 / 2.0, 3.0 * st.rms_curvature**2 / 8.0


def summit_statistics(m0: float, m2: float, m4: float) -> SummitStatistics:
    """Summit density, radius and height distribution from the profile moments.

    Nayak (1971) for the density; McCool (1986) for ``R_s``, ``sigma_s``, ``z_s``. Needs
    ``alpha = m0 m4/m2^2 > 0.8968`` (true for any real spectrum, ``alpha >= 1``).
    """
    m0 = positive("m0", m0)
    m2 = positive("m2", m2)
    m4 = positive("m4", m4)
    alpha = m0 * m4 / m2**2
    if alpha <= 0.8968:
        raise ParameterError(f"bandwidth m0*m4/m2^2 must be > 0.8968, got {alpha:.6g}")
    return SummitStatistics(
        density=m4 / (6.0 * math.pi * math.sqrt(3.0) * m2),
        radius=0.375 * math.sqrt(math.pi / m4),
        height_std=math.sqrt(m0 * (1.0 - 0.8968 / alpha)),
        mean_height=4.0 * math.sqrt(m0 / (math.pi * alpha)),
        bandwidth=alpha,
        m0=m0,
        m2=m2,
        m4=m4,
    )


def summit_statistics_from_heights(heights, *, pixel_size: float = 1.0) -> SummitStatistics:
    """:func:`summit_statistics` of :func:`spectral_moments` of a height map."""
    return summit_statistics(*spectral_moments(heights, pixel_size=pixel_size))


def fuller_tabor_parameter(summit_height_std, summit_radius, contact_modulus, work_of_adhesion):
    """Fuller & Tabor's adhesion parameter ``theta = E* sigma_s^(3/2)/(w R_s^(1/2))``.

    Fuller & Tabor (1975) write ``theta = E sigma^(3/2)/(R^(1/2) Delta_gamma)`` with
    ``Delta_gamma`` the work of adhesion w; here ``E = E*`` (authors who use the JKR
    modulus ``K = 4E*/3`` get a theta 4/3 larger). Its meaning: the ratio of the
    summit-height spread to the JKR jump-out distance
    ``delta_d = (3/4)(pi^2 w^2 R/E*^2)^(1/3)`` is ``(sigma_s/delta_d)^(3/2) =
    (4/3)^(3/2) theta/pi = 0.49 theta``. The pull-off force drops quickly with theta
    (Fuller & Tabor's main result); with :func:`greenwood_williamson` (JKR summits,
    unloading) the largest tensile mean pressure is 94 %, 36 % and 4 % of the
    smooth-summit value ``1.5 pi w R_s eta`` at theta = 0.3, 3 and 10.

    Parameters
    ----------
    summit_height_std : float
        sigma_s > 0 [length].
    summit_radius : float
        R_s > 0 [length].
    contact_modulus : float
        E* > 0 [pressure].
    work_of_adhesion : float
        w > 0 [pressure × length].
    """
    s = positive("summit_height_std", summit_height_std)
    R = positive("summit_radius", summit_radius)
    E = positive("contact_modulus", contact_modulus)
    w = positive("work_of_adhesion", work_of_adhesion)
    return E * s**1.5 / (w * math.sqrt(R))


def _upper_tail(t):
    from scipy.special import erfc  # scipy on first use: import roughcontact stays light

    return 0.5 * erfc(t / math.sqrt(2.0))


def _tail_moment(n: float, t: float) -> float:
    """``\\int_t^inf (s - t)^n phi(s) ds`` for the standard normal density phi."""
    from scipy.integrate import quad  # scipy on first use: import roughcontact stays light

    if t >= 0:  # factor out phi(t) so that quad sees an O(1) integrand
        f = quad(lambda u: u**n * math.exp(-u * t - 0.5 * u * u), 0, math.inf,
                 epsabs=0, epsrel=1e-10, limit=200)[0]  # fmt: skip
        return math.exp(-0.5 * t * t) / _SQ2PI * f
    g = quad(lambda u: u**n * math.exp(-0.5 * (u + t) ** 2), 0, math.inf,
             epsabs=0, epsrel=1e-10, limit=200)[0]  # fmt: skip
    return g / _SQ2PI


def _jkr_integrals(t, sig, R, E, w, branch):
    """Per-summit JKR area and load averaged over the heights, at standardised separation t.

    Reduced variables (J. A. Greenwood, Tribol. Lett. 65, 159 (2017)): ``a = l A``,
    ``delta = delta0 D(A)``, ``F = w R P(A)`` with ``l = (w R^2/E*)^(1/3)``, ``delta0 = l^2/R``,
    ``D = A^2 - sqrt(2 pi A)``, ``P = (4/3) A^3 - sqrt(8 pi A^3)``.
    """
    from scipy.integrate import quad  # scipy on first use: import roughcontact stays light
    from scipy.optimize import brentq

    ell = (w * R * R / E) ** (1.0 / 3.0)
    d0 = ell * ell / R
    a_start = (2.0 * math.pi) ** (1.0 / 3.0) if branch == "loading" else (math.pi / 8) ** (1 / 3)

    def D(A):
        return A * A - math.sqrt(2.0 * math.pi * A)

    def weight(A):  # phi(s) ds with s = t + delta/sigma
        s = t + d0 * D(A) / sig
        return math.exp(-0.5 * s * s) / _SQ2PI * d0 / sig * (2.0 * A - math.sqrt(math.pi / (2 * A)))

    top = (max(12.0, t + 12.0) - t) * sig / d0  # D at s = max(12, t + 12)
    hi = max(2.0 * a_start, 1.0)
    while D(hi) < top:
        hi *= 2.0
    a_end = brentq(lambda A: D(A) - top, a_start, hi)
    pts = []
    if D(a_start) < -t * sig / d0 < top:  # the distribution's peak, s = 0
        pts.append(brentq(lambda A: D(A) + t * sig / d0, a_start, a_end))
    kw = {"epsabs": 0, "epsrel": 1e-9, "limit": 400, "points": pts or None}
    area = quad(lambda A: math.pi * ell**2 * A * A * weight(A), a_start, a_end, **kw)[0]
    load = quad(
        lambda A: w * R * (4 / 3 * A**3 - math.sqrt(8 * math.pi * A**3)) * weight(A),
        a_start, a_end, **kw)[0]  # fmt: skip
    count = _upper_tail(t + d0 * D(a_start) / sig)
    return area, load, count


@dataclass(frozen=True, eq=False)
class GreenwoodWilliamsonCurve:
    """Area and load against separation (see :func:`greenwood_williamson`).

    Attributes
    ----------
    separation : ndarray
        d, flat above the mean plane of the heights [length].
    area_fraction : ndarray
        A/A0.
    mean_pressure : ndarray
        p = N/A0 [pressure] (> 0 compressive).
    contact_density : ndarray
        Summits in contact per unit area [1/length^2].
    summits : SummitStatistics
    contact_modulus, work_of_adhesion : float
    asperity, branch : str
    """

    separation: np.ndarray
    area_fraction: np.ndarray
    mean_pressure: np.ndarray
    contact_density: np.ndarray
    summits: SummitStatistics
    contact_modulus: float
    work_of_adhesion: float
    asperity: str
    branch: str

    def kappa(self, rms_slope: float) -> np.ndarray:
        """``kappa = h'_rms E* (A/A0)/p`` at each separation (PNAS 2014, Eq. 3)."""
        s = positive("rms_slope", rms_slope)
        with np.errstate(divide="ignore", invalid="ignore"):
            return s * self.contact_modulus * self.area_fraction / self.mean_pressure

    @property
    def pull_off(self) -> float:
        """Largest tensile mean pressure on the curve, ``max(0, -min p)`` [pressure]."""
        return float(max(0.0, -np.min(self.mean_pressure)))


def greenwood_williamson(
    separation,
    summits: SummitStatistics,
    *,
    contact_modulus: float = 1.0,
    work_of_adhesion: float = 0.0,
    asperity: str = "hertz",
    branch: str = "loading",
) -> GreenwoodWilliamsonCurve:
    """Greenwood–Williamson area and load, with Hertz, DMT or JKR (Fuller–Tabor) summits.

    Parameters
    ----------
    separation : float or array
        d, distance from the mean plane of the heights to the flat [length].
    summits : SummitStatistics
        From :func:`summit_statistics` or :func:`summit_statistics_from_heights`.
    contact_modulus : float
        E* > 0 [pressure].
    work_of_adhesion : float
        w >= 0 [pressure × length]; must be > 0 for ``"dmt"`` and ``"jkr"``.
    asperity : {"hertz", "dmt", "jkr"}
        Asperity law (module docstring).
    branch : {"loading", "unloading"}
        Only for ``"jkr"``: contacts form at touching / survive to the JKR jump-out.

    Returns
    -------
    GreenwoodWilliamsonCurve
    """
    if asperity not in _ASPERITIES:
        raise ParameterError(f"asperity must be one of {_ASPERITIES}, got {asperity!r}")
    if branch not in _BRANCHES:
        raise ParameterError(f"branch must be one of {_BRANCHES}, got {branch!r}")
    E = positive("contact_modulus", contact_modulus)
    w = float(work_of_adhesion)
    if asperity == "hertz":
        if w != 0:
            raise ParameterError("asperity 'hertz' is non-adhesive: work_of_adhesion must be 0")
    else:
        w = positive("work_of_adhesion", work_of_adhesion)
    d = np.atleast_1d(np.asarray(separation, dtype=float))
    if not np.all(np.isfinite(d)):
        raise ParameterError(f"separation must be finite, got {separation!r}")
    eta, R, sig = summits.density, summits.radius, summits.height_std
    t = (d - summits.mean_height) / sig
    area, load, count = (np.empty_like(t) for _ in range(3))
    for i, ti in enumerate(t):
        if asperity == "jkr":
            a, p, c = _jkr_integrals(float(ti), sig, R, E, w, branch)
        else:
            a = math.pi * R * sig * _tail_moment(1.0, ti)
            p = 4.0 / 3.0 * E * math.sqrt(R) * sig**1.5 * _tail_moment(1.5, ti)
            c = _upper_tail(ti)
            if asperity == "dmt":
                p -= 2.0 * math.pi * w * R * c
        area[i], load[i], count[i] = eta * a, eta * p, eta * c
    return GreenwoodWilliamsonCurve(
        separation=d,
        area_fraction=area,
        mean_pressure=load,
        contact_density=count,
        summits=summits,
        contact_modulus=E,
        work_of_adhesion=w,
        asperity=asperity,
        branch=branch,
    )
