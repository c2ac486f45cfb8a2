"""The adhesive part of the main job: a built-in study reproducing the substance of Figs. 1-4.

One surface family (H = 0.8, h'rms = 0.1, λs = 4 a0, λL = L/2: at 256², A_rep/λs² ≈ 41 at
1 % contact, enough contacts for the paper's statistics) on a half-space, the paper's
smoothed 9-3 LJ wall at adhesion lengths from clearly non-sticky to clearly sticky, five
seeds; each task an approach/retraction path analysed at A_rep = 1 % of A0
(Pastewka & Robbins, PNAS 111, 3298 (2014)), keeping the pressure map of its approach
state nearest A_rep = 2 % of A0 for the contact maps of Fig. 1. The seeds are combined by
:func:`roughcontact.studies.aggregate.aggregate_seeds` (through 1/κ), the verdicts by the
one rule of :mod:`roughcontact.analysis.stickiness`. Results, figures and a Markdown
report go to one directory; a rerun resumes what is there.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

__all__ = ["ADHESION_LENGTHS", "MAP_AREA", "demo_study", "run_demo_study", "summary_lines"]

#: From clearly not sticky to clearly sticky for this surface family: the measured onset
#: (κ changing sign) lies between 0.001 and 0.005 at 256², so both sides are tested.
ADHESION_LENGTHS = (0.0005, 0.001, 0.002, 0.005, 0.02)
#: A_rep/A0 of the contact maps of Fig. 1 (about the paper's; the figures' default).
MAP_AREA = 0.02
SHORT_CUTOFF = 4.0
#: (label, cell) of the table's columns; a cell formats one aggregated row.
_COLUMNS = (
    ("ℓa/a0", lambda r: f"{r['adhesion_length']:g}"),
    ("seeds", lambda r: str(r["analysed"])),
    ("κ(1 %)", lambda r: _num(r.get("kappa"))),
    ("1/κ [95 % CI]", lambda r: _interval(r, "inverse_kappa")),
    ("κ_rep paper's wall", lambda r: _num(r.get("kappa_rep"))),
    ("κ_rep hard wall (corr.)", lambda r: _pair(r, "kappa_rep_hard_wall")),
    ("δ/a0", lambda r: _num(r.get("band_width"), 2)),
    ("κ_att", lambda r: _num(r.get("kappa_att"))),
    ("κ_att Eq. 7", lambda r: _num(r.get("predicted_kappa_att"))),
    ("A_rep/A_att", lambda r: _num(r.get("area_ratio"))),
    ("Eq. 6", lambda r: _num(r.get("predicted_area_ratio"))),
    ("pull-off N/(A0E*)", lambda r: _num(r.get("pull_off"), 2)),
    ("measured", lambda r: str(r.get("verdict"))),
    ("Eq. 10 (κ_rep measured)", lambda r: str(r.get("predicted_verdict"))),
    ("Eq. 10 (κ_rep = 2)", lambda r: str(r.get("predicted_verdict_continuum"))),
)


def demo_study(size: int, seeds) -> dict:
    """The built-in study as the dict a TOML study file would give."""
    return {
        "study": {"name": "demo", "description": "roughcontact demo: Figs. 1-4"},
        "surface": {
            "size": int(size),
            "hurst": 0.8,
            "rms_slope": 0.1,
            "short_cutoff": SHORT_CUTOFF,
            "seeds": [int(s) for s in seeds],
        },
        "substrate": {"contact_modulus": 1.0},
        "interaction": {"law": "lj93smooth", "adhesion_length": list(ADHESION_LENGTHS)},
        "path": {
            "unit": "rms_height",
            "start": 0.5,
            "stop": -2.0,
            "step": 0.125,
            "retract": True,
            # the retraction returns to 3 a0 above the first contact, beyond the reach
            # of the strongest attraction, so that the pull-off is measured
            "lead_in": [3.0, 1.5],
        },
        "solver": {"tol": 1e-6},
        "analysis": {"target_area": 0.01},
        # Fig. 1 needs one pressure map per task, at the approach state nearest MAP_AREA
        # (the state figure1 shows); a few 100 kB in all instead of 0.5 MB per step
        "output": {"fields_at_area": [MAP_AREA], "fields": ["pressure"]},
    }


def _num(value, digits: int = 3) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "–"
    if math.isinf(value):
        return "∞" if value > 0 else "−∞"
    return f"{value:.{digits}g}".replace("-", "−")


def _interval(row, key) -> str:
    low, high = row.get(f"{key}_low"), row.get(f"{key}_high")
    if low is None or math.isnan(low):
        return _num(row.get(key))
    return f"{_num(row.get(key), 2)} [{_num(low, 2)}, {_num(high, 2)}]"


def _pair(row, key) -> str:
    return f"{_num(row.get(key))} ({_num(row.get(key + '_corrected'))})"


def _table(rows) -> list[str]:
    head = [label for label, _ in _COLUMNS]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    lines += ["| " + " | ".join(cell(r) for _, cell in _COLUMNS) + " |" for r in rows]
    return lines


def _span(rows, key, digits=3) -> str:
    values = [r[key] for r in rows if r.get(key) is not None and math.isfinite(r[key])]
    if not values:
        return "–"
    lo, hi = min(values), max(values)
    return (
        _num(lo, digits)
        if f"{lo:.{digits}g}" == f"{hi:.{digits}g}"
        else (f"{_num(lo, digits)}–{_num(hi, digits)}")
    )


def _ratios(rows, measured, predicted):
    return [
        dict(r, ratio=r[measured] / r[predicted])
        for r in rows
        if all(
            r.get(k) is not None and math.isfinite(r[k]) and r[k] != 0
            for k in (measured, predicted)
        )
    ]


def summary_lines(rows) -> list[str]:
    """What agrees with the paper, what differs and why, in a few lines (from ``rows``)."""
    if not rows:
        return ["No finished task: nothing to compare."]
    lines = []
    by_verdict = {}
    for r in rows:
        by_verdict.setdefault(r["verdict"], []).append(f"{r['adhesion_length']:g}")
    lines.append(
        "Measured (κ < 0 at A_rep = 1 % of A0; over the seeds, the interval of 1/κ): "
        + "; ".join(f"{v} at ℓa/a0 = {', '.join(las)}" for v, las in by_verdict.items())
        + "."
    )
    for key, what in (
        ("predicted_verdict", "Eq. 10 with the measured κ_rep"),
        ("predicted_verdict_continuum", "Eq. 10 with the continuum κ_rep = 2"),
    ):
        decided = [r for r in rows if r["verdict"] != "undecided"]
        agree = sum(1 for r in decided if r[key] == r["verdict"])
        lines.append(f"{what} agrees with the measured verdict in {agree} of {len(decided)} "
                     "decided cases.")  # fmt: skip
    lines.append(
        f"κ_rep of the paper's wall is {_span(rows, 'kappa_rep')}, a hard wall on the same "
        f"surfaces gives {_span(rows, 'kappa_rep_hard_wall')} "
        f"({_span(rows, 'kappa_rep_hard_wall_corrected')} with the corrected area). The paper's "
        "wall (site stiffness k = E*/(2a0), softer than the substrate's on-site stiffness) "
        f"counts a band δ = {_span(rows, 'band_width', 2)} a0 around each contact as repulsive "
        f"(πδ/d_rep = {_span(rows, 'band_fraction', 2)}); a larger grid keeps it. The paper's "
        "κ_rep ≈ 2 is the continuum hard-wall value. The verdicts use the measured κ_rep."
    )
    eq4 = _span(rows, "attractive_pressure_over_w_per_dr")
    lines.append(f"Eq. 4: the mean attractive pressure is {eq4} × w/Δr.")
    for measured, predicted, name in (
        ("area_ratio", "predicted_area_ratio", "A_rep/A_att against Eq. 6"),
        ("kappa_att", "predicted_kappa_att", "κ_att against Eq. 7"),
    ):
        ratios = _ratios(rows, measured, predicted)
        if ratios:
            lines.append(
                f"{name} (measured/predicted, measured d_rep): "
                + ", ".join(f"{r['ratio']:.2f} at ℓa/a0 = {r['adhesion_length']:g}" for r in ratios)
                + "."
            )
    lines.append(
        "Eqs. 6-7 assume the gap outside the contacts is the non-adhesive one: they hold for "
        "weak adhesion; stronger adhesion pulls the surfaces together and A_att grows beyond "
        "Eq. 6 (κ_att below Eq. 7). The pull-off force is reported beside the verdict, not "
        "part of it: a few adhering asperities give a small pull-off on any adhesive surface."
    )
    return lines


def _map_rows(maps) -> list[dict]:
    """ℓa, seed and the A_rep/A0, A_att/A0 of each map of Fig. 1 (as drawn)."""
    from ..plot import contact_masks

    rows = []
    for ds in maps:
        params = json.loads(ds.attrs.get("task_parameters", "{}"))
        rep, att, _, _ = contact_masks(ds, MAP_AREA)
        rows.append(
            {
                "adhesion_length": params.get("adhesion_length"),
                "seed": params.get("seed"),
                "repulsive_area": float(rep.mean()),
                "attractive_area": float(att.mean()),
            }
        )
    return rows


def _figure1_note(map_rows) -> list[str]:
    """The report's paragraph on Fig. 1 (or why it is missing)."""
    if not map_rows:
        return ["Fig. 1 (contact maps) not drawn: no finished task holds a pressure map."]
    panels = "; ".join(
        f"ℓa/a0 = {r['adhesion_length']:g}: A_rep/A0 = {r['repulsive_area']:.4f}, "
        f"A_att/A0 = {r['attractive_area']:.4f}"
        for r in map_rows
    )
    return [
        f"Fig. 1: contact maps of seed {map_rows[0]['seed']} on the approach, at the state "
        f"nearest A_rep/A0 = {MAP_AREA:g} for each adhesion length ({panels}); repulsive "
        "sites orange, attractive sites black."
    ]


def _figures(out: Path, ds):
    """Draw Figs. 1-4 (PNG and PDF) from the collected study and its task files."""
    from ..plot import save_figures, study_maps

    maps = study_maps(out / "tasks")
    figures = save_figures(
        ds, out / "figures", formats=("png", "pdf"), maps=maps, target_area=MAP_AREA
    )
    return figures, _map_rows(maps)


def run_demo_study(out_dir, *, size: int = 256, seeds=(1, 2, 3, 4, 5), workers=None, progress=True):
    """Run (or resume) the built-in study, collect it, draw Figs. 1-4, write ``report.md``.

    The directory is locked for the whole run (:mod:`roughcontact.studies.lock`): a second
    demo writing into it fails at once instead of mixing its files with this one's.

    Returns a JSON-ready dict: the per-ℓa table, the paths of the outputs, the run summary,
    the areas of Fig. 1's maps.
    """
    from ..studies import run_study, study_from_dict
    from ..studies.lock import directory_lock

    out = Path(out_dir)
    spec = study_from_dict(demo_study(size, seeds), source="<roughcontact demo>")
    with directory_lock(out, hint="run 'roughcontact demo' again (it resumes)"):
        summary = run_study(spec, out / "tasks", resume=True, workers=workers, progress=progress)
        return _outputs(out, size, seeds, summary)


def _outputs(out: Path, size, seeds, summary) -> dict:
    """Collect the finished study, draw the figures, write ``report.md``; the JSON dict."""
    from .._io import write_netcdf_atomic
    from ..studies import collect_study
    from ..studies.aggregate import aggregate_seeds

    ds = collect_study(out / "tasks")
    write_netcdf_atomic(ds, out / "demo.nc")  # atomic; a full disk is one clear error
    figures, map_rows = _figures(out, ds)
    rows = aggregate_seeds(ds)
    summary_text = summary_lines(rows)
    report = [
        "# roughcontact demo",
        "",
        f"Self-affine surfaces {size}², H = 0.8, h'rms = 0.1, λs = {SHORT_CUTOFF:g} a0, "
        f"λL = L/2, seeds {list(seeds)}; the paper's smoothed 9-3 LJ wall (k = E*/(2 a0), "
        "Δr = √(24 a0 ℓa)) on an elastic half-space; approach and retraction under "
        "displacement control; everything measured at A_rep = 1 % of A0 on the approach "
        "(Pastewka & Robbins, PNAS 111, 3298 (2014)).",
        "",
        *_table(rows),
        "",
        "Over the seeds, κ-like quantities are combined through their inverses: "
        "κ = 1/mean(1/κ), with the 95 % interval of mean(1/κ) (1/κ = N/(h'rms E* A_rep) is "
        "additive and finite where κ diverges). measured: sticky ⇔ the interval of 1/κ lies "
        "below 0, not sticky above, undecided when it contains 0. Eq. 10: the same rule on "
        "the predicted 1/κ = 1/κ_rep − 1/κ_att (Eq. 7 with the measured d_rep), with the "
        "measured κ_rep and with κ_rep = 2. κ_rep hard wall: the non-adhesive hard wall on "
        "the same surfaces at A_rep = 1 % (in brackets: with the perimeter-corrected area); "
        "δ: the width of the paper's wall's repulsive band, (A_rep − A_rep,hw)/P at the same "
        "repulsive load. Per-seed values are in demo.nc.",
        "",
        *summary_text,
        "",
        *_figure1_note(map_rows),
        "",
        f"Run: {summary}",
        "",
        *[f"![{name}](figures/{Path(p[0]).name})" for name, p in figures.items() if p],
    ]
    (out / "report.md").write_text("\n".join(report) + "\n", encoding="utf-8")
    return {
        "table": rows,
        "summary": summary_text,
        "report": str(out / "report.md"),
        "dataset": str(out / "demo.nc"),
        "figures": {k: [str(x) for x in v] for k, v in figures.items()},
        "tasks": summary.tasks,
        "failed": summary.failed,
        "analysis_errors": summary.analysis_errors,
        "contact_maps": map_rows,
        "table_markdown": _table(rows),
    }
