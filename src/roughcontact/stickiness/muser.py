r"""Müser's generalised Tabor parameter: which adhesion regime, not whether it sticks.

M. H. Müser, "A dimensionless measure for adhesion and effects of the range of adhesion
in contacts of nominally flat surfaces", Tribol. Lett. (2016): Tabor's parameter
with the radius of curvature of the rough surface's asperities,

.. math::
    \mu_T = \frac{R^{1/3}\,\ell_a^{2/3}}{\Delta r}
          = \Bigl(\frac{R\, w^2}{E^{*2}\, \Delta r^3}\Bigr)^{1/3},
    \qquad R = 1/h''_{rms},\quad \ell_a = w/E^*,

the definition with which the Adhesion package (ContactEngineering, Sanner & Pastewka;
its example ``adhesive_simulation_rough``) evaluates "the generalized Tabor parameter
following Martin Müser" (``R = 1/h''rms``, ``mu = R^(1/3) (w/E*)^(2/3)/rho``). The
contact-scale radius of Pastewka & Robbins' Eq. 8, ``R_c = 2/h''rms``, gives a μT
larger by ``2^(1/3)`` (1.26); it is shown beside it (``values["mu_T_rc"]``), so a reader
who uses that radius has the number too. μT ≫ 1: short-range, JKR-like adhesion with a
crack-like contact edge and hysteresis; μT ≪ 1: long-range, DMT-like. The parameter
classifies the regime; it has no stickiness threshold, so it gives **no verdict** (the
threshold 1 is the regime boundary, reported as such).
"""

from __future__ import annotations

import math

from .result import Criterion, CriterionResult

KEY = "muser"
VALIDATED = (
    "GFMD simulations of rough adhesive contacts (Müser 2016; contact-mechanics challenge, "
    "Müser et al., Tribol. Lett. 65, 118 (2017)): the regime, not the onset of stickiness"
)
#: Said with every result: which radius, where it comes from, and the other one.
DEFINITION = (
    "R = 1/h''rms as in the Adhesion package's example of Müser's parameter "
    "(μT = R^(1/3) ℓa^(2/3)/Δr, ℓa = w/E*); with Pastewka & Robbins' R_c = 2/h''rms "
    "(Eq. 8) μT is 2^(1/3) = 1.26 times larger (values: mu_T_rc)"
)
#: Kept for old imports: the note that replaced "definition unverified".
UNVERIFIED = DEFINITION
DESCRIPTOR = Criterion(
    key=KEY,
    name="Müser (generalised Tabor)",
    reference="M. H. Müser, Tribol. Lett. (2016), generalised Tabor parameter",
    formula="μT = R^(1/3) ℓa^(2/3)/Δr = (R w²/(E*² Δr³))^(1/3), R = 1/h''rms; μT > 1 JKR-like",
    parameter_symbol="μT",
    threshold=1.0,
    sticky_below=False,
    validated=VALIDATED,
    notes=("classifies the adhesion regime; gives no stickiness verdict", DEFINITION),
)


def evaluate(inputs) -> CriterionResult:
    """μT = (R w²/(E*² Δr³))^(1/3) with R = 1/h''rms; a regime, no verdict (dimensionless).

    ``values``: ``asperity_radius`` R [length of the inputs], ``mu_T_rc`` (μT with
    R_c = 2/h''rms, Pastewka & Robbins' Eq. 8), ``regime``.
    """
    if math.isnan(inputs.interaction_range) or math.isnan(inputs.rms_curvature):
        return DESCRIPTOR.result(no_verdict_reason="needs the interaction range and h''rms")
    R = 1.0 / inputs.rms_curvature
    E, dr = inputs.contact_modulus, inputs.interaction_range
    mu = (R * inputs.work_of_adhesion**2 / (E**2 * dr**3)) ** (1.0 / 3.0)
    mu_rc = mu * 2.0 ** (1.0 / 3.0)
    regime = "JKR-like" if mu > 1 else "DMT-like"
    why = (
        f"a regime indicator, not a stickiness rule (μT = {mu:.3g} with R = 1/h''rms: "
        + ("short-range, JKR-like" if mu > 1 else "long-range, DMT-like")
        + f"; {mu_rc:.3g} with R_c = 2/h''rms)"
    )
    return DESCRIPTOR.result(
        mu,
        values={"asperity_radius": R, "mu_T_rc": mu_rc, "regime": regime},
        no_verdict_reason=why,
    )
