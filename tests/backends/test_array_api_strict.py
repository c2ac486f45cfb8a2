"""The backend-agnostic parts of the core run on array_api_strict arrays (CPU).

array_api_strict implements only the array API standard, so any NumPy-only call that
slipped into these functions (the laws, the substrate's operators, the statistics) fails
here; results must equal the NumPy ones. Solves on array_api_strict heights go to the
compiled program and come back on the heights' device (``roughcontact._accelerator``;
the routing itself is tested in test_routing.py).
"""

import numpy as np
import pytest

import roughcontact as rc

xp = pytest.importorskip("array_api_strict")

LAWS = [
    rc.SmoothLJ93.from_adhesion_length(0.005),
    rc.LennardJones93(work_of_adhesion=0.01),
    rc.Exponential(work_of_adhesion=0.01, range=0.4),
    rc.Exponential(work_of_adhesion=0.01, range=0.4, core_stiffness=2.0),
    rc.MaugisDugdale(work_of_adhesion=0.01, range=0.4),
]


def strict(a):
    return xp.asarray(np.asarray(a))


@pytest.mark.parametrize("law", LAWS, ids=lambda law: law.name + str(law.hard_core))
def test_interaction_laws(law):
    g = np.linspace(-0.2, 2.0, 97)
    for method in ("energy", "pressure", "curvature"):
        got = getattr(law, method)(strict(g))
        assert isinstance(got, type(strict(g)))
        np.testing.assert_allclose(np.asarray(got), getattr(law, method)(g), rtol=1e-14)
    rep, att = law.classify(strict(g))
    np.testing.assert_array_equal(np.asarray(rep), law.classify(g)[0])
    np.testing.assert_array_equal(np.asarray(att), law.classify(g)[1])


@pytest.mark.parametrize("thickness", [None, 7.0])
def test_substrate_operators(thickness):
    sub = rc.Substrate((16, 12), thickness=thickness, poisson=0.3)
    p = np.random.default_rng(0).normal(size=(16, 12))
    w = sub.deflection(strict(p))
    assert isinstance(w, type(strict(p)))
    np.testing.assert_allclose(np.asarray(w), sub.deflection(p), rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(
        np.asarray(sub.pressure(w)), sub.pressure(sub.deflection(p)), rtol=1e-12, atol=1e-13
    )
    assert sub.energy(w) == pytest.approx(sub.energy(sub.deflection(p)), rel=1e-12)


def test_statistics():
    h = rc.self_affine((32, 24), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=3)
    assert rc.statistics(strict(h)).to_dict() == pytest.approx(rc.statistics(h).to_dict())


DEVICE_CASES = [
    (rc.HardWall(), "load", 2e-3),
    (rc.HardWall(), "offset", -0.1),
    (rc.SmoothLJ93.from_adhesion_length(0.005), "offset", 0.8),
    (rc.Exponential(work_of_adhesion=0.005, range=0.5), "offset", -0.1),
    (rc.Exponential(work_of_adhesion=0.005, range=0.5), "load", 1e-3),
]


@pytest.mark.parametrize(("law", "control", "value"), DEVICE_CASES)
def test_everything_stays_on_the_heights_device(law, control, value):
    # array_api_strict refuses to mix arrays of two devices, as a GPU would (cuda:1
    # against cuda:0); every array the core creates must follow the heights
    if not hasattr(xp, "Device"):
        pytest.skip("array_api_strict without multiple devices")
    other = xp.Device("device1")
    h = rc.self_affine((32, 32), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=3)
    sub = rc.Substrate((32, 32), thickness=7.0, poisson=0.3)
    value = value + float(h.max()) if control == "offset" else value
    ref = rc.solve(h, sub, law, **{control: value})
    got = rc.solve(xp.asarray(h, device=other), sub, law, **{control: value})
    # the record's fields stay there too (a host copy only through to_numpy)
    assert all(getattr(got, k).device == other for k in ("pressure", "gap", "deflection"))
    if isinstance(law, rc.Exponential) and control == "offset":
        # the bounded solver's path is sensitive to its float32 convolutions, which
        # numpy.fft (strict) and scipy.fft (NumPy) round differently: the same state
        # to the default tolerance (1e-8)
        assert got.converged and abs(got.iterations - ref.iterations) <= 2
        np.testing.assert_allclose(got.to_numpy().pressure, ref.pressure, rtol=1e-9, atol=1e-8)
    else:
        assert got.converged and got.iterations == ref.iterations
        np.testing.assert_allclose(got.to_numpy().pressure, ref.pressure, rtol=1e-9, atol=1e-12)
    warm = rc.solve(xp.asarray(h, device=other), sub, law, initial=ref, **{control: value})
    assert warm.converged
    # a warm start from a record on that device
    again = rc.solve(xp.asarray(h, device=other), sub, law, initial=got, **{control: value})
    assert again.converged and again.pressure.device == other


def test_paths_and_statistics_on_another_device():
    if not hasattr(xp, "Device"):
        pytest.skip("array_api_strict without multiple devices")
    h = rc.self_affine((32, 32), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=3)
    hd = xp.asarray(h, device=xp.Device("device1"))
    assert rc.statistics(hd).to_dict() == pytest.approx(rc.statistics(h).to_dict())
    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    offsets = float(h.max()) + np.array([1.2, 1.0, 0.8])
    ds = rc.approach_retract(hd, rc.Substrate((32, 32)), law, offsets=offsets)
    # computed by the compiled program on JAX's CPU device (the heights moved once)
    jax = pytest.importorskip("jax")
    assert ds.attrs["device"] == str(jax.devices("cpu")[0]) and bool(ds.attrs["all_converged"])
    ref = rc.approach_retract(h, rc.Substrate((32, 32)), law, offsets=offsets)
    np.testing.assert_allclose(ds["load"], ref["load"], rtol=1e-6, atol=1e-12)
