r"""Dahlquist's criterion for pressure-sensitive adhesives: a modulus rule.

C. A. Dahlquist, in *Treatise on Adhesion and Adhesives*, vol. 2, ed. R. L. Patrick
(Dekker, 1969), p. 219; and *Adhesion: Fundamentals and Practice* (1966). Tapes are
tacky when their modulus (at the ~1 s contact time of a tack test) is below about
0.1 MPa (a creep compliance above 1e-6 cm²/dyn); roughness and w do not enter:

.. math::
    D = E / (0.1\,\mathrm{MPa}) < 1 .

E is Young's modulus when known, else the contact modulus E* (E* = E/(1-ν²) exceeds E
by at most 4/3). Needs SI: in lattice units there is no scale and no verdict.
"""

from __future__ import annotations

import math

from .result import Criterion, CriterionResult

KEY = "dahlquist"
#: 0.1 MPa [Pa].
THRESHOLD_PA = 1.0e5
VALIDATED = "empirical rule for pressure-sensitive adhesives (tapes); no roughness"
DESCRIPTOR = Criterion(
    key=KEY,
    name="Dahlquist",
    reference="C. A. Dahlquist, Treatise on Adhesion and Adhesives 2, 219 (1969)",
    formula="D = E/(0.1 MPa) < 1",
    parameter_symbol="D",
    threshold=1.0,
    sticky_below=True,
    validated=VALIDATED,
)


def evaluate(inputs) -> CriterionResult:
    """D = E/0.1 MPa < 1 (SI inputs only; E [Pa], else E*)."""
    notes = []
    E = inputs.youngs_modulus
    if math.isnan(E):
        E = inputs.contact_modulus
        notes.append("Young's modulus unknown: E* used (at most 4/3 larger than E)")
    if inputs.units != "SI":
        why = "a modulus rule in Pa; lattice units carry no scale"
        return DESCRIPTOR.result(notes=notes, values={"modulus": E}, no_verdict_reason=why)
    return DESCRIPTOR.result(E / THRESHOLD_PA, notes=notes, values={"modulus": E})
