"""The demo's Markdown report: the per-ℓa table, what agrees with the paper, Fig. 1's note.

Text only, from the rows of :func:`roughcontact.studies.aggregate.aggregate_seeds` (one
per adhesion length ℓa, seeds combined through 1/κ) and the areas of Fig. 1's maps;
measured and predicted quantities as defined by Pastewka & Robbins, PNAS 111, 3298
(2014): κ, κ_rep, κ_att (Eqs. 2-3), A_rep/A_att (Eq. 6), κ_att (Eq. 7), the verdict
(Eq. 10). Loads N/(A0 E*), lengths in a0.
"""

from __future__ import annotations

import math
from pathlib import Path

__all__ = ["figure1_note", "report_lines", "summary_lines", "table_lines"]


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


def table_lines(rows) -> list[str]:
    """The Markdown table of the aggregated rows, one line per ℓa."""
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


def figure1_note(map_rows, map_area: float) -> list[str]:
    """The report's paragraph on Fig. 1 (or why it is missing).

    ``map_rows``: ℓa, seed, A_rep/A0 and A_att/A0 of each map as drawn; ``map_area``: the
    A_rep/A0 at which the maps were picked.
    """
    if not map_rows:
        return ["Fig. 1 (contact maps) not drawn: no finished task holds a pressure map."]
    panels = "; ".join(
        f"ℓa/a0 = {r['adhesion_length']:g}: A_rep/A0 = {r['repulsive_area']:.4f}, "
        f"A_att/A0 = {r['attractive_area']:.4f}"
        for r in map_rows
    )
    return [
        f"Fig. 1: contact maps of seed {map_rows[0]['seed']} on the approach, at the state "
        f"nearest A_rep/A0 = {map_area:g} for each adhesion length ({panels}); repulsive "
        "sites orange, attractive sites black."
    ]


def report_lines(
    *, size, seeds, short_cutoff, rows, summary, map_rows, map_area, run, figures
) -> list[str]:
    """The lines of ``report.md``.

    Parameters
    ----------
    size, seeds, short_cutoff
        The study's grid size n (n² sites), seeds and λs (a0).
    rows : list of dict
        The aggregated rows (one per ℓa).
    summary : list of str
        :func:`summary_lines` of ``rows``.
    map_rows, map_area
        As for :func:`figure1_note`.
    run : object
        The run summary, printed as it is.
    figures : dict
        Figure name -> the paths written (the first is linked).
    """
    return [
        "# roughcontact demo",
        "",
        f"Self-affine surfaces {size}², H = 0.8, h'rms = 0.1, λs = {short_cutoff:g} a0, "
        f"λL = L/2, seeds {list(seeds)}; the paper's smoothed 9-3 LJ wall (k = E*/(2 a0), "
        "Δr = √(24 a0 ℓa)) on an elastic half-space; approach and retraction under "
        "displacement control; everything measured at A_rep = 1 % of A0 on the approach "
        "(Pastewka & Robbins, PNAS 111, 3298 (2014)).",
        "",
        *table_lines(rows),
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
        *summary,
        "",
        *figure1_note(map_rows, map_area),
        "",
        f"Run: {run}",
        "",
        *[f"![{name}](figures/{Path(p[0]).name})" for name, p in figures.items() if p],
    ]
