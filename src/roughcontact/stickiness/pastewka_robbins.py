r"""Pastewka & Robbins (2014), Eq. 10: the criterion of the paper this library reproduces.

L. Pastewka and M. O. Robbins, PNAS 111, 3298 (2014), Eq. 10, with d_rep from Eq. 9
(``d_rep = 4 h'_rms/h''_rms``) and κ_rep = 2::

    S = (h'_rms Δr/(κ_rep ℓa)) (h'_rms d_rep/(4 Δr))^(2/3)  <  π (3/16)^(2/3) = 1.029

sticky when S is below the threshold (equivalently κ_att < κ_rep). The computation is
:func:`roughcontact.theory.pastewka_robbins.predict` (the same code as
``roughcontact criterion`` and the path analysis); this module only wraps it in the
common :class:`~roughcontact.stickiness.result.CriterionResult`.
"""

from __future__ import annotations

import math

from ..theory.pastewka_robbins import KAPPA_REP, STICKINESS_THRESHOLD, predict
from .result import Criterion, CriterionResult

KEY = "pastewka_robbins"
VALIDATED = (
    "GFMD simulations of self-affine surfaces (H = 0.3 to 0.8, h'rms = 0.1 to 0.3, "
    "λs = 4 to 32 a0, short-range 9-3 wall; Pastewka & Robbins 2014, Fig. 4); judged on "
    "the reproduction's 72 parameter sets (reproduction/README.md)"
)
DESCRIPTOR = Criterion(
    key=KEY,
    name="Pastewka & Robbins",
    reference="L. Pastewka, M. O. Robbins, PNAS 111, 3298 (2014), Eq. 10",
    formula="S = (h'rms Δr/(κ_rep ℓa)) (h'rms d_rep/(4Δr))^(2/3) < π(3/16)^(2/3)",
    parameter_symbol="S",
    threshold=STICKINESS_THRESHOLD,
    sticky_below=True,
    validated=VALIDATED,
)


def evaluate(inputs, *, kappa_rep: float = KAPPA_REP) -> CriterionResult:
    """Eq. 10 on :class:`~roughcontact.stickiness.inputs.CriterionInputs` (needs Δr, h''rms)."""
    notes = (f"d_rep = 4 h'rms/h''rms (Eq. 9), kappa_rep = {kappa_rep:g}",)
    if math.isnan(inputs.interaction_range) or math.isnan(inputs.rms_curvature):
        why = "needs the interaction range and h''rms"
        return DESCRIPTOR.result(notes=notes, no_verdict_reason=why)
    p = predict(
        rms_slope=inputs.rms_slope,
        interaction_range=inputs.interaction_range,
        adhesion_length=inputs.adhesion_length,
        rms_curvature=inputs.rms_curvature,
        kappa_rep=kappa_rep,
    )
    values = {"d_rep": p.d_rep, "area_ratio": p.area_ratio, "kappa_att": p.kappa_att,
              "kappa": p.kappa}  # fmt: skip
    return DESCRIPTOR.result(p.stickiness_parameter, notes=notes, values=values)
