"""Host syncs and arrays created per iteration, counted on array_api_strict (the CPU proxy).

On a GPU each conversion of a device array to a Python scalar waits for the device, and
each array created is a kernel launch and an allocation; ``benchmarks/host_syncs.py``
counts both without a GPU (see there). Before the solvers kept their scalars on the
device (issue 34) an iteration made 9-20 syncs (hard wall 9-14, smooth 18, bounded 20)
and created 70-230 arrays. Since the hard-wall and bounded loops run blocks of device
steps (init / step / terminate, :mod:`roughcontact.solvers._blocks`) a step makes no
sync at all and the host checks once per block.

Targets of issue 34: at most 2 syncs and 40 arrays per iteration. The syncs are met by
every solver, load control included (its count includes every inner solve's set-up,
result record and first, projected or bracketed, steps: its inner solves here take ~8
iterations; they reuse the heights' statistics, and the line search brings its next
point in the guess's transfer). The arrays are not: every array-API operation is an
array, and a step of these methods is 57-111 passes over a field and 100-240 arrays
with the scalars (benchmarks/README.md attributes them per source line: the FFT
convolutions, the law's evaluations, the method's elementwise work); the tests below
hold the counts reached so that they cannot grow unnoticed, and mark the unmet targets
as expected failures (strict: they fail once met, so that the bounds here are
tightened).
"""

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

import roughcontact as rc

xp = pytest.importorskip("array_api_strict")

BENCH = Path(__file__).resolve().parents[2] / "benchmarks" / "host_syncs.py"
_spec = importlib.util.spec_from_file_location("_bench_host_syncs", BENCH)
host_syncs = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(host_syncs)

N = 64
#: (syncs, arrays) per iteration reached at 64², marginal over 6 -> 12 iterations (measured:
#: 0.83/153, 1.00/106, 1.67/164, 1.17/214, 1.93/302 syncs/arrays), with a little room for
#: round-off in the paths taken
REACHED = {
    "hardwall-load": (1.0, 160),
    "hardwall-offset": (1.2, 115),
    "smooth": (2.0, 170),
    "bounded": (1.4, 220),
    "load-control": (2.0, 310),  # per inner iteration, the inner solves' set-up included
}
#: before: 13.7/105, 9.0/70, 17.0/190, 19.0/196, 24.7/244 syncs/arrays per iteration
BEFORE_SYNCS = {"hardwall-load": 13, "hardwall-offset": 9, "smooth": 17, "bounded": 19,
                "load-control": 24}  # fmt: skip


@pytest.fixture(scope="module")
def counts():
    return {name: host_syncs.measure(run, 6, whole) for name, run, whole in host_syncs.problems(N)}


@pytest.mark.parametrize("solver", list(REACHED))
def test_host_syncs_and_arrays_per_iteration(counts, solver):
    got = counts[solver]
    syncs, arrays = REACHED[solver]
    assert got["syncs"] <= syncs, got
    assert got["arrays"] <= arrays, got
    assert got["copies"] == 0, got  # no field crosses to the host inside the loop
    assert got["syncs"] <= 2  # issue 34's target
    assert got["syncs"] < BEFORE_SYNCS[solver] / 4


@pytest.mark.xfail(strict=True, reason="issue 34's targets not reached: see the docstring")
@pytest.mark.parametrize("solver", list(REACHED))
def test_issue_34_targets(counts, solver):
    assert counts[solver]["syncs"] <= 2 and counts[solver]["arrays"] <= 40


def _problem(control):
    h = rc.self_affine((32, 32), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=3)
    value = {"load": 2e-3, "offset": float(h.max()) - 0.3 * float(h.std())}[control]
    return h, rc.Substrate((32, 32)), {control: value}


@pytest.mark.parametrize("control", ["load", "offset"])
@pytest.mark.parametrize("pre", [True, False])
def test_a_hard_wall_step_makes_no_host_sync(monkeypatch, control, pre):
    from roughcontact.solvers import _pk_dense

    h, sub, kw = _problem(control)
    seen = []
    step = _pk_dense._Dense.step

    def counted(self, st, *args, **kwargs):
        self.kind.pre = pre
        with host_syncs.counting() as c:
            out = step(self, st, *args, **kwargs)
        seen.append(c["syncs"])
        return out

    monkeypatch.setattr(_pk_dense._Dense, "step", counted)
    rc.solve(xp.asarray(h), sub, rc.HardWall(), max_iter=12, tol=1e-15, **kw)
    assert len(seen) >= 12 and seen == [0] * len(seen)


def test_a_bounded_block_makes_one_host_sync(monkeypatch):
    from roughcontact.solvers import _bounded_steps

    h = rc.sphere((32, 32), 20.0)
    seen = []
    block = _bounded_steps._DeviceSteps.block

    def counted(self, st, n, *args, **kwargs):
        with host_syncs.counting() as c:
            out = block(self, st, n, *args, **kwargs)
        seen.append((n, out[1], c["syncs"]))
        return out

    monkeypatch.setattr(_bounded_steps._DeviceSteps, "block", counted)
    law = rc.Exponential(work_of_adhesion=0.01, range=0.4)
    res = rc.solve(xp.asarray(h), rc.Substrate((32, 32)), law, offset=-0.4, tol=1e-10)
    assert res.converged and seen
    assert all(syncs == 1 for _, _, syncs in seen)  # the block's one transfer
    assert sum(taken for _, taken, _ in seen) > res.iterations / 2  # most steps on the device


def test_a_smooth_block_makes_one_host_sync(monkeypatch):
    from roughcontact.solvers import _smooth_steps

    h = rc.self_affine((32, 32), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=3)
    seen = []
    block = _smooth_steps._DeviceSteps.block

    def counted(self, st, stiff, diagonal, restarts, *args, **kwargs):
        with host_syncs.counting() as c:
            out = block(self, st, stiff, diagonal, restarts, *args, **kwargs)
        seen.append((len(restarts), out[1], c["syncs"]))
        return out

    monkeypatch.setattr(_smooth_steps._DeviceSteps, "block", counted)
    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    offset = float(h.max()) + 0.6
    res = rc.solve(xp.asarray(h), rc.Substrate((32, 32)), law, offset=offset, tol=1e-9)
    ref = rc.solve(h, rc.Substrate((32, 32)), law, offset=offset, tol=1e-9)
    assert res.converged and res.iterations == ref.iterations
    assert all(syncs == 1 for _, _, syncs in seen)  # the block's one transfer
    assert sum(taken for _, taken, _ in seen) > res.iterations / 2  # most steps on the device


def test_projection_off_numpy_takes_the_same_newton_steps():
    # the Newton steps computed ahead of each transfer give the NumPy loop's projection,
    # also where everything is clipped at first (count 0: to the first breakpoint)
    from roughcontact.solvers.bounded import project_feasible

    rng = np.random.default_rng(4)
    for shift in (0.0, 3.0, -3.0):
        v, lower = rng.normal(size=400) + shift, rng.normal(size=400) - 0.5
        ref = project_feasible(v, lower, True)
        got = np.asarray(project_feasible(xp.asarray(v), xp.asarray(lower), True))
        np.testing.assert_array_equal(got, ref)
        assert abs(got.mean()) < 1e-13 and np.all(got >= lower)


def test_block_schedule():
    from roughcontact.solvers._blocks import BLOCK, FIRST_BLOCK, Schedule

    s = Schedule()
    assert s.next(100) == FIRST_BLOCK
    for _ in range(5):
        s.ran(True, s.next(100), 1.0)
    assert s.next(100) == BLOCK and s.next(3) == 3  # doubled to the cap; a known stop
    s.ran(True, 8, 1.0)
    s.ran(True, 8, 2.0**-8)  # the residual halves each step: the threshold 2^-11 is 3 away
    assert s.next(100, 2.0**-8, 2.0**-11) == 4
    s.ran(False, 0, 1.0)  # not one step taken: back off, 1 host iteration, then 1 step
    assert not s.ready() and s.ready() and s.next(100) == 1
    assert Schedule(every=1).next(100) == 1  # a callback sees every iteration


def test_dense_and_numpy_hard_wall_agree_to_the_iteration_at_the_check_interval():
    # the host checks every few steps, but frozen steps make the reported iteration the
    # first converged one: the same count as the NumPy loop, which checks every step
    for control in ("load", "offset"):
        h, sub, kw = _problem(control)
        for tol in (1e-6, 1e-9, 1e-12):
            ref = rc.solve(h, sub, rc.HardWall(), tol=tol, **kw)
            got = rc.solve(xp.asarray(h), sub, rc.HardWall(), tol=tol, **kw)
            assert got.iterations == ref.iterations and got.converged
            np.testing.assert_allclose(got.pressure, ref.pressure, rtol=1e-8, atol=1e-10)


def test_the_counter_sees_syncs_copies_and_arrays():
    import array_api_strict as xp
    import numpy as np

    with host_syncs.counting() as c:
        a = xp.asarray(np.arange(100.0))
        b = a * 2.0
        float(xp.sum(b))
        bool(xp.any(b > 0))
        np.asarray(b)
    assert c["syncs"] == 3 and c["copies"] == 1 and c["arrays"] >= 5


def test_line_search_next_point_is_the_hosts():
    # off NumPy the line search computes the point it evaluates after a guess not taken
    # with the guess (one transfer): it must be the host's to the bit (same iterations)
    from roughcontact.solvers.line_search import _device_next
    from roughcontact.solvers.roots import false_position

    rng = np.random.default_rng(7)
    cases = [(1.0, 0.0, -1.0), (4.0, -2.0, -1.0), (1e-8, 3.0, -1e-3), (0.5, math.nan, -1.0)]
    cases += [(rng.uniform(1e-8, 4), rng.normal(), -abs(rng.normal())) for _ in range(200)]
    for hi, f_hi, slope0 in cases:
        got = float(
            _device_next(xp, *(xp.asarray(v, dtype=xp.float64) for v in (hi, f_hi, slope0)))
        )
        want = 2.0 * hi if f_hi < 0 else false_position(0.0, slope0, hi, f_hi)
        assert got == want, (hi, f_hi, slope0)


def test_load_control_takes_numpys_iterations():
    # the inner solves reuse the heights' statistics and the line search's speculated
    # points: the same iterations as NumPy's nested search (NumPy itself now puts the load
    # inside the one minimisation, solvers/_free_mean.py; a partial forces the search)
    import functools

    from roughcontact.solvers.bounded import minimize_energy_bounded
    from roughcontact.solvers.load_control import solve_at_load

    h = rc.sphere((32, 32), 20.0)
    sub, law = rc.Substrate((32, 32)), rc.Exponential(work_of_adhesion=0.01, range=0.4)
    ref = solve_at_load(functools.partial(minimize_energy_bounded), h, sub, law, load=2e-4,
                        initial=None, tol=1e-10, max_iter=5000, callback=None)  # fmt: skip
    got = rc.solve(xp.asarray(h), sub, law, load=2e-4, tol=1e-10)
    assert got.converged and got.iterations == ref.iterations
    # (the offsets differ in the last digits: numpy.fft and scipy.fft round differently)
    assert got.offset == pytest.approx(ref.offset, abs=1e-9)


def test_constant_operands():
    # the cached operands give the Python scalar's values; NumPy keeps the Python scalar
    from roughcontact._backend import constant

    g = xp.asarray(np.array([-1.0, -0.0, 0.0, 2.0]))
    assert constant(0.5, np.zeros(3)) == 0.5
    for value in (0.0, -0.0, 0.4):
        c = constant(value, g)
        assert c.shape == (1,) and c.dtype == g.dtype and constant(value, g) is c
        with np.errstate(divide="ignore", invalid="ignore"):  # NaN and ±inf compared too
            np.testing.assert_array_equal(np.asarray(g / c), np.asarray(g / value))
    assert math.copysign(1.0, float(constant(-0.0, g)[0])) == -1.0  # not 0.0's entry
    g32 = xp.astype(g, xp.float32)
    assert constant(0.4, g32).dtype == xp.float32
    assert np.array_equal(np.asarray(g32 * constant(0.4, g32)), np.asarray(g32 * 0.4))


def test_by_line_attribution_adds_up():
    # --by-line charges every array, field and sync to a line of the package: the lines'
    # counts add up to the totals, and the hard wall's step is charged to its own module
    run = dict((name, run) for name, run, _ in host_syncs.problems(32))["hardwall-offset"]
    got = host_syncs.measure(run, 3, False, by_line=True)
    for kind in ("syncs", "arrays", "fields"):
        assert sum(got["lines"][kind].values()) == pytest.approx(got[kind])
    top = max(got["lines"]["arrays"], key=got["lines"]["arrays"].get)
    assert top.startswith("solvers/_pk_dense.py:")
