"""Precision and misuse on JAX heights: float64 without JAX's global x64 switch, float32
mode, a one-line error when traced inside ``jax.jit``, and a path after the switch was
turned on in a session that had used roughcontact already (issue 42)."""

import numpy as np
import pytest

import roughcontact as rc

jax = pytest.importorskip("jax")
jnp = pytest.importorskip("jax.numpy")

LAW = rc.SmoothLJ93.from_adhesion_length(0.005)


@pytest.fixture()
def x32():
    old = bool(jax.config.jax_enable_x64)
    jax.config.update("jax_enable_x64", False)
    yield
    jax.config.update("jax_enable_x64", old)


def rough(n=64):
    h = rc.self_affine((n, n), hurst=0.8, rms_slope=0.3, short_cutoff=4.0, seed=1)
    return h, rc.Substrate((n, n)), float(h.max() - 0.5 * h.std())


@pytest.mark.filterwarnings("error::UserWarning")  # JAX's truncation warnings included
def test_float64_without_the_global_switch(x32):
    h, sub, d = rough()
    res = rc.solve(jnp.asarray(h), sub, LAW, offset=d, dtype="float64")
    assert not jax.config.jax_enable_x64  # the user's setting is left alone
    assert res.pressure.dtype == jnp.float64 and res.converged, res.message
    # jnp.asarray(h) kept float32 heights (x64 off): the float64 solve of those
    ref = rc.solve(h.astype(np.float32).astype(np.float64), sub, LAW, offset=d)
    p = np.asarray(res.pressure)
    assert np.linalg.norm(p - ref.pressure) / np.linalg.norm(ref.pressure) <= 1e-6
    assert res.iterations == pytest.approx(ref.iterations, rel=0.25)
    # float64 heights made inside a scope are solved in float64 by default
    with jax.enable_x64(True):
        h64 = jnp.asarray(h)
    res = rc.solve(h64, sub, LAW, offset=d)
    assert res.pressure.dtype == jnp.float64 and res.converged
    ref = rc.solve(h, sub, LAW, offset=d)
    assert np.linalg.norm(np.asarray(res.pressure) - ref.pressure) <= 1e-6 * np.linalg.norm(
        ref.pressure
    )


@pytest.mark.filterwarnings("error::UserWarning")
def test_float32_mode_converges(x32):
    h, sub, d = rough()
    for law in (LAW, rc.MaugisDugdale(0.01, 0.5)):
        res = rc.solve(jnp.asarray(h), sub, law, offset=d)
        assert res.pressure.dtype == jnp.float32
        assert res.converged, res.message
        ref = rc.solve(h, sub, law, offset=d)
        assert abs(res.repulsive_area - ref.repulsive_area) * h.size <= 3
    res = rc.solve(jnp.asarray(h), sub, LAW, load=0.01)  # load control: the same precision
    assert res.pressure.dtype == jnp.float32 and res.converged, res.message
    assert res.load == pytest.approx(0.01, rel=1e-4)


@pytest.mark.parametrize("x64", [False, True])
def test_tracing_gives_a_one_line_error(x64):
    h, sub, d = rough(32)
    old = bool(jax.config.jax_enable_x64)
    jax.config.update("jax_enable_x64", x64)
    try:

        @jax.jit
        def solve_traced(x):
            return rc.solve(x, sub, LAW, offset=d).pressure

        @jax.jit
        def path_traced(x):
            return rc.approach_retract(x, sub, offsets=[d]).load

        for traced in (solve_traced, path_traced):
            with pytest.raises(rc.ParameterError, match="traced by jax.jit") as err:
                traced(jnp.asarray(h))
            assert "\n" not in str(err.value)
    finally:
        jax.config.update("jax_enable_x64", old)


def test_path_after_switching_x64_on_mid_session():
    h, sub, d = rough(32)
    old = bool(jax.config.jax_enable_x64)
    try:
        jax.config.update("jax_enable_x64", False)
        before = rc.approach_retract(jnp.asarray(h), sub, offsets=[d + 1.0, d])
        jax.config.update("jax_enable_x64", True)  # switched on once rc had been used
        for law in (None, LAW):
            path = rc.approach_retract(jnp.asarray(h), sub, law, offsets=[d + 1.0, d])
            assert path.attrs["dtype"] == "float64" and bool(path.attrs["all_converged"])
        assert path.sizes["step"] == 3 and float(path.repulsive_area[1]) > 0
        assert before.attrs["dtype"] == "float64"  # a path's default, x64 on or off
    finally:
        jax.config.update("jax_enable_x64", old)
