r"""Fuller & Tabor (1975): the adhesion parameter of a Greenwood–Williamson summit bed.

K. N. G. Fuller and D. Tabor, Proc. R. Soc. Lond. A 345, 327 (1975): JKR summits of
radius R_s with Gaussian heights of spread σ_s,

.. math::
    \theta = \frac{E^* \sigma_s^{3/2}}{w R_s^{1/2}}

(:func:`roughcontact.theory.greenwood_williamson.fuller_tabor_parameter`), with σ_s
and R_s the summit statistics of Nayak (1971) and McCool (1986) from the spectral
moments. Fuller & Tabor's pull-off falls steeply with θ and never reaches
exactly zero, so the threshold is a convention: here **sticky if θ < 10**, where the
pull-off of the summit bed is still ≳ 4 % of the smooth-summit value
(:func:`~roughcontact.theory.greenwood_williamson.greenwood_williamson`, JKR summits:
94 %, 36 % and 4 % at θ = 0.3, 3 and 10).
"""

from __future__ import annotations

from ..theory.greenwood_williamson import fuller_tabor_parameter
from .result import Criterion, CriterionResult

KEY = "fuller_tabor"
#: Sticky below this θ (a convention, see the module docstring).
THRESHOLD = 10.0
VALIDATED = (
    "experiments of rubber spheres on rough perspex (Fuller & Tabor 1975); Pastewka & "
    "Robbins 2014 found simulations qualitatively inconsistent with Greenwood–Williamson "
    "theories"
)
DESCRIPTOR = Criterion(
    key=KEY,
    name="Fuller & Tabor",
    reference="K. N. G. Fuller, D. Tabor, Proc. R. Soc. Lond. A 345, 327 (1975)",
    formula="θ = E* σs^(3/2)/(w Rs^(1/2)) < 10 (Nayak/McCool summits)",
    parameter_symbol="θ",
    threshold=THRESHOLD,
    sticky_below=True,
    validated=VALIDATED,
    notes=(
        "threshold θ = 10 is a convention (pull-off ≈ 4 % of the smooth value)",
        "E* in θ (authors using K = 4E*/3 get a θ 4/3 larger)",
    ),
)


def evaluate(inputs, *, threshold: float = THRESHOLD) -> CriterionResult:
    """θ = E* σ_s^(3/2)/(w R_s^(1/2)) < ``threshold`` (needs h_rms and h''_rms)."""
    summits = inputs.summits()
    if summits is None:
        why = "needs h_rms and h''rms (summit statistics)"
        return DESCRIPTOR.result(threshold=threshold, no_verdict_reason=why)
    theta = fuller_tabor_parameter(summits.height_std, summits.radius,
                                   inputs.contact_modulus, inputs.work_of_adhesion)  # fmt: skip
    values = {"summit_height_std": summits.height_std, "summit_radius": summits.radius,
              "summit_density": summits.density, "bandwidth": summits.bandwidth}  # fmt: skip
    return DESCRIPTOR.result(theta, threshold=threshold, values=values)
