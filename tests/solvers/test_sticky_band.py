"""The smooth solver's sticky band (the line search's sites kept between iterations)."""

import numpy as np
import pytest

import roughcontact as rc
from roughcontact.interactions import SmoothLJ93
from roughcontact.solvers import smooth
from roughcontact.solvers._inplace import StickyBand, Workspace
from roughcontact.solvers.line_search import line_minimum


@pytest.mark.parametrize("patch", [False, True], ids=["periodic", "patch"])
def test_the_band_covers_every_site_the_law_can_reach(patch):
    # oracle: min(gap, gap + alpha s) < cutoff for some 0 <= alpha <= 4, site by site, on
    # every iteration of a random walk of the gap (steps alpha s as the solver takes them)
    rng = np.random.default_rng(11)
    gap = 1.0 + rng.exponential(1.5, 4096)
    mask = None
    if patch:
        mask = np.zeros(gap.size, bool)
        mask[: gap.size // 2] = True
    work = Workspace(gap, mask)
    band = StickyBand(work, 1.35, 0.1)
    law = SmoothLJ93.from_adhesion_length(0.005)
    selected = 0
    for step in range(40):
        # mostly a slow approach of every site (the band must be widened in time), now
        # and then a fast one
        s = -0.02 * rng.random(gap.size) if step % 9 else 0.2 * rng.standard_normal(gap.size)
        chosen = band.select(gap, s, 4.0, law.curvature)
        reach = np.minimum(gap, gap + 4.0 * s) < 1.35
        if mask is not None:
            reach &= mask
        if chosen is None:  # too fast an approach: the line search's own band
            band.moved(0.5, None, {})
        else:
            selected += 1
            sites, s_sites, gap_sites, curvature = chosen
            assert np.all(np.isin(np.flatnonzero(reach), sites))
            np.testing.assert_allclose(s_sites, s[sites], rtol=0, atol=0)
            np.testing.assert_allclose(gap_sites, gap[sites], rtol=1e-15)
            np.testing.assert_allclose(curvature, law.curvature(gap[sites]), rtol=1e-15)
            trial_gap = gap_sites + 0.5 * s_sites
            band.moved(0.5, sites, {"gap": trial_gap, "curvature": law.curvature(trial_gap)})
        gap = gap + 0.5 * s
    assert selected >= 20  # on most iterations (a fast approach: 3 skipped)


def test_the_line_search_on_the_band_is_the_one_on_its_own_sites():
    # the same step and pressure (to rounding) on a superset of the sites, with the
    # curvature at alpha = 0 given and the last trial's gap and curvature returned
    rng = np.random.default_rng(5)
    law = SmoothLJ93.from_adhesion_length(0.05)
    gap = 0.8 + rng.exponential(1.0, 8192)
    s = 0.05 * rng.standard_normal(gap.size)
    kw, ks = rng.standard_normal((2, gap.size)) * 1e-2
    slope0 = float(s @ (kw - law.pressure(gap)))
    if slope0 > 0:
        s = -s
        slope0 = -slope0
    alpha, sites, p = line_minimum(law, gap, s, kw, ks, slope0, rtol=0.05, with_pressure=True)
    wide = np.flatnonzero(gap < law.cutoff + 1.0)
    trial = {}
    band = (wide, s[wide], gap[wide], law.curvature(gap[wide]))
    alpha2, sites2, p2 = line_minimum(
        law, gap, s, kw, ks, slope0, rtol=0.05, with_pressure=True, band=band, trial=trial
    )
    assert sites2 is wide
    assert alpha2 == pytest.approx(alpha, rel=1e-12)
    full, full2 = np.zeros_like(gap), np.zeros_like(gap)
    full[sites], full2[sites2] = p, p2
    np.testing.assert_allclose(full2, full, rtol=1e-10, atol=1e-12 * np.abs(p).max())
    np.testing.assert_allclose(trial["gap"], gap[wide] + alpha2 * s[wide], rtol=1e-15)
    np.testing.assert_allclose(trial["curvature"], law.curvature(trial["gap"]), rtol=1e-15)


class _NoBand(StickyBand):
    def select(self, gap, s, reach, curvature):
        self.sites = None
        return None


@pytest.mark.parametrize("la", [0.005, 0.05])
@pytest.mark.parametrize("dtype", ["float64", "float32"])
def test_a_path_with_the_band_is_the_path_without(monkeypatch, la, dtype):
    # the warm-started approach of benchmarks/adhesive.py (64²): the same iterations and
    # states as with the line search's own band on every iteration
    h = rc.self_affine((64, 64), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=3)
    sub = rc.Substrate((64, 64))
    law = SmoothLJ93.from_adhesion_length(la)
    d_start = float(h.max()) + 1.0  # to the hard wall's offset at 5e-4 E* (+ a0), 5 steps
    d_end = float(rc.solve(h, sub, rc.HardWall(), load=5e-4, tol=1e-8).offset) + 1.0
    offsets = d_start - (d_start - d_end) * np.arange(1, 6) / 5

    def path():
        out, state = [], None
        for d in offsets:
            state = rc.solve(h, sub, law, offset=float(d), initial=state, tol=1e-6, dtype=dtype)
            assert state.converged
            out.append(state)
        return out

    with_band = path()
    monkeypatch.setattr(smooth, "StickyBand", _NoBand)
    without = path()
    for a, b in zip(with_band, without, strict=True):
        assert abs(a.iterations - b.iterations) <= 2
        assert np.max(np.abs(a.gap - b.gap)) < (1e-7 if dtype == "float64" else 1e-4)


def test_the_fused_law_evaluation_is_the_two_evaluations():
    for la in (0.005, 0.05):
        law = SmoothLJ93.from_adhesion_length(la)
        for dtype in (np.float64, np.float32):
            # the 9-3 core, its quadratic continuation below 0.05 a0, the quartic, beyond
            g = np.concatenate([np.linspace(-0.5, 3.0, 4001), [law.cutoff, 1.0, 0.05]])
            g = g.astype(dtype)
            p, c = law.pressure_and_curvature(g)
            assert p.dtype == c.dtype == dtype
            rtol = 1e-15 if dtype == np.float64 else 1e-7
            np.testing.assert_allclose(p, law.pressure(g), rtol=rtol, atol=0)
            np.testing.assert_allclose(c, law.curvature(g), rtol=rtol, atol=0)
            assert np.all(p[g >= law.cutoff] == 0) and np.all(c[g >= law.cutoff] == 0)


def test_the_dense_blocks_are_the_indexed_ones():
    # the block preconditioner with grid-sized factors (a large stiff set) gives the same z
    # and K z as with the stiff sites' indices, to rounding
    from roughcontact.solvers._block import _dense_blocks, _precondition
    from roughcontact.solvers.fourier import compliance_operator, stiffness_operator

    sub = rc.Substrate((64, 64))
    rng = np.random.default_rng(2)
    gr = rng.standard_normal(64 * 64)
    gr -= gr.mean()
    stiff = np.flatnonzero(rng.random(gr.size) < 0.4)
    diagonal = 1.0 / (sub.self_stiffness + rng.random(stiff.size))
    compliance = compliance_operator(sub, work_grid=True)
    stiffness = stiffness_operator(sub, work_grid=True)
    work = Workspace(gr)
    for fast in (None, np.empty(gr.size, np.float32)):
        result = None if fast is None else np.empty_like(fast)
        z, kz = _precondition(gr, stiff, diagonal, compliance, stiffness, True, work=work,
                              fast=fast, result=result)  # fmt: skip
        z, kz = z.copy(), kz.copy()
        dense = _dense_blocks(stiff, diagonal, gr)
        z2, kz2 = _precondition(gr, stiff, diagonal, compliance, stiffness, True, work=work,
                                fast=fast, result=result, dense=dense)  # fmt: skip
        scale = np.abs(z).max()
        rtol = 1e-13 if fast is None else 1e-6
        np.testing.assert_allclose(z2, z, rtol=0, atol=rtol * scale)
        np.testing.assert_allclose(kz2, kz, rtol=0, atol=rtol * np.abs(kz).max())
        assert abs(z2.mean()) <= 1e-15 * scale  # mean-free (the rigid uniform mode)
        # on the stiff sites the diagonal block, less one shift (the mean)
        shift = z2[stiff] - gr[stiff] * diagonal
        np.testing.assert_allclose(shift, shift[0], rtol=0, atol=1e-14 * scale)
