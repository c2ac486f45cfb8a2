r"""Persson & Tosatti (2001): the elastic energy of full conformal contact against w.

B. N. J. Persson and E. Tosatti, J. Chem. Phys. 115, 5597 (2001). Pressing a flat
elastic half-space into full contact with the rough surface stores (per nominal area)

.. math::
    \frac{U_{el}}{A_0} = \frac{E^*}{4}\int d^2q\, |q|\, C(q) = \frac{E^*}{4}
    \langle|\nabla^{1/2}h|^2\rangle
    \quad\Bigl(= \frac{\pi E^*}{2}\int_{q_0}^{q_1} dq\, q^2 C(q)\Bigr),

with C(q) normalised as ``h_rms^2 = ∫d²q C(q)`` (the same number as SurfaceTopography's
``elastic_energy``). The interface gains ``w A*`` with the true area
``A*/A0 ≈ 1 + h'_rms^2/2`` (small slopes), so the effective work of adhesion is
``w_eff = w A*/A0 - U_el/A0`` and the surfaces stick (full contact is favoured) when

.. math::
    \Pi = \frac{U_{el}/A_0}{w\,(1 + h'^2_{rms}/2)} < 1 .

Assumes full contact (soft solids, JKR-like short-range adhesion); it ignores the
interaction range Δr.
"""

from __future__ import annotations

import math

from .result import Criterion, CriterionResult

KEY = "persson_tosatti"
VALIDATED = (
    "peel/pull-off experiments of soft elastomers on rough hard surfaces (Dalvi et al., "
    "PNAS 116, 25484 (2019)); not against simulations of hard solids with short-range "
    "adhesion"
)
DESCRIPTOR = Criterion(
    key=KEY,
    name="Persson & Tosatti",
    reference="B. N. J. Persson, E. Tosatti, J. Chem. Phys. 115, 5597 (2001)",
    formula="Π = (E*/4)∫d²q|q|C(q) / (w (1 + h'rms²/2)) < 1",
    parameter_symbol="Π",
    threshold=1.0,
    sticky_below=True,
    validated=VALIDATED,
    notes=(
        "full conformal contact assumed; the interaction range does not enter",
        "true area A*/A0 = 1 + h'rms²/2 (small slopes)",
    ),
)


def elastic_energy_full_contact(contact_modulus, half_derivative_variance):
    """``U_el/A0 = (E*/4) ∫d²q |q| C(q)`` [pressure × length]."""
    return contact_modulus / 4.0 * half_derivative_variance


def evaluate(inputs) -> CriterionResult:
    """Π = U_el/(A0 w (1 + h'rms²/2)) < 1 (needs the half-derivative variance M_1)."""
    if math.isnan(inputs.half_derivative_variance):
        why = "needs the power spectrum (M_1 = ∫d²q |q| C)"
        return DESCRIPTOR.result(no_verdict_reason=why)
    u = elastic_energy_full_contact(inputs.contact_modulus, inputs.half_derivative_variance)
    area = 1.0 + inputs.rms_slope**2 / 2.0
    values = {
        "elastic_energy_per_area": u,
        "true_area_ratio": area,
        "effective_work_of_adhesion": inputs.work_of_adhesion * area - u,
    }
    return DESCRIPTOR.result(u / (inputs.work_of_adhesion * area), values=values)
