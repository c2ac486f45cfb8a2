r"""Stickiness criteria judged by the simulation, and the adhesion hysteresis of a study.

Moved here from :mod:`roughcontact.studies.claims` (which re-exports every name):

* :func:`criterion` -- Eq. 10 of Pastewka & Robbins with the *measured* κ_rep and d_rep
  (and κ_rep = 2), confusion tables against the measured verdicts;
* :func:`necessary_condition` -- ``ℓa/a0 ≳ 0.5 h'_rms``.

New:

* :func:`stickiness_criteria` -- every criterion of :mod:`roughcontact.stickiness`,
  evaluated *a priori* on each parameter set (its inputs from the self-affine spectrum in
  closed form: H, h'rms, λs, L, the system size, the roll-off, E*, w, Δr), against the
  measured verdict (sticky ⇔ 1/κ < 0 at A_rep = 1 %, seeds combined through 1/κ). For
  each criterion: the confusion table, the agreement among the sets where both decide,
  and the best agreement any threshold on the same parameter could reach (whether the
  criterion's *form* orders the sets correctly, whatever its constant);
* :func:`adhesion_hysteresis` -- the energy an approach–retraction cycle dissipates
  (:mod:`roughcontact.analysis.hysteresis`, per A0 in units of E* a0) and the number of
  jumps, per task from the collected steps, summarised by ℓa/a0 and per parameter set
  (mean ± sd over seeds).
"""

from __future__ import annotations

import math

import numpy as np

from ..analysis.stickiness import NOT_STICKY, STICKY, UNDECIDED
from ..theory.pastewka_robbins import KAPPA_REP, NECESSARY_CONDITION_CONSTANT
from .aggregate import aggregate_seeds

__all__ = ["adhesion_hysteresis", "criterion", "necessary_condition", "stickiness_criteria"]

VERDICTS = (STICKY, NOT_STICKY, UNDECIDED)


def _confusion(measured, predicted) -> dict:
    table = {m: {p: 0 for p in VERDICTS} for m in VERDICTS}
    for m, p in zip(measured, predicted, strict=True):
        if m in table and p in table[m]:
            table[m][p] += 1
    decided = [
        (m, p)
        for m, p in zip(measured, predicted, strict=True)
        if m != UNDECIDED and p != UNDECIDED
    ]
    agree = sum(m == p for m, p in decided)
    return {"table": table, "decided": len(decided), "agree": agree}


def _task_verdict(sticky) -> str:
    if sticky is None or (isinstance(sticky, float) and math.isnan(sticky)):
        return UNDECIDED
    return STICKY if bool(sticky) else NOT_STICKY


def criterion(ds, *, confidence=0.95) -> dict:
    r"""Eq. 10: sticky iff ``1/κ_att > 1/κ_rep``; confusion tables.

    Per parameter set (seeds combined through 1/κ,
    :func:`~roughcontact.studies.aggregate.aggregate_seeds`): the measured verdict
    against the predicted one with the measured κ_rep and with κ_rep = 2; and per task
    (one seed each: "sticky"/"not sticky", never undecided).
    """
    from ._claim_data import DISAGREEMENT_KEYS, _analysed, _task

    rows = aggregate_seeds(ds, confidence=confidence)
    rows = [r for r in rows if r["analysed"]]
    measured = [r["verdict"] for r in rows]
    out = {
        "parameter_sets": len(rows),
        "measured_kappa_rep": _confusion(measured, [r["predicted_verdict"] for r in rows]),
        "continuum_kappa_rep": _confusion(
            measured, [r["predicted_verdict_continuum"] for r in rows]
        ),
    }
    tasks = _analysed(ds)
    per_task = [_task_verdict(_task(ds, "sticky")[i]) for i in tasks]
    for key, name in (
        ("predicted_sticky", "per_task_measured_kappa_rep"),
        ("predicted_sticky_continuum", "per_task_continuum_kappa_rep"),
    ):
        v = _task(ds, key)
        if v is not None:
            out[name] = _confusion(per_task, [_task_verdict(v[i]) for i in tasks])
    out["disagreements"] = [
        {k: r.get(k) for k in DISAGREEMENT_KEYS}
        for r in rows
        if UNDECIDED not in (r["verdict"], r["predicted_verdict"])
        and r["verdict"] != r["predicted_verdict"]
    ]
    return out


def necessary_condition(ds, *, confidence=0.95) -> dict:
    r"""``ℓa/a0 ≳ 0.5 h'_rms`` (unrounded: ``c/κ_rep`` with c = 0.9717, κ_rep = 2).

    Per parameter set: whether ℓa/a0 reaches ``(c/2) h'_rms`` (the nominal slope), and
    the measured verdict; counts of sticky sets that violate it (the paper: none). The
    condition assumes Δr ≈ a0 ≤ δh; ``applicable`` counts the sets where the analysis
    found that true.
    """
    from ._claim_data import _analysed, _levels, _task

    rows = [r for r in aggregate_seeds(ds, confidence=confidence) if r["analysed"]]
    bound = NECESSARY_CONDITION_CONSTANT / KAPPA_REP
    a0 = _task(ds, "pixel_size")
    a0 = float(np.nanmedian(a0)) if a0 is not None else 1.0
    table = {"met": dict.fromkeys(VERDICTS, 0), "not_met": dict.fromkeys(VERDICTS, 0)}
    for r in rows:
        try:
            la = float(r.get("adhesion_length"))
        except (TypeError, ValueError):  # a non-adhesive set ("" / None): nothing to meet
            continue
        if not np.isfinite(la):
            continue
        met = la / a0 >= bound * r["rms_slope"]
        table["met" if met else "not_met"][r["verdict"]] += 1
    tasks = _analysed(ds)
    note = (
        np.asarray(ds["necessary_condition"].values)[tasks]
        if "necessary_condition" in ds.variables
        else []
    )
    applicable = int(sum(1 for n in note if not str(n).startswith("not applicable")))
    la, dr = _task(ds, "adhesion_length"), _task(ds, "range")
    ranges = (
        {
            str(lv): float(np.nanmedian(dr[tasks][la[tasks] == lv]) / a0)
            for lv in _levels(ds, "adhesion_length", tasks)
        }
        if dr is not None
        else {}
    )
    return {
        "bound": bound,
        "table": table,
        "sticky_without_condition": table["not_met"][STICKY],
        "applicable_tasks": applicable,
        "tasks": int(tasks.size),
        "range_over_a0": ranges,
    }


# ------------------------------------------------------------------ the field's criteria
def _float(row, key, default=math.nan) -> float:
    v = row.get(key, default)
    try:
        return float(v)
    except (TypeError, ValueError):
        return default


def _row_inputs(row):
    """CriterionInputs of one parameter set from its spectrum, or the reason there are none."""
    from .._validate import ParameterError
    from ..stickiness import self_affine_inputs

    a0 = _float(row, "pixel_size", 1.0)
    size = _float(row, "size") * a0
    lam_L = _float(row, "long_cutoff")
    if not math.isfinite(lam_L):
        lam_L = size / 2
    slope, height = _float(row, "rms_slope"), _float(row, "rms_height")
    rolloff = str(row.get("rolloff", True)).lower() not in ("false", "0")
    try:
        return self_affine_inputs(
            hurst=_float(row, "hurst"),
            rms_slope=slope if math.isfinite(slope) else None,
            rms_height=None if math.isfinite(slope) else height,
            short_cutoff=_float(row, "short_cutoff"),
            long_cutoff=lam_L,
            size=size,
            rolloff=rolloff,
            contact_modulus=_float(row, "contact_modulus", 1.0),
            work_of_adhesion=_float(row, "work_of_adhesion"),
            interaction_range=_float(row, "range"),
        )
    except ParameterError as err:
        return str(err)


def _best_threshold(params, measured, sticky_below) -> dict:
    """The threshold on ``params`` that agrees with most decided measured verdicts."""
    pairs = [(p, m) for p, m in zip(params, measured, strict=True)
             if math.isfinite(p) and m in (STICKY, NOT_STICKY)]  # fmt: skip
    if not pairs:
        return {"threshold": math.nan, "agree": 0, "decided": 0}
    values = sorted({p for p, _ in pairs})
    cuts = [
        values[0] * 0.5,
        *[(a + b) / 2 for a, b in zip(values, values[1:], strict=False)],
        values[-1] * 2,
    ]
    best = (-1, math.nan)
    for c in cuts:
        agree = sum((p < c if sticky_below else p > c) == (m == STICKY) for p, m in pairs)
        if agree > best[0]:
            best = (agree, c)
    return {"threshold": best[1], "agree": best[0], "decided": len(pairs)}


def stickiness_criteria(ds, *, confidence=0.95) -> dict:
    """Every criterion of :mod:`roughcontact.stickiness` against the measured verdicts.

    Returns ``{"parameter_sets", "criteria": {key: {...}}, "sets": [...]}``; per criterion
    its name, reference, parameter symbol and threshold, the ``confusion`` table (measured
    × predicted; "undecided" on the predicted side is "no verdict"), ``agree`` of
    ``decided``, and ``best_threshold`` (the threshold on the same parameter that agrees
    with most decided sets, and how many it gets right).
    """
    from ..stickiness import CRITERIA, DESCRIPTORS

    rows = [r for r in aggregate_seeds(ds, confidence=confidence) if r["analysed"]]
    measured = [r["verdict"] for r in rows]
    results = []
    for r in rows:
        inputs = _row_inputs(r)
        results.append(
            {k: f(inputs) for k, f in CRITERIA.items()} if not isinstance(inputs, str) else {}
        )
    out = {"parameter_sets": len(rows), "criteria": {}, "sets": []}
    for key, d in DESCRIPTORS.items():
        res = [x.get(key) for x in results]
        predicted = [_task_verdict(None if x is None else x.sticky) for x in res]
        params = [math.nan if x is None else x.parameter for x in res]
        block = _confusion(measured, predicted)
        block.update(
            name=d.name,
            reference=d.reference,
            parameter_symbol=d.parameter_symbol,
            threshold=d.threshold,
            sticky_below=d.sticky_below,
            validated=d.validated,
            best_threshold=_best_threshold(params, measured, d.sticky_below),
            no_verdict=sum(x is None or x.sticky is None for x in res),
        )
        out["criteria"][key] = block
    for r, res in zip(rows, results, strict=True):
        out["sets"].append(
            {
                **{k: r.get(k) for k in ("hurst", "rms_slope", "short_cutoff", "adhesion_length")},
                "verdict": r["verdict"],
                **{f"{k}_parameter": (v.parameter if v else math.nan) for k, v in res.items()},
            }
        )
    return out


# ------------------------------------------------------------------------- hysteresis
def adhesion_hysteresis(ds, *, confidence=0.95) -> dict:
    """Energy dissipated per approach–retraction cycle, per task, summarised by ℓa/a0.

    Per task (the collected steps in order): ``W = -∮ N dd`` per A0 [E* a0], its bound
    from the jump steps, and the jumps in and out; per ℓa the spread over tasks
    (median, 16th-84th percentiles) of W, of the jumps and of W per jump, and the count
    of tasks whose cycle is not closed; ``by_parameter_set``: per parameter set (tasks
    that differ only in the seed) the mean and sample standard deviation over its seeds
    of the same (``{"mean", "sd", "seeds"}``); ``task_columns``: whether the collection
    has the per-task variables of ``study collect`` (else they come from the steps alone).
    """
    from ..analysis.hysteresis import hysteresis_from_steps
    from ._claim_data import _levels, _spread

    if "offset" not in ds.variables or "branch" not in ds.variables:
        return {"tasks": 0, "by_adhesion_length": [], "by_parameter_set": [],
                "task_columns": False}  # fmt: skip
    off = np.asarray(ds["offset"].values, dtype=float)
    load = np.asarray(ds["load"].values, dtype=float)
    branch = np.asarray(ds["branch"].values).astype(str)
    jump = np.asarray(ds["jump"].values, dtype=bool) if "jump" in ds.variables else None
    conv = np.asarray(ds["converged"].values, dtype=bool) if "converged" in ds.variables else None
    done = np.asarray(ds["status"].values == "done") if "status" in ds.variables else None
    tasks = [i for i in range(off.shape[0]) if done is None or done[i]]
    per = {}
    for i in tasks:
        per[i] = hysteresis_from_steps(
            off[i], load[i], branch[i], None if jump is None else jump[i],
            None if conv is None else conv[i],
        )  # fmt: skip
    la = np.asarray(ds["adhesion_length"].values, dtype=float)
    out = {
        "tasks": len(per),
        "by_adhesion_length": [],
        "by_parameter_set": _by_parameter_set(ds, per),
        # new collections carry them per task (``study collect``); older ones only the steps
        "task_columns": all(k in ds.variables for k in _TASK_COLUMNS),
    }
    for lv in _levels(ds, "adhesion_length", np.asarray(tasks, dtype=int)):
        sel = [per[i] for i in tasks if la[i] == lv]
        out["by_adhesion_length"].append({"adhesion_length": lv, **_summary(sel, _spread)})
    return out


def _summary(sel, statistic) -> dict:
    """``statistic`` (a spread over tasks, or mean ± sd over seeds) of each cycle quantity."""
    return {
        "tasks": len(sel),
        **{
            key: statistic([getattr(h, key) for h in sel])
            for key in ("dissipated_energy", "energy_uncertainty", "jumps", "energy_per_jump")
        },
        "not_closed": sum(not h.closed for h in sel),
    }


#: The per-task hysteresis variables ``study collect`` writes (PathAnalysis fields).
_TASK_COLUMNS = ("dissipated_energy", "dissipated_energy_bound", "jumps", "energy_per_jump")


def _mean_sd(values) -> dict:
    """Mean and sample standard deviation over seeds of the finite values (NaN sd: one)."""
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v)]
    return {
        "mean": float(v.mean()) if v.size else math.nan,
        "sd": float(v.std(ddof=1)) if v.size > 1 else math.nan,
        "seeds": int(v.size),
    }


def _by_parameter_set(ds, per) -> list[dict]:
    """Per parameter set (tasks differing only in the seed): mean ± sd over its seeds of W,
    its bound, the jumps and W per jump (units of :func:`adhesion_hysteresis`)."""
    from .aggregate import _parameter_sets

    keys, groups = _parameter_sets(ds)
    rows = []
    for label, tasks in groups.items():
        sel = [per[i] for i in tasks if i in per]
        if not sel:
            continue
        rows.append({**dict(zip(keys, label, strict=True)), **_summary(sel, _mean_sd)})
    return rows


# ------------------------------------------------------------------------ the report
def _n(x, digits=3) -> str:
    # "nan": a parameter-set label of a parameter the study does not set (aggregate._plain)
    if x is None or x == "nan" or (isinstance(x, float) and not math.isfinite(x)):
        return "—"
    return f"{x:.{digits}g}"


def report_lines(c) -> list[str]:
    """Markdown of :func:`report_blocks`."""
    from ..htmlreport import markdown_lines

    return markdown_lines(report_blocks(c))


def report_blocks(c) -> list:
    """Sections 9 and 10 of the report (:mod:`roughcontact.htmlreport` blocks) from
    :func:`stickiness_criteria` and :func:`adhesion_hysteresis` (``c``: the claims of
    :func:`roughcontact.studies.claims.all_claims`)."""
    from ..htmlreport import Bullets, Heading, Para, Table

    B = []
    sc = c.get("stickiness_criteria")
    if sc:
        rows = []
        for b in sc["criteria"].values():
            t = b["table"]
            bt = b["best_threshold"]
            sign = "<" if b["sticky_below"] else ">"
            agree = f"{b['agree']} of {b['decided']}" if b["decided"] else "no verdict"
            rows.append((
                b["name"], b["parameter_symbol"], f"{sign} {_n(b['threshold'])}",
                str(t[STICKY][STICKY]), str(t[STICKY][NOT_STICKY]), str(t[NOT_STICKY][STICKY]),
                str(t[NOT_STICKY][NOT_STICKY]),
                f"{t[UNDECIDED][STICKY]}/{t[UNDECIDED][NOT_STICKY]}",
                agree, f"{sign} {_n(bt['threshold'])} ({bt['agree']} of {bt['decided']})",
            ))  # fmt: skip
        B += [
            Heading(
                "9. Which criterion predicts the onset of stickiness in the paper's own model?"
            ),
            Para(
                "*Not in the paper.* Every criterion of `roughcontact.stickiness`, evaluated a "
                "priori on each parameter set (inputs from the self-affine spectrum in closed "
                "form: H, h′rms, λs, L, the roll-off, E*, w, Δr; Eq. 10 with d_rep = "
                f"4h′rms/h″rms and κ_rep = 2), against the measured verdict "
                f"({sc['parameter_sets']} parameter sets; rows measured, columns predicted; a "
                "criterion without a verdict counts as undecided). *Best threshold*: the "
                "threshold on the same parameter that agrees with the most decided sets — "
                "whether the criterion's form orders the sets right, whatever its constant."
            ),
            Table(
                (
                    "criterion",
                    "parameter",
                    "threshold",
                    "sticky→sticky",
                    "sticky→not",
                    "not→sticky",
                    "not→not",
                    "undecided→sticky/not",
                    "agree (decided)",
                    "best threshold (agree)",
                ),
                tuple(rows),
            ),  # fmt: skip
            Para(
                "Dahlquist's rule needs SI (no scale in lattice units) and Müser's parameter "
                "(R = 1/h''rms, as the Adhesion package evaluates it) classifies the regime "
                "without a stickiness threshold: neither gives a verdict here. The Fuller–Tabor "
                "threshold θ = 10 is a convention. No bearing-area criterion (Ciavarella's BAM, "
                "Violano et al.) is evaluated: its equations could not be checked against the "
                "papers (see the docs)."
            ),
            Para("Where each criterion had been validated before this table:"),
            Bullets(tuple(f"{b['name']}: {b['validated']}." for b in sc["criteria"].values())),
        ]
    hy = c.get("adhesion_hysteresis")
    if hy and hy.get("by_adhesion_length"):
        rows = []
        for r in hy["by_adhesion_length"]:
            cols = [
                f"{_n(r[k]['median'])} [{_n(r[k]['p16'])}, {_n(r[k]['p84'])}]"
                for k in ("dissipated_energy", "energy_uncertainty", "jumps", "energy_per_jump")
            ]
            rows.append((_n(r["adhesion_length"]), *cols, str(r["not_closed"])))
        B += [
            Heading("10. Adhesion hysteresis: energy dissipated per approach–retraction cycle"),
            Para(
                "*Not in the paper.* W = −∮N dd per A0 (units of E* a0) over each task's "
                "collected steps; the bound sums |ΔN||Δd|/2 over the steps flagged as jumps (the "
                "steps do not resolve where a jump happens). A cycle without jumps dissipates "
                "nothing: its W is 0 within the bound 1e-6 of the path's ∫|N| |dd| (the bound "
                "column then holds it; roughcontact.analysis.hysteresis). "
                f"{hy['tasks']} tasks; median [16th, 84th percentile] over tasks:"
            ),
            Table(
                ("ℓa/a0", "W/(E* a0)", "bound", "jumps", "W per jump", "cycles not closed"),
                tuple(rows),
            ),  # fmt: skip
            *_set_blocks(hy),
        ]
    return B


def _ms(d) -> str:
    """``mean ± sd`` over seeds (``mean`` alone with one seed)."""
    if not d["seeds"]:
        return "—"
    return _n(d["mean"]) + ("" if d["seeds"] < 2 else f" ± {_n(d['sd'], 2)}")


def _set_blocks(hy) -> list:
    """§10's table per parameter set (mean ± sd over seeds), as blocks."""
    from ..htmlreport import Para, Table

    sets = hy.get("by_parameter_set") or []
    if not sets:
        return []
    source = (
        "the task variables written by `study collect`"
        if hy.get("task_columns")
        else "the collected steps: this data predates the per-task hysteresis variables "
        "(dissipated_energy, dissipated_energy_bound, jumps, energy_per_jump) that "
        "`study collect` now writes for new runs; both come from the same function"
    )
    return [
        Para(
            f"Per parameter set ({len(sets)}; mean ± sample standard deviation over its seeds, "
            f"computed from {source}). W in units of E* a0 per A0; a cycle without jumps "
            "counts 0 (no dissipation; its trapezoid's round-off is of order 1e-12):"
        ),
        Table(
            (
                "H",
                "h′rms",
                "λs/a0",
                "ℓa/a0",
                "seeds",
                "W/(E* a0)",
                "jumps",
                "W per jump",
                "not closed",
            ),
            tuple(
                (
                    _n(r.get("hurst")),
                    _n(r.get("rms_slope")),
                    _n(r.get("short_cutoff")),
                    _n(r.get("adhesion_length")),
                    str(r["dissipated_energy"]["seeds"]),
                    _ms(r["dissipated_energy"]),
                    _ms(r["jumps"]),
                    _ms(r["energy_per_jump"]),
                    str(r["not_closed"]),
                )
                for r in sets
            ),
        ),  # fmt: skip
    ]
