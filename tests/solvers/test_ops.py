"""Shared solver operators."""

import math

import numpy as np
import pytest

import roughcontact as rc
from roughcontact.solvers.fourier import compliance_operator, in_single_precision
from roughcontact.solvers.loop_control import RELIABLE_EVERY, ReliableUpdates
from roughcontact.solvers.reductions import dot


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


def test_anderson_bjorck_keeps_a_bracket():
    from roughcontact.solvers.roots import anderson_bjorck

    f = lambda x: x**3 - 1e-3  # noqa: E731
    a, b = 0.0, 1.0
    f_a, f_b = f(a), f(b)
    for x in (0.5, 0.2, 0.05, 0.12, 0.09, 0.101):
        a, f_a, b, f_b = anderson_bjorck(a, f_a, b, f_b, x, f(x))
        assert b == x and (f_a > 0) != (f_b > 0)
        assert min(a, b) <= 0.1 <= max(a, b)


@pytest.mark.parametrize(
    "f, a, b, root",
    [
        (lambda x: x**3 - 1e-3, 0.0, 1.0, 0.1),
        (lambda x: math.exp(8.0 * x) - 2.0, 0.0, 1.0, math.log(2.0) / 8.0),
        (lambda x: math.tan(x) - 1.0, 0.0, 1.5, math.pi / 4),
        (lambda x: math.expm1(60.0 * x) - 1.0, 0.0, 4.0, math.log(2.0) / 60.0),  # f(b) ~ 1e104
        (lambda x: 1.0 - math.exp(-40.0 * (x - 0.3)), 0.0, 2.0, 0.3),
    ],
)
def test_bracketed_root_against_closed_forms(f, a, b, root):
    from roughcontact.solvers.roots import bracketed_root

    calls = []

    def counted(x):
        calls.append(x)
        return f(x)

    # stop, as the line search does, at a fraction of |f| at the ends (Illinois' regula falsi
    # needs 13, 14, 10, > 60 and 32 evaluations for these; this 15, 13, 7, 28 and 12)
    tol = 1e-6 * min(abs(f(a)), abs(f(b)))
    x, evaluations = bracketed_root(counted, a, f(a), b, f(b), lambda fx: abs(fx) <= tol, 60)
    assert evaluations == len(calls) <= 30
    assert abs(f(x)) <= tol
    assert x == pytest.approx(root, rel=1e-5)
