r"""Non-adhesive area–load laws of Persson and of Bush, Gibson & Thomas.

Both are written with the area–load prefactor of Pastewka & Robbins (PNAS 111, 3298
(2014), Eqs. 2-3): at small loads ``A/A0 = kappa p/(h'_rms E*)``, with ``p = N/A0`` the
mean pressure, ``E* = E/(1 - nu^2)`` the contact modulus and ``h'_rms`` the rms slope
(Eq. 1). Any consistent units (lattice units: pressures in E*).

**Persson** (B. N. J. Persson, J. Chem. Phys. 115, 3840 (2001); Persson et al., J. Phys.:
Condens. Matter 17, R1 (2005)). The stress distribution diffuses with magnification; the
contact fraction at full magnification is::

    A/A0 = erf(1/(2 sqrt(G))),   G = (pi/4) (E*/p)^2 \int_{q0}^{q1} q^3 C(q) dq

With the isotropic power spectrum C(q) normalised as in
:func:`roughcontact.surfaces.power_spectrum` (``h_rms^2 = \int d^2q C``), the slope is
``h'_rms^2 = \int d^2q q^2 C = 2 pi \int q^3 C dq``, so ``G = (h'_rms E*/p)^2/8`` and::

    A/A0 = erf(sqrt(2) p/(h'_rms E*))   ->   kappa = 2 sqrt(2)/sqrt(pi) = sqrt(8/pi) = 1.596

at small loads (``erf x ~ 2x/sqrt(pi)``); A/A0 -> 1 at large loads. (Persson's ``E`` in
G is ``E/(1 - nu^2)``, our E*.)

**Bush–Gibson–Thomas** (A. W. Bush, R. D. Gibson, T. R. Thomas, Wear 35, 87 (1975)).
Nayak's random-process summits, each a Hertzian paraboloid with its two principal
curvatures, without elastic interaction between asperities. At small loads the area is
proportional to the load with ``kappa = sqrt(2 pi) = 2.507``, independent of the
bandwidth parameter; :func:`bgt_area` is this small-load asymptote (valid for
``A/A0 << 1``; the full BGT law bends down at larger areas).

References
----------
Persson, J. Chem. Phys. 115, 3840 (2001). Bush, Gibson & Thomas, Wear 35, 87 (1975).
Hyun, Pei, Molinari & Robbins, Phys. Rev. E 70, 026117 (2004) (the kappa comparison).
"""

from __future__ import annotations

import math

import numpy as np

from .._validate import ParameterError, positive
from .._validate import nonnegative_array as _nonneg

__all__ = [
    "BGT_KAPPA",
    "PERSSON_KAPPA",
    "bgt_area",
    "persson_area",
    "persson_load",
]

#: Persson's small-load prefactor ``sqrt(8/pi) = 1.596``.
PERSSON_KAPPA = math.sqrt(8.0 / math.pi)
#: Bush–Gibson–Thomas small-load prefactor ``sqrt(2 pi) = 2.507``.
BGT_KAPPA = math.sqrt(2.0 * math.pi)


def _out(x):
    x = np.asarray(x)
    return x if x.ndim else x.item()


def persson_area(load, rms_slope, contact_modulus=1.0):
    """Persson's contact fraction ``A/A0 = erf(sqrt(2) p/(h'_rms E*))``.

    Parameters
    ----------
    load : float or array
        Mean pressure ``p = N/A0`` >= 0 [pressure].
    rms_slope : float
        h'_rms > 0 [dimensionless] (the full-magnification rms slope).
    contact_modulus : float
        E* > 0 [pressure].

    Returns
    -------
    float or ndarray
        A/A0 in [0, 1].
    """
    from scipy.special import erf  # scipy on first use: import roughcontact stays light

    p = _nonneg("load", load)
    s = positive("rms_slope", rms_slope)
    E = positive("contact_modulus", contact_modulus)
    return _out(erf(math.sqrt(2.0) * p / (s * E)))


def persson_load(area_fraction, rms_slope, contact_modulus=1.0):
    """Inverse of :func:`persson_area`: ``p = h'_rms E* erfinv(A/A0)/sqrt(2)``.

    ``area_fraction`` in [0, 1) (1 needs an infinite load) [dimensionless].
    """
    from scipy.special import erfinv  # scipy on first use: import roughcontact stays light

    a = _nonneg("area_fraction", area_fraction)
    if np.any(a >= 1):
        raise ParameterError(f"area_fraction must be in [0, 1), got {area_fraction!r}")
    s = positive("rms_slope", rms_slope)
    E = positive("contact_modulus", contact_modulus)
    return _out(s * E * erfinv(a) / math.sqrt(2.0))


def bgt_area(load, rms_slope, contact_modulus=1.0):
    """Bush–Gibson–Thomas small-load law ``A/A0 = sqrt(2 pi) p/(h'_rms E*)``.

    Parameters as in :func:`persson_area`. The asymptote of BGT for ``A/A0 << 1``; it is
    not clipped at 1.
    """
    p = _nonneg("load", load)
    s = positive("rms_slope", rms_slope)
    E = positive("contact_modulus", contact_modulus)
    return _out(BGT_KAPPA * p / (s * E))
