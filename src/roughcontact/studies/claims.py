r"""The claims of Pastewka & Robbins (2014), one by one, measured on a collected study.

Each function takes the dataset of :func:`roughcontact.studies.collect_study` (lattice
units: areas and loads per nominal area A0, loads in units of E*, lengths in units of
a0) and returns a JSON-ready dict of numbers; :func:`all_claims` runs them all and
:mod:`roughcontact.studies.report` writes them beside the paper's statements. Every
number is computed here from the dataset alone, so a report and its data cannot
disagree.

Uncertainty over seeds: a statistic is computed per seed (over the tasks of that
realisation) and its mean over seeds is given with a Student-t interval
(``*_low``/``*_high``; NaN with fewer than two seeds). Spreads over tasks are the
16th-84th percentiles (``p16``/``p84``). Only converged steps and analysed tasks (κ
exists) enter. The claims (equation numbers of the paper):

* Eq. 3: ``A_rep ∝ N_rep`` at small area, measured as the local
  :math:`\kappa_{rep}(A) = h'_{rms}E^*A_{rep}/N_{rep}` relative to its value at the
  target area, per decade of ``A_rep``;
* κ_rep ≈ 2: the paper's definition (the adhesive run's N_rep) and the hard-wall
  reference (raw and Yastrebov-corrected area) per λs;
* adhesion does not change ``N_rep/A_rep`` (Fig. 3, upper inset): κ_rep over the
  hard-wall κ_rep, per ℓa;
* Eq. 4: ``N_att = (w/Δr) A_att`` at every step, per ℓa, and the decades of A_att;
* Eq. 9: ``A_rep = P d_rep/π`` with ``d_rep`` within a factor 2 of ``4h'_rms/h''_rms``;
* Eqs. 6 and 7 where ``A_att < A_rep`` and where they break (``A_att > A_rep``);
* Eq. 10: sticky iff ``1/κ_att > 1/κ_rep``, confusion tables with the measured κ_rep and
  with κ_rep = 2;
* ``1/κ_att`` linear in ℓa at fixed geometry, and the necessary condition
  ``ℓa/a0 ≳ 0.5 h'_rms``;
* the field's other stickiness criteria against the measured verdicts, and the energy
  dissipated per approach–retraction cycle
  (:mod:`roughcontact.studies.criteria_claims`, which also holds Eq. 10's tables).

Reference: L. Pastewka and M. O. Robbins, PNAS 111, 3298 (2014).
"""

from __future__ import annotations

import math

import numpy as np

from .._validate import ParameterError
from ..analysis.stickiness import NOT_STICKY, STICKY, UNDECIDED, inverse_mean
from ..theory.pastewka_robbins import KAPPA_REP
from ._claim_data import (  # the helpers every claim shares
    _analysed,
    _approach_steps,
    _groups,
    _levels,
    _median,
    _per_seed,
    _seeds,
    _slope,
    _spread,
    _t_interval,
    _task,
)
from .aggregate import _mean_interval, aggregate_seeds  # noqa: F401 (re-exported)
from .criteria_claims import (  # moved there; names kept here
    _confusion,  # noqa: F401
    _task_verdict,  # noqa: F401
    adhesion_hysteresis,
    criterion,
    necessary_condition,
    stickiness_criteria,
)

__all__ = [
    "adhesion_and_repulsive_pressure",
    "adhesion_hysteresis",
    "all_claims",
    "area_load_linearity",
    "attractive_pressure",
    "contact_diameter",
    "criterion",
    "kappa_att_scaling",
    "kappa_rep_by_cutoff",
    "necessary_condition",
    "stickiness_criteria",
    "thin_rim_theory",
]

#: Edges of the A_rep/A0 bins of the Eq. 3 linearity (two per decade).
AREA_EDGES = (1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 1e-1)
#: A ratio counts as "the relation holds" within this factor of 1 (Eq. 3 and Eq. 4).
LINEAR_BAND = 0.1
#: Paper: d_rep/π within a factor of 2 of 4h'_rms/(π h''_rms) (Fig. 3, lower inset).
D_REP_FACTOR = 2.0
VERDICTS = (STICKY, NOT_STICKY, UNDECIDED)


# ----------------------------------------------------------------------------- claims
def area_load_linearity(ds, *, target_area=0.01, confidence=0.95) -> dict:
    r"""Eq. 3, ``A_rep = κ_rep N_rep/(h'_rms E*)``: the range of A_rep where it is linear.

    Per converged approach step, :math:`\kappa_{rep}(A) = h'_{rms}E^*A_{rep}/N_{rep}`
    divided by the task's κ_rep at ``target_area``; per bin of :data:`AREA_EDGES`, the
    median and spread of that ratio over steps. ``linear_from``/``linear_to``: the
    contiguous bins around ``target_area`` whose median is within
    :data:`LINEAR_BAND` of 1 (bin edges, A_rep/A0), overall and per seed.
    """
    tasks = _analysed(ds)
    kr = _task(ds, "kappa_rep")
    s, es = _slope(ds), _task(ds, "contact_modulus")
    st = _approach_steps(ds, tasks)
    a, n = st["repulsive_area"], st["repulsive_load"]
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = (s[tasks, None] * es[tasks, None] * a / n) / kr[tasks, None]
    ratio = np.where((a > 0) & (n > 0), ratio, np.nan)

    def bins(rows):
        out = []
        for lo, hi in zip(AREA_EDGES[:-1], AREA_EDGES[1:], strict=True):
            sel = (a[rows] >= lo) & (a[rows] < hi)
            out.append({"from": lo, "to": hi, **_spread(ratio[rows][sel])})
        return out

    def linear_range(table):
        centre = next((j for j, b in enumerate(table) if b["from"] <= target_area < b["to"]), None)
        ok = [abs(b["median"] - 1) <= LINEAR_BAND for b in table]
        if centre is None or not ok[centre]:
            return math.nan, math.nan
        lo = hi = centre
        while lo > 0 and ok[lo - 1]:
            lo -= 1
        while hi < len(table) - 1 and ok[hi + 1]:
            hi += 1
        return table[lo]["from"], table[hi]["to"]

    all_rows = np.arange(tasks.size)
    table = bins(all_rows)
    lo, hi = linear_range(table)
    seeds = _seeds(ds)[tasks]
    per_seed = {}
    for sd in np.unique(seeds):
        per_seed[str(sd)] = dict(zip(("from", "to"), linear_range(bins(seeds == sd)), strict=True))
    # the paper analyses only A_rep >= 10 lambda_s^2 (enough asperities in contact)
    a0 = _task(ds, "pixel_size")
    a0 = a0 if a0 is not None else np.ones(ds.sizes["task"])
    nominal = (
        np.asarray(ds["size"].values, dtype=float) ** 2 * a0**2 if "size" in ds.coords else None
    )
    lam = _task(ds, "short_cutoff") if "short_cutoff" in ds.coords else None
    statistical = {}
    if nominal is not None and lam is not None:
        for level in _levels(ds, "short_cutoff", tasks):
            i = tasks[lam[tasks] == level][0]
            statistical[str(level)] = float(10 * level**2 / nominal[i])
    return {
        "bins": table,
        "linear_from": lo,
        "linear_to": hi,
        "band": LINEAR_BAND,
        "per_seed": per_seed,
        "tasks": int(tasks.size),
        "statistical_from": statistical,
    }


def kappa_rep_by_cutoff(ds, *, confidence=0.95) -> dict:
    r"""κ_rep per λs: the paper's definition and the hard-wall reference (raw, corrected).

    Per seed, κ = 1/mean(1/κ) over the tasks at that λs (1/κ is the additive quantity,
    :func:`~roughcontact.analysis.stickiness.inverse_mean`); then the mean of the
    per-seed κ with its interval. The paper: κ_rep ≈ 2.
    """
    tasks = _analysed(ds)
    lam = (
        _task(ds, "short_cutoff")
        if "short_cutoff" in ds.coords
        else np.full(ds.sizes["task"], np.nan)
    )
    rows = []
    keys = ("kappa_rep", "kappa_rep_hard_wall", "kappa_rep_hard_wall_corrected")
    for level in (
        [*_levels(ds, "short_cutoff", tasks), "all"] if "short_cutoff" in ds.coords else ["all"]
    ):
        sel = tasks if level == "all" else tasks[lam[tasks] == level]
        row = {"short_cutoff": level, "tasks": int(sel.size)}
        for key in keys:
            v = _task(ds, key)
            if v is None:
                continue
            row[key] = _per_seed(ds, sel, lambda t, v=v: inverse_mean(v[t]).value, confidence)
            row[f"{key}_spread"] = _spread(v[sel])
        rows.append(row)
    return {"rows": rows, "paper": KAPPA_REP}


def adhesion_and_repulsive_pressure(ds, *, confidence=0.95) -> dict:
    r"""Fig. 3 upper inset: adhesion does not change ``N_rep/A_rep`` (i.e. κ_rep).

    Per ℓa: κ_rep/κ_rep,hw (the same surface without adhesion, raw site count), and per
    surface (all parameters but ℓa, same seed) the change of κ_rep from the smallest to
    the largest ℓa, ``κ_rep(ℓa_max)/κ_rep(ℓa_min) - 1``.
    """
    tasks = _analysed(ds)
    kr, hw = _task(ds, "kappa_rep"), _task(ds, "kappa_rep_hard_wall")
    la = _task(ds, "adhesion_length")
    rows = []
    for level in _levels(ds, "adhesion_length", tasks):
        sel = tasks[la[tasks] == level]
        ratio = kr / hw if hw is not None else np.full(kr.shape, np.nan)
        rows.append(
            {
                "adhesion_length": level,
                "tasks": int(sel.size),
                "over_hard_wall": _spread(ratio[sel]),
                "over_hard_wall_seeds": _per_seed(ds, sel, _median(ratio), confidence),
            }
        )
    change = []
    for members in _groups(ds, tasks, drop=("adhesion_length",)).values():
        m = np.asarray(members)
        if m.size < 2:
            continue
        lo, hi = m[np.argmin(la[m])], m[np.argmax(la[m])]
        change.append(kr[hi] / kr[lo] - 1)
    return {"rows": rows, "change_smallest_to_largest": _spread(change)}


def attractive_pressure(ds, *, confidence=0.95) -> dict:
    r"""Eq. 4, ``N_att = (w/Δr) A_att``: the ratio at every converged approach step.

    Per ℓa (and over all): median and spread of :math:`N_{att}/((w/\Delta r)A_{att})`
    over steps with ``A_att > 0``, the decades of A_att they span, the fraction of steps
    within :data:`LINEAR_BAND` of 1, and the ratio at the target area
    (``attractive_pressure_over_w_per_dr``) over seeds.
    """
    tasks = _analysed(ds)
    st = _approach_steps(ds, tasks)
    w, dr = _task(ds, "work_of_adhesion"), _task(ds, "range")
    la = _task(ds, "adhesion_length")
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = st["attractive_load"] / (st["attractive_area"] * (w / dr)[tasks, None])
    ok = st["attractive_area"] > 0
    at_target = _task(ds, "attractive_pressure_over_w_per_dr")

    def summary(rows, sel_tasks):
        r, a = ratio[rows][ok[rows]], st["attractive_area"][rows][ok[rows]]
        within = np.abs(r - 1) <= LINEAR_BAND
        return {
            "steps": _spread(r),
            "decades": float(np.log10(a.max() / a.min())) if a.size else math.nan,
            "area_from": float(a.min()) if a.size else math.nan,
            "area_to": float(a.max()) if a.size else math.nan,
            "fraction_within_band": float(within.mean()) if r.size else math.nan,
            "at_target": _per_seed(ds, sel_tasks, _median(at_target), confidence),
        }

    rows = []
    for level in _levels(ds, "adhesion_length", tasks):
        mask = la[tasks] == level
        rows.append({"adhesion_length": level, **summary(mask, tasks[mask])})
    return {"rows": rows, "all": summary(np.ones(tasks.size, bool), tasks), "band": LINEAR_BAND}


def contact_diameter(ds, *, confidence=0.95) -> dict:
    r"""Eq. 9: ``A_rep = P d_rep/π`` and ``d_rep`` against ``4h'_rms/h''_rms``.

    ``d_rep`` (πA_rep/P at the target area) over the prediction from the measured
    slope and curvature: median, spread, fraction within :data:`D_REP_FACTOR`; and per
    task the variation of πA_rep/P over its approach steps with
    ``1e-3 <= A_rep/A0 <= 3e-2`` (``max/min - 1``; the paper: < 25 % over 2-3 decades).
    """
    tasks = _analysed(ds)
    d, pred = _task(ds, "d_rep"), _task(ds, "predicted_d_rep")
    if pred is None or not np.isfinite(pred[tasks]).any():
        pred = _task(ds, "d_rep_predicted")
    ratio = d / pred
    r = ratio[tasks]
    within = np.abs(np.log(r[np.isfinite(r)])) <= math.log(D_REP_FACTOR)
    st = _approach_steps(ds, tasks)
    a, p = st["repulsive_area"], st["perimeter"]
    with np.errstate(divide="ignore", invalid="ignore"):
        dstep = np.where((a >= 1e-3) & (a <= 3e-2) & (p > 0), math.pi * a / p, np.nan)
    var = [np.nanmax(row) / np.nanmin(row) - 1 for row in dstep if np.isfinite(row).sum() >= 2]
    return {
        "ratio": _spread(r),
        "ratio_seeds": _per_seed(ds, tasks, _median(ratio), confidence),
        "fraction_within_factor": float(within.mean()) if within.size else math.nan,
        "factor": D_REP_FACTOR,
        "variation_with_area": _spread(var),
    }


def thin_rim_theory(ds, *, confidence=0.95) -> dict:
    r"""Eqs. 6 and 7 where the attractive rim is thin (``A_att < A_rep``) and where not.

    measured/predicted of ``A_rep/A_att`` (Eq. 6) and of κ_att (Eq. 7), the prediction
    with the measured ``d_rep = πA_rep/P`` and with ``4h'_rms/h''_rms``; split by regime
    and per ℓa in the thin-rim regime.
    """
    tasks = _analysed(ds)
    ar = _task(ds, "area_ratio")
    la = _task(ds, "adhesion_length")
    pairs = {
        "area_ratio": ("area_ratio", "predicted_area_ratio"),
        "kappa_att": ("kappa_att", "predicted_kappa_att"),
        "area_ratio_from_curvature": ("area_ratio", "predicted_area_ratio_from_curvature"),
        "kappa_att_from_curvature": ("kappa_att", "predicted_kappa_att_from_curvature"),
    }
    out = {}
    for regime, mask in (("thin_rim", ar > 1), ("wide_rim", ar <= 1)):
        sel = tasks[mask[tasks]]
        block = {"tasks": int(sel.size)}
        for name, (m, p) in pairs.items():
            if _task(ds, p) is None:
                continue
            ratio = _task(ds, m) / _task(ds, p)
            block[name] = _spread(ratio[sel])
            block[f"{name}_seeds"] = _per_seed(ds, sel, _median(ratio), confidence)
        if regime == "thin_rim":
            katt = _task(ds, "kappa_att") / _task(ds, "predicted_kappa_att")
            area = ar / _task(ds, "predicted_area_ratio")
            block["by_adhesion_length"] = [
                {
                    "adhesion_length": lv,
                    "kappa_att": _spread(katt[sel[la[sel] == lv]]),
                    "area_ratio": _spread(area[sel[la[sel] == lv]]),
                }
                for lv in _levels(ds, "adhesion_length", sel)
            ]
        out[regime] = block
    return out


def kappa_att_scaling(ds, *, confidence=0.95) -> dict:
    r"""``1/κ_att`` against ℓa at fixed geometry: the exponent of κ_att ∝ ℓa^β.

    Per surface (all parameters but ℓa, one seed) with at least two ℓa, the
    least-squares slope β of log κ_att against log ℓa, measured and from Eq. 7 (the
    prediction carries Δr(ℓa) of the interaction law: for the smoothed 9-3 wall
    Δr ∝ ℓa^(1/2), so Eq. 7 gives β = -5/6 rather than -1).
    """
    tasks = _analysed(ds)
    la = _task(ds, "adhesion_length")
    out = {}
    for name, key in (("measured", "kappa_att"), ("predicted", "predicted_kappa_att")):
        v = _task(ds, key)
        if v is None:
            continue
        slopes, seeds = [], []
        for members in _groups(ds, tasks, drop=("adhesion_length",)).values():
            m = np.asarray(members)
            m = m[np.isfinite(v[m]) & (v[m] > 0)]
            if np.unique(la[m]).size >= 2:
                slopes.append(float(np.polyfit(np.log(la[m]), np.log(v[m]), 1)[0]))
                seeds.append(_seeds(ds)[m[0]])
        slopes, seeds = np.asarray(slopes), np.asarray(seeds)
        per_seed = [float(np.median(slopes[seeds == s])) for s in np.unique(seeds)]
        out[name] = {**_spread(slopes), "seeds": _t_interval(per_seed, confidence)}
    return out


def all_claims(ds, *, confidence=0.95, target_area=0.01) -> dict:
    """Every claim of this module on ``ds``, by name (NaN where a number does not exist;
    :func:`roughcontact._validate.json_safe` makes it JSON)."""
    if not 0 < confidence < 1:
        raise ParameterError(f"confidence must be in (0, 1), got {confidence!r}")
    return {
        "eq3_linearity": area_load_linearity(ds, target_area=target_area, confidence=confidence),
        "kappa_rep": kappa_rep_by_cutoff(ds, confidence=confidence),
        "repulsive_pressure_and_adhesion": adhesion_and_repulsive_pressure(
            ds, confidence=confidence
        ),
        "eq4_attractive_pressure": attractive_pressure(ds, confidence=confidence),
        "eq9_contact_diameter": contact_diameter(ds, confidence=confidence),
        "eqs6_7_thin_rim": thin_rim_theory(ds, confidence=confidence),
        "eq10_criterion": criterion(ds, confidence=confidence),
        "kappa_att_scaling": kappa_att_scaling(ds, confidence=confidence),
        "necessary_condition": necessary_condition(ds, confidence=confidence),
        "stickiness_criteria": stickiness_criteria(ds, confidence=confidence),
        "adhesion_hysteresis": adhesion_hysteresis(ds, confidence=confidence),
    }
