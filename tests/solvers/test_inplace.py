"""The in-place vector updates of the smooth solver against plain NumPy expressions."""

import numpy as np
import pytest

from roughcontact.solvers._inplace import Workspace


@pytest.mark.parametrize("spread", [0.02, 0.5, 5.0], ids=["sparse", "medium", "dense"])
def test_band_is_every_site_the_law_can_reach(spread):
    # oracle: the definition min(gap, gap + reach s) < cutoff, site by site, for bands of
    # a few per cent to most of the grid (both of band()'s ways), repeatedly on one
    # workspace (it remembers whether the last band was dense)
    rng = np.random.default_rng(7)
    gap = 1.0 + rng.exponential(3.0, 4096)
    work = Workspace(gap)
    for step in range(6):
        s = spread * rng.standard_normal(gap.size)
        if step == 3:
            s = np.abs(s)  # only receding sites: the band is the sites already inside
        expected = np.flatnonzero(np.minimum(gap, gap + 4.0 * s) < 1.35)
        np.testing.assert_array_equal(work.band(gap, s, 4.0, 1.35), expected)


def test_updates_match_the_expressions():
    rng = np.random.default_rng(3)
    x, y = rng.standard_normal((2, 1000))
    work = Workspace(x)
    np.testing.assert_allclose(work.axpy(y.copy(), 0.3, x), y + 0.3 * x, rtol=1e-15)
    np.testing.assert_allclose(work.scale_sub(y.copy(), 0.7, x), 0.7 * y - x, rtol=1e-15)
    np.testing.assert_array_equal(work.negative(np.empty_like(x), x), -x)
    np.testing.assert_allclose(work.shifted(np.empty_like(x), x, 0.25), x - 0.25, rtol=1e-15)
    single = work.cast(np.empty(1000, np.float32), x)
    assert single.dtype == np.float32
    np.testing.assert_array_equal(single, x.astype(np.float32))
    np.testing.assert_array_equal(work.sites(x > 0), np.flatnonzero(x > 0))
