"""The smooth solver's uniform block under load control spans the uniform mode and the
body's lift at fixed contact (_free_mean.lift_mode, adhesive_rules.lift_shape /
pair_coefficients, the same in _smooth_jax): its rules against the elastic operator, and
load-controlled path steps at the cost of offset-controlled ones."""

import importlib

import numpy as np
import pytest
from _helpers import warm_steps_by_load_and_offset

import roughcontact as rc
from roughcontact.solvers._inplace import Workspace
from roughcontact.solvers.fourier import stiffness_operator
from roughcontact.solvers.smooth_rules import STIFF_FRACTION

rules = importlib.import_module("roughcontact.solvers.adhesive_rules")
free_mean = importlib.import_module("roughcontact.solvers._free_mean")


def _problem(n, la, seed=7):
    h = rc.self_affine((n, n), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=seed)
    return h, rc.Substrate((n, n)), rc.SmoothLJ93.from_adhesion_length(la)


def test_pair_coefficients_solve_the_two_by_two_block():
    h = (2.0, 0.5, 1.0)
    c0, c1 = rules.pair_coefficients(*h, 0.3, -0.2, 10.0)
    np.testing.assert_allclose(np.array([[2.0, 0.5], [0.5, 1.0]]) @ [c0, c1], [0.3, -0.2],
                               rtol=1e-12)  # fmt: skip
    # each bounded by the reach; a singular block: the uniform direction alone
    assert rules.pair_coefficients(*h, 1e9, 0.0, 0.5) == (0.5, -0.5)
    c0, c1 = rules.pair_coefficients(2.0, 1.0, 0.5, 0.3, 0.1, 10.0)  # det = 0
    assert c0 == pytest.approx(0.15) and c1 == 0.0


def test_lift_mode_is_the_body_lifted_off_its_stiff_sites():
    h, sub, law = _problem(64, 0.005)
    offset = float(np.quantile(h, 0.9)) + 1.0  # about a tenth of the sites in contact
    gap = (offset - h).ravel()
    u, ku, (h00, h01, h11) = free_mean.lift_mode(law, gap, sub, Workspace(gap))
    curvature = np.maximum(law.curvature(gap), 0.0)
    stiff = curvature > STIFF_FRACTION * sub.self_stiffness
    assert 0 < stiff.sum() < gap.size
    assert np.all(u[stiff] == 0.0) and u[~stiff].mean() > 1.0  # zero on the contact
    n = gap.size
    exact = stiffness_operator(sub)(u)  # K u in float64: the float32 one within 1e-5
    assert np.abs(ku - exact).max() <= 1e-5 * np.abs(exact).max()
    assert h00 == pytest.approx(curvature.mean(), rel=1e-12)
    assert h01 == pytest.approx((curvature * u).mean(), rel=1e-9, abs=1e-15)
    assert h11 == pytest.approx((u @ exact + (curvature * u) @ u) / n, rel=1e-5)
    assert h00 * h11 > h01 * h01  # positive definite
    # out of contact: no lift mode (the uniform shift alone)
    far = (h.max() + 10.0 - h).ravel()
    assert free_mean.lift_mode(law, far, sub, Workspace(far)) is None


@pytest.mark.parametrize(("n", "la", "ratio"), [(128, 0.005, 1.2), (128, 0.05, 1.2)])
def test_load_path_steps_cost_an_offset_step(monkeypatch, n, la, ratio):
    # measured (median warm step, load / offset): 128² la 0.005 37 / 34.5, la 0.05 20 /
    # 19; with the uniform block alone before 50.5 and 22 (1.46x, 1.16x); 256² 1.53x ->
    # 1.09x at la 0.005, 1.08x at 0.05 (benchmarks/README.md)
    h, sub, law = _problem(n, la)
    loads = np.linspace(0.0, 2e-3, 5)
    by_load, warm_load, warm_offset = warm_steps_by_load_and_offset(h, sub, law, loads)
    assert warm_load <= ratio * warm_offset, (warm_load, warm_offset)
    if la == 0.005:  # the uniform block alone (FreeMean.add without K z): the same states
        add = free_mean.FreeMean.add
        monkeypatch.setattr(free_mean.FreeMean, "add",
                            lambda self, z, gr, gap, it, every, kz=None:
                            add(self, z, gr, gap, it, every))  # fmt: skip
        before = rc.approach_retract(h, sub, law, loads=loads, retract=False)
        np.testing.assert_allclose(before["offset"].values, by_load["offset"].values,
                                   atol=1e-6)  # fmt: skip
        assert np.median(before["iterations"].values[1:]) >= 1.25 * warm_load
