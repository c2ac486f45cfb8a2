r"""Stickiness criterion for real materials, in SI units (Pastewka & Robbins 2014, Eq. 10).

Inputs may be numbers (taken as SI: Pa, J/m^2, m, 1/m) or strings with units, e.g.
``"10 MPa"``, ``"50 mJ/m^2"``, ``"0.05 J/m2"``, ``"0.5 nm"``, ``"10 um"`` / ``"10 µm"``,
``"0.2 1/nm"``, ``"1e8 m^-1"`` (see :func:`parse_quantity`). The theory itself is
:mod:`roughcontact.theory.pastewka_robbins`; this module adds units, the conversion
``E* = E/(1 - nu^2)`` and the quantities the paper's Discussion talks about.

**Atomic spacing a0.** The necessary condition ``l_a/a0 >~ 0.5 h'_rms`` comes from the
paper's Discussion: "roughness on crystalline surfaces occurs in the form of terraces
with height ~a0", so no contact can have a height change ``delta_h`` below ~a0, and the
interaction range is ``Delta_r ~ a0``. For real materials a0 is the atomic bond length or
step height; the default 0.3 nm is a typical value (C–C bond 0.154 nm as in the paper's
diamond example, Si(111) step 0.31 nm, graphite layer 0.335 nm). Pass the material's own.

**Quantities beyond the verdict.** Since the margin (``kappa_rep/kappa_att``) is
proportional to ``l_a = w/E*`` and to ``d_rep^(-2/3)``, the largest contact modulus that
still sticks is ``E* × margin`` and the largest contact diameter ``d_rep × margin^(3/2)``
(for the other inputs fixed); both are reported, as are the two pressures whose ratio
forms the first factor of Eq. 10, ``p_rep = h'_rms E*/kappa_rep`` and ``w/Delta_r``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ._validate import JsonRecord, ParameterError, positive
from .theory.pastewka_robbins import KAPPA_REP, STICKINESS_THRESHOLD, predict
from .units import DIMENSIONS, parse_quantity

__all__ = ["DIMENSIONS", "StickinessCriterion", "parse_quantity", "stickiness_criterion"]

# The unit table and parser live in roughcontact.units; these names stay importable here.


def _si(value, dimension: str, name: str) -> float:
    """``parse_quantity`` followed by the check that the value is finite and > 0."""
    return positive(name, parse_quantity(value, dimension, name))


@dataclass(frozen=True)
class StickinessCriterion(JsonRecord):
    """Verdict of Eq. 10 for one material pair and surface (see :func:`stickiness_criterion`).

    All dimensional values in SI: pressures in Pa, ``work_of_adhesion`` in J/m^2, lengths
    in m, ``rms_curvature`` in 1/m. ``youngs_modulus``/``poisson`` are NaN if E* was given.
    ``margin = kappa_rep/kappa_att`` (> 1 sticky); ``kappa`` is negative when sticky.
    """

    contact_modulus: float
    youngs_modulus: float
    poisson: float
    work_of_adhesion: float
    rms_slope: float
    interaction_range: float
    d_rep: float
    d_rep_source: str
    rms_curvature: float
    kappa_rep: float
    atomic_spacing: float
    adhesion_length: float
    adhesion_length_over_atomic_spacing: float
    repulsive_pressure: float
    attractive_pressure: float
    area_ratio: float
    kappa_att: float
    kappa: float
    stickiness_parameter: float
    threshold: float
    margin: float
    sticky: bool
    necessary_condition_met: bool
    max_sticky_contact_modulus: float
    max_sticky_d_rep: float


def stickiness_criterion(
    *,
    work_of_adhesion,
    rms_slope,
    interaction_range,
    contact_modulus=None,
    youngs_modulus=None,
    poisson=None,
    d_rep=None,
    rms_curvature=None,
    kappa_rep: float = KAPPA_REP,
    atomic_spacing="0.3 nm",
) -> StickinessCriterion:
    """Is a rough contact sticky? Eq. 10 of Pastewka & Robbins (2014) in SI units.

    Parameters
    ----------
    work_of_adhesion : float or str
        w > 0 [J/m^2], e.g. ``"50 mJ/m^2"``.
    rms_slope : float or str
        h'_rms > 0 [dimensionless].
    interaction_range : float or str
        Delta_r > 0 [m], e.g. ``"0.5 nm"``.
    contact_modulus : float or str, optional
        E* > 0 [Pa] (``1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2``). Or give instead
    youngs_modulus, poisson : optional
        E > 0 [Pa] and ``-1 < nu <= 0.5`` of the compliant body against a rigid one:
        ``E* = E/(1 - nu^2)``.
    d_rep : float or str, optional
        Mean contact diameter [m]. Give exactly one of ``d_rep`` and
    rms_curvature : float or str, optional
        h''_rms [1/m]; ``d_rep = 4 h'_rms/h''_rms`` (Eq. 9).
    kappa_rep : float, optional
        Non-adhesive prefactor, default 2.
    atomic_spacing : float or str, optional
        a0 [m] for the necessary condition ``l_a/a0 >~ 0.5 h'_rms``; default 0.3 nm.

    Returns
    -------
    StickinessCriterion
    """
    if (contact_modulus is None) == (youngs_modulus is None):
        raise ParameterError("give exactly one of contact_modulus (E*) and youngs_modulus (E)")
    if contact_modulus is not None:
        if poisson is not None:
            raise ParameterError("poisson goes with youngs_modulus, not with contact_modulus (E*)")
        E = nu = math.nan
        E_star = _si(contact_modulus, "pressure", "contact_modulus")
    else:
        if poisson is None:
            raise ParameterError("youngs_modulus needs poisson (E* = E/(1 - poisson^2))")
        E = _si(youngs_modulus, "pressure", "youngs_modulus")
        nu = parse_quantity(poisson, "dimensionless", "poisson")
        if not (-1.0 < nu <= 0.5):
            raise ParameterError(f"poisson must be in (-1, 0.5], got {poisson!r}")
        E_star = E / (1.0 - nu * nu)
    if (d_rep is None) == (rms_curvature is None):
        raise ParameterError("give exactly one of d_rep and rms_curvature")
    w = _si(work_of_adhesion, "energy per area", "work_of_adhesion")
    s = _si(rms_slope, "dimensionless", "rms_slope")
    dr = _si(interaction_range, "length", "interaction_range")
    a0 = _si(atomic_spacing, "length", "atomic_spacing")
    kr = _si(kappa_rep, "dimensionless", "kappa_rep")
    d = None if d_rep is None else _si(d_rep, "length", "d_rep")
    curv = None if rms_curvature is None else _si(rms_curvature, "inverse length", "rms_curvature")
    la = w / E_star
    p = predict(rms_slope=s, interaction_range=dr, adhesion_length=la, d_rep=d,
                rms_curvature=curv, kappa_rep=kr, atomic_spacing=a0)  # fmt: skip
    return StickinessCriterion(
        contact_modulus=E_star,
        youngs_modulus=E,
        poisson=nu,
        work_of_adhesion=w,
        rms_slope=s,
        interaction_range=dr,
        d_rep=p.d_rep,
        d_rep_source=p.d_rep_source,
        rms_curvature=p.rms_curvature,
        kappa_rep=kr,
        atomic_spacing=a0,
        adhesion_length=la,
        adhesion_length_over_atomic_spacing=la / a0,
        repulsive_pressure=s * E_star / kr,
        attractive_pressure=w / dr,
        area_ratio=p.area_ratio,
        kappa_att=p.kappa_att,
        kappa=p.kappa,
        stickiness_parameter=p.stickiness_parameter,
        threshold=STICKINESS_THRESHOLD,
        margin=p.margin,
        sticky=p.sticky,
        necessary_condition_met=p.necessary_condition_met,
        max_sticky_contact_modulus=E_star * p.margin,
        max_sticky_d_rep=p.d_rep * p.margin**1.5,
    )
