r"""The one stickiness rule, and how κ-like quantities are combined over realisations.

**Measured verdict.** Pastewka & Robbins, PNAS 111, 3298 (2014): "the surfaces become
sticky when κ changes sign". At the target repulsive area (1 % of :math:`A_0`) on the
approach,

.. math::
    \frac1\kappa = \frac{N}{h'_{rms} E^* A_{rep}} = \frac1{\kappa_{rep}} - \frac1{\kappa_{att}},

and a path is **sticky** when :math:`1/\kappa < 0`: the surfaces hold together under
tension at that contact area. The pull-off force is reported beside the verdict, never
mixed into it (a few adhering asperities give a small pull-off on any adhesive surface).

**Predicted verdict.** Eq. 10, equivalently :math:`\kappa_{att} < \kappa_{rep}`, is the
same rule applied to the predicted :math:`1/\kappa = 1/\kappa_{rep} - 1/\kappa_{att}^{Eq. 7}`.

**Over realisations (seeds).** :math:`1/\kappa` is :math:`N/A_{rep}` up to constants:
an additive quantity, finite through the onset of stickiness, while κ itself diverges
there and changes sign. So the mean and the confidence interval are taken of
:math:`1/\kappa` (likewise :math:`1/\kappa_{rep}`, :math:`1/\kappa_{att}`) and
:math:`\kappa = 1/\overline{(1/\kappa)}` is reported; κ is never averaged. The verdict
over seeds is "sticky" when the whole interval of :math:`1/\kappa` lies below zero,
"not sticky" when it lies above, and "undecided" when it contains zero. With a single
realisation there is no interval and the sign decides.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validate import ParameterError, json_ready

__all__ = [
    "NOT_STICKY",
    "STICKY",
    "UNDECIDED",
    "VERDICTS",
    "InverseMean",
    "inverse_mean",
    "is_sticky",
    "verdict",
]

STICKY = "sticky"
NOT_STICKY = "not sticky"
UNDECIDED = "undecided"
#: Every verdict the rule gives.
VERDICTS = (STICKY, NOT_STICKY, UNDECIDED)


def _inverse(kappa: float) -> float:
    """1/κ with 1/±inf = 0 (no load at the target area: the onset itself)."""
    k = float(kappa)
    return 0.0 if math.isinf(k) else (math.nan if k == 0 or math.isnan(k) else 1.0 / k)


def is_sticky(kappa: float) -> bool | None:
    """The measured rule for one path: sticky ⇔ :math:`1/\\kappa < 0` (None if κ is NaN).

    ``kappa`` is :math:`h'_{rms}E^*A_{rep}/N` at the target area [dimensionless];
    ``inf`` (zero load at the target area) is the onset and counts as not sticky.
    """
    inv = _inverse(kappa)
    return None if math.isnan(inv) else bool(inv < 0)


def verdict(low: float, high: float) -> str:
    """The rule on an interval ``[low, high]`` of :math:`1/\\kappa` (or a single value twice).

    "sticky" if ``high < 0``, "not sticky" if ``low >= 0``, else "undecided"; NaN bounds
    give "undecided".
    """
    if math.isnan(low) or math.isnan(high):
        return UNDECIDED
    if high < 0:
        return STICKY
    if low >= 0:
        return NOT_STICKY
    return UNDECIDED


@dataclass(frozen=True)
class InverseMean:
    """Mean of :math:`1/x` over realisations and its confidence interval.

    ``n`` realisations with a finite value; ``mean``, ``low``, ``high`` bound
    :math:`\\overline{1/x}` (Student-t interval at ``confidence``; NaN for n < 2);
    ``values`` the per-realisation :math:`1/x`. ``value = 1/mean`` is the reported x
    (``inf`` when the mean is 0); ``value_low``/``value_high`` the interval mapped back to
    x, which is unbounded (``-inf``, ``inf``) when the interval of 1/x contains 0.
    """

    n: int
    mean: float
    low: float
    high: float
    confidence: float
    values: tuple[float, ...]

    @property
    def value(self) -> float:
        return _inverse(self.mean) if self.mean != 0 else math.inf

    @property
    def value_low(self) -> float:
        """Lower end of the interval of x (from the upper end of 1/x)."""
        if math.isnan(self.high) or self.low <= 0 <= self.high:
            return math.nan if math.isnan(self.high) else -math.inf
        return 1.0 / self.high

    @property
    def value_high(self) -> float:
        """Upper end of the interval of x (from the lower end of 1/x)."""
        if math.isnan(self.low) or self.low <= 0 <= self.high:
            return math.nan if math.isnan(self.low) else math.inf
        return 1.0 / self.low

    @property
    def verdict(self) -> str:
        """The stickiness rule applied to this mean of 1/κ (module docstring)."""
        if self.n == 0:
            return UNDECIDED
        if self.n == 1:
            return verdict(self.mean, self.mean)
        return verdict(self.low, self.high)

    def to_dict(self) -> dict:
        out = json_ready(self)
        out["values"] = [None if not math.isfinite(v) else v for v in self.values]
        for key in ("value", "value_low", "value_high", "verdict"):
            v = getattr(self, key)
            out[key] = None if isinstance(v, float) and not math.isfinite(v) else v
        return out


def inverse_mean(values, *, confidence: float = 0.95) -> InverseMean:
    """Aggregate κ-like values over realisations through their inverses (module docstring).

    Parameters
    ----------
    values : sequence of float
        Per-realisation κ, κ_rep or κ_att [dimensionless]; ``±inf`` (no load of that
        kind) enters as 1/x = 0, NaN (no value: a failed task) is left out.
    confidence : float
        Two-sided confidence level of the Student-t interval of the mean of 1/x, in (0, 1).

    Returns
    -------
    InverseMean
    """
    if not 0 < confidence < 1:
        raise ParameterError(f"confidence must be in (0, 1), got {confidence!r}")
    inv = np.array([_inverse(v) for v in np.asarray(values, dtype=float).ravel()])
    inv = inv[np.isfinite(inv)]
    n = int(inv.size)
    if n == 0:
        return InverseMean(0, math.nan, math.nan, math.nan, confidence, ())
    mean = float(inv.mean())
    if n < 2:
        return InverseMean(n, mean, math.nan, math.nan, confidence, tuple(inv.tolist()))
    from scipy.stats import t

    half = float(t.ppf(0.5 + confidence / 2, n - 1)) * float(inv.std(ddof=1)) / math.sqrt(n)
    return InverseMean(n, mean, mean - half, mean + half, confidence, tuple(inv.tolist()))
