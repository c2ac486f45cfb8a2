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

from .result import CriterionResult, decide, no_verdict

KEY = "dahlquist"
#: 0.1 MPa [Pa].
THRESHOLD_PA = 1.0e5
VALIDATED = "empirical rule for pressure-sensitive adhesives (tapes); no roughness"


def evaluate(inputs) -> CriterionResult:
    """D = E/0.1 MPa < 1 (SI inputs only)."""
    notes = []
    E = inputs.youngs_modulus
    if math.isnan(E):
        E = inputs.contact_modulus
        notes.append("Young's modulus unknown: E* used (at most 4/3 larger than E)")
    if inputs.units != "SI":
        D = math.nan
        sticky, verdict, margin = no_verdict("a modulus rule in Pa; lattice units carry no scale")
    else:
        D = E / THRESHOLD_PA
        sticky, verdict, margin = decide(D, 1.0, True)
    return CriterionResult(
        key=KEY,
        name="Dahlquist",
        reference="C. A. Dahlquist, Treatise on Adhesion and Adhesives 2, 219 (1969)",
        formula="D = E/(0.1 MPa) < 1",
        parameter_symbol="D",
        parameter=D,
        threshold=1.0,
        sticky_below=True,
        sticky=sticky,
        verdict=verdict,
        margin=margin,
        validated=VALIDATED,
        notes=tuple(notes),
        values={"modulus": E},
    )
