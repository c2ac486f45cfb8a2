"""Paths on JAX heights: each state a compiled solve warm-started on the device, the
per-state numbers read in a few transfers; the NumPy path's areas and jumps."""

import numpy as np
import pytest

import roughcontact as rc

jax = pytest.importorskip("jax")
jnp = pytest.importorskip("jax.numpy")


def rough(n=64):
    h = rc.self_affine((n, n), hurst=0.8, rms_slope=0.3, short_cutoff=4.0, seed=1)
    return h, rc.Substrate((n, n))


def same_path(pj, ref):
    for key in ("repulsive_area", "attractive_area", "load", "offset"):
        np.testing.assert_allclose(pj[key].values, ref[key].values, rtol=0, atol=1e-6)
    np.testing.assert_array_equal(pj.jump.values, ref.jump.values)
    np.testing.assert_array_equal(pj.repulsive_patches.values, ref.repulsive_patches.values)
    assert bool(pj.attrs["all_converged"]) and bool(ref.attrs["all_converged"])


def test_approach_retract_with_jumps(x64):
    h, sub = rough()
    law = rc.SmoothLJ93.from_adhesion_length(0.05)
    offsets = np.linspace(h.max() + 1.0, h.max() - 1.5 * h.std(), 8)
    ref = rc.approach_retract(h, sub, law, offsets=offsets, fields_at=[3])
    pj = rc.approach_retract(jnp.asarray(h), sub, law, offsets=offsets, fields_at=[3])
    same_path(pj, ref)
    assert int(ref.jump.sum()) >= 1  # the path snaps: the jumps are compared
    assert pj.attrs["dtype"] == "float64"
    np.testing.assert_allclose(pj.pressure.values, ref.pressure.values, atol=1e-8)


def test_load_path_and_run_path(x64):
    from roughcontact.workflows.pipeline import run_path

    h, sub = rough()
    law = rc.MaugisDugdale(0.01, 0.5)
    ref = rc.approach_retract(h, sub, law, loads=[0.002, 0.01])
    pj = rc.approach_retract(jnp.asarray(h), sub, law, loads=[0.002, 0.01])
    same_path(pj, ref)
    kw = {"offsets": [0.5, 0.0, -0.5], "offset_unit": "rms_height", "analysis": {}}
    a = run_path(h, sub, law, **kw)
    b = run_path(jnp.asarray(h), sub, law, **kw)
    same_path(b.path, a.path)
    assert b.pull_off == pytest.approx(a.pull_off, rel=1e-6, abs=1e-12)


def test_patch_count_on_the_device():
    from roughcontact.analysis.contact_geometry import count_patches, patch_count

    rng = np.random.default_rng(1)
    for _ in range(20):
        shape = tuple(rng.integers(1, 24, 2))
        mask = rng.random(shape) < rng.random()
        for periodic in (True, False):
            on_device = patch_count(jnp.asarray(mask), periodic=periodic)
            assert isinstance(on_device, jax.Array)  # fetched with the state's numbers
            assert int(on_device) == count_patches(mask, periodic=periodic)


def test_one_read_per_state(x64, monkeypatch):
    # the states' solves read their outcome with their record, and the path's patch counts
    # and jumps come in one read when the dataset is made: reads = states + 2 (the heights'
    # statistics once, the patch counts and jumps once)
    import roughcontact.solvers.reductions as reductions

    h, sub = rough()
    law = rc.SmoothLJ93.from_adhesion_length(0.05)
    offsets = np.linspace(h.max() + 1.0, h.max() - 1.5 * h.std(), 4)
    rc.approach_retract(jnp.asarray(h), sub, law, offsets=offsets)  # compiles
    reads = []
    to_numpy = reductions.to_numpy
    monkeypatch.setattr(reductions, "to_numpy", lambda x: reads.append(x.shape) or to_numpy(x))
    path = rc.approach_retract(jnp.asarray(h), sub, law, offsets=offsets)
    assert path.sizes["step"] == 7
    assert len(reads) <= 7 + 2, reads
