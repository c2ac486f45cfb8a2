"""The backend-agnostic parts of the core run on array_api_strict arrays (CPU).

array_api_strict implements only the array API standard, so any NumPy-only call that
slipped into these functions fails here; results must equal the NumPy ones. (The
hard-wall solver has a NumPy loop on index arrays and an array-API loop on masks; the
latter runs here and must take the same steps as the former.)
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


def test_smooth_solver_and_path():
    h = rc.self_affine((32, 32), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=3)
    sub = rc.Substrate((32, 32))
    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    d = float(h.max()) + 0.6
    ref = rc.solve(h, sub, law, offset=d, tol=1e-9)
    got = rc.solve(strict(h), sub, law, offset=d, tol=1e-9)
    assert got.converged and got.iterations == ref.iterations
    np.testing.assert_allclose(got.pressure, ref.pressure, rtol=1e-9, atol=1e-12)
    assert got.repulsive_area == ref.repulsive_area
    offsets = d + np.array([0.4, 0.2, 0.0])
    path = rc.approach_retract(strict(h), sub, law, offsets=offsets, tol=1e-8)
    np.testing.assert_allclose(
        path["load"], rc.approach_retract(h, sub, law, offsets=offsets, tol=1e-8)["load"]
    )


@pytest.mark.parametrize(
    "law",
    [
        rc.Exponential(work_of_adhesion=0.01, range=0.4),
        rc.MaugisDugdale(work_of_adhesion=0.01, range=0.4),
    ],
    ids=lambda law: law.name,
)
def test_bounded_solver(law):
    h = rc.sphere((32, 32), 20.0)
    sub = rc.Substrate((32, 32))
    ref = rc.solve(h, sub, law, offset=-0.4, tol=1e-10)
    got = rc.solve(strict(h), sub, law, offset=-0.4, tol=1e-10)
    assert got.converged and abs(got.iterations - ref.iterations) <= 2
    # the same state to the solvers' tolerance (force imbalance 1e-10 E*): the float32
    # convolutions round differently in numpy.fft (strict) and scipy.fft (NumPy)
    np.testing.assert_allclose(got.pressure, ref.pressure, rtol=1e-9, atol=1e-10)


def test_load_control():
    h = rc.sphere((32, 32), 20.0)
    sub = rc.Substrate((32, 32))
    law = rc.Exponential(work_of_adhesion=0.01, range=0.4)
    ref = rc.solve(h, sub, law, load=-2e-4, tol=1e-10)
    got = rc.solve(strict(h), sub, law, load=-2e-4, tol=1e-10)
    assert got.converged and got.offset == pytest.approx(ref.offset, abs=1e-9)


@pytest.mark.parametrize("control", [{"load": 2e-3}, {"offset": None}], ids=["load", "offset"])
@pytest.mark.parametrize("thickness", [None, 10.0])
def test_hard_wall_dense_loop_takes_the_same_steps(control, thickness):
    h = rc.self_affine((48, 40), hurst=0.7, rms_slope=0.2, short_cutoff=4, seed=5)
    sub = rc.Substrate((48, 40), thickness=thickness, poisson=0.3)
    if "offset" in control:
        control = {"offset": float(h.max()) - 0.3 * float(h.std())}
    ref = rc.solve(h, sub, rc.HardWall(), tol=1e-10, **control)
    got = rc.solve(strict(h), sub, rc.HardWall(), tol=1e-10, **control)
    assert ref.converged and got.converged
    # the same steps (both add point responses when few sites change), up to round-off
    assert got.iterations == ref.iterations
    np.testing.assert_allclose(got.pressure, ref.pressure, rtol=1e-9, atol=1e-12 * ref.load)
    assert got.offset == pytest.approx(ref.offset, abs=1e-9)
    np.testing.assert_array_equal(got.pressure > 0, ref.pressure > 0)
    # warm start from a NumPy result, the other way round
    warm = rc.solve(strict(h), sub, rc.HardWall(), initial=ref, tol=1e-10, **control)
    assert warm.converged and warm.iterations <= 2


@pytest.mark.parametrize("thickness", [None, 10.0])
def test_hard_wall_dense_loop_same_steps_with_large_contact(thickness):
    # displacement control with most of the surface in contact: interpenetrating sites
    # join the preconditioned step and the rigid uniform mode gets its stiffness, in both
    # loops alike
    h = rc.self_affine((48, 40), hurst=0.7, rms_slope=0.2, short_cutoff=4, seed=5)
    sub = rc.Substrate((48, 40), thickness=thickness, poisson=0.5)
    offset = float(h.max()) - 2.5 * float(h.std())
    ref = rc.solve(h, sub, rc.HardWall(), offset=offset, tol=1e-10)
    got = rc.solve(strict(h), sub, rc.HardWall(), offset=offset, tol=1e-10)
    assert ref.converged and got.converged and ref.repulsive_area > 0.2
    assert got.iterations == ref.iterations
    np.testing.assert_allclose(got.pressure, ref.pressure, rtol=1e-9, atol=1e-12 * ref.load)


@pytest.mark.parametrize("control", [{"load": 2e-3}, {"offset": None}], ids=["load", "offset"])
def test_plain_hard_wall_dense_loop_takes_the_same_steps(control):
    from roughcontact.solvers import polonsky_keer

    h = rc.self_affine((48, 40), hurst=0.7, rms_slope=0.2, short_cutoff=4, seed=5)
    sub = rc.Substrate((48, 40))
    if "offset" in control:
        control = {"offset": float(h.max()) - 0.3 * float(h.std())}
    ref = polonsky_keer(h, sub, tol=1e-10, precondition=False, **control)
    got = polonsky_keer(strict(h), sub, tol=1e-10, precondition=False, **control)
    assert ref.converged and got.converged and got.iterations == ref.iterations
    np.testing.assert_allclose(got.pressure, ref.pressure, rtol=1e-9, atol=1e-12 * ref.load)


def test_hard_wall_path():
    h = rc.sphere((32, 32), 12.0)
    sub = rc.Substrate((32, 32))
    loads = [1e-3, 3e-3, 1e-2]
    ref = rc.approach_retract(h, sub, loads=loads, retract=False)
    got = rc.approach_retract(strict(h), sub, loads=loads, retract=False)
    np.testing.assert_allclose(got["offset"], ref["offset"], rtol=1e-9)
    np.testing.assert_array_equal(got["repulsive_area"], ref["repulsive_area"])


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
    assert ds.attrs["device"] == str(xp.Device("device1")) and bool(ds.attrs["all_converged"])


def test_hard_wall_nested_start_on_any_backend():
    # the coarse-grid start (block means, broadcast back) is array-API code: the same
    # coarse solves and fine steps as on NumPy
    n = 256  # NESTED_MIN_SIZE points: one coarse level
    h = rc.self_affine((n, n), hurst=0.8, rms_slope=0.1, short_cutoff=8, seed=2)
    sub = rc.Substrate((n, n))
    ref = rc.solve(h, sub, rc.HardWall(), load=2e-3, tol=1e-10)
    got = rc.solve(strict(h), sub, rc.HardWall(), load=2e-3, tol=1e-10)
    assert ref.converged and got.converged and got.iterations == ref.iterations
    np.testing.assert_allclose(got.pressure, ref.pressure, rtol=1e-9, atol=1e-12 * ref.load)


def test_hard_wall_dense_loop_same_steps_after_a_lost_contact_set():
    # the restart with plain steps and their end take the same course in both loops
    h = rc.self_affine((128, 128), hurst=0.8, rms_slope=0.1, short_cutoff=8, seed=2)
    sub = rc.Substrate((128, 128))
    offset = float(h.mean()) + 0.01 * float(h.std())
    ref = rc.solve(h, sub, rc.HardWall(), offset=offset, tol=1e-9)
    got = rc.solve(strict(h), sub, rc.HardWall(), offset=offset, tol=1e-9)
    assert ref.converged and got.converged and got.iterations == ref.iterations
    np.testing.assert_allclose(got.pressure, ref.pressure, rtol=1e-8, atol=1e-11 * ref.load)
