"""The committed reproduction data still follow from the code (a regression on the science).

Two tasks of ``reproduction/reproduction.toml`` (L = 1024 a0) are recomputed at reduced
cost — the approach only, up to a bearing-area offset of 2.5 % (past A_rep = 1 %) instead of the
whole approach and retraction — and compared step by step with ``reproduction/data/
steps.csv``, and their path analysis with ``reproduction/data/tasks.csv``. A solver,
surface or analysis change that moves the science fails here.

Tolerances: the solver stops at a force imbalance of 1e-7 E* per site, and the same
path is followed from the same warm starts, so loads agree to far better than the
1e-4 relative (plus 1e-9 E* absolute) asked here and areas to within two sites;
κ's to 1e-3 relative (interpolation between the same steps).
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest
from _helpers import assert_numbers_close

ROOT = Path(__file__).resolve().parents[2]
STUDY = ROOT / "reproduction" / "reproduction.toml"
DATA = ROOT / "reproduction" / "data"
#: seed-1 members of the grid: H = 0.3, h'rms = 0.1 with (lambda_s/a0, l_a/a0) = (4, 0.0005)
#: and (16, 0.005), the cheapest of their adhesion lengths (~1 min together on 2 cores)
TASKS = ("00000", "00021")
STOP_AT = 0.025  # bearing-area offsets up to here: A_rep/A0 passes 1 % (1.15 % for 00000)
STEP_KEYS = ("repulsive_area", "attractive_area", "repulsive_load", "attractive_load", "load")

pd = pytest.importorskip("pandas")


def _committed():
    tasks = pd.read_csv(DATA / "tasks.csv", dtype={"task": str})
    steps = pd.read_csv(DATA / "steps.csv", dtype={"task": str})
    return tasks.set_index("task"), steps


@pytest.fixture(scope="module")
def recomputed():
    from roughcontact.studies import load_study
    from roughcontact.studies.task import compute_task

    spec = load_study(STUDY)
    out = {}
    for task in spec.tasks:
        if task.id not in TASKS:
            continue
        path = dict(task.settings["path"])
        path["values"] = [v for v in path["values"] if v <= STOP_AT]
        path["retract"] = False
        settings = {**task.settings, "path": path}
        out[task.id] = compute_task(dataclasses.replace(task, settings=settings))
    return out


@pytest.mark.slow
@pytest.mark.parametrize("task_id", TASKS)
def test_steps_match_committed_data(recomputed, task_id):
    tasks, steps = _committed()
    assert tasks.loc[task_id, "status"] == "done"
    ds = recomputed[task_id]
    mine = steps[(steps.task == task_id) & (steps.branch == "approach")].sort_values("step")
    n = ds.sizes["step"]
    assert len(mine) >= n  # the committed approach is longer (up to 5 % bearing area)
    n_sites = float(tasks.loc[task_id, "size"]) ** 2
    for key in STEP_KEYS:
        new, old = np.asarray(ds[key].values, dtype=float), mine[key].to_numpy()[:n]
        if key.endswith("area"):
            np.testing.assert_allclose(new, old, rtol=0, atol=2 / n_sites, err_msg=key)
        else:
            np.testing.assert_allclose(new, old, rtol=1e-4, atol=1e-9, err_msg=key)


@pytest.mark.slow
@pytest.mark.parametrize("task_id", TASKS)
def test_analysis_matches_committed_data(recomputed, task_id):
    tasks, _ = _committed()
    analysis = json.loads(recomputed[task_id].attrs["analysis"])
    assert analysis, recomputed[task_id].attrs["analysis_error"]
    for key in ("kappa", "kappa_rep", "kappa_att", "kappa_rep_hard_wall", "d_rep"):
        assert analysis[key] == pytest.approx(float(tasks.loc[task_id, key]), rel=1e-3), key
    assert analysis["verdict"] == tasks.loc[task_id, "verdict"]


def test_report_numbers_follow_from_committed_data(tmp_path):
    """The committed report is what ``study report`` makes of the committed data."""
    from roughcontact.studies.report import write_report

    committed = json.loads((ROOT / "reproduction" / "claims.json").read_text())
    made = write_report(DATA / "collected.nc", tmp_path)
    # The same data through another numpy/scipy (fits, medians) moves the last digits:
    # the claims' numbers agree to 1e-9 relative, far below what the report prints (3-4
    # significant digits); keys, verdicts, counts and texts exactly.
    assert_numbers_close(json.loads((tmp_path / "claims.json").read_text()), committed)
    assert made["claims"]["eq3_linearity"]["tasks"] == committed["eq3_linearity"]["tasks"]
