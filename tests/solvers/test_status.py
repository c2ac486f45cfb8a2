"""Every result carries a SolveStatus beside its message; converged is status CONVERGED."""

import dataclasses
import importlib
import json

import numpy as np
import pytest

import roughcontact as rc
from roughcontact import SolveStatus
from roughcontact.interactions import MaugisDugdale, SmoothLJ93

smooth = importlib.import_module("roughcontact.solvers.smooth")
bounded = importlib.import_module("roughcontact.solvers.bounded")

N = 16
H = rc.self_affine((N, N), hurst=0.8, rms_slope=0.1, short_cutoff=4.0, seed=3)
SUB = rc.Substrate((N, N))
SMOOTH = SmoothLJ93.from_adhesion_length(0.005)
HARD_CORE = MaugisDugdale(work_of_adhesion=0.01, range=0.5)
TOP = float(H.max())


class _BrokenLaw(SmoothLJ93):
    """NaN forces once the surfaces come closer than a0/2: a broken user law."""

    def pressure(self, gap):
        p = super().pressure(gap)
        return np.where(np.asarray(gap) < 0.5, np.nan, p)


class _BrokenCore(MaugisDugdale):
    """A hard-core law with NaN forces on the cohesive zone."""

    def pressure(self, gap):
        p = super().pressure(gap)
        return np.where(np.asarray(gap) < 0.25, np.nan, p)


def _stop(it, residual):
    return True


# (name, solve arguments, expected status); each solve is cheap (16² grid)
CASES = [
    ("pk-converged", dict(load=1e-3), SolveStatus.CONVERGED),
    ("pk-no-contact", dict(offset=TOP + 1.0), SolveStatus.CONVERGED),
    ("pk-cap", dict(load=1e-3, max_iter=1), SolveStatus.ITERATION_LIMIT),
    ("pk-callback", dict(load=1e-3, callback=_stop), SolveStatus.CALLBACK),
    ("pk-offset-cap", dict(offset=TOP - 0.3, max_iter=1), SolveStatus.ITERATION_LIMIT),
    ("smooth-converged", dict(interaction=SMOOTH, offset=TOP + 0.5), SolveStatus.CONVERGED),
    (
        "smooth-cap",
        dict(interaction=SMOOTH, offset=TOP - 0.3, max_iter=1),
        SolveStatus.ITERATION_LIMIT,
    ),
    (
        "smooth-callback",
        dict(interaction=SMOOTH, offset=TOP - 0.3, callback=_stop),
        SolveStatus.CALLBACK,
    ),
    (
        "smooth-non-finite",
        dict(interaction=_BrokenLaw(work_of_adhesion=0.005), offset=TOP - 0.5),
        SolveStatus.NON_FINITE,
    ),
    (
        "smooth-stalled",
        dict(interaction=SMOOTH, offset=TOP + 0.5, tol=1e-16),  # below the floor
        SolveStatus.STALLED,
    ),
    (
        "smooth-runaway",
        dict(interaction=SMOOTH, offset=TOP - 1.0),  # far through full contact: ~1e13 E*
        SolveStatus.RUNAWAY,
    ),
    (
        "bounded-converged",
        dict(interaction=HARD_CORE, offset=TOP - 0.3),
        SolveStatus.CONVERGED,
    ),
    (
        "bounded-cap",
        dict(interaction=HARD_CORE, offset=TOP - 0.3, max_iter=1),
        SolveStatus.ITERATION_LIMIT,
    ),
    (
        "bounded-callback",
        dict(interaction=HARD_CORE, offset=TOP - 0.3, callback=_stop),
        SolveStatus.CALLBACK,
    ),
    (
        "bounded-non-finite",
        dict(interaction=_BrokenCore(work_of_adhesion=0.01, range=0.5), offset=TOP - 0.3),
        SolveStatus.NON_FINITE,
    ),
    ("load-control-converged", dict(interaction=SMOOTH, load=1e-3), SolveStatus.CONVERGED),
    (
        "load-control-beyond-pull-off",
        dict(interaction=SMOOTH, load=-1.0),
        SolveStatus.DETACHED,
    ),
    (
        "load-control-full-contact",  # the wall's reaction carries it (test_bounded.py)
        dict(interaction=HARD_CORE, load=10.0),
        SolveStatus.CONVERGED,
    ),
    (
        "load-control-inner-cap",
        dict(interaction=SMOOTH, load=1e-3, max_iter=1),
        SolveStatus.ITERATION_LIMIT,
    ),
]


def _solve(kwargs):
    kwargs = dict(kwargs)
    interaction = kwargs.pop("interaction", None)
    return rc.solve(H, SUB, interaction, **kwargs)


@pytest.mark.parametrize(("kwargs", "status"), [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_status_is_set_and_converged_follows_it(kwargs, status):
    res = _solve(kwargs)
    assert res.status is status, res.message
    assert isinstance(res.status, SolveStatus)
    assert res.converged == (res.status is SolveStatus.CONVERGED)
    summary = res.summary()
    assert summary["status"] == status.value and type(summary["status"]) is str
    assert json.loads(json.dumps(summary))["status"] == status.value


@pytest.mark.parametrize("module", [smooth, bounded], ids=["smooth", "bounded"])
def test_line_search_failure(monkeypatch, module):
    def failing(*args, with_pressure=False, **kwargs):
        return (np.nan, None, None) if with_pressure else np.nan

    monkeypatch.setattr(module, "line_minimum", failing)
    law = SMOOTH if module is smooth else HARD_CORE
    res = rc.solve(H, SUB, law, offset=TOP - 0.3)
    assert res.status is SolveStatus.LINE_SEARCH_FAILED and not res.converged
    assert "line search failed" in res.message


def test_float32_stall_guard_reports_stalled():
    ops = importlib.import_module("roughcontact.solvers.loop_control")
    guard = ops.StallGuard("float32", patience=2)
    end = None
    for it in range(10):
        if (end := ops.stopping(False, 1.0, guard, it, 100)) is not None:
            break
    assert end is not None and end[0] is SolveStatus.STALLED and "stalled" in end[1]
    assert ops.stopping(True, 0.0, guard, 0, 100)[0] is SolveStatus.CONVERGED
    fresh = ops.StallGuard("float32")
    assert ops.stopping(False, 1.0, fresh, 5, 5)[0] is SolveStatus.ITERATION_LIMIT


def test_crawl_guard_stops_a_crawl_as_an_iteration_limit_and_lets_progress_go_on():
    ops = importlib.import_module("roughcontact.solvers.loop_control")
    assert isinstance(ops.stall_guard("float64"), ops.StallGuard)
    assert not isinstance(ops.stall_guard("float64"), ops.CrawlGuard)
    with ops.guarding_crawl():
        guard = ops.stall_guard("float64")
    assert isinstance(guard, ops.CrawlGuard) and not ops.crawl_guarded()
    # a 3-fold fall within every 40 iterations goes on (steps of 2.8 %: 0.972**39 < 1/3) ...
    residual, end = 1.0, None
    for it in range(400):
        residual *= 0.972
        if (end := ops.stopping(False, residual, guard, it, 10**6)) is not None:
            break
    assert end is None
    # ... one that falls only 2.9-fold in 40 iterations is a crawl: stopped at the 40th
    crawl, stops = ops.CrawlGuard(), []
    for it in range(200):
        if (end := ops.stopping(False, 0.1 * 0.9737**it, crawl, it, 10**6)) is not None:
            stops.append(it)
            break
    assert stops == [ops.CRAWL_PATIENCE]
    assert end[0] is SolveStatus.ITERATION_LIMIT and "no progress" in end[1]
    assert "40 iterations" in end[1] and "0.1" in end[1]


def test_enum_is_exported_and_string_valued():
    assert rc.SolveStatus is SolveStatus is rc.solvers.SolveStatus
    assert "SolveStatus" in rc.__all__ and "SolveStatus" in rc.solvers.__all__
    assert SolveStatus.CONVERGED == "converged"
    assert SolveStatus("stopped_by_callback") is SolveStatus.CALLBACK
    assert len({s.value for s in SolveStatus}) == len(SolveStatus)


def test_status_and_converged_cannot_disagree():
    res = rc.solve(H, SUB, load=1e-3)
    with pytest.raises(ValueError, match="contradicts"):
        dataclasses.replace(res, converged=False)
    with pytest.raises(ValueError, match="contradicts"):
        dataclasses.replace(res, status=SolveStatus.STALLED)
    again = dataclasses.replace(res, converged=False, status="iteration_limit")
    assert again.status is SolveStatus.ITERATION_LIMIT


def test_path_records_the_status_per_step():
    ds = rc.approach_retract(H, SUB, offsets=TOP - np.array([0.0, 0.2]), max_iter=1)
    assert ds["status"].dtype.kind == "U"
    statuses = [SolveStatus(s) for s in ds["status"].values]
    converged = [bool(c) for c in ds["converged"].values]
    assert converged == [s is SolveStatus.CONVERGED for s in statuses]
    assert SolveStatus.ITERATION_LIMIT in statuses


def test_path_stops_on_a_non_finite_status():
    law = _BrokenLaw(work_of_adhesion=0.005)
    with pytest.raises(rc.PathError, match="step 1") as info:
        rc.approach_retract(H, SUB, law, offsets=TOP + np.array([1.5, -0.5]))
    assert info.value.partial.sizes["step"] == 1
    assert list(info.value.partial["status"].values) == ["converged"]
