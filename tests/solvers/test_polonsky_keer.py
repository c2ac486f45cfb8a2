"""Hard-wall solver against Westergaard, Hertz and exact identities."""

import importlib

import numpy as np
import pytest

import roughcontact as rc
from roughcontact.theory import (
    hertz,
    westergaard_contact_fraction,
    westergaard_full_contact_pressure,
    westergaard_pressure,
)


def wavy(n=512, amplitude=0.5):
    wavelength = float(n)
    h = rc.sinusoid((n, 2), wavelength, amplitude)
    return h, rc.Substrate((n, 2)), wavelength, amplitude


@pytest.mark.parametrize("fraction_of_pstar", [0.05, 0.2, 0.5, 0.8])
def test_westergaard_area_and_pressure(fraction_of_pstar):
    h, sub, lam, amp = wavy()
    pstar = westergaard_full_contact_pressure(amp, lam, 1.0)
    pbar = fraction_of_pstar * pstar
    res = rc.solve(h, sub, rc.HardWall(), load=pbar, tol=1e-10)
    assert res.converged
    frac = westergaard_contact_fraction(pbar, amp, lam, 1.0)
    n = h.shape[0]
    assert abs(res.repulsive_area - frac) * n <= 2.0  # within a pixel at each edge
    x = np.arange(n, dtype=float)
    p_theory = westergaard_pressure(x, pbar, amp, lam, 1.0)
    p = res.pressure[:, 0]
    err = np.linalg.norm(p - p_theory) / np.linalg.norm(p_theory)
    assert err < 0.03
    assert res.load == pytest.approx(pbar, rel=1e-12)


def test_westergaard_full_contact():
    h, sub, lam, amp = wavy(256)
    pstar = westergaard_full_contact_pressure(amp, lam, 1.0)
    res = rc.solve(h, sub, load=1.2 * pstar, tol=1e-10)
    assert res.repulsive_area == 1.0
    x = np.arange(h.shape[0], dtype=float)
    np.testing.assert_allclose(
        res.pressure[:, 0], 1.2 * pstar + pstar * np.cos(2 * np.pi * x / lam), atol=1e-8 * pstar
    )


def test_hertz_sphere_in_large_periodic_cell():
    n, radius = 256, 250.0
    h = rc.sphere((n, n), radius)
    sub = rc.Substrate((n, n), contact_modulus=2.0)
    loads = [40.0, 80.0, 160.0]  # total loads N
    indent_excess = []
    for total in loads:
        res = rc.solve(h, sub, load=total / sub.nominal_area, tol=1e-10)
        hz = hertz(load=total, radius=radius, contact_modulus=2.0)
        assert res.converged
        # contact radius from the area and central pressure
        a = np.sqrt(res.repulsive_area * sub.nominal_area / np.pi)
        assert a == pytest.approx(hz.contact_radius, rel=0.03)
        assert res.pressure.max() == pytest.approx(hz.central_pressure, rel=0.03)
        # indentation: summit h = 0 at zero gap, so the centre deflection is -offset
        indent_excess.append((-res.offset - hz.indentation) / total)
    # periodic images and the zero mean deflection add a term linear in N
    assert np.ptp(indent_excess) < 0.03 * abs(np.mean(indent_excess))


@pytest.fixture(scope="module")
def rough():
    h = rc.self_affine((128, 128), hurst=0.8, rms_slope=0.1, short_cutoff=8, seed=3)
    return h, rc.Substrate((128, 128))


def test_signorini_conditions_and_load(rough):
    h, sub = rough
    res = rc.solve(h, sub, load=1e-3, tol=1e-9)
    assert res.converged and res.residual <= 1e-9
    assert res.pressure.min() >= 0
    hrms = h.std()
    assert res.gap.min() >= -2e-9 * hrms
    assert np.abs(res.gap[res.pressure > 0]).max() <= 2e-9 * hrms
    assert res.load == pytest.approx(1e-3, rel=1e-12)
    assert res.repulsive_load == pytest.approx(1e-3, rel=1e-12)
    assert res.attractive_area == 0 and res.attractive_load == 0
    np.testing.assert_allclose(res.deflection, sub.deflection(res.pressure), atol=1e-12)
    assert res.perimeter_edges == rc.perimeter_edges(res.pressure > 0)


def test_displacement_control_matches_load_control(rough):
    h, sub = rough
    by_load = rc.solve(h, sub, load=2e-3, tol=1e-10)
    by_offset = rc.solve(h, sub, offset=by_load.offset, tol=1e-10)
    assert by_offset.converged
    assert by_offset.load == pytest.approx(2e-3, rel=1e-6)
    assert by_offset.repulsive_area == pytest.approx(by_load.repulsive_area, abs=2 / h.size)


def test_warm_start_saves_iterations(rough):
    h, sub = rough
    first = rc.solve(h, sub, load=1e-3)
    again = rc.solve(h, sub, load=1e-3, initial=first)
    assert again.converged and again.iterations < first.iterations
    np.testing.assert_allclose(again.pressure, first.pressure, atol=1e-6 * first.pressure.max())


def test_finite_layer_mean_pressure_is_uniform_mode_times_mean_deflection(rough):
    h, _ = rough
    sub = rc.Substrate(h.shape, thickness=64.0, poisson=0.3)
    res = rc.solve(h, sub, offset=h.max() - 0.5, tol=1e-10)
    assert res.converged
    k0 = rc.elastic.uniaxial_layer_stiffness(64.0, 1.0, 0.3)
    assert res.load == pytest.approx(k0 * res.deflection.mean(), rel=1e-8)


def test_nonadhesive_kappa_rep_near_two():
    # Pastewka & Robbins 2014, Eq. 2: kappa_rep close to 2 (literature 1.8-2.6)
    n = 256
    h = rc.self_affine((n, n), hurst=0.8, rms_slope=0.1, short_cutoff=8, seed=11)
    sub = rc.Substrate((n, n))
    areas, loads, prev = [], [], None
    for load in np.geomspace(2e-4, 1e-3, 4):
        prev = rc.solve(h, sub, load=load, initial=prev)
        areas.append(prev.repulsive_area)
        loads.append(prev.load)
    load_1 = rc.analysis.interpolate_at_area(areas, loads, 0.01)
    assert 1.8 <= rc.analysis.kappa(0.01, load_1, 0.1) <= 2.6


def test_no_contact_and_zero_load(rough):
    h, sub = rough
    res = rc.solve(h, sub, offset=h.max() + 1.0)
    assert res.converged and res.load == 0 and res.repulsive_area == 0
    res = rc.solve(h, sub, load=0.0)
    assert res.converged and res.repulsive_area == 0 and res.offset == pytest.approx(h.max())


def test_iteration_cap_is_reported(rough):
    h, sub = rough
    res = rc.solve(h, sub, load=1e-3, max_iter=3)
    assert not res.converged and res.iterations == 3
    assert "cap" in res.message and res.residual > res.tol


def test_callback_sees_every_iteration_and_can_stop(rough):
    h, sub = rough
    seen = []
    res = rc.solve(h, sub, load=1e-3, callback=lambda it, r: seen.append((it, r)) or it >= 5)
    assert [s[0] for s in seen] == [1, 2, 3, 4, 5]
    assert not res.converged and "callback" in res.message


@pytest.mark.parametrize(
    "heights,kwargs,match",
    [
        (np.full((8, 8), np.nan), {"load": 1e-3}, "heights"),
        (np.zeros(8), {"load": 1e-3}, "heights"),
        (np.zeros((8, 8)), {"load": -1e-3}, "load"),
        (np.zeros((8, 8)), {"load": 1e-3, "offset": 0.0}, "exactly one"),
        (np.zeros((8, 8)), {}, "exactly one"),
        (np.zeros((8, 9)), {"load": 1e-3}, "shape"),
        (np.zeros((8, 8)), {"load": 1e-3, "tol": 0.0}, "tol"),
    ],
)
def test_bad_input(heights, kwargs, match):
    with pytest.raises(rc.ParameterError, match=match):
        rc.solve(heights, rc.Substrate((8, 8)), **kwargs)


@pytest.mark.parametrize("control", ["load", "offset"])
def test_preconditioning_changes_the_path_not_the_solution(control):
    # Vollebregt's stiffness preconditioner on the contact set: the same Signorini
    # solution, in fewer iterations (the plain method's count grows with the patches)
    from roughcontact.solvers import polonsky_keer

    h = rc.self_affine((128, 128), hurst=0.8, rms_slope=0.1, short_cutoff=8, seed=3)
    sub = rc.Substrate((128, 128))
    kw = {"load": 1e-3} if control == "load" else {"offset": float(h.max() - 1.5 * h.std())}
    plain = polonsky_keer(h, sub, tol=1e-10, precondition=False, **kw)
    pre = polonsky_keer(h, sub, tol=1e-10, **kw)
    assert plain.converged and pre.converged
    assert 0.005 < pre.repulsive_area < 0.1
    np.testing.assert_array_equal(pre.pressure > 0, plain.pressure > 0)
    err = np.linalg.norm(pre.pressure - plain.pressure) / np.linalg.norm(plain.pressure)
    assert err < 1e-8
    assert pre.offset == pytest.approx(plain.offset, abs=1e-9 * h.std())
    assert pre.iterations < plain.iterations


@pytest.mark.parametrize("control", ["load", "offset"])
@pytest.mark.parametrize("periodic_only", [False, True], ids=["default", "periodic-only"])
def test_single_precision_convolutions_reach_float64_accuracy(control, periodic_only, monkeypatch):
    # the step, correction and preconditioner convolutions run in float32 (~1e-7
    # rounding); exact float64 evaluations replace their drift ("reliable updates"), so
    # a tolerance far below float32's resolution is met, checked here against an
    # independent float64 deflection. A replacement that comes late, when the drift
    # (~1e-7 of the distance travelled) exceeds the residual, restarts the conjugate
    # directions, which were built on the drifted field.
    import importlib

    from roughcontact.solvers import loop_control

    pk = importlib.import_module("roughcontact.solvers.polonsky_keer")
    if periodic_only:  # replacements that come late, when the drift exceeds the residual
        monkeypatch.setattr(loop_control, "RELIABLE_DROP", 0.0)
        monkeypatch.setattr(loop_control, "RELIABLE_EVERY", 20)
    h = rc.self_affine((128, 128), hurst=0.8, rms_slope=0.1, short_cutoff=8, seed=3)
    sub = rc.Substrate((128, 128))
    kw = {"load": 1e-3} if control == "load" else {"offset": float(h.max() - 1.5 * h.std())}
    res = pk.polonsky_keer(h, sub, tol=1e-12, **kw)
    assert res.converged and res.residual <= 1e-12
    gap = res.offset - h + sub.deflection(res.pressure)
    hrms = h.std()
    assert np.abs(gap[res.pressure > 0]).max() <= 2e-12 * hrms
    assert gap.min() >= -2e-12 * hrms


@pytest.mark.parametrize("thickness", [None, 20.0], ids=["half-space", "incompressible-layer"])
@pytest.mark.parametrize("depth", [2.0, 2.5, 3.0])
def test_displacement_control_with_large_contact_converges(depth, thickness):
    # deep offsets (a third to all of the surface in contact) on substrates with a rigid
    # uniform mode: the preconditioned steps once stalled here (the gap's mean never
    # entered the direction) or cycled through restarts until the iteration cap
    from roughcontact.solvers import polonsky_keer

    h = rc.self_affine((64, 64), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=1)
    sub = rc.Substrate((64, 64), thickness=thickness, poisson=0.5)
    offset = max(float(h.max() - depth * h.std()), 0.02 * float(h.std()))
    res = rc.solve(h, sub, offset=offset, tol=1e-10)
    assert res.converged and res.iterations < 100
    # Signorini conditions against an independent deflection of the returned pressure
    gap = offset - h + sub.deflection(res.pressure)
    hrms = h.std()
    assert res.pressure.min() >= 0 and 0.1 < res.repulsive_area < 1.0
    assert np.abs(gap[res.pressure > 0]).max() <= 2e-10 * hrms
    assert gap.min() >= -2e-10 * hrms
    # the plain method finds the same state
    plain = polonsky_keer(h, sub, offset=offset, tol=1e-10, precondition=False)
    np.testing.assert_allclose(res.pressure, plain.pressure, atol=1e-8 * plain.pressure.max())


@pytest.mark.parametrize("control", ["load", "offset"])
def test_steps_do_not_depend_on_the_units(control):
    # every step scales with E* (pressures) and a0 (lengths): the same iterations in
    # other units, the same solution scaled
    h = rc.self_affine((64, 64), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=2)
    kw = {"load": 2e-2} if control == "load" else {"offset": float(h.max() - 2.0 * h.std())}
    ref = rc.solve(h, rc.Substrate((64, 64)), tol=1e-10, **kw)
    es, a0 = 1e3, 1e-2  # heights scale with a0, pressures with E*
    scaled = {k: v * (es if k == "load" else a0) for k, v in kw.items()}
    sub = rc.Substrate((64, 64), contact_modulus=es, pixel_size=a0)
    got = rc.solve(h * a0, sub, tol=1e-10, **scaled)
    assert got.converged and abs(got.iterations - ref.iterations) <= 1
    np.testing.assert_allclose(got.pressure / es, ref.pressure, atol=1e-9 * ref.pressure.max())


def test_few_joining_sites_keep_the_conjugate_directions(monkeypatch):
    # restarting the directions whenever a site or two interpenetrate and join the step
    # made the late iterations steepest descent; keeping them (the new sites start with
    # no direction) reaches the same solution in fewer iterations
    from roughcontact.solvers import _pk_sparse, polonsky_keer

    h = rc.self_affine((256, 256), hurst=0.8, rms_slope=0.1, short_cutoff=8, seed=1)
    sub = rc.Substrate((256, 256))
    kept = polonsky_keer(h, sub, load=1e-2, tol=1e-10, nested=False)
    monkeypatch.setattr(_pk_sparse, "JOINING_KEEPS_DIRECTIONS", 0.0)
    restarted = polonsky_keer(h, sub, load=1e-2, tol=1e-10, nested=False)
    assert kept.converged and restarted.converged
    assert kept.iterations <= restarted.iterations - 3
    np.testing.assert_allclose(kept.pressure, restarted.pressure, atol=1e-8 * kept.pressure.max())


@pytest.mark.parametrize(
    ("control", "thickness"), [("load", None), ("offset", None), ("load", 40.0)]
)
def test_nested_cold_start_finds_the_same_solution_faster(control, thickness, monkeypatch):
    # a cold solve on a large grid starts from the problem solved on the grid coarsened
    # 2x2 (recursively): the same Signorini solution in fewer iterations on the fine grid
    from roughcontact.solvers import polonsky_keer

    pk = importlib.import_module("roughcontact.solvers.polonsky_keer")
    h = rc.self_affine((256, 256), hurst=0.8, rms_slope=0.1, short_cutoff=8, seed=2)
    sub = rc.Substrate((256, 256), thickness=thickness, poisson=0.3)
    kw = {"load": 2e-3} if control == "load" else {"offset": float(h.max() - 1.5 * h.std())}
    coarse_grids = []
    guess = pk._coarse_guess

    def spy(h, substrate, *args):
        coarse_grids.append(substrate.shape)
        return guess(h, substrate, *args)

    monkeypatch.setattr(pk, "_coarse_guess", spy)
    nested = polonsky_keer(h, sub, tol=1e-10, **kw)
    cold = polonsky_keer(h, sub, tol=1e-10, nested=False, **kw)
    assert nested.converged and cold.converged
    assert coarse_grids == [(256, 256), (128, 128)]  # 128² is below NESTED_MIN_SIZE
    assert nested.iterations < cold.iterations
    np.testing.assert_array_equal(nested.pressure > 0, cold.pressure > 0)
    np.testing.assert_allclose(nested.pressure, cold.pressure, atol=1e-8 * cold.pressure.max())
    assert nested.offset == pytest.approx(cold.offset, abs=1e-9 * h.std())


def test_nested_start_skipped_on_odd_grids_and_warm_starts():
    from roughcontact.solvers import polonsky_keer

    h = rc.self_affine((257, 256), hurst=0.8, rms_slope=0.1, short_cutoff=8, seed=2)
    sub = rc.Substrate((257, 256))
    a = polonsky_keer(h, sub, load=2e-3)
    b = polonsky_keer(h, sub, load=2e-3, nested=False)
    assert a.iterations == b.iterations and np.array_equal(a.pressure, b.pressure)
    warm = polonsky_keer(h, sub, load=2e-3, initial=a)
    assert warm.converged and warm.iterations <= 2


def test_preconditioning_resumes_after_a_lost_contact_set(monkeypatch):
    # with most of the surface in contact the first preconditioned steps from the local
    # guess can lose the whole contact set; the restart then takes plain steps, which
    # cannot repeat that path, and preconditioned ones again once the residual is well
    # below its value before the loss (plain to the end took 290 iterations here)
    from roughcontact.solvers import pk_rules

    h = rc.self_affine((128, 128), hurst=0.8, rms_slope=0.1, short_cutoff=8, seed=2)
    sub = rc.Substrate((128, 128))
    offset = float(h.mean()) + 0.01 * float(h.std())
    res = rc.solve(h, sub, offset=offset, tol=1e-9)
    assert res.converged and res.iterations < 80 and res.repulsive_area > 0.8
    gap = offset - h + sub.deflection(res.pressure)
    assert np.abs(gap[res.pressure > 0]).max() <= 2e-9 * h.std()
    assert gap.min() >= -2e-9 * h.std()
    monkeypatch.setattr(pk_rules, "RESUME_PRECONDITIONING", 0.0)  # plain to the end
    slow = rc.solve(h, sub, offset=offset, tol=1e-9)
    assert slow.converged and slow.iterations > 2 * res.iterations
    np.testing.assert_allclose(res.pressure, slow.pressure, atol=1e-7 * slow.pressure.max())
