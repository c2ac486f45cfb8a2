"""The smooth solver's compiled JAX loop (:mod:`roughcontact.solvers._smooth_jax`): the
NumPy loop's iterations and answers, warm starts, and a loop that never talks to the host
(checked under ``jax.transfer_guard("disallow")``)."""

import numpy as np
import pytest
from _helpers import assert_donated, donatable

import roughcontact as rc

jax = pytest.importorskip("jax")
jnp = pytest.importorskip("jax.numpy")

LAW = rc.SmoothLJ93.from_adhesion_length(0.005)
SOFT_CORE = rc.Exponential(0.01, 0.5, core_stiffness=1.0)


def rough(n=64, seed=1):
    """Heights (a0 = 1: rms ~1-2 a0), the substrate, and an offset with 1-10 % of the
    surface in repulsive and attractive contact."""
    h = rc.self_affine((n, n), hurst=0.8, rms_slope=0.3, short_cutoff=4.0, seed=seed)
    return h, rc.Substrate((n, n)), float(h.max() - 0.5 * h.std())


def rel_l2(a, b):
    return float(np.linalg.norm(np.asarray(a) - b) / np.linalg.norm(b))


def agree(res, ref):
    """The acceptance of issue 38: iterations within 1.25x, pressures to 1e-6 (rel. L2)."""
    assert ref.converged and res.converged, res.message
    assert res.iterations <= 1.25 * ref.iterations + 1
    assert ref.iterations <= 1.25 * res.iterations + 1
    assert rel_l2(res.pressure, ref.pressure) <= 1e-6
    assert res.repulsive_area == pytest.approx(ref.repulsive_area, abs=1e-6)
    assert res.attractive_area == pytest.approx(ref.attractive_area, abs=1e-6)
    assert res.load == pytest.approx(ref.load, rel=1e-6, abs=1e-12)


@pytest.mark.parametrize(("law", "n"), [(LAW, 64), (SOFT_CORE, 64), (LAW, 128)])
def test_same_answer_as_the_numpy_loop(x64, law, n):
    h, sub, d = rough(n, seed=n // 64)
    ref = rc.solve(h, sub, law, offset=d)
    res = rc.solve(jnp.asarray(h), sub, law, offset=d)
    agree(res, ref)
    assert isinstance(res.pressure, jax.Array) and res.pressure.dtype == jnp.float64
    assert res.solver == ref.solver and res.residual <= 1e-8
    np.testing.assert_allclose(np.asarray(res.gap), ref.gap, atol=1e-8 * float(h.std()))
    # a warm start from the result (on the device) as the NumPy loop's from its own
    ref2 = rc.solve(h, sub, law, offset=d - 0.2 * float(h.std()), initial=ref)
    res2 = rc.solve(jnp.asarray(h), sub, law, offset=d - 0.2 * float(h.std()), initial=res)
    agree(res2, ref2)


def test_the_issue_example_solves(x64):
    h, _, d = rough()
    res = rc.solve(jnp.asarray(h), rc.Substrate(h.shape), LAW, offset=d)
    assert res.converged and res.repulsive_area > 0 and res.attractive_area > 0


def test_no_host_transfer_inside_the_loop(x64):
    from roughcontact.solvers import _smooth_jax as sj

    h, sub, d = rough()
    base = jnp.asarray(d - h)
    st, k = sj.prepare(jnp.zeros_like(base), sub, LAW, base=base, tol=1e-8, max_iter=500,
                       restart_every=200, refresh_every=10, warm=False)  # fmt: skip
    static = {"law": LAW, "rigid": True, "stall": False, "floor": True}
    first, second, third = donatable(st, 3)
    with jax.transfer_guard("disallow"):
        final = sj.run(first, k, **static)  # compiles and runs
        final = sj.run(second, k, **static)  # the compiled program
        with pytest.raises(Exception, match="(?i)disallowed"):  # the guard is armed: a
            sj.run(third, k._replace(tol=1e-8), **static)  # host scalar is refused
    assert_donated(second)
    assert int(final.status) == sj.CONVERGED and float(final.residual) <= 1e-8
    ref = rc.solve(h, sub, LAW, offset=d)
    assert int(final.it) == ref.iterations
    assert rel_l2(LAW.pressure(np.asarray(final.gap)), ref.pressure) <= 1e-6


def test_iteration_cap_gives_unconverged(x64):
    h, sub, d = rough()
    res = rc.solve(jnp.asarray(h), sub, LAW, offset=d, max_iter=7)
    ref = rc.solve(h, sub, LAW, offset=d, max_iter=7)
    assert res.status is rc.SolveStatus.ITERATION_LIMIT and not res.converged
    assert res.iterations == ref.iterations == 7
    assert res.residual == pytest.approx(ref.residual, rel=1e-6)


def test_float32_converges(x32):
    h, sub, d = rough()
    res = rc.solve(jnp.asarray(h, dtype=jnp.float32), sub, LAW, offset=d)
    assert res.pressure.dtype == jnp.float32
    assert res.converged, res.message
    ref = rc.solve(h, sub, LAW, offset=d)
    assert rel_l2(res.pressure, ref.pressure) <= 1e-4
    assert abs(res.repulsive_area - ref.repulsive_area) * h.size <= 3


@pytest.mark.parametrize("loop", ["numpy", "jax"])
def test_float32_converges_beside_a_deep_pit(x64, loop):
    # one site 100 a0 deep: a gap of 100 a0 rounds to 7.6e-6 a0 in float32, and K w formed
    # from gap - base carried that rounding (a residual floor ~1e-5 E*: "stalled" after 200
    # iterations). Both loops advance w itself in float32 and converge as without the pit
    h = rc.self_affine((128, 128), hurst=0.8, rms_slope=0.1, short_cutoff=8, long_cutoff=64, seed=1)
    h[128 // 3, 128 // 5] -= 100.0
    sub = rc.Substrate(h.shape)
    d = rc.solve(h, sub, load=5e-4).offset + 1.0
    ref = rc.solve(h, sub, LAW, offset=d)
    single = h.astype(np.float32) if loop == "numpy" else jnp.asarray(h, dtype=jnp.float32)
    res = rc.solve(single, sub, LAW, offset=d, dtype="float32")
    assert res.converged, res.message
    assert res.iterations <= 2 * ref.iterations
    assert abs(res.repulsive_area - ref.repulsive_area) * h.size <= 3
    assert np.max(np.abs(np.asarray(res.deflection, dtype=float) - ref.deflection)) <= 1e-4


def test_float64_floor_guard_as_the_numpy_loop(x64):
    # deep compression (pressures ~1e9 E*): both loops stop at the rounding floor, alike,
    # and judge it on the physical pressure scale: a runaway, not "stalled"
    h = rc.self_affine((64, 64), hurst=0.8, rms_slope=0.1, short_cutoff=4.0, seed=1)
    sub = rc.Substrate((64, 64))
    law = rc.SmoothLJ93(contact_modulus=1.0, pixel_size=1.0, work_of_adhesion=0.05)
    ref = rc.solve(h, sub, law, offset=float(h.max()) - 0.7)
    res = rc.solve(jnp.asarray(h), sub, law, offset=float(h.max()) - 0.7)
    assert ref.status is res.status is rc.SolveStatus.RUNAWAY
    assert res.message.startswith("runaway: pressures reach"), res.message
    assert res.iterations == pytest.approx(ref.iterations, rel=0.25)


@pytest.mark.parametrize("precision", ["x32", "x64"])
def test_deep_compression_is_a_runaway_on_jax_as_on_numpy(precision, request):
    # pushed 1 a0 below max(h) with w = 0.05: uniform pressures ~1e13 E*, beyond any
    # elastic equilibrium. NumPy says "runaway"; in float32 the compiled loop's force
    # balance of those pressures rounds to exactly 0 and once came back "converged"
    request.getfixturevalue(precision)
    h = rc.self_affine((64, 64), hurst=0.8, rms_slope=0.1, short_cutoff=4.0, seed=1)
    sub = rc.Substrate((64, 64))
    law = rc.SmoothLJ93(contact_modulus=1.0, pixel_size=1.0, work_of_adhesion=0.05)
    offset = float(h.max()) - 1.0
    ref = rc.solve(h, sub, law, offset=offset)
    res = rc.solve(jnp.asarray(h), sub, law, offset=offset)
    assert ref.status is rc.SolveStatus.RUNAWAY
    assert res.status is rc.SolveStatus.RUNAWAY and not res.converged, res.message
    assert res.message.startswith("runaway: pressures reach"), res.message
    # one that rounds its force balance to 0 in float64 too (the NumPy loop once said
    # "converged" there): the same verdict in both loops
    from _helpers import flat_through_contact

    h2, law2, offset2 = flat_through_contact()
    for heights in (h2, jnp.asarray(h2)):
        flat = rc.solve(heights, sub, law2, offset=offset2)
        assert flat.status is rc.SolveStatus.RUNAWAY, flat.message
    # a physical state of the same surface is not touched by the check
    ok = rc.solve(jnp.asarray(h), sub, law, offset=float(h.max()) + 0.5)
    assert ok.converged
