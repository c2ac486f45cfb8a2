"""float64 solves stuck at their rounding floor (deep compression) stop early and say why."""

import importlib

import numpy as np
import pytest

import roughcontact as rc

smooth = importlib.import_module("roughcontact.solvers.smooth")

N = 64
H = rc.self_affine((N, N), hurst=0.8, rms_slope=0.1, short_cutoff=4.0, seed=1)
SUB = rc.Substrate((N, N))
LAW = rc.SmoothLJ93(contact_modulus=1.0, pixel_size=1.0, work_of_adhesion=0.05)
EPS = np.finfo(np.float64).eps


@pytest.mark.parametrize("depth", [0.7, 1.0, 100.0])
def test_deep_compression_stops_at_the_float64_floor(depth):
    # max(h) - 0.7: pressures ~1e9 E* (floor ~3e-7 > tol); - 100: ~1e16 E*, where the
    # conjugate-gradient denominator used to be exactly 0 (ZeroDivisionError)
    res = rc.solve(H, SUB, LAW, offset=float(H.max()) - depth)
    assert not res.converged
    assert res.message.startswith("stalled at the float64 rounding floor"), res.message
    assert "as accurate as float64 allows" in res.message and "pressure scale" in res.message
    assert res.iterations < 500  # was the 5000-iteration cap
    scale = float(np.abs(res.pressure).max())
    assert scale > 1e8 and res.residual <= smooth.FLOOR_ULPS * EPS * scale


def test_deep_load_control_stops_early():
    res = rc.solve(H, SUB, LAW, load=1e9)
    assert not res.converged and "stalled at the float64 rounding floor" in res.message
    assert res.iterations < 2000


@pytest.mark.parametrize(
    ("offset", "kwargs"),
    [
        (-0.1, {}),
        (-0.4, {}),
        (-0.6, {}),  # 1e6 E*: converges 14 floors above the rounding floor
        (-0.3, {"tol": 1e-12}),
        (0.5, {}),
    ],
)
def test_normal_solves_take_the_same_iterations(monkeypatch, offset, kwargs):
    d = float(H.max()) + offset
    guarded = rc.solve(H, SUB, LAW, offset=d, **kwargs)
    monkeypatch.setattr(smooth, "FLOOR_ULPS", 0)  # never at the floor: the guard is off
    plain = rc.solve(H, SUB, LAW, offset=d, **kwargs)
    assert guarded.converged and plain.converged
    assert guarded.iterations == plain.iterations
    np.testing.assert_array_equal(guarded.deflection, plain.deflection)


def test_floor_guard_needs_both_no_progress_and_the_floor():
    off = smooth.FloorGuard(lambda r: None, "float64", lambda: 1.0, 1.0, 1e-8)
    # a plateau far above the floor (1e-6 vs 2e-16): never a stall
    assert all(off(1e-6) is None for _ in range(10 * smooth.FLOOR_PATIENCE))
    guard = smooth.FloorGuard(lambda r: None, "float64", lambda: 1e9, 1.0, 1e-8)
    floor = EPS * 1e9
    messages = [guard(3 * floor) for _ in range(smooth.FLOOR_PATIENCE + 1)]
    assert messages[:-1] == [None] * smooth.FLOOR_PATIENCE
    assert messages[-1].startswith("stalled at the float64 rounding floor")
    # halving the best residual starts a new window
    guard = smooth.FloorGuard(lambda r: None, "float64", lambda: 1e9, 1.0, 1e-8)
    r, results = 100 * floor, []
    for _ in range(3 * smooth.FLOOR_PATIENCE):
        r *= 0.99  # halves every 69 iterations, within the patience
        results.append(guard(r))
    assert results == [None] * (3 * smooth.FLOOR_PATIENCE)
    # float32 keeps its own guard (whose message wins), never this one
    single = smooth.FloorGuard(lambda r: "float32 stall", "float32", lambda: 1e9, 1.0, 1e-6)
    assert single(3 * floor) == "float32 stall"
    quiet = smooth.FloorGuard(lambda r: None, "float32", lambda: 1e9, 1.0, 1e-6)
    assert all(quiet(3 * floor) is None for _ in range(3 * smooth.FLOOR_PATIENCE))
