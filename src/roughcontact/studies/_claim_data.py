"""What every claim of a study report reads from a collected study: per-task values,
the analysed tasks, spreads and t-intervals over seeds, parameter levels and groups.

Shared by :mod:`.claims` and :mod:`.criteria_claims`; ``ds`` is a collected study
(:func:`~roughcontact.studies.collect.collect_study`).
"""

from __future__ import annotations

import math

import numpy as np

from .._validate import ParameterError
from .aggregate import _mean_interval

#: What :func:`criterion` lists of a parameter set whose decided verdicts differ.
DISAGREEMENT_KEYS = (
    "hurst",
    "rms_slope",
    "short_cutoff",
    "adhesion_length",
    "verdict",
    "predicted_verdict",
    "predicted_verdict_continuum",
    "kappa",
    "kappa_att",
    "predicted_kappa_att",
    "kappa_rep",
)


def _task(ds, name) -> np.ndarray:
    return np.asarray(ds[name].values, dtype=float) if name in ds.variables else None


def _analysed(ds) -> np.ndarray:
    """Indices of the tasks with a path analysis (κ exists, ±inf included)."""
    if "kappa" not in ds.variables:
        raise ParameterError("the dataset has no path analysis ('kappa'): collect a study first")
    kappa = _task(ds, "kappa")
    done = np.asarray(ds["status"].values == "done") if "status" in ds.variables else True
    return np.flatnonzero(~np.isnan(kappa) & done)


def _slope(ds) -> np.ndarray:
    """h'_rms each task's analysis used (the measured one when collected)."""
    for name in ("measured_rms_slope", "rms_slope"):
        v = _task(ds, name)
        if v is not None and np.all(np.isfinite(v[_analysed(ds)])):
            return v
    return _task(ds, "rms_slope")


def _seeds(ds) -> np.ndarray:
    if "seed" in ds.coords:
        return np.asarray(ds["seed"].values)
    return np.zeros(ds.sizes["task"], dtype=int)


def _spread(values) -> dict:
    """Median, 16th/84th percentiles, min, max and count of the finite values."""
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v)]
    if v.size == 0:
        return {
            "median": math.nan,
            "p16": math.nan,
            "p84": math.nan,
            "min": math.nan,
            "max": math.nan,
            "count": 0,
        }
    p16, med, p84 = np.percentile(v, [16, 50, 84])
    return {
        "median": float(med),
        "p16": float(p16),
        "p84": float(p84),
        "min": float(v.min()),
        "max": float(v.max()),
        "count": int(v.size),
    }


def _t_interval(values, confidence=0.95) -> dict:
    """Mean of per-seed values with its Student-t interval (NaN below two seeds)."""
    mean, low, high, n = _mean_interval(values, confidence)
    return {"mean": mean, "low": low, "high": high, "seeds": n}


def _per_seed(ds, tasks, statistic, confidence=0.95) -> dict:
    """``statistic(task indices of one seed)`` per seed, then its mean over seeds."""
    seeds = _seeds(ds)
    tasks = np.asarray(tasks, dtype=int)
    per = [statistic(tasks[seeds[tasks] == s]) for s in np.unique(seeds[tasks])]
    return _t_interval(per, confidence)


def _median(values):
    """A statistic for :func:`_per_seed`: the median of ``values`` over the given tasks."""
    return lambda t: float(np.nanmedian(values[t])) if t.size else math.nan


def _approach_steps(ds, tasks) -> dict:
    """Per-step arrays (tasks × step) restricted to converged approach steps of ``tasks``."""
    on = np.asarray(ds["branch"].values == "approach")[tasks]
    if "converged" in ds.variables:
        on &= np.asarray(ds["converged"].values, dtype=bool)[tasks]
    names = ("repulsive_area", "repulsive_load", "attractive_area", "attractive_load", "perimeter")
    out = {k: np.where(on, np.asarray(ds[k].values, dtype=float)[tasks], np.nan) for k in names}
    return out


def _groups(ds, tasks, drop) -> dict:
    """Tasks grouped by their parameters except those in ``drop`` (e.g. ℓa)."""
    from .schema import SWEEP_KEYS

    keys = [k for k in (*SWEEP_KEYS, "seed") if k in ds.coords and k not in drop]
    keys = [k for k in keys if k not in ("work_of_adhesion", "range", "law_inputs")]
    out: dict[tuple, list[int]] = {}
    for i in tasks:
        label = tuple(str(np.asarray(ds[k].values)[i]) for k in keys)
        out.setdefault(label, []).append(int(i))
    return out


def _levels(ds, name, tasks) -> list[float]:
    return sorted(set(np.asarray(ds[name].values, dtype=float)[tasks].tolist()))
