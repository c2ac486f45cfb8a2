r"""Müser's generalised Tabor parameter: which adhesion regime, not whether it sticks.

M. H. Müser, Tribol. Lett. (2016) ("A dimensionless measure for adhesion and
effects of the range of adhesion in contacts of nominally flat surfaces"): Tabor's
parameter with the asperity radius of the rough surface,

.. math::
    \mu_T = \Bigl(\frac{R_c\, w^2}{E^{*2}\, \Delta r^3}\Bigr)^{1/3},
    \qquad R_c = 2/h''_{rms}

(the contact-scale radius of Pastewka & Robbins, Eq. 8). **This definition is not
verified against Müser's paper**: it has not been checked there whether Müser uses
R_c = 2/h''rms, 1/h''rms or another radius (and which prefactor); another radius scales
μT by a constant factor (2^(-1/3) for 1/h''rms) and so moves the regime boundary, but no
stickiness verdict, since none is given. Every result says so in its notes (JSON) and in
its verdict text. μT ≫ 1: short-range,
JKR-like adhesion with a crack-like contact edge and hysteresis; μT ≪ 1: long-range,
DMT-like. The parameter classifies the regime; it has no stickiness threshold, so it
gives **no verdict** (the threshold 1 is the regime boundary, reported as such).
"""

from __future__ import annotations

import math

from .result import Criterion, CriterionResult

KEY = "muser"
VALIDATED = (
    "GFMD simulations of rough adhesive contacts (Müser 2016; contact-mechanics challenge, "
    "Müser et al., Tribol. Lett. 65, 118 (2017)): the regime, not the onset of stickiness"
)
#: Said with every result: the definition is this library's reading, not checked.
UNVERIFIED = (
    "definition unverified against Müser (2016): Tabor's parameter with R_c = 2/h''rms "
    "(Pastewka & Robbins, Eq. 8) is this library's reading"
)
DESCRIPTOR = Criterion(
    key=KEY,
    name="Müser (generalised Tabor)",
    reference="M. H. Müser, Tribol. Lett. (2016), generalised Tabor parameter",
    formula="μT = (Rc w²/(E*² Δr³))^(1/3), Rc = 2/h''rms; μT > 1 JKR-like",
    parameter_symbol="μT",
    threshold=1.0,
    sticky_below=False,
    validated=VALIDATED,
    notes=("classifies the adhesion regime; gives no stickiness verdict", UNVERIFIED),
)


def evaluate(inputs) -> CriterionResult:
    """μT = (R_c w²/(E*² Δr³))^(1/3) with R_c = 2/h''rms; a regime, no verdict (dimensionless).

    The definition is unverified against Müser's paper (see the module docstring).
    """
    if math.isnan(inputs.interaction_range) or math.isnan(inputs.rms_curvature):
        return DESCRIPTOR.result(no_verdict_reason="needs the interaction range and h''rms")
    Rc = 2.0 / inputs.rms_curvature
    E, dr = inputs.contact_modulus, inputs.interaction_range
    mu = (Rc * inputs.work_of_adhesion**2 / (E**2 * dr**3)) ** (1.0 / 3.0)
    regime = "JKR-like" if mu > 1 else "DMT-like"
    why = (
        f"a regime indicator, not a stickiness rule (μT = {mu:.3g}: "
        + ("short-range, JKR-like" if mu > 1 else "long-range, DMT-like")
        + "; definition unverified)"
    )
    return DESCRIPTOR.result(
        mu, values={"asperity_radius": Rc, "regime": regime}, no_verdict_reason=why
    )
