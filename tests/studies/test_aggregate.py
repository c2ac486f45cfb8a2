"""Seeds combined through 1/κ, one verdict rule, per parameter set of a collected study."""

import math

import numpy as np
import pytest
import xarray as xr

from roughcontact import ParameterError
from roughcontact.studies.aggregate import aggregate_seeds


def collected(kappa_by_la, kappa_rep=4.0, kappa_att_pred=None):
    """A minimal collected study: tasks = ℓa × seeds with the given per-seed κ."""
    la, seed, kappa = [], [], []
    for value, kappas in kappa_by_la.items():
        for s, k in enumerate(kappas, start=1):
            la.append(value)
            seed.append(s)
            kappa.append(k)
    n = len(kappa)
    kappa = np.array(kappa)
    # 1/κ_att = 1/κ_rep − 1/κ: the identity the analysis obeys
    with np.errstate(divide="ignore"):
        kappa_att = 1 / (1 / kappa_rep - 1 / kappa)
    pred = kappa_att if kappa_att_pred is None else np.full(n, kappa_att_pred)
    return xr.Dataset(
        {
            "kappa": ("task", kappa),
            "kappa_rep": ("task", np.full(n, kappa_rep)),
            "kappa_att": ("task", kappa_att),
            "predicted_kappa_att": ("task", pred),
            "predicted_kappa": ("task", 1 / (1 / kappa_rep - 1 / pred)),
            "predicted_kappa_continuum": ("task", 1 / (1 / 2.0 - 1 / pred)),
            "pull_off": ("task", np.linspace(0, 1e-3, n)),
            "analysis_error": ("task", np.array([""] * n)),
            "steps_not_converged": ("task", np.zeros(n)),
        },
        coords={
            "task": [f"{i:02d}" for i in range(n)],
            "adhesion_length": ("task", np.array(la)),
            "hurst": ("task", np.full(n, 0.8)),
            "seed": ("task", np.array(seed)),
        },
    )


def test_divergent_seeds_are_undecided_not_averaged():
    ds = collected({0.002: [-180.0, 7.2, 15.4], 0.0005: [5.4, 3.6, 5.6], 0.02: [-0.5, -1.0, -0.7]})
    rows = {r["adhesion_length"]: r for r in aggregate_seeds(ds)}
    assert set(rows) == {0.002, 0.0005, 0.02}
    mid = rows[0.002]
    inv = np.array([-1 / 180, 1 / 7.2, 1 / 15.4])
    assert mid["kappa"] == pytest.approx(1 / inv.mean())  # 15.1, not the mean −52.5
    assert mid["inverse_kappa"] == pytest.approx(inv.mean())
    assert mid["inverse_kappa_low"] < 0 < mid["inverse_kappa_high"]
    assert mid["verdict"] == "undecided"
    assert mid["kappa_values"] == [-180.0, 7.2, 15.4] and mid["seeds"] == [1, 2, 3]
    assert rows[0.0005]["verdict"] == "not sticky" and rows[0.02]["verdict"] == "sticky"
    # κ_rep = 4 for every seed: its aggregate is exact; the identity survives aggregation
    r = rows[0.0005]
    assert r["kappa_rep"] == pytest.approx(4.0)
    assert 1 / r["kappa"] == pytest.approx(1 / r["kappa_rep"] - 1 / r["kappa_att"])
    assert r["pull_off"] == pytest.approx(np.mean(ds["pull_off"].values[3:6]))


def test_predicted_verdicts_use_the_same_rule():
    # κ_att (Eq. 7) = 3: sticky against the measured κ_rep = 4, not against κ_rep = 2
    ds = collected({0.005: [-8.0, -9.0, -10.0]}, kappa_att_pred=3.0)
    (row,) = aggregate_seeds(ds)
    assert row["predicted_verdict"] == "sticky"
    assert row["predicted_verdict_continuum"] == "not sticky"


def test_tasks_without_analysis_are_counted_not_averaged():
    ds = collected({0.001: [5.0, 6.0, 7.0]})
    ds["kappa"].values[1] = math.nan
    ds["analysis_error"].values[1] = "target area 0.01 is not reached"
    ds["steps_not_converged"].values[2] = 4
    (row,) = aggregate_seeds(ds)
    assert row["tasks"] == 3 and row["analysed"] == 2 and row["analysis_errors"] == 1
    assert row["unconverged_steps"] == 4 and row["seeds"] == [1, 3]
    assert row["kappa"] == pytest.approx(1 / np.mean([1 / 5.0, 1 / 7.0]))


def test_bad_input():
    with pytest.raises(ParameterError, match="collected study"):
        aggregate_seeds(xr.Dataset())
    with pytest.raises(ParameterError, match="confidence"):
        aggregate_seeds(collected({0.001: [1.0]}), confidence=0)
