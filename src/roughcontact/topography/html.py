"""``report.html`` of :func:`roughcontact.stick`: the stick result record as page blocks.

:func:`stick_blocks` describes a :class:`~roughcontact.topography.result.StickResult` in
the blocks of :mod:`roughcontact.htmlreport`, in the order a reader needs them: the
verdict with its scope and margin (and, in plain words, why there is none), the inputs,
the scan map, the PSD, the scale-dependent slope and margin, the field's criteria, every
note, the simulation (with ``--simulate``). Every value comes from the record's JSON
(``StickResult.to_dict()``, the same dict ``--json`` prints and ``result.json`` holds)
or from the text output's own functions on the record (the pieces of
``roughcontact.topography.report.summary``), so text, JSON and HTML say the same thing;
the figures are those of ``roughcontact.topography.report``, inline. :func:`stick_html`
renders the page (:func:`roughcontact.htmlreport.render_html`).
"""

from __future__ import annotations

import hashlib
from pathlib import Path

from ..htmlreport import Bullets, Callout, Heading, Para, Table, figure_block
from ._text import length_text, range_text

__all__ = ["SCAN_PERCENTILES", "stick_blocks", "stick_html"]

#: The colour scale of the scan map spans these percentiles of the heights (robust to
#: spikes; said in the caption).
SCAN_PERCENTILES = (1.0, 99.0)


def _g(x, fmt=".3g") -> str:
    return "—" if x is None else f"{x:{fmt}}"


def _answer(sticky) -> str:
    return {True: "sticky", False: "not sticky"}.get(sticky, "no verdict")


def _tone(sticky) -> str:
    return {True: "sticky", False: "not-sticky"}.get(sticky, "open")


def _scope(d) -> str:
    """The verdict's scope in words: the whole surface, the measured scale only, none."""
    lam_c, a0 = length_text(d["measured_scale"]), length_text(d["inputs"]["atomic_spacing"])
    scope = d.get("scope") or ""
    if d["sticky"] is None:
        return f"no verdict for the whole surface (roughness from {lam_c} down to {a0})"
    if scope == "all scales (necessary condition)":
        return (f"whole surface: the necessary condition fails with the roughness measured "
                f"down to {lam_c} already")  # fmt: skip
    if scope.startswith("all scales"):
        return (f"whole surface: every smallest roughness scale from the measured {lam_c} "
                f"down to a0 = {a0} (extrapolated below {lam_c})")  # fmt: skip
    if scope == "measured scale":
        return f"measured scale only: the roughness down to {lam_c}; nothing extrapolated"
    return scope


def _verdict(result, d) -> Callout:
    v = result.verdict
    rows = [("verdict", d["verdict"]), ("scope", _scope(d))]
    if "sticky_measured_scale" in d:  # the measured scale's own answer, where recorded
        rows.append(("at the measured scale", _answer(d["sticky_measured_scale"])))
    lam_c = length_text(d["measured_scale"])
    rows.append(("margin κ_rep/κ_att (> 1 sticks)", f"{_g(d['margin'])} measured down to {lam_c}"))
    if d.get("extrapolated") is not None:
        lo, hi = d["margin_atomic_range"]
        rows.append(("margin extrapolated to a0",
                     f"{_g(d['margin_atomic'])} ({range_text(lo, hi)} within H = "
                     f"{range_text(*d['hurst_interval'], '.2f')})"))  # fmt: skip
    why = [n for n in d["notes"] if n.startswith("no extrapolated verdict")]
    if v.sticky is None and v.depends_below is not None:
        why.append(
            f"the verdict depends on roughness below {length_text(v.depends_below)}, below "
            f"the measured {length_text(d['measured_scale'])}: measure finer or with a "
            "sharper tip"
        )
    if d.get("no_extrapolation") and not why:
        why.append(f"nothing extrapolated: {d['no_extrapolation']}")
    rows += [("why no verdict" if d["sticky"] is None else "why this scope", w) for w in why]
    if d.get("continuum_reason"):
        rows.append(("validity", f"Eq. 10 leaves its validity below "
                     f"{length_text(d['continuum_limit'])}, where the extrapolation reaches "
                     f"{d['continuum_reason']}"))  # fmt: skip
    return Callout(f"Verdict: {d['verdict']}", _tone(d["sticky"]), tuple(rows))


def _sha256(path) -> str:
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except OSError:
        return "— (not a file)"


def _inputs(d) -> Table:
    from .missing import fill_note

    scan, inp = d["scan"], d["inputs"]
    source = scan.get("source") or ""
    size = " × ".join(length_text(x) for x in scan["physical_size"])
    pixel = " × ".join(length_text(x) for x in scan["pixel_size"])
    missing = d.get("missing_data")
    rows = [
        ("file", Path(source).name if source else "(in memory)", ""),
        ("sha256 of the file", _sha256(source) if source else "—", ""),
        ("data channel", scan.get("channel") or "—", ""),
        ("grid", " × ".join(str(n) for n in scan["shape"]), "points"),
        ("pixel size", pixel, "per axis"),
        ("scan size", size, "per axis"),
        ("detrending", str(scan.get("detrend")), ""),
        ("missing points", fill_note(missing, 0) if missing else "none", ""),
        ("contact modulus E*", _g(inp["contact_modulus"]), "Pa"),
        ("E* and the counter-body", inp.get("contact_modulus_formula") or "—", ""),
        ("Young's modulus E", _g(inp.get("youngs_modulus")), "Pa"),
        ("Poisson ratio", _g(inp.get("poisson")), "1"),
        ("counter-body modulus", _g(inp.get("counter_modulus")) if inp.get("counter_modulus")
         else "rigid", "Pa"),  # fmt: skip
        ("work of adhesion w", _g(inp["work_of_adhesion"]), "J/m²"),
        ("interaction range Δr", _g(inp["interaction_range"]), "m"),
        ("atomic spacing a0", _g(inp["atomic_spacing"]), "m"),
        ("κ_rep", f"{_g(inp['kappa_rep'])} ({inp.get('kappa_rep_note', '')})", "1"),
        ("tip radius", f"{_g(inp.get('tip_radius'))} ({inp.get('tip_radius_source', '')})", "m"),
        ("reliability cutoff", f"{_g(d.get('reliability_cutoff'))} "
         f"({inp.get('reliability_cutoff_source', '')})", "m"),  # fmt: skip
        ("PSD window", f"{scan.get('window')} (periodic: {scan.get('periodic')})", ""),
    ]
    return Table(("input", "value", "unit"), tuple(rows))


def _criteria(d) -> list:
    from ..stickiness.table import NOT_EVALUATED

    table = d.get("criteria")
    if not table:
        return []
    rows = tuple(
        (c["name"], c["parameter_symbol"], _g(c["parameter"], ".4g"),
         f"{'<' if c['sticky_below'] else '>'} {_g(c['threshold'], '.4g')}", c["verdict"],
         c["validated"], "; ".join(c.get("notes") or ()) or "—")
        for c in table["criteria"]
    )  # fmt: skip
    names = {c["key"]: c["name"] for c in table["criteria"]}
    ag = table["agreement"]

    def say(keys):
        return ", ".join(names[k] for k in keys) or "none"

    lines = [
        f"The criteria disagree: sticky by {say(ag['sticky'])}; not sticky by "
        f"{say(ag['not_sticky'])}."
        if ag["disagree"]
        else "The criteria with a verdict agree."
    ]
    if ag["no_verdict"]:
        lines.append(f"No verdict from {say(ag['no_verdict'])} (see the row).")
    if "simulation" in ag:
        lines.append(f"Simulation: {ag['simulation']}; agreeing: "
                     f"{say(ag['agree_with_simulation'])}.")  # fmt: skip
    lines.append(f"Not evaluated: {NOT_EVALUATED}.")
    return [
        Heading("The field's stickiness criteria"),
        Table(
            ("criterion", "parameter", "value (1)", "sticky if", "verdict",
             "validated against", "model choices and caveats"),
            rows,
            caption=f"With the roughness down to the measured {length_text(table['scale'])} "
            "(no extrapolation); every parameter is dimensionless.",
        ),  # fmt: skip
        Para(*lines),
    ]


def _lines(lines) -> list:
    """The text output's lines of a block, without its notes (they are under Notes)."""
    return [line for line in lines if not line.startswith("note: ")]


def _simulation(result, d, dpi, contact_map=None) -> list:
    from .figures import figure_contact_map
    from .summaries import simulation_summary

    sim, hy = d.get("simulation"), d.get("hysteresis")
    if sim is None:
        return []
    text = _lines(simulation_summary(result.simulation))
    blocks = [Heading("Simulation (--simulate)"), Para(*text)]
    fig = contact_map if contact_map is not None else figure_contact_map(result)
    if fig is not None:
        blocks.append(figure_block(fig, fmt="png", dpi=dpi, alt="Contact map of the first "
            "simulated seed at 1 % repulsive area: repulsive sites orange, attractive black",
            caption="Contact map of the first seed near A_rep = 1 % of A0 (repulsive orange, "
            "attractive black)."))  # fmt: skip
    from ..plot.hysteresis import hysteresis_figure

    for run in result.simulation.runs:
        path = run.path
        if path is None or "branch" not in path.variables:
            continue
        if not (path["branch"].values == "retract").any():
            continue
        blocks.append(figure_block(hysteresis_figure(path, label=f"seed {run.seed}"),
            fmt="png", dpi=dpi,
            alt=f"Load against approach of seed {run.seed}: approach and retraction, the "
            "enclosed area shaded (dissipated energy)",
            caption=f"Force–offset loop of seed {run.seed} (lattice units: load N/A0 in E*, "
            "approach in a0); the shaded area is the energy dissipated per cycle."))  # fmt: skip
    per_hy = {s["seed"]: s for s in (hy or {}).get("seeds", [])}
    rows = []
    for s in sim["seeds"]:
        h = per_hy.get(s["seed"], {})
        rows.append((str(s["seed"]), _g(s["kappa"]), _g(s["kappa_rep"]), _g(s["kappa_att"]),
                     _g(s["inverse_kappa"]), s["verdict"], s["predicted_verdict"],
                     _g(s["pull_off_pressure"]), _g(h.get("dissipated_energy_si")),
                     str(h.get("jumps", "—")), f"{s['steps']} ({s['steps_not_converged']})",
                     s.get("error") or "—"))  # fmt: skip
    blocks.append(Table(
        ("seed", "κ (1)", "κ_rep (1)", "κ_att (1)", "1/κ (1)", "measured", "Eq. 10",
         "pull-off (Pa)", "dissipated (J/m²)", "jumps", "steps (not converged)", "error"),
        tuple(rows), caption="Per seed, at A_rep = 1 % of A0 on the approach."))  # fmt: skip
    if hy is not None:
        from .summaries import hysteresis_summary

        blocks.append(Para(*_lines(hysteresis_summary(result.hysteresis))))
    return blocks


def stick_blocks(result, *, dpi: int = 150, figures=None) -> list:
    """The page of ``result`` (a StickResult) as :mod:`roughcontact.htmlreport` blocks.

    ``figures``: the figures of ``roughcontact.topography.report.FIGURES`` (and
    ``contact_map``) already made, by name (the scan's with :data:`SCAN_PERCENTILES`);
    the others are made here. Every figure is inline as a PNG at ``dpi``.
    """
    from . import figures as _r

    made = dict(figures or {})

    def fig(name, make, **kw):
        return made[name] if name in made else make(result, **kw)

    def png(name, make, *, alt, caption, **kw):
        return figure_block(fig(name, make, **kw), fmt="png", dpi=dpi, alt=alt, caption=caption)

    d = result.to_dict()
    lo, hi = SCAN_PERCENTILES
    good = d.get("good_range") or {}
    limits = [f"fit range {length_text(d['hurst_fit_range'][0])} to "
              f"{length_text(d['hurst_fit_range'][1])} (shaded)",
              f"measured scale {length_text(d['measured_scale'])} (dotted)"]  # fmt: skip
    if good.get("resolution"):
        limits.append(f"resolution limit {length_text(good['resolution'])}")
    limits.append(f"noise floor {_g(good['noise_level'])} (dash-dotted)"
                  if good.get("noise_level") else "no noise floor found")  # fmt: skip
    notes = list(d["notes"])
    for extra in (d.get("simulation") or {}, d.get("hysteresis") or {}):
        notes += [n for n in extra.get("notes", []) if n not in notes]
    return [
        _verdict(result, d),
        Heading("Inputs"),
        _inputs(d),
        Heading("The scan"),
        png("scan", _r.figure_scan, percentiles=SCAN_PERCENTILES,
            alt="Height map of the detrended scan" if d["scan"]["dim"] == 2 else
            "Height profile of the detrended line scan",
            caption=f"The scan after detrending ({d['scan']['detrend']})"
            + (f"; the colour scale spans the heights' percentiles {lo:g} to {hi:g} (robust "
               "to spikes: heights beyond are drawn in its end colours)."
               if d["scan"]["dim"] == 2 else ": the whole profile.")),  # fmt: skip
        Heading("Power spectral density"),
        png("psd", _r.figure_psd, alt="Power spectral density against wavevector, "
            "log-log, with the self-affine fit and its extrapolation",
            caption="PSD with the Hurst fit H = "
            f"{d['hurst']:.2f} ± {d['hurst_stderr']:.2f}, its band "
            f"{range_text(*d['hurst_interval'], '.2f')} (shaded, extrapolated dashed); "
            + "; ".join(limits) + "."),  # fmt: skip
        Heading("Scale-dependent slope and margin"),
        png("slope", _r.figure_slope, alt="rms slope and rms curvature against the "
            "smallest roughness scale, measured and extrapolated",
            caption="h′rms and h″rms (1/m) against the smallest roughness scale λs (m): "
            "measured (solid) and extrapolated over the H band (dashed, shaded)."),  # fmt: skip
        png("margin", _r.figure_margin, alt="The margin κ_rep/κ_att against the "
            "smallest roughness scale, sticky above 1",
            caption="The margin κ_rep/κ_att against λs (m): sticky above 1 (shaded); "
            "dotted lines where the verdict flips."),  # fmt: skip
        *_criteria(d),
        Heading("Notes"),
        Bullets(tuple(notes)) if notes else Para("none"),
        *_simulation(result, d, dpi, made.get("contact_map")),
    ]


def stick_html(result, *, command: str | None = None, dpi: int = 150, figures=None) -> str:
    """The self-contained page of ``result`` (``report.html`` of ``stick -o``)."""
    from ..htmlreport import provenance, render_html

    source = getattr(result.topography, "source", "") or "scan"
    return render_html(
        f"Is it sticky? {Path(source).name}",
        stick_blocks(result, dpi=dpi, figures=figures),
        subtitle="Pastewka & Robbins, PNAS 111, 3298 (2014), Eq. 10, on a measured scan "
        "(roughcontact stick)",
        provenance_rows=provenance(command),
    )
