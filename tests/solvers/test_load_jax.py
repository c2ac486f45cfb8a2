"""Adhesive load control on JAX heights as one compiled program: the load inside the one
minimisation (the gap's uniform mode free, :mod:`roughcontact.solvers._free_mean`'s method
with :mod:`roughcontact.solvers.adhesive_rules`' rules) in the compiled smooth loop. The
NumPy one-minimisation solve's iterations and answers, the load carried, honest statuses
(the runaway / full-contact cases of ``test_load_control_runaway.py``), and a loop that
never talks to the host (``jax.transfer_guard("disallow")``)."""

import importlib

import numpy as np
import pytest
from _helpers import assert_donated, donatable

import roughcontact as rc
from roughcontact import SolveStatus
from roughcontact.solvers.adhesive_rules import physical_pressure_scale

jax = pytest.importorskip("jax")
jnp = pytest.importorskip("jax.numpy")
load_control = importlib.import_module("roughcontact.solvers.load_control")

LAW = rc.SmoothLJ93.from_adhesion_length(0.005)
STRONG = rc.SmoothLJ93.from_adhesion_length(0.05)
SOFT_CORE = rc.Exponential(0.01, 0.5, core_stiffness=1.0)


def surface(n=64, seed=7):
    h = rc.self_affine((n, n), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=seed)
    return h, rc.Substrate((n, n))


def rel_l2(a, b):
    return float(np.linalg.norm(np.asarray(a) - b) / np.linalg.norm(b))


def agree(res, ref, load):
    """Issue 38's acceptance: iterations within 1.25x, pressures to 1e-6 (rel. L2); and
    the load carried to the solver's tolerance (E* = 1)."""
    assert ref.converged and res.converged, res.message
    assert res.status is ref.status
    assert res.iterations <= 1.25 * ref.iterations + 1
    assert ref.iterations <= 1.25 * res.iterations + 1
    assert rel_l2(res.pressure, ref.pressure) <= 1e-6
    assert abs(res.load - load) <= res.tol
    assert res.offset == pytest.approx(ref.offset, abs=1e-8)
    assert res.repulsive_area == pytest.approx(ref.repulsive_area, abs=1e-6)


@pytest.mark.parametrize(("law", "load"), [(LAW, 1e-3), (LAW, 0.0), (LAW, -1e-3),
                                           (SOFT_CORE, 2e-3), (STRONG, 1e-3)])  # fmt: skip
def test_same_answer_as_the_numpy_one_minimisation(x64, law, load):
    h, sub = surface()
    ref = rc.solve(h, sub, law, load=load)
    res = rc.solve(jnp.asarray(h), sub, law, load=load)
    agree(res, ref, load)
    assert isinstance(res.pressure, jax.Array) and res.pressure.dtype == jnp.float64
    # the one minimisation, not the nested search (10-30x the iterations): a step warm
    # from the state, as the NumPy loop's from its own
    ref2 = rc.solve(h, sub, law, load=load + 2e-3, initial=ref)
    res2 = rc.solve(jnp.asarray(h), sub, law, load=load + 2e-3, initial=res)
    agree(res2, ref2, load + 2e-3)


def test_the_compiled_loop_takes_the_load_without_the_host(x64):
    from roughcontact.solvers import _smooth_jax as sj
    from roughcontact.solvers.smooth import minimize_energy

    h, sub = surface()
    d = float(h.max() + LAW.equilibrium_distance)
    hj = jnp.asarray(h)
    st, k = sj.prepare(jnp.zeros_like(hj), sub, LAW, base=d - hj, tol=1e-8, max_iter=500,
                       restart_every=200, refresh_every=10, warm=False, load=1e-3,
                       heights=hj)  # fmt: skip
    static = {"law": LAW, "rigid": True, "stall": False, "floor": True}
    first, second, third = donatable(st, 3)
    with jax.transfer_guard("disallow"):
        final = sj.run(first, k, **static)  # compiles and runs
        final = sj.run(second, k, **static)  # the compiled program
        with pytest.raises(Exception, match="(?i)disallowed"):  # the guard is armed: a
            sj.run(third, k._replace(load=1e-3), **static)  # host scalar is refused
    assert_donated(second)
    ref = minimize_energy(h, sub, LAW, offset=d, load=1e-3)
    assert int(final.status) == sj.CONVERGED and int(final.it) == ref.iterations
    p = np.asarray(LAW.pressure(final.gap))
    assert rel_l2(p, ref.pressure) <= 1e-6
    assert abs(float(p.mean()) - 1e-3) <= 1e-8  # the load carried inside the loop


@pytest.mark.parametrize("load", [1e-3, 0.3])
def test_strong_adhesion_no_runaway_and_full_contact(x64, load):
    # the issue 39 cases (128², ℓa 0.05, cold): the load carried with physical pressures
    # (once a runaway of 3.7e13 E* called "stalled"); 0.3 only full contact carries
    n = 128
    h, sub = surface(n)
    res = rc.solve(jnp.asarray(h), sub, STRONG, load=load)
    assert res.status is SolveStatus.CONVERGED, res.message
    assert abs(res.load - load) <= res.tol
    scale = physical_pressure_scale(h, sub, STRONG)
    assert float(jnp.max(jnp.abs(res.pressure))) < 10 * (scale + load)
    if load == 0.3:
        assert res.repulsive_area == 1.0
    else:
        assert 0.2 < res.repulsive_area < 1.0
    ref = rc.solve(h, sub, STRONG, load=load)
    agree(res, ref, load)


def test_beyond_pull_off_is_detached(x64):
    h, sub = surface()
    ref = rc.solve(h, sub, LAW, load=-0.05)
    res = rc.solve(jnp.asarray(h), sub, LAW, load=-0.05)
    assert ref.status is SolveStatus.DETACHED
    assert res.status is SolveStatus.DETACHED and not res.converged, res.message
    assert "pull-off" in res.message


def test_load_path_on_jax_heights(x64):
    h, sub = surface()
    loads = [1e-3, 4e-3, 1e-3, -1e-3]
    ref = rc.approach_retract(h, sub, LAW, loads=loads)
    pj = rc.approach_retract(jnp.asarray(h), sub, LAW, loads=loads)
    np.testing.assert_allclose(pj["load"].values, ref["load"].values, atol=1e-7)
    np.testing.assert_allclose(pj.offset.values, ref.offset.values, atol=1e-7)
    np.testing.assert_allclose(pj.repulsive_area.values, ref.repulsive_area.values, atol=1e-6)
    it, it_ref = pj.iterations.values, ref.iterations.values
    assert np.all(it <= 1.25 * it_ref + 1) and np.all(it_ref <= 1.25 * it + 1)
    assert (pj.jump.values == ref.jump.values).all()


HARD_CORE = rc.Exponential(0.005, 1.0)


@pytest.mark.parametrize(("law", "load"), [(HARD_CORE, 1e-3), (HARD_CORE, -1e-3),
                                           (rc.MaugisDugdale(0.01, 0.5), 1e-3)])  # fmt: skip
def test_hard_core_same_answer_as_the_numpy_one_minimisation(x64, law, load):
    # the bounded loop with the wall's multiplier fixed at the load, the mean of w free
    h, sub = surface()
    ref = rc.solve(h, sub, law, load=load)
    res = rc.solve(jnp.asarray(h), sub, law, load=load)
    agree(res, ref, load)
    assert res.solver == "bounded-cg"
    ref2 = rc.solve(h, sub, law, load=load + 2e-3, initial=ref)
    res2 = rc.solve(jnp.asarray(h), sub, law, load=load + 2e-3, initial=res)
    agree(res2, ref2, load + 2e-3)


def test_hard_core_full_contact_and_detached(x64):
    h, sub = surface()
    res = rc.solve(jnp.asarray(h), sub, HARD_CORE, load=0.5)  # only full contact carries it
    assert res.status is SolveStatus.CONVERGED and res.repulsive_area == 1.0, res.message
    assert abs(res.load - 0.5) <= res.tol and "full contact" in res.message
    off = rc.solve(jnp.asarray(h), sub, HARD_CORE, load=-0.2)  # beyond the pull-off force
    assert off.status is SolveStatus.DETACHED and "pull-off" in off.message


def test_the_bounded_loop_takes_the_load_without_the_host(x64):
    from roughcontact.solvers import _bounded_jax as bj
    from roughcontact.solvers.bounded import minimize_energy_bounded
    from roughcontact.solvers.bounded_rules import ON_WALL

    h, sub = surface()
    d = float(h.max())
    hj = jnp.asarray(h)
    st, k = bj.prepare(jnp.zeros_like(hj), sub, base=d - hj, wall_tol=ON_WALL * float(h.std()),
                       tol=1e-8, max_iter=500, restart_every=200, load=1e-3, heights=hj,
                       law=HARD_CORE)  # fmt: skip
    static = {"law": HARD_CORE, "rigid": True, "stall": False}
    first, second, third = donatable(st, 3)
    with jax.transfer_guard("disallow"):
        final = bj.run(first, k, **static)  # compiles and runs
        final = bj.run(second, k, **static)  # the compiled program
        with pytest.raises(Exception, match="(?i)disallowed"):
            bj.run(third, k._replace(load=1e-3), **static)
    assert_donated(second)
    ref = minimize_energy_bounded(h, sub, HARD_CORE, offset=d, load=1e-3)
    assert int(final.status) == bj.CONVERGED and int(final.it) == ref.iterations
    traction = np.asarray(bj.fields(final, k, HARD_CORE)[0])
    assert rel_l2(traction, ref.pressure) <= 1e-6
    assert abs(float(traction.mean()) - 1e-3) <= 1e-8


def test_physical_scale_on_the_device(x64):
    # load control's pressure scale from JAX heights: the rms slope computed on their
    # device (one scalar read, not the grid), the NumPy value
    from roughcontact.solvers.adhesive_rules import rms_slope

    h, sub = surface()
    assert rms_slope(jnp.asarray(h), 1.0) == pytest.approx(rms_slope(h, 1.0), rel=1e-12)
    assert physical_pressure_scale(jnp.asarray(h), sub, LAW) == pytest.approx(
        physical_pressure_scale(h, sub, LAW), rel=1e-12
    )


@pytest.mark.parametrize("law", [LAW, HARD_CORE])
def test_float32_load_control(x32, law):
    # float32 heights with JAX's x64 switch off: float32 fields, the load carried to the
    # float32 tolerance, iterations as the NumPy float32 one-minimisation solve's (1.25x)
    h, sub = surface()
    ref = rc.solve(h, sub, law, load=1e-3, dtype="float32")
    res = rc.solve(jnp.asarray(h, dtype=jnp.float32), sub, law, load=1e-3)
    assert res.status is SolveStatus.CONVERGED, res.message
    assert res.pressure.dtype == jnp.float32 and abs(res.load - 1e-3) <= 2 * res.tol
    assert res.iterations <= 1.25 * ref.iterations + 1
    assert rel_l2(res.pressure, np.asarray(ref.pressure, dtype=float)) <= 1e-3


def test_the_coarse_start_in_the_compiled_loop(x64):
    # nested iteration of a cold load-controlled solve (load_control._coarse_start, 128²
    # and up): the compiled loop solves the coarse grid too, with the NumPy loop's answers
    h, sub = surface(128)
    ref = rc.solve(h, sub, LAW, load=0.0)
    res = rc.solve(jnp.asarray(h), sub, LAW, load=0.0)
    assert "coarsened grid" in ref.message and "coarsened grid" in res.message
    agree(res, ref, 0.0)
    assert isinstance(res.pressure, jax.Array)


def _first_contact_case():
    h = rc.self_affine((64, 64), hurst=0.5, rms_slope=0.2, short_cutoff=4, seed=1)
    return h, rc.Substrate(h.shape), rc.MaugisDugdale(work_of_adhesion=0.002, range=0.2)


def test_a_cold_hard_core_reaches_contact_from_the_first_wall_contact_as_on_numpy(x64):
    # the compiled bounded loop's search upward from the first wall contact
    # (bounded_rules.CONTACT_DOUBLINGS): the NumPy loop's state, no restart (94 iterations
    # before, with a restart; 12 now). (With Maugis-Dugdale on this surface the two loops
    # take 13 iterations each to two states carrying load 0: at iteration 3 their line
    # searches get the same inputs to 1e-15 and stop at alpha 5.3 and 76.5, far beyond the
    # wall, where the law is flat and the projected search takes over.)
    h, sub, _ = _first_contact_case()
    law = rc.Exponential(work_of_adhesion=0.002, range=0.2)
    ref = rc.solve(h, sub, law, load=0.0)
    res = rc.solve(jnp.asarray(h), sub, law, load=0.0)
    assert isinstance(res.pressure, jax.Array)
    assert "hard-wall" not in res.message and "hard-wall" not in ref.message
    agree(res, ref, 0.0)


def test_a_cold_hard_core_past_its_budget_restarts_as_on_numpy(x64, monkeypatch):
    # the same budget and the same hard-wall start (the hard wall's compiled loop on the
    # device), forced by a budget of 5 iterations: the NumPy loop's state
    h, sub, law = _first_contact_case()
    monkeypatch.setattr(load_control, "COLD_HARD_CORE_BUDGET", 5)
    ref = rc.solve(h, sub, law, load=0.0)
    res = rc.solve(jnp.asarray(h), sub, law, load=0.0)
    assert isinstance(res.pressure, jax.Array)
    assert "started from the hard-wall state" in res.message
    assert "started from the hard-wall state" in ref.message
    agree(res, ref, 0.0)
