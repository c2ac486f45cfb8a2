"""Smooth-interaction solver: force balance, energy bookkeeping, limits, paths."""

import math

import numpy as np
import pytest

import roughcontact as rc
from roughcontact.checks import load_work_balance
from roughcontact.interactions import SmoothLJ93


@pytest.fixture(scope="module")
def system():
    h = rc.self_affine((64, 64), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=5)
    return h, rc.Substrate((64, 64))


def test_force_balance_and_bookkeeping(system):
    h, sub = system
    law = SmoothLJ93.from_adhesion_length(0.005)
    res = rc.solve(h, sub, law, offset=h.max() + 0.8, tol=1e-10)
    assert res.converged and res.residual <= 1e-10
    p_int = law.pressure(res.gap)
    # elastic pressure balances the interaction pressure (up to the rigid mean)
    np.testing.assert_allclose(sub.pressure(res.deflection), p_int - p_int.mean(), atol=2e-10)
    rep, att = law.classify(res.gap)
    assert res.repulsive_area == pytest.approx(rep.mean())
    assert res.attractive_area == pytest.approx(att.mean())
    assert res.repulsive_load - res.attractive_load == pytest.approx(res.load, abs=1e-14)
    assert res.attractive_load > 0 and res.repulsive_load > 0


def test_energy_bookkeeping_along_a_branch(system):
    # dE_total/dd = -N, so the work of the load equals the change of total energy
    h, sub = system
    law = SmoothLJ93.from_adhesion_length(0.0005)
    offsets = h.max() + np.linspace(0.6, 0.4, 21)
    energy_change, work = load_work_balance(h, sub, law, offsets, tol=1e-11)
    assert energy_change == pytest.approx(work, rel=2e-3)


def test_weak_adhesion_repulsion_tends_to_hard_wall(system):
    # a stiff, short-ranged wall at distance a0 is the hard wall shifted by a0
    h, sub = system
    hard = rc.solve(h, sub, offset=h.max() - 0.3, tol=1e-10)
    law = SmoothLJ93(stiffness=200.0, range=0.005)  # w = 4e-4: weak
    soft = rc.solve(h, sub, law, offset=h.max() - 0.3 + 1.0, tol=1e-9)
    assert soft.converged
    assert soft.repulsive_load == pytest.approx(hard.load, rel=0.03)
    assert soft.repulsive_area == pytest.approx(hard.repulsive_area, rel=0.15)


def test_warm_start_and_cap(system):
    h, sub = system
    law = SmoothLJ93.from_adhesion_length(0.005)
    first = rc.solve(h, sub, law, offset=h.max() + 0.7)
    again = rc.solve(h, sub, law, offset=h.max() + 0.7, initial=first)
    assert again.iterations < first.iterations
    capped = rc.solve(h, sub, law, offset=h.max() + 0.7, max_iter=2)
    assert not capped.converged and "cap" in capped.message


def test_approach_retract_path_and_pull_off(system, tmp_path):
    h, sub = system
    law = SmoothLJ93.from_adhesion_length(0.05)
    # back out past a0 + Δr (2.1 a0): the retraction must separate for a pull-off
    offsets = h.max() + np.linspace(2.2, 0.6, 11)
    ds = rc.approach_retract(h, sub, law, offsets=offsets, retract=True, fields_at=[0, -1])
    assert ds.sizes["step"] == 21
    assert list(ds["branch"].values[:11]) == ["approach"] * 11
    assert ds.attrs["all_converged"] == 1
    retract = ds.where(ds["branch"] == "retract", drop=True)
    assert ds.attrs["separated"] == 1 and retract["repulsive_area"].values[-1] == 0
    assert ds.attrs["pull_off"] == pytest.approx(max(0.0, -float(retract["load"].min())))
    assert ds.attrs["pull_off"] > 0  # strongly adhesive, smooth at small scales
    assert ds["pressure"].shape == (2, 64, 64)
    ds.to_netcdf(tmp_path / "p.nc", engine="h5netcdf")


def test_bad_path_input(system):
    h, sub = system
    with pytest.raises(rc.ParameterError, match="empty"):
        rc.approach_retract(h, sub, SmoothLJ93.from_adhesion_length(0.005), offsets=[])
    with pytest.raises(rc.ParameterError, match="exactly one"):
        rc.approach_retract(h, sub, offsets=[1.0], loads=[1.0])
    with pytest.raises(rc.ParameterError, match="load"):
        rc.solve(h, sub, SmoothLJ93.from_adhesion_length(0.005), load=float("nan"))


def test_load_control_matches_displacement_control(system):
    h, sub = system
    law = SmoothLJ93.from_adhesion_length(0.005)
    res = rc.solve(h, sub, law, load=2e-3, tol=1e-10)
    assert res.converged and res.load == pytest.approx(2e-3, abs=1e-10)
    again = rc.solve(h, sub, law, offset=res.offset, initial=res, tol=1e-10)
    assert again.load == pytest.approx(2e-3, abs=1e-9)
    assert again.repulsive_area == pytest.approx(res.repulsive_area)
    # a load-controlled path warm-starts each load from the last
    ds = rc.approach_retract(h, sub, law, loads=[1e-3, 2e-3, 4e-3], retract=False, tol=1e-9)
    assert ds.attrs["control"] == "load" and ds.attrs["all_converged"]
    np.testing.assert_allclose(ds["load"], [1e-3, 2e-3, 4e-3], atol=1e-9)


class _BrokenLaw(SmoothLJ93):
    """Returns NaN forces once the surfaces come closer than a0/2: a broken user law."""

    def pressure(self, gap):
        p = super().pressure(gap)
        return np.where(np.asarray(gap) < 0.5, np.nan, p)


def test_non_finite_state_stops_the_path_and_names_the_step(system):
    h, sub = system
    law = _BrokenLaw(work_of_adhesion=0.005)
    offsets = h.max() + np.array([1.5, 1.2, 0.9, 0.0])
    with pytest.raises(rc.PathError, match="step 3") as info:
        rc.approach_retract(h, sub, law, offsets=offsets)
    assert info.value.partial.sizes["step"] == 3  # the steps before it are kept


# ----------------------------------------------------------- the block preconditioner
def _converged_state(n=128):
    h = rc.self_affine((n, n), hurst=0.8, rms_slope=0.1, short_cutoff=8, seed=1)
    sub = rc.Substrate((n, n))
    law = SmoothLJ93.from_adhesion_length(0.005)
    # a few per cent repulsive area, the paper's regime
    res = rc.solve(h, sub, law, offset=h.max() + 1.0 - 1.2 * h.std(), tol=1e-8)
    assert res.converged and 0.01 < res.repulsive_area < 0.1
    return sub, law, res


def _operators(sub, law, gap, single=False):
    from roughcontact.solvers.fourier import compliance_operator, stiffness_operator
    from roughcontact.solvers.smooth import _precondition, _stiff_sites

    g = gap.ravel()
    stiff, diagonal = _stiff_sites(law, g, sub.self_stiffness)
    kop, gop = stiffness_operator(sub), compliance_operator(sub)

    def block(r):
        # single: both convolutions in float32, as in the solver (K z comes back in float32)
        fast = np.empty(r.size, np.float32) if single else None
        return _precondition(r, stiff, diagonal, gop, kop, sub.rigid_mean, fast=fast)

    def hessian(x):
        return kop(x) + law.curvature(g) * x

    return block, hessian, kop


@pytest.mark.parametrize("single", [False, True], ids=["float64", "float32-convolutions"])
def test_block_preconditioner_is_symmetric_positive_definite(single):
    sub, law, res = _converged_state(64)
    block, _, kop = _operators(sub, law, res.gap, single)
    rng = np.random.default_rng(0)
    x, y = (v - v.mean() for v in rng.standard_normal((2, 64 * 64)))
    bx, kbx = block(x)
    by, _ = block(y)
    assert abs(bx.mean()) < 1e-14  # stays in the mean-free space of the rigid mode
    # symmetric up to the float32 rounding of its Green's-function block
    assert x @ by == pytest.approx(y @ bx, rel=1e-6)
    assert x @ bx > 0 and y @ by > 0
    # K z: exact in float64; float32 rounding (~1e-7) when convolved in single precision
    assert kbx.dtype == (np.float32 if single else np.float64)
    rounding = 1e-6 if single else 1e-12
    np.testing.assert_allclose(kbx, kop(bx), atol=rounding * np.abs(kbx).max())


def test_block_preconditioner_bounds_the_spectrum():
    # Green's function alone: the largest eigenvalue of the preconditioned Hessian grows
    # like V'' R / E* with the contact patches' size R; the block preconditioner bounds
    # it (Lanczos on B H in the B^-1 inner product = eigenvalues of B^1/2 H B^1/2)
    from scipy.sparse.linalg import LinearOperator, eigs

    from roughcontact.solvers.fourier import compliance_operator

    sub, law, res = _converged_state(128)
    block, hessian, _ = _operators(sub, law, res.gap)
    green = compliance_operator(sub)
    m = 128 * 128

    def largest(precondition):
        op = LinearOperator((m, m), matvec=lambda x: precondition(hessian(x - x.mean())))
        return eigs(op, k=1, which="LR", tol=1e-4, return_eigenvectors=False).real.max()

    lam_block = largest(lambda r: block(r - r.mean())[0])
    lam_green = largest(lambda r: green(r - r.mean()))
    assert lam_block < 3.0
    assert lam_green > 2.0 * lam_block


def test_refresh_every_is_validated(system):
    h, sub = system
    with pytest.raises(rc.ParameterError, match="refresh_every"):
        rc.solvers.minimize_energy(
            h, sub, SmoothLJ93.from_adhesion_length(0.005), offset=h.max(), refresh_every=0
        )


@pytest.mark.parametrize("periodic_only", [False, True], ids=["default", "periodic-only"])
def test_single_precision_convolutions_reach_float64_accuracy(system, periodic_only, monkeypatch):
    # K z and the preconditioner run in float32 (~1e-7 rounding); K w is replaced by an
    # exact float64 evaluation as the residual falls and before convergence is declared,
    # so the force balance holds far below float32's resolution (independent check).
    # Late replacements (drift above the residual) restart the conjugate directions.
    from roughcontact.solvers import loop_control

    if periodic_only:
        monkeypatch.setattr(loop_control, "RELIABLE_DROP", 0.0)
        monkeypatch.setattr(loop_control, "RELIABLE_EVERY", 20)
    h, sub = system
    law = SmoothLJ93.from_adhesion_length(0.05)
    res = rc.solve(h, sub, law, offset=h.max() + 0.2, tol=1e-12)
    assert res.converged and res.residual <= 1e-12
    assert res.repulsive_area > 0.01
    p_int = law.pressure(res.gap)
    np.testing.assert_allclose(sub.pressure(res.deflection), p_int - p_int.mean(), atol=3e-12)


class _SteepCore:
    """p(g) = exp(stiffness (1 - g)): a repulsion whose force spans many decades."""

    cutoff = math.inf

    def __init__(self, stiffness):
        self.stiffness, self.calls = stiffness, 0

    def pressure(self, gap):
        self.calls += 1
        return np.exp(self.stiffness * (1.0 - gap))

    def curvature(self, gap):
        return -self.stiffness * self.pressure(gap)


@pytest.mark.parametrize("stiffness", [2.0, 30.0, 60.0])
def test_line_search_meets_its_tolerance_in_few_evaluations(stiffness):
    # phi'(alpha) = c0 + alpha c1 - s.p(gap + alpha s) along an approach (s < 0) onto a
    # steep core: the Newton guess from alpha = 0 lands where phi' is 1e10x larger, and
    # plain regula falsi then crawls; the bisection safeguard must bound the evaluations
    from roughcontact.solvers.line_search import line_minimum

    rng = np.random.default_rng(4)
    gap = rng.uniform(1.5, 3.0, 200)
    s = -rng.uniform(0.5, 1.0, 200)
    ks = 0.01 * s  # a weak elastic term: c1 = s.ks > 0
    kw = np.zeros(200)
    law = _SteepCore(stiffness)
    slope0 = -float(s @ law.pressure(gap)) - 50.0  # phi'(0) < 0: descent
    kw[:] = -50.0 / float(s @ s) * s  # c0 = s.kw = -50
    law.calls = 0
    alpha = line_minimum(law, gap, s, kw, ks, slope0, rtol=1e-3)

    def phi_slope(a):
        return float(s @ kw) + a * float(s @ ks) - float(s @ law.pressure(gap + a * s))

    assert math.isfinite(alpha) and alpha > 0
    assert abs(phi_slope(alpha)) <= 1e-3 * abs(slope0)
    assert law.calls <= 30  # regula falsi with Illinois: 60 without meeting the tolerance


@pytest.mark.parametrize("overlap", [False, True])
def test_background_elastic_pressure_takes_the_same_steps(system, overlap, monkeypatch):
    # K z on the background thread while the line search selects its band: the same
    # operations in the same order, so the same iterations and bit-identical fields
    import roughcontact.solvers.smooth as smooth

    h, sub = system
    law = SmoothLJ93(contact_modulus=1.0, pixel_size=1.0, range=0.3)
    offset = float(h.max()) - 0.5
    monkeypatch.setattr(smooth, "overlaps_fft", lambda size: False)
    ref = rc.solve(h, sub, law, offset=offset, tol=1e-9)
    monkeypatch.setattr(smooth, "overlaps_fft", lambda size: overlap)
    got = rc.solve(h, sub, law, offset=offset, tol=1e-9)
    assert ref.converged and got.iterations == ref.iterations
    np.testing.assert_array_equal(got.deflection, ref.deflection)
    np.testing.assert_array_equal(got.pressure, ref.pressure)
