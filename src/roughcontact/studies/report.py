"""``roughcontact study report``: a study's data, figures and the paper's claims checked.

From a study directory (or its collected NetCDF file) it writes, inside the output
directory only and each file atomically:

* ``data/collected.nc`` — the collected dataset without wall-clock times (per task and
  per step scalars, no field maps); ``data/tasks.csv`` (one row per task: parameters,
  path analysis), ``data/steps.csv`` (one row per computed step), ``data/
  parameter_sets.csv`` (seeds combined, :func:`~roughcontact.studies.aggregate.
  aggregate_seeds`);
* ``claims.json`` — every number of :mod:`roughcontact.studies.claims`;
* ``versions.json`` — the study (name, sha256, tasks done) and the software versions;
* ``figures/fig2_area_load.png``, ``fig3_collapse.png``, ``fig4_theory.png`` — the
  paper's Figs. 2-4 in its symbol code;
* ``README.md`` — the claims one by one with our numbers beside them.

The report is size-agnostic: the same command makes it for L = 1024 a0 or 4096 a0.
"""

from __future__ import annotations

import io
import json
import math
import platform
from pathlib import Path

import numpy as np

from .._io import write_bytes_atomic, write_netcdf_atomic
from .._validate import ParameterError, json_safe
from . import claims as _claims

__all__ = ["load_collected", "render_report", "write_report"]

STEP_COLUMNS = (
    "branch",
    "offset",
    "load",
    "repulsive_load",
    "attractive_load",
    "repulsive_area",
    "attractive_area",
    "perimeter",
    "mean_gap",
    "iterations",
    "residual",
    "repulsive_patches",
    "converged",
    "jump",
)


def load_collected(source):
    """The collected dataset of a study directory or of a collected ``.nc`` file."""
    import xarray as xr

    from .collect import TIMINGS, collect_study

    src = Path(source)
    if src.is_dir():
        return collect_study(src, include_timings=False)
    try:
        ds = xr.load_dataset(src, engine="h5netcdf")
    except (OSError, ValueError) as err:
        raise ParameterError(
            f"{str(src)!r} is neither a study directory nor a readable NetCDF file ({err})"
        ) from None
    if "task" not in ds.dims:
        raise ParameterError(
            f"{str(src)!r} is not a collected study (no 'task' dimension); make one with "
            "'roughcontact study collect DIR -o OUT.nc'"
        )
    return ds.drop_vars([k for k in TIMINGS if k in ds.variables])


# ------------------------------------------------------------------------- tables
def _tasks_frame(ds):
    import pandas as pd

    cols = {"task": np.asarray(ds["task"].values)}
    for name, var in {**ds.coords, **ds.data_vars}.items():
        if var.dims == ("task",):
            cols[name] = np.asarray(var.values)
    return pd.DataFrame(cols)


def _steps_frame(ds):
    import pandas as pd

    frames = []
    task_ids = np.asarray(ds["task"].values)
    n_steps = np.asarray(ds["n_steps"].values, dtype=int)
    for i, tid in enumerate(task_ids):
        n = n_steps[i]
        if n == 0:
            continue
        block = {"task": np.repeat(tid, n), "step": np.arange(n)}
        for name in STEP_COLUMNS:
            if name in ds.variables:
                block[name] = np.asarray(ds[name].values)[i, :n]
        frames.append(pd.DataFrame(block))
    return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame()


def _sets_frame(ds):
    import pandas as pd

    from .aggregate import aggregate_seeds

    rows = aggregate_seeds(ds)
    return pd.DataFrame([{k: v for k, v in r.items() if not isinstance(v, list)} for r in rows])


def _csv(frame) -> bytes:
    return frame.to_csv(index=False, float_format="%.10g").encode()


# ------------------------------------------------------------------------- text
def _n(x, digits=3) -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "–"
    if isinstance(x, str):
        return x
    if x != 0 and (abs(x) < 1e-3 or abs(x) >= 1e4):
        return f"{x:.{digits - 1}e}"
    return f"{x:.{digits}g}"


def _iv(d) -> str:
    """``mean [low, high]`` of a per-seed interval (or just the mean, and why)."""
    if not d or d.get("seeds", 0) == 0:
        return "–"
    if d["seeds"] < 2:
        return f"{_n(d['mean'])} (1 seed: no interval)"
    return f"{_n(d['mean'])} [{_n(d['low'])}, {_n(d['high'])}]"


def _sp(d) -> str:
    """``median (p16-p84, n = count)``."""
    if not d or d.get("count", 0) == 0:
        return "–"
    return f"{_n(d['median'])} ({_n(d['p16'])}–{_n(d['p84'])}, n = {d['count']})"


def _confusion_lines(block, title) -> list[str]:
    verdicts = _claims.VERDICTS
    lines = [f"{title}: {block['agree']} of {block['decided']} decided cases agree.", ""]
    lines.append("| measured ↓ / predicted → | " + " | ".join(verdicts) + " |")
    lines.append("|---|" + "---|" * len(verdicts))
    for m in verdicts:
        lines.append(f"| {m} | " + " | ".join(str(block["table"][m][p]) for p in verdicts) + " |")
    return [*lines, ""]


def _header(meta) -> list[str]:
    return [
        f"# {meta['title']}",
        "",
        "Generated by `roughcontact study report` from the data in this folder; do not edit "
        "by hand. L. Pastewka and M. O. Robbins, *Contact between rough surfaces and a "
        "criterion for macroscopic adhesion*, PNAS 111, 3298 (2014).",
        "",
        f"- Study: `{meta['study_name']}` (sha256 `{meta['study_sha256'][:12]}…`), "
        f"{meta['tasks_done']} tasks done, {meta['tasks_failed']} failed, "
        f"{meta['tasks_missing']} missing; {meta['analysed']} analysed; seeds "
        f"{meta['seeds']}.",
        f"- Grid: {meta['grid']}.",
        f"- Unconverged steps: {meta['unconverged_steps']} (left out of every number below).",
        f"- roughcontact {meta['versions']['roughcontact']}, Python "
        f"{meta['versions']['python']}, NumPy {meta['versions']['numpy']}, SciPy "
        f"{meta['versions']['scipy']}.",
        "",
        "Lattice units: lengths in units of a0, pressures in units of E*, areas and loads "
        "per nominal area A0. κ's are combined over tasks and seeds through 1/κ. Intervals "
        "are 95 % Student-t intervals over seeds of the per-seed statistic (none with one "
        "seed); spreads are the 16th–84th percentiles over tasks or steps.",
        "",
        "## How to regenerate",
        "",
        "```console",
        f"$ roughcontact study run {meta['study_file']} -o {meta['study_dir']} --resume",
        f"$ roughcontact study report {meta['study_dir']} -o {meta['report_dir']}",
        "```",
        "",
        "The report alone also rebuilds from the committed data: "
        f"`roughcontact study report {meta['report_dir']}/data/collected.nc -o OUT`.",
        "",
    ]


def _claim_lines(c) -> list[str]:
    L = []
    lin = c["eq3_linearity"]
    L += [
        "## 1. A_rep ∝ N at small area (Eq. 3)",
        "",
        "*Paper:* the repulsive area is proportional to the load at small areas.  ",
        "*Here:* κ_rep(A) = h′rms E* A_rep/N_rep along each approach, over its value at "
        f"A_rep = 1 % (1 = linear). Linear within ±{lin['band']:.0%} for "
        f"A_rep/A0 in [{_n(lin['linear_from'])}, {_n(lin['linear_to'])}] (bins below; per "
        "seed: "
        + ", ".join(
            f"seed {s}: [{_n(v['from'])}, {_n(v['to'])}]" for s, v in lin["per_seed"].items()
        )
        + ").",
        "",
        "| A_rep/A0 | κ_rep(A)/κ_rep(1 %) median (16–84 %, steps) |",
        "|---|---|",
        *[f"| {_n(b['from'])}–{_n(b['to'])} | {_sp(b)} |" for b in lin["bins"]],
        "",
        "The paper analyses only A_rep ≥ 10 λs² (enough asperities in contact), here "
        "A_rep/A0 ≥ "
        + ", ".join(f"{_n(v)} (λs = {_n(float(k))} a0)" for k, v in lin["statistical_from"].items())
        + "; below, the ratio is set by the first few asperities, not by the linear law.",
        "",
    ]
    kr = c["kappa_rep"]
    L += [
        "## 2. κ_rep ≈ 2 — two definitions",
        "",
        "*Paper:* κ_rep ≈ 2 (the continuum hard-wall value).  ",
        "*Here:* κ_rep = h′rms E* A_rep/N_rep at A_rep = 1 %: the paper's definition (N_rep of "
        "the adhesive run, the 9-3 wall's finite stiffness) and the hard-wall reference on the "
        "same surface (raw site count, and the Yastrebov-corrected area).",
        "",
        "| λs/a0 | tasks | paper's definition | hard wall | hard wall, corrected |",
        "|---|---|---|---|---|",
    ]
    for row in kr["rows"]:
        lam = "all" if row["short_cutoff"] == "all" else _n(row["short_cutoff"])
        L.append(
            f"| {lam} | {row['tasks']} | {_iv(row.get('kappa_rep'))} | "
            f"{_iv(row.get('kappa_rep_hard_wall'))} | "
            f"{_iv(row.get('kappa_rep_hard_wall_corrected'))} |"
        )
    L += [
        "",
        "The paper's definition exceeds the hard wall's: the 9-3 wall is soft (k = E*/(2a0)), "
        "so sites in a band of width δ around each contact feel repulsion that a hard wall "
        "would count as gap; δ/d_rep shrinks as λs grows, and the two approach each other.",
        "",
    ]
    ad = c["repulsive_pressure_and_adhesion"]
    L += [
        "## 3. N_rep/A_rep unchanged by adhesion (Fig. 3, upper inset)",
        "",
        "*Paper:* adhesion does not change the mean repulsive pressure h′rms E*/κ_rep.  ",
        "*Here:* κ_rep / κ_rep(hard wall, same surface) per ℓa, and per surface the change of "
        "κ_rep from the smallest to the largest ℓa: "
        f"{_sp(ad['change_smallest_to_largest'])}.",
        "",
        "| ℓa/a0 | κ_rep/κ_rep,hw over tasks | over seeds |",
        "|---|---|---|",
        *[
            f"| {_n(r['adhesion_length'])} | {_sp(r['over_hard_wall'])} | "
            f"{_iv(r['over_hard_wall_seeds'])} |"
            for r in ad["rows"]
        ],
        "",
    ]
    e4 = c["eq4_attractive_pressure"]
    L += [
        "## 4. N_att = (w/Δr) A_att (Eq. 4)",
        "",
        "*Paper:* the ratio is 1 over five decades.  ",
        f"*Here:* N_att/((w/Δr)A_att) at every converged approach step with A_att > 0 over "
        f"{_n(e4['all']['decades'])} decades of A_att ({_n(e4['all']['area_from'])} to "
        f"{_n(e4['all']['area_to'])}): {_sp(e4['all']['steps'])}; within ±{e4['band']:.0%} "
        f"of 1 at {_n(100 * e4['all']['fraction_within_band'])} % of the steps.",
        "",
        "| ℓa/a0 | ratio per step | decades of A_att | within band | at A_rep = 1 % (seeds) |",
        "|---|---|---|---|---|",
        *[
            f"| {_n(r['adhesion_length'])} | {_sp(r['steps'])} | {_n(r['decades'])} | "
            f"{_n(100 * r['fraction_within_band'])} % | {_iv(r['at_target'])} |"
            for r in e4["rows"]
        ],
        "",
    ]
    e9 = c["eq9_contact_diameter"]
    L += [
        "## 5. A_rep = P d_rep/π, d_rep within ×2 of 4h′rms/h″rms (Fig. 3, lower inset)",
        "",
        "*Paper:* d_rep/π always within a factor of 2 of 4h′rms/(π h″rms); d_rep changes by "
        "< 25 % over 2–3 decades of A_rep.  ",
        f"*Here:* d_rep/(4h′rms/h″rms) = {_sp(e9['ratio'])} (over seeds {_iv(e9['ratio_seeds'])}); "
        f"within ×{_n(e9['factor'])} for {_n(100 * e9['fraction_within_factor'])} % of the "
        f"tasks. Variation of πA_rep/P for 1e-3 ≤ A_rep/A0 ≤ 3e-2 (max/min − 1): "
        f"{_sp(e9['variation_with_area'])}.",
        "",
    ]
    th = c["eqs6_7_thin_rim"]
    L += [
        "## 6. Eqs. 6 and 7 where A_att < A_rep, and where they break",
        "",
        "*Paper:* measured = predicted for weak adhesion; deviations when A_att > A_rep.  ",
        "*Here:* measured/predicted (prediction with the measured d_rep = πA_rep/P, and with "
        "4h′rms/h″rms):",
        "",
        "| regime | tasks | A_rep/A_att (Eq. 6) | κ_att (Eq. 7) | Eq. 6, d_rep from h″ | "
        "Eq. 7, d_rep from h″ |",
        "|---|---|---|---|---|---|",
    ]
    for name, label in (("thin_rim", "A_att < A_rep"), ("wide_rim", "A_att > A_rep")):
        b = th[name]
        L.append(
            f"| {label} | {b['tasks']} | {_sp(b.get('area_ratio'))} | "
            f"{_sp(b.get('kappa_att'))} | {_sp(b.get('area_ratio_from_curvature'))} | "
            f"{_sp(b.get('kappa_att_from_curvature'))} |"
        )
    L += [
        "",
        "Thin-rim regime per ℓa (measured/predicted):",
        "",
        "| ℓa/a0 | A_rep/A_att | κ_att |",
        "|---|---|---|",
    ]
    for r in th["thin_rim"].get("by_adhesion_length", []):
        L.append(f"| {_n(r['adhesion_length'])} | {_sp(r['area_ratio'])} | {_sp(r['kappa_att'])} |")
    cr = c["eq10_criterion"]
    L += [
        "",
        "## 7. Sticky iff 1/κ_att > 1/κ_rep (Eq. 10)",
        "",
        '*Paper:* "our numerical results show stickiness if and only if this condition is met".  ',
        f"*Here:* per parameter set ({cr['parameter_sets']}), seeds combined through 1/κ "
        '("undecided" when the interval of 1/κ contains 0). Measured: sticky ⇔ 1/κ < 0 at '
        "A_rep = 1 %. Predicted: Eq. 7's κ_att against κ_rep.",
        "",
        *_confusion_lines(cr["measured_kappa_rep"], "With the measured κ_rep"),
        *_confusion_lines(cr["continuum_kappa_rep"], "With κ_rep = 2"),
    ]
    if "per_task_measured_kappa_rep" in cr:
        b, b2 = cr["per_task_measured_kappa_rep"], cr["per_task_continuum_kappa_rep"]
        L += [
            f"Per task (one seed each): {b['agree']} of {b['decided']} agree with the measured "
            f"κ_rep, {b2['agree']} of {b2['decided']} with κ_rep = 2.",
            "",
        ]
    if cr["disagreements"]:
        L += [
            "Parameter sets where the decided verdicts differ (measured κ_rep):",
            "",
            "| H | h′rms | λs/a0 | ℓa/a0 | measured | predicted | κ_rep = 2 | κ | κ_att | κ_rep |",
            "|---|---|---|---|---|---|---|---|---|---|",
        ]
        for r in cr["disagreements"]:
            L.append(
                "| "
                + " | ".join(
                    _n(r.get(k)) if not isinstance(r.get(k), str) else r[k]
                    for k in (
                        "hurst",
                        "rms_slope",
                        "short_cutoff",
                        "adhesion_length",
                        "verdict",
                        "predicted_verdict",
                        "predicted_verdict_continuum",
                        "kappa",
                        "kappa_att",
                        "kappa_rep",
                    )
                )
                + " |"
            )
        L.append("")
    ks, nc = c["kappa_att_scaling"], c["necessary_condition"]
    meas, pred = ks.get("measured", {}), ks.get("predicted", {})
    L += [
        "## 8. κ_att ∝ 1/ℓa at fixed geometry; ℓa/a0 ≳ 0.5 h′rms",
        "",
        "*Paper:* 1/κ_att rises linearly with ℓa; sticking needs ℓa/a0 ≳ 0.5 h′rms.  ",
        f"*Here:* the exponent β of κ_att ∝ ℓa^β per surface: measured {_sp(meas)} (over seeds "
        f"{_iv(meas.get('seeds'))}); Eq. 7 on the same tasks {_sp(pred)}. With the smoothed "
        "9-3 wall the range grows with ℓa (Δr ∝ ℓa^½), so Eq. 7 itself gives β = −5/6, not −1.",
        "",
        f"Necessary condition ℓa/a0 ≥ {_n(nc['bound'])} h′rms (nominal h′rms), parameter sets:",
        "",
        "| condition | sticky | not sticky | undecided |",
        "|---|---|---|---|",
        *[
            f"| {'met' if k == 'met' else 'not met'} | "
            + " | ".join(str(nc["table"][k][v]) for v in _claims.VERDICTS)
            + " |"
            for k in ("met", "not_met")
        ],
        "",
        f"Sticky sets that violate it: {nc['sticky_without_condition']}. The condition assumes "
        f"Δr ≈ a0 ≤ δh, which holds in {nc['applicable_tasks']} of {nc['tasks']} tasks here "
        "(Δr/a0 = "
        + ", ".join(f"{_n(v)} at ℓa/a0 = {_n(float(k))}" for k, v in nc["range_over_a0"].items())
        + ").",
        "",
    ]
    return L


def _figure_lines(figures) -> list[str]:
    if not figures:
        return []
    return [
        "## Figures",
        "",
        "Symbols as in the paper: shape by H (triangle 0.3, square 0.5, circle 0.8), colour by "
        "ℓa/a0 (black, blue, red), filled/open by h′rms (0.1/0.3), size by λs.",
        "",
        *[f"![{name}](figures/{name}.png)\n" for name in figures],
    ]


def render_report(claims: dict, meta: dict, figures=()) -> str:
    """The Markdown report of :func:`roughcontact.studies.claims.all_claims` numbers."""
    return "\n".join([*_header(meta), *_claim_lines(claims), *_figure_lines(figures)]) + "\n"


def _versions() -> dict:
    import scipy
    import xarray

    from .. import __version__

    return {
        "roughcontact": __version__,
        "python": platform.python_version(),
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "xarray": xarray.__version__,
    }


def _meta(ds, source, out, claims) -> dict:
    seeds = sorted(set(np.asarray(ds["seed"].values).tolist())) if "seed" in ds.coords else []
    a = ds.attrs
    grid = []
    for key, label in (
        ("size", "n"),
        ("hurst", "H"),
        ("rms_slope", "h′rms"),
        ("short_cutoff", "λs/a0"),
        ("adhesion_length", "ℓa/a0"),
    ):
        if key in ds.coords:
            levels = ", ".join(_n(v) for v in sorted(set(ds[key].values.tolist())))
            grid.append(f"{label} ∈ {{{levels}}}")
    settings = json.loads(a.get("study_settings", "{}") or "{}")
    study_dir = str(source) if Path(source).is_dir() else "STUDY_DIR"
    study_file = f"{study_dir}/study.toml" if Path(source).is_dir() else "STUDY.toml"
    done = (np.asarray(ds["status"].values) == "done") if "status" in ds.variables else None
    return {
        "title": f"Reproduction of Pastewka & Robbins (2014): study '{a.get('study_name', '?')}'",
        "study_name": a.get("study_name", "?"),
        "study_sha256": a.get("study_sha256", "?"),
        "tasks_done": int(a.get("tasks_done", done.sum() if done is not None else 0)),
        "tasks_failed": int(a.get("tasks_failed", 0)),
        "tasks_missing": int(a.get("tasks_missing", 0)),
        "analysed": claims["eq3_linearity"]["tasks"],
        "seeds": seeds,
        "grid": "; ".join(grid),
        "unconverged_steps": int(np.nansum(ds["steps_not_converged"].values))
        if "steps_not_converged" in ds.variables
        else 0,
        "target_area": settings.get("analysis", {}).get("target_area", 0.01),
        "study_file": study_file,
        "study_dir": study_dir,
        "report_dir": str(out),
        "versions": _versions(),
    }


def write_report(source, out_dir, *, confidence: float = 0.95, dpi: int = 120) -> dict:
    """Write the data, claims, figures and ``README.md`` of a study into ``out_dir``.

    Parameters
    ----------
    source : path-like
        A study directory (``roughcontact study run -o DIR``) or a collected ``.nc``.
    out_dir : path-like
        Output directory (created); nothing is written elsewhere.
    confidence : float
        Level of the intervals over seeds, in (0, 1).
    dpi : int
        Resolution of the PNG figures.

    Returns
    -------
    dict
        ``{"claims": ..., "files": [written paths]}``.
    """
    ds = load_collected(source)
    out = Path(out_dir)
    claims = _claims.all_claims(ds, confidence=confidence)
    meta = _meta(ds, source, out, claims)
    files = []
    data = out / "data"
    data.mkdir(parents=True, exist_ok=True)
    files.append(write_netcdf_atomic(ds, data / "collected.nc"))
    for name, frame in (
        ("tasks", _tasks_frame(ds)),
        ("steps", _steps_frame(ds)),
        ("parameter_sets", _sets_frame(ds)),
    ):
        files.append(write_bytes_atomic(data / f"{name}.csv", _csv(frame)))
    text = json.dumps(json_safe(claims), indent=1, sort_keys=True, allow_nan=False)
    files.append(write_bytes_atomic(out / "claims.json", (text + "\n").encode()))
    versions = {
        k: meta[k]
        for k in (
            "study_name",
            "study_sha256",
            "tasks_done",
            "tasks_failed",
            "tasks_missing",
            "seeds",
            "versions",
        )
    }
    text = json.dumps(json_safe(versions), indent=1, sort_keys=True)
    files.append(write_bytes_atomic(out / "versions.json", (text + "\n").encode()))
    figures = _figures(ds, out / "figures", dpi, files)
    readme = render_report(claims, meta, figures)
    files.append(write_bytes_atomic(out / "README.md", readme.encode()))
    return {"claims": claims, "files": [str(f) for f in files]}


def _figures(ds, fig_dir, dpi, files) -> list[str]:
    """Figs. 2-4 as PNG (atomically); the names of those made."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..plot.figures import FIGURES

    fig_dir.mkdir(parents=True, exist_ok=True)
    made = []
    for name, make in FIGURES.items():
        fig = make(ds)
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=dpi, bbox_inches="tight")
        plt.close(fig)
        files.append(write_bytes_atomic(fig_dir / f"{name}.png", buf.getvalue()))
        made.append(name)
    return made
