"""The one result type of every stickiness criterion."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from .._validate import json_safe

__all__ = ["NO_VERDICT", "Criterion", "CriterionResult"]

#: Verdict words (the first two as in :mod:`roughcontact.analysis.stickiness`).
STICKY, NOT_STICKY, NO_VERDICT = "sticky", "not sticky", "no verdict"


@dataclass(frozen=True)
class CriterionResult:
    """One criterion evaluated on one surface and material pair.

    Attributes
    ----------
    key : str
        Registry name (``"pastewka_robbins"``, ``"persson_tosatti"``, ...).
    name, reference, formula : str
        Human name, the paper, the formula in words/symbols.
    parameter_symbol : str
        The dimensionless parameter's symbol.
    parameter : float
        Its value (NaN when the inputs do not allow it).
    threshold : float
        The value at which the verdict changes (NaN for a regime indicator).
    sticky_below : bool
        True when ``parameter < threshold`` means sticky.
    sticky : bool or None
        The verdict; None when there is none.
    verdict : str
        ``"sticky"``, ``"not sticky"`` or ``"no verdict: <why>"``.
    margin : float
        Distance from the threshold as a factor: ``threshold/parameter`` when sticky
        below, ``parameter/threshold`` otherwise (> 1 sticky; NaN without a verdict).
    validated : str
        Where it has been checked against simulation or experiment, in words.
    notes : tuple of str
        Model choices and caveats that bear on this verdict.
    values : dict
        Intermediate quantities (units of the inputs).
    """

    key: str
    name: str
    reference: str
    formula: str
    parameter_symbol: str
    parameter: float
    threshold: float
    sticky_below: bool
    sticky: bool | None
    verdict: str
    margin: float
    validated: str
    notes: tuple = ()
    values: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        """JSON-ready dict (non-finite numbers become None)."""
        from dataclasses import asdict

        out = asdict(self)
        out["notes"] = list(self.notes)
        return json_safe(out)


@dataclass(frozen=True)
class Criterion:
    """What a criterion *is*, written once: everything of its result but the numbers.

    Each criterion module holds one of these (``DESCRIPTOR``) and computes only its
    parameter; :meth:`result` turns (descriptor, parameter, notes, values) into the
    :class:`CriterionResult`, so the fifteen fields are assembled in one place.

    Attributes
    ----------
    key, name, reference, formula, parameter_symbol : str
        As in :class:`CriterionResult`.
    threshold : float
        Default threshold (a criterion may take another one per call).
    sticky_below : bool
        True when ``parameter < threshold`` means sticky.
    validated : str
        Where it has been checked against simulation or experiment, in words.
    notes : tuple of str
        Model choices stated with every result of this criterion.
    """

    key: str
    name: str
    reference: str
    formula: str
    parameter_symbol: str
    threshold: float
    sticky_below: bool
    validated: str
    notes: tuple = ()

    def result(self, parameter=math.nan, *, notes=(), values=None, threshold=None,
               no_verdict_reason=None) -> CriterionResult:  # fmt: skip
        """The :class:`CriterionResult` of ``parameter`` (dimensionless).

        ``threshold``: this call's threshold (default :attr:`threshold`);
        ``no_verdict_reason``: give no verdict, and say why (a regime indicator, missing
        inputs); ``notes`` are added after the descriptor's own; ``values`` are the
        intermediate quantities (units of the inputs).
        """
        threshold = self.threshold if threshold is None else float(threshold)
        parameter = float(parameter)
        if no_verdict_reason is not None:
            sticky, verdict, margin = no_verdict(no_verdict_reason)
        else:
            sticky, verdict, margin = decide(parameter, threshold, self.sticky_below)
        return CriterionResult(
            key=self.key,
            name=self.name,
            reference=self.reference,
            formula=self.formula,
            parameter_symbol=self.parameter_symbol,
            parameter=parameter,
            threshold=threshold,
            sticky_below=self.sticky_below,
            sticky=sticky,
            verdict=verdict,
            margin=margin,
            validated=self.validated,
            notes=(*self.notes, *notes),
            values=dict(values or {}),
        )


def decide(parameter: float, threshold: float, sticky_below: bool):
    """``(sticky, verdict, margin)`` of a parameter against its threshold."""
    if not math.isfinite(parameter):
        return None, f"{NO_VERDICT}: the parameter could not be computed", math.nan
    sticky = parameter < threshold if sticky_below else parameter > threshold
    if sticky_below:
        margin = threshold / parameter if parameter > 0 else math.inf
    else:
        margin = parameter / threshold
    return bool(sticky), STICKY if sticky else NOT_STICKY, margin


def no_verdict(reason: str):
    """``(None, "no verdict: <reason>", NaN)``."""
    return None, f"{NO_VERDICT}: {reason}", math.nan
