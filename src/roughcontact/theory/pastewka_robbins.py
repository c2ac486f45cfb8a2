r"""Pastewka–Robbins theory of adhesive rough contact and the stickiness criterion.

L. Pastewka and M. O. Robbins, "Contact between rough surfaces and a criterion for
macroscopic adhesion", PNAS 111, 3298 (2014). Symbols (any consistent units; lattice
units a0 = 1, E* = 1 by default):

* ``h'_rms`` rms slope (Eq. 1), ``h''_rms`` rms curvature (Eq. 8) of the rough surface;
* ``E*`` contact modulus, ``w`` work of adhesion, ``l_a = w/E*`` adhesion length;
* ``Delta_r`` interaction range (attraction vanishes beyond ``a0 + Delta_r``);
* ``d_rep`` mean diameter of the repulsive contacts, ``A_rep = P d_rep / pi``;
* ``kappa_rep ~ 2`` the non-adhesive area–load prefactor, ``p_rep = h'_rms E*/kappa_rep``.

The theory (Eq. numbers of the paper)::

    N_att = (w/Delta_r) A_att                                                    (4)
    1/kappa = 1/kappa_rep - 1/kappa_att,  kappa_att = (h'_rms Delta_r/l_a) A_rep/A_att (5)
    A_rep/A_att = d_rep/(pi d_att)
                = (16/(9 pi))^(1/3) (h'_rms d_rep/(pi Delta_r))^(2/3)             (6)
    kappa_att = (h'_rms Delta_r/l_a) (16/(9 pi))^(1/3) (h'_rms d_rep/(pi Delta_r))^(2/3)  (7)
    1/R = h''_rms/2,  d_rep = 4 h'_rms/h''_rms                                   (8, 9)
    delta_h = h'_rms^2/h''_rms = h'_rms d_rep/4                                  (9)

Eq. 6 is the ratio *repulsive over attractive* area (``area_ratio`` everywhere in
roughcontact); it exceeds 1 in the regime where the theory holds (a thin attractive
rim, ``A_att << A_rep``). The gap outside a contact edge rises as ``x^(3/2)``; with the
cylinder of contact radius ``d_rep/2`` the gap is ``(4/3) h'_rms x^(3/2)/d_rep^(1/2)``,
and ``d_att`` is the distance ``x`` where it reaches ``Delta_r`` (SI of the paper, S-I).

**Stickiness (Eq. 10).** Surfaces stick when the external load at fixed ``A_rep`` changes
sign, ``1/kappa_att > 1/kappa_rep``, i.e. ``kappa_att < kappa_rep``. With Eq. 7 this is::

    S = (h'_rms Delta_r/(kappa_rep l_a)) (h'_rms d_rep/(4 Delta_r))^(2/3)
      < pi (3/16)^(2/3) = 1.0291...                                              (10)

Indeed ``(16/(9 pi))^(1/3) pi^(-2/3) 4^(2/3) = (256/9)^(1/3)/pi = 1/(pi (3/16)^(2/3))``,
so ``S / (pi (3/16)^(2/3)) = kappa_att/kappa_rep`` exactly. The **margin** is defined
as ``pi (3/16)^(2/3) / S = kappa_rep/kappa_att``: > 1 sticky, < 1 not sticky. Because
``kappa_att`` is proportional to ``1/l_a``, the margin is the factor by which ``l_a``
(or ``w``, or ``1/E*``) exceeds its value at the onset of stickiness.

**Necessary condition.** Inserting ``Delta_r ~ a0 <= delta_h`` (roughness cannot change
height by less than about one atomic spacing a0) into Eq. 7 gives
``kappa_att >= c h'_rms a0/l_a`` with ``c = (16/(9 pi))^(1/3) (4/pi)^(2/3) =
(256/(9 pi^3))^(1/3) = 0.9717``, so sticking requires ``l_a/a0 > (c/kappa_rep) h'_rms``
= ``0.486 h'_rms`` for ``kappa_rep = 2``; the paper rounds this to
``l_a/a0 >~ 0.5 h'_rms``. :func:`necessary_condition` uses the unrounded ``c/kappa_rep``
so that, under the stated assumptions, Eq. 10 never reports "sticky" while the necessary
condition fails. On real crystalline surfaces ``delta_h >= a0`` holds by construction; a
simulated surface with continuous heights need not satisfy it, and
:func:`necessary_condition_applicability` says when the condition is "not applicable":
``delta_h < a0`` (contacts smaller than one atomic step) or ``Delta_r`` not about ``a0``
(outside ``[a0/2, 2 a0]``), as in lattice simulations with small ``l_a``, where Eq. 10
itself still applies.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validate import JsonRecord, ParameterError, positive
from .._validate import positive_array as _pos

__all__ = [
    "AREA_RATIO_PREFACTOR",
    "KAPPA_REP",
    "NECESSARY_CONDITION_CONSTANT",
    "STICKINESS_THRESHOLD",
    "PastewkaRobbinsPrediction",
    "area_ratio",
    "asperity_radius",
    "attractive_load",
    "height_change",
    "kappa_att",
    "kappa_att_from_area_ratio",
    "kappa_from_components",
    "necessary_condition",
    "necessary_condition_applicability",
    "necessary_condition_verdict",
    "predict",
    "predicted_d_rep",
    "stickiness_margin",
    "stickiness_parameter",
]

#: ``(16/(9 pi))^(1/3)``, the prefactor of Eq. 6.
AREA_RATIO_PREFACTOR = (16.0 / (9.0 * math.pi)) ** (1.0 / 3.0)
#: ``pi (3/16)^(2/3) = 1.0291``, the right-hand side of Eq. 10 ("~ 1" in the paper).
STICKINESS_THRESHOLD = math.pi * (3.0 / 16.0) ** (2.0 / 3.0)
#: The paper's non-adhesive area–load prefactor ``kappa_rep ~ 2`` (Eq. 2, Fig. 4).
KAPPA_REP = 2.0
#: ``c = (256/(9 pi^3))^(1/3) = 0.9717``: ``kappa_att >= c h'_rms a0/l_a`` if
#: ``Delta_r = a0 <= delta_h`` (the necessary condition).
NECESSARY_CONDITION_CONSTANT = (256.0 / (9.0 * math.pi**3)) ** (1.0 / 3.0)
#: ``Delta_r`` counts as "about a0" for the necessary condition within this factor.
RANGE_ABOUT_SPACING = 2.0


def _out(x):
    x = np.asarray(x)
    return x if x.ndim else x.item()


def attractive_load(attractive_area, work_of_adhesion, interaction_range):
    """Eq. 4: ``N_att = (w/Delta_r) A_att`` [force, or pressure for areas per A0].

    ``attractive_area`` A_att >= 0 [length^2, or a fraction of A0]; ``work_of_adhesion``
    w > 0 [energy/length^2]; ``interaction_range`` Delta_r > 0 [length].
    """
    a = np.asarray(attractive_area, dtype=float)
    if not np.all(np.isfinite(a)) or np.any(a < 0):
        raise ParameterError(f"attractive_area must be finite and >= 0, got {attractive_area!r}")
    w = _pos("work_of_adhesion", work_of_adhesion)
    dr = _pos("interaction_range", interaction_range)
    return _out(w / dr * a)


def area_ratio(rms_slope, d_rep, interaction_range):
    """Eq. 6: ``A_rep/A_att = (16/(9 pi))^(1/3) (h'_rms d_rep/(pi Delta_r))^(2/3)``.

    Parameters
    ----------
    rms_slope : float or array
        h'_rms > 0 [dimensionless].
    d_rep : float or array
        Mean contact diameter d_rep > 0 [length] (measured ``pi A_rep/P`` or
        :func:`predicted_d_rep`).
    interaction_range : float or array
        Delta_r > 0 [length].

    Returns
    -------
    float or ndarray
        A_rep/A_att [dimensionless].
    """
    s = _pos("rms_slope", rms_slope)
    d = _pos("d_rep", d_rep)
    dr = _pos("interaction_range", interaction_range)
    return _out(AREA_RATIO_PREFACTOR * (s * d / (math.pi * dr)) ** (2.0 / 3.0))


def kappa_att_from_area_ratio(rms_slope, interaction_range, adhesion_length, area_ratio):
    """Eq. 5: ``kappa_att = (h'_rms Delta_r/l_a) A_rep/A_att`` [dimensionless].

    ``adhesion_length`` is ``l_a = w/E*`` > 0 [length]; ``area_ratio`` is A_rep/A_att > 0.
    """
    s = _pos("rms_slope", rms_slope)
    dr = _pos("interaction_range", interaction_range)
    la = _pos("adhesion_length", adhesion_length)
    r = _pos("area_ratio", area_ratio)
    return _out(s * dr / la * r)


def kappa_att(rms_slope, d_rep, interaction_range, adhesion_length):
    """Eq. 7: Eq. 5 with Eq. 6 [dimensionless]::

        kappa_att = (h'_rms Delta_r/l_a) (16/(9 pi))^(1/3) (h'_rms d_rep/(pi Delta_r))^(2/3)

    Parameters as in :func:`area_ratio`; ``adhesion_length`` is ``l_a = w/E*`` > 0 [length].
    """
    r = area_ratio(rms_slope, d_rep, interaction_range)
    return kappa_att_from_area_ratio(rms_slope, interaction_range, adhesion_length, r)


def kappa_from_components(kappa_rep, kappa_att):
    """``kappa`` from ``1/kappa = 1/kappa_rep - 1/kappa_att`` (Eqs. 2-5).

    Returns ``inf`` exactly at the onset of stickiness (``kappa_att = kappa_rep``) and a
    negative value for sticky surfaces. ``kappa_att = inf`` (no adhesion) gives ``kappa_rep``.
    """
    kr = _pos("kappa_rep", kappa_rep)
    ka = np.asarray(kappa_att, dtype=float)
    if np.any(np.isnan(ka)) or np.any(ka <= 0):
        raise ParameterError(f"kappa_att must be > 0 (inf allowed), got {kappa_att!r}")
    inv = 1.0 / kr - 1.0 / ka
    with np.errstate(divide="ignore"):
        k = np.where(inv == 0, np.inf, 1.0 / np.where(inv == 0, 1.0, inv))
    return _out(k)


def asperity_radius(rms_curvature):
    """Eq. 8: the contact-scale radius of curvature ``R = 2/h''_rms`` [length]."""
    return _out(2.0 / _pos("rms_curvature", rms_curvature))


def predicted_d_rep(rms_slope, rms_curvature):
    """Eq. 9 (text above it): ``d_rep = 4 h'_rms/h''_rms`` [length]."""
    return _out(4.0 * _pos("rms_slope", rms_slope) / _pos("rms_curvature", rms_curvature))


def height_change(rms_slope, d_rep):
    """Eq. 9: height change from contact edge to centre, ``delta_h = h'_rms d_rep/4`` [length]
    (``= h'_rms^2/h''_rms`` with the predicted d_rep)."""
    return _out(_pos("rms_slope", rms_slope) * _pos("d_rep", d_rep) / 4.0)


def stickiness_parameter(rms_slope, d_rep, interaction_range, adhesion_length, kappa_rep=KAPPA_REP):
    """Left-hand side of Eq. 10,
    ``S = (h'_rms Delta_r/(kappa_rep l_a)) (h'_rms d_rep/(4 Delta_r))^(2/3)``.

    Sticky if ``S < STICKINESS_THRESHOLD = pi (3/16)^(2/3)``; ``S/STICKINESS_THRESHOLD =
    kappa_att/kappa_rep``. The first factor is the ratio of the repulsive pressure
    ``h'_rms E*/kappa_rep`` to the attractive one ``w/Delta_r``; the second comes from the
    area ratio (Eq. 6).
    """
    s = _pos("rms_slope", rms_slope)
    d = _pos("d_rep", d_rep)
    dr = _pos("interaction_range", interaction_range)
    la = _pos("adhesion_length", adhesion_length)
    kr = _pos("kappa_rep", kappa_rep)
    return _out(s * dr / (kr * la) * (s * d / (4.0 * dr)) ** (2.0 / 3.0))


def stickiness_margin(rms_slope, d_rep, interaction_range, adhesion_length, kappa_rep=KAPPA_REP):
    """``STICKINESS_THRESHOLD / S = kappa_rep/kappa_att`` (Eq. 10): > 1 sticky, < 1 not.

    The factor by which ``l_a = w/E*`` exceeds its value at the onset of stickiness.
    """
    S = stickiness_parameter(rms_slope, d_rep, interaction_range, adhesion_length, kappa_rep)
    return _out(STICKINESS_THRESHOLD / np.asarray(S))


def necessary_condition(adhesion_length, rms_slope, atomic_spacing=1.0, kappa_rep=KAPPA_REP):
    """The necessary (not sufficient) condition for adhesion, ``l_a/a0 > (c/kappa_rep) h'_rms``.

    ``c = NECESSARY_CONDITION_CONSTANT = 0.9717`` (module docstring), i.e.
    ``l_a/a0 > 0.486 h'_rms`` for ``kappa_rep = 2`` (the paper: ``l_a/a0 >~ 0.5 h'_rms``).

    ``adhesion_length`` l_a = w/E* > 0 [length]; ``rms_slope`` h'_rms > 0;
    ``atomic_spacing`` a0 > 0 [length], the bond distance or smallest height step
    (1 in lattice units); ``kappa_rep`` > 0. Returns a bool (array for array input).
    """
    la = _pos("adhesion_length", adhesion_length)
    s = _pos("rms_slope", rms_slope)
    a0 = _pos("atomic_spacing", atomic_spacing)
    kr = _pos("kappa_rep", kappa_rep)
    return _out(la / a0 > NECESSARY_CONDITION_CONSTANT / kr * s)


def necessary_condition_applicability(height_change, interaction_range, atomic_spacing=1.0):
    """Why the necessary condition does not apply, or ``""`` when its assumptions hold.

    The condition assumes ``delta_h >= a0`` (no contact changes height by less than one
    atomic step) and ``Delta_r ~ a0`` (here: within a factor ``RANGE_ABOUT_SPACING`` = 2).
    ``height_change`` delta_h = h'_rms d_rep/4 (Eq. 9), ``interaction_range`` Delta_r and
    ``atomic_spacing`` a0, all > 0 in the same length unit. Returns a reason such as
    ``"delta_h = 0.07 a0 < a0"``; several are joined by ``"; "``.
    """
    dh = positive("height_change", height_change)
    dr = positive("interaction_range", interaction_range)
    a0 = positive("atomic_spacing", atomic_spacing)
    reasons = []
    if dh < a0:
        reasons.append(f"delta_h = h'rms d_rep/4 = {dh / a0:.3g} a0 < a0")
    if not a0 / RANGE_ABOUT_SPACING <= dr <= RANGE_ABOUT_SPACING * a0:
        reasons.append(f"Delta_r = {dr / a0:.3g} a0 is not about a0")
    return "; ".join(reasons)


def necessary_condition_verdict(met: bool, reason: str) -> str:
    """``"met"``, ``"not met"`` or ``"not applicable: <reason>"`` (one wording everywhere)."""
    if reason:
        return f"not applicable: {reason}"
    return "met" if met else "not met"


@dataclass(frozen=True)
class PastewkaRobbinsPrediction(JsonRecord):
    """Everything the theory predicts for one surface and interaction (see :func:`predict`).

    The inputs (``rms_slope``, ``d_rep`` as used, ``interaction_range``,
    ``adhesion_length``, ``kappa_rep``, ``atomic_spacing``; lengths in the caller's
    units), ``d_rep_source`` (``"given"`` or ``"predicted"`` = ``4 h'_rms/h''_rms``),
    ``rms_curvature`` (NaN unless given), and:

    * ``area_ratio`` A_rep/A_att (Eq. 6), ``kappa_att`` (Eq. 7);
    * ``kappa = 1/(1/kappa_rep - 1/kappa_att)``: negative when sticky, inf at the onset;
    * ``height_change`` ``delta_h = h'_rms d_rep/4`` (Eq. 9);
    * ``stickiness_parameter`` S, the left-hand side of Eq. 10;
    * ``margin = pi (3/16)^(2/3)/S = kappa_rep/kappa_att`` (> 1 sticky) and ``sticky``
      (``S < pi (3/16)^(2/3)``, equivalently ``kappa_att < kappa_rep``);
    * ``threshold_adhesion_length = l_a/margin``, l_a at the onset of stickiness;
    * ``necessary_condition_met``: ``l_a/a0 > 0.486 h'_rms`` (:func:`necessary_condition`;
      for real crystalline surfaces, where ``delta_h >= a0`` holds by construction; check
      a simulated surface with :func:`necessary_condition_applicability`).
    """

    rms_slope: float
    d_rep: float
    d_rep_source: str
    rms_curvature: float
    interaction_range: float
    adhesion_length: float
    kappa_rep: float
    atomic_spacing: float
    area_ratio: float
    kappa_att: float
    kappa: float
    height_change: float
    stickiness_parameter: float
    margin: float
    sticky: bool
    threshold_adhesion_length: float
    necessary_condition_met: bool


def predict(
    *,
    rms_slope: float,
    interaction_range: float,
    adhesion_length: float,
    d_rep: float | None = None,
    rms_curvature: float | None = None,
    kappa_rep: float = KAPPA_REP,
    atomic_spacing: float = 1.0,
) -> PastewkaRobbinsPrediction:
    """All predictions of the Pastewka–Robbins theory (Eqs. 5-10) for one parameter set.

    Parameters
    ----------
    rms_slope : float
        h'_rms > 0.
    interaction_range : float
        Delta_r > 0 [length].
    adhesion_length : float
        l_a = w/E* > 0 [length].
    d_rep : float, optional
        Measured mean contact diameter ``pi A_rep/P`` [length]. Give exactly one of
        ``d_rep`` and ``rms_curvature``.
    rms_curvature : float, optional
        h''_rms [1/length]; then ``d_rep = 4 h'_rms/h''_rms`` (Eq. 9).
    kappa_rep : float, optional
        Non-adhesive prefactor, default 2 (the paper's value, Fig. 4); pass a measured
        one to override.
    atomic_spacing : float, optional
        a0 for the necessary condition [length]; 1 in lattice units.

    Returns
    -------
    PastewkaRobbinsPrediction
    """
    if (d_rep is None) == (rms_curvature is None):
        raise ParameterError("give exactly one of d_rep and rms_curvature")
    s = positive("rms_slope", rms_slope)
    dr = positive("interaction_range", interaction_range)
    la = positive("adhesion_length", adhesion_length)
    kr = positive("kappa_rep", kappa_rep)
    a0 = positive("atomic_spacing", atomic_spacing)
    if d_rep is None:
        curv = positive("rms_curvature", rms_curvature)
        d, source = predicted_d_rep(s, curv), "predicted"
    else:
        curv, d, source = math.nan, positive("d_rep", d_rep), "given"
    ratio = area_ratio(s, d, dr)
    k_att = kappa_att_from_area_ratio(s, dr, la, ratio)
    S = stickiness_parameter(s, d, dr, la, kr)
    margin = STICKINESS_THRESHOLD / S
    return PastewkaRobbinsPrediction(
        rms_slope=s,
        d_rep=d,
        d_rep_source=source,
        rms_curvature=curv,
        interaction_range=dr,
        adhesion_length=la,
        kappa_rep=kr,
        atomic_spacing=a0,
        area_ratio=ratio,
        kappa_att=k_att,
        kappa=kappa_from_components(kr, k_att),
        height_change=height_change(s, d),
        stickiness_parameter=S,
        margin=margin,
        sticky=bool(S < STICKINESS_THRESHOLD),
        threshold_adhesion_length=la / margin,
        necessary_condition_met=bool(necessary_condition(la, s, a0, kr)),
    )
