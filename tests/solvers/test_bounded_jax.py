"""The bounded solver's compiled JAX loop (:mod:`roughcontact.solvers._bounded_jax`) and
adhesive load control on JAX heights: the NumPy loops' iterations and answers, and a
loop that never talks to the host (``jax.transfer_guard("disallow")``)."""

import numpy as np
import pytest
from _helpers import assert_donated, donatable

import roughcontact as rc

jax = pytest.importorskip("jax")
jnp = pytest.importorskip("jax.numpy")

DUGDALE = rc.MaugisDugdale(0.01, 0.5)
HARD_EXP = rc.Exponential(0.01, 0.5)
SOFT_CORE = rc.Exponential(0.01, 0.5, core_stiffness=1.0)


def rough(n=64, seed=1):
    """Heights (rms ~1-2 pixels), the substrate and the heights' top."""
    h = rc.self_affine((n, n), hurst=0.8, rms_slope=0.3, short_cutoff=4.0, seed=seed)
    return h, rc.Substrate((n, n))


def agree(res, ref):
    """The acceptance of issue 38: iterations within 1.25x, pressures to 1e-6 (rel. L2)."""
    assert ref.converged and res.converged, res.message
    assert res.iterations <= 1.25 * ref.iterations + 1
    assert ref.iterations <= 1.25 * res.iterations + 1
    p = np.asarray(res.pressure)
    assert np.linalg.norm(p - ref.pressure) / np.linalg.norm(ref.pressure) <= 1e-6
    assert res.repulsive_area == pytest.approx(ref.repulsive_area, abs=1e-6)
    assert res.attractive_area == pytest.approx(ref.attractive_area, abs=1e-6)
    assert res.load == pytest.approx(ref.load, rel=1e-6, abs=1e-12)


@pytest.mark.parametrize("law", [DUGDALE, HARD_EXP])
def test_same_answer_as_the_numpy_loop(x64, law):
    h, sub = rough()
    # deep enough that the first steps cross the wall (projection, halvings)
    d = float(h.max() - 1.5 * h.std())
    ref = rc.solve(h, sub, law, offset=d)
    res = rc.solve(jnp.asarray(h), sub, law, offset=d)
    agree(res, ref)
    assert isinstance(res.pressure, jax.Array) and res.solver == "bounded-cg"
    assert float(jnp.min(res.gap)) >= -1e-12 * float(h.std())  # the wall holds
    ref2 = rc.solve(h, sub, law, offset=d + 0.5 * float(h.std()), initial=ref)
    res2 = rc.solve(jnp.asarray(h), sub, law, offset=d + 0.5 * float(h.std()), initial=res)
    agree(res2, ref2)


@pytest.mark.parametrize("law", [DUGDALE, HARD_EXP])
def test_offset_at_the_mean_is_full_contact_as_on_numpy(x64, law):
    # the one feasible state of offset = mean(h) (test_bounded.py): converged at once with
    # the smallest reaction as the multiplier, and the same note
    h, sub = rough()
    d = float(np.mean(h))
    ref = rc.solve(h, sub, law, offset=d)
    res = rc.solve(jnp.asarray(h), sub, law, offset=d)
    agree(res, ref)
    assert "full contact" in res.message and "full contact" in ref.message


def test_no_host_transfer_inside_the_loop(x64):
    from roughcontact.solvers import _bounded_jax as bj

    h, sub = rough()
    d = float(h.max() - 1.5 * h.std())
    base = jnp.asarray(d - h)
    st, k = bj.prepare(jnp.zeros_like(base), sub, base=base, wall_tol=1e-12 * float(h.std()),
                       tol=1e-8, max_iter=500, restart_every=200)  # fmt: skip
    static = {"law": HARD_EXP, "rigid": True, "stall": False}
    first, second, third = donatable(st, 3)
    with jax.transfer_guard("disallow"):
        final = bj.run(first, k, **static)  # compiles and runs
        final = bj.run(second, k, **static)  # the compiled program
        with pytest.raises(Exception, match="(?i)disallowed"):  # the guard is armed: a
            bj.run(third, k._replace(tol=1e-8), **static)  # host scalar is refused
    assert_donated(second)
    assert int(final.status) == bj.CONVERGED and float(final.residual) <= 1e-8
    ref = rc.solve(h, sub, HARD_EXP, offset=d)
    assert int(final.it) == ref.iterations


def test_projection_matches_numpy(x64):
    from roughcontact.solvers import _bounded_jax as bj
    from roughcontact.solvers.bounded import project_feasible

    rng = np.random.default_rng(0)
    v, lower = rng.normal(size=(32, 32)), rng.normal(size=(32, 32)) - 0.5
    ref = project_feasible(v.reshape(-1), lower.reshape(-1), True).reshape(32, 32)
    u = np.asarray(bj.project(jnp.asarray(v), jnp.asarray(lower), True, jnp.float64))
    np.testing.assert_allclose(u, ref, atol=1e-12)
    assert abs(u.mean()) <= 1e-13 and (u >= lower).all()


@pytest.mark.parametrize(("law", "load"), [(SOFT_CORE, 0.005), (HARD_EXP, 0.01)])
def test_load_control(x64, law, load):
    h, sub = rough()
    ref = rc.solve(h, sub, law, load=load)
    res = rc.solve(jnp.asarray(h), sub, law, load=load)
    agree(res, ref)
    assert res.load == pytest.approx(load, abs=1e-8)
    assert res.offset == pytest.approx(ref.offset, abs=1e-8 * float(h.std()))
