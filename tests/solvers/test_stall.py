"""float64 solves stuck at their rounding floor stop early and say why: a runaway (deep
compression, pressures beyond any elastic equilibrium) is a failure, never "stalled"."""

import importlib

import numpy as np
import pytest
from _helpers import flat_through_contact

import roughcontact as rc
from roughcontact import SolveStatus

smooth = importlib.import_module("roughcontact.solvers.smooth")
rules = importlib.import_module("roughcontact.solvers.adhesive_rules")

N = 64
H = rc.self_affine((N, N), hurst=0.8, rms_slope=0.1, short_cutoff=4.0, seed=1)
SUB = rc.Substrate((N, N))
LAW = rc.SmoothLJ93(contact_modulus=1.0, pixel_size=1.0, work_of_adhesion=0.05)
EPS = np.finfo(np.float64).eps


def test_a_runaway_that_rounds_to_zero_is_not_converged():
    # it once came back "converged", residual 0.0: recomputed, its force balance is 1e-2 E*
    h, law, offset = flat_through_contact()
    res = rc.solve(h, SUB, law, offset=offset)
    assert res.status is SolveStatus.RUNAWAY and not res.converged, res.message
    assert res.message.startswith("runaway: pressures reach"), res.message
    assert float(np.abs(res.pressure).max()) > 1e12
    # a cap stops short of the state: "iteration_limit" says so, not a verdict on it
    capped = rc.solve(h, SUB, law, offset=offset, max_iter=1)
    assert capped.status is SolveStatus.ITERATION_LIMIT


@pytest.mark.parametrize("depth", [0.7, 1.0, 100.0])
def test_deep_compression_is_a_runaway_not_a_stall(depth):
    # max(h) - 0.7: pressures ~1e9 E* (floor ~3e-7 > tol); - 100: ~1e16 E*, where the
    # conjugate-gradient denominator used to be exactly 0 (ZeroDivisionError). These
    # states are at float64's floor of their own pressures, which no elastic body holds:
    # once reported as "stalled ... as accurate as float64 allows"
    res = rc.solve(H, SUB, LAW, offset=float(H.max()) - depth)
    assert not res.converged and res.status is SolveStatus.RUNAWAY
    assert res.message.startswith("runaway: pressures reach"), res.message
    assert "beyond any elastic equilibrium" in res.message
    assert "as accurate as float64 allows" not in res.message
    assert res.iterations < 500  # was the 5000-iteration cap
    scale = float(np.abs(res.pressure).max())
    assert scale > 1e8 and res.residual <= smooth.FLOOR_ULPS * EPS * scale


def test_deep_load_control_stops_early():
    # the load asked for is part of the pressure scale: 1e9 E* is resolved to its floor
    res = rc.solve(H, SUB, LAW, load=1e9)
    assert not res.converged and "stalled at the float64 rounding floor" in res.message
    assert res.status is SolveStatus.STALLED
    assert res.iterations < 2000


def test_core_sites_below_their_rounding_are_stalled_without_the_floor_claim():
    # tol below the rounding of a few core sites' pressures (~90 E*): not a runaway, and
    # not "as accurate as float64 allows" on the physical scale (~0.1 E*) either
    res = rc.solve(H, SUB, LAW, offset=float(H.max()) - 0.3, tol=1e-15)
    assert res.status is SolveStatus.STALLED and res.iterations < 500
    assert "as accurate as float64 allows" not in res.message
    assert "largest local pressure" in res.message


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
    # converged, and said to be outside linear elasticity when its pressures exceed E*
    deep = float(np.abs(guarded.pressure).max()) > 1.0
    assert ("beyond the linear-elastic half-space" in guarded.message) == deep, guarded.message
    # below max(h) this surface is in full contact at a mean gap under a0: 2.9-1e6 E*
    assert deep == (offset < 0) and (deep or guarded.message == "converged")
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


@pytest.mark.parametrize(
    ("own", "physical", "kind", "start"),
    [
        (1e9, 1e9, "stalled", "stalled at the float64 rounding floor"),  # scale = own
        (1e9, 0.1, "runaway", "runaway: pressures reach 1e+09 E*"),  # 1e10 scales
        (90.0, 0.1, "stalled", "stalled: residual"),  # core sites, not the floor claim
    ],
)
def test_floor_verdict_judges_on_the_physical_scale(own, physical, kind, start):
    guard = smooth.FloorGuard(lambda r: None, "float64", lambda: own, 1.0, 1e-8,
                              lambda: physical)  # fmt: skip
    residual = 3 * EPS * own
    messages = [guard(residual) for _ in range(smooth.FLOOR_PATIENCE + 1)]
    assert messages[-1].startswith(start), messages[-1]
    assert guard.kind == kind


def test_physical_pressure_scale_of_the_law_and_the_slope():
    law = rc.SmoothLJ93.from_adhesion_length(0.05)
    # the smoothed 9-3 wall's largest tension: -min p over its range (sampled finely)
    gaps = np.linspace(1.0, law.cutoff, 200001)
    assert rules.largest_attraction(law) == pytest.approx(-law.pressure(gaps).min(), rel=1e-4)
    slope = rules.rms_slope(H, 1.0)
    dx, dy = np.roll(H, -1, 0) - H, np.roll(H, -1, 1) - H
    assert slope == pytest.approx(np.sqrt(np.mean(dx**2 + dy**2)), rel=1e-12)
    assert rules.physical_pressure_scale(H, SUB, law) == pytest.approx(
        max(slope, rules.largest_attraction(law)), rel=1e-12
    )
    # the lowest offset load control tries: the law's repulsion there is load + 10 P
    lowest = rules.lowest_smooth_offset(law, 0.0, 1e-3, 0.1)
    assert float(law.pressure(np.array([lowest]))[0]) == pytest.approx(1.001, rel=1e-6)
