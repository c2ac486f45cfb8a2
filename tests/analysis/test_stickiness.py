"""The one stickiness rule and the aggregation of κ over seeds through 1/κ."""

import math

import numpy as np
import pytest
from scipy import stats

from roughcontact import ParameterError
from roughcontact.analysis.stickiness import (
    NOT_STICKY,
    STICKY,
    UNDECIDED,
    inverse_mean,
    is_sticky,
    verdict,
)


def test_single_path_rule_is_the_sign_of_one_over_kappa():
    assert is_sticky(-180.0) is True and is_sticky(-0.5) is True
    assert is_sticky(7.2) is False and is_sticky(math.inf) is False  # zero load: the onset
    assert is_sticky(-math.inf) is False  # 1/κ = 0 either way
    assert is_sticky(math.nan) is None


def test_interval_rule():
    assert verdict(-0.3, -0.1) == STICKY
    assert verdict(0.1, 0.3) == NOT_STICKY
    assert verdict(-0.1, 0.3) == UNDECIDED
    assert verdict(math.nan, 0.1) == UNDECIDED


def test_seeds_across_the_divergence_are_averaged_as_inverses():
    # the seeds: κ = −180, +7.2, +15.4 averaged to −52.5 ± 110; N/A_rep is additive
    kappas = [-180.0, 7.2, 15.4]
    r = inverse_mean(kappas)
    inv = np.array([1 / k for k in kappas])
    assert r.n == 3 and r.values == pytest.approx(tuple(inv))
    assert r.mean == pytest.approx(inv.mean())
    assert r.value == pytest.approx(1 / inv.mean())  # 15.1, not −52.5
    half = stats.t.ppf(0.975, 2) * inv.std(ddof=1) / math.sqrt(3)
    assert (r.low, r.high) == pytest.approx((inv.mean() - half, inv.mean() + half))
    # the interval of 1/κ straddles 0 → undecided, κ's interval is unbounded
    assert r.low < 0 < r.high and r.verdict == UNDECIDED
    assert r.value_low == -math.inf and r.value_high == math.inf


def test_clear_cases_and_mapped_interval():
    sticky = inverse_mean([-3.0, -4.0, -5.0])
    assert sticky.verdict == STICKY and sticky.value < 0
    assert sticky.value_low <= sticky.value <= sticky.value_high
    plain = inverse_mean([2.0, 2.2, 2.4])
    assert plain.verdict == NOT_STICKY
    assert plain.value == pytest.approx(1 / np.mean([1 / 2.0, 1 / 2.2, 1 / 2.4]))
    assert plain.value_low < plain.value < plain.value_high


def test_no_attraction_and_missing_values():
    r = inverse_mean([math.inf, math.inf, math.nan])  # κ_att without attraction; a failed task
    assert r.n == 2 and r.mean == 0 and math.isinf(r.value)
    one = inverse_mean([-7.0])
    assert one.n == 1 and math.isnan(one.low) and one.verdict == STICKY  # the sign decides
    none = inverse_mean([math.nan])
    assert none.n == 0 and none.verdict == UNDECIDED
    assert inverse_mean([1.0, 2.0]).verdict == UNDECIDED  # two seeds: t(1) = 12.7, wide
    d = inverse_mean([1.0, 2.0, 1.5]).to_dict()
    assert d["verdict"] == NOT_STICKY and d["value"] == pytest.approx(1 / np.mean([1, 0.5, 2 / 3]))
    with pytest.raises(ParameterError, match="confidence"):
        inverse_mean([1.0], confidence=1.5)
