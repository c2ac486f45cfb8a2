"""The hard wall's compiled JAX loop: the NumPy solver's answer, Westergaard's, and a loop
that never talks to the host (checked under ``jax.transfer_guard("disallow")``)."""

import numpy as np
import pytest
from _helpers import assert_donated, donatable

import roughcontact as rc
from roughcontact.theory import (
    westergaard_contact_fraction,
    westergaard_full_contact_pressure,
    westergaard_pressure,
)

jax = pytest.importorskip("jax")
jnp = pytest.importorskip("jax.numpy")


def rough(n=64):
    h = rc.self_affine((n, n), hurst=0.8, rms_slope=0.1, short_cutoff=4.0, seed=3)
    return h, rc.Substrate((n, n))


@pytest.mark.parametrize("control", ["load", "offset"])
def test_same_answer_as_the_numpy_solver(x64, control):
    h, sub = rough()
    kw = {"load": 0.01} if control == "load" else {"offset": float(h.max() - 1.5 * h.std())}
    ref = rc.solve(h, sub, rc.HardWall(), **kw)
    res = rc.solve(jnp.asarray(h), sub, rc.HardWall(), **kw)
    assert ref.converged and res.converged, res.message
    assert res.residual <= 1e-8
    assert isinstance(res.pressure, jax.Array) and res.pressure.dtype == jnp.float64
    p = np.asarray(res.pressure)
    assert np.abs(p - ref.pressure).max() <= 1e-6 * ref.pressure.max()
    assert res.repulsive_area == ref.repulsive_area > 0.005
    assert res.offset == pytest.approx(ref.offset, abs=1e-8 * float(h.std()))
    assert res.load == pytest.approx(ref.load, rel=1e-10)
    np.testing.assert_allclose(np.asarray(res.gap), ref.gap, atol=1e-8 * float(h.std()))
    assert abs(res.iterations - ref.iterations) <= 2  # the same iteration


def test_plain_steps_agree_too(x64):
    h, sub = rough()
    ref = rc.polonsky_keer(h, sub, load=0.02, precondition=False)
    res = rc.polonsky_keer(jnp.asarray(h), sub, load=0.02, precondition=False)
    assert res.converged and ref.converged
    assert np.abs(np.asarray(res.pressure) - ref.pressure).max() <= 1e-6 * ref.pressure.max()


@pytest.mark.parametrize("fraction_of_pstar", [0.2, 0.6])
def test_westergaard(x64, fraction_of_pstar):
    n, amp = 256, 0.5
    lam = float(n)
    h = rc.sinusoid((n, 2), lam, amp)
    pstar = westergaard_full_contact_pressure(amp, lam, 1.0)
    pbar = fraction_of_pstar * pstar
    res = rc.solve(jnp.asarray(h), rc.Substrate((n, 2)), load=pbar, tol=1e-10)
    assert res.converged, res.message
    frac = westergaard_contact_fraction(pbar, amp, lam, 1.0)
    assert abs(res.repulsive_area - frac) * n <= 2.0  # within a pixel at each edge
    p_theory = westergaard_pressure(np.arange(n, dtype=float), pbar, amp, lam, 1.0)
    p = np.asarray(res.pressure)[:, 0]
    assert np.linalg.norm(p - p_theory) / np.linalg.norm(p_theory) < 0.03
    assert res.load == pytest.approx(pbar, rel=1e-12)


@pytest.mark.parametrize("control", ["load", "offset"])
def test_no_host_transfer_inside_the_loop(x64, control):
    from roughcontact.solvers import _pk_jax

    h, sub = rough()
    hj = jnp.asarray(h)
    target = 0.01 * h.size if control == "load" else None
    offset = None if control == "load" else float(h.max() - 1.5 * h.std())
    p0 = jnp.full(h.shape, 0.01) if control == "load" else jnp.maximum(hj - offset, 0.0)
    st, k = _pk_jax.prepare(p0, sub, h=hj, target=target, offset=offset, scale=float(h.std()),
                            winkler=0.5, tol=1e-8, max_iter=500, precondition=True)  # fmt: skip
    static = {"load": control == "load", "precondition": True, "rigid_mean": True}
    first, second, third = donatable(st, 3)
    with jax.transfer_guard("disallow"):
        final, d = _pk_jax.run(first, k, stall=False, **static)  # compiles and runs
        final, d = _pk_jax.run(second, k, stall=False, **static)  # the compiled program
        with pytest.raises(Exception, match="(?i)disallowed"):  # the guard is armed: a
            _pk_jax.run(third, k._replace(tol=1e-8), stall=False, **static)  # host scalar
    assert_donated(second)
    it, residual, status = (int(final.it), float(final.residual), int(final.status))
    assert status == _pk_jax.CONVERGED and residual <= 1e-8 and it > 5
    ref = rc.polonsky_keer(h, sub, load=None if target is None else 0.01, offset=offset)
    assert np.abs(np.asarray(final.p) - ref.pressure).max() <= 1e-6 * ref.pressure.max()
    assert float(d) == pytest.approx(ref.offset, abs=1e-8 * float(h.std()))


def test_iteration_cap_gives_unconverged(x64):
    h, sub = rough()
    res = rc.solve(jnp.asarray(h), sub, load=0.01, max_iter=3)
    assert not res.converged
    assert res.status is rc.SolveStatus.ITERATION_LIMIT
    assert res.iterations == 3 and res.residual > 1e-8
    # a stop other than convergence still returns G p exactly (not the step's increments)
    exact = sub.deflection(np.asarray(res.pressure))
    np.testing.assert_allclose(np.asarray(res.deflection), exact, rtol=0, atol=1e-14)


def test_bad_input_is_a_one_line_error(x64):
    h, sub = rough()
    bad = h.copy()
    bad[3, 4] = np.nan
    with pytest.raises(rc.ParameterError, match="finite"):
        rc.solve(jnp.asarray(bad), sub, load=0.01)
    with pytest.raises(rc.ParameterError, match="periodic substrate"):
        rc.solve(jnp.asarray(h), rc.Substrate(h.shape, periodic=False), load=0.01)
    with pytest.raises(rc.ParameterError, match="callback"):
        rc.solve(jnp.asarray(h), sub, load=0.01, callback=lambda it, r: False)


@pytest.mark.filterwarnings("error::UserWarning")  # no warning per float64 reduction
def test_float64_without_x64_and_float32_works(x32):
    h, sub = rough()
    res = rc.solve(jnp.asarray(h), sub, load=0.01, dtype="float64")  # no global switch
    assert not jax.config.jax_enable_x64  # (left as it was)
    assert res.pressure.dtype == jnp.float64 and res.converged, res.message
    h32 = h.astype(np.float32).astype(np.float64)  # what jnp.asarray(h) kept of h
    ref64 = rc.solve(h32, sub, load=0.01)
    p = np.asarray(res.pressure)
    assert np.abs(p - ref64.pressure).max() <= 1e-6 * ref64.pressure.max()
    res = rc.solve(jnp.asarray(h), sub, load=0.01)  # JAX's default: float32
    assert res.pressure.dtype == jnp.float32
    assert res.converged, res.message
    ref = rc.solve(h, sub, load=0.01)
    assert np.abs(np.asarray(res.pressure) - ref.pressure).max() <= 1e-4 * ref.pressure.max()
    assert abs(res.repulsive_area - ref.repulsive_area) * h.size <= 3


def test_lost_contact_set_restarts_as_the_numpy_loop(x64):
    # most of the surface in contact: the first preconditioned steps lose the whole
    # contact set, the loop restarts from the overlap with plain steps and returns to
    # preconditioned ones later (on the device: a lax.cond, no host decision)
    h = rc.self_affine((128, 128), hurst=0.8, rms_slope=0.1, short_cutoff=8, seed=2)
    sub = rc.Substrate((128, 128))
    offset = float(h.mean()) + 0.01 * float(h.std())
    ref = rc.solve(h, sub, offset=offset, tol=1e-9)
    res = rc.solve(jnp.asarray(h), sub, offset=offset, tol=1e-9)
    assert ref.converged and res.converged, res.message
    assert res.iterations < 80 and abs(res.iterations - ref.iterations) <= 3
    assert res.repulsive_area > 0.8
    np.testing.assert_allclose(np.asarray(res.pressure), ref.pressure,
                               atol=1e-7 * ref.pressure.max())  # fmt: skip
