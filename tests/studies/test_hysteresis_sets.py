"""A tiny study's hysteresis: `study collect` writes it per task, the report per set."""

from __future__ import annotations

import numpy as np
import pytest

from roughcontact.studies import collect_study, run_study
from roughcontact.studies.criteria_claims import adhesion_hysteresis, report_lines


def test_collect_writes_the_hysteresis_and_the_report_aggregates_it_per_set(tmp_path, make_study):
    out = tmp_path / "out"
    summary = run_study(make_study(), out, scheduler="synchronous", progress=False)
    assert summary.ok
    ds = collect_study(out)
    # study collect: one value per task, from the path analysis of each task
    for name in ("dissipated_energy", "dissipated_energy_bound", "jumps", "energy_per_jump"):
        assert ds[name].dims == ("task",), name
    W = np.asarray(ds["dissipated_energy"].values, dtype=float)
    assert np.all(np.isfinite(W))
    hy = adhesion_hysteresis(ds)
    assert hy["task_columns"] is True
    sets = hy["by_parameter_set"]
    assert len(sets) == 4  # 2 H x 2 l_a, two seeds each
    seed_ = np.asarray(ds["seed"].values)
    for r in sets:
        tasks = [
            i for i in range(ds.sizes["task"])
            if ds["hurst"].values[i] == r["hurst"]
            and ds["adhesion_length"].values[i] == r["adhesion_length"]
        ]  # fmt: skip
        assert sorted(seed_[tasks].tolist()) == [1, 2]
        # the report's per-set numbers (from the steps) against the task variables (from the
        # path analysis of each task): mean and sample sd of the two seeds, by hand
        a, b = W[tasks]
        d = r["dissipated_energy"]
        assert d["seeds"] == 2 and d["mean"] == pytest.approx((a + b) / 2, rel=1e-9, abs=1e-15)
        assert d["sd"] == pytest.approx(abs(a - b) / np.sqrt(2), rel=1e-9, abs=1e-15)
        j = np.asarray(ds["jumps"].values, dtype=float)[tasks]
        assert r["jumps"]["mean"] == pytest.approx(j.mean())
    text = "\n".join(report_lines({"adhesion_hysteresis": hy}))
    assert "Per parameter set (4; mean ± sample standard deviation" in text
    assert "task variables written by `study collect`" in text
    # an old collection without the per-task variables: said so, computed from the steps
    old = ds.drop_vars(["dissipated_energy", "dissipated_energy_bound", "jumps",
                        "energy_per_jump"])  # fmt: skip
    hy_old = adhesion_hysteresis(old)
    assert hy_old["task_columns"] is False
    assert hy_old["by_parameter_set"][0]["dissipated_energy"] == sets[0]["dissipated_energy"]
    assert "predates the per-task hysteresis variables" in "\n".join(
        report_lines({"adhesion_hysteresis": hy_old})
    )
