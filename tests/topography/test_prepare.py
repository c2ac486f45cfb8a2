"""Detrending and the tip-radius reliability cutoff.

Oracles: exact polynomials are removed to rounding and the residual of a noisy one is
orthogonal to the basis (the normal equations); numpy.polyfit in 1D; the analytic
scale-dependent curvature of a sinusoid, 4 A sin²(pi l / (2 lambda)) / (l/2)², whose
root in l is found with scipy's brentq; SurfaceTopography's detrending and its
``scanning_probe_reliability_cutoff`` on real scans (peers).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from roughcontact import ParameterError
from roughcontact.topography import (
    Topography,
    detrend,
    load_topography,
    reliability_cutoff,
    scale_dependent_curvature,
)

DATA = Path(__file__).resolve().parents[1] / "data" / "topographies"


def data_file(name: str) -> Path:
    """A real instrument file kept in the repository (tests/data/topographies/README.md)."""
    import SurfaceTopography  # noqa: F401  (a test dependency: it must be installed)

    path = DATA / name
    assert path.is_file(), f"test data {path} missing from the repository"
    return path


def grid(shape, pixel_size):
    axes = [np.arange(n) * p for n, p in zip(shape, pixel_size, strict=True)]
    return np.meshgrid(*axes, indexing="ij")


# ----------------------------------------------------------------------------- detrend


@pytest.mark.parametrize("mode", ["plane", "curvature"])
def test_polynomial_removed_exactly_2d(mode):
    px = (2e-9, 3e-9)
    x, y = grid((24, 17), px)
    xc, yc = x.mean(), y.mean()  # coefficients are about the scan centre
    bend = mode == "curvature"
    h = 4e-9 + 0.03 * x - 0.05 * y + bend * (2e5 * x**2 - 1e5 * x * y + 3e5 * y**2)
    out = detrend(Topography(h, px), mode)
    assert np.max(np.abs(out.heights)) < 1e-12 * np.max(np.abs(h))
    assert out.info["detrend"] == mode
    c = out.info["detrend_coefficients"]
    # d h / d x and d h / d y at the centre
    assert c["x"] == pytest.approx(0.03 + bend * (4e5 * xc - 1e5 * yc), rel=1e-9)
    assert c["y"] == pytest.approx(-0.05 + bend * (6e5 * yc - 1e5 * xc), rel=1e-9)
    if bend:
        assert (c["x^2"], c["x*y"], c["y^2"]) == pytest.approx((2e5, -1e5, 3e5), rel=1e-9)


@pytest.mark.parametrize("mode", ["height", "plane", "curvature"])
def test_residual_orthogonal_to_the_basis(mode):
    rng = np.random.default_rng(3)
    x, y = grid((32, 20), (1.0, 1.0))
    h = 0.2 * x + 0.1 * y + 0.01 * x * y + rng.standard_normal(x.shape)
    r = detrend(Topography(h, 1.0), mode).heights
    basis = {
        "height": [np.ones_like(x)],
        "plane": [np.ones_like(x), x, y],
        "curvature": [np.ones_like(x), x, y, x * x, x * y, y * y],
    }[mode]
    for b in basis:  # normal equations: B^T r = 0
        assert abs(np.sum(b * r)) < 1e-10 * np.sqrt(np.sum(b * b) * np.sum(r * r))
    assert np.sum(r**2) <= np.sum((h - h.mean()) ** 2)


@pytest.mark.parametrize(("mode", "degree"), [("height", 0), ("plane", 1), ("curvature", 2)])
def test_line_scan_against_polyfit(mode, degree):
    rng = np.random.default_rng(5)
    x = np.arange(200) * 0.5e-6
    h = 1e-7 * np.sin(x / 7e-6) + 3e-3 * x + rng.standard_normal(200) * 1e-8
    expected = h - np.polyval(np.polyfit(x, h, degree), x)
    out = detrend(Topography(h, 0.5e-6), mode).heights
    np.testing.assert_allclose(out, expected, rtol=0, atol=1e-12 * np.max(np.abs(h)))


def test_periodicity_and_none():
    h = np.random.default_rng(0).standard_normal((8, 8))
    topo = Topography(h, 1.0, periodic=True)
    assert detrend(topo, "height").periodic is True  # a constant keeps the period
    assert detrend(topo, "plane").periodic is False
    same = detrend(topo, "none")
    np.testing.assert_array_equal(same.heights, h)
    assert same.info["detrend"] == "none" and topo.info == {}  # the argument is untouched
    with pytest.raises(ParameterError, match="mode must be one of"):
        detrend(topo, "quadratic")


@pytest.mark.parametrize(("mode", "peer"), [("height", "center"), ("plane", "height"),
                                            ("curvature", "curvature")])  # fmt: skip
def test_detrend_against_surface_topography(mode, peer):
    path = data_file("nid-1.nid")
    from SurfaceTopography import open_topography

    theirs = open_topography(str(path)).topography().detrend(detrend_mode=peer).heights()
    ours = detrend(load_topography(path), mode).heights
    np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-9 * np.std(ours))


# ------------------------------------------------------------------ reliability cutoff


def sinusoid_cutoff(a, wavelength, target):
    """Scale l where 4 A sin²(pi l / (2 lambda)) / (l/2)² = target, l in (0, 2 lambda)."""

    def excess(scale):
        return 4 * a * math.sin(math.pi * scale / (2 * wavelength)) ** 2 / (scale / 2) ** 2

    return brentq(lambda s: excess(s) - target, 1e-9 * wavelength, 2 * wavelength)


@pytest.mark.parametrize("periodic", [True, False])
@pytest.mark.parametrize("dim", [1, 2])
def test_sinusoid_analytic_cutoff(periodic, dim):
    px, n, wavelength, a = 1e-8, 256, 64e-8, 2e-8  # summit at x = 16 pixels
    x = np.arange(n) * px
    h = a * np.sin(2 * np.pi * x / wavelength)
    if dim == 2:
        h = np.repeat(h[:, None], 5, axis=1)
    topo = Topography(h, px, periodic=periodic)
    curvature = a * (2 * np.pi / wavelength) ** 2
    for radius in (2.0 / curvature, 5.0 / curvature):  # f / R = 1/4 and 1/10 of A k²
        out = reliability_cutoff(topo, radius, safety_factor=0.5)
        expected = sinusoid_cutoff(a, wavelength, 0.5 / radius)
        assert out.cutoff == pytest.approx(expected, rel=2e-3)
        assert out.tip_radius == radius and out.tip_radius_source == "argument"
        assert not out.all_scales and "reliable above" in out.message


def test_sinusoid_curvature_at_each_scale():
    px, wavelength, a = 1.0, 40.0, 3.0
    h = a * np.sin(2 * np.pi * np.arange(200) / wavelength)
    topo = Topography(h, px, periodic=True)
    for m in (1, 3, 7, 15):
        scale = 2 * m * px
        c = scale_dependent_curvature(topo, m)
        expected = -h * 4 * np.sin(np.pi * scale / (2 * wavelength)) ** 2 / (scale / 2) ** 2
        np.testing.assert_allclose(c, expected, rtol=1e-9, atol=1e-12)


def test_no_cutoff_and_all_scales():
    px, wavelength, a = 1.0, 64.0, 1.0
    h = a * np.sin(2 * np.pi * np.arange(64) / wavelength)
    topo = Topography(h, px, periodic=True)
    curvature = a * (2 * np.pi / wavelength) ** 2
    blunt = reliability_cutoff(topo, 0.5 / (1.01 * curvature))  # f/R just above A k²
    assert blunt.cutoff is None and "no tip artefacts" in blunt.message
    # at the largest scale (l = lambda, half-width 32) the curvature is 16 A / lambda²
    sharp = reliability_cutoff(topo, 0.5 / (0.99 * 16 * a / wavelength**2))
    assert sharp.all_scales and sharp.cutoff == pytest.approx(64.0)
    assert "no reliable data" in sharp.message


def test_tip_radius_unknown_and_from_file():
    topo = Topography(np.random.default_rng(0).standard_normal((16, 16)), 1.0)
    out = reliability_cutoff(topo)
    assert out.cutoff is None and out.message == "no reliability cutoff (tip radius unknown)"
    assert json.loads(json.dumps(out.to_dict()))["tip_radius_source"] == "unknown"
    scan = load_topography(data_file("dektak-1.csv"))
    stored = reliability_cutoff(scan)
    assert stored.tip_radius_source == "file" and stored.tip_radius == pytest.approx(2.5e-6)


def test_dektak_cutoff_against_surface_topography():
    path = data_file("dektak-1.csv")
    from SurfaceTopography import open_topography

    topo = open_topography(str(path)).topography()  # non-uniform, in um
    theirs = topo.short_reliability_cutoff() * 1e-6
    ours = reliability_cutoff(load_topography(path)).cutoff
    assert ours == pytest.approx(theirs, rel=0.05)  # they interpolate the raw positions


@pytest.mark.parametrize("radius", [1e-6, 3e-6])
def test_afm_cutoff_against_surface_topography(radius):
    path = data_file("nid-1.nid")
    from SurfaceTopography import open_topography

    topo = open_topography(str(path)).topography()  # m
    theirs = topo.scanning_probe_reliability_cutoff(radius)
    ours = reliability_cutoff(load_topography(path), radius)
    assert ours.cutoff == pytest.approx(theirs, rel=0.05)
    assert not ours.all_scales


def test_reliability_bad_input():
    topo = Topography(np.zeros((8, 8)) + np.arange(8), 1.0)
    for bad in (0, -1.0, float("nan"), "1 nm"):
        with pytest.raises(ParameterError, match="tip_radius"):
            reliability_cutoff(topo, bad)
    with pytest.raises(ParameterError, match="axis"):
        reliability_cutoff(topo, 1.0, axis=2)
    with pytest.raises(ParameterError, match="safety_factor"):
        reliability_cutoff(topo, 1.0, safety_factor=0)
    with pytest.raises(ParameterError, match="square pixels"):
        reliability_cutoff(Topography(np.ones((8, 8)), (1.0, 2.0)), 1.0, axis=None)
