r"""The stickiness criteria of the field, side by side.

Every criterion is one small module: its frozen
:class:`~roughcontact.stickiness.result.Criterion` descriptor (key, name, reference,
formula, parameter symbol, threshold, direction, validated regime) and the computation
of its parameter, evaluated on one
:class:`~roughcontact.stickiness.inputs.CriterionInputs` and answering with a
:class:`~roughcontact.stickiness.result.CriterionResult` (its dimensionless parameter,
threshold, verdict and where it has been validated):

=====================  ============================================================
``pastewka_robbins``   Eq. 10 of Pastewka & Robbins (2014); delegates to
                       :mod:`roughcontact.theory.pastewka_robbins` (as
                       :mod:`roughcontact.criterion` does in SI)
``persson_tosatti``    elastic energy of full contact vs w (Persson & Tosatti 2001)
``fuller_tabor``       θ = E*σs^(3/2)/(w Rs^(1/2)) over summit statistics (1975)
``dahlquist``          E < 0.1 MPa (tapes; SI only)
``muser``              generalised Tabor parameter, R = 1/h"rms: a regime, no verdict (2016)
=====================  ============================================================

The *measured* verdict of a simulation (sticky ⇔ 1/κ < 0 at A_rep = 1 % of A0) is
:mod:`roughcontact.analysis.stickiness`; how each criterion fares against it on the
reproduction's parameter sets is :mod:`roughcontact.studies.criteria_claims`.
"""

from __future__ import annotations

from . import dahlquist, fuller_tabor, muser, pastewka_robbins, persson_tosatti
from .inputs import (
    CriterionInputs,
    inputs_from_criterion,
    inputs_from_heights,
    self_affine_inputs,
    self_affine_moments,
)
from .result import NO_VERDICT, Criterion, CriterionResult
from .table import agreement, criteria_table, criteria_table_for_heights, format_table

__all__ = [
    "CRITERIA",
    "DESCRIPTORS",
    "NO_VERDICT",
    "Criterion",
    "CriterionInputs",
    "CriterionResult",
    "agreement",
    "criteria_table",
    "criteria_table_for_heights",
    "evaluate",
    "evaluate_all",
    "format_table",
    "inputs_from_criterion",
    "inputs_from_heights",
    "self_affine_inputs",
    "self_affine_moments",
]

_MODULES = (pastewka_robbins, persson_tosatti, fuller_tabor, dahlquist, muser)
#: Every criterion by key, in the order of the tables.
CRITERIA = {m.KEY: m.evaluate for m in _MODULES}
#: Every criterion's :class:`~roughcontact.stickiness.result.Criterion` (what it is:
#: name, reference, formula, threshold, where validated) by key, in table order.
DESCRIPTORS = {m.KEY: m.DESCRIPTOR for m in _MODULES}


def evaluate(key: str, inputs: CriterionInputs, **options) -> CriterionResult:
    """One criterion by its key (:data:`CRITERIA`) on ``inputs``."""
    from .._validate import ParameterError

    if key not in CRITERIA:
        raise ParameterError(f"criterion must be one of {list(CRITERIA)}, got {key!r}")
    return CRITERIA[key](inputs, **options)


def evaluate_all(inputs: CriterionInputs) -> list[CriterionResult]:
    """Every criterion of :data:`CRITERIA` on ``inputs``, in table order."""
    return [f(inputs) for f in CRITERIA.values()]
