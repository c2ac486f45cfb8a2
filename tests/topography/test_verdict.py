"""The stickiness verdict of a scan: Eq. 10 against the smallest roughness scale.

Oracles: :func:`roughcontact.criterion.stickiness_criterion` fed the same statistics
(and a surface's known h'_rms), the closed-form lambda_s-dependence of a self-affine
spectrum continued below the measured scale (Eq. 10 written out here), its asymptote
``margin ~ lambda_s^((3 - 5H)/3)``, and the scalings of Eq. 10 with kappa_rep and E*.
"""

import json
import math

import numpy as np
import pytest

import roughcontact as rc
from roughcontact import ParameterError
from roughcontact.criterion import stickiness_criterion
from roughcontact.topography import Topography, reliability_cutoff, stick
from roughcontact.topography.verdict import UNITS

NM = 1e-9
RUBBER = {"work_of_adhesion": "50 mJ/m^2", "interaction_range": "0.5 nm"}


def _topo(n=128, hurst=0.3, a=10 * NM, short=2, periodic=True, seed=1, slope=0.1):
    h = rc.self_affine(n, hurst=hurst, rms_slope=slope, short_cutoff=short * a,
                       pixel_size=a, seed=seed)  # fmt: skip
    return Topography(h, (a, a), periodic=periodic, height_unit="m", info={"length_unit": "m"})


def _criterion(slope, curvature, modulus, kappa_rep=2.0):
    return stickiness_criterion(rms_slope=slope, rms_curvature=curvature,
                                contact_modulus=modulus, kappa_rep=kappa_rep, **RUBBER)  # fmt: skip


@pytest.mark.parametrize("factor", [0.5, 2.0])
def test_verdict_equals_the_criterion_on_a_surface_of_known_slope(factor):
    """No extrapolation (a0 at the short cutoff): sticky exactly when Eq. 10 says so."""
    a = 1 * NM
    topo = _topo(n=128, hurst=0.6, a=a, short=8, seed=3)
    exact = rc.statistics(topo.heights, pixel_size=a)
    onset = _criterion(0.1, exact.rms_curvature, 1e6).max_sticky_contact_modulus
    modulus = factor * onset
    r = stick(topo, modulus=modulus, detrend="height", reliability_cutoff=8 * a,
              atomic_spacing=8 * a, **RUBBER)  # fmt: skip
    ref = _criterion(0.1, exact.rms_curvature, modulus)
    assert r.statistics.rms_slope == pytest.approx(0.1, rel=1e-10)
    assert r.margin == pytest.approx(ref.margin, rel=1e-9)
    assert r.sticky is ref.sticky is (factor < 1)
    assert r.verdict.text == ("sticky" if factor < 1 else "not sticky")
    assert r.verdict.scales.tolist() == [8 * a]


@pytest.mark.parametrize("periodic", [True, False])
@pytest.mark.parametrize("dim", [1, 2])
def test_every_margin_is_the_criterion_of_the_statistics_used(periodic, dim):
    topo = _topo(periodic=periodic)
    if dim == 1:
        topo = Topography(topo.heights[:, 0], topo.pixel_size[:1], periodic=periodic,
                          height_unit="m", info={"length_unit": "m"})  # fmt: skip
    r = stick(topo, modulus="3 MPa", tip_radius=None, **RUBBER)
    s, v = r.statistics, r.verdict
    measured = _criterion(s.rms_slope, s.rms_curvature, 3e6)
    assert measured.to_dict() == v.measured.to_dict()
    assert r.to_dict()["criterion_measured"] == measured.to_dict()
    np.testing.assert_array_equal(v.margins[:, 0], measured.margin)
    if not v.extrapolated:  # a short profile's poor Hurst fit: the measured scale only
        assert "poorly" in v.no_extrapolation or "not self-affine" in v.no_extrapolation
        assert v.scales.tolist() == [s.measured_scale]
        # issue 41: a scoped answer is not the surface's
        assert v.sticky_measured_scale is measured.sticky
        assert v.sticky is (False if not measured.necessary_condition_met else None)
        return
    for i in (0, v.centre, len(v.hurst) - 1):
        for j in (1, v.scales.size // 2, -1):
            ref = _criterion(v.slopes[i, j], v.curvatures[i, j], 3e6)
            assert v.margins[i, j] == pytest.approx(ref.margin, rel=1e-12)
            s_ij, c_ij = s.extrapolated_at(v.scales[j], hurst=v.hurst[i])
            assert (s_ij, c_ij) == pytest.approx((v.slopes[i, j], v.curvatures[i, j]))
    c = v.centre
    assert v.atomic.to_dict() == _criterion(v.slopes[c, -1], v.curvatures[c, -1], 3e6).to_dict()
    assert v.scales[0] == s.measured_scale and v.scales[-1] == pytest.approx(0.3 * NM)


def _analytic_margin(stats, lam, modulus, w=0.05, dr=0.5 * NM, kappa_rep=2.0):
    """Eq. 10 with h'_rms, h''_rms of the fitted power law continued below lambda_c."""
    fit = stats.fit
    H, q_c, q = fit.hurst, 2 * np.pi / stats.measured_scale, 2 * np.pi / lam
    amp = 2 * np.pi * fit.psd_pivot * fit.q_pivot ** (2 + 2 * H)  # 2 pi q C(q) q^k dq
    s2 = stats.rms_slope**2 + amp * (q ** (2 - 2 * H) - q_c ** (2 - 2 * H)) / (2 - 2 * H)
    c2 = stats.rms_curvature**2 + amp * (q ** (4 - 2 * H) - q_c ** (4 - 2 * H)) / (4 - 2 * H)
    s, c = math.sqrt(s2), math.sqrt(c2)
    d_rep, l_a = 4 * s / c, w / modulus
    S = s * dr / (kappa_rep * l_a) * (s * d_rep / (4 * dr)) ** (2 / 3)
    return math.pi * (3 / 16) ** (2 / 3) / S


@pytest.mark.parametrize("where", [0.5, 0.37])  # 0.5: the flip is a point of the sweep
def test_flip_scale_from_the_analytic_scale_dependence(where):
    from scipy.optimize import brentq

    topo = _topo(hurst=0.3, a=10 * NM)
    first = stick(topo, modulus="10 MPa", hurst_sigmas=0, **RUBBER)
    stats = first.statistics
    lam_c, a0 = stats.measured_scale, 0.3 * NM
    mid = lam_c ** (1 - where) * a0**where
    modulus = 1e7 * _analytic_margin(stats, mid, 1e7)  # margin ∝ l_a = w/E*: 1 at mid
    assert _analytic_margin(stats, lam_c, modulus) > 1 > _analytic_margin(stats, a0, modulus)
    r = stick(topo, modulus=modulus, hurst_sigmas=0, **RUBBER)
    v = r.verdict
    ref = brentq(lambda x: _analytic_margin(stats, math.exp(x), modulus) - 1, math.log(a0),
                 math.log(lam_c), xtol=1e-14)  # fmt: skip
    assert v.flip_scale == pytest.approx(math.exp(ref), rel=1e-8)
    assert v.flip_scale == pytest.approx(mid, rel=1e-8)
    assert v.flip_scales == (v.flip_scale,) and v.sticky is None
    assert v.depends_below == v.flip_scale
    assert v.text.startswith("depends on roughness below")
    assert v.margin > 1 > v.margin_atomic
    assert v.margin_atomic == pytest.approx(_analytic_margin(stats, a0, modulus), rel=1e-9)
    # deep below lambda_c: margin ~ lambda_s^((3 - 5H)/3)
    H = stats.fit.hurst
    local = math.log(v.margins[0, -1] / v.margins[0, -2]) / math.log(v.scales[-1] / v.scales[-2])
    assert local == pytest.approx((3 - 5 * H) / 3, abs=0.02)


def test_hurst_uncertainty_makes_the_verdict_open():
    """Sticky at every scale with the fitted H, not with all of its band: undecided."""
    topo = _topo(hurst=0.3, a=10 * NM)
    base = stick(topo, modulus="10 MPa", hurst_sigmas=0, **RUBBER)
    assert base.verdict.margin_atomic < base.margin  # the margin falls towards a0
    modulus = 1e7 * base.verdict.margin_atomic / 1.05  # margin 1.05 at a0 with the fitted H
    r = stick(topo, modulus=modulus, **RUBBER)
    v = r.verdict
    assert v.margins[v.centre].min() == pytest.approx(1.05, rel=1e-9)
    assert v.flip_scale is None and v.flip_scales == ()
    lo, hi = v.margin_atomic_range
    assert lo < 1 < hi
    assert v.sticky is None and v.depends_below is not None
    assert v.flip_scale_range[1] == v.depends_below
    assert "flips within H" in v.text
    lo_h, hi_h = r.statistics.fit.interval(2)
    assert v.hurst[0] == pytest.approx(lo_h) and v.hurst[-1] == pytest.approx(hi_h)
    assert r.to_dict()["sticky"] is None
    # the same surface clearly stiffer or softer is decided
    assert stick(topo, modulus=modulus * 100, **RUBBER).sticky is False
    assert stick(topo, modulus=modulus / 1e3, **RUBBER).sticky is True


def test_margin_scales_with_kappa_rep_and_poisson_gives_e_star():
    topo = _topo()
    r2 = stick(topo, modulus="10 MPa", **RUBBER)
    r4 = stick(topo, modulus="10 MPa", kappa_rep=4, **RUBBER)
    assert r4.margin == pytest.approx(2 * r2.margin, rel=1e-12)  # Eq. 10: S ∝ 1/kappa_rep
    assert r2.inputs["kappa_rep"] == 2 and "paper" in r2.inputs["kappa_rep_note"]
    e = stick(topo, modulus="7.5 MPa", poisson=0.5, **RUBBER)
    assert e.inputs["contact_modulus"] == pytest.approx(1e7)
    assert e.inputs["youngs_modulus"] == pytest.approx(7.5e6)
    assert e.margin == pytest.approx(r2.margin, rel=1e-12)


def test_tip_radius_sets_the_measured_scale():
    topo = _topo(n=128, hurst=0.8, a=10 * NM, slope=0.5)
    radius = 40 * NM
    expected = reliability_cutoff(topo, radius).cutoff
    assert expected is not None
    r = stick(topo, modulus="10 MPa", tip_radius="40 nm", detrend="none", **RUBBER)
    assert r.statistics.measured_scale == pytest.approx(max(expected, 20 * NM))
    assert r.inputs["tip_radius"] == pytest.approx(radius)
    assert any("reliab" in n for n in r.notes)


def test_file_and_topography_give_the_same_answer(tmp_path):
    topo = _topo(periodic=False)
    path = tmp_path / "scan.npy"
    np.save(path, np.asarray(topo.heights) / NM)
    from_file = stick(path, modulus="10 MPa", pixel_size="10 nm", height_unit="nm", **RUBBER)
    direct = stick(topo, modulus="10 MPa", **RUBBER)
    assert from_file.margin == pytest.approx(direct.margin, rel=1e-9)
    assert from_file.verdict.margin_atomic == pytest.approx(direct.verdict.margin_atomic, rel=1e-9)


def test_json_has_keys_and_a_unit_for_every_number():
    d = stick(_topo(), modulus="10 MPa", **RUBBER).to_dict()
    text = json.dumps(d, allow_nan=False)
    assert json.loads(text) == d
    for key in ("sticky", "margin", "rms_slope", "rms_curvature", "d_rep", "units", "hurst",
                "hurst_stderr", "reliability_cutoff", "flip_scale", "verdict", "measured",
                "extrapolated", "inputs", "margin_atomic", "provenance"):  # fmt: skip
        assert key in d
    assert d["units"] == UNITS
    assert d["d_rep"] == pytest.approx(4 * d["rms_slope"] / d["rms_curvature"])
    assert d["extrapolated"]["scale"] == pytest.approx(0.3 * NM)

    def leaves(obj, path):
        if isinstance(obj, dict):
            for k, v in obj.items():
                yield from leaves(v, f"{path}.{k}" if path else k)
        elif isinstance(obj, list):
            for v in obj:
                yield from leaves(v, path)
        elif isinstance(obj, (int, float)) and not isinstance(obj, bool):
            yield path

    skip = ("units", "provenance")
    for path in leaves(d, ""):
        if path.startswith(skip):
            continue
        head = path.split(".")[0]
        assert path in UNITS or f"{head}.*" in UNITS, path


def test_bad_input_is_a_one_line_parameter_error():
    topo = _topo()
    cases = [
        ({"modulus": "-10 MPa"}, "modulus"),
        ({"modulus": "10 m"}, "modulus"),
        ({"modulus": "10 MPa", "kappa_rep": -1}, "kappa_rep"),
        ({"modulus": "10 MPa", "poisson": 0.7}, "poisson"),
        ({"modulus": "10 MPa", "tip_radius": "1 nm", "reliability_cutoff": "5 nm"}, "not both"),
        ({"modulus": "10 MPa", "channel": "Height"}, "channel"),
        ({"modulus": "10 MPa", "hurst_sigmas": -1}, "hurst_sigmas"),
        ({"modulus": "10 MPa", "atomic_spacing": "0 nm"}, "atomic_spacing"),
    ]
    for kwargs, word in cases:
        with pytest.raises(ParameterError, match=word) as info:
            stick(topo, **kwargs, **RUBBER)
        assert "\n" not in str(info.value)
    x = np.arange(64.0) * NM
    tilted = Topography(np.add.outer(x, 2 * x), NM, height_unit="m", info={"length_unit": "m"})
    with pytest.raises(ParameterError, match="flat"):
        stick(tilted, modulus="10 MPa", **RUBBER)  # a plane leaves only round-off
    lattice = Topography(np.asarray(topo.heights), 1.0)
    with pytest.raises(ParameterError, match="pixel_size"):
        stick(lattice, modulus="10 MPa", **RUBBER)


@pytest.mark.parametrize("dim", [2, 1])
def test_criteria_table_beside_the_verdict_uses_the_measured_moments(dim):
    """The field's criteria at the measured scale: the same h'_rms/h''_rms as the verdict,
    and M1 = int d^2q |q| C(q) equal to the direct FFT sum over the same modes (2D), or to
    the isotropic 2D surface's M1 from its profiles, <|cos theta|> = 2/pi (1D)."""
    a = 10 * NM
    h = rc.self_affine(128, hurst=0.8, rms_slope=0.1, short_cutoff=4 * a, pixel_size=a, seed=3)
    spec = np.abs(np.fft.fft2(h - h.mean())) ** 2 / h.size**2
    q = 2 * np.pi * np.hypot(*np.meshgrid(np.fft.fftfreq(128, a), np.fft.fftfreq(128, a)))
    m1 = float(np.sum((q * spec)[q <= np.pi / a]))
    if dim == 1:  # a profile: average the moments of all rows through the same reader path
        rows = [stick(Topography(r, (a,), periodic=True, height_unit="m",
                                 info={"length_unit": "m"}), modulus="3 MPa", detrend="none",
                      **RUBBER)
                for r in h[::4]]  # fmt: skip
        got = np.mean([r.criteria["inputs"]["half_derivative_variance"] for r in rows])
        assert got == pytest.approx(m1, rel=0.15)  # 32 profiles of one surface
        return
    topo = Topography(h, (a, a), periodic=True, height_unit="m", info={"length_unit": "m"})
    r = stick(topo, modulus="3 MPa", detrend="none", **RUBBER)  # the oracle's heights
    table = r.criteria
    assert table["scale"] == pytest.approx(r.statistics.measured_scale)
    assert table["inputs"]["rms_slope"] == pytest.approx(r.statistics.rms_slope)
    assert table["inputs"]["half_derivative_variance"] == pytest.approx(m1, rel=1e-6)
    keys = [c["key"] for c in table["criteria"]]
    assert "pastewka_robbins" in keys and "persson_tosatti" in keys
    pr = next(c for c in table["criteria"] if c["key"] == "pastewka_robbins")
    assert pr["sticky"] == r.verdict.measured.sticky  # the same Eq. 10 at the same scale
    assert json.loads(json.dumps(r.to_dict()))["criteria"]["criteria"][0]["key"] == keys[0]
