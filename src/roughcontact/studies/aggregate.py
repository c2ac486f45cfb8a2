r"""Statistics over the realisations (seeds) of each parameter set of a collected study.

Tasks that differ only in their seed are one parameter set. Over them:

* κ, κ_rep (both definitions), κ_att and the predicted κ's are combined through their
  inverses (:func:`roughcontact.analysis.stickiness.inverse_mean`): 1/κ is
  :math:`N/(h'_{rms}E^*A_{rep})`, additive and finite through the onset of stickiness,
  where κ itself diverges and changes sign. ``kappa = 1/mean(1/κ)``; the interval is
  that of the mean of 1/κ (``inverse_kappa_low``/``_high``).
* ``area_ratio`` :math:`A_{rep}/A_{att}` likewise through :math:`A_{att}/A_{rep}` (the
  attractive area at a fixed repulsive area is the additive quantity).
* Other quantities (pull-off, δ, d_rep, Eq. 4's ratio): mean and Student-t interval.
* The verdicts: the one rule of :mod:`roughcontact.analysis.stickiness` on the interval of
  1/κ (measured), of the predicted 1/κ with the measured κ_rep (Eq. 10) and with the
  continuum κ_rep = 2.

Per-seed values stay in the collected dataset; nothing here averages κ itself.
"""

from __future__ import annotations

import math

import numpy as np

from .._validate import ParameterError
from ..analysis.stickiness import inverse_mean
from .schema import SWEEP_KEYS

__all__ = ["INVERSE_KEYS", "MEAN_KEYS", "aggregate_seeds"]

#: Aggregated through their inverses.
INVERSE_KEYS = (
    "kappa",
    "kappa_rep",
    "kappa_rep_hard_wall",
    "kappa_rep_hard_wall_corrected",
    "kappa_att",
    "predicted_kappa_att",
    "predicted_kappa",
    "predicted_kappa_continuum",
    "area_ratio",
    "predicted_area_ratio",
)
#: Aggregated as plain means.
MEAN_KEYS = (
    "pull_off",
    "band_width",
    "band_fraction",
    "d_rep",
    "attractive_pressure_over_w_per_dr",
    "kappa_fit",
)
#: (verdict key, the κ whose 1/κ interval decides it)
_VERDICTS = (
    ("verdict", "kappa"),
    ("predicted_verdict", "predicted_kappa"),
    ("predicted_verdict_continuum", "predicted_kappa_continuum"),
)


def _mean_interval(values, confidence):
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v)]
    if v.size == 0:
        return math.nan, math.nan, math.nan, 0
    mean = float(v.mean())
    if v.size < 2:
        return mean, math.nan, math.nan, 1
    from scipy.stats import t

    half = float(t.ppf(0.5 + confidence / 2, v.size - 1)) * float(v.std(ddof=1))
    half /= math.sqrt(v.size)
    return mean, mean - half, mean + half, int(v.size)


def _parameter_sets(ds):
    """Groups of task indices with equal parameters (all but the seed), in task order."""
    keys = [k for k in SWEEP_KEYS if k in ds.coords and k != "seed"]
    groups: dict[tuple, list[int]] = {}
    for i in range(ds.sizes["task"]):
        label = tuple(_plain(ds[k].values[i]) for k in keys)
        groups.setdefault(label, []).append(i)
    return keys, groups


def _plain(value):
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and math.isnan(value):
        return "nan"  # NaN != NaN: make equal parameter sets group together
    return value


def aggregate_seeds(ds, *, confidence: float = 0.95) -> list[dict]:
    """One row per parameter set of a collected study (module docstring).

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`roughcontact.studies.collect_study`.
    confidence : float
        Two-sided level of the intervals, in (0, 1).

    Returns
    -------
    list of dict
        Per parameter set: its parameters (the task coordinates but ``seed``), ``seeds``
        (those with an analysis), ``tasks``, ``analysed``, ``analysis_errors``,
        ``unconverged_steps``; for each of ``INVERSE_KEYS`` the value ``1/mean(1/x)``,
        ``inverse_<key>`` with ``inverse_<key>_low``/``_high`` (the interval of the mean
        of 1/x) and ``<key>_values`` per seed; for each of ``MEAN_KEYS`` the mean with
        ``<key>_low``/``_high``; ``verdict``, ``predicted_verdict`` (Eq. 10, measured
        κ_rep) and ``predicted_verdict_continuum`` (κ_rep = 2): "sticky", "not sticky"
        or "undecided". Dimensionless except pull-off (N/A0, units of E*) and lengths
        (units of a0).
    """
    if not 0 < confidence < 1:
        raise ParameterError(f"confidence must be in (0, 1), got {confidence!r}")
    if "task" not in getattr(ds, "dims", {}):
        raise ParameterError("aggregate_seeds needs a collected study (a 'task' dimension)")
    keys, groups = _parameter_sets(ds)
    rows = []
    for label, tasks in groups.items():
        row = dict(zip(keys, label, strict=True))
        errors = [str(ds["analysis_error"].values[i]) for i in tasks if "analysis_error" in ds]
        # analysed: κ exists (±inf included: zero load at the target area, the onset)
        kappa = np.asarray(ds["kappa"].values, dtype=float) if "kappa" in ds else None
        analysed = [i for i in tasks if kappa is not None and not math.isnan(kappa[i])]
        row |= {
            "tasks": len(tasks),
            "analysed": len(analysed),
            "seeds": [int(ds["seed"].values[i]) for i in analysed] if "seed" in ds.coords else [],
            "analysis_errors": sum(1 for e in errors if e),
            "unconverged_steps": int(
                np.nansum([float(ds["steps_not_converged"].values[i]) for i in tasks])
            )
            if "steps_not_converged" in ds
            else 0,
        }
        stats = {}
        for key in INVERSE_KEYS:
            if key not in ds:
                continue
            values = [float(ds[key].values[i]) for i in analysed]
            m = stats[key] = inverse_mean(values, confidence=confidence)
            row[key] = m.value
            row[f"inverse_{key}"] = m.mean
            row[f"inverse_{key}_low"], row[f"inverse_{key}_high"] = m.low, m.high
            row[f"{key}_values"] = values
        for key in MEAN_KEYS:
            if key in ds:
                mean, low, high, _ = _mean_interval(
                    [float(ds[key].values[i]) for i in analysed], confidence
                )
                row[key], row[f"{key}_low"], row[f"{key}_high"] = mean, low, high
        for name, key in _VERDICTS:
            row[name] = stats[key].verdict if key in stats else None
        rows.append(row)
    return rows
