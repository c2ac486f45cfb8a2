"""Load control inside the one minimisation (the uniform mode free, solvers/_free_mean.py):
as cheap as displacement control, the same state as the nested root search."""

import functools
import importlib

import numpy as np
import pytest
from _helpers import warm_steps_by_load_and_offset

import roughcontact as rc
from roughcontact import SolveStatus

load_control = importlib.import_module("roughcontact.solvers.load_control")
projection = importlib.import_module("roughcontact.solvers._projection")
smooth = importlib.import_module("roughcontact.solvers.smooth")


def _problem(n, la, seed=7):
    h = rc.self_affine((n, n), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=seed)
    return h, rc.Substrate((n, n)), rc.SmoothLJ93.from_adhesion_length(la)


@pytest.mark.parametrize(
    ("n", "la", "load", "ratio"),
    [
        # measured 1.13 / 1.24 / 1.41; the nested root search took 10-30x (benchmarks/README.md)
        (64, 0.05, 1e-3, 1.5),
        (64, 0.05, 0.0, 1.5),
        (32, 0.005, 1e-3, 2.0),
    ],
)
def test_cold_load_control_costs_at_most_the_offset_solve_times(n, la, load, ratio):
    h, sub, law = _problem(n, la)
    res = rc.solve(h, sub, law, load=load)
    assert res.converged and abs(res.load - load) <= res.tol, res.message
    same = rc.solve(h, sub, law, offset=res.offset)  # the offset-controlled solve to it
    assert same.converged and np.abs(same.gap - res.gap).max() < 1e-6
    assert res.iterations <= ratio * same.iterations, (res.iterations, same.iterations)


def test_the_same_state_as_the_nested_root_search():
    h, sub, law = _problem(32, 0.05, seed=1)
    one = rc.solve(h, sub, law, load=5e-4)
    # a minimiser that is not minimize_energy itself takes the nested search
    nested_minimize = functools.partial(smooth.minimize_energy)
    nested = load_control.solve_at_load(
        nested_minimize, h, sub, law, load=5e-4, initial=None, tol=None, max_iter=5000,
        callback=None,
    )  # fmt: skip
    assert one.converged and nested.converged
    assert one.offset == pytest.approx(nested.offset, abs=1e-6)
    np.testing.assert_allclose(one.pressure, nested.pressure, atol=1e-6)
    assert nested.iterations > 3 * one.iterations  # why it was replaced


@pytest.mark.parametrize(("la", "ratio"), [(0.005, 1.5), (0.05, 1.5)])
def test_load_controlled_path_step_costs_an_offset_step(la, ratio):
    h, sub, law = _problem(64, la)
    loads = np.linspace(0.0, 2e-3, 5)
    by_load, warm_load, warm_offset = warm_steps_by_load_and_offset(h, sub, law, loads)
    assert warm_load <= ratio * warm_offset, (warm_load, warm_offset)


def test_beyond_pull_off_is_still_detached():
    h, sub, law = _problem(32, 0.005)
    res = rc.solve(h, sub, law, load=-1.0)
    assert res.status is SolveStatus.DETACHED and not res.converged


def test_the_uniform_block_rules():
    rules = importlib.import_module("roughcontact.solvers.adhesive_rules")
    # the elastic floor E* pi / L out of contact, the curvature's fraction in contact
    assert rules.uniform_stiffness(0.0, 2.0, 64.0) == pytest.approx(2.0 * np.pi / 64.0)
    assert rules.uniform_stiffness(10.0, 1.0, 64.0) == pytest.approx(rules.UNIFORM_FRACTION * 10)
    # the shift mean(gr)/k_u, bounded by the reach either way
    assert rules.uniform_shift(0.01, 0.1, 0.5) == pytest.approx(0.1)
    assert rules.uniform_shift(1e9, 0.05, 0.5) == 0.5
    assert rules.uniform_shift(-1e9, 0.05, 0.5) == -0.5


@pytest.mark.parametrize("load", [1e-3, 0.0])
def test_hard_core_load_in_one_minimisation(load):
    # the bounded solver with mu = -load and a free mean: the nested search took 150-550
    h, sub, _ = _problem(64, 0.05)
    law = rc.Exponential(work_of_adhesion=0.05, range=1.0)
    res = rc.solve(h, sub, law, load=load)
    assert res.converged and abs(res.load - load) <= res.tol, res.message
    same = rc.solve(h, sub, law, offset=res.offset)
    assert same.converged and np.abs(same.gap - res.gap).max() < 1e-6
    assert res.iterations <= 2.0 * same.iterations, (res.iterations, same.iterations)
    bounded = importlib.import_module("roughcontact.solvers.bounded")
    nested = load_control.solve_at_load(
        functools.partial(bounded.minimize_energy_bounded), h, sub, law, load=load,
        initial=None, tol=None, max_iter=5000, callback=None,
    )  # fmt: skip
    assert nested.converged and nested.offset == pytest.approx(res.offset, abs=1e-6)
    assert nested.iterations > 3 * res.iterations


@pytest.mark.parametrize(("la", "load"), [(0.005, 0.0), (0.05, 1e-3)])
def test_cold_load_control_starts_from_the_coarse_grid(monkeypatch, la, load):
    # nested iteration (adhesive_rules.NESTED_MIN_SIZE, 128² and up): measured 112 -> 52
    # iterations here (+59 on 64²) at la 0.005, load 0, against 49 offset-controlled;
    # 64 -> 29 (+39) against 55 at la 0.05 (benchmarks/README.md)
    h, sub, law = _problem(128, la)
    res = rc.solve(h, sub, law, load=load)
    assert res.converged and abs(res.load - load) <= res.tol, res.message
    assert "coarsened grid" in res.message  # the coarse work is said
    same = rc.solve(h, sub, law, offset=res.offset)
    assert same.converged and np.abs(same.gap - res.gap).max() < 1e-6
    assert res.iterations <= 1.5 * same.iterations, (res.iterations, same.iterations)
    # the same state as the cold start on this grid alone, which costs more here
    rules = importlib.import_module("roughcontact.solvers.adhesive_rules")
    assert rules.nests((128, 128)) and not rules.nests((64, 64)) and not rules.nests((130, 127))
    monkeypatch.setattr(load_control, "nests", lambda shape: False)
    alone = rc.solve(h, sub, law, load=load)
    assert alone.converged and "coarsened" not in alone.message
    assert np.abs(alone.gap - res.gap).max() < 1e-6
    assert alone.offset == pytest.approx(res.offset, abs=1e-6)
    assert alone.iterations > 1.2 * res.iterations, (alone.iterations, res.iterations)


def test_hard_core_cold_load_control_starts_from_the_coarse_grid(monkeypatch):
    # the bounded solver's free mode takes the same nested start (measured at 128², la 0.005,
    # load 0: 31 -> 29 iterations here against 17 offset-controlled; 256²: 65 -> 54 vs 23;
    # with the contact's lift as the uniform block, i39d: 19 -> 19 here, 30 -> 27 at 256²)
    h, sub, _ = _problem(128, 0.005)
    law = rc.Exponential(work_of_adhesion=0.005, range=1.0)
    res = rc.solve(h, sub, law, load=0.0)
    assert res.converged and abs(res.load) <= res.tol and "coarsened grid" in res.message
    monkeypatch.setattr(load_control, "nests", lambda shape: False)
    alone = rc.solve(h, sub, law, load=0.0)
    assert alone.converged and np.abs(alone.gap - res.gap).max() < 1e-6


def _first_contact_case():
    # a weak, short-ranged Maugis-Dugdale law on a rough surface at load 0: barely in
    # contact, the search direction carries the body's lift, along which the line minimum
    # lay far beyond any step the wall admits
    h = rc.self_affine((64, 64), hurst=0.5, rms_slope=0.2, short_cutoff=4, seed=1)
    return h, rc.Substrate(h.shape), rc.MaugisDugdale(work_of_adhesion=0.002, range=0.2)


def test_a_cold_hard_core_reaches_contact_from_the_first_wall_contact(monkeypatch):
    # every halving of the projected step rose and projected-gradient steps crawled
    # through the jump into contact (106 iterations, then a restart from the hard wall);
    # searched upward from the first wall contact (bounded_rules.CONTACT_DOUBLINGS):
    # 13 iterations against 9 offset-controlled, no restart
    h, sub, law = _first_contact_case()
    res = rc.solve(h, sub, law, load=0.0)
    assert res.status is SolveStatus.CONVERGED, res.message
    assert abs(res.load) <= res.tol and 0 < res.repulsive_area < 0.05
    assert "hard-wall" not in res.message
    assert float(np.abs(res.pressure).max()) < 10 * law.work_of_adhesion / law.range + 1
    same = rc.solve(h, sub, law, offset=res.offset)  # the offset-controlled solve to it
    assert same.converged and np.abs(same.gap - res.gap).max() < 1e-6
    assert res.iterations <= 2 * same.iterations, (res.iterations, same.iterations)
    single = rc.solve(h, sub, law, load=0.0, dtype="float32")
    assert single.converged and "hard-wall" not in single.message, single.message
    assert single.repulsive_area == pytest.approx(res.repulsive_area, abs=2 / h.size)
    # without the search the same solve crawls and restarts (what it did before)
    monkeypatch.setattr(projection, "CONTACT_DOUBLINGS", 0)
    crawl = rc.solve(h, sub, law, load=0.0)
    assert crawl.converged and "crawled" in crawl.message
    assert crawl.iterations > 3 * res.iterations


def test_a_cold_hard_core_past_its_budget_restarts_from_the_hard_wall(monkeypatch):
    # the fallback for a solve from first contact that still crawls (2 of 72 cold solves
    # at 128² in benchmarks/README.md), forced here by a budget of 5 iterations: the solve
    # starts again from the hard-wall state at load sigma_max and unloads
    h, sub, law = _first_contact_case()
    monkeypatch.setattr(load_control, "COLD_HARD_CORE_BUDGET", 5)
    res = rc.solve(h, sub, law, load=0.0)
    assert res.status is SolveStatus.CONVERGED, res.message
    assert abs(res.load) <= res.tol and 0 < res.repulsive_area < 0.05
    assert "started from the hard-wall state" in res.message and "hysteresis" in res.message
    assert float(np.abs(res.pressure).max()) < 10 * law.work_of_adhesion / law.range + 1
    # in single precision too: the hard-wall start takes float32's own tolerance (it
    # asked for 1e-8, below float32's floor: a ParameterError blaming the user's tol)
    single = rc.solve(h, sub, law, load=0.0, dtype="float32")
    assert single.status is SolveStatus.CONVERGED and "hard-wall state" in single.message
    assert single.repulsive_area == pytest.approx(res.repulsive_area, abs=2 / h.size)


def test_a_crawl_into_contact_is_caught_by_the_guard_and_restarts():
    # a strong, short-ranged Exponential law on a steep surface at a small tension still
    # crawls from first contact (128²; the guard: no 3-fold fall in 40 iterations)
    h = rc.self_affine((128, 128), hurst=0.5, rms_slope=0.2, short_cutoff=4, seed=3)
    law = rc.Exponential(work_of_adhesion=0.05, range=0.2)
    res = rc.solve(h, rc.Substrate(h.shape), law, load=-1e-4)
    assert res.status is SolveStatus.CONVERGED, res.message
    assert abs(res.load + 1e-4) <= res.tol
    assert "crawled" in res.message and "started from the hard-wall state" in res.message


def test_a_tension_beyond_the_approachs_pull_off_is_carried_by_the_unloading_branch():
    # the approach from first contact (the jump in at load 0, then pulled) separates at
    # -1e-3 E*; unloading from the hard-wall state at load sigma_max carries it (the
    # crawl's restart used to find that branch by accident, and without it the answer was
    # "no state carries load")
    h = rc.self_affine((128, 128), hurst=0.8, rms_slope=0.3, short_cutoff=4, seed=11)
    law = rc.Exponential(work_of_adhesion=0.05, range=0.2)
    res = rc.solve(h, rc.Substrate(h.shape), law, load=-1e-3)
    assert res.status is SolveStatus.CONVERGED, res.message
    assert abs(res.load + 1e-3) <= res.tol and res.repulsive_area > 0
    assert "separated beyond its pull-off force" in res.message and "hysteresis" in res.message
    # where neither branch holds the tension, the detachment says that both were tried
    h = rc.self_affine((64, 64), hurst=0.8, rms_slope=0.3, short_cutoff=4, seed=11)
    law = rc.MaugisDugdale(work_of_adhesion=0.01, range=0.5)
    off = rc.solve(h, rc.Substrate(h.shape), law, load=-1e-3)
    assert off.status is SolveStatus.DETACHED and "nor did the state unloaded" in off.message
