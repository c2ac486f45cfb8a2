"""Shared solver operators."""

import numpy as np
import pytest

import roughcontact as rc
from roughcontact.solvers._ops import compliance_operator, in_single_precision


@pytest.mark.parametrize("thickness", [None, 8.0])
def test_operator_in_single_precision(thickness):
    sub = rc.Substrate((64, 48), thickness=thickness, poisson=0.3)
    green = compliance_operator(sub)
    green32 = in_single_precision(green)
    x = np.random.default_rng(1).standard_normal(64 * 48)
    exact, single = green(x), green32(x)
    assert single.dtype == np.float64  # the caller's precision comes back
    # float32 rounding, nothing more
    assert 1e-10 < np.abs(single - exact).max() / np.abs(exact).max() < 1e-5
    x32 = x.astype(np.float32)  # a float32 computation is left alone
    np.testing.assert_array_equal(green32(x32), green(x32))
