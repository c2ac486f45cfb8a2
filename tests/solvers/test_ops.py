"""Shared solver operators."""

import math

import numpy as np
import pytest

import roughcontact as rc
from roughcontact.solvers._ops import (
    RELIABLE_EVERY,
    ReliableUpdates,
    compliance_operator,
    dot,
    in_single_precision,
)


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


@pytest.mark.parametrize("n", [7, 8192, 65536, 3 * 8192 + 1001, 257 * 263])
@pytest.mark.parametrize(
    "dtypes", [("float64", "float64"), ("float32", "float64"), ("float32",) * 2]
)
def test_dot_is_the_float64_inner_product(n, dtypes):
    # oracle: math.fsum of the products in float64 (correctly rounded), for the row-wise
    # path (float64, n >= DOT_CHUNK with and without a tail) and the einsum path
    rng = np.random.default_rng(n)
    a = rng.standard_normal(n).astype(dtypes[0])
    b = rng.standard_normal(n).astype(dtypes[1])
    exact = math.fsum(a.astype(np.float64) * b.astype(np.float64))
    got = dot(a, b)
    assert isinstance(got, float)
    # float64 accumulation: error ~ eps64 x (terms summed in sequence) x sum |a b|, far
    # below float32 accumulation (~1e-7 sum |a b|)
    bound = 1e-12 * math.fsum(np.abs(a.astype(np.float64) * b.astype(np.float64)))
    assert abs(got - exact) <= bound


def test_reliable_updates_schedule():
    # an exact evaluation when the tolerance is met, after a 1000-fold drop and every
    # RELIABLE_EVERY iterations; a restart when the exact residual is twice the iterated one
    reliable = ReliableUpdates(tol=1e-10)
    assert reliable.check(1.0, exact=True) is None
    assert reliable.check(2e-3, exact=False) is None
    assert reliable.check(1e-3, exact=False) == "refresh"
    assert reliable.check(3e-3, exact=True) == "restart"  # drift above twice the iterated 1e-3
    assert reliable.check(2e-3, exact=False) is None
    assert reliable.check(1e-10, exact=False) == "refresh"
    assert reliable.check(1e-10, exact=True) is None
    for _ in range(RELIABLE_EVERY):
        reliable.step()
    assert reliable.check(1.5e-10, exact=False) == "refresh"  # neither tol nor a drop
